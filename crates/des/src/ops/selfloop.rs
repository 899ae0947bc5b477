//! Self-loops and inverse projection.

use crate::automaton::{Alphabet, Automaton, Transition};
use crate::error::{Error, Result};

/// Adds each event of `events` to the alphabet of `a` with a self-loop at
/// every state. The events must be new to `a`: adding loops on an event
/// that already has transitions would change what `a` says about it.
pub fn selfloop(a: &Automaton, events: &Alphabet) -> Result<Automaton> {
    let mut alphabet = a.alphabet().clone();
    let mut added = Vec::with_capacity(events.len());
    for (_, e) in events.iter() {
        if a.alphabet().contains(&e.name) {
            return Err(Error::Incompatible(format!(
                "selfloop: event `{}` is already in the alphabet of `{}`",
                e.name,
                a.name()
            )));
        }
        added.push(alphabet.insert_event(e).expect("new event"));
    }
    if added.is_empty() {
        return Ok(a.clone());
    }
    // New events have the largest ids, so appending keeps rows sorted.
    let mut offsets = Vec::with_capacity(a.num_states() + 1);
    let mut edges = Vec::with_capacity(a.num_transitions() + a.num_states() * added.len());
    offsets.push(0u32);
    for s in a.states() {
        edges.extend_from_slice(a.transitions(s));
        edges.extend(added.iter().map(|&event| Transition { event, target: s }));
        offsets.push(u32::try_from(edges.len()).map_err(|_| {
            Error::Incompatible(format!(
                "selfloop: `{}` grows beyond 2^32 transitions",
                a.name()
            ))
        })?);
    }
    let (name, _, names, initial, marked, _, _) = a.clone().into_parts();
    Ok(Automaton::from_parts(
        name, alphabet, names, initial, marked, offsets, edges,
    ))
}

/// Inverse projection of `a` onto the larger alphabet `onto`: the events
/// of `onto` that `a` does not have are self-looped everywhere. Every event
/// of `a` must be in `onto` with the same controllability.
pub fn inverse_projection(a: &Automaton, onto: &Alphabet) -> Result<Automaton> {
    let mut missing = Alphabet::new();
    for (_, e) in a.alphabet().iter() {
        match onto.id(&e.name) {
            None => {
                return Err(Error::Incompatible(format!(
                    "inverse projection: event `{}` of `{}` is not in the target alphabet",
                    e.name,
                    a.name()
                )))
            }
            Some(id)
                if a.alphabet().controllability_stated()
                    && onto.controllability_stated()
                    && onto.is_controllable(id) != e.controllable =>
            {
                return Err(Error::Incompatible(format!(
                    "inverse projection: event `{}` has conflicting controllability",
                    e.name
                )))
            }
            Some(_) => {}
        }
    }
    for (_, e) in onto.iter() {
        if !a.alphabet().contains(&e.name) {
            missing.insert_event(e).expect("from one alphabet");
        }
    }
    selfloop(a, &missing)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    #[test]
    fn selfloops_appear_at_every_state_with_the_given_controllability() {
        let g = auto("G", &[("a", true)], &[("0", "a", "1")], &["1"]);
        let mut extra = Alphabet::new();
        extra.insert("u", false).unwrap();
        let l = selfloop(&g, &extra).unwrap();
        let u = l.alphabet().id("u").unwrap();
        assert!(!l.alphabet().is_controllable(u));
        for s in l.states() {
            assert_eq!(l.successor(s, u), Some(s));
        }
        assert_eq!(l.num_transitions(), 3);
    }

    #[test]
    fn selfloop_on_a_known_event_is_an_error() {
        let g = auto("G", &[("a", true)], &[("0", "a", "1")], &["1"]);
        let mut extra = Alphabet::new();
        extra.insert("a", true).unwrap();
        assert!(selfloop(&g, &extra).is_err());
    }

    #[test]
    fn inverse_projection_adds_only_missing_events() {
        let g = auto("G", &[("a", true)], &[("0", "a", "1")], &["1"]);
        let mut onto = Alphabet::new();
        onto.insert("b", false).unwrap();
        onto.insert("a", true).unwrap();
        let l = inverse_projection(&g, &onto).unwrap();
        assert!(l.alphabet().same_events(&onto));
        assert_eq!(l.num_transitions(), 3);
        let mut small = Alphabet::new();
        small.insert("b", false).unwrap();
        assert!(inverse_projection(&g, &small).is_err());
    }
}
