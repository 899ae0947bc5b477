//! Reachability, coreachability, trim, and sub-automata.

use crate::automaton::{Automaton, EventId, StateId, Transition};
use fixedbitset::FixedBitSet;

/// The transition relation read backwards: for each state, the
/// `(source, event)` pairs that lead into it. Built in O(n + m) by counting
/// sort.
#[derive(Debug, Clone)]
pub struct Reverse {
    offsets: Vec<u32>,
    sources: Vec<(StateId, EventId)>,
}

impl Reverse {
    /// The reverse relation of `a`.
    pub fn new(a: &Automaton) -> Reverse {
        let n = a.num_states();
        let mut offsets = vec![0u32; n + 1];
        for t in a.edges() {
            offsets[t.target.index() + 1] += 1;
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut sources = vec![(StateId(0), EventId(0)); a.num_transitions()];
        for (s, e, t) in a.iter_transitions() {
            let slot = &mut fill[t.index()];
            sources[*slot as usize] = (s, e);
            *slot += 1;
        }
        Reverse { offsets, sources }
    }

    /// The `(source, event)` pairs of transitions entering `s`.
    #[inline]
    pub fn predecessors(&self, s: StateId) -> &[(StateId, EventId)] {
        &self.sources[self.offsets[s.index()] as usize..self.offsets[s.index() + 1] as usize]
    }
}

/// The states reachable from the initial state.
pub fn reachable(a: &Automaton) -> FixedBitSet {
    let mut seen = FixedBitSet::with_capacity(a.num_states());
    let Some(init) = a.initial() else {
        return seen;
    };
    let mut stack = vec![init];
    seen.insert(init.index());
    while let Some(s) = stack.pop() {
        for t in a.transitions(s) {
            if !seen.put(t.target.index()) {
                stack.push(t.target);
            }
        }
    }
    seen
}

/// The states from which some marked state can be reached.
pub fn coreachable(a: &Automaton) -> FixedBitSet {
    coreachable_within(a, &Reverse::new(a), None)
}

/// The states from which a marked state in `within` can be reached along
/// states of `within` (all states when `None`).
pub(crate) fn coreachable_within(
    a: &Automaton,
    rev: &Reverse,
    within: Option<&FixedBitSet>,
) -> FixedBitSet {
    let allowed = |s: StateId| within.is_none_or(|w| w.contains(s.index()));
    let mut seen = FixedBitSet::with_capacity(a.num_states());
    let mut stack: Vec<StateId> = a.marked_states().filter(|&s| allowed(s)).collect();
    for &s in &stack {
        seen.insert(s.index());
    }
    while let Some(s) = stack.pop() {
        for &(p, _) in rev.predecessors(s) {
            if allowed(p) && !seen.put(p.index()) {
                stack.push(p);
            }
        }
    }
    seen
}

/// The accessible part: states reachable from the initial state.
pub fn accessible(a: &Automaton) -> Automaton {
    restrict(a, &reachable(a))
}

/// The coaccessible part: states that can reach a marked state.
pub fn coaccessible(a: &Automaton) -> Automaton {
    restrict(a, &coreachable(a))
}

/// The trim part: accessible and coaccessible states.
pub fn trim(a: &Automaton) -> Automaton {
    let co = coaccessible(a);
    accessible(&co)
}

/// `true` when every state is accessible and coaccessible.
pub fn is_trim(a: &Automaton) -> bool {
    let n = a.num_states();
    reachable(a).count_ones(..) == n && coreachable(a).count_ones(..) == n
}

/// The sub-automaton on the states in `keep`, renumbered densely in their
/// old order; transitions into dropped states disappear, and so does the
/// initial state if it is dropped.
pub fn restrict(a: &Automaton, keep: &FixedBitSet) -> Automaton {
    let n = a.num_states();
    if keep.count_ones(..) == n {
        return a.clone();
    }
    let mut new_id = vec![u32::MAX; n];
    let mut count = 0u32;
    for s in keep.ones().filter(|&s| s < n) {
        new_id[s] = count;
        count += 1;
    }
    let mut offsets = Vec::with_capacity(count as usize + 1);
    offsets.push(0u32);
    let mut edges = Vec::new();
    let mut marked = FixedBitSet::with_capacity(count as usize);
    let mut old_ids = Vec::with_capacity(count as usize);
    for s in a.states() {
        let id = new_id[s.index()];
        if id == u32::MAX {
            continue;
        }
        for t in a.transitions(s) {
            let target = new_id[t.target.index()];
            if target != u32::MAX {
                edges.push(Transition {
                    event: t.event,
                    target: StateId(target),
                });
            }
        }
        offsets.push(edges.len() as u32);
        if a.is_marked(s) {
            marked.insert(id as usize);
        }
        old_ids.push(s.0);
    }
    let initial = a
        .initial()
        .map(|s| new_id[s.index()])
        .filter(|&i| i != u32::MAX)
        .map(StateId);
    Automaton::from_parts(
        a.name().to_owned(),
        a.alphabet().clone(),
        a.state_names().select(&old_ids),
        initial,
        marked,
        offsets,
        edges,
    )
}

/// [`restrict`] of an automaton given away: the kept rows are moved down
/// inside its own vectors, so the result needs no second copy of the
/// transitions.
pub(crate) fn restrict_owned(a: Automaton, keep: &FixedBitSet) -> Automaton {
    let n = a.num_states();
    if keep.count_ones(..) == n {
        return a;
    }
    let mut new_id = vec![u32::MAX; n];
    let mut count = 0u32;
    for s in keep.ones().filter(|&s| s < n) {
        new_id[s] = count;
        count += 1;
    }
    let (name, alphabet, names, initial, old_marked, mut offsets, mut edges) = a.into_parts();
    let mut marked = FixedBitSet::with_capacity(count as usize);
    let mut old_ids = Vec::with_capacity(count as usize);
    let (mut written, mut kept) = (0usize, 0usize);
    let mut row_start = offsets[0] as usize;
    for s in 0..n {
        // Read before `offsets[kept]` (kept <= s + 1) is overwritten.
        let row_end = offsets[s + 1] as usize;
        if new_id[s] != u32::MAX {
            for k in row_start..row_end {
                let t = edges[k];
                let target = new_id[t.target.index()];
                if target != u32::MAX {
                    edges[written] = Transition {
                        event: t.event,
                        target: StateId(target),
                    };
                    written += 1;
                }
            }
            if old_marked.contains(s) {
                marked.insert(kept);
            }
            old_ids.push(s as u32);
            kept += 1;
            offsets[kept] = written as u32;
        }
        row_start = row_end;
    }
    offsets.truncate(kept + 1);
    offsets.shrink_to_fit();
    edges.truncate(written);
    edges.shrink_to_fit();
    let initial = initial
        .map(|s| new_id[s.index()])
        .filter(|&i| i != u32::MAX)
        .map(StateId);
    Automaton::from_parts(
        name,
        alphabet,
        names.select(&old_ids),
        initial,
        marked,
        offsets,
        edges,
    )
}

/// A shortest event string from the initial state to each state of
/// `targets`: breadth-first search that stops at the first state of
/// `targets` found and returns it with the string leading to it.
pub fn shortest_path_to(
    a: &Automaton,
    mut is_target: impl FnMut(StateId) -> bool,
) -> Option<(StateId, Vec<EventId>)> {
    let init = a.initial()?;
    let n = a.num_states();
    // parent[s] = (predecessor, event); u32::MAX marks "unseen".
    let mut parent = vec![(u32::MAX, EventId(0)); n];
    parent[init.index()] = (init.0, EventId(0));
    let mut queue = std::collections::VecDeque::from([init]);
    while let Some(s) = queue.pop_front() {
        if is_target(s) {
            let mut path = Vec::new();
            let mut cur = s;
            while cur != init {
                let (p, e) = parent[cur.index()];
                path.push(e);
                cur = StateId(p);
            }
            path.reverse();
            return Some((s, path));
        }
        for t in a.transitions(s) {
            if parent[t.target.index()].0 == u32::MAX {
                parent[t.target.index()] = (s.0, t.event);
                queue.push_back(t.target);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::automaton::AutomatonBuilder;

    /// 0 -a-> 1 -b-> 2 (marked), 1 -c-> 3 (dead end), 4 unreachable -a-> 2
    fn sample() -> Automaton {
        let mut b = AutomatonBuilder::new("g");
        for (e, c) in [("a", true), ("b", false), ("c", true)] {
            b.add_event(e, c).unwrap();
        }
        for s in ["0", "1", "2", "3", "4"] {
            b.add_state(s);
        }
        b.set_initial_by_name("0").unwrap();
        b.mark_by_name("2");
        for (s, e, t) in [
            ("0", "a", "1"),
            ("1", "b", "2"),
            ("1", "c", "3"),
            ("4", "a", "2"),
        ] {
            b.add_transition_by_name(s, e, t, 0).unwrap();
        }
        b.build().unwrap()
    }

    fn ones(set: &FixedBitSet) -> Vec<usize> {
        set.ones().collect()
    }

    #[test]
    fn reachable_and_coreachable_sets() {
        let g = sample();
        assert_eq!(ones(&reachable(&g)), [0, 1, 2, 3]);
        assert_eq!(ones(&coreachable(&g)), [0, 1, 2, 4]);
        assert!(!is_trim(&g));
    }

    #[test]
    fn trim_keeps_names_and_drops_dead_and_unreachable_states() {
        let t = trim(&sample());
        let names: Vec<_> = t.states().map(|s| t.state_name(s).into_owned()).collect();
        assert_eq!(names, ["0", "1", "2"]);
        assert_eq!(t.num_transitions(), 2);
        assert!(is_trim(&t));
        assert_eq!(t.state_name(t.initial().unwrap()), "0");
    }

    #[test]
    fn dropping_the_initial_state_leaves_no_initial_state() {
        let g = sample();
        let mut keep = FixedBitSet::with_capacity(5);
        keep.insert(2);
        keep.insert(4);
        let r = restrict(&g, &keep);
        assert_eq!(r.initial(), None);
        assert_eq!(r.num_transitions(), 1);
    }

    #[test]
    fn restricting_in_place_gives_what_restrict_gives() {
        let g = sample();
        for bits in 0u32..32 {
            let mut keep = FixedBitSet::with_capacity(5);
            keep.extend((0..5).filter(|i| bits & (1 << i) != 0));
            assert_eq!(
                restrict_owned(g.clone(), &keep),
                restrict(&g, &keep),
                "{bits:05b}"
            );
        }
    }

    #[test]
    fn shortest_path_is_breadth_first() {
        let g = sample();
        let (s, path) = shortest_path_to(&g, |s| s.0 == 3).unwrap();
        assert_eq!(s, StateId(3));
        let names: Vec<_> = path.iter().map(|&e| g.alphabet().name(e)).collect();
        assert_eq!(names, ["a", "c"]);
        assert!(shortest_path_to(&g, |s| s.0 == 4).is_none());
    }

    #[test]
    fn reverse_relation_lists_all_predecessors() {
        let g = sample();
        let r = Reverse::new(&g);
        let mut p: Vec<_> = r.predecessors(StateId(2)).iter().map(|x| x.0 .0).collect();
        p.sort();
        assert_eq!(p, [1, 4]);
        assert!(r.predecessors(StateId(0)).is_empty());
    }
}
