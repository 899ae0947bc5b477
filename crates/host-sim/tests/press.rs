//! The stamping press of the sequence-control lesson (docs/seeds.md C): the
//! work cycle with its Moore output table, the stop/reset path, the
//! lesson's known weaknesses (auto ignored away from the top; a stuck limit
//! switch deadlocks), its state-7 variant (same code, other model), part
//! sensor debouncing, and fault mode on an unexpected event.

mod common;
use common::{events, Run};

/// Output table of the lesson, states 1..6: auto lamp, part hold, up
/// solenoid, down solenoid.
const TABLE: [(&str, [bool; 4]); 6] = [
    ("1", [false, false, false, false]),
    ("2", [true, false, false, false]),
    ("3", [true, true, false, true]),
    ("4", [true, true, true, false]),
    ("5", [false, false, false, false]),
    ("6", [true, false, false, false]),
];

fn outputs_of(state: &str) -> [bool; 4] {
    TABLE.iter().find(|(s, _)| *s == state).unwrap().1
}

/// Ram at the top, one idle scan, then auto: state 2.
fn armed(file: &str) -> Run {
    let mut run = Run::load(file);
    run.set("top_ls", true);
    run.scan();
    assert_eq!(events(&run.step("auto_pb", true)), ["auto"]);
    run.set("auto_pb", false);
    assert_eq!(run.state("press"), "2");
    run
}

/// Places a part and waits out the 3-scan debounce: state 3.
fn part_in(run: &mut Run) {
    run.set("part", true);
    let rows = run.scans(3);
    assert!(rows[..2].iter().all(|r| r.events.is_empty()));
    assert_eq!(events(&rows[2]), ["part_in"], "debounced over 3 scans");
}

#[test]
fn work_cycle_follows_the_output_table() {
    let mut run = armed("press.plc.toml");
    let mut seen = vec![run.state("press")];
    part_in(&mut run);
    seen.push(run.state("press"));
    run.step("top_ls", false); // the ram leaves the top: no event bound
    run.step("bottom_ls", true);
    seen.push(run.state("press"));
    run.step("bottom_ls", false);
    run.step("top_ls", true);
    seen.push(run.state("press"));
    run.set("part", false);
    run.until_event("part_out", 3);
    seen.push(run.state("press"));
    assert_eq!(seen, ["2", "3", "4", "6", "2"]);
    // Every row of the trace shows the outputs of its state.
    for row in run.trace() {
        assert_eq!(
            row.outputs,
            outputs_of(row.state("press").unwrap()),
            "scan {}",
            row.scan
        );
    }
}

#[test]
fn stop_while_going_down_then_reset() {
    let mut run = armed("press.plc.toml");
    part_in(&mut run);
    run.step("top_ls", false);
    assert_eq!(events(&run.step("stop_pb", true)), ["stop"]);
    assert_eq!(run.state("press"), "5");
    assert_eq!(run.scan().outputs, outputs_of("5"), "everything off");
    assert_eq!(events(&run.step("reset_pb", true)), ["reset"]);
    assert_eq!(run.state("press"), "1");
}

#[test]
fn auto_is_ignored_unless_the_ram_is_at_the_top() {
    // The lesson's weakness: after stop and reset the ram is half-way, and
    // A needs the top limit switch, so the press waits.
    let mut run = armed("press.plc.toml");
    part_in(&mut run);
    run.step("top_ls", false);
    run.step("stop_pb", true);
    run.step("reset_pb", true);
    run.set("auto_pb", false);
    run.scan();
    let row = run.step("auto_pb", true);
    assert!(row.events.is_empty(), "auto needs top_ls");
    assert!(run.scans(100).iter().all(|r| r.events.is_empty()));
    assert_eq!(run.state("press"), "1");
}

#[test]
fn state_7_returns_the_ram_to_the_top() {
    // Same project, other model (press7): after reset the ram goes up
    // first (up solenoid on in state 7), then auto works again.
    let mut run = armed("press7.plc.toml");
    part_in(&mut run);
    run.step("top_ls", false);
    run.step("stop_pb", true);
    run.step("reset_pb", true);
    assert_eq!(run.state("press"), "7");
    assert!(run.out("up_sol") && !run.out("down_sol"));
    assert_eq!(events(&run.step("top_ls", true)), ["at_top"]);
    assert_eq!(run.state("press"), "1");
    assert!(!run.out("up_sol"));
    run.set("auto_pb", false);
    run.scan();
    assert_eq!(events(&run.step("auto_pb", true)), ["auto"]);
}

#[test]
fn a_stuck_bottom_limit_switch_deadlocks_with_the_ram_driven_down() {
    let mut run = armed("press.plc.toml");
    part_in(&mut run);
    run.step("top_ls", false);
    let rows = run.scans(1000);
    assert!(rows
        .iter()
        .all(|r| r.events.is_empty() && r.fault.is_none()));
    assert_eq!(run.state("press"), "3");
    assert!(run.out("down_sol"), "nothing in the model notices");
}

#[test]
fn part_sensor_bounce_shorter_than_the_filter_is_ignored() {
    let mut run = armed("press.plc.toml");
    for _ in 0..10 {
        run.step("part", true);
        run.step("part", true);
        run.step("part", false);
    }
    assert!(run
        .trace()
        .iter()
        .all(|r| !r.events.contains(&"part_in".to_owned())));
    assert_eq!(run.state("press"), "2");
}

#[test]
fn unexpected_limit_switch_faults_with_safe_outputs_until_reset() {
    let mut run = armed("press.plc.toml");
    // The ram cannot reach the bottom while the press waits for a part.
    let row = run.step("bottom_ls", true);
    assert_eq!(row.fault.as_deref(), Some("Unexpected:at_bottom"));
    assert_eq!(row.ignored, ["at_bottom"]);
    assert!(row.outputs.iter().all(|&o| !o));
    for row in run.scans(10) {
        assert_eq!(row.fault.as_deref(), Some("Unexpected:at_bottom"));
    }
    run.set("bottom_ls", false);
    let row = run.step("reset_pb", true);
    assert_eq!(row.fault, None);
    assert!(row.events.is_empty(), "the reset edge only re-initialises");
    assert_eq!(run.state("press"), "1");
    run.set("reset_pb", false);
    run.scan();
    assert_eq!(events(&run.step("auto_pb", true)), ["auto"]);
}
