//! Random projects: [`ProjectSpec`] is plain data whose references are
//! indices resolved modulo the current counts by [`ProjectSpec::build`],
//! so that any shrunk value still builds a valid project; the strategies
//! that draw them, narrow ([`NARROW`]) or wide ([`WIDE`]); random Petri
//! nets added to a project.

use des::automaton::{EventId, StateId};
use des::AutomatonBuilder;
use plc_project::{
    Action, Drive, Event, EventGuard, Guarded, GuardedSource, Input, Net, NetSource, Origin,
    Output, Project, Supervisor, SupervisorSource, Timer, Trigger, Unexpected, COUNTER_BITS,
};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::Index as Pick;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Debug;
use std::ops::RangeInclusive;
use std::path::PathBuf;

/// Members per word of the executor's input images and event sets.
pub(crate) const WORD: usize = 32;

/// How many inputs and events the projects of a family have.
pub(crate) struct Shape {
    /// Inputs; the largest count is also the bits of an input flip mask.
    pub(crate) inputs: RangeInclusive<usize>,
    /// Events; the largest count is also the transition slots per state.
    pub(crate) events: RangeInclusive<usize>,
}

/// The first two families: every input image and event set fits in one
/// word.
pub(crate) const NARROW: Shape = Shape {
    inputs: 2..=5,
    events: 2..=8,
};

/// The wide family: input images and event sets of two or three words, so
/// that inputs and events 31, 32 and 33 always exist.
pub(crate) const WIDE: Shape = Shape {
    inputs: 33..=70,
    events: 33..=70,
};

// A wide flip mask is a u128.
const _: () = assert!(*WIDE.inputs.end() <= 128);

/// A timer preset: a multiple of the scan period or any small value.
#[derive(Debug, Clone, Copy)]
pub(crate) enum PresetSpec {
    Periods(u32),
    Millis(u32),
}

/// How an output is driven.
#[derive(Debug, Clone)]
pub(crate) enum DriveSpec {
    Actions {
        initial: bool,
    },
    /// (supervisor, states) entries of a state map.
    States(Vec<(Pick, Vec<Pick>)>),
}

/// An output: safe level and drive.
#[derive(Debug, Clone)]
pub(crate) struct OutputSpec {
    pub(crate) safe: bool,
    pub(crate) drive: DriveSpec,
}

/// The source of an uncontrollable event.
#[derive(Debug, Clone)]
pub(crate) enum TriggerSpec {
    Rising(Vec<Pick>),
    Falling(Vec<Pick>),
    /// A timer; the input is the fallback source when there are no timers.
    Expired(Pick, Pick),
}

/// An action; outputs are picked among the action-driven ones, and
/// timer actions are dropped when there are no timers.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ActionSpec {
    Set(Pick),
    Clear(Pick),
    Start(Pick),
    Reset(Pick),
}

/// An event; a controllable one ignores `trigger`, `when` and `unless`,
/// an uncontrollable one ignores `request`.
#[derive(Debug, Clone)]
pub(crate) struct EventSpec {
    pub(crate) controllable: bool,
    pub(crate) operator: bool,
    pub(crate) trigger: TriggerSpec,
    pub(crate) when: Vec<Pick>,
    pub(crate) unless: Vec<Pick>,
    pub(crate) request: Option<Pick>,
    pub(crate) actions: Vec<ActionSpec>,
}

/// The events a supervisor has, before more are added so that every
/// controllable event is in some alphabet.
#[derive(Debug, Clone)]
pub(crate) enum AlphabetSpec {
    /// The picked events.
    Picked(Vec<Pick>),
    /// Every event of the project.
    Every,
}

/// A supervisor: alphabet, initial state and transition rows.
#[derive(Debug, Clone)]
pub(crate) struct SupervisorSpec {
    pub(crate) alphabet: AlphabetSpec,
    pub(crate) initial: Pick,
    /// One row per state: the target on the i-th event of the (sorted)
    /// alphabet, if defined.
    pub(crate) rows: Vec<Vec<Option<Pick>>>,
}

/// A random project before it is built (see the module docs).
#[derive(Debug, Clone)]
pub(crate) struct ProjectSpec {
    pub(crate) scan_period_ms: u32,
    pub(crate) max_commands_per_scan: u16,
    pub(crate) unexpected: Unexpected,
    pub(crate) reset: Option<Pick>,
    /// The background image test's share per scan: a few words, so that
    /// passes complete (and compare) many times in a run.
    pub(crate) rom_test_bytes_per_scan: u16,
    /// `[plc] stored_sets_bytes`: 0 (every supervisor computes its allowed
    /// sets), a little (some store them) or plenty (all do).
    pub(crate) stored_sets_bytes: u32,
    pub(crate) debounce: Vec<u8>,
    pub(crate) timers: Vec<PresetSpec>,
    pub(crate) outputs: Vec<OutputSpec>,
    pub(crate) events: Vec<EventSpec>,
    pub(crate) supervisors: Vec<SupervisorSpec>,
}

/// `picks` resolved into `0..len`, duplicates dropped, order kept.
pub(crate) fn resolve(picks: &[Pick], len: usize) -> Vec<usize> {
    let mut out = Vec::new();
    for p in picks {
        let i = p.index(len);
        if !out.contains(&i) {
            out.push(i);
        }
    }
    out
}

impl ProjectSpec {
    /// The project this spec describes; valid by construction.
    pub(crate) fn build(&self) -> Project {
        let inputs = self.build_inputs();
        let timers = self.build_timers();
        let outputs = self.build_outputs();
        let action_driven: Vec<usize> = (0..outputs.len())
            .filter(|&o| matches!(outputs[o].drive, Drive::Actions { .. }))
            .collect();
        let sizes = Sizes {
            inputs: inputs.len(),
            timers: timers.len(),
            action_driven: &action_driven,
        };
        let events: Vec<Event> = self
            .events
            .iter()
            .enumerate()
            .map(|(e, spec)| build_event(e, spec, &sizes))
            .collect();
        let supervisors = self.build_supervisors(&events);
        Project {
            path: PathBuf::from("random.plc.toml"),
            name: "random".to_owned(),
            scan_period_ms: self.scan_period_ms,
            max_commands_per_scan: self.max_commands_per_scan,
            unexpected: self.unexpected,
            reset: self.reset.map(|r| r.index(inputs.len())),
            overrun_limit: 1,
            overrun_fault: false,
            lost_edge_fault: false,
            rom_test_bytes_per_scan: self.rom_test_bytes_per_scan,
            stored_sets_bytes: self.stored_sets_bytes,
            inputs,
            outputs,
            timers,
            switches: Vec::new(),
            events,
            supervisors,
            nets: Vec::new(),
            guarded: Vec::new(),
            board: None,
            warnings: Vec::new(),
            files: Vec::new(),
        }
    }

    pub(crate) fn build_inputs(&self) -> Vec<Input> {
        self.debounce
            .iter()
            .enumerate()
            .map(|(i, &d)| Input {
                name: format!("i{i}"),
                debounce_scans: d,
                line: 0,
            })
            .collect()
    }

    pub(crate) fn build_timers(&self) -> Vec<Timer> {
        self.timers
            .iter()
            .enumerate()
            .map(|(t, p)| Timer {
                name: format!("t{t}"),
                preset_ms: match *p {
                    PresetSpec::Periods(n) => n * self.scan_period_ms,
                    PresetSpec::Millis(ms) => ms,
                },
                line: 0,
            })
            .collect()
    }

    pub(crate) fn build_outputs(&self) -> Vec<Output> {
        let states: Vec<usize> = self.supervisors.iter().map(|s| s.rows.len()).collect();
        self.outputs
            .iter()
            .enumerate()
            .map(|(o, spec)| build_output(o, spec, &states))
            .collect()
    }

    /// The alphabets (sorted global event indices): the picked events, and
    /// every controllable event nobody picked goes to supervisor `e mod n`.
    pub(crate) fn alphabets(&self, events: &[Event]) -> Vec<Vec<usize>> {
        let mut sets: Vec<BTreeSet<usize>> = self
            .supervisors
            .iter()
            .map(|s| match &s.alphabet {
                AlphabetSpec::Picked(picked) => resolve(picked, events.len()).into_iter().collect(),
                AlphabetSpec::Every => (0..events.len()).collect(),
            })
            .collect();
        for (e, ev) in events.iter().enumerate() {
            if ev.controllable && !sets.iter().any(|s| s.contains(&e)) {
                let n = sets.len();
                sets[e % n].insert(e);
            }
        }
        sets.into_iter().map(|s| s.into_iter().collect()).collect()
    }

    pub(crate) fn build_supervisors(&self, events: &[Event]) -> Vec<Supervisor> {
        self.alphabets(events)
            .iter()
            .zip(&self.supervisors)
            .enumerate()
            .map(|(j, (alphabet, spec))| build_supervisor(j, spec, alphabet, events))
            .collect()
    }
}

/// Counts an event's references are resolved against.
pub(crate) struct Sizes<'a> {
    pub(crate) inputs: usize,
    pub(crate) timers: usize,
    pub(crate) action_driven: &'a [usize],
}

pub(crate) fn build_output(o: usize, spec: &OutputSpec, states: &[usize]) -> Output {
    let drive = match &spec.drive {
        DriveSpec::Actions { initial } => Drive::Actions { initial: *initial },
        DriveSpec::States(entries) => {
            // One entry per supervisor, as a TOML table gives them.
            let mut map: BTreeMap<usize, Vec<StateId>> = BTreeMap::new();
            for (sup, listed) in entries {
                let j = sup.index(states.len());
                let list = map.entry(j).or_default();
                for s in resolve(listed, states[j]) {
                    let s = StateId(s as u32);
                    if !list.contains(&s) {
                        list.push(s);
                    }
                }
            }
            Drive::States(map.into_iter().collect())
        }
    };
    Output {
        name: format!("o{o}"),
        safe: spec.safe,
        drive,
        line: 0,
    }
}

pub(crate) fn build_trigger(spec: &TriggerSpec, sizes: &Sizes<'_>) -> Trigger {
    match spec {
        TriggerSpec::Rising(list) => Trigger::Rising(resolve(list, sizes.inputs)),
        TriggerSpec::Falling(list) => Trigger::Falling(resolve(list, sizes.inputs)),
        TriggerSpec::Expired(_, input) if sizes.timers == 0 => {
            Trigger::Rising(vec![input.index(sizes.inputs)])
        }
        TriggerSpec::Expired(timer, _) => Trigger::Expired(timer.index(sizes.timers)),
    }
}

/// Actions in the validated order: clears, sets (never of a cleared
/// output), timer resets, timer starts; duplicates dropped.
pub(crate) fn build_actions(specs: &[ActionSpec], sizes: &Sizes<'_>) -> Vec<Action> {
    let (mut clears, mut sets, mut resets, mut starts) = (vec![], vec![], vec![], vec![]);
    let outputs = sizes.action_driven;
    for spec in specs {
        let (list, item) = match *spec {
            ActionSpec::Clear(p) if !outputs.is_empty() => {
                (&mut clears, outputs[p.index(outputs.len())])
            }
            ActionSpec::Set(p) if !outputs.is_empty() => {
                (&mut sets, outputs[p.index(outputs.len())])
            }
            ActionSpec::Reset(p) if sizes.timers > 0 => (&mut resets, p.index(sizes.timers)),
            ActionSpec::Start(p) if sizes.timers > 0 => (&mut starts, p.index(sizes.timers)),
            _ => continue,
        };
        if !list.contains(&item) {
            list.push(item);
        }
    }
    sets.retain(|o| !clears.contains(o));
    let mut actions: Vec<Action> = clears.into_iter().map(Action::Clear).collect();
    actions.extend(sets.into_iter().map(Action::Set));
    actions.extend(resets.into_iter().map(Action::Reset));
    actions.extend(starts.into_iter().map(Action::Start));
    actions
}

pub(crate) fn build_event(e: usize, spec: &EventSpec, sizes: &Sizes<'_>) -> Event {
    let actions = build_actions(&spec.actions, sizes);
    let name = format!("e{e}");
    if spec.controllable {
        return Event {
            name,
            controllable: true,
            origin: Origin::Controller,
            trigger: Trigger::Command,
            when: Vec::new(),
            unless: Vec::new(),
            request: spec.request.map(|r| r.index(sizes.inputs)),
            actions,
            line: 0,
        };
    }
    Event {
        name,
        controllable: false,
        origin: if spec.operator {
            Origin::Operator
        } else {
            Origin::Plant
        },
        trigger: build_trigger(&spec.trigger, sizes),
        when: resolve(&spec.when, sizes.inputs),
        unless: resolve(&spec.unless, sizes.inputs),
        request: None,
        actions,
        line: 0,
    }
}

pub(crate) fn build_supervisor(
    j: usize,
    spec: &SupervisorSpec,
    alphabet: &[usize],
    events: &[Event],
) -> Supervisor {
    let mut b = AutomatonBuilder::new(format!("s{j}"));
    let ids: Vec<EventId> = alphabet
        .iter()
        .map(|&e| {
            b.add_event(&events[e].name, events[e].controllable)
                .expect("fresh event")
        })
        .collect();
    let states: Vec<StateId> = spec.rows.iter().map(|_| b.add_anonymous_state()).collect();
    b.set_initial(states[spec.initial.index(states.len())])
        .expect("one initial state");
    for (s, row) in spec.rows.iter().enumerate() {
        for (slot, &id) in ids.iter().enumerate() {
            if let Some(target) = row[slot] {
                b.add_transition(states[s], id, states[target.index(states.len())], 0);
            }
        }
    }
    Supervisor {
        name: format!("s{j}"),
        automaton: b.build().expect("deterministic by construction"),
        local_events: alphabet.iter().copied().zip(ids).collect(),
        source: SupervisorSource::File(PathBuf::from(format!("s{j}.toml"))),
        line: 0,
        max_logic_effort: None,
    }
}

pub(crate) fn picks(len: RangeInclusive<usize>) -> impl Strategy<Value = Vec<Pick>> {
    vec(any::<Pick>(), len)
}

pub(crate) fn preset() -> impl Strategy<Value = PresetSpec> {
    prop_oneof![
        (1u32..=6).prop_map(PresetSpec::Periods),
        (1u32..=80).prop_map(PresetSpec::Millis),
    ]
}

pub(crate) fn output() -> impl Strategy<Value = OutputSpec> {
    let drive = prop_oneof![
        2 => any::<bool>().prop_map(|initial| DriveSpec::Actions { initial }),
        1 => vec((any::<Pick>(), picks(1..=3)), 1..=2).prop_map(DriveSpec::States),
    ];
    (any::<bool>(), drive).prop_map(|(safe, drive)| OutputSpec { safe, drive })
}

pub(crate) fn trigger() -> impl Strategy<Value = TriggerSpec> {
    prop_oneof![
        2 => picks(1..=3).prop_map(TriggerSpec::Rising),
        2 => picks(1..=3).prop_map(TriggerSpec::Falling),
        1 => (any::<Pick>(), any::<Pick>()).prop_map(|(t, i)| TriggerSpec::Expired(t, i)),
    ]
}

/// A `when`/`unless` list: mostly empty.
pub(crate) fn conditions() -> impl Strategy<Value = Vec<Pick>> {
    prop_oneof![3 => Just(Vec::new()), 1 => picks(1..=2)]
}

pub(crate) fn action() -> impl Strategy<Value = ActionSpec> {
    prop_oneof![
        any::<Pick>().prop_map(ActionSpec::Set),
        any::<Pick>().prop_map(ActionSpec::Clear),
        any::<Pick>().prop_map(ActionSpec::Start),
        any::<Pick>().prop_map(ActionSpec::Reset),
    ]
}

pub(crate) fn event() -> impl Strategy<Value = EventSpec> {
    (
        proptest::bool::weighted(0.4),
        any::<bool>(),
        trigger(),
        conditions(),
        conditions(),
        proptest::option::weighted(0.3, any::<Pick>()),
        vec(action(), 0..=3),
    )
        .prop_map(
            |(controllable, operator, trigger, when, unless, request, actions)| EventSpec {
                controllable,
                operator,
                trigger,
                when,
                unless,
                request,
                actions,
            },
        )
}

/// A supervisor of the narrow families: 1–5 picked events, a number of
/// states drawn from `states`, and about 60 % of the (state, event) pairs
/// with a transition.
pub(crate) fn supervisor(states: RangeInclusive<usize>) -> impl Strategy<Value = SupervisorSpec> {
    let alphabet = picks(1..=5).prop_map(AlphabetSpec::Picked);
    supervisor_over(&NARROW, alphabet, 0.6, states)
}

/// A supervisor of the wide family: a few events, many (usually more than
/// 32 distinct, so its rows are read in several slices) or every event.
/// About 80 % of the (state, event) pairs have a transition: a wide
/// project has many shared events, and sparser supervisors would leave
/// most runs in fault mode. 1–8 states: the narrow families cover larger
/// supervisors, and with 1–12 a wide case took about three times as long.
pub(crate) fn wide_supervisor() -> impl Strategy<Value = SupervisorSpec> {
    let alphabet = prop_oneof![
        2 => picks(1..=8).prop_map(AlphabetSpec::Picked),
        2 => picks(40..=90).prop_map(AlphabetSpec::Picked),
        1 => Just(AlphabetSpec::Every),
    ];
    supervisor_over(&WIDE, alphabet, 0.8, 1..=8)
}

/// A supervisor of the wide family whose rows repeat: 24–40 states, each
/// with one of 1–3 patterns of defined events (about 80 % of a row) over
/// many or every event, its targets random. Rows that repeat make the
/// table backend store them keyed, a dictionary of rows; with more than
/// 32 local events the rows of that dictionary are packed, not one a
/// word ([`executor::table::keyed_stride`]).
pub(crate) fn keyed_wide_supervisor() -> impl Strategy<Value = SupervisorSpec> {
    let alphabet = prop_oneof![
        picks(40..=90).prop_map(AlphabetSpec::Picked),
        Just(AlphabetSpec::Every),
    ];
    let events = *WIDE.events.end();
    let patterns = vec(vec(proptest::bool::weighted(0.8), events), 1..=3);
    let state = (any::<Pick>(), vec(any::<Pick>(), events));
    (alphabet, any::<Pick>(), patterns, vec(state, 24..=40)).prop_map(
        |(alphabet, initial, patterns, states)| SupervisorSpec {
            alphabet,
            initial,
            rows: states
                .into_iter()
                .map(|(pattern, targets)| {
                    let pattern = &patterns[pattern.index(patterns.len())];
                    pattern
                        .iter()
                        .zip(targets)
                        .map(|(&defined, target)| defined.then_some(target))
                        .collect()
                })
                .collect(),
        },
    )
}

/// A supervisor of a `shape` project over `alphabet`, with a transition
/// on each (state, event) pair with probability `defined`.
pub(crate) fn supervisor_over(
    shape: &Shape,
    alphabet: impl Strategy<Value = AlphabetSpec>,
    defined: f64,
    states: RangeInclusive<usize>,
) -> impl Strategy<Value = SupervisorSpec> {
    let row = vec(
        proptest::option::weighted(defined, any::<Pick>()),
        *shape.events.end(),
    );
    (alphabet, any::<Pick>(), vec(row, states)).prop_map(|(alphabet, initial, rows)| {
        SupervisorSpec {
            alphabet,
            initial,
            rows,
        }
    })
}

/// Random `shape` projects with 1–4 supervisors drawn from `supervisor`.
pub(crate) fn project(
    shape: &Shape,
    supervisor: impl Strategy<Value = SupervisorSpec>,
) -> impl Strategy<Value = ProjectSpec> {
    (
        1u32..=20,
        0u16..=3,
        prop_oneof![Just(Unexpected::Fault), Just(Unexpected::Ignore)],
        proptest::option::weighted(0.85, any::<Pick>()),
        (1u16..=16).prop_map(|words| 4 * words),
        prop_oneof![Just(0u32), Just(24), Just(4096)],
        vec(0u8..=3, shape.inputs.clone()),
        vec(preset(), 0..=3),
        vec(output(), 1..=5),
        vec(event(), shape.events.clone()),
        vec(supervisor, 1..=4),
    )
        .prop_map(
            |(
                period,
                max,
                unexpected,
                reset,
                rom_test_bytes_per_scan,
                stored_sets_bytes,
                debounce,
                timers,
                outputs,
                events,
                supervisors,
            )| {
                ProjectSpec {
                    scan_period_ms: period,
                    max_commands_per_scan: max,
                    unexpected,
                    reset,
                    rom_test_bytes_per_scan,
                    stored_sets_bytes,
                    debounce,
                    timers,
                    outputs,
                    events,
                    supervisors,
                }
            },
        )
}

/// Adds one or two random Petri nets to `project`, from `seed`: 2–6
/// places holding 0–2 tokens each, the transitions a random subset of the
/// events (each with its event's controllability), every transition
/// taking one or two arcs of weight 1–2 and giving back as many tokens
/// (so every net is bounded; weights of 2 make counters of two or more
/// bits), and one new output per net driven by a place map of one or two
/// places. The counters are laid out as `[[net]]` lays them out, from the
/// bounds of the reachability graph.
pub(crate) fn add_random_nets(project: &mut Project, seed: u64) {
    use des::petri::{reach, NetBuilder};
    use des::Location;
    let mut state = seed | 1;
    let mut next = move |n: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n as u64) as usize
    };
    let at = || Location::new("random.net.toml", 1, 1);
    for k in 0..1 + next(2) {
        let places = 2 + next(5);
        let mut b = NetBuilder::new(format!("n{k}"));
        for p in 0..places {
            b.add_place(&format!("p{p}"), None, next(3) as u32, at())
                .expect("place");
        }
        let mut events = Vec::new();
        for (e, ev) in project.events.iter().enumerate() {
            if next(2) == 0 {
                continue;
            }
            b.add_transition(&ev.name, None, ev.controllable, true, at())
                .expect("transition");
            // As many tokens out as in, spread over one or two places
            // each way (one arc per place: weights add up).
            let tokens = 1 + next(2) as u32;
            let arcs = |next: &mut dyn FnMut(usize) -> usize| {
                let mut weights = vec![0u32; places];
                for _ in 0..tokens {
                    weights[next(places)] += 1;
                }
                weights
            };
            let input = arcs(&mut next);
            let output = arcs(&mut next);
            for p in 0..places {
                if input[p] > 0 {
                    b.add_arc(&format!("p{p}"), &ev.name, input[p], at())
                        .expect("input arc");
                }
                if output[p] > 0 {
                    b.add_arc(&ev.name, &format!("p{p}"), output[p], at())
                        .expect("output arc");
                }
            }
            events.push(e);
        }
        let net = b.build();
        let bounds = reach::reachability(&net, 100_000).expect("bounded").bounds;
        assert!(
            Net::counter_widths(&net, &bounds)
                .iter()
                .all(|&w| w <= COUNTER_BITS),
            "counters fit"
        );
        let n = project.nets.len();
        let mapped: Vec<usize> = (0..1 + next(2)).map(|_| next(places)).collect();
        project.outputs.push(Output {
            name: format!("net{n}_out"),
            safe: next(2) == 0,
            drive: Drive::Places(vec![(n, mapped)]),
            line: 0,
        });
        project.nets.push(Net {
            name: format!("n{k}"),
            events,
            bounds,
            markings: 0,
            control_places: 0,
            source: NetSource::File("random.net.toml".into()),
            line: 0,
            net,
        });
    }
}

/// Makes the last supervisors of `project` (one or more, from `seed`) the
/// components of a symbolic supervisor with random guards: each
/// controllable event guarded or not, a guard a random decision diagram
/// of up to 8 nodes (children first, as guard files have them) over the
/// components' state bits, laid out as a guard file lays them out (each
/// component's bits most significant first). A project without
/// supervisors is left as it is.
pub(crate) fn add_random_guards(project: &mut Project, seed: u64) {
    let supervisors = project.supervisors.len();
    if supervisors == 0 {
        return;
    }
    let mut state = seed | 1;
    let mut next = move |n: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n.max(1) as u64) as usize
    };
    let first = supervisors - 1 - next(supervisors);
    let mut bits = Vec::new();
    for j in first..supervisors {
        let states = project.supervisors[j].automaton.num_states() as u32;
        let width = u32::BITS - states.saturating_sub(1).leading_zeros();
        for k in 0..width {
            bits.push((j, width - 1 - k));
        }
    }
    let mut guards = Vec::new();
    for (e, ev) in project.events.iter().enumerate() {
        if !ev.controllable || next(3) == 0 {
            continue;
        }
        let count = if bits.is_empty() { 0 } else { next(9) };
        let nodes: Vec<[u32; 3]> = (0..count)
            .map(|i| {
                let at = i + 2;
                [next(bits.len()) as u32, next(at) as u32, next(at) as u32]
            })
            .collect();
        // Mostly the last node (a table's root); now and then a constant
        // or an inner node.
        let root = match next(6) {
            0 => next(count + 2),
            _ => count + 1,
        } as u32;
        guards.push(EventGuard {
            event: e,
            text: format!("random guard of event {e}"),
            root: if count == 0 { root.min(1) } else { root },
            nodes,
        });
    }
    for j in first..supervisors {
        project.supervisors[j].source = SupervisorSource::Component {
            guarded: "g".to_owned(),
            file: "random.toml".into(),
        };
    }
    project.guarded.push(Guarded {
        name: "g".to_owned(),
        components: first..supervisors,
        bits,
        guards,
        closed_loop_states: "0".to_owned(),
        source: GuardedSource::File("random.guards.toml".into()),
        line: 0,
    });
}
