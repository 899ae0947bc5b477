//! The syntax tree the parser builds and the compiler checks.

use crate::error::Pos;

/// A name as written, with its position.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Ident {
    pub text: String,
    pub pos: Pos,
}

impl Ident {
    /// The case-folded key names are compared by.
    pub fn key(&self) -> String {
        self.text.to_ascii_uppercase()
    }
}

/// What a POU is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PouKind {
    /// `PROGRAM`.
    Program,
    /// `FUNCTION_BLOCK`.
    FunctionBlock,
    /// `FUNCTION`.
    Function,
}

#[derive(Clone, Debug)]
pub(crate) struct Pou {
    pub kind: PouKind,
    pub name: Ident,
    /// A function's result type.
    pub result: Option<TypeRef>,
    pub blocks: Vec<VarBlock>,
    pub body: Vec<Stmt>,
}

/// The section a variable is declared in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Section {
    /// `VAR_INPUT`.
    Input,
    /// `VAR_OUTPUT`.
    Output,
    /// `VAR` (also `VAR CONSTANT`).
    Local,
    /// `VAR_TEMP`: re-initialised at every call.
    Temp,
}

#[derive(Clone, Debug)]
pub(crate) struct VarBlock {
    pub section: Section,
    pub constant: bool,
    pub decls: Vec<VarDecl>,
}

#[derive(Clone, Debug)]
pub(crate) struct VarDecl {
    pub names: Vec<Ident>,
    pub address: Option<(String, Pos)>,
    pub ty: TypeRef,
    pub init: Option<Init>,
}

#[derive(Clone, Debug)]
pub(crate) enum TypeRef {
    /// An elementary type or a function block.
    Named(Ident),
    Array {
        dims: Vec<(i128, i128)>,
        element: Ident,
        pos: Pos,
    },
}

#[derive(Clone, Debug)]
pub(crate) enum Init {
    Scalar(Expr),
    Array(Vec<ArrayInit>, Pos),
}

#[derive(Clone, Debug)]
pub(crate) enum ArrayInit {
    Value(Expr),
    /// `n(v)`, or `n()` for `n` defaults.
    Repeat {
        count: u128,
        value: Option<Expr>,
        pos: Pos,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum UnaryOp {
    Neg,
    Not,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BinaryOp {
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Lt,
    Gt,
    Le,
    Ge,
    Eq,
    Ne,
    And,
    Xor,
    Or,
}

impl BinaryOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Mod => "MOD",
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Lt => "<",
            BinaryOp::Gt => ">",
            BinaryOp::Le => "<=",
            BinaryOp::Ge => ">=",
            BinaryOp::Eq => "=",
            BinaryOp::Ne => "<>",
            BinaryOp::And => "AND",
            BinaryOp::Xor => "XOR",
            BinaryOp::Or => "OR",
        }
    }
}

/// A typed literal's value part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TypedValue {
    Int(i128),
    Bool(bool),
}

#[derive(Clone, Debug)]
pub(crate) enum Expr {
    /// An untyped integer literal (never negative; `-` is an operator).
    Int(u128, Pos),
    Bool(bool, Pos),
    Typed {
        ty: Ident,
        value: TypedValue,
        pos: Pos,
    },
    Var(VarRef),
    Call {
        name: Ident,
        args: Vec<Arg>,
    },
    Unary {
        op: UnaryOp,
        operand: Box<Expr>,
        pos: Pos,
    },
    Binary {
        op: BinaryOp,
        left: Box<Expr>,
        right: Box<Expr>,
        pos: Pos,
    },
}

impl Expr {
    pub fn pos(&self) -> Pos {
        match self {
            Expr::Int(_, pos) | Expr::Bool(_, pos) => *pos,
            Expr::Typed { pos, .. } | Expr::Unary { pos, .. } | Expr::Binary { pos, .. } => *pos,
            Expr::Var(v) => v.pos(),
            Expr::Call { name, .. } => name.pos,
        }
    }
}

/// `a`, `a[i, j]`, `inst.q`, `inst.arr[i]`.
#[derive(Clone, Debug)]
pub(crate) struct VarRef {
    pub parts: Vec<PathPart>,
}

impl VarRef {
    pub fn pos(&self) -> Pos {
        self.parts[0].name.pos
    }
}

#[derive(Clone, Debug)]
pub(crate) struct PathPart {
    pub name: Ident,
    pub index: Option<Vec<Expr>>,
}

#[derive(Clone, Debug)]
pub(crate) enum Arg {
    Positional(Expr),
    /// `name := expr`.
    Input(Ident, Expr),
    /// `name => variable`.
    Output(Ident, VarRef),
}

#[derive(Clone, Debug)]
pub(crate) enum CaseLabel {
    Value(Expr),
    Range(Expr, Expr),
}

#[derive(Clone, Debug)]
pub(crate) struct CaseArm {
    pub labels: Vec<CaseLabel>,
    pub body: Vec<Stmt>,
}

#[derive(Clone, Debug)]
pub(crate) enum Stmt {
    Assign {
        target: VarRef,
        value: Expr,
        pos: Pos,
    },
    /// A function block or function invoked as a statement.
    Call {
        name: Ident,
        args: Vec<Arg>,
    },
    If {
        branches: Vec<(Expr, Vec<Stmt>)>,
        otherwise: Vec<Stmt>,
    },
    Case {
        selector: Expr,
        arms: Vec<CaseArm>,
        otherwise: Vec<Stmt>,
    },
    For {
        var: Ident,
        from: Expr,
        to: Expr,
        by: Option<Expr>,
        body: Vec<Stmt>,
        pos: Pos,
    },
    While {
        cond: Expr,
        body: Vec<Stmt>,
        pos: Pos,
    },
    Repeat {
        body: Vec<Stmt>,
        until: Expr,
        pos: Pos,
    },
    Exit(Pos),
    Return,
}

/// A source file: its POUs and configurations, each in order.
#[derive(Clone, Debug, Default)]
pub(crate) struct SourceAst {
    pub pous: Vec<Pou>,
    pub configurations: Vec<ConfigurationDecl>,
}

/// `CONFIGURATION name ... END_CONFIGURATION`.
#[derive(Clone, Debug)]
pub(crate) struct ConfigurationDecl {
    pub name: Ident,
    pub resources: Vec<ResourceDecl>,
}

/// `RESOURCE name ON type ... END_RESOURCE`; both `None` for the single
/// resource of a configuration that declares tasks and programs directly.
#[derive(Clone, Debug)]
pub(crate) struct ResourceDecl {
    pub name: Option<Ident>,
    pub on: Option<Ident>,
    pub tasks: Vec<TaskDecl>,
    pub programs: Vec<ProgramDecl>,
}

/// `TASK name (INTERVAL := T#..., PRIORITY := n);`
#[derive(Clone, Debug)]
pub(crate) struct TaskDecl {
    pub name: Ident,
    /// Milliseconds and where the literal is.
    pub interval: Option<(i64, Pos)>,
    pub priority: Option<i64>,
}

/// `PROGRAM instance WITH task : pou;`
#[derive(Clone, Debug)]
pub(crate) struct ProgramDecl {
    pub name: Ident,
    pub task: Option<Ident>,
    pub pou: Ident,
}
