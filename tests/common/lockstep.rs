//! What the lockstep tests of exported PLC programs share: the projects,
//! what one scan leaves in the executor's terms, host-sim's side of it,
//! the random inputs and the coverage kept.
//!
//! Included by `st_lockstep.rs` (the ST run by `iec-st`) and
//! `matiec_lockstep.rs` (the ST compiled by matiec and gcc).

#![allow(dead_code)]

use executor::Fault;
use host_sim::inputs::InputRow;
use host_sim::Sim;
use plc_project::{self as project, Project};
use std::collections::BTreeSet;

/// The repository root.
pub use e2e::repo as root;

/// The project at `rel` (from the root), loaded or the test fails.
pub fn load(rel: &str) -> Project {
    project::load(&root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// Every project with `[board]` or without: the seeds, the benchmark AGV,
/// the boiler both ways, the nets, names IEC compilers reserve, the
/// conveyor module's symbolic supervisor (guards), the manufacturing
/// testbed (45 automata) and its guard supervisor of the whole (51).
pub const PROJECTS: [&str; 15] = [
    "models/motivating.plc.toml",
    "models/press.plc.toml",
    "models/press7.plc.toml",
    "models/conveyor.plc.toml",
    "models/crane.plc.toml",
    "models/agv.plc.toml",
    "models/boiler/boiler.plc.toml",
    "models/boiler/boiler_mono.plc.toml",
    "models/petri/mixers.plc.toml",
    "models/petri/cell/cell.plc.toml",
    "tests/fixtures/iec_names/iec_names.plc.toml",
    "models/module.plc.toml",
    "models/testbed/testbed.plc.toml",
    "models/testbed/whole.plc.toml",
    "models/breakdown.plc.toml",
];

/// What one scan left, on either side, in the executor's terms.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Observed {
    /// Events executed, in order.
    pub executed: Vec<u16>,
    /// Unexpected events, in order.
    pub unexpected: Vec<u16>,
    /// Each supervisor's state; a net's marking packed as the executor
    /// packs it.
    pub states: Vec<u32>,
    /// The output image.
    pub outputs: Vec<bool>,
    /// Fault cause and event (−1: none), if in fault mode.
    pub fault: Option<(i64, i64)>,
    /// Faults entered since power-on.
    pub faults: u32,
    /// Unexpected events ignored since power-on.
    pub ignored: u32,
}

/// A fault as the exported block reports it (`FAULT_CAUSE`,
/// `FAULT_EVENT`).
pub fn fault_code(fault: Option<Fault>) -> Option<(i64, i64)> {
    fault.map(|f| match f {
        Fault::Unexpected { event } => (iec_export::scan::CAUSE_UNEXPECTED, i64::from(event)),
        Fault::Corrupt => (iec_export::scan::CAUSE_CORRUPT, -1),
        other => panic!("{other:?} cannot happen in a replay"),
    })
}

/// host-sim's last scan.
pub fn observe_sim(sim: &Sim) -> Observed {
    let c = sim.controller();
    let r = c.record();
    Observed {
        executed: r.executed.to_vec(),
        unexpected: r.unexpected.to_vec(),
        states: r.states.to_vec(),
        outputs: r.outputs.to_vec(),
        fault: fault_code(r.fault),
        faults: c.counters().faults,
        ignored: c.counters().ignored,
    }
}

/// The states of `Observed` from a PLC's automaton states and net
/// markings (place by place), the markings packed as lowering lays the
/// nets out.
pub fn pack_states(project: &Project, automata: &[u32], markings: &[Vec<u32>]) -> Vec<u32> {
    let mut states = automata.to_vec();
    for (n, net) in project.nets.iter().enumerate() {
        let layout = codegen::lower::NetLayout::of(net);
        states.extend((0..layout.groups()).map(|g| layout.pack(g, &markings[n])));
    }
    states
}

/// What a lockstep run went through, for the coverage assertions.
#[derive(Debug, Default)]
pub struct Coverage {
    /// Scans compared.
    pub scans: usize,
    /// Events executed at least once.
    pub executed: BTreeSet<u16>,
    /// Faults entered (host-sim's counter at the end).
    pub faults: u32,
    /// Scans that left fault mode.
    pub resets: usize,
}

impl Coverage {
    /// Asserts that the runs exercised what they compared: some event
    /// executed, and where faults happened in a project with a reset
    /// input, resets too; `what` names the runs.
    pub fn assert_exercised(&self, project: &Project, what: &str) {
        assert!(!self.executed.is_empty(), "{what}: no event executed");
        if self.faults > 0 && project.reset.is_some() {
            assert!(self.resets > 0, "{what}: faults but no reset: {self:?}");
        }
    }

    /// One line for the test's output.
    pub fn summary(&self, project: &Project) -> String {
        format!(
            "{} scans, {} of {} events, {} faults, {} resets",
            self.scans,
            self.executed.len(),
            project.events.len(),
            self.faults,
            self.resets
        )
    }

    /// Adds a run's coverage.
    pub fn add(&mut self, other: Coverage) {
        self.scans += other.scans;
        self.executed.extend(other.executed);
        self.faults += other.faults;
        self.resets += other.resets;
    }
}

/// Runs `rows` through a fresh host-sim and compares each scan with the
/// PLC's observation of the same scan (`plc(k, host)`, called in order);
/// panics at the first difference, naming everything.
pub fn compare(
    project: &Project,
    rows: &[InputRow],
    what: &str,
    mut plc: impl FnMut(usize, &InputRow) -> Observed,
) -> Coverage {
    let mut sim = Sim::new(project.clone(), codegen::backend::Backend::Table).expect("sim");
    sim.retain_trace(false);
    let mut cov = Coverage::default();
    let mut was_fault = false;
    for (k, row) in rows.iter().enumerate() {
        let trace = sim
            .scan_with(row.time_ms, &row.values)
            .expect("scan")
            .clone();
        let host = observe_sim(&sim);
        let theirs = plc(k, row);
        assert_eq!(
            host, theirs,
            "{} ({what}): scan {k} at {} ms differs (left host-sim, right the PLC program); host-sim's row: {trace:?}",
            project.name, row.time_ms
        );
        cov.scans += 1;
        cov.executed.extend(&host.executed);
        cov.faults = host.faults;
        if was_fault && host.fault.is_none() {
            cov.resets += 1;
        }
        was_fault = host.fault.is_some();
    }
    cov
}

/// `scans` rows at the project's period from `start_ms`, whose inputs
/// each toggle with probability 1/16 per scan (seeded xorshift), and
/// whose clock now and then jumps ahead, so that timers run out.
pub fn blind_inputs(project: &Project, scans: usize, seed: u64, start_ms: u64) -> Vec<InputRow> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let mut values = vec![false; project.inputs.len()];
    let mut time_ms = start_ms;
    (0..scans)
        .map(|_| {
            for v in &mut values {
                if next() % 16 == 0 {
                    *v = !*v;
                }
            }
            time_ms += u64::from(project.scan_period_ms)
                * if next() % 64 == 0 {
                    1 + next() % 500
                } else {
                    1
                };
            InputRow {
                time_ms,
                values: values.clone(),
            }
        })
        .collect()
}

/// Rows moved `offset_ms` later (a clock that wraps during the run when
/// the offset is close to 2^32).
pub fn shifted(rows: Vec<InputRow>, offset_ms: u64) -> Vec<InputRow> {
    rows.into_iter()
        .map(|r| InputRow {
            time_ms: r.time_ms + offset_ms,
            values: r.values,
        })
        .collect()
}

/// Rows put on the period grid (`k · period`), as a PLC task running the
/// program sees its inputs: the program keeps its own clock.
pub fn on_grid(project: &Project, rows: Vec<InputRow>) -> Vec<InputRow> {
    let period = u64::from(project.scan_period_ms);
    rows.into_iter()
        .enumerate()
        .map(|(k, r)| InputRow {
            time_ms: k as u64 * period,
            values: r.values,
        })
        .collect()
}

/// The boiler's closed-loop scenarios (all but the controller stall,
/// whose overrun a PLC's own task watchdog handles), each run by host-sim
/// with the plant: its input image per scan, to replay into a PLC
/// program.
pub fn boiler_scenarios(project: &Project) -> Vec<(&'static str, Vec<InputRow>)> {
    use host_sim::boiler::{self, scenarios, BoilerParams, BoilerPlant, IoMap as Boiler};
    let io = Boiler::new(project).expect("boiler signals");
    scenarios::NAMES
        .iter()
        .filter(|n| **n != "controller-stall")
        .map(|name| {
            let (script, duration) = scenarios::named(name).expect("scenario");
            let mut sim = Sim::new(project.clone(), codegen::backend::Backend::Table).expect("sim");
            let mut plant = BoilerPlant::new(BoilerParams::default(), 1);
            let run = boiler::run(&mut sim, &mut plant, &script, duration).expect("runs");
            let rows = run.input_rows(&io);
            (*name, rows)
        })
        .collect()
}

/// `text` with the first defined target in the first row of the dense
/// transition array `table` changed to another state: a mutant the
/// lockstep must find.
pub fn mutant(text: &str, table: &str) -> String {
    let start = text
        .find(&format!("{table} : ARRAY"))
        .expect("a dense transition array");
    let row = start + text[start..].find("*) ").expect("a row label") + 3;
    let end = row + text[row..].find('\n').expect("row end");
    let values: Vec<&str> = text[row..end].trim_end_matches(',').split(", ").collect();
    let k = values
        .iter()
        .position(|v| *v != "-1")
        .expect("a defined target");
    let mut changed: Vec<String> = values.iter().map(|v| v.to_string()).collect();
    changed[k] = if values[k] == "0" { "1" } else { "0" }.to_string();
    let mut row_text = changed.join(", ");
    if text[row..end].ends_with(',') {
        row_text.push(',');
    }
    format!("{}{}{}", &text[..row], row_text, &text[end..])
}

/// The message of a test's panic, for asserting what it said.
pub fn panic_text(payload: Box<dyn std::any::Any + Send>) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}

/// The conveyor module (`models/module.plc.toml`) with every command's
/// guard replaced by a random decision diagram of 24 to 39 nodes over a
/// window of eight state bits (a valid node table: children first), which
/// the export writes as chains of temporaries where no short sum of
/// products states it; the executor runs the same guards.
pub fn module_with_random_guards(seed: u64) -> Project {
    let mut project = load("models/module.plc.toml");
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut below = |n: u64| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x % n.max(1)
    };
    let g = &mut project.guarded[0];
    let bits = g.bits.len() as u64;
    for eg in &mut g.guards {
        // Nodes reading the bits of a few neighbouring components, so
        // that the guard depends on states the scan moves.
        let nodes = 24 + below(16) as u32;
        let window = below(bits.saturating_sub(8));
        eg.nodes = (0..nodes)
            .map(|k| {
                let bit = (window + below(8)).min(bits - 1) as u32;
                let low = below(u64::from(k) + 2) as u32;
                let high = below(u64::from(k) + 2) as u32;
                [bit, low, high]
            })
            .collect();
        eg.root = nodes + 1;
        eg.text = format!("random guard of {nodes} nodes");
    }
    project
}
