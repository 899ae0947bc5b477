//! Values exchanged with the host: a BOOL or an integer with its type.

use std::fmt;

use crate::types::{IntType, Type};

/// A typed scalar value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Value {
    /// A BOOL.
    Bool(bool),
    /// An integer or bit string; `value` is within `ty`'s range.
    Int {
        /// The IEC type.
        ty: IntType,
        /// The mathematical value (a ULINT needs more than `i64`).
        value: i128,
    },
}

impl Value {
    /// An integer of type `ty`; `None` if `value` is out of its range.
    pub fn int(ty: IntType, value: i128) -> Option<Value> {
        ty.contains(value).then_some(Value::Int { ty, value })
    }

    /// The value's type.
    pub fn ty(&self) -> Type {
        match self {
            Value::Bool(_) => Type::Bool,
            Value::Int { ty, .. } => Type::Int(*ty),
        }
    }

    /// The BOOL, if it is one.
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Bool(b) => Some(*b),
            Value::Int { .. } => None,
        }
    }

    /// The integer, if it is one and fits an `i64`.
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Value::Bool(_) => None,
            Value::Int { value, .. } => i64::try_from(*value).ok(),
        }
    }

    /// The integer, if it is one.
    pub fn as_i128(&self) -> Option<i128> {
        match self {
            Value::Bool(_) => None,
            Value::Int { value, .. } => Some(*value),
        }
    }

    /// The value from a stored cell of type `ty`.
    pub(crate) fn from_cell(ty: Type, cell: i64) -> Value {
        match ty {
            Type::Bool => Value::Bool(cell != 0),
            Type::Int(ty) => Value::Int {
                ty,
                value: ty.value_of(cell),
            },
        }
    }
}

impl fmt::Display for Value {
    /// As an IEC literal: `TRUE`, `INT#-5`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Bool(true) => f.write_str("TRUE"),
            Value::Bool(false) => f.write_str("FALSE"),
            Value::Int { ty, value } => write!(f, "{ty}#{value}"),
        }
    }
}

impl From<bool> for Value {
    fn from(b: bool) -> Value {
        Value::Bool(b)
    }
}
