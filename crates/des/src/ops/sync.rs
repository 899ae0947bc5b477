//! Synchronous composition (`sync`, parallel composition) and product
//! (`meet`) of any number of automata.
//!
//! Both explore the reachable part of the product breadth-first from the
//! tuple of initial states. A product state is a tuple of component states,
//! packed into one `u64` when the components' state counts allow it (else
//! stored flat in one `Vec<u32>`), and interned through a hash table of
//! `u32` ids into it, so a state costs 8 bytes (or `4 × components`) plus
//! the table slot. States are numbered in discovery order, which lets the
//! transition rows be appended directly in CSR form. State names are
//! composed from the tuples when asked for, not stored.
//!
//! - `sync`: the alphabet is the union; an event moves every component
//!   that has it and leaves the others where they are, and is possible
//!   when every component that has it can take it.
//! - `meet`: the alphabet is the intersection; the language is the
//!   intersection of the components' languages.

use super::Progress;
use crate::automaton::{
    Alphabet, Automaton, Composed, EventId, Layout, StateId, StateNames, Transition, Tuples,
};
use crate::error::{Error, Result};
use fixedbitset::FixedBitSet;
use hashbrown::HashTable;
use rustc_hash::FxBuildHasher;
use std::hash::BuildHasher;
use std::sync::Arc;

/// How the alphabets of the components combine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Composition {
    /// Union of alphabets, shared events synchronise (parallel composition).
    Sync,
    /// Intersection of alphabets (product, language intersection).
    Meet,
}

/// Options of [`compose`].
#[derive(Clone, Copy)]
pub struct ComposeOptions<'a> {
    /// Name product states `a.b.c` from the components' state names.
    pub name_states: bool,
    /// Give up with an error beyond this many product states (default
    /// [`DEFAULT_MAX_STATES`]).
    pub max_states: usize,
    /// Receives the number of states explored now and then.
    pub progress: &'a dyn Progress,
}

/// The default bound on the states of a composition: far above any
/// benchmark (phil10 composes 59,047 states) and reached in under a second
/// on a quiet machine (0.7 s), so that a composition that explodes (30 independent two-state
/// plants: 2^30 states) is refused at once with the limit named, instead
/// of exhausting memory minutes later. Beyond it a composition is
/// [`Error::StateLimit`]; how a user raises it is the caller's to say.
pub const DEFAULT_MAX_STATES: usize = 500_000;

impl Default for ComposeOptions<'_> {
    fn default() -> Self {
        ComposeOptions {
            name_states: true,
            max_states: DEFAULT_MAX_STATES,
            progress: &(),
        }
    }
}

/// The result of [`compose`]: the product automaton and, for each of its
/// states, the tuple of component states it stands for.
#[derive(Debug, Clone)]
pub struct Product {
    /// The product automaton.
    pub automaton: Automaton,
    tuples: Arc<Tuples>,
}

impl Product {
    /// The state of component `component` in product state `s`.
    #[inline]
    pub fn component_state(&self, s: StateId, component: usize) -> StateId {
        StateId(self.tuples.get(s.index(), component))
    }

    /// The tuple of component states of product state `s`.
    pub fn tuple(&self, s: StateId) -> Vec<u32> {
        (0..self.tuples.width())
            .map(|j| self.tuples.get(s.index(), j))
            .collect()
    }
}

/// Parallel composition of `components`, states named from theirs.
pub fn sync(components: &[&Automaton]) -> Result<Automaton> {
    Ok(compose(components, Composition::Sync, ComposeOptions::default())?.automaton)
}

/// Product (language intersection) of `components`.
pub fn meet(components: &[&Automaton]) -> Result<Automaton> {
    Ok(compose(components, Composition::Meet, ComposeOptions::default())?.automaton)
}

/// The alphabet of a composition, or the controllability conflict that
/// prevents it.
pub fn composed_alphabet(components: &[&Automaton], mode: Composition) -> Result<Alphabet> {
    let union = Alphabet::union(components.iter().map(|a| a.alphabet())).map_err(|c| {
        let owners: Vec<String> = components
            .iter()
            .filter_map(|a| {
                let id = a.alphabet().id(&c.name)?;
                let kind = if a.alphabet().is_controllable(id) {
                    "controllable"
                } else {
                    "uncontrollable"
                };
                Some(format!("{kind} in `{}`", a.name()))
            })
            .collect();
        Error::Incompatible(format!(
            "event `{}` has conflicting controllability: {}",
            c.name,
            owners.join(", ")
        ))
    })?;
    Ok(match mode {
        Composition::Sync => union,
        Composition::Meet => {
            let mut out = Alphabet::new();
            out.set_controllability_stated(union.controllability_stated());
            for (_, e) in union.iter() {
                if components.iter().all(|a| a.alphabet().contains(&e.name)) {
                    out.insert_event(e).expect("union has no conflicts");
                }
            }
            out
        }
    })
}

/// One component's transition function, as a dense table when that is
/// small, else looked up in its CSR rows.
pub(super) enum Delta<'a> {
    Dense { table: Vec<u32>, events: usize },
    Sparse(&'a Automaton),
}

const DENSE_LIMIT: usize = 1 << 22;

impl<'a> Delta<'a> {
    pub(super) fn new(a: &'a Automaton) -> Self {
        let events = a.alphabet().len();
        let size = a.num_states().saturating_mul(events);
        if size > DENSE_LIMIT {
            return Delta::Sparse(a);
        }
        let mut table = vec![u32::MAX; size];
        for (s, e, t) in a.iter_transitions() {
            table[s.index() * events + e.index()] = t.0;
        }
        Delta::Dense { table, events }
    }

    #[inline]
    pub(super) fn next(&self, s: u32, e: EventId) -> Option<u32> {
        match self {
            Delta::Dense { table, events } => {
                let t = table[s as usize * events + e.index()];
                (t != u32::MAX).then_some(t)
            }
            Delta::Sparse(a) => a.successor(StateId(s), e).map(|t| t.0),
        }
    }
}

/// Interned product-state tuples, packed when the layout allows.
struct TupleStore {
    width: usize,
    layout: Option<Layout>,
    keys: Vec<u64>,
    flat: Vec<u32>,
    table: HashTable<u32>,
    hasher: FxBuildHasher,
}

impl TupleStore {
    fn new(components: &[&Automaton]) -> Self {
        let sizes: Vec<usize> = components.iter().map(|a| a.num_states()).collect();
        TupleStore {
            width: components.len(),
            layout: Layout::packed(&sizes),
            keys: Vec::new(),
            flat: Vec::new(),
            table: HashTable::new(),
            hasher: FxBuildHasher,
        }
    }

    fn len(&self) -> usize {
        match self.layout {
            Some(_) => self.keys.len(),
            None => self.flat.len() / self.width.max(1),
        }
    }

    /// Copies tuple `id` into `out`.
    fn load(&self, id: usize, out: &mut [u32]) {
        match &self.layout {
            Some(layout) => {
                for (j, q) in out.iter_mut().enumerate() {
                    *q = layout.get(self.keys[id], j);
                }
            }
            None => out.copy_from_slice(&self.flat[id * self.width..(id + 1) * self.width]),
        }
    }

    /// The id of `tuple`, and whether it is new.
    fn intern(&mut self, tuple: &[u32]) -> (u32, bool) {
        let id = self.len() as u32;
        if let Some(layout) = &self.layout {
            let key = layout.pack(tuple);
            let hash = self.hasher.hash_one(key);
            let keys = &self.keys;
            if let Some(&found) = self.table.find(hash, |&i| keys[i as usize] == key) {
                return (found, false);
            }
            self.keys.push(key);
            let (keys, hasher) = (&self.keys, &self.hasher);
            self.table
                .insert_unique(hash, id, |&i| hasher.hash_one(keys[i as usize]));
            return (id, true);
        }
        let hash = self.hasher.hash_one(tuple);
        let width = self.width;
        let flat = &self.flat;
        let eq = |&i: &u32| &flat[i as usize * width..(i as usize + 1) * width] == tuple;
        if let Some(&found) = self.table.find(hash, eq) {
            return (found, false);
        }
        self.flat.extend_from_slice(tuple);
        let (flat, hasher) = (&self.flat, &self.hasher);
        self.table.insert_unique(hash, id, |&i| {
            hasher.hash_one(&flat[i as usize * width..(i as usize + 1) * width])
        });
        (id, true)
    }

    /// The tuples, in id order.
    fn into_tuples(self) -> Tuples {
        match self.layout {
            Some(layout) => {
                let mut keys = self.keys;
                keys.shrink_to_fit();
                Tuples::Packed { keys, layout }
            }
            None => {
                let mut data = self.flat;
                data.shrink_to_fit();
                Tuples::Flat {
                    data,
                    width: self.width,
                }
            }
        }
    }
}

/// The refusal of composition `name` once it passes `max_states` states.
pub(crate) fn state_limit(name: &str, max_states: usize) -> Error {
    Error::StateLimit {
        max_states,
        message: format!("composition `{name}` exceeds the limit of {max_states} states"),
    }
}

/// Refuses composition `name` once its transitions no longer fit the
/// 32-bit row offsets.
pub(crate) fn check_transitions(edges: &[Transition], name: &str) -> Result<()> {
    if edges.len() >= u32::MAX as usize {
        return Err(Error::Incompatible(format!(
            "composition `{name}` exceeds 2^32 transitions"
        )));
    }
    Ok(())
}

/// The reachable product of `components` under `mode`.
///
/// With no components the result is the one-state automaton of the empty
/// string (marked), the neutral element of both operations.
pub fn compose(
    components: &[&Automaton],
    mode: Composition,
    options: ComposeOptions<'_>,
) -> Result<Product> {
    let alphabet = composed_alphabet(components, mode)?;
    let name = components
        .iter()
        .map(|a| a.name())
        .collect::<Vec<_>>()
        .join(match mode {
            Composition::Sync => "||",
            Composition::Meet => "&&",
        });
    let width = components.len();
    if width == 0 {
        let mut marked = FixedBitSet::with_capacity(1);
        marked.insert(0);
        let automaton = Automaton::from_parts(
            name,
            alphabet,
            StateNames::Indices,
            Some(StateId(0)),
            marked,
            vec![0, 0],
            Vec::new(),
        );
        return Ok(Product {
            automaton,
            tuples: Arc::default(),
        });
    }

    // For each event of the result, the (component, local event) pairs
    // that must all move.
    let participants: Vec<Vec<(usize, EventId)>> = alphabet
        .iter()
        .map(|(_, e)| {
            components
                .iter()
                .enumerate()
                .filter_map(|(j, a)| a.alphabet().id(&e.name).map(|id| (j, id)))
                .collect()
        })
        .collect();

    let initial: Option<Vec<u32>> = components
        .iter()
        .map(|a| a.initial().map(|s| s.0))
        .collect();
    let Some(initial) = initial else {
        return Ok(Product {
            automaton: Automaton::empty(name, alphabet),
            tuples: Arc::default(),
        });
    };

    let deltas: Vec<Delta> = components.iter().map(|a| Delta::new(a)).collect();
    let mut store = TupleStore::new(components);
    store.intern(&initial);

    let mut offsets = vec![0u32];
    let mut edges: Vec<Transition> = Vec::new();
    let mut current = vec![0u32; width];
    let mut next = vec![0u32; width];
    let mut moved: Vec<(usize, u32)> = Vec::with_capacity(width);
    let mut s = 0usize;
    while s < store.len() {
        store.load(s, &mut current);
        next.copy_from_slice(&current);
        for (g, parts) in participants.iter().enumerate() {
            moved.clear();
            let all = parts
                .iter()
                .all(|&(j, e)| match deltas[j].next(current[j], e) {
                    Some(t) => {
                        moved.push((j, t));
                        true
                    }
                    None => false,
                });
            if !all {
                continue;
            }
            for &(j, t) in &moved {
                next[j] = t;
            }
            let (target, fresh) = store.intern(&next);
            if fresh && store.len() > options.max_states {
                return Err(state_limit(&name, options.max_states));
            }
            for &(j, _) in &moved {
                next[j] = current[j];
            }
            edges.push(Transition {
                event: EventId(g as u32),
                target: StateId(target),
            });
        }
        check_transitions(&edges, &name)?;
        offsets.push(edges.len() as u32);
        s += 1;
        if s % (1 << 16) == 0 {
            options.progress.report("compose", s);
        }
    }

    let n = store.len();
    drop(std::mem::take(&mut store.table));
    let tuples = Arc::new(store.into_tuples());
    let mut marked = FixedBitSet::with_capacity(n);
    for s in 0..n {
        if components
            .iter()
            .enumerate()
            .all(|(j, a)| a.is_marked(StateId(tuples.get(s, j))))
        {
            marked.insert(s);
        }
    }
    // Names are joined from the components' when asked for, not stored.
    let names = if options.name_states {
        let parts = components.iter().map(|a| a.state_names().clone()).collect();
        StateNames::Composed(Arc::new(Composed::new(parts, Arc::clone(&tuples))))
    } else {
        StateNames::Indices
    };
    let automaton = Automaton::from_parts(
        name,
        alphabet,
        names,
        Some(StateId(0)),
        marked,
        offsets,
        edges,
    );
    Ok(Product { automaton, tuples })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::automaton::AutomatonBuilder;

    fn machine(name: &str, start: &str, finish: &str) -> Automaton {
        let mut b = AutomatonBuilder::new(name);
        b.add_event(start, true).unwrap();
        b.add_event(finish, false).unwrap();
        b.set_initial_by_name("I").unwrap();
        b.mark_by_name("I");
        b.add_transition_by_name("I", start, "W", 0).unwrap();
        b.add_transition_by_name("W", finish, "I", 0).unwrap();
        b.build().unwrap()
    }

    #[test]
    fn disjoint_alphabets_interleave() {
        let m1 = machine("M1", "s1", "f1");
        let m2 = machine("M2", "s2", "f2");
        let p = sync(&[&m1, &m2]).unwrap();
        assert_eq!((p.num_states(), p.num_transitions()), (4, 8));
        assert_eq!(p.alphabet().len(), 4);
        assert_eq!(p.marked().count_ones(..), 1);
        assert_eq!(p.state_name(p.initial().unwrap()), "I.I");
        assert_eq!(p.name(), "M1||M2");
    }

    #[test]
    fn shared_events_synchronise() {
        // A buffer: f1 fills it, s2 empties it. M1 || BUF || M2.
        let m1 = machine("M1", "s1", "f1");
        let m2 = machine("M2", "s2", "f2");
        let mut b = AutomatonBuilder::new("BUF");
        b.add_event("f1", false).unwrap();
        b.add_event("s2", true).unwrap();
        b.set_initial_by_name("0").unwrap();
        b.mark_by_name("0");
        b.add_transition_by_name("0", "f1", "1", 0).unwrap();
        b.add_transition_by_name("1", "s2", "0", 0).unwrap();
        let buf = b.build().unwrap();
        let p = sync(&[&m1, &buf, &m2]).unwrap();
        // s2 needs a full buffer: from the initial state only s1 is possible.
        let init = p.initial().unwrap();
        let first: Vec<_> = p
            .transitions(init)
            .iter()
            .map(|t| p.alphabet().name(t.event))
            .collect();
        assert_eq!(first, ["s1"]);
        // Every combination is reachable, but not every transition.
        assert_eq!((p.num_states(), p.num_transitions()), (8, 12));
    }

    #[test]
    fn meet_intersects_languages_and_alphabets() {
        let m1 = machine("A", "a", "b");
        let mut b = AutomatonBuilder::new("B");
        b.add_event("a", true).unwrap();
        b.add_event("c", false).unwrap();
        b.set_initial_by_name("0").unwrap();
        b.mark_by_name("0");
        b.add_transition_by_name("0", "a", "0", 0).unwrap();
        let other = b.build().unwrap();
        let m = meet(&[&m1, &other]).unwrap();
        assert_eq!(m.alphabet().len(), 1);
        // a then (b is not shared, so) stuck: strings "", "a".
        assert_eq!((m.num_states(), m.num_transitions()), (2, 1));
    }

    #[test]
    fn conflicting_controllability_names_both_automata() {
        let m1 = machine("A", "a", "b");
        let m2 = machine("B", "b", "a");
        let err = sync(&[&m1, &m2]).unwrap_err().to_string();
        assert!(
            err.contains("`b`") && err.contains("`A`") && err.contains("`B`"),
            "{err}"
        );
    }

    #[test]
    fn a_component_without_initial_state_gives_the_empty_product() {
        let m1 = machine("A", "a", "b");
        let e = Automaton::empty("E", Alphabet::new());
        assert!(sync(&[&m1, &e]).unwrap().is_empty());
    }

    #[test]
    fn component_tuples_are_recorded() {
        let m1 = machine("M1", "s1", "f1");
        let m2 = machine("M2", "s2", "f2");
        let p = compose(&[&m1, &m2], Composition::Sync, ComposeOptions::default()).unwrap();
        for s in p.automaton.states() {
            let name = p.automaton.state_name(s).into_owned();
            let expect = format!(
                "{}.{}",
                m1.state_name(p.component_state(s, 0)),
                m2.state_name(p.component_state(s, 1))
            );
            assert_eq!(name, expect);
        }
    }

    #[test]
    fn composing_nothing_gives_the_marked_empty_string() {
        let p = sync(&[]).unwrap();
        assert_eq!((p.num_states(), p.num_transitions()), (1, 0));
        assert!(p.is_marked(p.initial().unwrap()));
    }

    #[test]
    fn state_limit_is_enforced() {
        let m1 = machine("M1", "s1", "f1");
        let m2 = machine("M2", "s2", "f2");
        let options = ComposeOptions {
            max_states: 3,
            ..ComposeOptions::default()
        };
        let err = compose(&[&m1, &m2], Composition::Sync, options)
            .expect_err("four product states, a limit of 3");
        assert!(
            matches!(err, Error::StateLimit { max_states: 3, .. }),
            "{err:?}"
        );
        // The bound is named; how to raise it is the caller's to say.
        assert_eq!(
            err.to_string(),
            "composition `M1||M2` exceeds the limit of 3 states"
        );
    }
}
