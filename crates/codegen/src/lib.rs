//! PLC code generation: from supervisors and a PLC project to the program
//! the executor runs.
//!
//! The automata, their formats and the discrete-event operations live in
//! the [`des`] crate; they are re-exported here under their old paths
//! ([`automaton`], [`formats`], [`ops`], [`dot`], [`error`]).
//!
//! - [`backend`]: supervisors as bit-packed tables or CMSSM logic.
//! - [`dot`]: Graphviz output.
//! - [`project`]: PLC project files (`*.plc.toml`), parsed and validated.
//! - [`image`]: a project laid out as the executor's program image.
//! - [`emit`]: the generated Rust source; [`build`]: the build-script API.
//! - [`board`]: the `[board]` pin map as generated Rust and as a wiring
//!   table.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod backend;
pub mod board;
pub mod build;
pub mod emit;
pub mod iec;
pub mod image;
pub mod project;

pub use des;
pub use des::{automaton, dot, error, formats, ops};
pub use des::{Alphabet, Automaton, AutomatonBuilder, Error, EventId, Location, Result, StateId};
