//! Hand-built projects, and the press station with its hand-computed
//! trace, which pin the reference itself.

use crate::reference::{Cause, Record, Reference};
use des::automaton::{EventId, StateId};
use des::AutomatonBuilder;
use plc_project::{
    Action, Drive, Event, Input, Origin, Output, Project, Supervisor, SupervisorSource, Timer,
    Trigger, Unexpected,
};
use std::path::PathBuf;

pub(crate) fn input(name: &str, debounce_scans: u8) -> Input {
    Input {
        name: name.to_owned(),
        debounce_scans,
        line: 0,
    }
}

pub(crate) fn output_named(name: &str, safe: bool, drive: Drive) -> Output {
    Output {
        name: name.to_owned(),
        safe,
        drive,
        line: 0,
    }
}

/// An event; `trigger` `Command` makes it controllable.
pub(crate) fn event_named(name: &str, trigger: Trigger, actions: Vec<Action>) -> Event {
    let controllable = trigger == Trigger::Command;
    Event {
        name: name.to_owned(),
        controllable,
        origin: if controllable {
            Origin::Controller
        } else {
            Origin::Plant
        },
        trigger,
        when: Vec::new(),
        unless: Vec::new(),
        request: None,
        actions,
        line: 0,
    }
}

/// A supervisor over `alphabet` (global event indices, ascending) with
/// states `0..n`, initial state 0 and transitions (source, global event,
/// target).
pub(crate) fn supervisor_named(
    name: &str,
    events: &[Event],
    alphabet: &[usize],
    n: u32,
    transitions: &[(u32, usize, u32)],
) -> Supervisor {
    let mut b = AutomatonBuilder::new(name);
    let ids: Vec<EventId> = alphabet
        .iter()
        .map(|&e| {
            b.add_event(&events[e].name, events[e].controllable)
                .unwrap()
        })
        .collect();
    for _ in 0..n {
        b.add_anonymous_state();
    }
    b.set_initial(StateId(0)).unwrap();
    for &(s, e, t) in transitions {
        let slot = alphabet.iter().position(|&g| g == e).unwrap();
        b.add_transition(StateId(s), ids[slot], StateId(t), 0);
    }
    Supervisor {
        name: name.to_owned(),
        automaton: b.build().unwrap(),
        local_events: alphabet.iter().copied().zip(ids).collect(),
        source: SupervisorSource::File(PathBuf::from(format!("{name}.toml"))),
        line: 0,
        max_logic_effort: None,
    }
}

pub(crate) fn hand_project(
    inputs: Vec<Input>,
    outputs: Vec<Output>,
    timers: Vec<Timer>,
    events: Vec<Event>,
) -> Project {
    Project {
        path: PathBuf::from("hand.plc.toml"),
        name: "hand".to_owned(),
        scan_period_ms: 10,
        max_commands_per_scan: 1,
        unexpected: Unexpected::Fault,
        reset: None,
        overrun_limit: 1,
        overrun_fault: false,
        lost_edge_fault: false,
        rom_test_bytes_per_scan: 64,
        stored_sets_bytes: 1024,
        inputs,
        outputs,
        timers,
        switches: Vec::new(),
        events,
        supervisors: Vec::new(),
        nets: Vec::new(),
        guarded: Vec::new(),
        board: None,
        warnings: Vec::new(),
        files: Vec::new(),
    }
}

/// A press station. Inputs `btn` (debounce 2) and `rst` (reset); output
/// `lamp` (actions) and `moving` (state map, safe 1); timer `t` (50 ms).
/// Events: `press` (rising btn, sets lamp), `release` (falling btn, in no
/// alphabet, clears lamp), `tick` (t expired, clears lamp), `run`
/// (controllable, starts t). Supervisor S: idle -press-> armed -run->
/// running -tick-> idle.
pub(crate) fn press_station() -> Project {
    let events = vec![
        event_named("press", Trigger::Rising(vec![0]), vec![Action::Set(0)]),
        event_named("release", Trigger::Falling(vec![0]), vec![Action::Clear(0)]),
        event_named("tick", Trigger::Expired(0), vec![Action::Clear(0)]),
        event_named("run", Trigger::Command, vec![Action::Start(0)]),
    ];
    let s = supervisor_named(
        "S",
        &events,
        &[0, 2, 3],
        3,
        &[(0, 0, 1), (1, 3, 2), (2, 2, 0)],
    );
    let mut p = hand_project(
        vec![input("btn", 2), input("rst", 0)],
        vec![
            output_named("lamp", false, Drive::Actions { initial: false }),
            output_named("moving", true, Drive::States(vec![(0, vec![StateId(2)])])),
        ],
        vec![Timer {
            name: "t".to_owned(),
            preset_ms: 50,
            line: 0,
        }],
        events,
    );
    p.supervisors = vec![s];
    p.reset = Some(1);
    p
}

/// (btn, rst) raw inputs of the press-station run, one pair per scan.
pub(crate) const PRESS_INPUTS: [(bool, bool); 20] = [
    (false, false), // 0
    (true, false),  // 1: btn differs once
    (true, false),  // 2: twice -> F=1, press, run
    (false, false), // 3
    (false, false), // 4: F=0, release
    (true, false),  // 5
    (true, false),  // 6: press while running -> fault
    (true, false),  // 7: t due (70 ms) but faulted
    (true, true),   // 8: reset rises -> re-initialised
    (true, true),   // 9
    (false, false), // 10
    (false, false), // 11: release
    (true, false),  // 12
    (true, false),  // 13: press, run (deadline 180)
    (true, false),  // 14
    (false, false), // 15: glitch ...
    (true, false),  // 16: ... filtered out
    (true, false),  // 17
    (true, false),  // 18: 180 ms, tick
    (true, false),  // 19
];

/// The press-station samples with scan k at `start + 10 k` ms.
pub(crate) fn press_samples(start: u32) -> Vec<(u32, Vec<bool>)> {
    PRESS_INPUTS
        .iter()
        .zip(0u32..)
        .map(|(&(btn, rst), k)| (start.wrapping_add(10 * k), vec![btn, rst]))
        .collect()
}

pub(crate) fn run_reference(project: &Project, samples: &[(u32, Vec<bool>)]) -> Vec<Record> {
    let mut reference = Reference::new(project);
    samples
        .iter()
        .map(|(now, raw)| reference.scan(*now, raw))
        .collect()
}

/// (executed, unexpected, state, outputs, fault) as hand-computed.
pub(crate) type Expected = (
    &'static [usize],
    &'static [usize],
    u32,
    [bool; 2],
    Option<Cause>,
);

pub(crate) const PRESS: usize = 0;
pub(crate) const RELEASE: usize = 1;
pub(crate) const TICK: usize = 2;
pub(crate) const RUN: usize = 3;
pub(crate) const FAULTED: Option<Cause> = Some(Cause::Unexpected(PRESS));

pub(crate) const PRESS_TRACE: [Expected; 20] = [
    (&[], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[PRESS, RUN], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[RELEASE], &[], 2, [false, true], None),
    (&[], &[], 2, [false, true], None),
    (&[], &[PRESS], 2, [false, true], FAULTED),
    (&[], &[], 2, [false, true], FAULTED),
    (&[], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[RELEASE], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[PRESS, RUN], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[TICK], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
];
