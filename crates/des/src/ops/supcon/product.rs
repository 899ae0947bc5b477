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
//! pair (plant state, spec state) packed into one `u64`, interned through a
//! hash table of `u32` ids into the `Vec<u64>` of pairs.

use crate::automaton::{Automaton, Composed, Layout, StateId, StateNames, Transition, Tuples};
use crate::error::Result;
use crate::ops::sync::{
    check_transitions, composed_alphabet, state_limit, ComposeOptions, Composition, Delta,
};
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

/// Interned (plant, spec) pairs, packed as `g | e << 32`.
struct Pairs {
    keys: Vec<u64>,
    table: HashTable<u32>,
}

impl Pairs {
    fn len(&self) -> usize {
        self.keys.len()
    }

    fn pair(&self, id: usize) -> (u32, u32) {
        let key = self.keys[id];
        (key as u32, (key >> 32) as u32)
    }

    /// The id of `(g, e)`, and whether it is new.
    fn intern(&mut self, g: u32, e: u32) -> (u32, bool) {
        let key = u64::from(g) | (u64::from(e) << 32);
        let hash = FxBuildHasher.hash_one(key);
        let keys = &self.keys;
        if let Some(&id) = self.table.find(hash, |&id| keys[id as usize] == key) {
            return (id, false);
        }
        let id = self.len() as u32;
        self.keys.push(key);
        let keys = &self.keys;
        self.table
            .insert_unique(hash, id, |&i| FxBuildHasher.hash_one(keys[i as usize]));
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
        keys: Vec::new(),
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
                    return Err(state_limit(&name, options.max_states));
                }
                edges.push(Transition {
                    event: t.event,
                    target: StateId(target),
                });
            }
            check_transitions(&edges, &name)?;
        }
        offsets.push(edges.len() as u32);
        s += 1;
        if s % (1 << 16) == 0 {
            options.progress.report("compose", s);
        }
    }
    let n = store.len();
    let mut marked = FixedBitSet::with_capacity(n);
    for s in 0..n {
        let (g, e) = store.pair(s);
        if plant.is_marked(StateId(g)) && spec.is_marked(StateId(e)) {
            marked.insert(s);
        }
    }
    let Pairs { mut keys, table } = store;
    drop(table);
    let mut bad_set = FixedBitSet::with_capacity(n);
    bad_set.extend(bad);
    let names = if options.name_states {
        keys.shrink_to_fit();
        let parts = vec![plant.state_names().clone(), spec.state_names().clone()];
        let tuples = Tuples::Packed {
            keys,
            layout: Layout::pair(),
        };
        StateNames::Composed(Arc::new(Composed::new(parts, Arc::new(tuples))))
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
