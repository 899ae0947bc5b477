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
//! One scan of [`run`]: the operator's button actions due are applied, the
//! controller scans the switches the plant shows, the invariants are
//! checked on the plant, the output image and the controlled net's
//! marking read from the controller, and the plant runs one period under
//! the new outputs.

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
    actions: Vec<(u64, Unit, bool)>,
}

impl Operator {
    /// No action.
    pub fn new() -> Operator {
        Operator::default()
    }

    /// Presses the start button of `reactor` at `at_ms` for `hold_ms`.
    pub fn press(mut self, at_ms: u64, reactor: Unit, hold_ms: u64) -> Operator {
        self.actions.push((at_ms, reactor, true));
        self.actions.push((at_ms + hold_ms, reactor, false));
        self.actions.sort_by_key(|&(t, _, _)| t);
        self
    }

    /// Presses the start button of `reactor` at `at_ms` and holds it:
    /// batch after batch.
    pub fn hold(mut self, at_ms: u64, reactor: Unit) -> Operator {
        self.actions.push((at_ms, reactor, true));
        self.actions.sort_by_key(|&(t, _, _)| t);
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
        let project = sim.project();
        let states = sim.controller().states();
        if let Some(net) = project.nets.first() {
            let first = project.group_supervisor(0, 0);
            return Ok(net.unpack(&states[first..first + net.groups()]));
        }
        let name = project.state_name(0, states[0]);
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
    let period = u64::from(sim.project().scan_period_ms);
    let end = plant.time_ms() + duration_ms;
    let mut next = 0;
    let mut out = CellRun {
        max_reaction_temps: [f64::MIN; 2],
        scan_period_ms: period,
        ..CellRun::default()
    };
    while plant.time_ms() < end {
        while let Some(&(_, reactor, pressed)) = operator
            .actions
            .get(next)
            .filter(|(at, _, _)| *at <= plant.time_ms())
        {
            plant.press(reactor, pressed);
            next += 1;
        }
        let sensors = plant.sensors();
        io.write_inputs(&sensors, sim)?;
        if out.sensors.last().is_none_or(|(_, s)| *s != sensors) {
            out.sensors.push((plant.time_ms(), sensors));
        }
        let row = sim.scan().clone();
        let commands = io.read_outputs(&row.outputs);
        out.events
            .extend(row.events.iter().map(|e| (plant.time_ms(), e.clone())));
        if out.commands.last().is_none_or(|(_, c)| *c != commands) {
            out.commands.push((plant.time_ms(), commands));
        }
        let mut state = plant.state();
        state.valves = commands;
        let marking = watch.marking(sim)?;
        let fault = sim.controller().fault().map(|f| format!("{f:?}"));
        out.violations.extend(
            watch
                .checker
                .check(&state, &marking, fault)
                .into_iter()
                .map(|rule| Violation {
                    time_ms: plant.time_ms(),
                    rule,
                }),
        );
        plant.step(period, &commands);
        out.scans += 1;
        track_extremes(&mut out, &plant.state(), plant.params());
    }
    out.last = plant.state();
    out.marking = watch
        .net
        .marking_name(&watch.marking(sim)?)
        .replace(' ', "");
    Ok(out)
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
