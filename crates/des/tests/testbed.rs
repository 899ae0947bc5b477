//! The testbed of docs/seeds.md B (`models/testbed/`): the committed
//! files are what the generator writes, and the paper's claims that we
//! can check hold: 29 modular supervisors, each controllable, decided on
//! its reduced plant.

#[path = "../examples/testbed.rs"]
mod testbed;

use des::formats;
use des::ops::{check_controllable_modular, ComposeOptions};
use des::Automaton;
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/testbed")
}

fn read(sub: &str) -> Vec<Automaton> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir().join(sub))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| formats::read_automaton(p).unwrap())
        .collect()
}

#[test]
fn the_committed_models_are_what_the_generator_writes() {
    let files = testbed::files();
    for (name, text) in &files {
        let path = dir().join(name);
        let committed =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            committed == *text,
            "{name} differs from the generator's: cargo run -p des --example testbed -- models/testbed"
        );
    }
    for sub in ["plant", "sup"] {
        for entry in std::fs::read_dir(dir().join(sub)).unwrap() {
            let name = format!("{sub}/{}", entry.unwrap().file_name().to_string_lossy());
            assert!(files.contains_key(&name), "{name} is not generated");
        }
    }
}

#[test]
fn every_supervisor_is_controllable_on_its_reduced_plant() {
    let plant = read("plant");
    let sups = read("sup");
    assert_eq!((plant.len(), sups.len()), (22, 29));
    let refs: Vec<&Automaton> = plant.iter().collect();
    for sup in &sups {
        let t = std::time::Instant::now();
        let v = check_controllable_modular(&refs, sup, ComposeOptions::default()).unwrap();
        eprintln!(
            "{} {:?} {} {} {:?}",
            sup.name(),
            v.reduced_names,
            v.reduced_states,
            v.rounds,
            t.elapsed()
        );
        assert!(v.controllable(), "{v:?}");
        assert_eq!(v.rounds, 1, "{}", sup.name());
    }
}

/// The closed loop: the 22 plant components and the 29 supervisors
/// composed as one (the plant alone is about 10^9 states; the
/// supervisors keep the closed loop small).
fn closed_loop() -> (Vec<Automaton>, des::ops::Product) {
    let mut all = read("plant");
    all.extend(read("sup"));
    let refs: Vec<&Automaton> = all.iter().collect();
    let options = ComposeOptions {
        name_states: false,
        ..ComposeOptions::default()
    };
    let product = des::ops::compose(&refs, des::ops::Composition::Sync, options).unwrap();
    (all, product)
}

#[test]
fn the_closed_loop_is_nonblocking_collision_free_and_keeps_the_routes() {
    let (all, product) = closed_loop();
    let a = &product.automaton;
    assert_eq!(a.num_states(), 12_318);
    // Nonblocking: from every state both trains can stop at their start
    // sensors again, cranes idle, no request pending.
    assert_eq!(des::ops::check_nonblocking(a), None);
    assert!(a.states().all(|s| !a.transitions(s).is_empty()));
    let component = |name: &str| all.iter().position(|c| c.name() == name).unwrap();
    for s in a.states() {
        // No collision: no section supervisor ever sees both trains in
        // its section.
        for (i, c) in all.iter().enumerate() {
            if c.name().starts_with("sup_section_") {
                let state = c.state_name(product.component_state(s, i)).into_owned();
                let occupied = state
                    .split(',')
                    .filter(|p| p.contains(":in") || p.contains(":entering"))
                    .count();
                assert!(occupied <= 1, "{}: {state}", c.name());
            }
        }
        // Routes: train 1 never reaches crane 3's siding, train 2 never
        // crane 2's.
        let at = |train: &str| {
            let i = component(&format!("order_{train}"));
            all[i]
                .state_name(product.component_state(s, i))
                .into_owned()
        };
        assert!(!["at21", "at22"].contains(&at("t1").as_str()));
        assert!(!["at6", "at7"].contains(&at("t2").as_str()));
    }
    // Every crane loads, and each train meets the cranes of its route.
    let events: std::collections::BTreeSet<&str> = a
        .iter_transitions()
        .map(|(_, e, _)| a.alphabet().name(e))
        .collect();
    for e in [
        "st_ld1", "st_ld2", "st_ld3", "t1_at13", "t2_at13", "t1_at6", "t2_at21",
    ] {
        assert!(events.contains(e), "{e} never happens");
    }
}
