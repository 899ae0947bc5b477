//! The Prenzel–Provost-class module (`models/module.plc.toml`, issue 24)
//! in closed loop: its symbolic supervisor (40 components, guards; a
//! closed loop of 3.57·10^12 states) runs in the executor, and the
//! machine is played by its own plant automata: each scan the plant may
//! take one uncontrollable event its automata allow (a part arriving at
//! or leaving a light sensor), shown to the controller as the sensor's
//! edge, and it follows every command the controller executes (a belt
//! starting forward or backward, stopping).
//!
//! What must hold, every scan: no fault and no unexpected event (the
//! supervisor is controllable: whatever the plant does is explained), no
//! executed event the plant automata refuse (no command the machine
//! cannot carry out), each belt's outputs equal to its plant automaton's
//! state. And nonblocking in practice: once arrivals stop and the parts
//! on the sensors leave, the whole closed loop comes to rest in a state
//! marked in every component.

mod common;

use codegen::backend::Backend;
use common::plant::Plant;
use des::automaton::StateId;
use host_sim::rng::Rng;
use host_sim::sim::Sim;
use plc_project::{GuardedSource, Trigger};
use std::collections::BTreeMap;

/// A number in `0..n` (`n > 0`).
fn below(rng: &mut Rng, n: usize) -> usize {
    (rng.next_u64() % n as u64) as usize
}

/// The plant automata the module's supervisor was synthesised from.
fn plant_of(sim: &Sim) -> Plant {
    let GuardedSource::Synthesized { plants, .. } = &sim.project().guarded[0].source else {
        panic!("the module's supervisor is synthesised symbolically");
    };
    let plant = Plant::of_files(plants);
    assert_eq!(plant.len(), 20, "10 light sensors and 10 belts");
    plant
}

/// The uncontrollable events and the input each one's edge moves (`true`:
/// a rising edge).
fn sensor_events(sim: &Sim) -> Vec<(String, String, bool)> {
    let p = sim.project();
    p.events
        .iter()
        .filter_map(|e| match &e.trigger {
            Trigger::Rising(list) => Some((e.name.clone(), p.inputs[list[0]].name.clone(), true)),
            Trigger::Falling(list) => Some((e.name.clone(), p.inputs[list[0]].name.clone(), false)),
            _ => None,
        })
        .collect()
}

/// Runs `scans` scans; while `arrivals` parts may arrive, else only leave.
/// The events executed, counted by name.
fn drive(
    sim: &mut Sim,
    plant: &mut Plant,
    rng: &mut Rng,
    scans: usize,
    arrivals: bool,
) -> BTreeMap<String, usize> {
    let sensors = sensor_events(sim);
    let mut executed = BTreeMap::new();
    for _ in 0..scans {
        if below(rng, 3) == 0 {
            let possible: Vec<&(String, String, bool)> = sensors
                .iter()
                .filter(|(e, _, rising)| (arrivals || !rising) && plant.allows(e))
                .collect();
            if !possible.is_empty() {
                let (event, input, rising) = possible[below(rng, possible.len())];
                assert!(plant.take(event));
                sim.set(input, *rising).unwrap();
            }
        }
        let row = sim.scan().clone();
        assert_eq!(row.fault, None, "scan {}: {:?}", row.scan, row);
        assert!(row.ignored.is_empty(), "scan {}: {:?}", row.scan, row);
        for e in &row.events {
            *executed.entry(e.clone()).or_insert(0) += 1;
            if !sensors.iter().any(|(s, _, _)| s == e) {
                assert!(
                    plant.take(e),
                    "scan {}: command {e} the plant cannot carry out",
                    row.scan
                );
            }
        }
        for i in 0..10 {
            let belt = plant.state(&format!("BELT{i}"));
            assert_eq!(
                (
                    sim.output(&format!("belt_fwd_{i}")).unwrap(),
                    sim.output(&format!("belt_rev_{i}")).unwrap()
                ),
                (belt == "forward", belt == "backward"),
                "scan {}: belt {i}",
                row.scan
            );
        }
    }
    executed
}

/// Whether every component of the symbolic supervisor is in a marked
/// state.
fn at_rest(sim: &Sim) -> bool {
    let p = sim.project();
    let states = sim.controller().states();
    p.guarded[0]
        .components
        .clone()
        .all(|j| p.supervisors[j].automaton.is_marked(StateId(states[j])))
}

#[test]
fn the_module_runs_its_plant_without_a_fault_and_comes_to_rest() {
    let mut sim = Sim::load("../../models/module.plc.toml".as_ref(), Backend::Table).unwrap();
    sim.retain_trace(false);
    assert_eq!(sim.project().supervisors.len(), 40, "40 components");
    assert_eq!(sim.project().guarded[0].closed_loop_states, "3570467226624");
    let mut plant = plant_of(&sim);
    // Scan 0 sees no edges (docs/semantics.md): the plant starts after it.
    assert_eq!(sim.scan().fault, None);
    let mut rng = Rng::new(0xB0DE);
    let mut total: BTreeMap<String, usize> = BTreeMap::new();
    let mut rests = 0;
    for round in 0..8 {
        for (e, n) in drive(&mut sim, &mut plant, &mut rng, 1_500, true) {
            *total.entry(e).or_insert(0) += n;
        }
        // No more parts: those on the sensors leave, the belts stop.
        drive(&mut sim, &mut plant, &mut rng, 300, false);
        assert!(
            at_rest(&sim),
            "round {round}: the closed loop did not come to rest"
        );
        rests += 1;
    }
    // Every command and sensor event of every station happened.
    for i in 0..10 {
        for e in ["RE_ls", "FE_ls", "fwd", "rev", "stop"] {
            let name = format!("{e}_{i}");
            assert!(
                total.get(&name).is_some_and(|&n| n > 0),
                "{name} never ran: {total:?}"
            );
        }
    }
    let events: usize = total.values().sum();
    eprintln!("module: 8 rounds of 1,800 scans, {events} events executed, at rest {rests} times");
}
