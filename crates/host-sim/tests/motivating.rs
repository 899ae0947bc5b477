//! The motivating example of the ladder-logic thesis (docs/seeds.md A, its
//! Table 3.1): every transition of the table exercised, the choice among
//! controllable events (declaration order, request input), the priority of
//! uncontrollable events, fault on an unexpected event and reset.

mod common;
use common::{events, Run};

/// Runs 0 → 1 → 2 → 3 (`a`, `b` and the command chosen in state 2).
fn to_state_3(run: &mut Run) -> Vec<String> {
    run.scan();
    assert_eq!(events(&run.step("x_a", true)), ["a"]);
    assert_eq!(run.state("motivating"), "1");
    let row = run.step("x_b", true);
    assert_eq!(run.state("motivating"), "3");
    row.events
}

#[test]
fn state_2_picks_c_hi_without_a_request() {
    let mut run = Run::load("motivating.plc.toml");
    // b is uncontrollable and runs first; then one command: c_lo is first
    // in order but not requested, so c_hi.
    assert_eq!(to_state_3(&mut run), ["b", "c_hi"]);
    assert!(run.out("x_c_hi") && !run.out("x_c_lo"));
}

#[test]
fn state_2_picks_c_lo_while_requested() {
    let mut run = Run::load("motivating.plc.toml");
    run.set("req_c_lo", true);
    assert_eq!(to_state_3(&mut run), ["b", "c_lo"]);
    assert!(run.out("x_c_lo") && !run.out("x_c_hi"));
}

#[test]
fn e_in_the_same_scan_wins_over_d_on() {
    let mut run = Run::load("motivating.plc.toml");
    to_state_3(&mut run);
    // State 3 allows e (plant) and d_on (command): e is seen first.
    let row = run.step("x_e", true);
    assert_eq!(events(&row), ["e", "c_cl"], "3 -e-> 9 -c_cl-> 0");
    assert_eq!(run.state("motivating"), "0");
    assert_eq!(run.on(&row), Vec::<String>::new());
}

#[test]
fn full_cycle_through_every_state() {
    let mut run = Run::load("motivating.plc.toml");
    to_state_3(&mut run);
    // 3 -d_on-> 4
    assert_eq!(events(&run.scan()), ["d_on"]);
    assert!(run.out("x_d_on") && run.out("x_c_hi"));
    // 4 -b-> 5 (b needs a new rising edge)
    assert!(run.step("x_b", false).events.is_empty());
    assert_eq!(events(&run.step("x_b", true)), ["b"]);
    assert_eq!(run.state("motivating"), "5");
    // 5 -f-> 6 -c_cl-> 7, then 7 -d_off-> 0: one command per scan
    assert_eq!(events(&run.step("x_f", true)), ["f", "c_cl"]);
    assert_eq!(run.state("motivating"), "7");
    assert!(!run.out("x_c_hi") && run.out("x_d_on"));
    assert_eq!(events(&run.scan()), ["d_off"]);
    assert_eq!(run.state("motivating"), "0");
    // Second round takes the other branch: 4 -f-> 8 -d_off-> 9 -c_cl-> 0.
    for input in ["x_a", "x_b", "x_f"] {
        run.set(input, false);
    }
    run.scan();
    run.step("x_a", true);
    run.step("x_b", true);
    assert_eq!(events(&run.scan()), ["d_on"]);
    assert_eq!(events(&run.step("x_f", true)), ["f", "d_off"]);
    assert_eq!(run.state("motivating"), "9");
    assert_eq!(events(&run.scan()), ["c_cl"]);
    assert_eq!(run.state("motivating"), "0");
    // Nothing left to do: quiet scans.
    assert!(run.scans(20).iter().all(|r| r.events.is_empty()));
}

#[test]
fn unexpected_event_faults_until_reset() {
    let mut run = Run::load("motivating.plc.toml");
    run.scan();
    // b in state 0 is not in Table 3.1.
    let row = run.step("x_b", true);
    assert_eq!(row.fault.as_deref(), Some("Unexpected:b"));
    assert!(row.events.is_empty());
    assert_eq!(row.ignored, ["b"]);
    // Fault mode holds, whatever the inputs do.
    for row in run.scans(5).iter().chain([&run.step("x_a", true)]) {
        assert_eq!(row.fault.as_deref(), Some("Unexpected:b"));
        assert!(row.events.is_empty());
        assert!(row.outputs.iter().all(|&o| !o), "safe image");
    }
    // A rising edge of reset re-initialises; other edges of that scan are dropped.
    let row = run.step("reset", true);
    assert_eq!(row.fault, None);
    assert!(row.events.is_empty());
    assert_eq!(run.state("motivating"), "0");
    // Back in business: a new edge of a is seen.
    run.set("x_a", false);
    run.scan();
    assert_eq!(events(&run.step("x_a", true)), ["a"]);
}
