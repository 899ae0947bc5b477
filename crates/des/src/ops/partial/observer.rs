//! Natural projection of a deterministic automaton onto the observable
//! events, made deterministic by subset construction.
//!
//! A state of the result is a set of states of the input, closed under
//! unobservable transitions: the states the input may be in after some
//! string with a given projection. It is marked when the set holds a
//! marked state, so the result recognises P(L) and P(Lm).

use crate::automaton::{Alphabet, Automaton, EventId, StateId, StateNames, Transition};
use crate::error::{Error, Result};
use fixedbitset::FixedBitSet;
use hashbrown::HashTable;
use rustc_hash::FxBuildHasher;
use std::hash::BuildHasher;

/// Interned subsets (sorted state lists), stored end to end.
#[derive(Default)]
struct Subsets {
    flat: Vec<u32>,
    starts: Vec<usize>,
    table: HashTable<u32>,
}

/// Subset `i` of the subsets stored end to end in `flat` from `starts`.
fn slice<'a>(flat: &'a [u32], starts: &[usize], i: u32) -> &'a [u32] {
    let i = i as usize;
    let end = starts.get(i + 1).copied().unwrap_or(flat.len());
    &flat[starts[i]..end]
}

impl Subsets {
    fn len(&self) -> usize {
        self.starts.len()
    }

    fn get(&self, id: usize) -> &[u32] {
        slice(&self.flat, &self.starts, id as u32)
    }

    /// The id of `set` (sorted, without repeats), and whether it is new.
    fn intern(&mut self, set: &[u32]) -> (u32, bool) {
        let hash = FxBuildHasher.hash_one(set);
        let (flat, starts) = (&self.flat, &self.starts);
        if let Some(&id) = self.table.find(hash, |&i| slice(flat, starts, i) == set) {
            return (id, false);
        }
        let id = self.len() as u32;
        self.starts.push(self.flat.len());
        self.flat.extend_from_slice(set);
        let (flat, starts) = (&self.flat, &self.starts);
        self.table.insert_unique(hash, id, |&i| {
            FxBuildHasher.hash_one(slice(flat, starts, i))
        });
        (id, true)
    }
}

/// Completes `set` with what unobservable transitions reach from it, and
/// sorts it; `seen` is all clear before and after.
fn unobservable_closure(
    a: &Automaton,
    observable: &[bool],
    set: &mut Vec<u32>,
    seen: &mut FixedBitSet,
) {
    set.retain(|&s| !seen.put(s as usize));
    let mut i = 0;
    while i < set.len() {
        for t in a.transitions(StateId(set[i])) {
            if !observable[t.event.index()] && !seen.put(t.target.index()) {
                set.push(t.target.0);
            }
        }
        i += 1;
    }
    for &s in set.iter() {
        seen.set(s as usize, false);
    }
    set.sort_unstable();
}

/// P(a): the deterministic automaton over the events of `a` where
/// `observable` holds (a mask over `a`'s event ids), refused beyond
/// `max_states` subsets. Without `beyond_marked`, marked subsets are not
/// expanded (no outgoing transitions): for callers that cut there, which
/// spares the subset construction most of its states.
pub(super) fn project_dfa(
    a: &Automaton,
    observable: &[bool],
    beyond_marked: bool,
    max_states: usize,
) -> Result<Automaton> {
    let mut alphabet = Alphabet::new();
    alphabet.set_controllability_stated(a.alphabet().controllability_stated());
    let local: Vec<Option<EventId>> = a
        .alphabet()
        .iter()
        .map(|(id, e)| {
            observable[id.index()]
                .then(|| alphabet.insert(&e.name, e.controllable).expect("distinct"))
        })
        .collect();
    let name = format!("P({})", a.name());
    let Some(init) = a.initial() else {
        return Ok(Automaton::empty(name, alphabet));
    };
    let mut seen = FixedBitSet::with_capacity(a.num_states());
    let mut subsets = Subsets::default();
    let mut set = vec![init.0];
    unobservable_closure(a, observable, &mut set, &mut seen);
    subsets.intern(&set);

    // Targets per projected event, and the events touched from one subset.
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); alphabet.len()];
    let mut touched: Vec<usize> = Vec::new();
    let mut offsets = vec![0u32];
    let mut edges: Vec<Transition> = Vec::new();
    let mut marked = Vec::new();
    let mut id = 0;
    while id < subsets.len() {
        let subset = subsets.get(id);
        if subset.iter().any(|&s| a.is_marked(StateId(s))) {
            marked.push(id);
            if !beyond_marked {
                offsets.push(edges.len() as u32);
                id += 1;
                continue;
            }
        }
        for &s in subset {
            for t in a.transitions(StateId(s)) {
                if let Some(e) = local[t.event.index()] {
                    if buckets[e.index()].is_empty() {
                        touched.push(e.index());
                    }
                    buckets[e.index()].push(t.target.0);
                }
            }
        }
        touched.sort_unstable();
        for &e in &touched {
            let mut set = std::mem::take(&mut buckets[e]);
            unobservable_closure(a, observable, &mut set, &mut seen);
            let (target, fresh) = subsets.intern(&set);
            if fresh && subsets.len() > max_states {
                return Err(Error::StateLimit {
                    max_states,
                    message: format!(
                        "the projection of `{}` onto the observable events exceeds the \
                         limit of {max_states} states (subset construction)",
                        a.name()
                    ),
                });
            }
            set.clear();
            buckets[e] = set;
            edges.push(Transition {
                event: EventId(e as u32),
                target: StateId(target),
            });
        }
        touched.clear();
        offsets.push(edges.len() as u32);
        id += 1;
    }
    let mut marks = FixedBitSet::with_capacity(subsets.len());
    marks.extend(marked);
    Ok(Automaton::from_parts(
        name,
        alphabet,
        StateNames::Indices,
        Some(StateId(0)),
        marks,
        offsets,
        edges,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    #[test]
    fn unobservable_events_are_erased_and_their_choices_merged() {
        // 0 -u-> 1 -a-> 2, 0 -a-> 3 -b-> 4 (marked); u unobservable.
        let g = auto(
            "G",
            &[("u", false), ("a", true), ("b", true)],
            &[
                ("0", "u", "1"),
                ("1", "a", "2"),
                ("0", "a", "3"),
                ("3", "b", "4"),
            ],
            &["4"],
        );
        let p = project_dfa(&g, &[false, true, true], true, 100).unwrap();
        assert_eq!(p.alphabet().len(), 2);
        // {0,1} -a-> {2,3} -b-> {4}.
        assert_eq!((p.num_states(), p.num_transitions()), (3, 2));
        assert_eq!(p.marked_states().count(), 1);
        assert!(project_dfa(&g, &[false, true, true], true, 2).is_err());
    }
}
