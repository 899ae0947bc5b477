//! Language-preserving state minimisation (`minstate`).
//!
//! Two states are merged when they have the same future: the same marking
//! and, for every event, either both no transition or transitions into
//! merged states. This is the coarsest such partition (the minimal
//! automaton for both the closed and the marked language, partial
//! transition function kept partial: blocking behaviour is preserved).
//!
//! The refinement follows Valmari and Lehtinen's partition refinement for
//! partial automata ("Efficient minimization of DFAs with partial
//! transition functions", STACS 2008): states and transitions are each
//! kept in a refinable partition; a block of transitions splits the state
//! blocks by "has a transition in this set", a new state block splits the
//! transition sets by "enters this block". Only the smaller half of each
//! split is queued, which gives O(m log n) time.

use super::reach::{reachable, restrict};
use crate::automaton::{Automaton, StateId, StateNames, Transition};
use fixedbitset::FixedBitSet;

/// A partition of `0..n` into sets whose elements are contiguous in
/// `elements`; elements can be marked and sets split into marked and
/// unmarked parts.
struct RefinablePartition {
    elements: Vec<u32>,
    position: Vec<u32>,
    set_of: Vec<u32>,
    first: Vec<u32>,
    end: Vec<u32>,
    marked: Vec<u32>,
    touched: Vec<u32>,
}

impl RefinablePartition {
    /// One set holding `0..n` (no set when `n == 0`).
    fn new(n: usize) -> Self {
        let sets = usize::from(n > 0);
        RefinablePartition {
            elements: (0..n as u32).collect(),
            position: (0..n as u32).collect(),
            set_of: vec![0; n],
            first: vec![0; sets],
            end: vec![n as u32; sets],
            marked: vec![0; sets],
            touched: Vec::new(),
        }
    }

    fn sets(&self) -> usize {
        self.first.len()
    }

    fn members(&self, set: usize) -> &[u32] {
        &self.elements[self.first[set] as usize..self.end[set] as usize]
    }

    fn mark(&mut self, e: u32) {
        let set = self.set_of[e as usize] as usize;
        let i = self.position[e as usize];
        let j = self.first[set] + self.marked[set];
        if i < j {
            return; // already marked
        }
        self.elements.swap(i as usize, j as usize);
        self.position[self.elements[i as usize] as usize] = i;
        self.position[self.elements[j as usize] as usize] = j;
        if self.marked[set] == 0 {
            self.touched.push(set as u32);
        }
        self.marked[set] += 1;
    }

    /// Splits every set with marked elements; the smaller part becomes a
    /// new set (appended), unless all elements were marked.
    fn split(&mut self) {
        while let Some(set) = self.touched.pop() {
            let set = set as usize;
            let mid = self.first[set] + self.marked[set];
            self.marked[set] = 0;
            if mid == self.end[set] {
                continue;
            }
            let new = self.first.len();
            let (lo, hi) = if mid - self.first[set] <= self.end[set] - mid {
                let range = (self.first[set], mid);
                self.first[set] = mid;
                range
            } else {
                let range = (mid, self.end[set]);
                self.end[set] = mid;
                range
            };
            self.first.push(lo);
            self.end.push(hi);
            self.marked.push(0);
            for i in lo..hi {
                self.set_of[self.elements[i as usize] as usize] = new as u32;
            }
        }
    }
}

/// The minimal automaton with the same closed and marked languages.
///
/// Unreachable states are dropped first. Result states are numbered in
/// breadth-first order from the initial state, so equal languages give
/// identical results. A merged state is named `{a,b,…}` after the states it
/// stands for (a single state keeps its name) when the input has names.
pub fn minstate(a: &Automaton) -> Automaton {
    let a = restrict(a, &reachable(a));
    let n = a.num_states();
    let Some(init) = a.initial() else {
        return Automaton::empty(a.name(), a.alphabet().clone());
    };

    // Transitions as parallel arrays: tail, label, head.
    let m = a.num_transitions();
    let mut tails = Vec::with_capacity(m);
    let mut labels = Vec::with_capacity(m);
    let mut heads = Vec::with_capacity(m);
    for (s, e, t) in a.iter_transitions() {
        tails.push(s.0);
        labels.push(e.0);
        heads.push(t.0);
    }
    // Incoming transitions of each state (CSR).
    let mut in_offsets = vec![0u32; n + 1];
    for &h in &heads {
        in_offsets[h as usize + 1] += 1;
    }
    for i in 0..n {
        in_offsets[i + 1] += in_offsets[i];
    }
    let mut fill = in_offsets.clone();
    let mut incoming = vec![0u32; m];
    for (t, &h) in heads.iter().enumerate() {
        incoming[fill[h as usize] as usize] = t as u32;
        fill[h as usize] += 1;
    }

    // State blocks, first split by marking.
    let mut blocks = RefinablePartition::new(n);
    for s in a.marked_states() {
        blocks.mark(s.0);
    }
    blocks.split();

    // Transition sets, first one per label: sort by label, then cut runs.
    let mut cords = RefinablePartition::new(m);
    if m > 0 {
        cords.elements.sort_unstable_by_key(|&t| labels[t as usize]);
        for (i, &t) in cords.elements.iter().enumerate() {
            cords.position[t as usize] = i as u32;
        }
        cords.first.clear();
        cords.end.clear();
        cords.marked.clear();
        let mut start = 0usize;
        for i in 1..=m {
            if i == m
                || labels[cords.elements[i] as usize] != labels[cords.elements[start] as usize]
            {
                let set = cords.first.len() as u32;
                for &t in &cords.elements[start..i] {
                    cords.set_of[t as usize] = set;
                }
                cords.first.push(start as u32);
                cords.end.push(i as u32);
                cords.marked.push(0);
                start = i;
            }
        }
    }

    let mut next_block = 1usize;
    let mut next_cord = 0usize;
    while next_cord < cords.sets() {
        for i in cords.first[next_cord]..cords.end[next_cord] {
            let t = cords.elements[i as usize];
            blocks.mark(tails[t as usize]);
        }
        blocks.split();
        next_cord += 1;
        while next_block < blocks.sets() {
            for i in blocks.first[next_block]..blocks.end[next_block] {
                let s = blocks.elements[i as usize] as usize;
                for &t in &incoming[in_offsets[s] as usize..in_offsets[s + 1] as usize] {
                    cords.mark(t);
                }
            }
            cords.split();
            next_block += 1;
        }
    }

    quotient(&a, &blocks, init)
}

/// The automaton of the blocks, numbered breadth-first from the initial
/// state's block.
fn quotient(a: &Automaton, blocks: &RefinablePartition, init: StateId) -> Automaton {
    let block_count = blocks.sets();
    let block_of = |s: StateId| blocks.set_of[s.index()] as usize;
    let mut order = vec![u32::MAX; block_count];
    let mut representative = Vec::with_capacity(block_count);
    order[block_of(init)] = 0;
    representative.push(init);
    let mut offsets = vec![0u32];
    let mut edges = Vec::new();
    let mut marked = FixedBitSet::with_capacity(block_count);
    let mut i = 0;
    while i < representative.len() {
        let rep = representative[i];
        if a.is_marked(rep) {
            marked.insert(i);
        }
        for t in a.transitions(rep) {
            let b = block_of(t.target);
            if order[b] == u32::MAX {
                order[b] = representative.len() as u32;
                representative.push(t.target);
            }
            edges.push(Transition {
                event: t.event,
                target: StateId(order[b]),
            });
        }
        offsets.push(edges.len() as u32);
        i += 1;
    }
    let names = StateNames::from_option(a.has_state_names().then(|| {
        representative
            .iter()
            .map(|&rep| {
                let members = blocks.members(block_of(rep));
                if members.len() == 1 {
                    a.state_name(rep).into_owned()
                } else {
                    let mut ids: Vec<u32> = members.to_vec();
                    ids.sort_unstable();
                    let names: Vec<_> = ids.iter().map(|&s| a.state_name(StateId(s))).collect();
                    format!("{{{}}}", names.join(","))
                }
            })
            .collect()
    }));
    marked.grow(representative.len());
    Automaton::from_parts(
        a.name().to_owned(),
        a.alphabet().clone(),
        names,
        Some(StateId(0)),
        marked,
        offsets,
        edges,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    #[test]
    fn equivalent_states_merge_and_get_a_set_name() {
        // Two copies of a two-state loop: 0 -a-> 1 -b-> 2 -a-> 3 -b-> 0.
        let g = auto(
            "G",
            &[("a", true), ("b", false)],
            &[
                ("0", "a", "1"),
                ("1", "b", "2"),
                ("2", "a", "3"),
                ("3", "b", "0"),
            ],
            &["0", "2"],
        );
        let m = minstate(&g);
        assert_eq!((m.num_states(), m.num_transitions()), (2, 2));
        assert_eq!(m.state_name(m.initial().unwrap()), "{0,2}");
        assert!(m.is_marked(m.initial().unwrap()));
    }

    #[test]
    fn marking_and_definedness_keep_states_apart() {
        // 1 and 2 differ only in marking; 3 and 4 differ in definedness
        // of c (closed language), although neither reaches a marked state.
        let g = auto(
            "G",
            &[("a", true), ("b", true), ("c", true), ("d", true)],
            &[
                ("0", "a", "1"),
                ("0", "b", "2"),
                ("1", "c", "3"),
                ("2", "c", "3"),
                ("0", "d", "4"),
                ("3", "c", "4"),
            ],
            &["1"],
        );
        let m = minstate(&g);
        assert_eq!(m.num_states(), 5);
    }

    #[test]
    fn unreachable_states_are_dropped() {
        let g = auto(
            "G",
            &[("a", true)],
            &[("0", "a", "0"), ("9", "a", "0")],
            &["0"],
        );
        assert_eq!(minstate(&g).num_states(), 1);
    }

    #[test]
    fn minimal_automata_are_unchanged() {
        let g = auto(
            "G",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("1", "b", "0")],
            &["0"],
        );
        let m = minstate(&g);
        assert_eq!((m.num_states(), m.num_transitions()), (2, 2));
        assert_eq!(m.state_name(StateId(1)), "1");
    }
}
