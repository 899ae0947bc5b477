//! Modular controllability on random small instances: the verdict on the
//! reduced plant (`des::ops::check_controllable_modular`) is the verdict
//! on the monolithic plant, and a counterexample is a string of the whole
//! plant after which the supervisor disables an event the plant enables.

use des::ops::{check_controllable, check_controllable_modular, sync, ComposeOptions};
use des::{Automaton, AutomatonBuilder, StateId};
use proptest::prelude::*;

/// Events and their controllability, fixed per name.
const POOL: [(&str, bool); 8] = [
    ("a", true),
    ("b", true),
    ("c", true),
    ("d", true),
    ("u", false),
    ("v", false),
    ("w", false),
    ("x", false),
];

/// A random automaton: each pool event is in its alphabet with
/// probability `weight`: `(event mask, states, transitions (source, pool
/// event index, target) filtered to the mask and made deterministic)`.
type Raw = (Vec<bool>, usize, Vec<(usize, usize, usize)>);

fn raw(max_states: usize, weight: f64) -> impl Strategy<Value = Raw> {
    (
        proptest::collection::vec(proptest::bool::weighted(weight), POOL.len()),
        1..=max_states,
    )
        .prop_flat_map(move |(mask, n)| {
            let transitions =
                proptest::collection::vec((0..n, 0..POOL.len(), 0..n), 0..(3 * n + 2));
            (Just(mask), Just(n), transitions)
        })
}

fn build(name: &str, (mask, n, transitions): &Raw) -> Automaton {
    let mut b = AutomatonBuilder::new(name);
    for (i, &(e, c)) in POOL.iter().enumerate() {
        if mask[i] {
            b.add_event(e, c).unwrap();
        }
    }
    let states: Vec<StateId> = (0..*n).map(|s| b.add_state(&s.to_string())).collect();
    b.set_initial(states[0]).unwrap();
    b.mark(states[0]);
    let mut seen = std::collections::HashSet::new();
    for &(s, e, t) in transitions {
        if !mask[e] || !seen.insert((s, e)) {
            continue;
        }
        let id = b.alphabet().id(POOL[e].0).unwrap();
        b.add_transition(states[s], id, states[t], 0);
    }
    b.build().unwrap()
}

/// Replays `path` in `a`, skipping events `a` does not have.
fn replay(a: &Automaton, path: &[String]) -> Option<StateId> {
    let mut s = a.initial()?;
    for name in path {
        if let Some(e) = a.alphabet().id(name) {
            s = a.successor(s, e)?;
        }
    }
    Some(s)
}

fn enables(a: &Automaton, s: StateId, name: &str) -> bool {
    a.alphabet()
        .id(name)
        .is_none_or(|e| a.successor(s, e).is_some())
}

/// The reduced-plant verdict equals the monolithic one on `components`
/// and a supervisor drawn as `sup`, kept to the events `keep` allows.
fn agree(
    components: &[Raw],
    sup: Raw,
    keep: impl Fn(&[Automaton], &str) -> bool,
) -> Result<(), TestCaseError> {
    let components: Vec<Automaton> = components
        .iter()
        .enumerate()
        .map(|(i, r)| build(&format!("G{i}"), r))
        .collect();
    let refs: Vec<&Automaton> = components.iter().collect();
    let plant = sync(&refs).unwrap();
    // The supervisor keeps only plant events.
    let (mut mask, n, transitions) = sup;
    for (i, m) in mask.iter_mut().enumerate() {
        *m &= plant.alphabet().contains(POOL[i].0) && keep(&components, POOL[i].0);
    }
    let sup = build("S", &(mask, n, transitions));
    let whole = check_controllable(&plant, &sup).unwrap();
    let modular = check_controllable_modular(&refs, &sup, ComposeOptions::default()).unwrap();
    prop_assert_eq!(
        modular.controllable(),
        whole.is_none(),
        "{:?} vs {:?}",
        modular,
        whole
    );
    if let (Some(c), Some(whole)) = (&modular.counterexample, &whole) {
        // The plant string is one of every component and of S, and
        // after it the plant enables the event S disables.
        for g in &components {
            let s = replay(g, &c.plant_path);
            prop_assert!(s.is_some(), "{} refuses {:?}", g.name(), c.plant_path);
            prop_assert!(enables(g, s.unwrap(), &c.witness.event));
        }
        let x = replay(&sup, &c.plant_path);
        prop_assert!(x.is_some());
        prop_assert!(!enables(&sup, x.unwrap(), &c.witness.event));
        // Its projection onto the reduced plant is the witness, no
        // longer than the projection of the monolithic witness.
        let reduced = |name: &String| {
            modular
                .reduced
                .iter()
                .any(|&i| components[i].alphabet().contains(name))
        };
        let projected: Vec<String> = c
            .plant_path
            .iter()
            .filter(|e| reduced(e))
            .cloned()
            .collect();
        prop_assert_eq!(&projected, &c.witness.path);
        let whole_projected = whole.path.iter().filter(|e| reduced(e)).count();
        prop_assert!(c.witness.path.len() <= whole_projected);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn the_reduced_plant_verdict_is_the_whole_plants(
        components in proptest::collection::vec(raw(3, 0.3), 2..=5),
        sup in raw(3, 0.2),
    ) {
        agree(&components, sup, |_, _| true)?;
    }

    /// The supervisor's events are the first component's alone, whose
    /// other events the rest shares: the reduced plant is that one
    /// component, and counterexamples often need lifting or growth.
    #[test]
    fn the_verdict_holds_when_only_the_rest_of_the_plant_constrains(
        components in proptest::collection::vec(raw(3, 0.4), 2..=5),
        sup in raw(2, 0.5),
    ) {
        agree(&components, sup, |all, name| {
            all[0].alphabet().contains(name)
                && all[1..].iter().all(|g| !g.alphabet().contains(name))
        })?;
    }
}
