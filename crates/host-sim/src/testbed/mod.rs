//! The manufacturing testbed of docs/seeds.md B (two trains, three
//! cranes, six switches, 26 sensors) in closed loop with its PLC project
//! (`models/testbed/testbed.plc.toml`: the 29 modular supervisors), every
//! scan checked.
//!
//! - [`track`]: the layout, sections and routes of
//!   `models/testbed/README.md`;
//! - [`plant`]: trains, switches and cranes ([`TestbedPlant`]) and the
//!   sensor faults a scenario injects;
//! - [`signals`]: the PLC's inputs and outputs by name ([`TestbedIo`]);
//! - [`invariants`]: what must hold every scan ([`Checker`]);
//! - [`record`]: what a run leaves ([`TestbedRun`]), its timeline;
//! - [`scenarios`]: the named scenarios of `host-sim testbed`.
//!
//! [`run`] is the [`closed_loop`] with the project on the executor as the
//! controller and the invariants checked on the plant every scan.

pub mod invariants;
pub mod plant;
pub mod record;
pub mod scenarios;
pub mod signals;
pub mod track;

pub use invariants::{Checker, Rule, Violation};
pub use plant::{Action, SensorFault, TestbedParams, TestbedPlant};
pub use record::TestbedRun;
pub use scenarios::Scenario;
pub use signals::{Commands, Inputs, TestbedIo};
pub use track::Train;

use crate::closed_loop::{self, Controller, Plant, Record, Scan};
use crate::sim::{Sim, SimError};

/// A problem setting up or running the testbed in closed loop.
#[derive(Debug, thiserror::Error)]
pub enum TestbedError {
    /// The project lacks some of the testbed's signals.
    #[error("the project lacks the testbed's {}", .0.join(", "))]
    MissingSignals(Vec<String>),
    /// The simulation failed.
    #[error(transparent)]
    Sim(#[from] SimError),
}

/// Runs the project in `sim` against `plant` for `duration_ms` of plant
/// time with the scenario's `actions` (at plant times, in time order),
/// every scan checked.
pub fn run(
    sim: &mut Sim,
    plant: &mut TestbedPlant,
    actions: &[(u64, Action)],
    duration_ms: u64,
) -> Result<TestbedRun, TestbedError> {
    let io = TestbedIo::new(sim.project()).map_err(TestbedError::MissingSignals)?;
    sim.retain_trace(false);
    let scan_period_ms = u64::from(sim.config().scan_period_ms);
    let mut plc = Plc { sim, io };
    let mut log = Log {
        checker: Checker::new(),
        run: TestbedRun {
            scan_period_ms,
            ..TestbedRun::default()
        },
    };
    closed_loop::run(&mut plc, plant, actions, duration_ms, &mut log)?;
    let mut out = log.run;
    out.trains = plant.trains.to_vec();
    out.cranes = plant.cranes.to_vec();
    Ok(out)
}

/// Runs the named scenario `name` with the project in `sim`; `None` for
/// an unknown name.
pub fn run_named(sim: &mut Sim, name: &str) -> Option<Result<TestbedRun, TestbedError>> {
    let s = scenarios::named(name)?;
    let mut plant = TestbedPlant::new(s.params);
    Some(run(sim, &mut plant, &s.actions, s.duration_ms))
}

/// What one scan of the testbed's controller reports.
#[derive(Debug, Clone, PartialEq)]
pub struct TestbedScan {
    /// Time of the scan, ms.
    pub time_ms: u64,
    /// The output image.
    pub commands: Commands,
    /// Executed events in order.
    pub events: Vec<String>,
    /// Fault cause on a scan spent in fault mode.
    pub fault: Option<String>,
}

/// The testbed in the closed loop: an action is a sensor fault.
impl Plant for TestbedPlant {
    type Action = Action;
    type State = TestbedPlant;
    type Inputs = Inputs;
    type Report = TestbedScan;

    fn time_ms(&self) -> u64 {
        TestbedPlant::time_ms(self)
    }

    fn apply(&mut self, action: &Action) {
        TestbedPlant::apply(self, action);
    }

    fn state(&self) -> TestbedPlant {
        self.clone()
    }

    fn inputs(&self) -> Inputs {
        TestbedPlant::inputs(self)
    }

    fn advance(&mut self, dt_ms: u64, report: &TestbedScan) {
        self.step(dt_ms, report.time_ms, &report.commands);
    }
}

/// The project in a [`Sim`] as the testbed's controller.
struct Plc<'a> {
    sim: &'a mut Sim,
    io: TestbedIo,
}

impl Controller<TestbedPlant> for Plc<'_> {
    type Error = TestbedError;

    fn scan_period_ms(&self) -> u64 {
        u64::from(self.sim.config().scan_period_ms)
    }

    fn scan(&mut self, inputs: &Inputs) -> Result<TestbedScan, TestbedError> {
        self.io.write_inputs(inputs, self.sim)?;
        let time_ms = self.sim.time_ms();
        let row = self.sim.scan();
        Ok(TestbedScan {
            time_ms,
            commands: self.io.read_outputs(&row.outputs),
            events: row.events.clone(),
            fault: row.fault.clone(),
        })
    }
}

/// A [`TestbedRun`] in the making, and the invariants it checks.
struct Log {
    checker: Checker,
    run: TestbedRun,
}

impl Record<TestbedPlant> for Log {
    fn record(&mut self, scan: Scan<TestbedPlant>, plant: &TestbedPlant) {
        let Scan {
            time_ms,
            state,
            inputs,
            report,
        } = scan;
        let out = &mut self.run;
        if out.inputs.last().is_none_or(|(_, i)| *i != inputs) {
            out.inputs.push((time_ms, inputs));
        }
        out.events
            .extend(report.events.iter().map(|e| (time_ms, e.clone())));
        if out.fault.is_none() {
            out.fault = report.fault.clone().map(|f| (time_ms, f));
        }
        out.last_commands = report.commands;
        out.violations.extend(
            self.checker
                .check(
                    time_ms,
                    &state,
                    &report.commands,
                    plant,
                    report.fault.is_some(),
                )
                .into_iter()
                .map(|rule| Violation { time_ms, rule }),
        );
        out.scans += 1;
    }
}
