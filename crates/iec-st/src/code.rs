//! The checked, resolved form the interpreter runs: every name is a slot
//! (an offset into the instance's memory, relative to the running POU's
//! frame), every operator carries the type it works in.

use crate::types::IntType;

/// An expression; evaluates to one cell (see [`crate::types`]).
#[derive(Clone, Debug)]
pub(crate) enum Expr {
    Const(i64),
    Load(u32),
    LoadElem(Box<ElemRef>),
    /// Logical NOT of a BOOL.
    Not(Box<Expr>),
    /// Bitwise NOT of a bit string.
    BitNot(IntType, Box<Expr>),
    Neg(IntType, Box<Expr>),
    Arith(Arith, IntType, Box<(Expr, Expr)>),
    /// `/` and `MOD`, which fault on a zero divisor.
    Divide {
        modulo: bool,
        ty: IntType,
        operands: Box<(Expr, Expr)>,
        line: u32,
    },
    Compare {
        op: Compare,
        unsigned: bool,
        operands: Box<(Expr, Expr)>,
    },
    /// AND, OR, XOR: the same bit operation serves BOOL (0/1) and bit strings.
    Logic(Logic, Box<(Expr, Expr)>),
    /// Reduce to a narrower (or other-signedness) integer type.
    Truncate(IntType, Box<Expr>),
    /// Integer to BOOL: `<> 0`.
    NonZero(Box<Expr>),
    Builtin(Builtin, Box<[Expr]>),
    Call(Box<FunctionCall>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Arith {
    Add,
    Sub,
    Mul,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Compare {
    Eq,
    Ne,
    Lt,
    Gt,
    Le,
    Ge,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Logic {
    And,
    Or,
    Xor,
}

/// Standard functions, each resolved to the type it works in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Builtin {
    Abs(IntType),
    /// MIN or MAX over two or more operands.
    Min {
        unsigned: bool,
    },
    Max {
        unsigned: bool,
    },
    /// `LIMIT(MN, IN, MX)`.
    Limit {
        unsigned: bool,
    },
    /// `SEL(G, IN0, IN1)`.
    Sel,
    Shl(IntType),
    Shr(IntType),
    Rol(IntType),
    Ror(IntType),
}

/// An array element whose index is only known at run time.
#[derive(Clone, Debug)]
pub(crate) struct ElemRef {
    /// Slot of the first element.
    pub base: u32,
    pub dims: Box<[Dim]>,
    pub line: u32,
}

#[derive(Clone, Debug)]
pub(crate) struct Dim {
    pub lo: i64,
    pub hi: i64,
    /// Cells between consecutive indices of this dimension.
    pub stride: u32,
    pub index: Expr,
    /// The index expression's type is unsigned (its cell may exceed `i64`).
    pub unsigned: bool,
}

/// A user FUNCTION invoked in an expression or as a statement.
#[derive(Clone, Debug)]
pub(crate) struct FunctionCall {
    pub pou: u32,
    /// (input slot in the function's frame, argument).
    pub args: Vec<(u32, Expr)>,
}

/// Where an assignment writes.
#[derive(Clone, Debug)]
pub(crate) enum Place {
    Slot(u32),
    Elem(Box<ElemRef>),
}

pub(crate) type Block = Vec<Stmt>;

#[derive(Clone, Debug)]
pub(crate) enum Stmt {
    Assign(Place, Expr),
    If {
        branches: Vec<(Expr, Block)>,
        otherwise: Block,
    },
    Case {
        selector: Expr,
        unsigned: bool,
        /// Disjoint label ranges sorted by `lo`: (lo, hi, arm), as values.
        labels: Vec<(i128, i128, u32)>,
        arms: Vec<Block>,
        otherwise: Block,
    },
    For {
        var: u32,
        ty: IntType,
        from: Expr,
        to: Expr,
        by: Expr,
        body: Block,
        line: u32,
    },
    While {
        cond: Expr,
        body: Block,
        line: u32,
    },
    Repeat {
        body: Block,
        until: Expr,
        line: u32,
    },
    Exit,
    Return,
    CallBlock(Box<BlockCall>),
    CallFunction(Box<FunctionCall>),
}

/// `inst(A := x, Q => y)`.
#[derive(Clone, Debug)]
pub(crate) struct BlockCall {
    /// Slot of the instance's frame in the caller's frame.
    pub instance: u32,
    pub pou: u32,
    /// (input slot in the instance frame, argument), assigned in order.
    pub inputs: Vec<(u32, Expr)>,
    /// (output slot in the instance frame, destination), copied after the body.
    pub outputs: Vec<(u32, Place)>,
}
