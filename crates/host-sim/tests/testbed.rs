//! The manufacturing testbed of seed B in closed loop (issue 24): the PLC
//! project `models/testbed/testbed.plc.toml` (the 29 modular supervisors)
//! against the plant simulation of `host_sim::testbed`, every scan checked
//! by its invariants: no collision, no switch thrown under a train, no
//! train over points set against it, routes kept, cranes loading only
//! their train, no train stuck while the controller runs.

use codegen::backend::Backend;
use host_sim::testbed::{self, Rule, TestbedRun};
use host_sim::Sim;
use plc_project::Project;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn project_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/testbed/testbed.plc.toml")
}

fn project() -> &'static Project {
    static PROJECT: OnceLock<Project> = OnceLock::new();
    PROJECT.get_or_init(|| plc_project::load(&project_path()).unwrap_or_else(|e| panic!("{e}")))
}

/// Runs scenario `name` with `project`.
fn run_on(project: &Project, name: &str) -> TestbedRun {
    let mut sim = Sim::new(project.clone(), Backend::Table).unwrap();
    testbed::run_named(&mut sim, name).unwrap().unwrap()
}

/// Runs scenario `name`, asserting that no invariant broke.
fn run(name: &str) -> TestbedRun {
    let run = run_on(project(), name);
    assert!(
        run.violations.is_empty(),
        "{name}: {} violations, the first: {:?}",
        run.violations.len(),
        &run.violations[..run.violations.len().min(5)]
    );
    println!(
        "{name}: {} scans, {} events, laps {}/{}, fault {:?}",
        run.scans,
        run.events.len(),
        run.laps(0),
        run.laps(1),
        run.fault
    );
    run
}

/// Seconds from each arrival of train `t` (1 or 2) at `sensor` to its
/// next `run_tI`.
fn waits_at(run: &TestbedRun, t: u8, sensor: u8) -> Vec<u64> {
    let (at, go) = (format!("t{t}_at{sensor}"), format!("run_t{t}"));
    run.events
        .iter()
        .enumerate()
        .filter(|(_, (_, e))| *e == at)
        .filter_map(|(i, (t0, _))| {
            run.events[i..]
                .iter()
                .find(|(_, e)| *e == go)
                .map(|(t1, _)| t1 - t0)
        })
        .collect()
}

#[test]
fn both_trains_lap_their_routes_and_every_crane_loads_its_trains() {
    let run = run("laps");
    assert!(run.fault.is_none(), "{:?}", run.fault);
    assert!(run.laps(0) >= 3 && run.laps(1) >= 3, "{:?}", run.trains);
    // Train 1 loaded by cranes 1 and 2, train 2 by cranes 1 and 3, every
    // lap; never by the other crane.
    for (crane, train, on_route) in [
        (1, 0, true),
        (1, 1, true),
        (2, 0, true),
        (2, 1, false),
        (3, 0, false),
        (3, 1, true),
    ] {
        let loads = run.loads(crane, train);
        if on_route {
            assert!(
                loads >= run.laps(train),
                "crane {crane}, train {train}: {loads}"
            );
        } else {
            assert_eq!(loads, 0, "crane {crane}, train {train}");
        }
    }
    // Every request served by its switch command and no command unasked;
    // every switch set diverging, and straight where a route bypasses
    // (cranes 2 and 3: both trains take crane 1's siding).
    for w in 1..=6 {
        for x in ['s', 'd'] {
            let cmd = format!("sw{w}_{x}");
            let asked: usize = (1..=2)
                .map(|t| run.count(&format!("t{t}_req_sw{w}_{x}")))
                .sum();
            assert_eq!(run.count(&cmd), asked, "{cmd}");
        }
        assert!(run.count(&format!("sw{w}_d")) > 0, "switch {w}");
        if w >= 3 {
            assert!(run.count(&format!("sw{w}_s")) > 0, "switch {w}");
        }
    }

    // The run's inputs replayed open loop give the same events: the
    // scenario of the QEMU harness (`cargo xtask qemu testbed` records it
    // through `host-sim testbed laps --inputs-csv`).
    let csv = run.inputs_csv(project()).unwrap();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("testbed-laps.inputs.csv");
    std::fs::write(&path, &csv).unwrap();
    let rows = host_sim::inputs::parse(&csv, &path, project()).unwrap();
    assert_eq!(rows.len() as u64, run.scans);
    let mut sim = Sim::new(project().clone(), Backend::Table).unwrap();
    sim.retain_trace(false);
    let mut events = Vec::new();
    for r in &rows {
        let row = sim.scan_with(r.time_ms, &r.values).unwrap();
        events.extend(row.events.iter().map(|e| (r.time_ms, e.clone())));
    }
    assert_eq!(events, run.events);
    print!("{}", &run.timeline()[..2000]);
}

#[test]
fn slow_cranes_hold_trains_and_the_other_waits_before_the_section() {
    let run = run("crane-cycles");
    assert!(run.fault.is_none(), "{:?}", run.fault);
    assert!(run.laps(0) >= 2 && run.laps(1) >= 2, "{:?}", run.trains);
    let params = testbed::scenarios::named("crane-cycles").unwrap().params;
    // Each train is held at crane 1's sensor for the whole load.
    for t in [1, 2] {
        let waits = waits_at(&run, t, 13);
        assert!(waits.len() >= 2, "train {t}: {waits:?}");
        assert!(waits.iter().all(|&w| w >= params.load_ms[0]), "{waits:?}");
    }
    // And some train waits at the approach sensor 11 while the other
    // occupies the siding of crane 1: the collision supervisor at work.
    let held: Vec<u64> = [1, 2].iter().flat_map(|&t| waits_at(&run, t, 11)).collect();
    assert!(held.iter().any(|&w| w > 1_000), "{held:?}");
}

/// The outputs of the last scan are at their safe levels.
fn assert_safe(run: &TestbedRun, project: &Project) {
    let io = testbed::TestbedIo::new(project).unwrap();
    let safe: Vec<bool> = project.outputs.iter().map(|o| o.safe).collect();
    assert_eq!(run.last_commands, io.read_outputs(&safe));
}

/// A sensor fault: the controller enters fault mode on an unexpected
/// sensor event after `from_ms`, nothing executes after it, the outputs
/// are safe and both trains stand.
fn faults_safely(name: &str, from_ms: u64, event: &str) {
    let run = run(name);
    let (at, cause) = run.fault.clone().expect("a fault");
    assert!(at >= from_ms, "{at}");
    assert_eq!(cause, format!("Unexpected:{event}"));
    assert!(run.events.iter().all(|(t, _)| *t <= at), "{:?}", run.events);
    assert_safe(&run, project());
    for t in &run.trains {
        assert!(
            matches!(t.place, testbed::plant::Place::At { .. }) || t.still_since_ms <= at + 10,
            "{t:?}"
        );
    }
    assert!(run.events.len() > 20, "the run got going first");
    println!("{}", run.timeline().lines().last().unwrap());
}

#[test]
fn a_sensor_reporting_the_wrong_train_ends_in_the_safe_state() {
    faults_safely("wrong-train", 15_000, "t1_at9");
}

#[test]
fn a_stuck_sensor_ends_in_the_safe_state() {
    faults_safely("stuck-sensor", 10_000, "t1_at20");
}

#[test]
fn without_the_collision_supervisors_the_checker_sees_trains_collide() {
    // The same project without its 14 sup_section_* entries: the
    // invariants must catch what they no longer prevent.
    let text = std::fs::read_to_string(project_path()).unwrap();
    let dir = project_path().parent().unwrap().to_path_buf();
    let kept: Vec<&str> = text
        .split("\n[[supervisor]]\n")
        .filter(|block| !block.contains("sup/sup_section_"))
        .collect();
    let variant = kept
        .join("\n[[supervisor]]\n")
        .replace("file = \"", &format!("file = \"{}/", dir.display()));
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("no_sections.plc.toml");
    std::fs::write(&path, variant).unwrap();
    let variant = plc_project::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(variant.supervisors.len(), project().supervisors.len() - 14);
    let run = run_on(&variant, "crane-cycles");
    assert!(
        run.violations
            .iter()
            .any(|v| matches!(v.rule, Rule::Collision(_))),
        "{:?}",
        run.violations
    );
}
