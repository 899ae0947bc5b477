//! Compose + supcon on the benchmark models (`models/bench`).
//!
//! `cargo bench -p des` measures our time alone; `cargo xtask
//! bench-faudes` puts it next to libFAUDES in one run.

use criterion::{criterion_group, criterion_main, Criterion};
use des::formats::read_automaton;
use des::ops::{self, ComposeOptions, Composition};
use des::Automaton;
use std::path::Path;
use std::time::Duration;

fn load(set: &str, keep: impl Fn(&str) -> bool) -> Vec<Automaton> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models/bench")
        .join(set);
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .expect("benchmark models")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.file_stem().and_then(|s| s.to_str()).is_some_and(&keep))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| read_automaton(p).expect("model"))
        .collect()
}

fn compose(parts: &[Automaton]) -> Automaton {
    let refs: Vec<&Automaton> = parts.iter().collect();
    let options = ComposeOptions {
        name_states: false,
        ..ComposeOptions::default()
    };
    ops::compose(&refs, Composition::Sync, options)
        .expect("composable")
        .automaton
}

fn compose_and_supcon(plants: &[Automaton], specs: &[Automaton]) -> Automaton {
    let plant = compose(plants);
    let spec = compose(specs);
    let options = ComposeOptions {
        name_states: false,
        ..ComposeOptions::default()
    };
    ops::supcon_with(&plant, &spec, options).expect("supcon")
}

fn is_spec(name: &str) -> bool {
    name.ends_with("SPEC") || name.ends_with("SP")
}

fn synthesis(c: &mut Criterion) {
    let mut group = c.benchmark_group("compose+supcon");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    for set in ["agv", "phil8", "phil10"] {
        let plants = load(set, |s| !is_spec(s));
        let specs = load(set, is_spec);
        group.bench_function(set, |b| b.iter(|| compose_and_supcon(&plants, &specs)));
    }
    group.finish();

    let mut group = c.benchmark_group("phases");
    group.sample_size(10);
    let plants = load("phil10", |s| !is_spec(s));
    group.bench_function("phil10 compose", |b| b.iter(|| compose(&plants)));
    let plant = compose(&plants);
    let everything = compose(&[]);
    group.bench_function("phil10 supcon", |b| {
        b.iter(|| ops::supcon(&plant, &everything).expect("supcon"))
    });
    let sup = ops::supcon(&plant, &everything).expect("supcon");
    group.bench_function("phil10 minstate", |b| b.iter(|| ops::minstate(&sup)));
    group.finish();
}

criterion_group!(benches, synthesis);
criterion_main!(benches);
