//! The product's transitions read backwards, as supcon needs them: for
//! each state the sources of all transitions into it (to find the states
//! that can reach a marked one) and, apart, the sources of the
//! uncontrollable ones (to spread badness). Four bytes per transition
//! plus four per uncontrollable one, built by counting sort.

use crate::automaton::{Automaton, StateId};
use fixedbitset::FixedBitSet;

/// Sources of transitions into each state, in compressed sparse rows.
struct Rows {
    offsets: Vec<u32>,
    sources: Vec<u32>,
}

impl Rows {
    /// The rows of the transitions of `a` that `keep(event)` accepts.
    fn new(a: &Automaton, keep: impl Fn(usize) -> bool) -> Rows {
        let n = a.num_states();
        let mut offsets = vec![0u32; n + 1];
        for t in a.edges().iter().filter(|t| keep(t.event.index())) {
            offsets[t.target.index() + 1] += 1;
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut sources = vec![0u32; offsets[n] as usize];
        for s in a.states() {
            for t in a.transitions(s).iter().filter(|t| keep(t.event.index())) {
                let slot = &mut fill[t.target.index()];
                sources[*slot as usize] = s.0;
                *slot += 1;
            }
        }
        Rows { offsets, sources }
    }

    fn of(&self, s: usize) -> &[u32] {
        &self.sources[self.offsets[s] as usize..self.offsets[s + 1] as usize]
    }
}

/// Predecessors of every state of a product, all and uncontrollable.
pub(super) struct Predecessors {
    all: Rows,
    uncontrollable: Rows,
}

impl Predecessors {
    /// The predecessors in `a`; `uncontrollable[e]` says which events are.
    pub(super) fn new(a: &Automaton, uncontrollable: &[bool]) -> Predecessors {
        Predecessors {
            all: Rows::new(a, |_| true),
            uncontrollable: Rows::new(a, |e| uncontrollable[e]),
        }
    }

    /// Marks bad every state with an uncontrollable transition into a bad
    /// one, starting from the states in `frontier` (already in `bad`).
    pub(super) fn spread_bad(&self, bad: &mut FixedBitSet, frontier: &mut Vec<StateId>) {
        while let Some(s) = frontier.pop() {
            for &pred in self.uncontrollable.of(s.index()) {
                if !bad.put(pred as usize) {
                    frontier.push(StateId(pred));
                }
            }
        }
    }

    /// The states outside `bad` that reach a marked state of `a` through
    /// states outside `bad`.
    pub(super) fn coreachable_good(&self, a: &Automaton, bad: &FixedBitSet) -> FixedBitSet {
        let mut seen = FixedBitSet::with_capacity(a.num_states());
        let mut stack: Vec<u32> = a
            .marked_states()
            .filter(|s| !bad.contains(s.index()))
            .map(|s| s.0)
            .collect();
        for &s in &stack {
            seen.insert(s as usize);
        }
        while let Some(s) = stack.pop() {
            for &p in self.all.of(s as usize) {
                if !bad.contains(p as usize) && !seen.put(p as usize) {
                    stack.push(p);
                }
            }
        }
        seen
    }
}
