//! `check_observable` against the definition itself (Lin and Wonham 1988),
//! evaluated by brute force: every string of the plant up to a length is
//! enumerated, those of K grouped by their projection, and every pair of
//! look-alikes s, s' and controllable σ with sσ ∈ K, s'σ ∈ L, s'σ ∉ K is
//! a violation. On small random plants and languages:
//!
//! - a violation found by brute force means ours reports one;
//! - ours reports a valid one (its strings replayed on the automata), and
//!   when it is short enough to be enumerated, brute force finds one too.

use des::ops::check_observable;
use des::{Automaton, AutomatonBuilder, StateId};
use proptest::prelude::*;
use std::collections::HashMap;

/// Events: name and controllability.
const EVENTS: [(&str, bool); 4] = [("a", true), ("b", true), ("u", false), ("c", true)];
/// Strings up to this length are enumerated.
const DEPTH: usize = 5;

/// A random deterministic automaton: for each state and event a target or
/// none, some states marked; initial state 0.
fn automaton(name: &str, states: usize, delta: &[Option<usize>]) -> Automaton {
    let mut b = AutomatonBuilder::new(name);
    for (e, c) in EVENTS {
        b.add_event(e, c).unwrap();
    }
    let ids: Vec<StateId> = (0..states).map(|_| b.add_anonymous_state()).collect();
    b.set_initial(ids[0]).unwrap();
    for (i, t) in delta.iter().enumerate() {
        if let Some(t) = t {
            let e = b.alphabet().id(EVENTS[i % EVENTS.len()].0).unwrap();
            b.add_transition(ids[i / EVENTS.len()], e, ids[t % states], 0);
        }
    }
    b.build().unwrap()
}

fn raw(max_states: usize) -> impl Strategy<Value = (usize, Vec<Option<usize>>)> {
    (1..=max_states).prop_flat_map(|n| {
        let cell = proptest::option::weighted(0.6, 0..n);
        (Just(n), proptest::collection::vec(cell, n * EVENTS.len()))
    })
}

/// Whether `string` is in the closed language of `a`.
fn accepts(a: &Automaton, string: &[&str]) -> bool {
    let Some(mut s) = a.initial() else {
        return false;
    };
    for e in string {
        match a.successor(s, a.alphabet().id(e).unwrap()) {
            Some(t) => s = t,
            None => return false,
        }
    }
    true
}

/// `s` followed by `e`.
fn with<'a>(s: &[&'a str], e: &'a str) -> Vec<&'a str> {
    let mut t = s.to_vec();
    t.push(e);
    t
}

/// Brute force: is there a violation with |s|, |s'| < DEPTH?
fn violated(g: &Automaton, k: &Automaton, observable: &[&str]) -> bool {
    // The strings of K up to DEPTH - 1 events, by projection.
    let mut by_projection: HashMap<Vec<&str>, Vec<Vec<&str>>> = HashMap::new();
    let mut layer: Vec<Vec<&str>> = vec![Vec::new()];
    for _ in 0..DEPTH {
        let mut next = Vec::new();
        for s in layer {
            if !accepts(k, &s) {
                continue;
            }
            let p: Vec<&str> = s
                .iter()
                .copied()
                .filter(|e| observable.contains(e))
                .collect();
            for (e, _) in EVENTS {
                let mut t = s.clone();
                t.push(e);
                next.push(t);
            }
            by_projection.entry(p).or_default().push(s);
        }
        layer = next;
    }
    by_projection.values().any(|alike| {
        alike.iter().any(|s| {
            alike.iter().any(|s2| {
                EVENTS.iter().any(|&(e, c)| {
                    c && accepts(k, &with(s, e))
                        && accepts(g, &with(s2, e))
                        && !accepts(k, &with(s2, e))
                })
            })
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn check_observable_is_the_definition(
        (gn, gd) in raw(4),
        (kn, kd) in raw(4),
        hidden in proptest::sample::subsequence(vec!["a", "b", "u", "c"], 0..=2),
    ) {
        let g = automaton("G", gn, &gd);
        let k = automaton("K", kn, &kd);
        let observable: Vec<&str> =
            EVENTS.iter().map(|e| e.0).filter(|e| !hidden.contains(e)).collect();
        let controllable: Vec<&str> = EVENTS.iter().filter(|e| e.1).map(|e| e.0).collect();
        let ours = check_observable(&g, &k, &controllable, &observable, 10_000).unwrap();
        let brute = violated(&g, &k, &observable);
        if brute {
            prop_assert!(ours.is_some(), "brute force finds a violation, ours none");
        }
        if let Some(v) = ours {
            let s: Vec<&str> = v.allowed_after.iter().map(String::as_str).collect();
            let s2: Vec<&str> = v.forbidden_after.iter().map(String::as_str).collect();
            let e = v.event.as_str();
            let p = |x: &[&str]| -> Vec<String> {
                x.iter().filter(|e| observable.contains(e)).map(|e| e.to_string()).collect()
            };
                        prop_assert!(controllable.contains(&e));
            prop_assert_eq!(p(&s), p(&s2));
            prop_assert!(accepts(&k, &with(&s, e)) && accepts(&k, &s2));
            prop_assert!(accepts(&g, &with(&s2, e)) && !accepts(&k, &with(&s2, e)));
            if s.len() < DEPTH && s2.len() < DEPTH {
                prop_assert!(brute, "ours finds {v:?}, brute force nothing");
            }
        }
    }
}
