//! Algebraic properties of the operations on random small automata:
//! minimisation, composition, synthesis, trimming and the controllability
//! check with its witness.
//!
//! Automata are drawn by [`automaton_over`] over a fixed pool of events
//! whose controllability never changes (so any two of them compose), with
//! a partial deterministic transition function and random marking.

use des::ops::{
    accessible, check_controllable, check_nonblocking, inverse_projection, is_trim, isomorphic,
    language_difference, language_equal, meet, minstate, supcon, sync, trim,
};
use des::{Automaton, AutomatonBuilder, StateId};
use proptest::prelude::*;
use proptest::sample::{subsequence, Index};
use std::collections::VecDeque;

/// The event pool: name and controllability, fixed per name.
const POOL: [(&str, bool); 6] = [
    ("a", true),
    ("b", true),
    ("c", true),
    ("u", false),
    ("v", false),
    ("w", false),
];

/// A random deterministic automaton before it is built: states `0..n`
/// (initial state 0), events as indices into [`POOL`], and for each state
/// and event (row-major) the target, if any.
#[derive(Debug, Clone)]
struct Raw {
    events: Vec<usize>,
    marked: Vec<bool>,
    delta: Vec<Option<usize>>,
}

impl Raw {
    fn states(&self) -> usize {
        self.marked.len()
    }

    /// The transitions as `(source, pool event, target)`.
    fn transitions(&self) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        let k = self.events.len();
        self.delta
            .iter()
            .enumerate()
            .filter_map(move |(i, t)| t.map(|t| (i / k, self.events[i % k], t)))
    }

    fn build(&self, name: &str) -> Automaton {
        self.build_with(name, false, |_, _| true)
    }

    /// Builds the automaton; `all_controllable` turns every event
    /// controllable, `keep(source, pool event)` filters transitions.
    fn build_with(
        &self,
        name: &str,
        all_controllable: bool,
        keep: impl Fn(usize, usize) -> bool,
    ) -> Automaton {
        let mut b = AutomatonBuilder::new(name);
        let ids: Vec<_> = self
            .events
            .iter()
            .map(|&e| {
                let (n, c) = POOL[e];
                (e, b.add_event(n, c || all_controllable).unwrap())
            })
            .collect();
        let states: Vec<StateId> = (0..self.states())
            .map(|_| b.add_anonymous_state())
            .collect();
        b.set_initial(states[0]).unwrap();
        for (s, &m) in self.marked.iter().enumerate() {
            if m {
                b.mark(states[s]);
            }
        }
        for (s, e, t) in self.transitions() {
            if keep(s, e) {
                let id = ids.iter().find(|x| x.0 == e).unwrap().1;
                b.add_transition(states[s], id, states[t], 0);
            }
        }
        b.build().unwrap()
    }
}

/// How [`automaton_over`] draws transitions and marking.
#[derive(Debug, Clone, Copy)]
struct Shape {
    /// Chance of a transition on a controllable event.
    controllable: f64,
    /// Chance of a transition on an uncontrollable event.
    uncontrollable: f64,
    /// Chance that a state is marked is one of these.
    marking: &'static [f64],
    /// Chance that the initial state is marked.
    initial_marked: f64,
    /// No uncontrollable transitions leave the initial state.
    resting: bool,
}

/// Anything goes: some automata mark nothing, many block.
const WILD: Shape = Shape {
    controllable: 0.6,
    uncontrollable: 0.6,
    marking: &[0.0, 0.2, 0.4, 0.7],
    initial_marked: 0.4,
    resting: false,
};

/// Plants where control has choices: marked initial state without
/// uncontrollable moves, mostly marked states, uncontrollable events rarer.
const PLANT: Shape = Shape {
    controllable: 0.7,
    uncontrollable: 0.45,
    marking: &[0.3, 0.6, 1.0],
    initial_marked: 0.95,
    resting: true,
};

/// Specifications that often forbid something uncontrollable.
const SPEC: Shape = Shape {
    controllable: 0.8,
    uncontrollable: 0.5,
    marking: &[0.5, 0.8, 1.0],
    initial_marked: 0.9,
    resting: false,
};

/// Random automata over exactly `events` with 1 to `max_states` states.
fn automaton_over(
    events: Vec<usize>,
    max_states: usize,
    shape: Shape,
) -> impl Strategy<Value = Raw> {
    (1..=max_states, proptest::sample::select(shape.marking)).prop_flat_map(move |(n, marking)| {
        let k = events.len();
        let cells: Vec<_> = (0..n * k)
            .map(|i| {
                let controllable = POOL[events[i % k]].1;
                let p = match (controllable, shape.resting && i < k) {
                    (true, _) => shape.controllable,
                    (false, true) => 0.0,
                    (false, false) => shape.uncontrollable,
                };
                (proptest::bool::weighted(p), 0..n).prop_map(|(some, t)| some.then_some(t))
            })
            .collect();
        (
            Just(events.clone()),
            proptest::bool::weighted(shape.initial_marked),
            proptest::collection::vec(proptest::bool::weighted(marking), n - 1),
            cells,
        )
            .prop_map(|(events, first, rest, delta)| Raw {
                events,
                marked: std::iter::once(first).chain(rest).collect(),
                delta,
            })
    })
}

/// A non-empty subset of the pool, in pool order.
fn events() -> impl Strategy<Value = Vec<usize>> {
    subsequence((0..POOL.len()).collect::<Vec<_>>(), 1..=POOL.len())
}

/// Random automata over a random subset of the pool.
fn automaton(max_states: usize) -> impl Strategy<Value = Raw> {
    events().prop_flat_map(move |e| automaton_over(e, max_states, WILD))
}

/// Random automata with many equivalent states: 2 or 3 copies of a small
/// automaton, each transition going to a random copy of its target.
fn unfolded(base_states: usize) -> impl Strategy<Value = Raw> {
    (automaton(base_states), 2..=3usize)
        .prop_flat_map(|(base, copies)| {
            let cells = base.delta.len() * copies;
            (
                Just(base),
                Just(copies),
                proptest::collection::vec(0..copies, cells),
            )
        })
        .prop_map(|(base, copies, choice)| {
            let n = base.states();
            let delta = choice
                .iter()
                .enumerate()
                .map(|(i, &c)| base.delta[i % base.delta.len()].map(|t| t + c * n))
                .collect();
            Raw {
                events: base.events,
                marked: base.marked.repeat(copies),
                delta,
            }
        })
}

/// A subset of the pool with at least one uncontrollable event.
fn plant_events() -> impl Strategy<Value = Vec<usize>> {
    events().prop_map(|mut e| {
        if e.iter().all(|&i| POOL[i].1) {
            e.push(3); // "u"
        }
        e
    })
}

/// `raw` with a trap: a new unmarked state without transitions, entered
/// from state `from` by the first uncontrollable event.
fn with_trap(raw: &Raw, from: Index) -> Raw {
    let n = raw.states();
    let k = raw.events.len();
    let Some(j) = raw.events.iter().position(|&e| !POOL[e].1) else {
        return raw.clone();
    };
    let mut delta = raw.delta.clone();
    delta[from.index(n) * k + j] = Some(n);
    delta.extend(std::iter::repeat_n(None, k));
    let mut marked = raw.marked.clone();
    marked.push(false);
    Raw {
        events: raw.events.clone(),
        marked,
        delta,
    }
}

/// A plant with at least one uncontrollable event and a specification over
/// a subset of its events.
fn plant_and_spec() -> impl Strategy<Value = (Raw, Raw)> {
    plant_events().prop_flat_map(|e| {
        // The specification mentions an uncontrollable event of the
        // plant: one that says nothing about them rarely needs control.
        let u = *e.iter().find(|&&i| !POOL[i].1).unwrap();
        let sub = subsequence(e.clone(), 1..=e.len()).prop_map(move |mut s| {
            if !s.contains(&u) {
                s.push(u);
                s.sort_unstable();
            }
            s
        });
        (
            automaton_over(e, 6, PLANT),
            sub.prop_flat_map(|s| automaton_over(s, 4, SPEC)),
        )
    })
}

/// The state `path` leads to from the initial state, if it is a string of
/// `a`.
fn replay(a: &Automaton, path: &[String]) -> Option<StateId> {
    let mut s = a.initial()?;
    for e in path {
        s = a.successor(s, a.alphabet().id(e)?)?;
    }
    Some(s)
}

/// `a` with its initial state moved to `s` (for comparing the futures of
/// two states).
fn started_at(a: &Automaton, s: StateId) -> Automaton {
    let mut b = AutomatonBuilder::new("at");
    for (_, e) in a.alphabet().iter() {
        b.add_event(&e.name, e.controllable).unwrap();
    }
    let states: Vec<StateId> = a.states().map(|_| b.add_anonymous_state()).collect();
    b.set_initial(states[s.index()]).unwrap();
    for m in a.marked_states() {
        b.mark(states[m.index()]);
    }
    for (p, e, q) in a.iter_transitions() {
        b.add_transition(states[p.index()], e, states[q.index()], 0);
    }
    b.build().unwrap()
}

/// The one-state automaton that marks everything (no events: `supcon`
/// self-loops the plant's).
fn everything() -> Automaton {
    let mut b = AutomatonBuilder::new("ALL");
    let s = b.add_state("0");
    b.set_initial(s).unwrap();
    b.mark(s);
    b.build().unwrap()
}

/// Breadth-first tree from the initial state: for each reached state, the
/// `(parent, pool event)` it was first reached by (`None` for the root).
fn bfs_tree(raw: &Raw) -> Vec<Option<Option<(usize, usize)>>> {
    let mut parent = vec![None; raw.states()];
    parent[0] = Some(None);
    let mut queue = VecDeque::from([0]);
    let k = raw.events.len();
    while let Some(s) = queue.pop_front() {
        for j in 0..k {
            if let Some(t) = raw.delta[s * k + j] {
                if parent[t].is_none() {
                    parent[t] = Some(Some((s, raw.events[j])));
                    queue.push_back(t);
                }
            }
        }
    }
    parent
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    /// (a) minstate keeps both languages, is minimal (no two result states
    /// have the same future), canonical (equal languages give isomorphic
    /// results) and idempotent, and never grows the accessible part.
    #[test]
    fn minstate_is_language_preserving_minimal_and_idempotent(
        raw in prop_oneof![automaton(7), unfolded(4)],
    ) {
        let a = raw.build("A");
        let m = minstate(&a);
        prop_assert_eq!(language_difference(&a, &m), None);
        prop_assert!(m.num_states() <= accessible(&a).num_states());
        prop_assert!(isomorphic(&m, &minstate(&m)), "not idempotent");
        // sync(a, a) has the same languages and a different state set.
        prop_assert!(isomorphic(&m, &minstate(&sync(&[&a, &a]).unwrap())), "not canonical");
        for p in m.states() {
            for q in m.states().filter(|&q| q > p) {
                prop_assert!(
                    !language_equal(&started_at(&m, p), &started_at(&m, q)),
                    "states {} and {} of the result are equivalent", p, q
                );
            }
        }
    }

    /// (b) sync is commutative up to isomorphism, associative (up to
    /// language equality, and in fact up to isomorphism), and idempotent
    /// on the accessible part.
    #[test]
    fn sync_is_commutative_and_associative(
        a in automaton(4),
        b in automaton(4),
        c in automaton(4),
    ) {
        let (a, b, c) = (a.build("A"), b.build("B"), c.build("C"));
        let ab = sync(&[&a, &b]).unwrap();
        prop_assert!(isomorphic(&ab, &sync(&[&b, &a]).unwrap()), "not commutative");
        let left = sync(&[&ab, &c]).unwrap();
        let right = sync(&[&a, &sync(&[&b, &c]).unwrap()]).unwrap();
        let flat = sync(&[&a, &b, &c]).unwrap();
        prop_assert_eq!(language_difference(&left, &right), None);
        prop_assert_eq!(language_difference(&left, &flat), None);
        prop_assert!(isomorphic(&left, &right) && isomorphic(&left, &flat));
        prop_assert!(isomorphic(&sync(&[&a, &a]).unwrap(), &accessible(&a)));
    }

    /// (c) supcon is controllable, nonblocking, trim, inside the plant and
    /// the specification, and a fixed point: synthesising against the
    /// result gives the result again.
    #[test]
    fn supcon_is_controllable_nonblocking_and_within_the_spec(
        (plant, spec) in plant_and_spec(),
    ) {
        let (plant, spec) = (plant.build("G"), spec.build("E"));
        let sup = supcon(&plant, &spec).unwrap();
        prop_assert_eq!(check_controllable(&plant, &sup).unwrap(), None);
        prop_assert_eq!(check_nonblocking(&sup), None);
        prop_assert!(is_trim(&sup));
        let spec_ext = inverse_projection(&spec, plant.alphabet()).unwrap();
        prop_assert_eq!(language_difference(&meet(&[&sup, &spec_ext]).unwrap(), &sup), None);
        prop_assert_eq!(language_difference(&meet(&[&sup, &plant]).unwrap(), &sup), None);
        prop_assert_eq!(language_difference(&supcon(&plant, &sup).unwrap(), &sup), None);
    }

    /// (c) With a specification that allows everything, supcon is the
    /// plant's trim part exactly when that part is controllable (else
    /// uncontrollable events into blocking states cut more), and always
    /// when every event is controllable.
    #[test]
    fn supcon_of_everything_is_the_trim_plant_when_that_is_controllable(
        raw in prop_oneof![
            automaton(6),
            plant_events().prop_flat_map(|e| automaton_over(e, 6, PLANT)),
        ],
        trap in proptest::option::of(any::<Index>()),
    ) {
        let raw = match trap {
            Some(from) => with_trap(&raw, from),
            None => raw,
        };
        let plant = raw.build("G");
        let sup = supcon(&plant, &everything()).unwrap();
        let t = trim(&plant);
        let controllable = check_controllable(&plant, &t).unwrap().is_none();
        prop_assert_eq!(language_equal(&sup, &t), controllable);
        let free = raw.build_with("G", true, |_, _| true);
        let sup = supcon(&free, &everything()).unwrap();
        prop_assert_eq!(language_difference(&sup, &trim(&free)), None);
    }

    /// (d) trim results are trim, have the states a naive count expects
    /// and the languages of the trimmed minimal automaton, and trimming
    /// again changes nothing; minimising a trim automaton keeps it trim.
    #[test]
    fn trim_results_are_trim(raw in automaton(7)) {
        let a = raw.build("A");
        let t = trim(&a);
        prop_assert!(is_trim(&t));
        prop_assert!(isomorphic(&t, &trim(&t)));
        prop_assert!(is_trim(&minstate(&t)));
        // Same marked language: trimming the minimal automaton gives an
        // automaton with the same languages as trimming the original.
        prop_assert_eq!(language_difference(&t, &trim(&minstate(&a))), None);
        // As many states as a naive count of the reachable states that
        // reach a marked state.
        let naive = a
            .states()
            .filter(|&s| {
                a.initial().is_some_and(|i| reaches(&a, i, s))
                    && a.marked_states().any(|m| reaches(&a, s, m))
            })
            .count();
        prop_assert_eq!(t.num_states(), naive);
    }

    /// (e) check_controllable accepts supcon's result and catches a
    /// sub-automaton of the plant that cuts an uncontrollable transition,
    /// with a witness that replays on both automata to a state where the
    /// plant has the event and the supervisor does not. When the other cuts
    /// are all controllable, the cut transition is the only violation, and
    /// the witness must name it.
    #[test]
    fn controllability_witnesses_replay(
        (plant_raw, spec_raw) in plant_and_spec(),
        pick in any::<Index>(),
        cuts in proptest::collection::vec(proptest::bool::weighted(0.3), 64),
        only_controllable_cuts in any::<bool>(),
    ) {
        let plant = plant_raw.build("G");
        let spec = spec_raw.build("E");
        let sup = supcon(&plant, &spec).unwrap();
        prop_assert_eq!(check_controllable(&plant, &sup).unwrap(), None);

        // A reachable uncontrollable transition (s, u) to cut; the
        // breadth-first path to s stays, so s stays reachable.
        let tree = bfs_tree(&plant_raw);
        let candidates: Vec<(usize, usize)> = plant_raw
            .transitions()
            .filter(|&(s, e, _)| !POOL[e].1 && tree[s].is_some())
            .map(|(s, e, _)| (s, e))
            .collect();
        if candidates.is_empty() {
            return Ok(()); // about a third of the plants; no need to reject
        }
        let (s, u) = candidates[pick.index(candidates.len())];
        let mut path_edges = Vec::new();
        let mut x = s;
        while let Some(Some((p, e))) = tree[x] {
            path_edges.push((p, e));
            x = p;
        }
        let depth = path_edges.len();
        // Other transitions go at random, except those on the path.
        let sub = plant_raw.build_with("S", false, |p, e| {
            let cut = cuts[(p * POOL.len() + e) % cuts.len()]
                && !path_edges.contains(&(p, e))
                && (POOL[e].1 || !only_controllable_cuts);
            (p, e) != (s, u) && !cut
        });

        let w = check_controllable(&plant, &sub).unwrap();
        prop_assert!(w.is_some(), "cut of ({}, {}) not reported", s, POOL[u].0);
        let w = w.unwrap();
        prop_assert!(w.path.len() <= depth, "witness {:?} longer than {}", w.path, depth);
        let g = replay(&plant, &w.path);
        let x = replay(&sub, &w.path);
        prop_assert!(g.is_some() && x.is_some(), "path {:?} does not replay", w.path);
        let (g, x) = (g.unwrap(), x.unwrap());
        let e = plant.alphabet().id(&w.event).unwrap();
        prop_assert!(!plant.alphabet().is_controllable(e));
        prop_assert!(plant.successor(g, e).is_some(), "plant cannot do {}", w.event);
        prop_assert!(
            sub.successor(x, sub.alphabet().id(&w.event).unwrap()).is_none(),
            "supervisor can do {}", w.event
        );
        prop_assert_eq!(&w.plant_state, &plant.state_name(g));
        prop_assert_eq!(&w.supervisor_state, &sub.state_name(x));
        if only_controllable_cuts {
            prop_assert_eq!((g.index(), w.event.as_str()), (s, POOL[u].0));
            prop_assert_eq!(x.index(), s);
        }
    }
}

/// Whether `to` is reachable from `from` in `a`.
fn reaches(a: &Automaton, from: StateId, to: StateId) -> bool {
    let mut seen = vec![false; a.num_states()];
    let mut stack = vec![from];
    seen[from.index()] = true;
    while let Some(s) = stack.pop() {
        if s == to {
            return true;
        }
        for t in a.transitions(s) {
            if !seen[t.target.index()] {
                seen[t.target.index()] = true;
                stack.push(t.target);
            }
        }
    }
    false
}
