//! Observability (Lin and Wonham 1988) of a closed language, with a
//! counterexample.
//!
//! The closed language K of `k` is observable with respect to the closed
//! language L of the plant, the controllable events Σc and the observable
//! events Σo when for all s, s' ∈ K with P(s) = P(s') and every σ ∈ Σc:
//! sσ ∈ K and s'σ ∈ L imply s'σ ∈ K. Otherwise a supervisor that sees
//! only P(s) cannot know whether to enable σ.
//!
//! The search runs breadth-first over triples (state of K after s, state
//! of K after s', state of G after s'): an unobservable event moves s or
//! s' alone, an observable one both. A triple where some controllable σ
//! leaves the first K state but not the second while G has it is a
//! violation. There are at most |K|²·|G| triples; no subset construction.

use super::{event_mask, names, over_plant_alphabet};
use crate::automaton::{Automaton, EventId, StateId};
use crate::error::{Error, Result};
use rustc_hash::FxHashMap;

/// Two strings that look the same and an event that K allows after one
/// and forbids after the other although the plant can do it.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct ObservabilityViolation {
    /// s: sσ ∈ K.
    pub allowed_after: Vec<String>,
    /// s', with P(s') = P(s): s' ∈ K, s'σ ∈ L but s'σ ∉ K.
    pub forbidden_after: Vec<String>,
    /// σ, controllable.
    pub event: String,
}

/// Which string a step of the search extends.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    Start,
    First,
    Second,
    Both,
}

/// Is the closed language of `k` observable with respect to the closed
/// language of `plant`, the `controllable` and the `observable` events?
/// `None` when it is, else a counterexample found breadth-first (fewest
/// events in s and s' together). Refused beyond `max_states` triples.
pub fn check_observable(
    plant: &Automaton,
    k: &Automaton,
    controllable: &[impl AsRef<str>],
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Option<ObservabilityViolation>> {
    let controllable = event_mask(plant, controllable, "controllable")?;
    let observable = event_mask(plant, observable, "observable")?;
    let k = over_plant_alphabet(plant, k)?;
    let (Some(k0), Some(g0)) = (k.initial(), plant.initial()) else {
        return Ok(None);
    };
    let mut triples: Vec<[StateId; 3]> = vec![[k0, k0, g0]];
    let mut parent: Vec<(u32, Side, EventId)> = vec![(0, Side::Start, EventId(0))];
    let mut index: FxHashMap<[StateId; 3], u32> = FxHashMap::default();
    index.insert([k0, k0, g0], 0);
    let mut i = 0;
    while i < triples.len() {
        let [x, y, g] = triples[i];
        for t in k.transitions(x) {
            let e = t.event;
            if controllable[e.index()]
                && k.successor(y, e).is_none()
                && plant.successor(g, e).is_some()
            {
                let (s, s_prime) = strings(&parent, i);
                return Ok(Some(ObservabilityViolation {
                    allowed_after: names(&k, &s),
                    forbidden_after: names(&k, &s_prime),
                    event: k.alphabet().name(e).to_owned(),
                }));
            }
        }
        let mut next = Vec::new();
        for t in k.transitions(x) {
            if !observable[t.event.index()] {
                next.push(([t.target, y, g], Side::First, t.event));
            } else if let (Some(y2), Some(g2)) =
                (k.successor(y, t.event), plant.successor(g, t.event))
            {
                next.push(([t.target, y2, g2], Side::Both, t.event));
            }
        }
        for t in k.transitions(y) {
            if !observable[t.event.index()] {
                if let Some(g2) = plant.successor(g, t.event) {
                    next.push(([x, t.target, g2], Side::Second, t.event));
                }
            }
        }
        for (triple, side, e) in next {
            if let std::collections::hash_map::Entry::Vacant(v) = index.entry(triple) {
                if triples.len() >= max_states {
                    return Err(Error::StateLimit {
                        max_states,
                        message: format!(
                            "the observability check of `{}` exceeds the limit of \
                             {max_states} state triples",
                            k.name()
                        ),
                    });
                }
                v.insert(triples.len() as u32);
                triples.push(triple);
                parent.push((i as u32, side, e));
            }
        }
        i += 1;
    }
    Ok(None)
}

/// The strings s and s' that lead to triple `i`.
fn strings(parent: &[(u32, Side, EventId)], mut i: usize) -> (Vec<EventId>, Vec<EventId>) {
    let (mut s, mut s_prime) = (Vec::new(), Vec::new());
    while parent[i].1 != Side::Start {
        let (p, side, e) = parent[i];
        if side != Side::Second {
            s.push(e);
        }
        if side != Side::First {
            s_prime.push(e);
        }
        i = p as usize;
    }
    s.reverse();
    s_prime.reverse();
    (s, s_prime)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    #[test]
    fn a_choice_after_an_unobservable_event_is_not_observable() {
        // G: 0 -u-> 1, both states can do c. K allows c at 0 only.
        let ev = [("u", false), ("c", true)];
        let g = auto(
            "G",
            &ev,
            &[("0", "u", "1"), ("0", "c", "2"), ("1", "c", "3")],
            &[],
        );
        let k = auto("K", &ev, &[("0", "u", "1"), ("0", "c", "2")], &[]);
        let v = check_observable(&g, &k, &["c"], &["c"], 100)
            .unwrap()
            .unwrap();
        assert_eq!(v.allowed_after, Vec::<String>::new());
        assert_eq!(v.forbidden_after, ["u"]);
        assert_eq!(v.event, "c");
        assert!(check_observable(&g, &k, &["c"], &["c", "u"], 100)
            .unwrap()
            .is_none());
        // Uncontrollable, c is not a control decision.
        let none: [&str; 0] = [];
        assert!(check_observable(&g, &k, &none, &["c"], 100)
            .unwrap()
            .is_none());
    }
}
