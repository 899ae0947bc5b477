//! The build-script path end to end. `build.rs` generates every seed
//! project with both backends through `codegen::build::Build`, as a
//! firmware crate's build script would; this file compiles each generated
//! source in its own module under `#[deny(warnings)]` (so generated code
//! is warning-free, clippy included when the workspace is linted) and
//! proves, for every project and backend, that
//!
//! - the generated name modules (`input`, `output`, `timer`, `event`,
//!   `supervisor`, `states`), `CONFIG` and `IMAGE_CRC` agree with the
//!   project and with the run-time image `codegen::lower` builds from it
//!   (`TableImage::new(&project).crc` for tables, the configuration CRC of
//!   `LogicImage` for logic), and the CRC of `PROGRAM`'s image is it;
//! - the generated δ (const tables or logic functions) equals the run-time
//!   table on every (supervisor, state, local event);
//! - `executor::Controller::new(&PROGRAM, Memory::new())` produces, scan by
//!   scan, the same trace as host-sim's run-time table simulation of the
//!   project (executed and unexpected events, states, outputs, fault, and
//!   the counters), on seeded pseudo-random input sequences whose biased
//!   toggles and clock jumps make every event, faults, resets and timer
//!   expiries happen (checked by coverage assertions).

use codegen::backend::Backend;
use codegen::lower::{LogicImage, Supervisors, TableImage};
use des::{EventId, StateId};
use executor::memory::Memory;
use executor::program::{Config, Index, Program};
use executor::Controller;
use host_sim::{Sim, TraceRow};
use plc_project::{self as project, Project, Trigger};
use std::collections::BTreeSet;

/// Each generated file in its own module, compiled with every warning
/// (clippy's too, under `cargo clippy`) an error, `dead_code` included:
/// the modules are private to this test binary, which reads only some of
/// the named constants, as a user's crate does.
macro_rules! generated {
    ($($module:ident),* $(,)?) => {$(
        #[deny(warnings)]
        mod $module {
            include!(concat!(env!("OUT_DIR"), "/", stringify!($module), ".rs"));
        }
    )*};
}

generated!(
    motivating_table,
    motivating_logic,
    press_table,
    press_logic,
    press7_table,
    press7_logic,
    conveyor_table,
    conveyor_logic,
    crane_table,
    crane_logic,
    motivating_match,
    press_match,
    press7_match,
    conveyor_match,
    crane_match,
    hostile_table,
    hostile_logic,
    hostile_match,
    mixers_table,
);

// The random name cases (`build_names.rs`): `generated!` over their
// modules and `name_cases()` listing them.
include!(concat!(env!("OUT_DIR"), "/names_cases.rs"));

/// One random name case on one backend: what the generated module
/// exports and the names the project declared.
struct NameCase {
    case: usize,
    backend: &'static str,
    program: &'static dyn Program,
    /// `NAMES` of inputs, outputs, timers, events and supervisors, then the
    /// first supervisor's `states`.
    names: [&'static [&'static str]; 6],
    /// The same, as the project and model file wrote them.
    expected: [&'static [&'static str]; 6],
}

/// The names property (`tests/build_names.rs`): seeded random projects
/// whose names are keywords, reserved-looking, suffix twins, non-ASCII,
/// bidirectional overrides, control characters, quotes and comment
/// markers compiled above under `#[deny(warnings)]` on every backend; each
/// name comes through as written and each program runs its model
/// (command from idle to busy, sensor back).
#[test]
fn random_names_compile_warning_free_on_every_backend_and_keep_their_text() {
    let cases = name_cases();
    assert!(!cases.is_empty());
    assert_eq!(
        cases.len() % Backend::ALL.len(),
        0,
        "every case on every backend"
    );
    for c in &cases {
        let at = format!("case {} on {}", c.case, c.backend);
        assert_eq!(c.names, c.expected, "{at}");
        for j in 0..c.expected[4].len() as Index {
            assert_eq!(c.program.next_state(j, 0, 0), Some(1), "{at}: command");
            assert_eq!(c.program.next_state(j, 1, 1), Some(0), "{at}: sensor");
            assert_eq!(
                c.program.next_state(j, 0, 1),
                None,
                "{at}: no sensor when idle"
            );
        }
    }
}

/// Supervisors named `fn`, `fn_`, `Self` and `type`, bidirectional
/// overrides and non-ASCII letters in names (`tests/fixtures/hostile/`):
/// every backend compiled above under `#[deny(warnings)]`, and the names
/// come through as written.
#[test]
fn hostile_names_compile_on_every_backend_and_keep_their_text() {
    let supervisors = ["fn", "fn_", "Self", "type"];
    assert_eq!(hostile_table::supervisor::NAMES, supervisors);
    assert_eq!(hostile_logic::supervisor::NAMES, supervisors);
    assert_eq!(hostile_match::supervisor::NAMES, supervisors);
    assert_eq!(hostile_table::input::NAMES[0], "go\u{2066}sensor");
    assert_eq!(hostile_logic::states::FN[1], "busy \u{202e} evil");
    for program in [
        &hostile_table::PROGRAM as &dyn Program,
        &hostile_logic::PROGRAM,
        &hostile_match::PROGRAM,
    ] {
        // `go` is enabled in every supervisor's initial state.
        for j in 0..4 {
            assert_eq!(program.next_state(j, 0, 0), Some(1), "supervisor {j}");
        }
    }
}

/// What a generated module exports, gathered for the generic checks.
struct Generated<P: Program + 'static, M: Memory> {
    /// `models/<model>.plc.toml`.
    model: &'static str,
    backend: Backend,
    program: &'static P,
    memory: fn() -> M,
    config: Config<'static>,
    crc: u32,
    inputs: &'static [&'static str],
    outputs: &'static [&'static str],
    timers: &'static [&'static str],
    events: &'static [&'static str],
    supervisors: &'static [&'static str],
    /// `COUNT` of `input`, `output`, `timer`, `event`, `supervisor`.
    counts: [usize; 5],
    /// `states::<SUPERVISOR>`, in declaration order.
    states: Vec<&'static [&'static str]>,
    /// States no run can enter (see [`CONVEYOR_NEVER`]).
    never: &'static [&'static str],
}

/// The states of the synthesised conveyor supervisor the controller never
/// enters: `blocked.off.idle.wanted` is only ever entered by `re_ls`, after
/// which the controller issues `start` in the same scan, so `fe_ls` never
/// leaves it for `clear.off.timing.wanted`, nor that one lead on to
/// `clear.off.idle.wanted` and `clear.on.idle.running`. The coverage check
/// asserts exactly these are missed.
const CONVEYOR_NEVER: &[&str] = &[
    "clear.off.idle.wanted",
    "clear.off.timing.wanted",
    "clear.on.idle.running",
];

/// One test per generated module.
macro_rules! conformance {
    ($($module:ident: $model:literal, $backend:ident, [$($sup:ident),*], $never:expr;)*) => {$(
        #[test]
        fn $module() {
            use $module as g;
            check(Generated {
                model: $model,
                backend: Backend::$backend,
                program: &g::PROGRAM,
                memory: g::Memory::new,
                config: g::CONFIG,
                crc: g::IMAGE_CRC,
                inputs: &g::input::NAMES,
                outputs: &g::output::NAMES,
                timers: &g::timer::NAMES,
                events: &g::event::NAMES,
                supervisors: &g::supervisor::NAMES,
                counts: [
                    g::input::COUNT,
                    g::output::COUNT,
                    g::timer::COUNT,
                    g::event::COUNT,
                    g::supervisor::COUNT,
                ],
                states: vec![$(&g::states::$sup[..]),*],
                never: $never,
            });
        }
    )*};
}

conformance! {
    motivating_table: "motivating", Table, [MOTIVATING], &[];
    motivating_logic: "motivating", Logic, [MOTIVATING], &[];
    press_table: "press", Table, [PRESS], &[];
    press_logic: "press", Logic, [PRESS], &[];
    press7_table: "press7", Table, [PRESS], &[];
    press7_logic: "press7", Logic, [PRESS], &[];
    conveyor_table: "conveyor", Table, [CONVEYOR], CONVEYOR_NEVER;
    conveyor_logic: "conveyor", Logic, [CONVEYOR], CONVEYOR_NEVER;
    crane_table: "crane", Table, [SUP_CRANE1, SUP_SECTION], &[];
    crane_logic: "crane", Logic, [SUP_CRANE1, SUP_SECTION], &[];
    motivating_match: "motivating", Match, [MOTIVATING], &[];
    press_match: "press", Match, [PRESS], &[];
    press7_match: "press7", Match, [PRESS], &[];
    conveyor_match: "conveyor", Match, [CONVEYOR], CONVEYOR_NEVER;
    crane_match: "crane", Match, [SUP_CRANE1, SUP_SECTION], &[];
    mixers_table: "petri/mixers", Table, [], &[];
}

/// Input sequences per model and backend: (seed, activity), each of
/// [`SCANS`] scans. The activity is the percentage of scans (outside fault
/// mode) that change an input: busy runs make events pile up within
/// scans, quiet ones let debounce filters settle and timers expire.
const RUNS: [(u64, u64); 8] = [
    (1, 60),
    (2, 60),
    (0x5eed, 30),
    (0x5eee, 30),
    (0xdead_beef, 10),
    (0xdead_bef0, 10),
    (20_240_229, 4),
    (20_240_230, 4),
];
const SCANS: usize = 2_000;

/// SplitMix64: tiny, deterministic, good enough for test stimuli.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `lo..=hi` (bias is irrelevant here).
    fn range(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.next() % (hi - lo + 1)
    }
}

/// Raw input images and scan times, steered by the current supervisor
/// states so that runs get deep into the models instead of faulting on the
/// first random edge:
///
/// - the raw image starts random (scan 0 has no edges);
/// - a run-dependent share of the scans changes one input. Nine times in
///   ten it is a *safe* toggle: one whose edge would fire only events that
///   every supervisor having them can take now (judged on the raw image).
///   Safe toggles that fire some event are preferred; among those that
///   fire none, ones that make a new safe firing toggle possible (release
///   a button so it can be pressed again, raise a `when` condition) are
///   preferred. The tenth time it is, as often as not, a toggle that
///   fires an event some supervisor cannot take now, else any input at
///   all, so that unexpected events and faults happen too (and every
///   undefined transition the runs reach is checked to be undefined);
/// - an input with a debounce filter keeps a new level long enough for
///   the filter to take it, unless a glitch toggles it back;
/// - in fault mode the reset input is pulsed after a while;
/// - the clock mostly advances by the scan period, sometimes by a few
///   periods, and now and then jumps past timer presets.
struct Stimulus<'p> {
    project: &'p Project,
    /// Per event, the supervisors that have it: (supervisor, local id).
    members: Vec<Vec<(usize, EventId)>>,
    period: u64,
    time: u64,
    raw: Vec<bool>,
    /// Scans each input keeps its level before a safe toggle may change it.
    hold: Vec<u64>,
    /// Percentage of scans that change an input.
    activity: u64,
}

impl<'p> Stimulus<'p> {
    fn new(project: &'p Project, activity: u64, rng: &mut Rng) -> Stimulus<'p> {
        let mut members = vec![Vec::new(); project.events.len()];
        for (j, sup) in project.supervisors.iter().enumerate() {
            for &(g, id) in &sup.local_events {
                members[g].push((j, id));
            }
        }
        let raw = project
            .inputs
            .iter()
            .enumerate()
            .map(|(i, _)| project.reset != Some(i) && rng.range(0, 1) == 1)
            .collect();
        Stimulus {
            project,
            members,
            period: u64::from(project.scan_period_ms),
            time: 0,
            raw,
            hold: vec![0; project.inputs.len()],
            activity,
        }
    }

    /// Whether every supervisor having event `g` can take it in `states`.
    fn feasible(&self, g: usize, states: &[u32]) -> bool {
        self.members[g].iter().all(|&(j, id)| {
            self.project.supervisors[j]
                .automaton
                .successor(StateId(states[j]), id)
                .is_some()
        })
    }

    /// The events an edge of input `i` of `image` would fire.
    fn fired_by_toggle(&self, image: &[bool], i: usize) -> Vec<usize> {
        let mut after = image.to_vec();
        after[i] = !after[i];
        let any = |image: &[bool], list: &[usize]| list.iter().any(|&x| image[x]);
        let holds = |e: &project::Event| {
            e.when.iter().all(|&x| after[x]) && e.unless.iter().all(|&x| !after[x])
        };
        self.project
            .events
            .iter()
            .enumerate()
            .filter(|(_, e)| match &e.trigger {
                Trigger::Rising(list) => {
                    list.contains(&i) && !any(image, list) && any(&after, list) && holds(e)
                }
                Trigger::Falling(list) => {
                    list.contains(&i) && any(image, list) && !any(&after, list) && holds(e)
                }
                Trigger::Command | Trigger::Expired(_) => false,
            })
            .map(|(g, _)| g)
            .collect()
    }

    /// The safe toggles of `image` in `states`: (firing, quiet) inputs.
    fn safe_toggles(&self, image: &[bool], states: &[u32]) -> (Vec<usize>, Vec<usize>) {
        let (mut firing, mut quiet) = (Vec::new(), Vec::new());
        for i in 0..image.len() {
            let fired = self.fired_by_toggle(image, i);
            if fired.iter().all(|&g| self.feasible(g, states)) {
                if fired.is_empty() {
                    quiet.push(i);
                } else {
                    firing.push(i);
                }
            }
        }
        (firing, quiet)
    }

    /// Picks a toggle that need not be safe: half the time one whose edge
    /// fires an event some supervisor cannot take now (if there is one),
    /// else any input.
    fn unsafe_toggle(&self, rng: &mut Rng, states: &[u32]) -> Option<usize> {
        let n = self.raw.len() as u64;
        let unexpected: Vec<usize> = (0..self.raw.len())
            .filter(|&i| {
                self.fired_by_toggle(&self.raw, i)
                    .iter()
                    .any(|&g| !self.feasible(g, states))
            })
            .collect();
        if !unexpected.is_empty() && rng.range(0, 1) == 0 {
            Some(unexpected[rng.range(0, unexpected.len() as u64 - 1) as usize])
        } else {
            Some(rng.range(0, n - 1) as usize)
        }
    }

    /// Picks the safe toggle to make, if any.
    fn safe_toggle(&self, rng: &mut Rng, states: &[u32]) -> Option<usize> {
        let (firing, quiet) = self.safe_toggles(&self.raw, states);
        let ready = |list: Vec<usize>| -> Vec<usize> {
            list.into_iter().filter(|&i| self.hold[i] == 0).collect()
        };
        let (firing, quiet) = (ready(firing), ready(quiet));
        let useful: Vec<usize> = quiet
            .iter()
            .copied()
            .filter(|&i| {
                let mut image = self.raw.clone();
                image[i] = !image[i];
                let (now, _) = self.safe_toggles(&image, states);
                now.iter().any(|x| !firing.contains(x))
            })
            .collect();
        let mut pools = Vec::new();
        if !firing.is_empty() && rng.range(0, 9) < 7 {
            pools.push(firing);
        }
        if !useful.is_empty() && rng.range(0, 9) < 7 {
            pools.push(useful);
        }
        pools.push(quiet);
        let pool = pools.into_iter().find(|p| !p.is_empty())?;
        Some(pool[rng.range(0, pool.len() as u64 - 1) as usize])
    }

    /// The time and raw image of the next scan, given the supervisor
    /// states and fault state after the previous one.
    fn next(&mut self, rng: &mut Rng, states: &[u32], faulted: bool) -> (u64, &[bool]) {
        let n = self.raw.len() as u64;
        for h in &mut self.hold {
            *h = h.saturating_sub(1);
        }
        let toggle = match self.project.reset {
            Some(r) if self.raw[r] => Some(r),
            Some(r) if faulted && rng.range(0, 19) == 0 => Some(r),
            _ if faulted || n == 0 || rng.range(0, 99) >= self.activity => None,
            _ if rng.range(0, 9) == 0 => self.unsafe_toggle(rng, states),
            _ => self.safe_toggle(rng, states),
        };
        if let Some(i) = toggle {
            self.raw[i] = !self.raw[i];
            self.hold[i] = u64::from(self.project.inputs[i].debounce_scans);
        }
        let time = self.time;
        self.time += match rng.range(0, 99) {
            0..=89 => self.period,
            90..=96 => self.period * rng.range(2, 5),
            _ => rng.range(300, 3_000),
        };
        (time, &self.raw)
    }
}

/// What the random runs reached, to show the stimuli are not vacuous.
#[derive(Default)]
struct Coverage {
    events: BTreeSet<String>,
    /// (supervisor, state) entered, including states left again within
    /// the same scan (replayed from the executed events).
    states: BTreeSet<(usize, u32)>,
    faults: usize,
    resets: usize,
}

impl Coverage {
    /// Records a scan that started in `before` and produced `row`.
    fn record(
        &mut self,
        p: &Project,
        members: &[Vec<(usize, EventId)>],
        before: &[u32],
        row: &TraceRow,
    ) {
        let mut states = before.to_vec();
        for name in &row.events {
            self.events.insert(name.clone());
            let g = p.event(name).expect("executed events are declared");
            for &(j, id) in &members[g] {
                let a = &p.supervisors[j].automaton;
                if let Some(next) = a.successor(StateId(states[j]), id) {
                    states[j] = next.0;
                    self.states.insert((j, next.0));
                }
            }
        }
        for (j, sup) in p.supervisors.iter().enumerate() {
            let state = sup.automaton.state_by_name(row.state(&sup.name).unwrap());
            self.states.insert((j, state.unwrap().0));
        }
    }
}

fn check<P: Program + 'static, M: Memory>(g: Generated<P, M>) {
    let what = format!("{} ({:?} backend)", g.model, g.backend);
    let path = e2e::model(&format!("models/{}.plc.toml", g.model));
    let project = project::load(&path).unwrap_or_else(|e| panic!("{what}: {e}"));

    // Names and counts.
    let names = |list: Vec<&str>| list.into_iter().map(str::to_owned).collect::<Vec<_>>();
    let owned = |list: &[&str]| names(list.to_vec());
    let p = &project;
    assert_eq!(
        owned(g.inputs),
        names(p.inputs.iter().map(|x| x.name.as_str()).collect()),
        "{what}: input names"
    );
    assert_eq!(
        owned(g.outputs),
        names(p.outputs.iter().map(|x| x.name.as_str()).collect()),
        "{what}: output names"
    );
    assert_eq!(
        owned(g.timers),
        names(p.timers.iter().map(|x| x.name.as_str()).collect()),
        "{what}: timer names"
    );
    assert_eq!(
        owned(g.events),
        names(p.events.iter().map(|x| x.name.as_str()).collect()),
        "{what}: event names"
    );
    // Automata, then the groups of every Petri net.
    let image = TableImage::new(p).unwrap();
    let supervisors = Supervisors::new(p, &image.pools.nets);
    assert_eq!(
        owned(g.supervisors),
        (0..supervisors.len())
            .map(|j| supervisors.name(j))
            .collect::<Vec<_>>(),
        "{what}: supervisor names"
    );
    assert_eq!(
        g.counts,
        [
            p.inputs.len(),
            p.outputs.len(),
            p.timers.len(),
            p.events.len(),
            supervisors.len()
        ],
        "{what}: COUNT constants"
    );
    assert_eq!(
        g.states.len(),
        p.supervisors.len(),
        "{what}: states modules"
    );
    for (listed, sup) in g.states.iter().zip(&p.supervisors) {
        let a = &sup.automaton;
        let expected: Vec<String> = a.states().map(|s| a.state_name(s).into_owned()).collect();
        assert_eq!(owned(listed), expected, "{what}: states of `{}`", sup.name);
    }

    // Configuration and CRC against the run-time image.
    // `Config` has no `PartialEq`; its `Debug` text shows every field.
    let runtime_config = format!("{:?}", image.config());
    assert_eq!(format!("{:?}", g.config), runtime_config, "{what}: CONFIG");
    assert_eq!(
        format!("{:?}", g.program.config()),
        runtime_config,
        "{what}: PROGRAM.config()"
    );
    // Tables: the CRC of configuration and tables; code backends: of the
    // configuration alone.
    let expected_crc = if g.backend == Backend::Table {
        image.crc
    } else {
        executor::image::config_crc(&image.config())
    };
    assert_eq!(g.crc, expected_crc, "{what}: IMAGE_CRC");
    if g.backend == Backend::Logic {
        assert_eq!(g.crc, LogicImage::new(p).unwrap().crc, "{what}: IMAGE_CRC");
    }
    assert_eq!(
        executor::image::crc(g.program),
        g.program.recorded_crc(),
        "{what}: the CRC of PROGRAM's image is not the one it records, so the \
         controller would start in Corrupt fault mode"
    );
    assert_eq!(g.program.recorded_crc(), g.crc, "{what}: recorded_crc()");

    // δ on every (supervisor, state, local event).
    for (j, sup) in p.supervisors.iter().enumerate() {
        let j = j as Index;
        for state in 0..sup.automaton.num_states() as u32 {
            for local in 0..sup.local_events.len() as Index {
                assert_eq!(
                    g.program.next_state(j, state, local),
                    image.next_state(j, state, local),
                    "{what}: δ of `{}` in state {state} on local event {local}",
                    sup.name
                );
            }
        }
    }

    // φ rows (what the controller reads after a move) on every
    // (supervisor, state) and every window of local events: the defined
    // events of δ, whichever way the backend computes them.
    for (j, sup) in p.supervisors.iter().enumerate() {
        let m = sup.local_events.len() as Index;
        for state in 0..sup.automaton.num_states() as u32 {
            for from in 0..m {
                for len in [1u8, 2, 5, 32] {
                    let expected = (0..u16::from(len)).fold(0u32, |row, k| {
                        let defined = from
                            .checked_add(k)
                            .is_some_and(|e| image.next_state(j as Index, state, e).is_some());
                        row | u32::from(defined) << k
                    });
                    assert_eq!(
                        g.program.enabled(j as Index, state, from, len),
                        expected,
                        "{what}: enabled row of `{}` in state {state} from {from}, {len} events",
                        sup.name
                    );
                }
            }
        }
    }

    // Scan by scan against host-sim.
    let mut coverage = Coverage::default();
    for (seed, activity) in RUNS {
        let mut controller =
            Controller::new(g.program, (g.memory)()).expect("Memory fits the program");
        let mut sim = Sim::new(project.clone(), Backend::Table).unwrap();
        let mut rng = Rng(seed);
        let mut stimulus = Stimulus::new(p, activity, &mut rng);
        let mut faulted = false;
        for k in 0..SCANS {
            let states = controller.states().to_vec();
            let (time, raw) = stimulus.next(&mut rng, &states, faulted);
            let record = controller.scan(time as u32, raw);
            let ours = TraceRow::from_record(&record, time, supervisors);
            let theirs = sim.scan_with(time, raw).unwrap();
            assert_eq!(
                &ours, theirs,
                "{what}: seed {seed:#x}, scan {k}, time {time} ms, raw inputs {raw:?}"
            );
            assert_eq!(
                controller.states(),
                sim.controller().states(),
                "{what}: seed {seed:#x}, scan {k}: state vectors"
            );
            assert_eq!(
                controller.counters(),
                sim.controller().counters(),
                "{what}: seed {seed:#x}, scan {k}: counters"
            );
            coverage.record(p, &stimulus.members, &states, &ours);
            match (faulted, ours.fault.is_some()) {
                (false, true) => coverage.faults += 1,
                (true, false) => coverage.resets += 1,
                _ => {}
            }
            faulted = ours.fault.is_some();
        }
    }

    // The stimuli reach everything worth comparing.
    let missing: Vec<&str> = p
        .events
        .iter()
        .map(|e| e.name.as_str())
        .filter(|e| !coverage.events.contains(*e))
        .collect();
    assert!(
        missing.is_empty(),
        "{what}: events never executed: {missing:?}"
    );
    for (j, sup) in p.supervisors.iter().enumerate() {
        let a = &sup.automaton;
        let mut missing: Vec<String> = a
            .states()
            .filter(|s| !coverage.states.contains(&(j, s.0)))
            .map(|s| a.state_name(s).into_owned())
            .collect();
        missing.sort();
        assert_eq!(
            missing, g.never,
            "{what}: states of `{}` never entered",
            sup.name
        );
    }
    // A project can fault only on an uncontrollable event (the mixers'
    // transitions are all commands) and leave fault mode only by a reset.
    let can_fault = p.events.iter().any(|e| !e.controllable);
    assert!(
        !can_fault || coverage.faults > 0 && (p.reset.is_none() || coverage.resets > 0),
        "{what}: {} faults and {} resets; the stimuli should cause both",
        coverage.faults,
        coverage.resets
    );
}
