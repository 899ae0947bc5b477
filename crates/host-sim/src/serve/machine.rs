//! The machine a served project runs against: what makes its inputs
//! change.
//!
//! - [`Machine::Supervisors`]: no plant model. The user (or the random
//!   driver) moves the inputs; the supervisors say which uncontrollable
//!   events they expect.
//! - [`Machine::Automata`]: the plant automata the project's supervisors
//!   were synthesised from ([`PlantAutomata`]), moved by every executed
//!   event; they say which uncontrollable events the machine can do next.
//!   Their unobservable events (a breakdown no sensor sees) are actions:
//!   the plant moves, the controller sees nothing.
//! - [`Machine::Boiler`], [`Machine::Cell`]: the physical simulations of
//!   [`crate::boiler`] and [`crate::cell`]; the plant sets every input, the
//!   user acts on it through its [`PlantAction`]s.

use crate::boiler::{self, BoilerParams, BoilerPlant, Disturbance, Selector, SensorFault};
use crate::cell::{CellIo, CellParams, CellPlant, Unit};
use des::automaton::{Automaton, EventId, StateId};
use des::formats::{self, Kind};
use plc_project::{GuardedSource, Project, SupervisorSource};
use std::path::PathBuf;

/// Which machine to simulate (`host-sim serve --plant`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlantChoice {
    /// The boiler or the cell when the project has their signals, else the
    /// plant automata when the project synthesises from some, else none.
    Auto,
    /// The plant automata of the project's synthesis.
    Automata,
    /// No plant model: inputs are the user's.
    Supervisors,
    /// The gas-fired boiler's physics.
    Boiler,
    /// The batch cell's physics.
    Cell,
}

/// An action on a plant, offered as a button.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlantAction {
    /// Something done to the boiler.
    Boiler(boiler::Action),
    /// A start button of the cell pressed (`true`) or released.
    Cell(Unit, bool),
    /// Unobservable event `k` of the plant automata
    /// ([`PlantAutomata::silent`]), taken where the plant can.
    Silent(usize),
}

/// A named [`PlantAction`].
#[derive(Debug, Clone)]
pub struct NamedAction {
    /// Its name in the API.
    pub name: String,
    /// Its label on the page.
    pub label: String,
    /// What it does.
    pub action: PlantAction,
}

/// An analog quantity of a physical plant, for plots.
#[derive(Debug, Clone, Copy)]
pub struct Analog {
    /// Its name in the API.
    pub name: &'static str,
    /// Its label.
    pub label: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// The bottom of its plot's fixed scale.
    pub min: f64,
    /// The top of its plot's fixed scale.
    pub max: f64,
}

/// The plant automata of a project, each in its current state.
#[derive(Debug, Clone)]
pub struct PlantAutomata {
    components: Vec<Automaton>,
    states: Vec<StateId>,
    /// Per component, per project event: its id there, if in its alphabet.
    ids: Vec<Vec<Option<EventId>>>,
    /// The unobservable events no project event names, each with its id
    /// per component.
    silent: Vec<(String, Vec<Option<EventId>>)>,
}

impl PlantAutomata {
    /// The plant and unspecified automata of every file a supervisor of
    /// `project` is synthesised from (each file once, each automaton name
    /// once), in initial state; `None` when no supervisor is synthesised.
    pub fn of_project(project: &Project) -> Result<Option<PlantAutomata>, des::Error> {
        let mut files: Vec<&PathBuf> = Vec::new();
        for sup in &project.supervisors {
            if let SupervisorSource::Synthesized { plants, .. } = &sup.source {
                files.extend(plants);
            }
        }
        for guarded in &project.guarded {
            if let GuardedSource::Synthesized { plants, .. } = &guarded.source {
                files.extend(plants);
            }
        }
        let mut seen_files = Vec::new();
        let mut components: Vec<Automaton> = Vec::new();
        for file in files {
            if seen_files.contains(&file) {
                continue;
            }
            seen_files.push(file);
            for c in formats::read_file(file)? {
                if matches!(c.kind, Kind::Plant | Kind::Unspecified)
                    && components.iter().all(|a| a.name() != c.automaton.name())
                {
                    components.push(c.automaton);
                }
            }
        }
        if components.is_empty() {
            return Ok(None);
        }
        let ids = components
            .iter()
            .map(|a| {
                project
                    .events
                    .iter()
                    .map(|e| a.alphabet().id(&e.name))
                    .collect()
            })
            .collect();
        let mut silent: Vec<(String, Vec<Option<EventId>>)> = Vec::new();
        for a in &components {
            for (_, e) in a.alphabet().unobservable() {
                if project.event(&e.name).is_none() && silent.iter().all(|(n, _)| *n != e.name) {
                    let per = components
                        .iter()
                        .map(|c| c.alphabet().id(&e.name))
                        .collect();
                    silent.push((e.name.clone(), per));
                }
            }
        }
        let states = components
            .iter()
            .map(|a| a.initial().unwrap_or(StateId(0)))
            .collect();
        Ok(Some(PlantAutomata {
            components,
            states,
            ids,
            silent,
        }))
    }

    /// The unobservable events the controller never sees, by name.
    pub fn silent(&self) -> impl ExactSizeIterator<Item = &str> {
        self.silent.iter().map(|(n, _)| n.as_str())
    }

    /// Whether the plant can do unobservable event `k` now.
    pub fn silent_possible(&self, k: usize) -> bool {
        let per = &self.silent[k].1;
        self.components
            .iter()
            .enumerate()
            .all(|(c, a)| per[c].is_none_or(|id| a.successor(self.states[c], id).is_some()))
    }

    /// Takes unobservable event `k` when the plant can (`true`); else
    /// nothing moves.
    pub fn take_silent(&mut self, k: usize) -> bool {
        if !self.silent_possible(k) {
            return false;
        }
        for (c, a) in self.components.iter().enumerate() {
            if let Some(id) = self.silent[k].1[c] {
                self.states[c] = a.successor(self.states[c], id).expect("possible");
            }
        }
        true
    }

    /// The components.
    pub fn components(&self) -> &[Automaton] {
        &self.components
    }

    /// Every component back in its initial state.
    pub fn restart(&mut self) {
        for (a, s) in self.components.iter().zip(&mut self.states) {
            *s = a.initial().unwrap_or(StateId(0));
        }
    }

    /// Each component's current state by name.
    pub fn state_names(&self) -> Vec<String> {
        self.components
            .iter()
            .zip(&self.states)
            .map(|(a, &s)| a.state_name(s).into_owned())
            .collect()
    }

    /// The first component that has project event `e` and cannot do it
    /// now, with its state's name; `None` when the plant can do `e`.
    pub fn refuses(&self, e: usize) -> Option<(&str, String)> {
        self.components
            .iter()
            .enumerate()
            .find(|&(c, a)| {
                self.ids[c][e].is_some_and(|id| a.successor(self.states[c], id).is_none())
            })
            .map(|(c, a)| (a.name(), a.state_name(self.states[c]).into_owned()))
    }

    /// Moves every component that has project event `e`; a component that
    /// cannot do it stays where it is, and is named in the error.
    pub fn step(&mut self, e: usize) -> Result<(), String> {
        let mut refused = Vec::new();
        for (c, a) in self.components.iter().enumerate() {
            if let Some(id) = self.ids[c][e] {
                match a.successor(self.states[c], id) {
                    Some(next) => self.states[c] = next,
                    None => refused.push(format!(
                        "{} in `{}`",
                        a.name(),
                        a.state_name(self.states[c])
                    )),
                }
            }
        }
        if refused.is_empty() {
            Ok(())
        } else {
            Err(refused.join(", "))
        }
    }
}

/// What simulates the machine.
pub enum Machine {
    /// No plant model.
    Supervisors,
    /// The project's plant automata.
    Automata(PlantAutomata),
    /// The boiler's physics.
    Boiler {
        /// The plant.
        plant: Box<BoilerPlant>,
        /// Where its signals are in the project.
        io: boiler::IoMap,
    },
    /// The batch cell's physics.
    Cell {
        /// The plant.
        plant: Box<CellPlant>,
        /// Where its signals are in the project.
        io: CellIo,
    },
}

/// The seed of the boiler's random ignition failures in a served run.
const BOILER_SEED: u64 = 1;

impl Machine {
    /// The machine `choice` names for `project`, or why there is none.
    pub fn new(project: &Project, choice: PlantChoice) -> Result<Machine, String> {
        let boiler = || {
            boiler::IoMap::new(project).map(|io| Machine::Boiler {
                plant: Box::new(BoilerPlant::new(BoilerParams::default(), BOILER_SEED)),
                io,
            })
        };
        let cell = || {
            CellIo::new(project).map(|io| Machine::Cell {
                plant: Box::new(CellPlant::new(CellParams::default())),
                io,
            })
        };
        let automata = || PlantAutomata::of_project(project).map_err(|e| e.to_string());
        match choice {
            PlantChoice::Auto => {
                if let Ok(m) = boiler() {
                    return Ok(m);
                }
                if let Ok(m) = cell() {
                    return Ok(m);
                }
                Ok(automata()?.map_or(Machine::Supervisors, Machine::Automata))
            }
            PlantChoice::Automata => automata()?.map(Machine::Automata).ok_or_else(|| {
                "the project synthesises no supervisor from plant files: no plant automata \
                 to simulate (try --plant supervisors)"
                    .to_owned()
            }),
            PlantChoice::Supervisors => Ok(Machine::Supervisors),
            PlantChoice::Boiler => boiler().map_err(|e| e.to_string()),
            PlantChoice::Cell => cell()
                .map_err(|missing| format!("the project lacks the cell's {}", missing.join(", "))),
        }
    }

    /// The machine as at time 0.
    pub fn restart(&mut self) {
        match self {
            Machine::Supervisors => {}
            Machine::Automata(a) => a.restart(),
            Machine::Boiler { plant, .. } => {
                **plant = BoilerPlant::new(BoilerParams::default(), BOILER_SEED);
            }
            Machine::Cell { plant, .. } => **plant = CellPlant::new(CellParams::default()),
        }
    }

    /// Its kind as the API names it.
    pub fn kind(&self) -> &'static str {
        match self {
            Machine::Supervisors => "supervisors",
            Machine::Automata(_) => "automata",
            Machine::Boiler { .. } => "boiler",
            Machine::Cell { .. } => "cell",
        }
    }

    /// One line on what simulates the machine.
    pub fn text(&self) -> String {
        match self {
            Machine::Supervisors => "no plant model: you move the inputs; the supervisors say \
                                     which events they expect"
                .to_owned(),
            Machine::Automata(a) if a.silent.is_empty() => format!(
                "the project's {} plant automata, moved by every executed event; you (or the \
                 random driver) choose among the uncontrollable events they can do",
                a.components.len()
            ),
            Machine::Automata(a) => format!(
                "the project's {} plant automata, moved by every executed event; you (or the \
                 random driver) choose among the uncontrollable events they can do, and \
                 {} the controller cannot see (buttons: the plant moves, nothing is sensed)",
                a.components.len(),
                a.silent
                    .iter()
                    .map(|(n, _)| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Machine::Boiler { .. } => "the gas-fired water-bath boiler's physics (flames, bath \
                                       and flue-gas temperatures) sets every input"
                .to_owned(),
            Machine::Cell { .. } => "the batch cell's physics (tank levels, reactor \
                                     temperatures) sets every input"
                .to_owned(),
        }
    }

    /// Whether the plant sets every input (the user may not).
    pub fn is_physical(&self) -> bool {
        matches!(self, Machine::Boiler { .. } | Machine::Cell { .. })
    }

    /// The plant's actions: the physical plants', the plant automata's
    /// unobservable events.
    pub fn actions(&self) -> Vec<NamedAction> {
        use boiler::Action as B;
        use boiler::Input as I;
        let b = |name: &str, label: &str, action| NamedAction {
            name: name.to_owned(),
            label: label.to_owned(),
            action: PlantAction::Boiler(action),
        };
        let c = |name: &str, label: &str, unit, pressed| NamedAction {
            name: name.to_owned(),
            label: label.to_owned(),
            action: PlantAction::Cell(unit, pressed),
        };
        match self {
            Machine::Boiler { .. } => vec![
                b("selector_off", "Selector: off", B::Selector(Selector::Off)),
                b(
                    "selector_low",
                    "Selector: low fire",
                    B::Selector(Selector::Low),
                ),
                b(
                    "selector_high",
                    "Selector: high fire",
                    B::Selector(Selector::High),
                ),
                b("reset", "Press reset", B::Reset),
                b(
                    "fail_ignitions",
                    "Next 3 ignitions fail",
                    B::Disturb(Disturbance::FailIgnitions(3)),
                ),
                b(
                    "pilot_flame_out",
                    "Pilot flame out (10 s)",
                    B::Disturb(Disturbance::PilotFlameOut { for_ms: 10_000 }),
                ),
                b(
                    "main_flame_out",
                    "Main flame out (10 s)",
                    B::Disturb(Disturbance::MainFlameOut { for_ms: 10_000 }),
                ),
                b(
                    "bath_hot",
                    "Bath excursion to 95 °C",
                    B::Disturb(Disturbance::BathTemperature(95.0)),
                ),
                b(
                    "flue_fouling",
                    "Fouled flue (+150 K)",
                    B::Disturb(Disturbance::FlueFouling(150.0)),
                ),
                b(
                    "flue_clean",
                    "Clean flue",
                    B::Disturb(Disturbance::FlueFouling(0.0)),
                ),
                b(
                    "main_flame_stuck",
                    "Main flame sensor stuck on",
                    B::SensorFault(I::MainFlame, SensorFault::StuckAt(true)),
                ),
                b(
                    "sensors_ok",
                    "Repair the main flame sensor",
                    B::SensorFault(I::MainFlame, SensorFault::None),
                ),
            ],
            Machine::Cell { .. } => vec![
                c("start_a_press", "Start A: press", Unit::A, true),
                c("start_a_release", "Start A: release", Unit::A, false),
                c("start_b_press", "Start B: press", Unit::B, true),
                c("start_b_release", "Start B: release", Unit::B, false),
            ],
            Machine::Automata(a) => a
                .silent()
                .enumerate()
                .map(|(k, name)| NamedAction {
                    name: name.to_owned(),
                    label: format!("{name} (unseen)"),
                    action: PlantAction::Silent(k),
                })
                .collect(),
            Machine::Supervisors => Vec::new(),
        }
    }

    /// Applies `action` to the plant; `false` when the plant cannot take
    /// it now (an unobservable event its automata do not allow).
    pub fn apply(&mut self, action: PlantAction) -> bool {
        match (self, action) {
            (Machine::Boiler { plant, .. }, PlantAction::Boiler(a)) => a.apply_to(plant),
            (Machine::Cell { plant, .. }, PlantAction::Cell(unit, pressed)) => {
                plant.press(unit, pressed)
            }
            (Machine::Automata(a), PlantAction::Silent(k)) => return a.take_silent(k),
            _ => {}
        }
        true
    }

    /// The physical plant's analog quantities (none for the others).
    pub fn analog(&self) -> &'static [Analog] {
        const fn a(
            name: &'static str,
            label: &'static str,
            unit: &'static str,
            max: f64,
        ) -> Analog {
            Analog {
                name,
                label,
                unit,
                min: 0.0,
                max,
            }
        }
        const BOILER: [Analog; 4] = [
            a("bath_c", "bath", "°C", 100.0),
            a("flue_c", "flue gas", "°C", 300.0),
            a("firing_kw", "burner", "kW", 200.0),
            a("load_kw", "load", "kW", 200.0),
        ];
        const CELL: [Analog; 6] = [
            a("mixer_a_m", "mixer A level", "m", 2.0),
            a("mixer_b_m", "mixer B level", "m", 2.0),
            a("reactor_a_m", "reactor A level", "m", 2.0),
            a("reactor_b_m", "reactor B level", "m", 2.0),
            a("reactor_a_c", "reactor A", "°C", 100.0),
            a("reactor_b_c", "reactor B", "°C", 100.0),
        ];
        match self {
            Machine::Boiler { .. } => &BOILER,
            Machine::Cell { .. } => &CELL,
            _ => &[],
        }
    }

    /// The analog quantities now, in [`Machine::analog`]'s order.
    pub fn analog_values(&self) -> Vec<f64> {
        match self {
            Machine::Boiler { plant, .. } => {
                let s = plant.state();
                vec![s.bath_c, s.flue_c, s.firing_kw, s.load_kw]
            }
            Machine::Cell { plant, .. } => {
                let s = plant.state();
                vec![
                    s.mixer_levels[0],
                    s.mixer_levels[1],
                    s.reactors[0].level,
                    s.reactors[1].level,
                    s.reactors[0].temp,
                    s.reactors[1].temp,
                ]
            }
            _ => Vec::new(),
        }
    }

    /// The raw input image a physical plant shows a project with `width`
    /// inputs (`None` for the others: the user's image holds).
    pub fn inputs(&self, width: usize) -> Option<Vec<bool>> {
        match self {
            Machine::Boiler { plant, io } => Some(io.raw_inputs(&plant.inputs())),
            Machine::Cell { plant, io } => Some(io.raw_image(&plant.sensors(), width)),
            _ => None,
        }
    }

    /// Advances a physical plant by `dt_ms` under the output image
    /// `outputs`.
    pub fn advance(&mut self, dt_ms: u64, outputs: &[bool]) {
        match self {
            Machine::Boiler { plant, io } => {
                if let Ok(out) = io.outputs_of(outputs) {
                    plant.step(dt_ms, &out);
                }
            }
            Machine::Cell { plant, io } => plant.step(dt_ms, &io.read_outputs(outputs)),
            _ => {}
        }
    }
}
