//! Supervisor reduction on the benchmark models: the reduced supervisor
//! gives the plant the closed and marked languages of the original.

use des::formats::read_automaton;
use des::ops::{self, ComposeOptions, Composition};
use des::Automaton;
use std::path::{Path, PathBuf};
use std::time::Instant;

fn bench_dir(set: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models/bench")
        .join(set)
}

fn compose(set: &str, names: &str) -> Automaton {
    let parts: Vec<Automaton> = names
        .split_whitespace()
        .map(|n| read_automaton(&bench_dir(set).join(format!("{n}.gen"))).unwrap())
        .collect();
    let refs: Vec<&Automaton> = parts.iter().collect();
    let options = ComposeOptions {
        name_states: false,
        ..ComposeOptions::default()
    };
    ops::compose(&refs, Composition::Sync, options)
        .unwrap()
        .automaton
}

fn closed_loop(g: &Automaton, s: &Automaton) -> Automaton {
    ops::sync(&[g, s]).unwrap()
}

/// Reduces supcon(plant, spec) and checks the closed loop; returns the
/// sizes before and after.
fn reduced(set: &str, plants: &str, specs: &str) -> (usize, usize) {
    let g = compose(set, plants);
    let e = compose(set, specs);
    let s = ops::supcon(&g, &e).unwrap();
    let start = Instant::now();
    let r = ops::reduce(&g, &s, 1 << 24).unwrap();
    let took = start.elapsed();
    let a = &r.automaton;
    eprintln!(
        "{set}: {} states → {} ({} transitions) in {took:?}",
        s.num_states(),
        a.num_states(),
        a.num_transitions()
    );
    assert_eq!(
        ops::language_difference(&closed_loop(&g, &s), &closed_loop(&g, a)),
        None,
        "{set}: the closed loop changed"
    );
    (s.num_states(), a.num_states())
}

#[test]
fn small_factory() {
    let (before, after) = reduced("smallfactory", "MACH1 MACH2", "BUFSPEC BRSPEC");
    assert_eq!(before, 12);
    assert!(after < before, "{after}");
}

#[test]
fn transfer_line() {
    let (before, after) = reduced("transferline", "M1 M2 TU", "B1SP B2SP");
    assert_eq!(before, 28);
    assert!(after < before, "{after}");
}

#[test]
fn agv() {
    let (before, after) = reduced(
        "agv",
        "AGV1 AGV2 AGV3 AGV4 AGV5",
        "Z1SPEC Z2SPEC Z3SPEC Z4SPEC WS1SPEC WS2SPEC WS3SPEC IPSSPEC",
    );
    assert_eq!(before, 4406);
    assert!(after <= 491, "{after}");
}

/// Localizes supcon(plant, spec) and checks the closed loop; returns the
/// states of the largest local controller and their sum.
fn localized(set: &str, plants: &str, specs: &str) -> (usize, usize) {
    let g = compose(set, plants);
    let e = compose(set, specs);
    let s = ops::supcon(&g, &e).unwrap();
    let start = Instant::now();
    let l = ops::localize(&g, &s, 1 << 24).unwrap();
    let took = start.elapsed();
    for (event, a) in &l.controllers {
        eprintln!(
            "{set}: {event}: {} states, {} events, {} transitions",
            a.num_states(),
            a.alphabet().len(),
            a.num_transitions()
        );
    }
    ops::check_localized(&g, &s, &l, ComposeOptions::default()).unwrap();
    let sizes: Vec<usize> = l.controllers.iter().map(|(_, a)| a.num_states()).collect();
    eprintln!("{set}: localized in {took:?}: {sizes:?}");
    (sizes.iter().copied().max().unwrap_or(0), sizes.iter().sum())
}

#[test]
fn small_factory_localized() {
    let (largest, _) = localized("smallfactory", "MACH1 MACH2", "BUFSPEC BRSPEC");
    assert!(largest <= 3, "{largest}");
}

#[test]
fn agv_localized() {
    let (largest, total) = localized(
        "agv",
        "AGV1 AGV2 AGV3 AGV4 AGV5",
        "Z1SPEC Z2SPEC Z3SPEC Z4SPEC WS1SPEC WS2SPEC WS3SPEC IPSSPEC",
    );
    assert!(largest < 4406 / 10, "{largest}");
    assert!(total < 4406, "{total}");
}
