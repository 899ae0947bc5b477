//! The PLC core on a PC: the same executor as the firmware, a virtual
//! clock, replay of input files into traces and waveforms, and (later)
//! plant simulations and scenario suites.
//!
//! - [`sim`]: a controller on a virtual clock ([`Sim`]).
//! - [`inputs`] reads and writes `inputs.csv`.
//! - [`trace`]: trace rows and `trace.csv`.
//! - [`vcd`] writes waveforms.
//! - [`lockstep`]: both backends side by side, compared every scan.
//! - [`replay`]: a whole input file through a project.
//! - [`scenario`]: postcard scenarios for the QEMU harness, random inputs.
//! - [`plant`]: the boiler as a physical plant in closed loop, and its safety invariants.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod inputs;
pub mod lockstep;
pub mod plant;
pub mod replay;
pub mod scenario;
pub mod sim;
pub mod trace;
pub mod vcd;

pub use lockstep::Lockstep;
pub use sim::{RuntimeProgram, Sim, SimError};
pub use trace::TraceRow;
