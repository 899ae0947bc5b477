//! The PLC scan cycle that runs synthesised supervisors.
//!
//! `#![no_std]`, no allocation (unless the `alloc` feature is asked for,
//! for hosts), no `unsafe`. The same source runs in the firmware on a
//! Cortex-M and in `host-sim` on a PC, so both produce the same trace.
//!
//! # Guarantees (SEMANTICS.md)
//!
//! Each call of [`Controller::scan`] with a time `t` (ms, wrapping) and the
//! raw input image:
//!
//! 1. **Samples** the inputs and debounces them (an input with
//!    `debounce_scans = d > 1` follows its raw value only after `d`
//!    consecutive differing scans, this one included); edges compare the
//!    filtered image with the previous scan's. Scan 0 has no edges, and
//!    its filtered value of every input, debounced or not, is the raw
//!    sample (a filter has no history to hold against at power-on).
//!    Filtering goes on in fault mode and is not reset by a fault reset.
//! 2. **In fault mode** writes the safe output image, unless the `reset`
//!    input rises: then everything is re-initialised and the initial image
//!    written; either way the scan ends there.
//! 3. **Timers** whose deadline is reached stop; their bound events occur.
//!    A timer started in scan k is first checked in scan k+1.
//! 4. **Uncontrollable events** that occurred (edges with their
//!    `when`/`unless` conditions, expiries) run in declaration order, each
//!    once: feasible ones (every supervisor having the event can take it)
//!    execute; an unexpected one enters fault mode with safe outputs, or is
//!    dropped and counted under the `ignore` policy.
//! 5. **Controllable events**: up to `max_commands_per_scan` times (0 = no
//!    limit), the first event in declaration order that is feasible, not
//!    executed in this scan, and whose request input (if any) is 1.
//! 6. **Outputs**: action-driven levels and Moore outputs (OR over the
//!    state map), written as one image.
//! 7. **Record**: a [`ScanRecord`] with the executed and unexpected events,
//!    the state vector, the outputs and the fault cause.
//!
//! The controller only ever moves a supervisor along a defined transition,
//! so every executed controllable event is allowed by every supervisor that
//! has it (control equivalence with the supervisors, modular or not; the
//! product is never built). A supervisor state out of range or a program
//! image whose CRC does not match is a `Corrupt` fault.
//!
//! The tests proving this are in `crates/codegen/tests/conformance.rs`
//! (table and logic backends against a reference interpreter over random
//! projects and inputs) and in this crate's unit tests.
//!
//! # Pieces
//!
//! - [`program`]: the static description ([`Config`]) and the [`Program`]
//!   trait for supervisor dynamics.
//! - [`table`]: bit-packed transition tables ([`TableProgram`]) and the
//!   image CRC.
//! - [`memory`]: RAM with sizes in the types ([`memory::StaticMemory`]).
//! - [`Controller`]: the scan cycle.
//! - [`pacing`]: when scans start: the fixed grid, skipped periods,
//!   overruns.
//!
//! # Features
//!
//! - `alloc`: [`memory::HeapMemory`], sized at run time (hosts).
//! - `defmt`: `defmt::Format` for [`Fault`] and [`Counters`].
//! - `replay`: recorded scans for replay harnesses (`replay` module).

#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

#[cfg(feature = "alloc")]
extern crate alloc;

mod controller;
mod inputs;
pub mod memory;
pub mod pacing;
pub mod program;
mod record;
#[cfg(feature = "replay")]
pub mod replay;
pub mod table;
mod timers;

pub use controller::{Controller, SizeMismatch};
pub use memory::Memory;
pub use program::{Config, Program};
pub use record::{Counters, Fault, ScanRecord};
pub use table::TableProgram;

#[cfg(test)]
mod tests;
