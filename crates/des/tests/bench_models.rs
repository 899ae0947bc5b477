//! The benchmark models of `models/bench/README.md`: plant sizes and
//! supcon results must match the published (textbook) figures.

use des::formats::read_automaton;
use des::ops::{self, ComposeOptions, Composition};
use des::Automaton;
use std::path::{Path, PathBuf};

fn bench_dir(set: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models/bench")
        .join(set)
}

fn load(set: &str, names: &[String]) -> Vec<Automaton> {
    names
        .iter()
        .map(|n| read_automaton(&bench_dir(set).join(format!("{n}.gen"))).unwrap())
        .collect()
}

fn compose(parts: &[Automaton]) -> Automaton {
    let refs: Vec<&Automaton> = parts.iter().collect();
    let options = ComposeOptions {
        name_states: false,
        ..ComposeOptions::default()
    };
    ops::compose(&refs, Composition::Sync, options)
        .unwrap()
        .automaton
}

fn names(list: &str) -> Vec<String> {
    list.split_whitespace().map(str::to_owned).collect()
}

/// Composes plants and specs, runs supcon, and checks the sizes; the
/// result must also be controllable, nonblocking and trim.
fn row(set: &str, plants: &[String], specs: &[String], plant: (usize, usize), sup: (usize, usize)) {
    let g = compose(&load(set, plants));
    assert_eq!((g.num_states(), g.num_transitions()), plant, "{set}: plant");
    let e = compose(&load(set, specs));
    let s = ops::supcon(&g, &e).unwrap();
    assert_eq!((s.num_states(), s.num_transitions()), sup, "{set}: supcon");
    assert!(ops::is_trim(&s), "{set}: supcon result is trim");
    assert_eq!(ops::check_controllable(&g, &s).unwrap(), None, "{set}");
    assert_eq!(ops::check_nonblocking(&s), None, "{set}");
}

fn philosophers(n: usize) -> Vec<String> {
    (1..=n)
        .flat_map(|i| [format!("P{i}"), format!("F{i}")])
        .collect()
}

#[test]
fn small_factory_is_12_states_24_transitions() {
    row(
        "smallfactory",
        &names("MACH1 MACH2"),
        &names("BUFSPEC BRSPEC"),
        (9, 24),
        (12, 24),
    );
}

#[test]
fn transfer_line_is_28_states_65_transitions() {
    row(
        "transferline",
        &names("M1 M2 TU"),
        &names("B1SP B2SP"),
        (8, 28),
        (28, 65),
    );
}

#[test]
fn agv_is_4406_states_11338_transitions() {
    row(
        "agv",
        &names("AGV1 AGV2 AGV3 AGV4 AGV5"),
        &names("Z1SPEC Z2SPEC Z3SPEC Z4SPEC WS1SPEC WS2SPEC WS3SPEC IPSSPEC"),
        (3072, 15360),
        (4406, 11338),
    );
}

#[test]
fn dining_philosophers_lose_exactly_the_deadlock() {
    for (n, plant, sup) in [
        (5, (243, 945), (241, 935)),
        (8, (6561, 40824), (6559, 40808)),
        (10, (59049, 459270), (59047, 459250)),
    ] {
        row(&format!("phil{n}"), &philosophers(n), &[], plant, sup);
    }
}
