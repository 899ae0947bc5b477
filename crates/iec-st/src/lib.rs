//! A parser, checker and interpreter for the subset of IEC 61131-3 (3rd
//! edition) Structured Text that `codegen st` emits. It is a test tool: it
//! runs an exported program in lockstep with the host simulation.
//!
//! Written from the standard, independently of the exporter, and strict like
//! a PLC compiler: undeclared names, type mismatches (no implicit conversion
//! except widening within SINT..LINT, USINT..ULINT, BYTE..LWORD), writes to
//! constants, inputs or FOR variables are compile errors with a line and
//! column; an array index out of range, a division by zero or a runaway
//! loop is a [`RuntimeError`], never a clamp. Integer arithmetic wraps
//! modulo the type's width like a PLC's.
//!
//! [`parse`] lexes, parses and compiles every POU, resolving names to slots,
//! so a [`Instance::call`] only interprets resolved code. A `CONFIGURATION`
//! (resources, cyclic tasks, program instances) is checked against the
//! POUs and listed by [`SourceFile::configurations`]; the host runs the
//! program at its task's interval.
//!
//! ```
//! let file = iec_st::parse(
//!     "FUNCTION_BLOCK counter
//!      VAR_INPUT up : BOOL; END_VAR
//!      VAR_OUTPUT n : UINT; END_VAR
//!      IF up THEN n := n + 1; END_IF;
//!      END_FUNCTION_BLOCK",
//! )?;
//! let mut fb = file.instantiate("counter")?;
//! fb.set("up", true.into())?;
//! fb.call()?;
//! fb.call()?;
//! assert_eq!(fb.get("n")?.as_i64(), Some(2));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

mod ast;
mod code;
mod compile;
mod configuration;
mod error;
mod instance;
mod lexer;
mod parser;
mod program;
mod run;
mod types;
mod value;

pub use ast::{PouKind, Section};
pub use configuration::{Configuration, ProgramInstance, Resource, Task};
pub use error::{Error, ErrorKind, Fault, Pos, RuntimeError};
pub use instance::{Instance, Slot, SourceFile, DEFAULT_ITERATION_LIMIT};
pub use program::{VarType, Variable};
pub use types::{Family, IntType, Type};
pub use value::Value;

/// Parses and checks a source file of POUs; the error, if any, carries the
/// line and column.
pub fn parse(source: &str) -> Result<SourceFile, Error> {
    let file = parser::parse_file(source)?;
    let program = compile::compile(&file)?;
    Ok(SourceFile::new(program))
}
