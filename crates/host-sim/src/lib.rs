//! The PLC core on a PC: the firmware's executor on a virtual clock, to
//! replay input files, record scenarios for the QEMU harness, and run the
//! boiler in closed loop with a simulation of its plant.
//!
//! - [`sim`]: a project on the executor and a virtual clock ([`Sim`]);
//!   [`lockstep`]: both backends side by side, compared every scan.
//! - [`inputs`] reads and writes `inputs.csv`; [`trace`]: trace rows and
//!   `trace.csv`; [`vcd`]: waveforms (GTKWave, Surfer), with [`gtkw`]
//!   save files that show them grouped.
//! - [`columns`]: terminal text within 120 columns (the timelines).
//! - [`plot`]: an SVG picture of any run (lanes of inputs, outputs,
//!   events, supervisor states, fault mode, analog quantities).
//! - [`replay`]: an input file through a project (`host-sim replay`);
//!   [`partial`]: output files that appear only once complete.
//! - [`scenario`]: postcard scenarios for the QEMU harness (`host-sim
//!   record`), from an input file or [`random_inputs`]; [`rng`]: the seeded
//!   generator behind everything random.
//! - [`serve`]: any project in the browser (`host-sim serve`): a local
//!   HTTP server holding one simulation, its JSON API and the page.
//! - [`closed_loop`]: a plant simulation in closed loop with a controller
//!   ([`closed_loop::Plant`], one runner for every plant):
//!   - [`boiler`]: the gas-fired boiler (`host-sim boiler`): its physics
//!     and sensor faults, scripts of operator actions and faults, the
//!     named scenarios, the safety checker, and a run's SVG and VCD;
//!   - [`cell`]: the batch process cell (two mixing tanks, two reactors)
//!     with its controlled Petri net, every scan checked;
//!   - [`testbed`]: the manufacturing testbed (two trains, three cranes,
//!     six switches) with its 29 modular supervisors (`host-sim
//!     testbed`), every scan checked.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod boiler;
pub mod cell;
pub mod closed_loop;
pub mod columns;
pub mod gtkw;
pub mod inputs;
pub mod lockstep;
pub mod partial;
pub mod plot;
pub mod random_inputs;
pub mod replay;
pub mod rng;
pub mod scenario;
pub mod serve;
pub mod sim;
pub mod testbed;
pub mod trace;
pub mod vcd;

pub use lockstep::Lockstep;
pub use sim::{Sim, SimError};
pub use trace::TraceRow;
