//! Program organisation units as the exporters see them: declarations
//! and an ST body, printed as Structured Text ([`super::st`]) or wrapped
//! in PLCopen XML ([`super::plcopen`]).

/// What kind of POU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PouKind {
    /// A function block: state kept between calls, instantiated by a
    /// program.
    FunctionBlock,
    /// A program: the unit a PLC task runs.
    Program,
}

/// An elementary or array type.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Type {
    /// `BOOL`.
    Bool,
    /// `SINT`, 8-bit signed.
    Sint,
    /// `INT`, 16-bit signed.
    Int,
    /// `DINT`, 32-bit signed.
    Dint,
    /// `UDINT`, 32-bit unsigned.
    Udint,
    /// `ARRAY [lo..hi, …] OF elem`.
    Array {
        /// Bounds of each dimension, inclusive.
        dims: Vec<(i64, i64)>,
        /// Element type (elementary).
        elem: Box<Type>,
    },
    /// An instance of the function block of this name.
    Instance(String),
}

impl Type {
    /// An array `[0..len-1]` of `elem`.
    pub fn array(len: usize, elem: Type) -> Type {
        Type::Array {
            dims: vec![(0, len as i64 - 1)],
            elem: Box::new(elem),
        }
    }

    /// The smallest signed integer type holding `lo..=hi`.
    pub fn signed_for(lo: i64, hi: i64) -> Type {
        if lo >= i64::from(i8::MIN) && hi <= i64::from(i8::MAX) {
            Type::Sint
        } else if lo >= i64::from(i16::MIN) && hi <= i64::from(i16::MAX) {
            Type::Int
        } else {
            Type::Dint
        }
    }

    /// Its IEC name (`BOOL`, `ARRAY [0..3] OF INT`, …).
    pub fn iec(&self) -> String {
        match self {
            Type::Bool => "BOOL".into(),
            Type::Sint => "SINT".into(),
            Type::Int => "INT".into(),
            Type::Dint => "DINT".into(),
            Type::Udint => "UDINT".into(),
            Type::Array { dims, elem } => {
                let dims: Vec<String> = dims.iter().map(|(lo, hi)| format!("{lo}..{hi}")).collect();
                format!("ARRAY [{}] OF {}", dims.join(", "), elem.iec())
            }
            Type::Instance(name) => name.clone(),
        }
    }

    /// Bytes of one value (arrays: every element), as a PLC stores them:
    /// a `BOOL` in one byte.
    pub fn bytes(&self) -> usize {
        match self {
            Type::Bool | Type::Sint => 1,
            Type::Int => 2,
            Type::Dint | Type::Udint => 4,
            Type::Array { dims, elem } => {
                dims.iter()
                    .map(|(lo, hi)| (hi - lo + 1) as usize)
                    .product::<usize>()
                    * elem.bytes()
            }
            Type::Instance(_) => 0,
        }
    }
}

/// An initial value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Init {
    /// One literal.
    Value(String),
    /// An array's elements in row-major order, in rows (a row each for
    /// one state of a transition array), each with a comment naming it.
    Rows(Vec<(String, Vec<String>)>),
}

/// One declared variable.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Var {
    /// Its IEC name.
    pub name: String,
    /// Its type.
    pub ty: Type,
    /// Its initial value, if not the type's default.
    pub init: Option<Init>,
    /// A direct address (`%IX0.0`), for located variables of programs.
    pub address: Option<String>,
    /// What it is, one line.
    pub doc: String,
}

impl Var {
    /// A variable with no initial value and no address.
    pub fn new(name: impl Into<String>, ty: Type, doc: impl Into<String>) -> Var {
        Var {
            name: name.into(),
            ty,
            init: None,
            address: None,
            doc: doc.into(),
        }
    }

    /// The same with an initial value.
    pub fn init(mut self, init: Init) -> Var {
        self.init = Some(init);
        self
    }
}

/// Which variable section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Section {
    /// `VAR_INPUT`.
    Input,
    /// `VAR_OUTPUT`.
    Output,
    /// `VAR`.
    Local,
    /// `VAR CONSTANT`.
    Constant,
}

impl Section {
    /// The keyword(s) opening the section in ST.
    pub fn keyword(self) -> &'static str {
        match self {
            Section::Input => "VAR_INPUT",
            Section::Output => "VAR_OUTPUT",
            Section::Local => "VAR",
            Section::Constant => "VAR CONSTANT",
        }
    }
}

/// A section of declarations.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VarBlock {
    /// Which section.
    pub section: Section,
    /// Its variables, in order.
    pub vars: Vec<Var>,
}

/// A POU: interface, locals and an ST body.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pou {
    /// Its IEC name.
    pub name: String,
    /// Function block or program.
    pub kind: PouKind,
    /// What it is; the first lines of the POU in ST.
    pub doc: Vec<String>,
    /// Declarations, in order (several blocks of one section may appear).
    pub blocks: Vec<VarBlock>,
    /// The statements, one per line, indented by four spaces per level.
    pub body: Vec<String>,
}

impl Pou {
    /// Every variable of `section`.
    pub fn vars(&self, section: Section) -> impl Iterator<Item = &Var> {
        self.blocks
            .iter()
            .filter(move |b| b.section == section)
            .flat_map(|b| &b.vars)
    }
}
