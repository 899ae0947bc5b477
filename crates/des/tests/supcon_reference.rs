//! supcon against a straightforward reference: the full product
//! `plant ‖ spec` (built by `compose`, nothing pruned), the textbook
//! fixpoint on it, and the good part the initial state reaches.
//!
//! supcon itself never expands a state where the specification disables an
//! uncontrollable plant event (`ops/supcon/product.rs`). The two must give
//! the same supervisor: the same states with the same names, marking and
//! transitions, in the same order. supcon numbers states in the
//! breadth-first order of that pruned search; the reference computes the
//! order from the full product by the same search, so any state missing,
//! extra or out of place shows.

use des::ops::{compose, supcon, supcon_with, sync, ComposeOptions, Composition};
use des::{Automaton, AutomatonBuilder, StateId};
use proptest::prelude::*;
use std::collections::VecDeque;

/// A supervisor as written to a file: per state in order its name,
/// marking and transitions `(event name, target index)`.
type Listing = Vec<(String, bool, Vec<(String, u32)>)>;

fn listing(a: &Automaton) -> Listing {
    a.states()
        .map(|s| {
            let row = a
                .transitions(s)
                .iter()
                .map(|t| (a.alphabet().name(t.event).to_owned(), t.target.0))
                .collect();
            (a.state_name(s).into_owned(), a.is_marked(s), row)
        })
        .collect()
}

/// supcon the textbook way on the full product, in the order of the
/// pruned breadth-first search.
fn reference(plant: &Automaton, spec: &Automaton) -> Listing {
    let product = compose(&[plant, spec], Composition::Sync, ComposeOptions::default()).unwrap();
    let p = &product.automaton;
    let n = p.num_states();
    let Some(init) = p.initial() else {
        return Vec::new();
    };
    let uncontrollable = |e: &str| {
        !plant
            .alphabet()
            .is_controllable(plant.alphabet().id(e).unwrap())
    };
    let succ = |s: usize, e: &str| {
        p.alphabet()
            .id(e)
            .and_then(|id| p.successor(StateId(s as u32), id))
            .map(|t| t.index())
    };
    // Bad at once: the plant can do an uncontrollable event the product
    // cannot.
    let bad_at_once: Vec<bool> = (0..n)
        .map(|s| {
            let g = product.component_state(StateId(s as u32), 0);
            plant.transitions(g).iter().any(|t| {
                let e = plant.alphabet().name(t.event);
                uncontrollable(e) && succ(s, e).is_none()
            })
        })
        .collect();
    let mut bad = bad_at_once.clone();
    loop {
        let mut changed = false;
        // Uncontrollable transitions into bad states.
        loop {
            let mut more = false;
            for s in 0..n {
                if !bad[s]
                    && p.transitions(StateId(s as u32)).iter().any(|t| {
                        uncontrollable(p.alphabet().name(t.event)) && bad[t.target.index()]
                    })
                {
                    bad[s] = true;
                    more = true;
                    changed = true;
                }
            }
            if !more {
                break;
            }
        }
        // Good states that reach no good marked state through good ones.
        let mut co: Vec<bool> = (0..n)
            .map(|s| !bad[s] && p.is_marked(StateId(s as u32)))
            .collect();
        loop {
            let mut more = false;
            for s in 0..n {
                if !bad[s]
                    && !co[s]
                    && p.transitions(StateId(s as u32))
                        .iter()
                        .any(|t| co[t.target.index()])
                {
                    co[s] = true;
                    more = true;
                }
            }
            if !more {
                break;
            }
        }
        for s in 0..n {
            if !bad[s] && !co[s] {
                bad[s] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    if bad[init.index()] {
        return Vec::new();
    }
    // The order: breadth-first from the initial state, expanding no state
    // that is bad at once; transitions in event order.
    let mut rank = vec![u32::MAX; n];
    let mut next_rank = 0;
    let mut queue = VecDeque::from([init.index()]);
    rank[init.index()] = 0;
    next_rank += 1;
    while let Some(s) = queue.pop_front() {
        if bad_at_once[s] {
            continue;
        }
        for t in p.transitions(StateId(s as u32)) {
            if rank[t.target.index()] == u32::MAX {
                rank[t.target.index()] = next_rank;
                next_rank += 1;
                queue.push_back(t.target.index());
            }
        }
    }
    // The good states reached through good states.
    let mut keep = vec![false; n];
    keep[init.index()] = true;
    let mut stack = vec![init.index()];
    while let Some(s) = stack.pop() {
        for t in p.transitions(StateId(s as u32)) {
            let t = t.target.index();
            if !bad[t] && !keep[t] {
                keep[t] = true;
                stack.push(t);
            }
        }
    }
    let mut kept: Vec<usize> = (0..n).filter(|&s| keep[s]).collect();
    kept.sort_by_key(|&s| rank[s]);
    let mut new_id = vec![u32::MAX; n];
    for (i, &s) in kept.iter().enumerate() {
        new_id[s] = i as u32;
    }
    kept.iter()
        .map(|&s| {
            let s = StateId(s as u32);
            let row = p
                .transitions(s)
                .iter()
                .filter(|t| keep[t.target.index()])
                .map(|t| {
                    (
                        p.alphabet().name(t.event).to_owned(),
                        new_id[t.target.index()],
                    )
                })
                .collect();
            (p.state_name(s).into_owned(), p.is_marked(s), row)
        })
        .collect()
}

/// A random deterministic automaton over `events` (`(name,
/// controllable)`), states named `{prefix}{i}`, state 0 initial.
fn random(
    name: &str,
    prefix: &str,
    events: &[(&str, bool)],
    states: usize,
    delta: &[Option<usize>],
    marked: &[bool],
) -> Automaton {
    let mut b = AutomatonBuilder::new(name);
    for &(e, c) in events {
        b.add_event(e, c).unwrap();
    }
    let ids: Vec<_> = (0..states)
        .map(|i| b.add_state(&format!("{prefix}{i}")))
        .collect();
    b.set_initial(ids[0]).unwrap();
    for (i, &m) in marked.iter().take(states).enumerate() {
        if m {
            b.mark(ids[i]);
        }
    }
    let k = events.len();
    for s in 0..states {
        for (j, &(e, _)) in events.iter().enumerate() {
            if let Some(t) = delta[s * k + j] {
                let id = b.alphabet().id(e).unwrap();
                b.add_transition(ids[s], id, ids[t % states], 0);
            }
        }
    }
    b.build().unwrap()
}

const EVENTS: [(&str, bool); 6] = [
    ("a", true),
    ("b", true),
    ("c", true),
    ("u", false),
    ("v", false),
    ("w", false),
];

/// Two plant components over all events and a specification over some.
fn instance() -> impl Strategy<Value = (Automaton, Automaton)> {
    let component = |n: usize, k: usize| {
        (
            proptest::collection::vec(proptest::option::weighted(0.6, 0..n), n * k),
            proptest::collection::vec(any::<bool>(), n),
        )
    };
    (
        2usize..6,
        2usize..5,
        1usize..5,
        proptest::sample::subsequence(EVENTS.to_vec(), 2..=6),
    )
        .prop_flat_map(move |(n1, n2, ns, spec_events)| {
            (
                component(n1, 6),
                component(n2, 6),
                component(ns, spec_events.len()),
                Just((n1, n2, ns, spec_events)),
            )
        })
        .prop_map(
            |((d1, m1), (d2, m2), (ds, ms), (n1, n2, ns, spec_events))| {
                let g1 = random("G1", "p", &EVENTS, n1, &d1, &m1);
                let g2 = random("G2", "q", &EVENTS[..3], n2, &d2[..n2 * 3], &m2);
                let plant = sync(&[&g1, &g2]).unwrap();
                let spec = random("E", "e", &spec_events, ns, &ds, &ms);
                (plant, spec)
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]

    /// The pruned supcon is the reference's supervisor, state for state
    /// (names, marking, transitions, order), named or numbered.
    #[test]
    fn pruned_supcon_is_the_full_products_supervisor((plant, spec) in instance()) {
        let sup = supcon(&plant, &spec).unwrap();
        let expected = reference(&plant, &spec);
        prop_assert_eq!(listing(&sup), expected.clone());
        prop_assert_eq!(sup.initial().is_some(), !expected.is_empty());
        let options = ComposeOptions { name_states: false, ..ComposeOptions::default() };
        let numbered = supcon_with(&plant, &spec, options).unwrap();
        prop_assert!(!numbered.has_state_names() || numbered.is_empty());
        prop_assert_eq!(numbered.offsets(), sup.offsets());
        prop_assert_eq!(numbered.edges(), sup.edges());
        prop_assert_eq!(numbered.marked(), sup.marked());
    }
}
