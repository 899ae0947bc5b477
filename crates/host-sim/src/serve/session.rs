//! One simulation of a served project: the executor on a virtual clock,
//! the machine it runs against, the input changes still due, the random
//! driver, and what the page shows (event log, plots, the run as files).
//!
//! Every scan runs at `scan × scan_period_ms` with the raw image the
//! machine (or the user) set, through [`Sim::scan_with`], exactly as
//! `host-sim replay` runs the rows of an inputs file: the run's
//! [`Session::inputs_csv`] replays into its [`Session::trace_csv`].

use super::history::{History, Series};
use super::machine::{Machine, NamedAction, PlantChoice};
use super::stimulus::{self, Change};
use crate::inputs::{self, InputRow};
use crate::rng::Rng;
use crate::sim::Sim;
use crate::trace::{self, fault_text, TraceRow};
use codegen::backend::Backend;
use plc_project::{Origin, Project, Trigger};
use std::collections::VecDeque;
use std::path::Path;

/// Entries the event log keeps.
pub const LOG_ENTRIES: usize = 200;

/// The most scans whose inputs a session keeps as text for download
/// (about 60 MB for the boiler); a longer run says so instead.
pub const KEPT_INPUTS: u64 = 2_000_000;

/// The most scans whose trace a session keeps as text for download (about
/// 60 MB for the boiler): beyond them, `host-sim replay` of the inputs
/// file writes it.
pub const KEPT_TRACE: u64 = 250_000;

/// The most scans one request may run.
pub const MAX_SCANS_PER_REQUEST: u64 = 10_000_000;

/// A scan that did something: events, a fault change, a user's action.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct LogEntry {
    /// Scan number.
    pub scan: u64,
    /// Its time.
    pub time_ms: u64,
    /// Executed events, in order.
    pub events: Vec<String>,
    /// Unexpected events.
    pub unexpected: Vec<String>,
    /// The fault cause, if the scan ended in fault mode.
    pub fault: Option<String>,
    /// What the user or the driver did before it.
    pub note: Option<String>,
}

/// The random driver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Driver {
    /// Only the user acts.
    None,
    /// Expected events (or plant actions) at random.
    Random,
}

/// A served simulation.
pub struct Session {
    sim: Sim,
    machine: Machine,
    actions: Vec<NamedAction>,
    period: u64,
    /// Scans run.
    scans: u64,
    /// The raw image the next scan reads (the user's, or the machine's).
    raw: Vec<bool>,
    pending: Vec<Change>,
    /// Events the driver made an input edge for, not yet executed, with
    /// the scan it was made in.
    awaiting: Vec<(usize, u64)>,
    /// Operator buttons to release once their event is seen.
    release: Vec<(usize, usize)>,
    notes: Vec<String>,
    log: VecDeque<LogEntry>,
    history: History,
    inputs_csv: String,
    trace_csv: String,
    driver: Driver,
    rng: Rng,
    /// The last scan's record.
    last: Option<TraceRow>,
    /// A note of what the machine refused, for the log.
    plant_refusals: Vec<String>,
}

/// The seed of the random driver.
const DRIVER_SEED: u64 = 1;

impl Session {
    /// A session of the project at `path` on `backend` against the machine
    /// `choice` names.
    pub fn load(path: &Path, backend: Backend, choice: PlantChoice) -> Result<Session, String> {
        let project = plc_project::load(path).map_err(|e| e.to_string())?;
        Session::new(project, backend, choice)
    }

    /// A session of `project`.
    pub fn new(project: Project, backend: Backend, choice: PlantChoice) -> Result<Session, String> {
        let machine = Machine::new(&project, choice)?;
        let mut sim = Sim::new(project, backend).map_err(|e| e.to_string())?;
        sim.retain_trace(false);
        let project = sim.project();
        let period = u64::from(sim.config().scan_period_ms.max(1));
        let mut session = Session {
            raw: vec![false; project.inputs.len()],
            history: History::new(
                project.inputs.len(),
                project.outputs.len(),
                machine.analog().len(),
            ),
            inputs_csv: String::new(),
            trace_csv: String::new(),
            actions: machine.actions(),
            machine,
            period,
            scans: 0,
            pending: Vec::new(),
            awaiting: Vec::new(),
            release: Vec::new(),
            notes: Vec::new(),
            log: VecDeque::new(),
            driver: Driver::None,
            rng: Rng::new(DRIVER_SEED),
            last: None,
            plant_refusals: Vec::new(),
            sim,
        };
        session.start_files();
        session.power_up();
        Ok(session)
    }

    /// A physical plant's first scan runs at once: the inputs it shows at
    /// rest are the baseline of edge detection (scan 0 has no edges), and
    /// whatever the user does to it comes after. With the other machines
    /// the user may set inputs before the first scan (a limit switch
    /// already closed at power-up).
    fn power_up(&mut self) {
        if self.machine.is_physical() {
            self.scan();
        }
    }

    fn start_files(&mut self) {
        let project = self.sim.project();
        self.inputs_csv = inputs::csv_header(project);
        self.inputs_csv.push('\n');
        self.trace_csv = trace::header(project);
        self.trace_csv.push('\n');
    }

    /// Back to time 0: a new controller, the machine as at start, no log.
    pub fn restart(&mut self) -> Result<(), String> {
        let mut sim =
            Sim::new(self.sim.project().clone(), self.backend()).map_err(|e| e.to_string())?;
        sim.retain_trace(false);
        self.sim = sim;
        self.machine.restart();
        self.scans = 0;
        self.raw.iter_mut().for_each(|v| *v = false);
        self.pending.clear();
        self.awaiting.clear();
        self.release.clear();
        self.notes.clear();
        self.log.clear();
        self.history.clear();
        self.rng = Rng::new(DRIVER_SEED);
        self.last = None;
        self.plant_refusals.clear();
        self.start_files();
        self.power_up();
        Ok(())
    }

    fn backend(&self) -> Backend {
        self.sim.controller().program().backend()
    }

    /// The simulation.
    pub fn sim(&self) -> &Sim {
        &self.sim
    }

    /// The project.
    pub fn project(&self) -> &Project {
        self.sim.project()
    }

    /// The machine.
    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// The physical plant's actions.
    pub fn actions(&self) -> &[NamedAction] {
        &self.actions
    }

    /// Scans run.
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// The time of the last scan (0 before the first).
    pub fn time_ms(&self) -> u64 {
        self.scans.saturating_sub(1) * self.period
    }

    /// The raw image the next scan reads.
    pub fn raw(&self) -> &[bool] {
        &self.raw
    }

    /// The last scan's row.
    pub fn last(&self) -> Option<&TraceRow> {
        self.last.as_ref()
    }

    /// The event log, oldest first.
    pub fn log(&self) -> impl Iterator<Item = &LogEntry> {
        self.log.iter()
    }

    /// The random driver.
    pub fn driver(&self) -> Driver {
        self.driver
    }

    /// Turns the random driver on or off.
    pub fn set_driver(&mut self, driver: Driver) {
        self.driver = driver;
    }

    /// Plot data ([`History::series`]).
    pub fn series(&self, points: usize, from_ms: u64) -> Series {
        self.history.series(points, from_ms)
    }

    /// The run so far as an inputs file, or why it is not kept.
    pub fn inputs_csv(&self) -> Result<&str, String> {
        if self.scans > KEPT_INPUTS {
            return Err(format!(
                "the run has {} scans; its inputs are kept for {KEPT_INPUTS} scans at most \
                 (restart for a shorter run)",
                self.scans
            ));
        }
        Ok(&self.inputs_csv)
    }

    /// The run so far as a trace file, or why it is not kept.
    pub fn trace_csv(&self) -> Result<&str, String> {
        if self.scans > KEPT_TRACE {
            return Err(format!(
                "the run has {} scans; its trace is kept for {KEPT_TRACE} scans at most: \
                 `host-sim replay PROJECT --inputs inputs.csv --out trace.csv` writes it",
                self.scans
            ));
        }
        Ok(&self.trace_csv)
    }

    /// An error when a physical plant sets every input.
    fn user_moves_inputs(&self) -> Result<(), String> {
        if self.machine.is_physical() {
            return Err(format!(
                "the {} plant sets every input; act on it instead",
                self.machine.kind()
            ));
        }
        Ok(())
    }

    /// Sets raw input `name` for the following scans; refused for a
    /// physical plant, which sets every input itself.
    pub fn set_input(&mut self, name: &str, value: bool) -> Result<(), String> {
        self.user_moves_inputs()?;
        let i = self
            .project()
            .input(name)
            .ok_or_else(|| format!("`{name}` is not an input of the project"))?;
        self.pending.retain(|c| c.input != i);
        self.raw[i] = value;
        self.notes.push(format!("{name} := {}", u8::from(value)));
        Ok(())
    }

    /// Applies the physical plant's action `name` before the next scan.
    pub fn act(&mut self, name: &str) -> Result<(), String> {
        let k = self
            .actions
            .iter()
            .position(|a| a.name == name)
            .ok_or_else(|| format!("`{name}` is not an action of this plant"))?;
        if !self.machine.apply(self.actions[k].action) {
            return Err(format!(
                "the plant cannot do `{name}` now (its automata are in {})",
                self.plant_states()
            ));
        }
        self.notes.push(self.actions[k].label.clone());
        Ok(())
    }

    /// Gives uncontrollable event `name` its input edge and runs scans
    /// until the executor executes it or finds it unexpected (or its
    /// patience runs out); refused for a physical plant and for events no
    /// input edge makes.
    pub fn click(&mut self, name: &str) -> Result<(), String> {
        self.user_moves_inputs()?;
        let e = self
            .project()
            .event(name)
            .ok_or_else(|| format!("`{name}` is not an event of the project"))?;
        let patience = self.schedule(e)?;
        self.notes.push(format!("clicked {name}"));
        for _ in 0..patience {
            self.scan();
            let row = self.last.as_ref().expect("just scanned");
            let seen = row.events.iter().chain(&row.ignored).any(|x| x == name);
            if seen || row.fault.is_some() {
                break;
            }
        }
        Ok(())
    }

    /// Plans event `e`'s edge from the next scan on; returns the scans it
    /// may take.
    fn schedule(&mut self, e: usize) -> Result<u64, String> {
        let project = self.sim.project();
        // The first scan sets the baseline of edge detection (no edge on
        // scan 0), so a change before it is planned for the scan after.
        let now = self.scans.max(1);
        let changes = stimulus::plan(project, e, &self.raw, now)?;
        let patience = stimulus::patience(project, &changes, now) + (now - self.scans);
        let event = &project.events[e];
        if event.origin == Origin::Operator {
            if let Trigger::Rising(list) = &event.trigger {
                if stimulus::releases(project, list[0]) {
                    self.release.push((e, list[0]));
                }
            }
        }
        let touched: Vec<usize> = changes.iter().map(|c| c.input).collect();
        self.pending.retain(|c| !touched.contains(&c.input));
        self.pending.extend(changes);
        Ok(patience)
    }

    /// Runs `n` scans.
    pub fn step(&mut self, n: u64) {
        for _ in 0..n {
            self.scan();
        }
    }

    /// One scan: the driver, due input changes, the
    /// executor, then the machine after it.
    fn scan(&mut self) {
        let scan = self.scans;
        let time = scan * self.period;
        if self.driver == Driver::Random {
            self.drive();
        }
        let raw = &mut self.raw;
        self.pending.retain(|c| {
            let due = c.at_scan <= scan;
            if due {
                raw[c.input] = c.value;
            }
            !due
        });
        if let Some(image) = self.machine.inputs(self.raw.len()) {
            self.raw = image;
        }
        let row = self
            .sim
            .scan_with(time, &self.raw)
            .expect("the image has one value per input")
            .clone();
        self.scans += 1;
        self.after_scan(&row);
        self.last = Some(row);
    }

    fn after_scan(&mut self, row: &TraceRow) {
        let project = self.sim.project();
        if self.scans <= KEPT_INPUTS {
            let input_row = InputRow {
                time_ms: row.time_ms,
                values: self.raw.clone(),
            };
            self.inputs_csv
                .push_str(&inputs::csv_line(row.scan, &input_row));
            self.inputs_csv.push('\n');
        }
        if self.scans <= KEPT_TRACE {
            self.trace_csv.push_str(&trace::csv_line(row));
            self.trace_csv.push('\n');
        }
        let events: Vec<usize> = row
            .events
            .iter()
            .filter_map(|name| project.event(name))
            .collect();
        // An edge lost to a fault or to the filter is not waited for long.
        let scan = row.scan;
        self.awaiting
            .retain(|&(e, at)| !events.contains(&e) && scan < at + 100);
        if let Machine::Automata(plant) = &mut self.machine {
            for &e in &events {
                if let Err(who) = plant.step(e) {
                    self.plant_refusals.push(format!(
                        "plant model cannot do {}: {who}",
                        project.events[e].name
                    ));
                }
            }
        }
        self.history.push(
            row.scan,
            row.time_ms,
            &self.raw,
            &row.outputs,
            row.fault.is_some(),
            &self.machine.analog_values(),
        );
        // Operator buttons whose event was seen are released.
        let seen = |e: usize| {
            let name = &project.events[e].name;
            row.events.iter().chain(&row.ignored).any(|x| x == name)
        };
        let (done, waiting): (Vec<_>, Vec<_>) = self.release.iter().partition(|&&(e, _)| seen(e));
        self.release = waiting;
        for (_, input) in done {
            if self.pending.iter().all(|c| c.input != input) {
                self.raw[input] = false;
            }
        }
        // The plant runs until the next scan under the outputs.
        self.machine.advance(self.period, &row.outputs);
        let fault_changed = self
            .last
            .as_ref()
            .map_or(row.fault.is_some(), |l| l.fault != row.fault);
        if !row.events.is_empty()
            || !row.ignored.is_empty()
            || fault_changed
            || !self.notes.is_empty()
            || !self.plant_refusals.is_empty()
        {
            let mut notes = std::mem::take(&mut self.notes);
            notes.append(&mut self.plant_refusals);
            if self.log.len() == LOG_ENTRIES {
                self.log.pop_front();
            }
            self.log.push_back(LogEntry {
                scan: row.scan,
                time_ms: row.time_ms,
                events: row.events.clone(),
                unexpected: row.ignored.clone(),
                fault: row.fault.clone(),
                note: (!notes.is_empty()).then(|| notes.join("; ")),
            });
        }
    }

    /// The random driver's move before a scan: after a fault, the reset
    /// pressed a few scans later; else now and then an expected event the
    /// machine can do (or a plant action), and request inputs flipped.
    fn drive(&mut self) {
        if self.machine.is_physical() {
            if self.rng.one_in(3_000) {
                let k = (self.rng.next_u64() % self.actions.len() as u64) as usize;
                self.machine.apply(self.actions[k].action);
                self.notes
                    .push(format!("driver: {}", self.actions[k].label));
            }
            return;
        }
        // Now and then an unobservable event the plant can do, never while
        // an event it made is on its way through the input filter (the
        // plant moves with that event when the executor executes it).
        if !self.actions.is_empty() && self.awaiting.is_empty() && self.rng.one_in(40) {
            let k = (self.rng.next_u64() % self.actions.len() as u64) as usize;
            if self.machine.apply(self.actions[k].action) {
                self.notes
                    .push(format!("driver: {}", self.actions[k].label));
            }
        }
        if !self.pending.is_empty() {
            return;
        }
        let project = self.sim.project();
        if self.sim.controller().fault().is_some() {
            if let Some(r) = project.reset {
                if self.rng.one_in(8) {
                    let now = self.scans;
                    let hold = u64::from(project.inputs[r].debounce_scans.max(1));
                    self.pending.push(Change {
                        at_scan: now,
                        input: r,
                        value: !self.raw[r],
                    });
                    if !self.raw[r] {
                        self.pending.push(Change {
                            at_scan: now + hold + 1,
                            input: r,
                            value: false,
                        });
                    }
                    self.notes
                        .push(format!("driver: reset ({})", project.inputs[r].name));
                }
            }
            return;
        }
        if self.rng.one_in(4) {
            let candidates: Vec<usize> = (0..project.events.len())
                .filter(|&e| self.clickable(e) && self.expected(e) && self.plant_can(e))
                .filter(|&e| stimulus::unmet_conditions(project, e, &self.raw).is_none())
                .collect();
            if !candidates.is_empty() {
                let e = candidates[(self.rng.next_u64() % candidates.len() as u64) as usize];
                let name = project.events[e].name.clone();
                if self.schedule(e).is_ok() {
                    self.notes.push(format!("driver: {name}"));
                    self.awaiting.push((e, self.scans));
                }
            }
        }
        let project = self.sim.project();
        let requests: Vec<usize> = project.events.iter().filter_map(|e| e.request).collect();
        if !requests.is_empty() && self.rng.one_in(10) {
            let r = requests[(self.rng.next_u64() % requests.len() as u64) as usize];
            self.raw[r] = !self.raw[r];
            self.notes.push(format!(
                "driver: {} := {}",
                project.inputs[r].name,
                u8::from(self.raw[r])
            ));
        }
    }

    /// Whether an input edge makes event `e` (the page may click it).
    pub fn clickable(&self, e: usize) -> bool {
        !self.machine.is_physical()
            && matches!(
                self.project().events[e].trigger,
                Trigger::Rising(_) | Trigger::Falling(_)
            )
    }

    /// Whether every supervisor lets event `e` occur now.
    pub fn expected(&self, e: usize) -> bool {
        self.sim
            .supervisors()
            .event_feasible(e, self.sim.controller().states())
    }

    /// The plant automata's states as `M1 down, M2 idle` (empty for other
    /// machines).
    fn plant_states(&self) -> String {
        match &self.machine {
            Machine::Automata(a) => a
                .components()
                .iter()
                .zip(a.state_names())
                .map(|(c, s)| format!("{} {s}", c.name()))
                .collect::<Vec<_>>()
                .join(", "),
            _ => String::new(),
        }
    }

    /// Whether the machine can do event `e` now (always, but for plant
    /// automata).
    pub fn plant_can(&self, e: usize) -> bool {
        match &self.machine {
            Machine::Automata(plant) => plant.refuses(e).is_none(),
            _ => true,
        }
    }

    /// The fault cause now.
    pub fn fault(&self) -> Option<String> {
        self.sim
            .controller()
            .fault()
            .map(|f| fault_text(f, self.project()))
    }
}
