//! The conveyor of the Structured-Text paper (docs/seeds.md E): the belt starts
//! on the rising edge of the light sensor and stops when the 1 s virtual
//! sensor (a timer started by the falling edge) expires; a new part
//! cancels the run-on. The supervisor is synthesised at build time.

mod common;
use common::{events, Run};

/// One idle scan, then a part reaches the sensor: `re_ls` after the
/// 2-scan debounce, and the belt starts in the same scan.
fn part_arrives(run: &mut Run) {
    run.set("ls", true);
    let rows = run.scans(2);
    assert!(rows[0].events.is_empty());
    assert_eq!(events(&rows[1]), ["re_ls", "start"]);
    assert!(run.out("belt"));
}

#[test]
fn belt_runs_until_one_second_after_the_part_has_passed() {
    let mut run = Run::load("conveyor.plc.toml");
    run.scan();
    part_arrives(&mut run);
    assert!(run
        .scans(50)
        .iter()
        .all(|r| r.events.is_empty() && r.outputs == [true]));
    run.set("ls", false);
    let fe = run.until_event("fe_ls", 2);
    assert_eq!(events(&fe), ["fe_ls"]);
    let gone = run.until_event("gone", 200);
    assert_eq!(events(&gone), ["gone", "stop"]);
    assert_eq!(gone.time_ms - fe.time_ms, 1000, "1 s virtual sensor");
    assert!(!run.out("belt"));
    assert_eq!(
        run.state("conveyor"),
        run.trace()[0].state("conveyor").unwrap()
    );
}

#[test]
fn a_new_part_during_the_run_on_keeps_the_belt_running() {
    let mut run = Run::load("conveyor.plc.toml");
    run.scan();
    part_arrives(&mut run);
    run.set("ls", false);
    let first_fe = run.until_event("fe_ls", 2);
    run.scans(50); // half-way through the run-on
    run.set("ls", true);
    assert_eq!(
        events(&run.until_event("re_ls", 2)),
        ["re_ls"],
        "already running"
    );
    // The timer was cancelled: no `gone` while the part is on the sensor.
    assert!(run
        .scans(300)
        .iter()
        .all(|r| r.events.is_empty() && r.outputs == [true]));
    run.set("ls", false);
    let fe = run.until_event("fe_ls", 2);
    let gone = run.until_event("gone", 200);
    assert_eq!(gone.time_ms - fe.time_ms, 1000);
    assert!(gone.time_ms - first_fe.time_ms > 1000);
    assert!(!run.out("belt"));
}

#[test]
fn sensor_noise_never_leaves_the_plant_model() {
    // The plant model covers everything the executor can produce from one
    // debounced sensor and the timer, and supcon made the supervisor
    // controllable for it: no input sequence can raise an unexpected event.
    let mut run = Run::load("conveyor.plc.toml");
    let mut x: u32 = 0x2545_f491;
    let (mut ls, mut glitch, mut running) = (false, false, false);
    for _ in 0..50_000 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        // Mostly long steady levels (parts, gaps beyond the run-on), some
        // one-scan glitches the debounce must swallow.
        if glitch || x % 53 == 0 {
            ls = !ls;
            glitch = false;
        } else if x % 211 == 1 {
            ls = !ls;
            glitch = true;
        }
        let row = run.step("ls", ls);
        assert_eq!(row.fault, None, "scan {}", row.scan);
        for e in &row.events {
            running = match e.as_str() {
                "start" => true,
                "stop" => false,
                _ => running,
            };
        }
        assert_eq!(
            row.outputs[0], running,
            "scan {}: belt follows start/stop",
            row.scan
        );
    }
    let trace = run.trace();
    let count = |e: &str| {
        trace
            .iter()
            .filter(|r| r.events.iter().any(|x| x == e))
            .count()
    };
    assert!(
        count("start") > 10 && count("gone") > 0,
        "the noise drove real cycles"
    );
    assert_eq!(count("start"), count("stop") + usize::from(run.out("belt")));
}
