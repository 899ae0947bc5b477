//! Conformance of the generated programs with the scan-cycle semantics.
//!
//! # What is tested
//!
//! For random valid projects and random input sequences, three
//! interpreters run side by side, scan by scan:
//!
//! - the **table backend** ([`TableImage`]) in the executor's [`Controller`],
//! - the **logic backend** ([`LogicImage`], minimised CMSSM covers) in the
//!   same controller,
//! - a **reference interpreter** ([`Reference`]) kept here, in test code.
//!
//! Every scan record must agree field by field (scan number, time,
//! executed events in order, unexpected events, state vector, output
//! image, fault cause), and so must the count of ignored events at the
//! end. Independently of all three interpreters, every scan is also checked
//! for **control equivalence** against the source automata
//! ([`check_control`]): replaying the executed events from the pre-scan
//! state vector with [`des::Automaton::successor`] must find every event defined
//! in every supervisor that has it (so no executed controllable event was
//! disabled) and must land on the recorded state vector (no supervisor
//! moves except along a defined transition, or back to its initial state in
//! a reset scan).
//!
//! # How the reference follows docs/semantics.md
//!
//! The reference is written from `docs/semantics.md` alone,
//! with plain `Vec`s and one hash map of transitions per supervisor, and
//! works on the [`Project`] model directly (never on the executor's
//! `Config`). One method per numbered rule of "One scan":
//!
//! 1. [`Reference::sample`]: debounce (`d > 1` consecutive differing scans,
//!    this one included), edges between F\[k-1\] and F\[k\]; scan 0 has no
//!    edges.
//! 2. [`Reference::fault_mode`]: in fault mode only a rising edge of the
//!    `reset` input does anything (re-initialise, fault cause cleared in
//!    that very record); otherwise the safe image.
//! 3. [`Reference::expire_timers`]: wrap-safe `deadline <= t`; expiry stops
//!    the timer; `start` sets `deadline = t + preset`.
//! 4. [`Reference::uncontrollable_phase`]: occurred events (edges of the OR
//!    of the bound inputs, expiries, with `when`/`unless` on F\[k\]) in
//!    declaration order; feasible ones execute (events in no alphabet are
//!    always feasible); an unexpected one faults (its actions never apply,
//!    events before it stay executed) or is counted and traced under
//!    `ignore`.
//! 5. [`Reference::controllable_phase`]: up to `max_commands_per_scan`
//!    times (0: no limit) the first controllable event in declaration order
//!    that is feasible, not yet executed in this scan, and whose `request`
//!    input is 1 in F\[k\].
//! 6. [`Reference::output_image`]: latched action-driven levels, Moore
//!    outputs as the OR over their state map, the safe image in fault mode.
//! 7. [`Record`]: the trace record.
//!
//! Where docs/semantics.md is silent the reference makes one choice, stated
//! here: the filtered value of a debounced input at scan 0 is its raw
//! sample (the filter has no history yet; F\[-1\] = F\[0\] then makes scan 0
//! edge-free, as rule 1 requires).
//!
//! The reference itself is pinned by two hand-computed traces
//! ([`reference_follows_a_hand_computed_trace`],
//! [`reference_runs_commands_of_modular_supervisors`]) and by a time-shift
//! test across the u32 wrap-around
//! ([`reference_trace_is_invariant_under_clock_wrap`]); the control check
//! by [`control_check_rejects_what_the_supervisors_forbid`].
//!
//! # Random projects and runs
//!
//! A narrow project ([`NARROW`]) has 2–5 inputs (debounce 0–3, usually
//! one of them the `reset` input), 0–3 timers (presets a multiple of the
//! scan period or any 1–80 ms), 1–5 outputs (action-driven or Moore), 2–8
//! events (about 40 % controllable, some with a request input; the others
//! bound to the rising or falling edge of the OR of 1–3 inputs or to a
//! timer expiry, some with `when`/`unless`), 0–3 actions per event, 1–4
//! deterministic supervisors with random partial transition functions over
//! random, overlapping alphabets, `max_commands_per_scan` 0–3 and either
//! unexpected-event policy. [`ProjectSpec`] is plain data whose references
//! are [`proptest::sample::Index`]es, resolved modulo the current counts
//! by [`ProjectSpec::build`], so any shrunk value still builds a valid
//! project (the rules of `project::validate`: controllability agrees with
//! the automata, every controllable event is in some alphabet, an output
//! is driven by actions or a state map, never both, no event sets and
//! clears one output, actions are ordered clears, sets, resets, starts,
//! only controllable events have a request input).
//!
//! A run ([`RunSpec`]) is 20–200 scans, one period apart with occasional
//! jitter or jumps, starting near 0 or (one run in four) just before the
//! u32 clock wraps; before each scan usually nothing or one input flips.
//! [`random_runs_exercise_every_rule`] checks that these generators really
//! execute every kind of event, enter and leave fault mode, ignore events
//! and wrap the clock.
//!
//! # Wide projects
//!
//! The executor keeps input images and event sets as 32-bit words and
//! reads a supervisor's enabled events in rows of up to 32 local events;
//! a narrow project fits in one word everywhere. A wide project ([`WIDE`])
//! is built the same way but has 33–70 inputs and 33–70 events, so inputs
//! and events 31, 32 and 33 always exist and every set spans two or three
//! words. Each of its supervisors (1–8 states, about 80 % of the (state,
//! event) pairs defined) has a few picked events, many (usually more than
//! 32, read in two or three slices) or every event; before each scan of
//! its run any of the 70 inputs a wide project can have may flip.
//! [`wide_runs_cross_every_word_boundary`] checks that events, commands
//! and request inputs past the first word are executed and used, that
//! inputs past the first word alone make edges, that supervisors move on
//! local events past the first slice of their rows, and that these runs
//! still reach every rule.
//!
//! A keyed wide project ([`keyed_wide_supervisor`]) has supervisors of
//! 24–40 states whose rows of defined events repeat (1–3 patterns over
//! many or every event): the table backend stores them keyed, a
//! dictionary of rows packed `m` bits apart for `m > 32` local events.
//! [`keyed_wide_cases_store_keyed_tables_and_move_past_the_first_word`]
//! checks that at least three tables in four are stored so and that the
//! runs move them on local events past the first 32.
//!
//! 8,500 cases have narrow projects with supervisors of 1–12 states and
//! 1,500 with 13–50 states (CMSSM synthesis, which runs on every case,
//! dominates their run time); 200 cases have wide projects and 60 keyed
//! wide ones (a wide case costs about as much as fifteen narrow ones,
//! mostly the logic backend evaluating its covers for every local event
//! when a state changes).
//!
//! # Where things are
//!
//! This file holds the tests; `reference.rs` the reference interpreter and
//! the trace record, `check.rs` the comparison of the three and the control
//! check, `projects.rs` random projects (and nets), `runs.rs` random input
//! sequences, `coverage.rs` what the random runs exercise, `hand.rs` the
//! hand-built projects and the press station's hand-computed trace.
//! Failures proptest finds are kept in `main.proptest-regressions`.

mod check;
mod coverage;
mod hand;
mod projects;
mod reference;
mod runs;

use crate::check::{check_control, check_run};
use crate::coverage::coverage_of;
use crate::hand::{
    event_named, hand_project, input, output_named, press_samples, press_station, run_reference,
    supervisor_named, PRESS, PRESS_TRACE, RUN, TICK,
};
use crate::projects::{
    add_random_guards, add_random_nets, keyed_wide_supervisor, project, supervisor,
    wide_supervisor, ProjectSpec, NARROW, WIDE,
};
use crate::reference::{Record, Reference};
use crate::runs::{run, wide_run, RunSpec};
use des::automaton::{EventId, StateId};
use plc_project::{Action, Drive, Event, Project, Trigger, Unexpected};
use proptest::prelude::*;
use proptest::test_runner::{FileFailurePersistence, RngAlgorithm, TestCaseError};
use std::collections::HashMap;

/// `cases` cases with the XorShift generator: in a debug build the default
/// ChaCha generator (unoptimised SIMD) took most of the run time.
///
/// Failures are kept beside this file, in `main.proptest-regressions`:
/// proptest's default would put them in `tests/proptest-regressions/main.txt`,
/// a name any other test crate with a `main.rs` would share.
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_algorithm: RngAlgorithm::XorShift,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..ProptestConfig::default()
    }
}

/// Builds and runs one random case; a failure also lists the project as
/// built, which is easier to read than the spec.
fn check_case(spec: &ProjectSpec, run: &RunSpec) -> Result<(), TestCaseError> {
    let project = spec.build();
    let samples = run.samples(project.inputs.len(), project.scan_period_ms);
    check_run(&project, &samples).map_err(|e| match e {
        TestCaseError::Fail(why) => TestCaseError::fail(format!("{why}\n{}", describe(&project))),
        other => other,
    })
}

/// A compact listing of `project` (events, inputs, … by index).
fn describe(project: &Project) -> String {
    use std::fmt::Write as _;
    let mut out = format!(
        "project: period {} ms, max_commands_per_scan {}, unexpected {:?}, reset {:?}\n",
        project.scan_period_ms, project.max_commands_per_scan, project.unexpected, project.reset
    );
    for (i, input) in project.inputs.iter().enumerate() {
        let _ = writeln!(out, "  input {i}: debounce {}", input.debounce_scans);
    }
    for (o, output) in project.outputs.iter().enumerate() {
        let _ = writeln!(
            out,
            "  output {o}: safe {}, {:?}",
            output.safe, output.drive
        );
    }
    for (t, timer) in project.timers.iter().enumerate() {
        let _ = writeln!(out, "  timer {t}: {} ms", timer.preset_ms);
    }
    for (e, ev) in project.events.iter().enumerate() {
        let _ = writeln!(
            out,
            "  event {e}: {:?}, when {:?}, unless {:?}, request {:?}, actions {:?}",
            ev.trigger, ev.when, ev.unless, ev.request, ev.actions
        );
    }
    for (j, sup) in project.supervisors.iter().enumerate() {
        let global: HashMap<EventId, usize> =
            sup.local_events.iter().map(|&(g, id)| (id, g)).collect();
        let transitions: Vec<String> = sup
            .automaton
            .iter_transitions()
            .map(|(s, e, t)| format!("{s} -{}-> {t}", global[&e]))
            .collect();
        let _ = writeln!(
            out,
            "  supervisor {j}: {} states, initial {}, events {:?}, transitions {}",
            sup.automaton.num_states(),
            sup.automaton.initial().expect("initial state"),
            sup.local_events.iter().map(|&(g, _)| g).collect::<Vec<_>>(),
            transitions.join(", ")
        );
    }
    out
}

proptest! {
    #![proptest_config(config(8_500))]

    /// Small supervisors (1–12 states): most of the cases.
    #[test]
    fn backends_match_reference_on_small_supervisors(
        spec in project(&NARROW, supervisor(1..=12)),
        run in run(),
    ) {
        check_case(&spec, &run)?;
    }
}

proptest! {
    #![proptest_config(config(1_500))]

    /// Petri nets beside the automata: the table backend's net layout
    /// against the reference's markings.
    #[test]
    fn table_backend_matches_reference_on_petri_nets(
        spec in project(&NARROW, supervisor(1..=12)),
        run in run(),
        seed in any::<u64>(),
    ) {
        let mut project = spec.build();
        add_random_nets(&mut project, seed);
        let samples = run.samples(project.inputs.len(), project.scan_period_ms);
        check_run(&project, &samples).map_err(|e| match e {
            TestCaseError::Fail(why) => TestCaseError::fail(format!("{why}\n{}\nnets: {:#?}", describe(&project), project.nets)),
            other => other,
        })?;
    }
}

proptest! {
    #![proptest_config(config(1_000))]

    /// Symbolic supervisors: random guards over the last supervisors'
    /// states hold commands back, in both backends as in the reference.
    #[test]
    fn backends_match_reference_with_guards(
        spec in project(&NARROW, supervisor(1..=12)),
        run in run(),
        seed in any::<u64>(),
    ) {
        let mut project = spec.build();
        add_random_guards(&mut project, seed);
        let samples = run.samples(project.inputs.len(), project.scan_period_ms);
        check_run(&project, &samples).map_err(|e| match e {
            TestCaseError::Fail(why) => TestCaseError::fail(format!("{why}\n{}\nguards: {:#?}", describe(&project), project.guarded)),
            other => other,
        })?;
    }
}

proptest! {
    #![proptest_config(config(1_500))]

    /// Supervisors of up to 50 states.
    #[test]
    fn backends_match_reference_on_large_supervisors(
        spec in project(&NARROW, supervisor(13..=50)),
        run in run(),
    ) {
        check_case(&spec, &run)?;
    }
}

proptest! {
    #![proptest_config(config(200))]

    /// Input images and event sets of two or three words, supervisors with
    /// more than 32 local events.
    #[test]
    fn backends_match_reference_on_wide_projects(
        spec in project(&WIDE, wide_supervisor()),
        run in wide_run(),
    ) {
        check_case(&spec, &run)?;
    }
}

proptest! {
    #![proptest_config(config(60))]

    /// Supervisors whose rows repeat, stored keyed with more than 32
    /// local events: the dictionary's rows packed, not one a word.
    #[test]
    fn backends_match_reference_on_keyed_wide_tables(
        spec in project(&WIDE, keyed_wide_supervisor()),
        run in wide_run(),
    ) {
        check_case(&spec, &run)?;
    }
}

/// The keyed wide cases are what they are for: the table backend stores
/// their supervisors keyed with more than 32 local events, and the runs
/// move them on local events past the first 32.
#[test]
fn keyed_wide_cases_store_keyed_tables_and_move_past_the_first_word() {
    use proptest::strategy::ValueTree;

    let strategy = (project(&WIDE, keyed_wide_supervisor()), wide_run());
    let mut runner = proptest::test_runner::TestRunner::new(config(40));
    let (mut keyed, mut tables) = (0, 0);
    for _ in 0..40 {
        let (spec, _) = strategy.new_tree(&mut runner).unwrap().current();
        let image = codegen::lower::TableImage::new(&spec.build()).unwrap();
        tables += image.tables.len();
        keyed += image
            .tables
            .iter()
            .filter(|t| t.layout == codegen::backend::table::Layout::Keyed && t.events > 32)
            .count();
    }
    assert!(
        keyed * 4 >= tables * 3,
        "{keyed} of {tables} tables keyed with more than 32 events"
    );
    let coverage = coverage_of(strategy, 40);
    assert!(
        coverage.high_local_moves > 0,
        "no move on a local event >= 32: {coverage:#?}"
    );
}

/// The random cases reach every rule: events of every kind execute,
/// faults are entered and left, events are ignored, the clock wraps; and
/// most scans are not spent in fault mode.
#[test]
fn random_runs_exercise_every_rule() {
    let coverage = coverage_of((project(&NARROW, supervisor(1..=12)), run()), 300);
    println!("{} scans: {:#?}", coverage.scans, coverage.counters());
    for (what, n) in coverage.counters() {
        assert!(n > 0, "no {what} in 300 random runs: {coverage:#?}");
    }
    assert!(
        coverage.scans_in_fault * 2 < coverage.scans,
        "most scans are spent in fault mode: {coverage:#?}"
    );
}

/// The wide cases cross every word boundary the executor has: events and
/// commands past the first word of an event set execute, a request input
/// and edges past the first word of the input image count, supervisors
/// move on local events past the first 32-event slice of their rows; and
/// they still reach every rule without spending most scans in fault mode.
#[test]
fn wide_runs_cross_every_word_boundary() {
    let coverage = coverage_of((project(&WIDE, wide_supervisor()), wide_run()), 100);
    println!(
        "{} scans: {:#?} {:#?}",
        coverage.scans,
        coverage.word_counters(),
        coverage.counters()
    );
    for (what, n) in coverage
        .word_counters()
        .into_iter()
        .chain(coverage.counters())
    {
        assert!(n > 0, "no {what} in 100 wide runs: {coverage:#?}");
    }
    assert!(
        coverage.scans_in_fault * 2 < coverage.scans,
        "most scans are spent in fault mode: {coverage:#?}"
    );
}

// ---------------------------------------------------------------------------
// The reference against hand-computed traces
// ---------------------------------------------------------------------------

/// Debounce, edges, an event in no alphabet, a timer, an unexpected event
/// faulting (safe image, timer expiry ignored in fault mode), reset
/// recovery (timer stopped) and a suppressed glitch.
#[test]
fn reference_follows_a_hand_computed_trace() {
    let project = press_station();
    let samples = press_samples(0);
    let trace = run_reference(&project, &samples);
    for (k, (got, want)) in trace.iter().zip(&PRESS_TRACE).enumerate() {
        let (executed, unexpected, state, outputs, fault) = *want;
        let want = Record {
            scan: k as u32,
            time_ms: 10 * k as u32,
            executed: executed.to_vec(),
            unexpected: unexpected.to_vec(),
            states: vec![state],
            outputs: outputs.to_vec(),
            fault,
        };
        assert_eq!(*got, want, "scan {k}");
    }
    check_run(&project, &samples).unwrap();
}

/// Shifting the clock so that the second timer runs across the u32
/// wrap-around (started at 2^32 - 21 ms, due at 29 ms) changes nothing but
/// the times.
#[test]
fn reference_trace_is_invariant_under_clock_wrap() {
    let project = press_station();
    let start = u32::MAX - 149;
    let shifted = press_samples(start);
    assert!(shifted[13].0 > shifted[18].0, "the run must cross the wrap");
    let plain = run_reference(&project, &press_samples(0));
    let wrapped = run_reference(&project, &shifted);
    for (k, (p, w)) in plain.iter().zip(&wrapped).enumerate() {
        let w = Record {
            time_ms: w.time_ms.wrapping_sub(start),
            ..w.clone()
        };
        assert_eq!(*p, w, "scan {k}");
    }
    check_run(&project, &shifted).unwrap();
}

/// Two supervisors sharing a controllable event with a request input, no
/// command limit, and an unexpected event under policy `ignore`.
///
/// Events: `u` (rising x), `a`, `go` (request `req`), `b`; outputs `lamp`
/// (set by `a`, cleared by `go`) and `b_done` (B in state 2).
/// A: 0 -a-> 1 -go-> 0. B: 0 -go-> 1 -b-> 2 -u-> 0.
#[test]
fn reference_runs_commands_of_modular_supervisors() {
    let events = vec![
        event_named("u", Trigger::Rising(vec![1]), vec![]),
        event_named("a", Trigger::Command, vec![Action::Set(0)]),
        Event {
            request: Some(0),
            ..event_named("go", Trigger::Command, vec![Action::Clear(0)])
        },
        event_named("b", Trigger::Command, vec![]),
    ];
    let a = supervisor_named("A", &events, &[1, 2], 2, &[(0, 1, 1), (1, 2, 0)]);
    let b = supervisor_named(
        "B",
        &events,
        &[0, 2, 3],
        3,
        &[(0, 2, 1), (1, 3, 2), (2, 0, 0)],
    );
    let mut project = hand_project(
        vec![input("req", 0), input("x", 0)],
        vec![
            output_named("lamp", false, Drive::Actions { initial: false }),
            output_named("b_done", false, Drive::States(vec![(1, vec![StateId(2)])])),
        ],
        Vec::new(),
        events,
    );
    project.supervisors = vec![a, b];
    project.max_commands_per_scan = 0;
    project.unexpected = Unexpected::Ignore;

    // (req, x) -> (executed, unexpected, states, outputs)
    type Step = (
        (bool, bool),
        &'static [usize],
        &'static [usize],
        [u32; 2],
        [bool; 2],
    );
    const STEPS: [Step; 6] = [
        ((false, false), &[1], &[], [1, 0], [true, false]),
        ((true, false), &[2, 1, 3], &[], [1, 2], [true, true]),
        ((false, true), &[0], &[], [1, 0], [true, false]),
        ((false, false), &[], &[], [1, 0], [true, false]),
        ((false, true), &[], &[0], [1, 0], [true, false]),
        ((true, true), &[2, 1, 3], &[], [1, 2], [true, true]),
    ];
    let samples: Vec<(u32, Vec<bool>)> = STEPS
        .iter()
        .zip(0u32..)
        .map(|(&((req, x), ..), k)| (10 * k, vec![req, x]))
        .collect();
    let mut reference = Reference::new(&project);
    for (k, (now, raw)) in samples.iter().enumerate() {
        let (_, executed, unexpected, states, outputs) = STEPS[k];
        let got = reference.scan(*now, raw);
        assert_eq!(got.executed, executed, "scan {k}: executed");
        assert_eq!(got.unexpected, unexpected, "scan {k}: unexpected");
        assert_eq!(got.states, states, "scan {k}: states");
        assert_eq!(got.outputs, outputs, "scan {k}: outputs");
        assert_eq!(got.fault, None, "scan {k}: fault");
    }
    assert_eq!(reference.ignored, 1);
    check_run(&project, &samples).unwrap();
}

/// The control-equivalence check rejects a command the supervisor does
/// not allow, a move along no transition, and a move in fault mode.
#[test]
fn control_check_rejects_what_the_supervisors_forbid() {
    let project = press_station();
    let record = |executed: &[usize], state: u32| Record {
        scan: 1,
        time_ms: 10,
        executed: executed.to_vec(),
        unexpected: Vec::new(),
        states: vec![state],
        outputs: vec![false, false],
        fault: None,
    };
    let check = |before: u32, faulted: bool, r: &Record| {
        check_control(&project, 1, &[before], faulted, r).is_ok()
    };
    assert!(check(0, false, &record(&[PRESS, RUN], 2)));
    assert!(
        !check(0, false, &record(&[RUN], 2)),
        "run is disabled in idle"
    );
    assert!(
        !check(0, false, &record(&[PRESS], 2)),
        "press leads to armed"
    );
    assert!(check(2, true, &record(&[], 0)), "a reset scan");
    assert!(!check(2, true, &record(&[], 1)), "no move in fault mode");
    assert!(
        !check(2, true, &record(&[TICK], 0)),
        "nothing runs in fault mode"
    );
}
