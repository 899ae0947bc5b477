//! Calls in expressions: user functions, the `<A>_TO_<B>` conversions and
//! the standard functions.

use super::expr::{error, fold, literal, ETy, Typed};
use super::{conversion, lookup, Cx, BUILTINS};
use crate::ast::{self, PouKind, Section};
use crate::code::{self, Builtin, Expr};
use crate::error::{Error, ErrorKind};
use crate::program::VarType;
use crate::types::Type;

impl Cx<'_> {
    pub(super) fn call_expr(
        &mut self,
        name: &ast::Ident,
        args: &[ast::Arg],
    ) -> Result<Typed, Error> {
        let key = name.key();
        let is_function =
            |id: &usize| self.pous[*id].as_ref().map(|p| p.kind) == Some(PouKind::Function);
        // Inside function `f`, `f` is the result variable but `f(...)` a call.
        let function = self.index.get(&key).filter(|id| is_function(id));
        if let Some(var) = lookup(self.vars, self.var_index, &key).filter(|_| function.is_none()) {
            let message = if var.instance_of.is_some() {
                format!(
                    "calling function block instance `{}` is a statement, not a value",
                    name.text
                )
            } else {
                format!("`{}` is a variable, not a function", name.text)
            };
            return Err(error(ErrorKind::Type, name.pos, message));
        }
        if let Some((from, to)) = conversion(&key) {
            let [arg] = self.positional(name, args, 1)?;
            let arg_pos = arg.pos();
            let typed = self.expr(arg)?;
            let code = self.coerce(typed, from, arg_pos, &format!("argument of {}", name.text))?;
            let code = match (from, to) {
                (_, Type::Bool) if from == Type::Bool => code,
                (_, Type::Bool) => Expr::NonZero(Box::new(code)),
                (Type::Bool, _) => code,
                (Type::Int(a), Type::Int(b)) if a.widens_to(b) => code,
                (_, Type::Int(b)) => Expr::Truncate(b, Box::new(code)),
            };
            return fold(code, ETy::from(to), name.pos);
        }
        if BUILTINS.contains(&key.as_str()) {
            return self.builtin(name, &key, args);
        }
        let Some(&id) = self.index.get(&key) else {
            return Err(error(
                ErrorKind::Name,
                name.pos,
                format!("unknown function `{}`", name.text),
            ));
        };
        if self.pous[id].as_ref().map(|p| p.kind) != Some(PouKind::Function) {
            let what = if self.initialiser {
                "an initial value must be a constant expression"
            } else {
                "only functions are called in expressions"
            };
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!("`{}`: {what}", name.text),
            ));
        }
        let call = self.function_call(id, name, args)?;
        let (_, ty) = self.pou(id).result.expect("a function has a result");
        Ok(Typed {
            code: Expr::Call(Box::new(call)),
            ty: ETy::from(ty),
        })
    }

    /// A user FUNCTION's arguments: all positional (every input, in order)
    /// or all formal (inputs left out keep their initial values).
    pub(super) fn function_call(
        &mut self,
        id: usize,
        name: &ast::Ident,
        args: &[ast::Arg],
    ) -> Result<code::FunctionCall, Error> {
        let f = self.pou(id);
        let mut out = Vec::with_capacity(args.len());
        let positional = args.iter().any(|a| matches!(a, ast::Arg::Positional(_)));
        if positional && args.len() != f.inputs.len() {
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!(
                    "`{}` takes {} input(s), given {}",
                    f.name,
                    f.inputs.len(),
                    args.len()
                ),
            ));
        }
        for (k, arg) in args.iter().enumerate() {
            let (input, e) = match arg {
                ast::Arg::Positional(e) => (&f.vars[f.inputs[k]], e),
                ast::Arg::Input(n, e) if !positional => {
                    let Some(input) = f.var(&n.text).filter(|v| v.section == Section::Input) else {
                        return Err(error(
                            ErrorKind::Name,
                            n.pos,
                            format!("function `{}` has no input `{}`", f.name, n.text),
                        ));
                    };
                    if out.iter().any(|&(s, _)| s == input.slot) {
                        return Err(error(
                            ErrorKind::Name,
                            n.pos,
                            format!("input `{}` given twice", n.text),
                        ));
                    }
                    (input, e)
                }
                ast::Arg::Input(n, _) | ast::Arg::Output(n, _) => {
                    return Err(error(
                        ErrorKind::Syntax,
                        n.pos,
                        "a call's arguments are all positional or all formal (`name := value`)",
                    ))
                }
            };
            let VarType::Scalar(ty) = input.ty else {
                return Err(error(
                    ErrorKind::Unsupported,
                    e.pos(),
                    "array inputs are not supported",
                ));
            };
            let typed = self.expr_for(e, ty)?;
            let code = self.coerce(typed, ty, e.pos(), &format!("input `{}`", input.name))?;
            out.push((input.slot, code));
        }
        self.calls.push((id, name.pos));
        Ok(code::FunctionCall {
            pou: id as u32,
            args: out,
        })
    }

    fn positional<'a, const N: usize>(
        &self,
        name: &ast::Ident,
        args: &'a [ast::Arg],
        min: usize,
    ) -> Result<[&'a ast::Expr; N], Error> {
        let exprs = self.positional_list(name, args, min, Some(N))?;
        Ok(std::array::from_fn(|k| exprs[k]))
    }

    fn positional_list<'a>(
        &self,
        name: &ast::Ident,
        args: &'a [ast::Arg],
        min: usize,
        max: Option<usize>,
    ) -> Result<Vec<&'a ast::Expr>, Error> {
        let mut exprs = Vec::with_capacity(args.len());
        for arg in args {
            match arg {
                ast::Arg::Positional(e) => exprs.push(e),
                ast::Arg::Input(n, _) | ast::Arg::Output(n, _) => {
                    return Err(error(
                        ErrorKind::Unsupported,
                        n.pos,
                        format!("call `{}` with positional arguments", name.text),
                    ))
                }
            }
        }
        if exprs.len() < min || max.is_some_and(|m| exprs.len() > m) {
            let expected = match max {
                Some(m) if m == min => format!("{m}"),
                Some(m) => format!("{min} to {m}"),
                None => format!("at least {min}"),
            };
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!(
                    "`{}` takes {expected} argument(s), given {}",
                    name.text,
                    exprs.len()
                ),
            ));
        }
        Ok(exprs)
    }

    /// The common type of several operands (MIN, MAX, LIMIT, SEL).
    fn common(
        &mut self,
        name: &ast::Ident,
        exprs: &[&ast::Expr],
    ) -> Result<(Type, Vec<Expr>), Error> {
        let typed: Vec<Typed> = exprs
            .iter()
            .map(|e| self.expr(e))
            .collect::<Result<_, _>>()?;
        let mut ty: Option<Type> = None;
        for (t, e) in typed.iter().zip(exprs) {
            let this = match t.ty {
                ETy::Literal(_) => continue,
                ETy::Bool => Type::Bool,
                ETy::Int(i) => Type::Int(i),
            };
            ty = Some(match ty {
                None => this,
                Some(prev) if prev.widens_to(this) => this,
                Some(prev) if this.widens_to(prev) => prev,
                Some(prev) => {
                    return Err(error(
                        ErrorKind::Type,
                        e.pos(),
                        format!(
                            "`{}` cannot combine {prev} and {this} without an explicit conversion",
                            name.text
                        ),
                    ))
                }
            });
        }
        let context = self.expected.filter(|t| matches!(t, Type::Int(_)));
        let Some(ty) = ty.or(context) else {
            return Err(error(
                ErrorKind::Type,
                name.pos,
                format!(
                    "`{}` of untyped literals only: give one a type (e.g. INT#1)",
                    name.text
                ),
            ));
        };
        let what = format!("argument of {}", name.text);
        let codes = typed
            .into_iter()
            .zip(exprs)
            .map(|(t, e)| self.coerce(t, ty, e.pos(), &what))
            .collect::<Result<_, _>>()?;
        Ok((ty, codes))
    }

    fn builtin(&mut self, name: &ast::Ident, key: &str, args: &[ast::Arg]) -> Result<Typed, Error> {
        let pos = name.pos;
        let unsigned = |ty: Type| !matches!(ty, Type::Int(t) if t.is_signed());
        let (builtin, codes, ty) = match key {
            "ABS" => {
                let [arg] = self.positional(name, args, 1)?;
                let typed = self.expr(arg)?;
                match typed.ty {
                    ETy::Literal(v) => return Ok(literal(v.abs())),
                    ETy::Int(t) if t.is_signed() => (Builtin::Abs(t), vec![typed.code], typed.ty),
                    ETy::Int(t) if !t.is_bit_string() => return Ok(typed),
                    ty => {
                        return Err(error(
                            ErrorKind::Type,
                            arg.pos(),
                            format!("ABS needs an integer, found {ty}"),
                        ))
                    }
                }
            }
            "MIN" | "MAX" => {
                let exprs = self.positional_list(name, args, 2, None)?;
                let (ty, codes) = self.common(name, &exprs)?;
                let b = if key == "MIN" {
                    Builtin::Min {
                        unsigned: unsigned(ty),
                    }
                } else {
                    Builtin::Max {
                        unsigned: unsigned(ty),
                    }
                };
                (b, codes, ETy::from(ty))
            }
            "LIMIT" => {
                let exprs = self.positional_list(name, args, 3, Some(3))?;
                let (ty, codes) = self.common(name, &exprs)?;
                (
                    Builtin::Limit {
                        unsigned: unsigned(ty),
                    },
                    codes,
                    ETy::from(ty),
                )
            }
            "SEL" => {
                let [g, in0, in1] = self.positional(name, args, 3)?;
                let g = self.condition(g, "SEL's selector G")?;
                let (ty, mut codes) = self.common(name, &[in0, in1])?;
                codes.insert(0, g);
                (Builtin::Sel, codes, ETy::from(ty))
            }
            _ => {
                let [input, count] = self.positional(name, args, 2)?;
                let typed = self.expr(input)?;
                let t = match typed.ty {
                    ETy::Int(t) if t.is_bit_string() => t,
                    _ => {
                        return Err(error(
                            ErrorKind::Type,
                            input.pos(),
                            format!("{key} needs a bit string (BYTE..LWORD), found {}", typed.ty),
                        ))
                    }
                };
                let n = self.expr(count)?;
                let n = match n.ty {
                    ETy::Literal(v) if v >= 0 => Expr::Const(v.min(i128::from(u8::MAX)) as i64),
                    ETy::Int(c) if !c.is_bit_string() => n.code,
                    ty => {
                        return Err(error(
                            ErrorKind::Type,
                            count.pos(),
                            format!(
                                "{key}'s shift count must be a non-negative integer, found {ty}"
                            ),
                        ))
                    }
                };
                let b = match key {
                    "SHL" => Builtin::Shl(t),
                    "SHR" => Builtin::Shr(t),
                    "ROL" => Builtin::Rol(t),
                    _ => Builtin::Ror(t),
                };
                (b, vec![typed.code, n], typed.ty)
            }
        };
        fold(Expr::Builtin(builtin, codes.into_boxed_slice()), ty, pos)
    }
}
