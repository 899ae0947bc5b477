//! Supervisor synthesis and PLC code generation.
//!
//! - [`automaton`]: the automaton model (dense ids, CSR transitions).
//! - [`formats`]: native TOML, libFAUDES `.gen`, TCT `.ads`, Waters `.wmod`.
//! - [`ops`]: the discrete-event operations (sync, supcon, minstate, …).
//! - [`backend`]: supervisors as bit-packed tables or CMSSM logic.
//! - [`dot`]: Graphviz output.
//! - [`project`]: PLC project files (`*.plc.toml`), parsed and validated.
//! - [`image`]: a project laid out as the executor's program image.
//! - [`emit`]: the generated Rust source; [`build`]: the build-script API.
//! - [`board`]: the `[board]` pin map as generated Rust and as a wiring
//!   table.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod automaton;
pub mod backend;
pub mod board;
pub mod build;
pub mod dot;
pub mod emit;
pub mod error;
pub mod formats;
pub mod image;
pub mod ops;
pub mod project;
#[cfg(test)]
mod testing;

pub use automaton::{Alphabet, Automaton, AutomatonBuilder, EventId, StateId};
pub use error::{Error, Location, Result};
