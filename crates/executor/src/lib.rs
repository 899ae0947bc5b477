//! The PLC scan cycle that runs synthesised supervisors.
//!
//! `#![no_std]`, no allocation (unless the `alloc` feature is asked for,
//! for hosts), no `unsafe`. The same source runs in the board firmware, in
//! the QEMU replay harness and in `host-sim` on a PC, so all of them
//! produce the same trace for the same inputs.
//!
//! The scan cycle's specification is `docs/semantics.md` in the
//! repository; this page summarises what the crate guarantees and names
//! the tests that hold it to that.
//!
//! # Example
//!
//! A one-supervisor program written by hand (the code generator emits
//! the same pieces from a project file: `CONFIG`, `PROGRAM` and a
//! `Memory` type): a start button whose press arms the supervisor, which
//! then lets the controller switch the motor on.
//!
//! ```
//! use executor::memory::StaticMemory;
//! use executor::program::{
//!     mask_word, Action, AllowedSets, Config, EventSpec, Guards, Index, InputSpec, Membership, OutputSpec,
//!     Program, Span, SupervisorSpec, Trigger, UnexpectedPolicy,
//! };
//! use executor::table::SupervisorTable;
//! use executor::image::config_crc;
//! use executor::{Controller, Fault, SizeMismatch};
//!
//! // Indices in declaration order: one input, one output, two events.
//! const START_PB: Index = 0;
//! const MOTOR: Index = 0;
//! const PRESSED: Index = 0; // uncontrollable: rising edge of START_PB
//! const RUN: Index = 1; // controllable: sets MOTOR
//! // Supervisor `starter`: IDLE --pressed--> ARMED --run--> RUNNING.
//! const IDLE: u32 = 0;
//! const ARMED: u32 = 1;
//! const RUNNING: u32 = 2;
//!
//! const CONFIG: Config<'static> = Config {
//!     name: "starter",
//!     scan_period_ms: 10,
//!     max_commands_per_scan: 1,
//!     unexpected: UnexpectedPolicy::Fault,
//!     reset: None,
//!     overrun_limit: 1,
//!     overrun_fault: false,
//!     lost_edge_fault: false,
//!     rom_test_bytes_per_scan: 64,
//!     // The button's edges can raise `pressed` (event_lists[0..1]).
//!     // Records are words, written with each kind's `to_words`.
//!     inputs: &[InputSpec { debounce_scans: 0, raises: Span::new(0, 1) }.to_words()],
//!     debounced: &[],
//!     debounce_mask: Span::EMPTY,
//!     outputs: &[OutputSpec { safe: false, initial: false, state_map: Span::EMPTY }.to_words()],
//!     timers: &[],
//!     events: &[
//!         EventSpec {
//!             trigger: Trigger::Rising(Span::new(0, 1)), // input_masks[0..1]
//!             when: Span::EMPTY,
//!             unless: Span::EMPTY,
//!             request: None,
//!             actions: Span::EMPTY,
//!             members: Span::new(0, 1), // memberships[0..1]
//!         }
//!         .to_words(),
//!         EventSpec {
//!             trigger: Trigger::Command,
//!             when: Span::EMPTY,
//!             unless: Span::EMPTY,
//!             request: None,
//!             actions: Span::new(0, 1), // actions[0..1]
//!             members: Span::new(1, 1), // memberships[1..2]
//!         }
//!         .to_words(),
//!     ],
//!     // Its alphabet in local order is event_lists[1..3]; no event is
//!     // outside it.
//!     supervisors: &[SupervisorSpec {
//!         states: 3,
//!         initial: IDLE,
//!         alphabet: Span::new(1, 2),
//!         outside: Span::EMPTY,
//!         // Computed from `next_state` as it moves (a generator may store
//!         // them: `AllowedSets`).
//!         allowed: AllowedSets::COMPUTED,
//!         contiguous: false,
//!     }
//!     .to_words()],
//!     // One word per mask (32 inputs per word): the button alone.
//!     input_masks: &[mask_word(0, &[START_PB])],
//!     event_lists: &[PRESSED as u32, PRESSED as u32, RUN as u32],
//!     // One word per set (32 events per word): the commands.
//!     event_masks: &[mask_word(0, &[RUN])],
//!     commands: Span::new(0, 1),
//!     requested: Span::EMPTY,
//!     actions: &[Action::Set(MOTOR).to_word()],
//!     memberships: &[
//!         Membership { supervisor: 0, local: 0 }.to_word(),
//!         Membership { supervisor: 0, local: 1 }.to_word(),
//!     ],
//!     state_map: &[],
//!     guards: Guards::NONE,
//!     allowed_index: &[],
//! };
//!
//! /// The supervisor as a `match` on (state, local event); its image is
//! /// the configuration alone.
//! struct Starter {
//!     /// The image CRC recorded when the program was made.
//!     crc: u32,
//! }
//!
//! impl Program for Starter {
//!     fn config(&self) -> Config<'_> {
//!         CONFIG
//!     }
//!     fn next_state(&self, _supervisor: Index, state: u32, local: Index) -> Option<u32> {
//!         match (state, local) {
//!             (IDLE, PRESSED) => Some(ARMED),
//!             (ARMED, RUN) => Some(RUNNING),
//!             _ => None,
//!         }
//!     }
//!     fn table(&self, _supervisor: Index) -> Option<SupervisorTable<'_>> {
//!         None // the supervisor is code, not a table
//!     }
//!     fn recorded_crc(&self) -> u32 {
//!         self.crc
//!     }
//! }
//!
//! let program = Starter { crc: config_crc(&CONFIG) };
//! // 1 input word, no debounced input, 1 output, 0 timers, 1 supervisor,
//! // 2 events in 1 word, 1 word of event set for the one supervisor.
//! type Memory = StaticMemory<1, 0, 1, 0, 1, 2, 1, 1>;
//! assert!(matches!(
//!     Controller::new(&program, StaticMemory::<1, 0, 1, 0, 1, 3, 1, 1>::new()),
//!     Err(SizeMismatch)
//! ));
//! let mut plc = Controller::new(&program, Memory::new()).expect("sized for CONFIG");
//!
//! // Scan 0 finds the button already held: no edge at power-on.
//! let r = plc.scan(0, &[true]);
//! assert!(r.executed.is_empty());
//! assert_eq!((r.states, r.outputs), (&[IDLE][..], &[false][..]));
//!
//! // Released, pressed again: the edge moves the supervisor, and in the
//! // same scan the controller picks `run`, now enabled, which starts the motor.
//! plc.scan(10, &[false]);
//! let r = plc.scan(20, &[true]);
//! assert_eq!(r.executed, [PRESSED, RUN]);
//! assert_eq!(r.states, [RUNNING]);
//! assert_eq!(r.outputs, [true]);
//!
//! // A press while running is an edge no supervisor expects: fault mode,
//! // safe outputs (and, without a reset input, until power-off).
//! plc.scan(30, &[false]);
//! let r = plc.scan(40, &[true]);
//! assert_eq!(r.fault, Some(Fault::Unexpected { event: PRESSED }));
//! assert_eq!(r.unexpected, [PRESSED]);
//! assert_eq!(r.outputs, [false]);
//! ```
//!
//! # Use it with a generated program
//!
//! A program is not written by hand: the `codegen` crate generates it
//! from a PLC project file (`*.plc.toml`) in the build script of your
//! crate. The dependency lines (paths into the repository; outside it,
//! to your checkout):
//!
//! ```toml
//! [dependencies]
//! executor = { path = "…/crates/executor" }
//! # Only for a project with a `[board]` section: the pin types of the
//! # generated `board` module.
//! boards = { path = "…/crates/boards" }
//!
//! [build-dependencies]
//! codegen = { path = "…/crates/codegen" }
//! ```
//!
//! `build.rs` writes `OUT_DIR/<name>.rs`, `<name>` being the project
//! file's name up to its first dot:
//!
//! ```ignore
//! fn main() {
//!     codegen::build::Build::new("conveyor.plc.toml").generate_or_exit();
//! }
//! ```
//!
//! and the crate includes it in a module of its own and runs it:
//!
//! ```ignore
//! mod conveyor {
//!     include!(concat!(env!("OUT_DIR"), "/conveyor.rs"));
//! }
//!
//! let mut plc = executor::Controller::new(&conveyor::PROGRAM, conveyor::Memory::new())
//!     .expect("the generated Memory is sized for the generated PROGRAM");
//! // Every `conveyor::CONFIG.scan_period_ms`: sample, scan, write.
//! let record = plc.scan(now_ms, &raw_inputs);
//! ```
//!
//! The generated module holds `PROGRAM` (a [`Program`]) and its `Memory`
//! type (a [`memory::StaticMemory`]), `CONFIG` (its [`Config`]),
//! `IMAGE_CRC` and `CONFIG_CRC`, the names in declaration order as
//! [`program::Index`] constants with a `COUNT` and `NAMES` (modules
//! `input`, `output`, `timer`, `event`, `supervisor`; `states` for the
//! state names of each supervisor), and, for a project with a `[board]`
//! section, `board` (the pin of each signal). It compiles warning-free
//! under `#![deny(warnings)]` whichever of these a crate uses.
//! `examples/my-plc/` in the repository is such a crate, with a PC `main`
//! (a scripted input sequence, the trace printed) and a Nucleo-F411RE
//! `main`.
//!
//! # Guarantees
//!
//! Each call of [`Controller::scan`] with a time `t` (ms, wrapping) and the
//! raw input image (`docs/semantics.md`, "One scan"):
//!
//! 1. **Samples** the inputs and debounces them (an input with
//!    `debounce_scans = d > 1` follows its raw value only after `d`
//!    consecutive differing scans, this one included); edges compare the
//!    filtered image with the previous scan's. Scan 0 has no edges, and
//!    its filtered value of every input, debounced or not, is the raw
//!    sample (a filter has no history to hold against at power-on).
//!    Filtering goes on in fault mode and is not reset by a fault reset.
//! 2. **In fault mode** writes the safe output image, unless the `reset`
//!    input rises and the last complete check of the program image
//!    matched: then everything is re-initialised and the initial image
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
//! product is never built). An image whose structure is wrong (an index
//! out of range, a span past its pool: [`validate`], checked once at
//! start-up by [`Controller::new`], so that no index in the scan can
//! panic; [`Controller::new_proven`] leaves it to the generator and runs
//! nothing of the image before its CRC matches), a supervisor state
//! out of range or a program image whose CRC does not match is a `Corrupt`
//! fault: the whole image is
//! checked at start-up, then again in the background, pass after pass,
//! `rom_test_bytes_per_scan` bytes per scan, so a flipped bit is found
//! within a bound of scans ([`image`], [`Controller::image_test`]). Late
//! scans and lost edges are found by the code that paces the scans and
//! reads the pins (the board firmware, host-sim's simulated stalls) and
//! reported with [`Controller::report_overrun`] and
//! [`Controller::report_lost_edge`]: counted, and faults when the project
//! says so.
//!
//! Memory is sized in its type ([`memory::StaticMemory`]) and sealed:
//! [`Controller::new`] refuses memory whose sizes differ from the
//! program's, and nothing outside the crate can reach its arrays.
//!
//! # Where it is proven
//!
//! - `crates/codegen/tests/conformance/`: the table and logic backends
//!   against a reference interpreter written from the specification, over
//!   10,000 random projects with random inputs, scan by scan, with control
//!   equivalence checked against the source automata.
//! - `tests/generated.rs`: the generated code (table, logic, `match`) of
//!   every seed project equals host-sim, scan by scan.
//! - `cargo xtask qemu`: the same programs on a Cortex-M4 under QEMU, with
//!   zero mismatches against host-sim.
//! - This crate's unit tests (`src/tests.rs`: edges, timers across the
//!   clock wrap, debounce, request inputs, fault mode and reset, corrupt
//!   images, memory sizes) and the examples on this page and in
//!   [`memory`].
//!
//! # Pieces
//!
//! - [`program`]: the static description ([`Config`]) and the [`Program`]
//!   trait for supervisor dynamics.
//! - [`table`]: bit-packed transition tables ([`TableProgram`]).
//! - [`image`]: the program image, its CRC, and the stream the background
//!   image test walks.
//! - [`memory`]: RAM with sizes in the types ([`memory::StaticMemory`]).
//! - [`Controller`]: the scan cycle.
//! - [`pacing`]: when scans start: the fixed grid, skipped periods,
//!   overruns.
//!
//! # Features
//!
//! - `alloc`: `memory::HeapMemory`, sized at run time (hosts).
//! - `defmt`: `defmt::Format` for [`Fault`] and [`Counters`].
//! - `replay`: recorded scans for replay harnesses (`replay` module).

#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

#[cfg(feature = "alloc")]
extern crate alloc;

mod bits;
pub mod compiled;
mod controller;
pub mod guards;
pub mod image;
mod inputs;
pub mod memory;
pub mod pacing;
pub mod parse;
pub mod program;
mod record;
#[cfg(feature = "replay")]
pub mod replay;
mod rom_test;
pub mod table;
pub mod timers;
pub mod validate;

pub use controller::{Controller, SizeMismatch};
pub use memory::Memory;
pub use program::{Config, Program};
pub use record::{Counters, Fault, ScanRecord};
pub use rom_test::ImageTest;
pub use table::TableProgram;

#[cfg(test)]
mod tests;
