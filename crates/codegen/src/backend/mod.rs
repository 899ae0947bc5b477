//! Backends: how a supervisor becomes code the executor runs.
//!
//! - [`table`]: bit-packed transition tables, decoded by the executor.
//! - `logic`: CMSSM next-state and output functions (Leduc–Wonham),
//!   minimised with Espresso.

pub mod logic;
pub mod table;
