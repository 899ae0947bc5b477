//! The gas-fired water-bath boiler of docs/seeds.md A in closed loop with
//! a controller, and its safety invariants.
//!
//! - [`physics`]: the plant itself ([`BoilerPlant`], [`BoilerParams`]):
//!   flames, heat balances, limit switches, the operator panel, and the
//!   sensor wiring it reads through (the ignition and extinction delays of
//!   a flame are in `flame`).
//! - [`signals`]: the boiler's PLC inputs and outputs by name, typed images.
//! - [`wiring`]: sensor faults (bounce, stuck-at, dropout).
//! - [`script`]: operator actions and fault injections at times
//!   ([`Script`]), by hand or from a seed; it drives the physics, which
//!   knows nothing of scripts.
//! - [`controller`]: what runs against the plant ([`BoilerController`]; a
//!   project on the executor is a [`Plc`]).
//! - [`record`]: the per-scan record of a run ([`Run`]).
//! - [`invariants`]: the safety checker ([`Checker`]).
//! - [`scenarios`]: the named scenarios of `host-sim boiler`.
//! - [`svg`]: a picture of a run; [`waveform`]: its VCD; [`timeline`]:
//!   the timeline `host-sim boiler` prints.
//! - [`error`]: what can go wrong ([`BoilerError`]).
//!
//! [`run`] and [`run_with`] are the [`closed_loop`] with the boiler's
//! script ([`Action::Stall`] hangs the controller), a
//! [`BoilerController`], and one [`RunRow`] per scan.
//!
//! ```no_run
//! use codegen::backend::Backend;
//! use host_sim::boiler::{self, BoilerParams, BoilerPlant, Invariants, Script, Selector};
//! use host_sim::Sim;
//!
//! let mut sim = Sim::load("models/boiler/boiler.plc.toml".as_ref(), Backend::Table)?;
//! let mut plant = BoilerPlant::new(BoilerParams::default(), 1);
//! let script = Script::new().at(1_000, Selector::Low).at(120_000, Selector::Off);
//! let run = boiler::run(&mut sim, &mut plant, &script, 180_000)?;
//! assert!(run.violations(&Invariants::default()).is_empty());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod controller;
pub mod error;
mod flame;
pub mod invariants;
pub mod physics;
pub mod record;
pub mod scenarios;
pub mod script;
pub mod signals;
pub mod svg;
pub mod timeline;
pub mod waveform;
pub mod wiring;

pub use controller::{BoilerController, ControllerScan, Plc};
pub use error::BoilerError;
pub use invariants::{
    check_replay, check_rows, Checker, Invariants, ProjectChecker, Rule, Violation,
};
pub use physics::{BoilerParams, BoilerPlant, BoilerState, Disturbance};
pub use record::{Run, RunRow};
pub use script::{Action, Script};
pub use signals::{Input, Inputs, IoMap, Output, Outputs, Selector};
pub use wiring::SensorFault;

use crate::closed_loop::{self, Controller, Plant, Record, Scan};
use crate::sim::Sim;

/// Runs the project in `sim` against `plant` for `duration_ms` of plant
/// time with `script`; every boiler signal is looked up by name first.
pub fn run(
    sim: &mut Sim,
    plant: &mut BoilerPlant,
    script: &Script,
    duration_ms: u64,
) -> Result<Run, BoilerError> {
    run_with(&mut Plc::new(sim)?, plant, script, duration_ms)
}

/// Runs `controller` against `plant` from the plant's current time for
/// `duration_ms`, one scan per scan period; script actions are at plant
/// times, and those due before the start are applied at once.
pub fn run_with<C: BoilerController + ?Sized>(
    controller: &mut C,
    plant: &mut BoilerPlant,
    script: &Script,
    duration_ms: u64,
) -> Result<Run, BoilerError> {
    let period = Controller::<BoilerPlant>::scan_period_ms(controller).max(1);
    let mut rows = Vec::with_capacity((duration_ms / period) as usize + 1);
    closed_loop::run(controller, plant, script.actions(), duration_ms, &mut rows)?;
    Ok(Run {
        scan_period_ms: period as u32,
        debounce: controller.debounce(),
        rows,
    })
}

/// The boiler in the closed loop: script actions, the input image with
/// its sensor faults, and the true state in every row.
impl Plant for BoilerPlant {
    type Action = Action;
    type State = BoilerState;
    type Inputs = Inputs;
    type Report = ControllerScan;

    fn time_ms(&self) -> u64 {
        BoilerPlant::time_ms(self)
    }

    fn apply(&mut self, action: &Action) {
        action.apply_to(self);
    }

    fn stall_ms(action: &Action) -> u64 {
        match *action {
            Action::Stall { ms } => ms,
            _ => 0,
        }
    }

    fn state(&self) -> BoilerState {
        BoilerPlant::state(self)
    }

    fn inputs(&self) -> Inputs {
        BoilerPlant::inputs(self)
    }

    fn advance(&mut self, dt_ms: u64, report: &ControllerScan) {
        self.step(dt_ms, &report.outputs);
    }
}

/// Every boiler controller runs in the closed loop as it is.
impl<C: BoilerController + ?Sized> Controller<BoilerPlant> for C {
    type Error = BoilerError;

    fn scan_period_ms(&self) -> u64 {
        u64::from(BoilerController::scan_period_ms(self))
    }

    fn scan(&mut self, inputs: &Inputs) -> Result<ControllerScan, BoilerError> {
        BoilerController::scan(self, inputs)
    }

    fn stall(&mut self, ms: u64) {
        BoilerController::stall(self, ms);
    }

    fn next_scan_in_ms(&self) -> u64 {
        BoilerController::next_scan_in_ms(self)
    }
}

/// The rows of a boiler run, one pushed per scan.
impl Record<BoilerPlant> for Vec<RunRow> {
    fn record(&mut self, scan: Scan<BoilerPlant>, _: &BoilerPlant) {
        let report = scan.report;
        self.push(RunRow {
            scan: self.len() as u64,
            time_ms: report.time_ms,
            inputs: scan.inputs,
            outputs: report.outputs,
            events: report.events,
            states: report.states,
            fault: report.fault,
            reinitialised: report.reinitialised,
            plant: scan.state,
        });
    }
}
