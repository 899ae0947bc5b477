//! Property checks with witnesses: controllability, nonblocking,
//! nonconflict.

use super::reach::{coreachable, shortest_path_to};
use super::supcon::check_spec_alphabet;
use super::sync::{compose, ComposeOptions, Composition};
use crate::automaton::{Automaton, EventId};
use crate::error::Result;

/// Why a supervisor is not controllable: after `path` (a string of the
/// closed loop), the plant can do the uncontrollable `event` and the
/// supervisor cannot.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct UncontrollableWitness {
    /// Events from the initial state.
    pub path: Vec<String>,
    /// The uncontrollable event the supervisor disables.
    pub event: String,
    /// The plant state reached by `path`.
    pub plant_state: String,
    /// The supervisor state reached by `path`.
    pub supervisor_state: String,
}

/// A reachable state from which no marked state can be reached, and a
/// shortest string leading to it.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct BlockingWitness {
    /// Events from the initial state.
    pub path: Vec<String>,
    /// The blocking state's name.
    pub state: String,
}

fn names(a: &Automaton, path: &[EventId]) -> Vec<String> {
    path.iter()
        .map(|&e| a.alphabet().name(e).to_owned())
        .collect()
}

fn quiet() -> ComposeOptions<'static> {
    ComposeOptions {
        name_states: false,
        ..ComposeOptions::default()
    }
}

/// Checks that `sup` never disables an uncontrollable plant event in the
/// closed loop `plant ‖ sup`. The supervisor's alphabet must be within the
/// plant's. `Ok(None)` means controllable.
pub fn check_controllable(
    plant: &Automaton,
    sup: &Automaton,
) -> Result<Option<UncontrollableWitness>> {
    check_controllable_with(plant, sup, quiet())
}

/// [`check_controllable`] with the closed loop composed under `options`
/// (its state bound and progress reports; state names are not needed and
/// never built).
pub fn check_controllable_with(
    plant: &Automaton,
    sup: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<Option<UncontrollableWitness>> {
    check_spec_alphabet(plant, sup)?;
    let options = ComposeOptions {
        name_states: false,
        ..options
    };
    let closed = compose(&[plant, sup], Composition::Sync, options)?;
    let p = &closed.automaton;
    // Plant first and sup ⊆ plant: product event ids are plant event ids.
    let violation = |s| {
        let g = closed.component_state(s, 0);
        let x = closed.component_state(s, 1);
        plant.transitions(g).iter().find_map(|t| {
            if plant.alphabet().is_controllable(t.event) {
                return None;
            }
            let e = sup.alphabet().id(plant.alphabet().name(t.event))?;
            sup.successor(x, e).is_none().then_some(t.event)
        })
    };
    let Some((s, path)) = shortest_path_to(p, |s| violation(s).is_some()) else {
        return Ok(None);
    };
    let event = violation(s).expect("found by the search");
    Ok(Some(UncontrollableWitness {
        path: names(p, &path),
        event: plant.alphabet().name(event).to_owned(),
        plant_state: plant.state_name(closed.component_state(s, 0)).into_owned(),
        supervisor_state: sup.state_name(closed.component_state(s, 1)).into_owned(),
    }))
}

/// Checks that every reachable state of `a` can reach a marked state.
/// `None` means nonblocking (the empty automaton is nonblocking).
pub fn check_nonblocking(a: &Automaton) -> Option<BlockingWitness> {
    let co = coreachable(a);
    let (s, path) = shortest_path_to(a, |s| !co.contains(s.index()))?;
    Some(BlockingWitness {
        path: names(a, &path),
        state: a.state_name(s).into_owned(),
    })
}

/// Checks that `automata` (modular supervisors, usually with the plant)
/// are nonconflicting: their synchronous composition is nonblocking.
pub fn check_nonconflicting(automata: &[&Automaton]) -> Result<Option<BlockingWitness>> {
    let options = ComposeOptions::default();
    let product = compose(automata, Composition::Sync, options)?;
    Ok(check_nonblocking(&product.automaton))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    fn plant() -> Automaton {
        auto(
            "G",
            &[("start", true), ("done", false), ("fail", false)],
            &[("0", "start", "1"), ("1", "done", "0"), ("1", "fail", "2")],
            &["0"],
        )
    }

    #[test]
    fn disabling_an_uncontrollable_event_is_reported_with_a_shortest_string() {
        let sup = auto(
            "S",
            &[("start", true), ("done", false), ("fail", false)],
            &[("0", "start", "1"), ("1", "done", "0")],
            &["0"],
        );
        let w = check_controllable(&plant(), &sup).unwrap().unwrap();
        assert_eq!(w.path, ["start"]);
        assert_eq!(w.event, "fail");
        assert_eq!(
            (w.plant_state.as_str(), w.supervisor_state.as_str()),
            ("1", "1")
        );
    }

    #[test]
    fn disabling_only_controllable_events_is_controllable() {
        let sup = auto("S", &[("start", true)], &[], &["0"]);
        assert_eq!(check_controllable(&plant(), &sup).unwrap(), None);
    }

    #[test]
    fn blocking_state_and_path_are_found() {
        let w = check_nonblocking(&plant()).unwrap();
        assert_eq!(w.path, ["start", "fail"]);
        assert_eq!(w.state, "2");
        let fine = auto("F", &[("a", true)], &[("0", "a", "0")], &["0"]);
        assert_eq!(check_nonblocking(&fine), None);
    }

    #[test]
    fn two_individually_nonblocking_supervisors_can_conflict() {
        // S1 insists on a before b, S2 on b before a: the closed loop of
        // both deadlocks after nothing.
        let s1 = auto(
            "S1",
            &[("a", true), ("b", true)],
            &[("0", "a", "1"), ("1", "b", "2")],
            &["2"],
        );
        let s2 = auto(
            "S2",
            &[("a", true), ("b", true)],
            &[("0", "b", "1"), ("1", "a", "2")],
            &["2"],
        );
        assert_eq!(check_nonblocking(&s1), None);
        let w = check_nonconflicting(&[&s1, &s2]).unwrap().unwrap();
        assert!(w.path.is_empty());
        assert_eq!(check_nonconflicting(&[&s1, &s1]).unwrap(), None);
    }
}
