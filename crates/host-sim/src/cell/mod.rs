//! The batch process cell of docs/seeds.md D (two mixing tanks, two
//! reactors) in closed loop with its PLC project
//! (`models/petri/cell/cell.plc.toml`, a controlled Petri net), every scan
//! checked.
//!
//! - [`params`]: the plant's numbers ([`CellParams`], ours: the paper has
//!   none);
//! - [`physics`]: levels (eq. 9–12), valves, switches ([`CellPlant`]);
//!   [`thermal`]: the reactor temperature (eq. 13) and its PI controller;
//! - [`signals`]: the PLC's inputs and outputs by name ([`CellIo`]);
//! - [`invariants`]: what must hold every scan ([`Checker`]);
//! - [`record`]: what a run leaves ([`CellRun`]: events, batches).
//!
//! [`run`] is the [`closed_loop`] with the operator's start buttons, the
//! project on the executor as the controller (its output image and the
//! controlled net's marking read after each scan), and the invariants
//! checked on the plant every scan into a [`CellRun`].

pub mod invariants;
pub mod params;
pub mod physics;
pub mod record;
pub mod signals;
pub mod thermal;

pub use invariants::{Checker, Rule, Violation};
pub use params::CellParams;
pub use physics::{CellPlant, CellState};
pub use record::{Batch, CellRun};
pub use signals::{CellIo, Commands, Sensors, Unit};

use crate::closed_loop::{self, Controller, Plant, Record, Scan};
use crate::sim::{Sim, SimError};
use des::petri::constraints::{self, Constraint};
use des::petri::PetriNet;
use plc_project::{NetSource, Project};

/// A problem setting up a closed-loop run of the cell.
#[derive(Debug, thiserror::Error)]
pub enum CellError {
    /// The project lacks some of the cell's signals.
    #[error("the project lacks the cell's {}", .0.join(", "))]
    MissingSignals(Vec<String>),
    /// The project has no controlled net to check against.
    #[error("the project runs no net synthesised from constraints")]
    NoControlledNet,
    /// A state of the controller is not a marking of the controlled net.
    #[error("state `{0}` is not a marking of the controlled net")]
    NotAMarking(String),
    /// Reading the constraints failed.
    #[error(transparent)]
    Model(#[from] des::Error),
    /// The simulation failed.
    #[error(transparent)]
    Sim(#[from] SimError),
}

/// The operator's start buttons: (time, reactor, pressed), applied when
/// the plant's time reaches them.
#[derive(Debug, Clone, Default)]
pub struct Operator {
    actions: Vec<(u64, (Unit, bool))>,
}

impl Operator {
    /// No action.
    pub fn new() -> Operator {
        Operator::default()
    }

    /// Presses the start button of `reactor` at `at_ms` for `hold_ms`.
    pub fn press(mut self, at_ms: u64, reactor: Unit, hold_ms: u64) -> Operator {
        self.actions.push((at_ms, (reactor, true)));
        self.actions.push((at_ms + hold_ms, (reactor, false)));
        self.actions.sort_by_key(|&(t, _)| t);
        self
    }

    /// Presses the start button of `reactor` at `at_ms` and holds it:
    /// batch after batch.
    pub fn hold(mut self, at_ms: u64, reactor: Unit) -> Operator {
        self.actions.push((at_ms, (reactor, true)));
        self.actions.sort_by_key(|&(t, _)| t);
        self
    }
}

/// The controlled net the controller runs and its checks: from a
/// project's `[[net]]` with `constraints`, and then usable for another
/// project that runs the same supervisor as an automaton whose states are
/// named by markings (`codegen petri reach`).
#[derive(Debug, Clone)]
pub struct Watch {
    net: PetriNet,
    checker: Checker,
}

impl Watch {
    /// The checks of `project`'s first net, synthesised from constraints.
    pub fn of_project(project: &Project, params: &CellParams) -> Result<Watch, CellError> {
        let net = project.nets.first().ok_or(CellError::NoControlledNet)?;
        let NetSource::Synthesized {
            plant, constraints, ..
        } = &net.source
        else {
            return Err(CellError::NoControlledNet);
        };
        let plant = des::petri::read_file(plant)?;
        let constraints = constraints::read_file(constraints, &plant)?;
        Ok(Watch::new(net.net.clone(), constraints, params))
    }

    /// The checks of `net` (plant places first, then one control place per
    /// constraint of `constraints`, in order); no constraint for a net
    /// run without a supervisor.
    pub fn new(net: PetriNet, constraints: Vec<Constraint>, params: &CellParams) -> Watch {
        Watch {
            checker: Checker::new(params, &net, constraints),
            net,
        }
    }

    /// The controlled net.
    pub fn net(&self) -> &PetriNet {
        &self.net
    }

    /// The marking the controller in `sim` holds: its net's groups
    /// unpacked, or the state of its one automaton read as a marking
    /// name (`ma1+mb2`, `2·p`).
    pub fn marking(&self, sim: &Sim) -> Result<Vec<u32>, CellError> {
        let supervisors = sim.supervisors();
        let states = sim.controller().states();
        if let Some(layout) = sim.nets().first() {
            return Ok(layout.unpack(&states[supervisors.net_supervisors(0)]));
        }
        let name = supervisors.state_name(0, states[0]);
        let mut marking = vec![0; self.net.places().len()];
        for term in name.split('+').map(str::trim).filter(|t| *t != "0") {
            let (count, id) = match term.split_once('·') {
                Some((k, id)) => (k.parse().ok(), id),
                None => (Some(1), term),
            };
            let (Some(count), Some(p)) = (count, self.net.place(id)) else {
                return Err(CellError::NotAMarking(name));
            };
            marking[p] = count;
        }
        Ok(marking)
    }
}

/// Runs the project in `sim` against `plant` for `duration_ms` of plant
/// time, with the operator's `actions`, every scan checked by `watch`.
pub fn run(
    sim: &mut Sim,
    plant: &mut CellPlant,
    operator: &Operator,
    watch: &Watch,
    duration_ms: u64,
) -> Result<CellRun, CellError> {
    let io = CellIo::new(sim.project()).map_err(CellError::MissingSignals)?;
    sim.retain_trace(false);
    let mut plc = Plc { sim, io, watch };
    let mut log = Log {
        checker: &watch.checker,
        run: CellRun {
            max_reaction_temps: [f64::MIN; 2],
            scan_period_ms: plc.scan_period_ms(),
            ..CellRun::default()
        },
    };
    closed_loop::run(&mut plc, plant, &operator.actions, duration_ms, &mut log)?;
    let mut out = log.run;
    out.last = plant.state();
    out.marking = watch
        .net
        .marking_name(&watch.marking(plc.sim)?)
        .replace(' ', "");
    Ok(out)
}

/// What one scan of the cell's controller reports.
#[derive(Debug, Clone, PartialEq)]
pub struct CellScan {
    /// The output image.
    pub commands: Commands,
    /// Executed events in order.
    pub events: Vec<String>,
    /// The controlled net's marking after the scan.
    pub marking: Vec<u32>,
    /// Fault cause on a scan spent in fault mode.
    pub fault: Option<String>,
}

/// The cell in the closed loop: an action is a start button pressed
/// (`true`) or released.
impl Plant for CellPlant {
    type Action = (Unit, bool);
    type State = CellState;
    type Inputs = Sensors;
    type Report = CellScan;

    fn time_ms(&self) -> u64 {
        CellPlant::time_ms(self)
    }

    fn apply(&mut self, &(reactor, pressed): &(Unit, bool)) {
        self.press(reactor, pressed);
    }

    fn state(&self) -> CellState {
        CellPlant::state(self)
    }

    fn inputs(&self) -> Sensors {
        self.sensors()
    }

    fn advance(&mut self, dt_ms: u64, report: &CellScan) {
        self.step(dt_ms, &report.commands);
    }
}

/// The project in a [`Sim`] as the cell's controller: the cell's signals
/// by name, the marking read through the [`Watch`].
struct Plc<'a> {
    sim: &'a mut Sim,
    io: CellIo,
    watch: &'a Watch,
}

impl Controller<CellPlant> for Plc<'_> {
    type Error = CellError;

    fn scan_period_ms(&self) -> u64 {
        u64::from(self.sim.config().scan_period_ms)
    }

    fn scan(&mut self, sensors: &Sensors) -> Result<CellScan, CellError> {
        self.io.write_inputs(sensors, self.sim)?;
        let row = self.sim.scan();
        let commands = self.io.read_outputs(&row.outputs);
        let events = row.events.clone();
        Ok(CellScan {
            commands,
            events,
            marking: self.watch.marking(self.sim)?,
            fault: self.sim.controller().fault().map(|f| format!("{f:?}")),
        })
    }
}

/// A [`CellRun`] in the making, and the invariants it checks.
struct Log<'a> {
    checker: &'a Checker,
    run: CellRun,
}

impl Record<CellPlant> for Log<'_> {
    fn record(&mut self, scan: Scan<CellPlant>, plant: &CellPlant) {
        let Scan {
            time_ms,
            mut state,
            inputs: sensors,
            report:
                CellScan {
                    commands,
                    events,
                    marking,
                    fault,
                },
        } = scan;
        let out = &mut self.run;
        if out.sensors.last().is_none_or(|(_, s)| *s != sensors) {
            out.sensors.push((time_ms, sensors));
        }
        out.events.extend(events.into_iter().map(|e| (time_ms, e)));
        if out.commands.last().is_none_or(|(_, c)| *c != commands) {
            out.commands.push((time_ms, commands));
        }
        state.valves = commands;
        out.violations.extend(
            self.checker
                .check(&state, &marking, fault)
                .into_iter()
                .map(|rule| Violation { time_ms, rule }),
        );
        out.scans += 1;
        track_extremes(out, &plant.state(), plant.params());
    }
}

/// Highest levels, and reactor temperatures while held at the reaction
/// temperature.
fn track_extremes(out: &mut CellRun, s: &CellState, p: &CellParams) {
    let levels = [
        s.mixer_levels[0],
        s.mixer_levels[1],
        s.reactors[0].level,
        s.reactors[1].level,
    ];
    for (max, level) in out.max_levels.iter_mut().zip(levels) {
        *max = max.max(level);
    }
    for (i, r) in s.reactors.iter().enumerate() {
        let v = s.valves.reactors[i];
        if v.tc_on && !v.tc_cool && r.temp > p.reaction_temp - 5.0 {
            out.max_reaction_temps[i] = out.max_reaction_temps[i].max(r.temp);
        }
    }
}
