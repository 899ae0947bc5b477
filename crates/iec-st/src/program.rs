//! A compiled source file: every POU with its variable table, frame layout,
//! initial values and resolved body.

use rustc_hash::FxHashMap;

use crate::ast::{PouKind, Section};
use crate::code::Block;
use crate::configuration::Configuration;
use crate::types::Type;

/// The shape of a declared variable.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum VarType {
    /// A BOOL or integer.
    Scalar(Type),
    /// An array of scalars, stored row-major (last index fastest).
    Array {
        /// The element type.
        element: Type,
        /// `(lo, hi)` of each dimension, inclusive.
        dims: Vec<(i64, i64)>,
    },
    /// An instance of the named function block.
    Instance(String),
}

/// A declared variable, as the host sees it.
#[derive(Clone, Debug)]
pub struct Variable {
    /// The name as declared.
    pub name: String,
    /// The block it is declared in.
    pub section: Section,
    /// Declared in `VAR CONSTANT`.
    pub constant: bool,
    /// `AT %...` address, upper case.
    pub address: Option<String>,
    /// Its type.
    pub ty: VarType,
    /// First cell in the POU's frame.
    pub(crate) slot: u32,
    /// The function block of an instance.
    pub(crate) instance_of: Option<u32>,
}

impl Variable {
    /// Is it a located input (`AT %I...`), which the host writes?
    pub fn is_located_input(&self) -> bool {
        self.address.as_deref().is_some_and(|a| a.starts_with("%I"))
    }
}

/// A compiled POU.
#[derive(Clone, Debug)]
pub(crate) struct Pou {
    pub name: String,
    pub kind: PouKind,
    /// Cells in one frame, nested instances included.
    pub size: usize,
    /// The frame's cells at start (nested instances' initial values included).
    pub init: Vec<i64>,
    /// VAR_TEMP cells and their initial values, reset at every call.
    pub temps: Vec<(u32, i64)>,
    pub vars: Vec<Variable>,
    /// Upper-case name → index in `vars`.
    pub index: FxHashMap<String, usize>,
    /// VAR_INPUT variables in declaration order (positional arguments).
    pub inputs: Vec<usize>,
    /// A function's result: slot and type.
    pub result: Option<(u32, Type)>,
    /// A function's frame, at a fixed place in every instance's memory.
    pub base: usize,
    pub body: Block,
}

impl Pou {
    pub fn var(&self, name: &str) -> Option<&Variable> {
        self.index
            .get(&name.to_ascii_uppercase())
            .map(|&i| &self.vars[i])
    }
}

/// Every POU of a source file, checked and resolved.
#[derive(Clone, Debug)]
pub(crate) struct Program {
    pub pous: Vec<Pou>,
    /// Upper-case POU name → index in `pous`.
    pub index: FxHashMap<String, usize>,
    /// Cells before the top instance's frame: the functions' frames.
    pub functions_size: usize,
    /// The checked `CONFIGURATION`s, in order.
    pub configurations: Vec<Configuration>,
}
