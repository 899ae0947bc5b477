//! Errors: source errors with a position, host-API errors, run-time faults.

use thiserror::Error;

/// A line and column in the source, both 1-based (columns count bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Pos {
    /// Line, from 1.
    pub line: u32,
    /// Column, from 1.
    pub column: u32,
}

/// What kind of rule a source error broke.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// A character sequence that is no token.
    Lexical,
    /// Tokens in an order the grammar does not allow.
    Syntax,
    /// An undeclared, duplicate or misused name.
    Name,
    /// Operand or assignment types that do not match.
    Type,
    /// A write the POU may not do (constant, input, FOR variable).
    Access,
    /// A literal, bound or initialiser out of range.
    Range,
    /// Valid IEC 61131-3 outside the supported subset.
    Unsupported,
}

/// An error in a source file or in a use of the host API.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum Error {
    /// The source breaks a rule of the language.
    #[error("line {}, column {}: {message}", pos.line, pos.column)]
    Source {
        /// The rule broken.
        kind: ErrorKind,
        /// Where.
        pos: Pos,
        /// What, for a person.
        message: String,
    },
    /// The host asked for something the instance does not have or allow.
    #[error("{path}: {message}")]
    Host {
        /// The path, POU or slot asked for.
        path: String,
        /// What is wrong.
        message: String,
    },
}

impl Error {
    pub(crate) fn at(kind: ErrorKind, pos: Pos, message: impl Into<String>) -> Error {
        Error::Source {
            kind,
            pos,
            message: message.into(),
        }
    }

    pub(crate) fn host(path: impl Into<String>, message: impl Into<String>) -> Error {
        Error::Host {
            path: path.into(),
            message: message.into(),
        }
    }

    /// The kind of a source error; `None` for a host-API error.
    pub fn kind(&self) -> Option<ErrorKind> {
        match self {
            Error::Source { kind, .. } => Some(*kind),
            Error::Host { .. } => None,
        }
    }

    /// The line of a source error; `None` for a host-API error.
    pub fn line(&self) -> Option<u32> {
        match self {
            Error::Source { pos, .. } => Some(pos.line),
            Error::Host { .. } => None,
        }
    }
}

/// Why a call stopped.
#[derive(Clone, Copy, Debug, Error, PartialEq, Eq)]
pub enum Fault {
    /// An array index outside the declared bounds.
    #[error("array index {index} outside {lo}..{hi}")]
    IndexOutOfRange {
        /// The index evaluated.
        index: i128,
        /// Lower bound of that dimension.
        lo: i64,
        /// Upper bound of that dimension.
        hi: i64,
    },
    /// `/` or `MOD` with a zero divisor.
    #[error("division by zero")]
    DivisionByZero,
    /// More loop iterations in one call than the guard allows.
    #[error("more than {0} loop iterations in one call")]
    IterationLimit(u64),
}

/// A fault while running a call; the instance keeps the writes done before it.
#[derive(Clone, Copy, Debug, Error, PartialEq, Eq)]
#[error("run-time error at line {line}: {fault}")]
pub struct RuntimeError {
    /// The fault.
    pub fault: Fault,
    /// The source line of the expression or loop that faulted.
    pub line: u32,
}
