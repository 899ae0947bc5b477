//! Expressions: typing (with untyped literals that take their context's
//! type), constant folding, and variable access with its visibility rules.

use std::fmt;

use rustc_hash::FxHashMap;

use super::layout::Frame;
use crate::ast::{self, BinaryOp, TypedValue, UnaryOp};
use crate::code::{Arith, Compare, Expr, Logic};
use crate::error::{Error, ErrorKind, Pos};
use crate::program::{Pou, Variable};
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

/// The compile context of one POU body or initialiser.
pub(crate) struct Cx<'c> {
    pub(super) pous: &'c [Option<Pou>],
    pub(super) index: &'c FxHashMap<String, usize>,
    pub(super) vars: &'c [Variable],
    pub(super) var_index: &'c FxHashMap<String, usize>,
    pub(super) init: &'c [i64],
    /// Compiling an initial value: only literals and earlier constants.
    pub(super) initialiser: bool,
    /// Slots of the enclosing FOR loops' control variables.
    pub(super) for_vars: Vec<u32>,
    /// Depth of enclosing loops (for EXIT).
    pub(super) loops: u32,
    /// Functions called and where, for the recursion check.
    pub calls: Vec<(usize, Pos)>,
    /// The type the enclosing assignment or argument expects: gives
    /// `SEL(g, 1, 2)` and the like a type when all their values are literals.
    pub(super) expected: Option<Type>,
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
}

pub(super) fn literal(v: i128) -> Typed {
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
pub(super) fn fold(code: Expr, ty: ETy, pos: Pos) -> Result<Typed, Error> {
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
