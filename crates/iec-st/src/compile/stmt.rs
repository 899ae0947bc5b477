//! Statements: assignments, control flow and calls.

use super::expr::{error, ETy};
use super::{conversion, lookup, Cx, BUILTINS};
use crate::ast::{self, Arg, CaseLabel, PouKind, Section, Stmt as S};
use crate::code::{Block, BlockCall, Expr, Stmt};
use crate::error::{Error, ErrorKind, Pos};
use crate::program::{VarType, Variable};
use crate::types::{IntType, Type};

impl Cx<'_> {
    pub(crate) fn block(&mut self, stmts: &[ast::Stmt]) -> Result<Block, Error> {
        stmts.iter().map(|s| self.stmt(s)).collect()
    }

    fn stmt(&mut self, stmt: &ast::Stmt) -> Result<Stmt, Error> {
        Ok(match stmt {
            S::Assign { target, value, pos } => {
                let access = self.resolve(target, true)?;
                let typed = self.expr_for(value, access.ty)?;
                let code = self.coerce(typed, access.ty, *pos, "assignment")?;
                Stmt::Assign(access.place, code)
            }
            S::Call { name, args } => self.call_stmt(name, args)?,
            S::If {
                branches,
                otherwise,
            } => Stmt::If {
                branches: branches
                    .iter()
                    .map(|(cond, body)| {
                        Ok((self.condition(cond, "an IF condition")?, self.block(body)?))
                    })
                    .collect::<Result<_, Error>>()?,
                otherwise: self.block(otherwise)?,
            },
            S::Case {
                selector,
                arms,
                otherwise,
            } => self.case(selector, arms, otherwise)?,
            S::For {
                var,
                from,
                to,
                by,
                body,
                pos,
            } => self.for_loop(var, from, to, by.as_ref(), body, *pos)?,
            S::While { cond, body, pos } => {
                let cond = self.condition(cond, "a WHILE condition")?;
                Stmt::While {
                    cond,
                    body: self.loop_body(body)?,
                    line: pos.line,
                }
            }
            S::Repeat { body, until, pos } => {
                let body = self.loop_body(body)?;
                Stmt::Repeat {
                    body,
                    until: self.condition(until, "an UNTIL condition")?,
                    line: pos.line,
                }
            }
            S::Exit(pos) => {
                if self.loops == 0 {
                    return Err(error(ErrorKind::Syntax, *pos, "EXIT outside a loop"));
                }
                Stmt::Exit
            }
            S::Return => Stmt::Return,
        })
    }

    fn loop_body(&mut self, body: &[ast::Stmt]) -> Result<Block, Error> {
        self.loops += 1;
        let block = self.block(body);
        self.loops -= 1;
        block
    }

    fn case(
        &mut self,
        selector: &ast::Expr,
        arms: &[ast::CaseArm],
        otherwise: &[ast::Stmt],
    ) -> Result<Stmt, Error> {
        let typed = self.expr(selector)?;
        let ty = match typed.ty {
            ETy::Int(t) => t,
            ETy::Literal(_) => IntType::Lint,
            ETy::Bool => {
                return Err(error(
                    ErrorKind::Type,
                    selector.pos(),
                    "a CASE selector must be an integer, found BOOL",
                ))
            }
        };
        let selector_code = self.coerce(typed, Type::Int(ty), selector.pos(), "CASE selector")?;
        let mut labels = Vec::new();
        let mut bodies = Vec::with_capacity(arms.len());
        for (k, arm) in arms.iter().enumerate() {
            for label in &arm.labels {
                let (lo, hi, at) = match label {
                    CaseLabel::Value(e) => {
                        let v = self.label(e, ty)?;
                        (v, v, e.pos())
                    }
                    CaseLabel::Range(a, b) => {
                        let (lo, hi) = (self.label(a, ty)?, self.label(b, ty)?);
                        if lo > hi {
                            return Err(error(
                                ErrorKind::Range,
                                a.pos(),
                                format!("empty CASE range {lo}..{hi}"),
                            ));
                        }
                        (lo, hi, a.pos())
                    }
                };
                labels.push((lo, hi, k as u32, at));
            }
            bodies.push(self.block(&arm.body)?);
        }
        labels.sort_by_key(|&(lo, ..)| lo);
        for pair in labels.windows(2) {
            let (_, hi, _, _) = pair[0];
            let (lo, _, _, at) = pair[1];
            if lo <= hi {
                return Err(error(
                    ErrorKind::Range,
                    at,
                    format!("CASE value {lo} is already covered by another label"),
                ));
            }
        }
        Ok(Stmt::Case {
            selector: selector_code,
            unsigned: !ty.is_signed(),
            labels: labels
                .into_iter()
                .map(|(lo, hi, k, _)| (lo, hi, k))
                .collect(),
            arms: bodies,
            otherwise: self.block(otherwise)?,
        })
    }

    /// A CASE label's value: a constant of the selector's type.
    fn label(&mut self, e: &ast::Expr, ty: IntType) -> Result<i128, Error> {
        let typed = self.expr(e)?;
        match self.coerce(typed, Type::Int(ty), e.pos(), "CASE label")? {
            Expr::Const(cell) => Ok(ty.value_of(cell)),
            _ => Err(error(
                ErrorKind::Type,
                e.pos(),
                "a CASE label must be a constant",
            )),
        }
    }

    fn for_loop(
        &mut self,
        name: &ast::Ident,
        from: &ast::Expr,
        to: &ast::Expr,
        by: Option<&ast::Expr>,
        body: &[ast::Stmt],
        pos: Pos,
    ) -> Result<Stmt, Error> {
        let target = ast::VarRef {
            parts: vec![ast::PathPart {
                name: name.clone(),
                index: None,
            }],
        };
        let access = self.resolve(&target, true)?;
        let (Type::Int(ty), crate::code::Place::Slot(var)) = (access.ty, access.place) else {
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!(
                    "a FOR control variable must be an integer, found {}",
                    access.ty
                ),
            ));
        };
        if ty.is_bit_string() {
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!("a FOR control variable must be an integer, found {ty}"),
            ));
        }
        let what = "FOR bound";
        let from_code = {
            let t = self.expr(from)?;
            self.coerce(t, Type::Int(ty), from.pos(), what)?
        };
        let to_code = {
            let t = self.expr(to)?;
            self.coerce(t, Type::Int(ty), to.pos(), what)?
        };
        let by_code = match by {
            Some(e) => {
                let t = self.expr(e)?;
                self.coerce(t, Type::Int(ty), e.pos(), "FOR step")?
            }
            None => Expr::Const(1),
        };
        self.for_vars.push(var);
        let body = self.loop_body(body);
        self.for_vars.pop();
        Ok(Stmt::For {
            var,
            ty,
            from: from_code,
            to: to_code,
            by: by_code,
            body: body?,
            line: pos.line,
        })
    }

    fn call_stmt(&mut self, name: &ast::Ident, args: &[Arg]) -> Result<Stmt, Error> {
        let key = name.key();
        if let Some(var) = lookup(self.vars, self.var_index, &key) {
            return self.block_call(var, name, args);
        }
        if let Some(&id) = self.index.get(&key) {
            if self.pou(id).kind == PouKind::Function {
                let call = self.function_call(id, name, args)?;
                return Ok(Stmt::CallFunction(Box::new(call)));
            }
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!("`{}` is a POU type; call an instance of it", name.text),
            ));
        }
        if BUILTINS.contains(&key.as_str()) || conversion(&key).is_some() {
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!("the result of `{}` is not used", name.text),
            ));
        }
        Err(error(
            ErrorKind::Name,
            name.pos,
            format!("undeclared function block instance `{}`", name.text),
        ))
    }

    /// `inst(IN := x, OUT => y)`: inputs assigned in order, the body run,
    /// then outputs copied.
    fn block_call(
        &mut self,
        var: &Variable,
        name: &ast::Ident,
        args: &[Arg],
    ) -> Result<Stmt, Error> {
        let Some(fb_id) = var.instance_of else {
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!("`{}` is not a function block instance", name.text),
            ));
        };
        let fb = self.pou(fb_id as usize);
        let mut inputs: Vec<(u32, Expr)> = Vec::new();
        let mut outputs = Vec::new();
        let mut seen: Vec<u32> = Vec::new();
        for arg in args {
            let (formal, section) = match arg {
                Arg::Positional(e) => {
                    return Err(error(
                        ErrorKind::Syntax,
                        e.pos(),
                        "a function block call takes formal arguments (`IN := value`, `OUT => variable`)",
                    ))
                }
                Arg::Input(n, _) => (n, Section::Input),
                Arg::Output(n, _) => (n, Section::Output),
            };
            let Some(member) = fb.var(&formal.text).filter(|m| m.section == section) else {
                let kind = if section == Section::Input {
                    "input"
                } else {
                    "output"
                };
                return Err(error(
                    ErrorKind::Name,
                    formal.pos,
                    format!("`{}` is not an {kind} of {}", formal.text, fb.name),
                ));
            };
            if seen.contains(&member.slot) {
                return Err(error(
                    ErrorKind::Name,
                    formal.pos,
                    format!("`{}` is given twice", formal.text),
                ));
            }
            seen.push(member.slot);
            let VarType::Scalar(member_ty) = member.ty else {
                return Err(error(
                    ErrorKind::Unsupported,
                    formal.pos,
                    "passing arrays to a function block is not supported",
                ));
            };
            match arg {
                Arg::Input(n, e) => {
                    let typed = self.expr_for(e, member_ty)?;
                    let code =
                        self.coerce(typed, member_ty, e.pos(), &format!("input `{}`", n.text))?;
                    inputs.push((member.slot, code));
                }
                Arg::Output(n, target) => {
                    let access = self.resolve(target, true)?;
                    if !member_ty.widens_to(access.ty) {
                        return Err(error(
                            ErrorKind::Type,
                            target.pos(),
                            format!(
                                "output `{}` is {member_ty}; it cannot be stored in a {}",
                                n.text, access.ty
                            ),
                        ));
                    }
                    outputs.push((member.slot, access.place));
                }
                Arg::Positional(_) => unreachable!("rejected above"),
            }
        }
        Ok(Stmt::CallBlock(Box::new(BlockCall {
            instance: var.slot,
            pou: fb_id,
            inputs,
            outputs,
        })))
    }
}
