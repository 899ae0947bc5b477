//! Partial observation in closed loop (`models/breakdown.plc.toml`): M1
//! breaks down without a sensor seeing it (`b1` unobservable), so the
//! supervisor the executor runs is supconnorm's result projected onto the
//! events the controller sees.
//!
//! The machine is played by its own plant automata. Each scan the plant
//! may take one uncontrollable event its automata allow: a finished part
//! raises the machine's done signal (`f1`, `f2`; the signal drops when the
//! controller starts the machine again), a repair is the technician's
//! button pressed and released (`r1`), and a breakdown (`b1`) only moves
//! the plant. The plant follows every command the controller executes.
//!
//! What must hold, every scan, on both backends alike: no fault and no
//! unexpected event, every command one the plant can carry out (the
//! controller never commands on a guess), the buffer within its two
//! slots, and the safety rule the controller cannot check directly: M2
//! never starts while M1 is down. Since the controller never knows M1 is
//! not down once started, M2 starts only while M1 is idle. And the cell
//! works: parts go through M2, breakdowns and repairs happen.

mod common;

use codegen::backend::Backend;
use common::plant::Plant;
use host_sim::rng::Rng;
use host_sim::sim::Sim;
use plc_project::SupervisorSource;
use std::collections::BTreeMap;

const PROJECT: &str = "../../models/breakdown.plc.toml";

/// Scans an input keeps its level before the plant moves it again: more
/// than the debounce filter's 2, so that every edge reaches the executor.
const DWELL: u64 = 3;

/// The two backends side by side, fed the same inputs.
struct Both {
    sims: [Sim; 2],
}

impl Both {
    fn set(&mut self, input: &str, level: bool) {
        for sim in &mut self.sims {
            sim.set(input, level).unwrap();
        }
    }

    fn scan(&mut self) -> host_sim::TraceRow {
        let table = self.sims[0].scan().clone();
        let logic = self.sims[1].scan().clone();
        assert_eq!(table, logic, "the backends differ");
        table
    }
}

#[test]
fn the_projected_supervisor_runs_the_cell_safely_without_seeing_breakdowns() {
    let load = |backend| {
        let mut sim = Sim::load(PROJECT.as_ref(), backend).unwrap();
        sim.retain_trace(false);
        sim
    };
    let mut both = Both {
        sims: [load(Backend::Table), load(Backend::Logic)],
    };
    let project = both.sims[0].project().clone();
    let cell = &project.supervisors[0].automaton;
    assert!(
        !cell.alphabet().contains("b1"),
        "the controller runs without b1"
    );
    assert!(project.events.iter().all(|e| e.name != "b1"));
    let SupervisorSource::Synthesized { plants, .. } = &project.supervisors[0].source else {
        panic!("the cell's supervisor is synthesised");
    };
    let mut plant = Plant::of_files(plants);

    let mut rng = Rng::new(0xB12E_A4D0);
    let mut changed: BTreeMap<&str, u64> = BTreeMap::new();
    let mut release_button_at: Option<u64> = None;
    let mut buffer = 0u32;
    let mut count: BTreeMap<String, usize> = BTreeMap::new();
    for scan in 0..20_000u64 {
        let settled = |changed: &BTreeMap<&str, u64>, input: &str| {
            changed.get(input).is_none_or(|&at| scan >= at + DWELL)
        };
        if release_button_at == Some(scan) {
            both.set("m1_repaired", false);
            changed.insert("m1_repaired", scan);
            release_button_at = None;
        }
        // Scan 0 sees no edges (docs/semantics.md): the plant starts after it.
        if scan > 0 && rng.next_u64() % 4 == 0 {
            let candidates: Vec<(&str, Option<&str>)> = [
                ("f1", Some("m1_done")),
                ("b1", None),
                ("r1", Some("m1_repaired")),
                ("f2", Some("m2_done")),
            ]
            .into_iter()
            .filter(|&(e, input)| plant.allows(e) && input.is_none_or(|i| settled(&changed, i)))
            // A breakdown is rarer than a finished part.
            .filter(|&(e, _)| e != "b1" || rng.next_u64() % 4 == 0)
            .collect();
            if !candidates.is_empty() {
                let (event, input) =
                    candidates[(rng.next_u64() % candidates.len() as u64) as usize];
                assert!(plant.take(event));
                *count.entry(format!("plant {event}")).or_default() += 1;
                if event == "f1" {
                    buffer += 1;
                }
                if let Some(input) = input {
                    both.set(input, true);
                    changed.insert(input, scan);
                    if input == "m1_repaired" {
                        release_button_at = Some(scan + DWELL);
                    }
                }
            }
        }
        let row = both.scan();
        assert_eq!(row.fault, None, "scan {scan}: {row:?}");
        assert!(row.ignored.is_empty(), "scan {scan}: {row:?}");
        for e in &row.events {
            *count.entry(e.clone()).or_default() += 1;
            match e.as_str() {
                "s1" | "s2" => {
                    if e == "s2" {
                        assert_eq!(
                            plant.state("M1"),
                            "idle",
                            "scan {scan}: M2 started while M1 may be down"
                        );
                        assert!(buffer > 0, "scan {scan}: M2 started on an empty buffer");
                        buffer -= 1;
                    }
                    assert!(
                        plant.take(e),
                        "scan {scan}: command {e} the plant cannot carry out"
                    );
                    // A started machine's done signal drops.
                    let done = if e == "s1" { "m1_done" } else { "m2_done" };
                    both.set(done, false);
                    changed.insert(done, scan);
                }
                _ => {}
            }
        }
        assert!(buffer <= 2, "scan {scan}: the buffer overflowed");
    }
    eprintln!("breakdown: 20,000 scans, {count:?}");
    for e in ["s1", "f1", "r1", "s2", "f2", "plant b1"] {
        assert!(count.get(e).is_some_and(|&n| n >= 20), "{e}: {count:?}");
    }
    // What the controller saw is what happened.
    for e in ["f1", "r1", "f2"] {
        let (seen, done) = (count[e], count[&format!("plant {e}")]);
        assert!(done - seen <= 1, "{e}: {done} happened, {seen} seen");
    }
}
