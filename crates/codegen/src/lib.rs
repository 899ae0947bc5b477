//! PLC code generation, the build-time stage: a validated PLC project
//! ([`plc_project`]) lowered to the executor's program image, its
//! supervisors encoded by a backend, and the Rust source a build script
//! writes.
//!
//! - [`backend`]: supervisors as bit-packed tables or CMSSM logic.
//! - [`lower`]: a project lowered once to the executor's program image
//!   (what each backend means is said there).
//! - [`emit`]: the generated Rust source; [`build`]: the build-script API.
//! - [`board`]: the `[board]` pin map as generated Rust and as a wiring
//!   table.
//! - [`Error`]: what generation refuses, a variant each, wrapping the
//!   automaton layer's [`des::Error`] for invalid projects and models.
//!
//! The automata and their operations are the [`des`] crate's; the front end
//! that reads projects is [`plc_project`]; the IEC 61131-3 export is the
//! `iec-export` crate and the command line the `codegen-cli` package.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod backend;
pub mod board;
pub mod build;
pub mod emit;
mod error;
pub mod lower;

pub use error::{Error, Result};
