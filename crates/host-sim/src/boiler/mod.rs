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
//! - [`svg`]: a picture of a run; [`waveform`]: its VCD.
//! - [`error`]: what can go wrong ([`PlantError`]).
//!
//! One scan of [`run`] / [`run_with`]:
//!
//! 1. script actions due at the plant's time (`at <= now`) are applied;
//! 2. the controller scans the input image the plant shows (sensor faults
//!    applied); a controller stall among those actions ([`Action::Stall`])
//!    hangs it right after this scan;
//! 3. the plant advances under the scan's outputs until the controller's
//!    next scan: one period, or as its schedule says after a stall (the
//!    late scan when the stall ends, then the grid in phase again).
//!
//! ```no_run
//! use codegen::emit::Backend;
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
pub mod waveform;
pub mod wiring;

pub use controller::{BoilerController, ControllerScan, Plc};
pub use error::PlantError;
pub use invariants::{
    check_replay, check_rows, Checker, Invariants, ProjectChecker, Rule, Violation,
};
pub use physics::{BoilerParams, BoilerPlant, Disturbance, PlantState};
pub use record::{Run, RunRow};
pub use script::{Action, Script};
pub use signals::{Input, Inputs, IoMap, Output, Outputs, Selector};
pub use wiring::SensorFault;

use crate::sim::Sim;

/// Runs the project in `sim` against `plant` for `duration_ms` of plant
/// time with `script`; every boiler signal is looked up by name first.
pub fn run(
    sim: &mut Sim,
    plant: &mut BoilerPlant,
    script: &Script,
    duration_ms: u64,
) -> Result<Run, PlantError> {
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
) -> Result<Run, PlantError> {
    let period = u64::from(controller.scan_period_ms().max(1));
    let end = plant.time_ms() + duration_ms;
    let actions = script.actions();
    let mut next = 0;
    let mut rows = Vec::with_capacity((duration_ms / period) as usize + 1);
    while plant.time_ms() < end {
        let mut stall = 0;
        while let Some((_, action)) = actions.get(next).filter(|(at, _)| *at <= plant.time_ms()) {
            if let Action::Stall { ms } = *action {
                stall += ms;
            }
            action.apply_to(plant);
            next += 1;
        }
        let state = plant.state();
        let inputs = plant.inputs();
        let scan = controller.scan(&inputs)?;
        if stall > 0 {
            controller.stall(stall);
        }
        // In steps of at most a period, so a stall is simulated as finely.
        let until = plant.time_ms() + controller.next_scan_in_ms().max(1);
        while plant.time_ms() < until {
            plant.step(period.min(until - plant.time_ms()), &scan.outputs);
        }
        rows.push(RunRow {
            scan: rows.len() as u64,
            time_ms: scan.time_ms,
            inputs,
            outputs: scan.outputs,
            events: scan.events,
            states: scan.states,
            fault: scan.fault,
            reinitialised: scan.reinitialised,
            plant: state,
        });
    }
    Ok(Run {
        scan_period_ms: period as u32,
        debounce: controller.debounce(),
        rows,
    })
}
