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
