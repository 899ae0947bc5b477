//! Crane 1 of Leduc and Wonham's testbed (docs/seeds.md B) with a
//! collision-protection section: two modular supervisors run side by side
//! and share `run_t1` / `run_t2`, so a train leaves the crane only when
//! both allow it. The paper's enable outputs are Moore outputs.

mod common;
use common::{events, Run};

/// A train reaches sensor 13 (2-scan debounce) and is held for loading.
fn arrives(run: &mut Run, sensor: &str, event: &str) {
    run.set(sensor, true);
    assert_eq!(events(&run.until_event(event, 2)), [event]);
}

/// Crane 1 loads the train at the sensor and releases it; the events of
/// the releasing scan.
fn load(run: &mut Run) -> Vec<String> {
    assert_eq!(events(&run.step("ld1_ready", true)), ["st_ld1"]);
    run.set("ld1_ready", false);
    assert!(run.out("crane1_load"));
    let row = run.step("ld1_done", true);
    assert_eq!(row.events[0], "f_ld1");
    run.set("ld1_done", false);
    assert!(!run.out("crane1_load"));
    assert_eq!(run.state("sup_crane1"), "idle");
    row.events
}

/// sup_crane1 and sup_section as written in the model files, for an
/// independent check: the successor, `None` where undefined.
fn model_step(crane: &str, section: &str, event: &str) -> Option<(String, String)> {
    let crane_next = match (crane, event) {
        ("idle", "t1_at13") => "train1",
        ("idle", "t2_at13") => "train2",
        ("train1" | "train2", "f_ld1") => "idle",
        ("train1" | "train2", "st_ld1") => crane,
        ("idle" | "train2", "run_t1") | ("idle" | "train1", "run_t2") => crane,
        (_, "t1_at14" | "t2_at14") => crane,
        _ => return None,
    };
    let section_next = match (section, event) {
        ("free", "run_t1") => "t1_in",
        ("free", "run_t2") => "t2_in",
        ("t1_in", "t1_at14") | ("t2_in", "t2_at14") => "free",
        (_, "t1_at13" | "t2_at13" | "f_ld1" | "st_ld1") => section,
        _ => return None,
    };
    Some((crane_next.to_owned(), section_next.to_owned()))
}

#[test]
fn enables_follow_the_papers_output_map() {
    let mut run = Run::load("crane.plc.toml");
    let row = run.scan();
    assert_eq!(
        run.on(&row),
        ["t1_enable", "t2_enable"],
        "φ1 = ¬qa0, φ2 = ¬qa1 at 00"
    );
    arrives(&mut run, "s13_t1", "t1_at13");
    assert_eq!(run.state("sup_crane1"), "train1");
    assert!(
        !run.out("t1_enable") && run.out("t2_enable"),
        "train 1 held"
    );
    load(&mut run);
    assert!(run.out("t1_enable") && run.out("t2_enable"));
    run.step("s13_t1", false);
    arrives(&mut run, "s13_t2", "t2_at13");
    assert!(
        run.out("t1_enable") && !run.out("t2_enable"),
        "train 2 held"
    );
}

#[test]
fn a_train_departs_only_when_both_supervisors_allow_it() {
    let mut run = Run::load("crane.plc.toml");
    run.scan();
    arrives(&mut run, "s13_t1", "t1_at13");
    // The train asks to leave while being loaded: the crane says no.
    run.set("t1_depart", true);
    assert!(run
        .scans(5)
        .iter()
        .all(|r| !r.events.contains(&"run_t1".to_owned())));
    // Released by the crane into a free section: goes in the same scan.
    assert_eq!(load(&mut run), ["f_ld1", "run_t1"]);
    assert_eq!(run.state("sup_section"), "t1_in");
    assert!(run.out("section_busy"));
    assert!(
        run.scans(5).iter().all(|r| r.events.is_empty()),
        "section occupied"
    );
    run.set("t1_depart", false);
    run.step("s13_t1", false);

    // Train 2 is loaded and wants to follow: the section holds it back.
    arrives(&mut run, "s13_t2", "t2_at13");
    load(&mut run);
    run.set("t2_depart", true);
    assert!(run.scans(20).iter().all(|r| r.events.is_empty()));
    assert_eq!(run.state("sup_crane1"), "idle", "the crane would let it go");
    // Train 1 leaves the section at sensor 14; train 2 goes in the same scan.
    run.set("s14_t1", true);
    assert_eq!(
        events(&run.until_event("t1_at14", 2)),
        ["t1_at14", "run_t2"]
    );
    assert_eq!(run.state("sup_section"), "t2_in");
}

#[test]
fn every_executed_command_is_allowed_by_both_supervisors() {
    // Control equivalence with the meet, checked on a long random run
    // against the model files' transitions, event by event within a scan.
    let mut run = Run::load("crane.plc.toml");
    let inputs = [
        "s13_t1",
        "s13_t2",
        "s14_t1",
        "s14_t2",
        "ld1_done",
        "ld1_ready",
        "t1_depart",
        "t2_depart",
        "reset",
    ];
    let mut levels = [false; 9];
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut state = (run.state("sup_crane1"), run.state("sup_section"));
    let mut commands = 0;
    for _ in 0..20_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let i = (x % 64) as usize;
        if i < inputs.len() {
            levels[i] = !levels[i];
            run.set(inputs[i], levels[i]);
        }
        let row = run.scan();
        if row.fault.is_some() || i == 8 {
            // Fault mode or the reset input moved: resynchronise.
            state = (run.state("sup_crane1"), run.state("sup_section"));
            continue;
        }
        for e in &row.events {
            state = model_step(&state.0, &state.1, e)
                .unwrap_or_else(|| panic!("scan {}: {e} not allowed in {state:?}", row.scan));
            commands += usize::from(e.starts_with("run_") || e == "st_ld1");
        }
        assert_eq!(state, (run.state("sup_crane1"), run.state("sup_section")));
    }
    assert!(
        commands > 50,
        "the random run exercised the commands ({commands})"
    );
}

#[test]
fn two_trains_at_one_crane_is_a_fault_until_reset() {
    let mut run = Run::load("crane.plc.toml");
    run.scan();
    arrives(&mut run, "s13_t1", "t1_at13");
    run.set("s13_t2", true);
    let rows = run.scans(2);
    assert_eq!(rows[1].fault.as_deref(), Some("Unexpected:t2_at13"));
    assert_eq!(run.on(&rows[1]), Vec::<String>::new(), "safe image");
    assert_eq!(run.step("reset", true).fault, None);
    assert_eq!(run.state("sup_crane1"), "idle");
    assert_eq!(run.state("sup_section"), "free");
}

#[test]
fn a_train_at_sensor_14_of_an_empty_section_is_unexpected() {
    let mut run = Run::load("crane.plc.toml");
    run.scan();
    run.set("s14_t2", true);
    let rows = run.scans(2);
    assert_eq!(rows[1].fault.as_deref(), Some("Unexpected:t2_at14"));
    assert_eq!(
        rows[1].states[1],
        ("sup_section".to_owned(), "free".to_owned())
    );
}
