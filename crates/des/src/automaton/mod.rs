//! Deterministic finite automata (generators) built for scale.
//!
//! An [`Automaton`] stores
//! - its events in an [`Alphabet`] (interned names, dense [`EventId`]s),
//! - states as dense [`StateId`]s `0..n`, names optional,
//! - the transition function in compressed sparse rows: for state `s`,
//!   `edges[offsets[s]..offsets[s + 1]]` holds its outgoing transitions
//!   sorted by event, one per event (determinism is an invariant).
//!
//! Eight bytes per transition and four per state: 10^7 transitions take
//! about 80 MB. Automata are immutable; operations build new ones, and
//! [`AutomatonBuilder`] is the one way in from files.

mod alphabet;
mod builder;
mod names;
mod tuples;

pub use alphabet::{Alphabet, ControllabilityConflict, Event, EventId};
pub use builder::{AutomatonBuilder, BuildError};
pub(crate) use names::{Composed, StateNames};
pub(crate) use tuples::{Layout, Tuples};

use fixedbitset::FixedBitSet;
use std::borrow::Cow;
use std::fmt;

/// Index of a state (dense, from 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct StateId(pub u32);

impl StateId {
    /// The index as `usize`.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for StateId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

/// One outgoing transition: on `event`, go to `target`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Transition {
    /// The event.
    pub event: EventId,
    /// The state reached.
    pub target: StateId,
}

/// A deterministic automaton `(Q, Σ, δ, q0, Qm)`; see the module docs.
///
/// Two automata are equal when they have the same name, alphabet, states
/// (with the same names), initial state, marking and transitions, however
/// their names are kept.
#[derive(Debug, Clone)]
pub struct Automaton {
    name: String,
    alphabet: Alphabet,
    state_names: StateNames,
    initial: Option<StateId>,
    marked: FixedBitSet,
    offsets: Vec<u32>,
    edges: Vec<Transition>,
}

impl Automaton {
    /// Assembles an automaton from its parts.
    ///
    /// `offsets` has one entry per state plus one; each row of `edges` must
    /// be sorted by event without repeats. Operations use this to emit their
    /// results without a builder; the invariants are checked in debug builds.
    pub(crate) fn from_parts(
        name: String,
        alphabet: Alphabet,
        state_names: StateNames,
        initial: Option<StateId>,
        marked: FixedBitSet,
        offsets: Vec<u32>,
        edges: Vec<Transition>,
    ) -> Automaton {
        let n = offsets.len() - 1;
        debug_assert_eq!(marked.len(), n);
        debug_assert_eq!(*offsets.last().unwrap() as usize, edges.len());
        debug_assert!(match &state_names {
            StateNames::Stored(v) => v.len() == n,
            _ => true,
        });
        debug_assert!(initial.is_none_or(|s| s.index() < n));
        debug_assert!(offsets.windows(2).all(|w| w[0] <= w[1]));
        debug_assert!((0..n).all(|s| {
            let row = &edges[offsets[s] as usize..offsets[s + 1] as usize];
            row.windows(2).all(|w| w[0].event < w[1].event)
                && row
                    .iter()
                    .all(|t| t.target.index() < n && t.event.index() < alphabet.len())
        }));
        Automaton {
            name,
            alphabet,
            state_names,
            initial,
            marked,
            offsets,
            edges,
        }
    }

    /// The automaton with no states over `alphabet` (the empty language).
    pub fn empty(name: impl Into<String>, alphabet: Alphabet) -> Automaton {
        Automaton::from_parts(
            name.into(),
            alphabet,
            StateNames::Indices,
            None,
            FixedBitSet::new(),
            vec![0],
            Vec::new(),
        )
    }

    /// The automaton's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Renames the automaton.
    pub fn set_name(&mut self, name: impl Into<String>) {
        self.name = name.into();
    }

    /// The events.
    pub fn alphabet(&self) -> &Alphabet {
        &self.alphabet
    }

    /// Number of states.
    #[inline]
    pub fn num_states(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of transitions.
    #[inline]
    pub fn num_transitions(&self) -> usize {
        self.edges.len()
    }

    /// `true` when the automaton has no states.
    pub fn is_empty(&self) -> bool {
        self.num_states() == 0
    }

    /// The initial state (`None` only for the empty automaton or one read
    /// from a file without initial state).
    #[inline]
    pub fn initial(&self) -> Option<StateId> {
        self.initial
    }

    /// Whether `s` is marked.
    #[inline]
    pub fn is_marked(&self, s: StateId) -> bool {
        self.marked.contains(s.index())
    }

    /// The marked states as a bit set indexed by state.
    pub fn marked(&self) -> &FixedBitSet {
        &self.marked
    }

    /// The marked states in order.
    pub fn marked_states(&self) -> impl Iterator<Item = StateId> + '_ {
        self.marked.ones().map(|s| StateId(s as u32))
    }

    /// All states in order.
    pub fn states(&self) -> impl ExactSizeIterator<Item = StateId> {
        (0..self.num_states() as u32).map(StateId)
    }

    /// `true` when states carry names.
    pub fn has_state_names(&self) -> bool {
        self.state_names.is_named()
    }

    /// The name of `s`: its given name, else its index.
    pub fn state_name(&self, s: StateId) -> Cow<'_, str> {
        self.state_names.name(s.index())
    }

    /// The state named `name` (a linear search; for tools, not hot loops).
    /// Unnamed automata answer to state indices.
    pub fn state_by_name(&self, name: &str) -> Option<StateId> {
        match &self.state_names {
            StateNames::Stored(names) => names
                .iter()
                .position(|n| n == name)
                .map(|i| StateId(i as u32)),
            StateNames::Composed(_) => {
                let mut buf = String::new();
                self.states().find(|&s| {
                    buf.clear();
                    self.state_names.write(s.index(), &mut buf);
                    buf == name
                })
            }
            StateNames::Indices => name
                .parse::<u32>()
                .ok()
                .filter(|&i| (i as usize) < self.num_states())
                .map(StateId),
        }
    }

    /// Records whether the events' controllability is stated (see
    /// [`Alphabet`]); a file that leaves it open can be asserted as is.
    pub fn set_controllability_stated(&mut self, stated: bool) {
        self.alphabet.set_controllability_stated(stated);
    }

    /// Makes the event `name` unobservable; `false` when the alphabet
    /// lacks it.
    pub fn set_unobservable(&mut self, name: &str) -> bool {
        match self.alphabet.id(name) {
            Some(id) => {
                self.alphabet.set_unobservable(id);
                true
            }
            None => false,
        }
    }

    /// Names the states, one name per state in order.
    pub(crate) fn set_state_names(&mut self, names: Vec<String>) {
        debug_assert_eq!(names.len(), self.num_states());
        self.state_names = StateNames::Stored(names);
    }

    /// Drops state names (operations then number states).
    pub fn clear_state_names(&mut self) {
        self.state_names = StateNames::Indices;
    }

    /// The outgoing transitions of `s`, sorted by event.
    #[inline]
    pub fn transitions(&self, s: StateId) -> &[Transition] {
        let i = s.index();
        &self.edges[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// δ(s, e), if defined.
    #[inline]
    pub fn successor(&self, s: StateId, e: EventId) -> Option<StateId> {
        let row = self.transitions(s);
        if row.len() <= 8 {
            row.iter().find(|t| t.event == e).map(|t| t.target)
        } else {
            row.binary_search_by_key(&e, |t| t.event)
                .ok()
                .map(|i| row[i].target)
        }
    }

    /// Every transition as `(source, event, target)`, sorted by source then
    /// event.
    pub fn iter_transitions(&self) -> impl Iterator<Item = (StateId, EventId, StateId)> + '_ {
        self.states().flat_map(move |s| {
            self.transitions(s)
                .iter()
                .map(move |t| (s, t.event, t.target))
        })
    }

    /// The row offsets of the transition table (one per state, plus one).
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// The transition table (rows per state, see [`Automaton::offsets`]).
    pub fn edges(&self) -> &[Transition] {
        &self.edges
    }

    /// Consumes the automaton into `(name, alphabet, names, initial,
    /// marked, offsets, edges)`, for operations that rebuild it.
    #[allow(clippy::type_complexity)]
    pub(crate) fn into_parts(
        self,
    ) -> (
        String,
        Alphabet,
        StateNames,
        Option<StateId>,
        FixedBitSet,
        Vec<u32>,
        Vec<Transition>,
    ) {
        (
            self.name,
            self.alphabet,
            self.state_names,
            self.initial,
            self.marked,
            self.offsets,
            self.edges,
        )
    }

    /// The state names.
    pub(crate) fn state_names(&self) -> &StateNames {
        &self.state_names
    }

    /// Appends the name of `s` to `out` (see [`Automaton::state_name`]),
    /// without allocating a string of its own.
    pub fn write_state_name(&self, s: StateId, out: &mut String) {
        self.state_names.write(s.index(), out);
    }

    /// Approximate heap bytes used (for reports).
    pub fn heap_bytes(&self) -> usize {
        self.offsets.capacity() * 4
            + self.edges.capacity() * std::mem::size_of::<Transition>()
            + self.marked.len() / 8
            + self.state_names.heap_bytes()
    }
}

impl PartialEq for Automaton {
    fn eq(&self, other: &Automaton) -> bool {
        // Same offsets, so the same number of states when names compare.
        let same_names = || match (&self.state_names, &other.state_names) {
            (StateNames::Indices, StateNames::Indices) => true,
            (StateNames::Stored(a), StateNames::Stored(b)) => a == b,
            (a, b) => {
                a.is_named() == b.is_named()
                    && self
                        .states()
                        .all(|s| a.name(s.index()) == b.name(s.index()))
            }
        };
        self.name == other.name
            && self.alphabet == other.alphabet
            && self.initial == other.initial
            && self.marked == other.marked
            && self.offsets == other.offsets
            && self.edges == other.edges
            && same_names()
    }
}

impl Eq for Automaton {}

#[cfg(test)]
mod tests {
    use super::*;

    /// MACH1 of the small factory: idle -start-> working -finish-> idle,
    /// working -break-> down -repair-> idle.
    pub(crate) fn mach1() -> Automaton {
        let mut b = AutomatonBuilder::new("MACH1");
        for (n, c) in [
            ("start", true),
            ("finish", false),
            ("break", false),
            ("repair", true),
        ] {
            b.add_event(n, c).unwrap();
        }
        b.set_initial_by_name("idle").unwrap();
        b.mark_by_name("idle");
        for (s, e, t) in [
            ("idle", "start", "working"),
            ("working", "finish", "idle"),
            ("working", "break", "down"),
            ("down", "repair", "idle"),
        ] {
            b.add_transition_by_name(s, e, t, 0).unwrap();
        }
        b.build().unwrap()
    }

    #[test]
    fn rows_are_sorted_by_event_and_successor_finds_targets() {
        let m = mach1();
        assert_eq!((m.num_states(), m.num_transitions()), (3, 4));
        let working = m.state_by_name("working").unwrap();
        let finish = m.alphabet().id("finish").unwrap();
        let brk = m.alphabet().id("break").unwrap();
        let row = m.transitions(working);
        assert!(row[0].event < row[1].event);
        assert_eq!(m.successor(working, finish), m.state_by_name("idle"));
        assert_eq!(m.state_name(m.successor(working, brk).unwrap()), "down");
        assert_eq!(m.successor(m.initial().unwrap(), brk), None);
        assert!(m.is_marked(m.initial().unwrap()));
        assert_eq!(m.iter_transitions().count(), 4);
    }

    #[test]
    fn successor_on_long_rows_uses_binary_search_correctly() {
        let mut b = AutomatonBuilder::new("wide");
        let s = b.add_state("s");
        b.set_initial(s).unwrap();
        for i in 0..40 {
            let e = b.add_event(&format!("e{i}"), i % 2 == 1).unwrap();
            let t = b.add_state(&format!("t{i}"));
            b.add_transition(s, e, t, 0);
        }
        let a = b.build().unwrap();
        for i in 0..40 {
            let e = a.alphabet().id(&format!("e{i}")).unwrap();
            assert_eq!(
                a.state_name(a.successor(StateId(0), e).unwrap()),
                format!("t{i}")
            );
        }
    }

    #[test]
    fn empty_automaton_has_no_states_and_no_initial_state() {
        let e = Automaton::empty("nothing", Alphabet::new());
        assert!(e.is_empty());
        assert_eq!(e.initial(), None);
        assert_eq!(e.iter_transitions().count(), 0);
    }
}
