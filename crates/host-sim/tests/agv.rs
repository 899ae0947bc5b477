//! The AGV benchmark with its supervisor reduced (`agv_reduced.plc.toml`)
//! and localized (`agv_localized.plc.toml`): the same signals as
//! `agv.plc.toml`, and scan by scan the same events, outputs and faults
//! under any inputs, noise included.

use codegen::backend::Backend;
use host_sim::random_inputs::guided_inputs;
use host_sim::Sim;
use plc_project::{Project, SupervisorSource};
use std::path::{Path, PathBuf};

fn model(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(file)
}

fn load(file: &str) -> Project {
    plc_project::load(&model(file)).unwrap()
}

/// The project's signals and events without their lines.
fn signals(mut p: Project) -> Project {
    p.supervisors.clear();
    p.name.clear();
    p.path = PathBuf::new();
    p.warnings.clear();
    p.files.clear();
    p.inputs.iter_mut().for_each(|i| i.line = 0);
    p.outputs.iter_mut().for_each(|o| o.line = 0);
    p.events.iter_mut().for_each(|e| e.line = 0);
    if let Some(b) = &mut p.board {
        b.line = 0;
        b.inputs.iter_mut().flatten().for_each(|pin| pin.line = 0);
        b.outputs.iter_mut().flatten().for_each(|pin| pin.line = 0);
    }
    p
}

#[test]
fn the_variants_declare_the_agvs_signals() {
    let agv = signals(load("agv.plc.toml"));
    for file in ["agv_reduced.plc.toml", "agv_localized.plc.toml"] {
        assert_eq!(signals(load(file)), agv, "{file}");
    }
}

#[test]
fn reduced_and_localized_run_beside_the_plant_components() {
    let names =
        |p: &Project| -> Vec<String> { p.supervisors.iter().map(|s| s.name.clone()).collect() };
    let reduced = load("agv_reduced.plc.toml");
    assert_eq!(
        names(&reduced),
        ["agv.AGV1", "agv.AGV2", "agv.AGV3", "agv.AGV4", "agv.AGV5", "agv"]
    );
    assert!(matches!(
        reduced.supervisors[0].source,
        SupervisorSource::Plant { .. }
    ));
    assert!(reduced.supervisors[5].automaton.num_states() <= 491);
    let localized = load("agv_localized.plc.toml");
    let controllers: Vec<&str> = localized.supervisors[5..]
        .iter()
        .map(|s| match &s.source {
            SupervisorSource::Synthesized { local: Some(e), .. } => e.as_str(),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        controllers,
        ["e11", "e13", "e21", "e23", "e31", "e33", "e41", "e43", "e51", "e53"]
    );
    let states: usize = localized.supervisors[5..]
        .iter()
        .map(|s| s.automaton.num_states())
        .sum();
    assert!(states < 4406 / 10, "{states}");
}

#[test]
fn every_variant_gives_the_same_events_outputs_and_faults_scan_by_scan() {
    let agv = load("agv.plc.toml");
    // Noise now and then: events the supervisor does not expect, which
    // every variant must ignore alike.
    let rows = guided_inputs(&agv, 20_000, 7, 10).unwrap();
    let mut sims: Vec<Sim> = [
        "agv.plc.toml",
        "agv_reduced.plc.toml",
        "agv_localized.plc.toml",
    ]
    .iter()
    .map(|f| {
        let mut sim = Sim::load(&model(f), Backend::Table).unwrap();
        sim.retain_trace(false);
        sim
    })
    .collect();
    let (mut executed, mut ignored) = (0, 0);
    for row in &rows {
        let rows: Vec<_> = sims
            .iter_mut()
            .map(|s| s.scan_with(row.time_ms, &row.values).unwrap().clone())
            .collect();
        for r in &rows[1..] {
            assert_eq!(
                (&r.events, &r.ignored, &r.outputs, &r.fault),
                (
                    &rows[0].events,
                    &rows[0].ignored,
                    &rows[0].outputs,
                    &rows[0].fault
                ),
                "scan {}",
                r.scan
            );
        }
        executed += rows[0].events.len();
        ignored += rows[0].ignored.len();
    }
    assert!(executed > 2_000, "{executed} events executed");
    assert!(ignored > 100, "{ignored} events ignored");
}
