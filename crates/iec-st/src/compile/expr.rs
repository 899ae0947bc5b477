//! Expressions: typing (with untyped literals that take their context's
//! type), constant folding, and variable access with its visibility rules.

use std::fmt;

use rustc_hash::FxHashMap;

use super::layout::Frame;
use super::{conversion, lookup, BUILTINS};
use crate::ast::{self, BinaryOp, PouKind, Section, TypedValue, UnaryOp, VarRef};
use crate::code::{self, Arith, Builtin, Compare, Dim, ElemRef, Expr, Logic, Place};
use crate::error::{Error, ErrorKind, Pos};
use crate::program::{Pou, VarType, Variable};
use crate::run::eval_const;
use crate::types::{IntType, Type};

/// The static type of an expression; an untyped literal keeps its value
/// until its context gives it a type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ETy {
    Bool,
    Int(IntType),
    Literal(i128),
}

impl From<Type> for ETy {
    fn from(ty: Type) -> ETy {
        match ty {
            Type::Bool => ETy::Bool,
            Type::Int(t) => ETy::Int(t),
        }
    }
}

impl fmt::Display for ETy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ETy::Bool => f.write_str("BOOL"),
            ETy::Int(t) => t.fmt(f),
            ETy::Literal(v) => write!(f, "the untyped literal {v}"),
        }
    }
}

/// A compiled expression with its type.
pub(super) struct Typed {
    pub code: Expr,
    pub ty: ETy,
}

pub(super) fn error(kind: ErrorKind, pos: Pos, message: impl Into<String>) -> Error {
    Error::at(kind, pos, message)
}

/// A resolved variable access.
pub(super) struct Access<'v> {
    pub place: Place,
    pub ty: Type,
    /// The variable named first in the path.
    pub root: &'v Variable,
}

/// The compile context of one POU body or initialiser.
pub(crate) struct Cx<'c> {
    pub(super) pous: &'c [Option<Pou>],
    pub(super) index: &'c FxHashMap<String, usize>,
    pub(super) vars: &'c [Variable],
    pub(super) var_index: &'c FxHashMap<String, usize>,
    init: &'c [i64],
    /// Compiling an initial value: only literals and earlier constants.
    initialiser: bool,
    /// Slots of the enclosing FOR loops' control variables.
    pub(super) for_vars: Vec<u32>,
    /// Depth of enclosing loops (for EXIT).
    pub(super) loops: u32,
    /// Functions called and where, for the recursion check.
    pub calls: Vec<(usize, Pos)>,
    /// The type the enclosing assignment or argument expects: gives
    /// `SEL(g, 1, 2)` and the like a type when all their values are literals.
    expected: Option<Type>,
}

impl<'c> Cx<'c> {
    pub(super) fn for_body(
        pous: &'c [Option<Pou>],
        index: &'c FxHashMap<String, usize>,
        id: usize,
    ) -> Cx<'c> {
        let pou = pous[id].as_ref().expect("laid out");
        Cx {
            pous,
            index,
            vars: &pou.vars,
            var_index: &pou.index,
            init: &pou.init,
            initialiser: false,
            for_vars: Vec::new(),
            loops: 0,
            calls: Vec::new(),
            expected: None,
        }
    }

    pub(super) fn for_initialiser(
        pous: &'c [Option<Pou>],
        index: &'c FxHashMap<String, usize>,
        frame: &'c Frame,
    ) -> Cx<'c> {
        Cx {
            pous,
            index,
            vars: &frame.vars,
            var_index: &frame.index,
            init: &frame.init,
            initialiser: true,
            for_vars: Vec::new(),
            loops: 0,
            calls: Vec::new(),
            expected: None,
        }
    }

    pub(super) fn pou(&self, id: usize) -> &'c Pou {
        self.pous[id].as_ref().expect("laid out")
    }

    /// The cell of a constant expression of type `ty`.
    pub(super) fn constant(&mut self, e: &ast::Expr, ty: Type) -> Result<i64, Error> {
        let typed = self.expr_for(e, ty)?;
        match self.coerce(typed, ty, e.pos(), "initial value")? {
            Expr::Const(cell) => Ok(cell),
            _ => Err(error(
                ErrorKind::Type,
                e.pos(),
                "an initial value must be a constant expression",
            )),
        }
    }

    /// `value` where a `to` is expected: the same type, an implicit widening
    /// in the same chain, or an untyped literal that fits.
    pub(super) fn coerce(
        &self,
        value: Typed,
        to: Type,
        pos: Pos,
        what: &str,
    ) -> Result<Expr, Error> {
        match (value.ty, to) {
            (ETy::Literal(v), Type::Int(t)) => {
                if t.contains(v) {
                    Ok(Expr::Const(t.cell_of(v)))
                } else {
                    Err(error(
                        ErrorKind::Range,
                        pos,
                        format!(
                            "{what}: literal {v} does not fit {t} ({}..{})",
                            t.min(),
                            t.max()
                        ),
                    ))
                }
            }
            (ETy::Bool, Type::Bool) => Ok(value.code),
            (ETy::Int(from), Type::Int(t)) if from.widens_to(t) => Ok(value.code),
            (from, to) => {
                let hint = match from {
                    ETy::Int(f) => format!(" (convert explicitly, e.g. {f}_TO_{to})"),
                    ETy::Bool => format!(" (convert explicitly, e.g. BOOL_TO_{to})"),
                    ETy::Literal(_) => String::new(),
                };
                Err(error(
                    ErrorKind::Type,
                    pos,
                    format!("{what}: {from} cannot be used as {to}{hint}"),
                ))
            }
        }
    }

    /// A BOOL condition.
    pub(super) fn condition(&mut self, e: &ast::Expr, what: &str) -> Result<Expr, Error> {
        let typed = self.expr(e)?;
        if typed.ty != ETy::Bool {
            return Err(error(
                ErrorKind::Type,
                e.pos(),
                format!("{what} must be BOOL, found {}", typed.ty),
            ));
        }
        Ok(typed.code)
    }

    /// `e`, compiled where a value of type `expected` is wanted.
    pub(super) fn expr_for(&mut self, e: &ast::Expr, expected: Type) -> Result<Typed, Error> {
        let outer = self.expected.replace(expected);
        let typed = self.expr(e);
        self.expected = outer;
        typed
    }

    pub(super) fn expr(&mut self, e: &ast::Expr) -> Result<Typed, Error> {
        match e {
            ast::Expr::Int(v, pos) => {
                let v = i128::try_from(*v)
                    .map_err(|_| error(ErrorKind::Range, *pos, "integer literal too large"))?;
                Ok(literal(v))
            }
            ast::Expr::Bool(b, _) => Ok(Typed {
                code: Expr::Const(i64::from(*b)),
                ty: ETy::Bool,
            }),
            ast::Expr::Typed { ty, value, pos } => typed_literal(ty, *value, *pos),
            ast::Expr::Var(r) => self.load(r),
            ast::Expr::Call { name, args } => self.call_expr(name, args),
            ast::Expr::Unary { op, operand, pos } => {
                let operand = self.expr(operand)?;
                self.unary(*op, operand, *pos)
            }
            ast::Expr::Binary {
                op,
                left,
                right,
                pos,
            } => {
                let left = self.expr(left)?;
                let right = self.expr(right)?;
                self.binary(*op, left, right, *pos)
            }
        }
    }

    fn unary(&mut self, op: UnaryOp, operand: Typed, pos: Pos) -> Result<Typed, Error> {
        let code = match (op, operand.ty) {
            (UnaryOp::Neg, ETy::Literal(v)) => return Ok(literal(-v)),
            (UnaryOp::Neg, ETy::Int(t)) if !t.is_bit_string() => {
                Expr::Neg(t, Box::new(operand.code))
            }
            (UnaryOp::Not, ETy::Bool) => Expr::Not(Box::new(operand.code)),
            (UnaryOp::Not, ETy::Int(t)) if t.is_bit_string() => {
                Expr::BitNot(t, Box::new(operand.code))
            }
            (UnaryOp::Neg, ty) => {
                return Err(error(
                    ErrorKind::Type,
                    pos,
                    format!("unary `-` needs an integer, found {ty}"),
                ))
            }
            (UnaryOp::Not, ty) => {
                return Err(error(
                    ErrorKind::Type,
                    pos,
                    format!("NOT needs BOOL or a bit string (BYTE..LWORD), found {ty}"),
                ))
            }
        };
        fold(code, operand.ty, pos)
    }

    /// The common type of two operands (see [`Cx::coerce`]).
    fn unify(
        &self,
        op: &str,
        left: Typed,
        right: Typed,
        pos: Pos,
    ) -> Result<(Type, Expr, Expr), Error> {
        let ty = match (left.ty, right.ty) {
            (ETy::Bool, ETy::Bool) => Type::Bool,
            (ETy::Int(t), ETy::Literal(_)) | (ETy::Literal(_), ETy::Int(t)) => Type::Int(t),
            (ETy::Int(a), ETy::Int(b)) if a.widens_to(b) => Type::Int(b),
            (ETy::Int(a), ETy::Int(b)) if b.widens_to(a) => Type::Int(a),
            (a, b) => {
                return Err(error(
                    ErrorKind::Type,
                    pos,
                    format!("`{op}` cannot combine {a} and {b} without an explicit conversion"),
                ))
            }
        };
        let what = format!("operand of `{op}`");
        let left = self.coerce(left, ty, pos, &what)?;
        let right = self.coerce(right, ty, pos, &what)?;
        Ok((ty, left, right))
    }

    pub(super) fn binary(
        &mut self,
        op: BinaryOp,
        left: Typed,
        right: Typed,
        pos: Pos,
    ) -> Result<Typed, Error> {
        if let (ETy::Literal(a), ETy::Literal(b)) = (left.ty, right.ty) {
            return fold_literals(op, a, b, pos);
        }
        let symbol = op.symbol();
        let (ty, l, r) = self.unify(symbol, left, right, pos)?;
        if matches!(op, BinaryOp::Div | BinaryOp::Mod) && matches!(r, Expr::Const(0)) {
            return Err(error(ErrorKind::Range, pos, "division by zero"));
        }
        let operands = Box::new((l, r));
        let (code, result) = match op {
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div | BinaryOp::Mod => {
                let t = match ty {
                    Type::Int(t) if !t.is_bit_string() => t,
                    _ => {
                        return Err(error(
                            ErrorKind::Type,
                            pos,
                            format!("`{symbol}` needs integer operands, found {ty}"),
                        ))
                    }
                };
                let code = match op {
                    BinaryOp::Add => Expr::Arith(Arith::Add, t, operands),
                    BinaryOp::Sub => Expr::Arith(Arith::Sub, t, operands),
                    BinaryOp::Mul => Expr::Arith(Arith::Mul, t, operands),
                    _ => Expr::Divide {
                        modulo: op == BinaryOp::Mod,
                        ty: t,
                        operands,
                        line: pos.line,
                    },
                };
                (code, ETy::Int(t))
            }
            BinaryOp::And | BinaryOp::Or | BinaryOp::Xor => {
                let bitwise = match ty {
                    Type::Bool => true,
                    Type::Int(t) => t.is_bit_string(),
                };
                if !bitwise {
                    return Err(error(
                        ErrorKind::Type,
                        pos,
                        format!("`{symbol}` needs BOOL or bit string (BYTE..LWORD) operands, found {ty}"),
                    ));
                }
                let logic = match op {
                    BinaryOp::And => Logic::And,
                    BinaryOp::Or => Logic::Or,
                    _ => Logic::Xor,
                };
                (Expr::Logic(logic, operands), ETy::from(ty))
            }
            _ => {
                let compare = match op {
                    BinaryOp::Eq => Compare::Eq,
                    BinaryOp::Ne => Compare::Ne,
                    BinaryOp::Lt => Compare::Lt,
                    BinaryOp::Gt => Compare::Gt,
                    BinaryOp::Le => Compare::Le,
                    _ => Compare::Ge,
                };
                let unsigned = !matches!(ty, Type::Int(t) if t.is_signed());
                let code = Expr::Compare {
                    op: compare,
                    unsigned,
                    operands,
                };
                (code, ETy::Bool)
            }
        };
        fold(code, result, pos)
    }

    /// Reads a variable, an array element or an instance's input/output.
    fn load(&mut self, r: &VarRef) -> Result<Typed, Error> {
        let access = self.resolve(r, false)?;
        let code = match access.place {
            Place::Slot(slot) => {
                let var = access.root;
                let constant_scalar =
                    var.constant && r.parts.len() == 1 && matches!(var.ty, VarType::Scalar(_));
                if constant_scalar {
                    Expr::Const(self.init[var.slot as usize])
                } else {
                    Expr::Load(slot)
                }
            }
            Place::Elem(elem) => Expr::LoadElem(elem),
        };
        Ok(Typed {
            code,
            ty: ETy::from(access.ty),
        })
    }

    /// The place a variable path names, with the access rules of a read or
    /// (`write`) a write from this POU's body.
    pub(super) fn resolve(&mut self, r: &VarRef, write: bool) -> Result<Access<'c>, Error> {
        let first = &r.parts[0];
        let key = first.name.key();
        let Some(root) = lookup(self.vars, self.var_index, &key) else {
            let message = if self.index.contains_key(&key) {
                format!("`{}` is a POU, not a variable", first.name.text)
            } else {
                format!("undeclared variable `{}`", first.name.text)
            };
            return Err(error(ErrorKind::Name, first.name.pos, message));
        };
        if self.initialiser && !(root.constant && r.parts.len() == 1 && first.index.is_none()) {
            return Err(error(
                ErrorKind::Type,
                first.name.pos,
                format!(
                    "an initial value may use literals and earlier scalar constants only, not `{}`",
                    first.name.text
                ),
            ));
        }
        if write {
            self.check_writable(root, first.name.pos)?;
        }
        let mut slot = root.slot;
        let mut var = root;
        let mut dynamic: Option<Box<ElemRef>> = None;
        for (k, part) in r.parts.iter().enumerate() {
            if k > 0 {
                let Some(fb) = var.instance_of.filter(|_| dynamic.is_none()) else {
                    return Err(error(
                        ErrorKind::Name,
                        part.name.pos,
                        format!("`{}` has no members", var.name),
                    ));
                };
                let fb = self.pou(fb as usize);
                let Some(member) = fb.var(&part.name.text) else {
                    return Err(error(
                        ErrorKind::Name,
                        part.name.pos,
                        format!(
                            "function block `{}` has no variable `{}`",
                            fb.name, part.name.text
                        ),
                    ));
                };
                check_visible(var, member, fb, write, part.name.pos)?;
                slot += member.slot;
                var = member;
            }
            if let Some(indices) = &part.index {
                dynamic = Some(self.index_into(var, slot, indices, part.name.pos)?);
            }
        }
        let ty = match (
            &var.ty,
            &dynamic,
            r.parts.last().and_then(|p| p.index.as_ref()),
        ) {
            (VarType::Scalar(ty), _, None) => *ty,
            (VarType::Array { element, .. }, Some(_), Some(_)) => *element,
            (VarType::Array { .. }, _, _) => {
                return Err(error(
                    ErrorKind::Type,
                    r.pos(),
                    format!("`{}` is an array; index it", var.name),
                ))
            }
            (VarType::Instance(fb), _, None) => {
                return Err(error(
                    ErrorKind::Type,
                    r.pos(),
                    format!("`{}` is an instance of {fb}, not a value", var.name),
                ))
            }
            _ => {
                return Err(error(
                    ErrorKind::Type,
                    r.pos(),
                    format!("`{}` is not an array", var.name),
                ))
            }
        };
        let place = match dynamic {
            Some(elem) if elem.dims.iter().all(|d| matches!(d.index, Expr::Const(_))) => {
                Place::Slot(elem.base + static_offset(&elem))
            }
            Some(elem) => Place::Elem(elem),
            None => Place::Slot(slot),
        };
        Ok(Access { place, ty, root })
    }

    fn check_writable(&self, var: &Variable, pos: Pos) -> Result<(), Error> {
        let reason = if var.constant {
            "is a constant"
        } else if var.section == Section::Input {
            "is an input (VAR_INPUT); a POU does not assign its inputs"
        } else if var.is_located_input() {
            "is located at an input address"
        } else if self.for_vars.contains(&var.slot) {
            "is the control variable of an enclosing FOR loop"
        } else {
            return Ok(());
        };
        Err(error(
            ErrorKind::Access,
            pos,
            format!("`{}` {reason}", var.name),
        ))
    }

    /// An array element: bounds checked now for constant indices.
    fn index_into(
        &mut self,
        var: &Variable,
        base: u32,
        indices: &[ast::Expr],
        pos: Pos,
    ) -> Result<Box<ElemRef>, Error> {
        let VarType::Array { dims, .. } = &var.ty else {
            return Err(error(
                ErrorKind::Type,
                pos,
                format!("`{}` is not an array", var.name),
            ));
        };
        if dims.len() != indices.len() {
            return Err(error(
                ErrorKind::Type,
                pos,
                format!(
                    "`{}` has {} dimension(s), indexed with {}",
                    var.name,
                    dims.len(),
                    indices.len()
                ),
            ));
        }
        let mut stride: u32 = 1;
        let mut out = Vec::with_capacity(dims.len());
        for (&(lo, hi), e) in dims.iter().zip(indices).rev() {
            let outer = self.expected.take();
            let typed = self.expr(e);
            self.expected = outer;
            let typed = typed?;
            let (index, unsigned) = match typed.ty {
                ETy::Literal(v) => {
                    if v < i128::from(lo) || v > i128::from(hi) {
                        return Err(error(
                            ErrorKind::Range,
                            e.pos(),
                            format!("index {v} outside {lo}..{hi} of `{}`", var.name),
                        ));
                    }
                    (Expr::Const(v as i64), false)
                }
                ETy::Int(t) if !t.is_bit_string() => {
                    if let Expr::Const(cell) = typed.code {
                        let v = t.value_of(cell);
                        if v < i128::from(lo) || v > i128::from(hi) {
                            return Err(error(
                                ErrorKind::Range,
                                e.pos(),
                                format!("index {v} outside {lo}..{hi} of `{}`", var.name),
                            ));
                        }
                        (Expr::Const(v as i64), false)
                    } else {
                        (typed.code, !t.is_signed())
                    }
                }
                ty => {
                    return Err(error(
                        ErrorKind::Type,
                        e.pos(),
                        format!("an array index must be an integer, found {ty}"),
                    ))
                }
            };
            out.push(Dim {
                lo,
                hi,
                stride,
                index,
                unsigned,
            });
            stride *= (hi - lo + 1) as u32;
        }
        out.reverse();
        Ok(Box::new(ElemRef {
            base,
            dims: out.into_boxed_slice(),
            line: pos.line,
        }))
    }

    fn call_expr(&mut self, name: &ast::Ident, args: &[ast::Arg]) -> Result<Typed, Error> {
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

fn literal(v: i128) -> Typed {
    Typed {
        code: Expr::Const(0),
        ty: ETy::Literal(v),
    }
}

fn typed_literal(ty: &ast::Ident, value: TypedValue, pos: Pos) -> Result<Typed, Error> {
    let Some(t) = Type::from_name(&ty.text) else {
        return Err(error(
            ErrorKind::Type,
            pos,
            format!("`{}#` is not an elementary type prefix", ty.text),
        ));
    };
    let cell = match (t, value) {
        (Type::Bool, TypedValue::Bool(b)) => i64::from(b),
        (Type::Bool, TypedValue::Int(v @ (0 | 1))) => v as i64,
        (Type::Bool, TypedValue::Int(v)) => {
            return Err(error(
                ErrorKind::Range,
                pos,
                format!("BOOL#{v}: a BOOL literal is 0 or 1"),
            ))
        }
        (Type::Int(it), TypedValue::Int(v)) if it.contains(v) => it.cell_of(v),
        (Type::Int(it), TypedValue::Int(v)) => {
            return Err(error(
                ErrorKind::Range,
                pos,
                format!("{v} does not fit {it} ({}..{})", it.min(), it.max()),
            ))
        }
        _ => return Err(error(ErrorKind::Type, pos, format!("invalid {t} literal"))),
    };
    Ok(Typed {
        code: Expr::Const(cell),
        ty: ETy::from(t),
    })
}

/// Two untyped literals combine exactly (no width yet), as IEC constant
/// expressions do.
fn fold_literals(op: BinaryOp, a: i128, b: i128, pos: Pos) -> Result<Typed, Error> {
    let range = |v: Option<i128>| {
        v.ok_or_else(|| error(ErrorKind::Range, pos, "constant expression overflows"))
    };
    let zero = || {
        error(
            ErrorKind::Range,
            pos,
            "division by zero in a constant expression",
        )
    };
    let boolean = |b: bool| Typed {
        code: Expr::Const(i64::from(b)),
        ty: ETy::Bool,
    };
    Ok(match op {
        BinaryOp::Add => literal(range(a.checked_add(b))?),
        BinaryOp::Sub => literal(range(a.checked_sub(b))?),
        BinaryOp::Mul => literal(range(a.checked_mul(b))?),
        BinaryOp::Div if b == 0 => return Err(zero()),
        BinaryOp::Mod if b == 0 => return Err(zero()),
        BinaryOp::Div => literal(a / b),
        BinaryOp::Mod => literal(a % b),
        BinaryOp::Eq => boolean(a == b),
        BinaryOp::Ne => boolean(a != b),
        BinaryOp::Lt => boolean(a < b),
        BinaryOp::Gt => boolean(a > b),
        BinaryOp::Le => boolean(a <= b),
        BinaryOp::Ge => boolean(a >= b),
        BinaryOp::And | BinaryOp::Or | BinaryOp::Xor => {
            return Err(error(
                ErrorKind::Type,
                pos,
                format!(
                    "`{}` of two untyped literals: give one a type (e.g. WORD#16#FF)",
                    op.symbol()
                ),
            ))
        }
    })
}

/// Evaluates `code` now if all its operands are constants.
fn fold(code: Expr, ty: ETy, pos: Pos) -> Result<Typed, Error> {
    if !operands_constant(&code) {
        return Ok(Typed { code, ty });
    }
    match eval_const(&code) {
        Ok(cell) => Ok(Typed {
            code: Expr::Const(cell),
            ty,
        }),
        Err(e) => Err(error(
            ErrorKind::Range,
            pos,
            format!("constant expression: {}", e.fault),
        )),
    }
}

fn operands_constant(code: &Expr) -> bool {
    let c = |e: &Expr| matches!(e, Expr::Const(_));
    match code {
        Expr::Not(e)
        | Expr::BitNot(_, e)
        | Expr::Neg(_, e)
        | Expr::Truncate(_, e)
        | Expr::NonZero(e) => c(e),
        Expr::Arith(_, _, ops)
        | Expr::Divide { operands: ops, .. }
        | Expr::Compare { operands: ops, .. }
        | Expr::Logic(_, ops) => c(&ops.0) && c(&ops.1),
        Expr::Builtin(_, args) => args.iter().all(c),
        Expr::Const(_) | Expr::Load(_) | Expr::LoadElem(_) | Expr::Call(_) => false,
    }
}

/// The offset of an element whose indices are all constant.
fn static_offset(elem: &ElemRef) -> u32 {
    elem.dims
        .iter()
        .map(|d| {
            let Expr::Const(i) = d.index else {
                unreachable!("checked constant")
            };
            (i - d.lo) as u32 * d.stride
        })
        .sum()
}

/// What an instance shows outside: inputs (read) and outputs (read); both
/// are written only by a call.
fn check_visible(
    instance: &Variable,
    member: &Variable,
    fb: &Pou,
    write: bool,
    pos: Pos,
) -> Result<(), Error> {
    let shown = matches!(member.section, Section::Input | Section::Output);
    if !shown {
        return Err(error(
            ErrorKind::Access,
            pos,
            format!(
                "`{}.{}` is internal to {}; only inputs and outputs are visible outside",
                instance.name, member.name, fb.name
            ),
        ));
    }
    if write {
        let how = if member.section == Section::Input {
            format!(
                "is set by a call `{}({} := ...)`",
                instance.name, member.name
            )
        } else {
            format!("is an output, written only by {}", fb.name)
        };
        return Err(error(
            ErrorKind::Access,
            pos,
            format!("`{}.{}` {how}", instance.name, member.name),
        ));
    }
    Ok(())
}
