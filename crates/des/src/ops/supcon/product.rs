//! The product `plant ‖ spec` that supcon searches, pruned as it is built.
//!
//! A product state where the specification disables an uncontrollable
//! event that the plant enables is *bad* at once: no supervisor can keep
//! it, so it gets no outgoing transitions and its successors are not
//! explored through it (libFAUDES's product does the same). Every other
//! state is expanded as in [`compose`](crate::ops::compose), so the good
//! part of the product, and everything supcon computes from it, is the same
//! as on the full product; only the states reachable solely through bad
//! ones are never built.
//!
//! States are numbered breadth-first in discovery order; a state is the
//! pair (plant state, spec state), interned as one `u64` key through a
//! hash table of `u32` ids into a flat `Vec<u32>` of pairs.

use crate::automaton::{Automaton, Composed, StateId, StateNames, Transition};
use crate::error::{Error, Result};
use crate::ops::sync::{composed_alphabet, ComposeOptions, Composition, Delta};
use fixedbitset::FixedBitSet;
use hashbrown::HashTable;
use rustc_hash::FxBuildHasher;
use std::hash::BuildHasher;
use std::sync::Arc;

/// The pruned product and its immediately bad states.
pub(super) struct Pruned {
    /// The product; bad states have no outgoing transitions.
    pub automaton: Automaton,
    /// States where the specification disables an uncontrollable event
    /// the plant enables.
    pub bad: FixedBitSet,
}

/// Interned (plant, spec) pairs.
struct Pairs {
    pairs: Vec<u32>,
    table: HashTable<u32>,
}

impl Pairs {
    fn key(g: u32, e: u32) -> u64 {
        (u64::from(g) << 32) | u64::from(e)
    }

    fn len(&self) -> usize {
        self.pairs.len() / 2
    }

    fn pair(&self, id: usize) -> (u32, u32) {
        (self.pairs[2 * id], self.pairs[2 * id + 1])
    }

    /// The id of `(g, e)`, and whether it is new.
    fn intern(&mut self, g: u32, e: u32) -> (u32, bool) {
        let hash = FxBuildHasher.hash_one(Self::key(g, e));
        let pairs = &self.pairs;
        let eq = |&id: &u32| pairs[2 * id as usize] == g && pairs[2 * id as usize + 1] == e;
        if let Some(&id) = self.table.find(hash, eq) {
            return (id, false);
        }
        let id = self.len() as u32;
        self.pairs.extend_from_slice(&[g, e]);
        let pairs = &self.pairs;
        self.table.insert_unique(hash, id, |&i| {
            let i = i as usize;
            FxBuildHasher.hash_one(Self::key(pairs[2 * i], pairs[2 * i + 1]))
        });
        (id, true)
    }
}

/// The reachable product of `plant` and `spec` (whose alphabet is within
/// the plant's), not expanded beyond its immediately bad states.
pub(super) fn pruned_product(
    plant: &Automaton,
    spec: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<Pruned> {
    let alphabet = composed_alphabet(&[plant, spec], Composition::Sync)?;
    let name = format!("{}||{}", plant.name(), spec.name());
    // The spec's alphabet is within the plant's and the plant comes first,
    // so product event ids are plant event ids.
    debug_assert!(alphabet
        .ids()
        .all(|e| plant.alphabet().name(e) == alphabet.name(e)));
    let (Some(g0), Some(e0)) = (plant.initial(), spec.initial()) else {
        return Ok(Pruned {
            automaton: Automaton::empty(name, alphabet),
            bad: FixedBitSet::new(),
        });
    };
    let spec_event: Vec<_> = alphabet
        .iter()
        .map(|(_, e)| spec.alphabet().id(&e.name))
        .collect();
    let uncontrollable: Vec<bool> = alphabet
        .ids()
        .map(|e| !alphabet.is_controllable(e))
        .collect();
    let delta = Delta::new(spec);

    let mut store = Pairs {
        pairs: Vec::new(),
        table: HashTable::new(),
    };
    store.intern(g0.0, e0.0);
    let mut bad = Vec::new();
    let mut offsets = vec![0u32];
    let mut edges: Vec<Transition> = Vec::new();
    let mut s = 0usize;
    while s < store.len() {
        let (g, e) = store.pair(s);
        let row = plant.transitions(StateId(g));
        // The spec's state after each plant transition; `None` where it
        // disables the event.
        let next = |t: &Transition| match spec_event[t.event.index()] {
            None => Some(e),
            Some(local) => delta.next(e, local),
        };
        if row
            .iter()
            .any(|t| uncontrollable[t.event.index()] && next(t).is_none())
        {
            bad.push(s);
        } else {
            for t in row {
                let Some(e2) = next(t) else { continue };
                let (target, fresh) = store.intern(t.target.0, e2);
                if fresh && store.len() > options.max_states {
                    return Err(Error::StateLimit {
                        max_states: options.max_states,
                        message: format!(
                            "composition `{name}` exceeds the limit of {} states",
                            options.max_states
                        ),
                    });
                }
                edges.push(Transition {
                    event: t.event,
                    target: StateId(target),
                });
            }
            if edges.len() >= u32::MAX as usize {
                return Err(Error::Incompatible(format!(
                    "composition `{name}` exceeds 2^32 transitions"
                )));
            }
        }
        offsets.push(edges.len() as u32);
        s += 1;
        if s % (1 << 16) == 0 {
            options.progress.report("compose", s);
        }
    }
    let n = store.len();
    let Pairs { mut pairs, table } = store;
    drop(table);
    let mut marked = FixedBitSet::with_capacity(n);
    for (s, pair) in pairs.chunks_exact(2).enumerate() {
        if plant.is_marked(StateId(pair[0])) && spec.is_marked(StateId(pair[1])) {
            marked.insert(s);
        }
    }
    let mut bad_set = FixedBitSet::with_capacity(n);
    bad_set.extend(bad);
    let names = if options.name_states {
        pairs.shrink_to_fit();
        let parts = vec![plant.state_names().clone(), spec.state_names().clone()];
        StateNames::Composed(Arc::new(Composed::new(parts, Arc::new(pairs))))
    } else {
        StateNames::Indices
    };
    edges.shrink_to_fit();
    let automaton = Automaton::from_parts(
        name,
        alphabet,
        names,
        Some(StateId(0)),
        marked,
        offsets,
        edges,
    );
    Ok(Pruned {
        automaton,
        bad: bad_set,
    })
}
