//! Natural projection onto a subset of the events, and the observer
//! property of that projection.
//!
//! The natural projection `P: Σ* → Σo*` erases the events outside `Σo`
//! (the *kept* events) from a string. [`project`] gives a deterministic
//! automaton for `P(L(G))` and `P(Lm(G))` by the subset construction: a
//! state of the result is the set of states of `G` that the strings with
//! one projection lead to, closed under the erased events; it is marked
//! when the set holds a marked state. Only the part reachable from the
//! initial set is built, states are numbered in breadth-first order and
//! named after their sets (`{idle,busy}`).
//!
//! # The observer property
//!
//! Wong and Wonham ("Hierarchical control of discrete-event systems",
//! 1996; the observer conditions again in Wong and Wonham, "On the
//! computation of observers in discrete-event systems", 2004) call `P` an
//! `Lm(G)`-observer when every continuation that the abstraction shows
//! after a string can really be followed by `G`:
//!
//! > for every string `s` of `L(G)` and every `t ∈ Σo*` with
//! > `P(s)·t ∈ P(Lm(G))`, there is a `u ∈ Σ*` with `s·u ∈ Lm(G)` and
//! > `P(s·u) = P(s)·t`.
//!
//! For a nonblocking `G` this is their definition word for word (`s`
//! ranging over the prefixes of `Lm(G)`, which are then all of `L(G)`).
//! For a blocking `G` it also asks that no string of `G` end in a state
//! from which the abstraction still promises a marked future: such an
//! `s`, with that future as `t`, is a counterexample.
//!
//! The `L(G)`-observer property is the same with the closed language in
//! place of the marked one (every state counted as marked). For a
//! nonblocking `G` the first implies the second. libFAUDES's
//! `IsNaturalObserver` holds exactly when both do: the differential tests
//! (`tests/faudes_diff/projection.rs`) compare it with both checks of
//! [`check_observer`] together.
//!
//! [`check_observer`] decides either. Let `H` be the projection of `G`. A
//! string `s` leads `G` to a state `x` and `H` to the set `X ∋ x`; the
//! condition for `s` is that every marked string of `H` from `X` is the
//! projection of a marked string of `G` from `x`, that is an inclusion of
//! `H` from `X` in the projection of `G` from `x`. The pairs `(x, X)` are
//! explored breadth-first, so the first pair that fails gives a shortest
//! `s`; its inclusion is decided breadth-first over pairs `(X', Y')` of a
//! state of `H` and a set of states of `G` (empty when `G` cannot follow),
//! so the continuation `t` found is a shortest one for that `s`. A pair
//! `(X', Y')` explored once without failure needs no second look, so all
//! the inclusions together cost at most one visit per pair.
//!
//! Both operations are bounded: beyond `max_states` states of the result
//! (or, for the observer check, pairs `(X', Y')`), or beyond
//! [`MEMBERS_PER_STATE`] `× max_states` original states listed in the
//! result's sets together, they stop with
//! [`Error::StateLimit`].

use super::equivalence::LanguageKind;
use crate::automaton::{Alphabet, Automaton, EventId, StateId, StateNames, Transition};
use crate::error::{Error, Result};
use fixedbitset::FixedBitSet;
use hashbrown::HashTable;
use rustc_hash::{FxBuildHasher, FxHashMap, FxHashSet};
use std::collections::VecDeque;
use std::hash::BuildHasher;

/// How many original states, on average, the result's sets may list per
/// allowed state before the projection is refused: the sets' memory (4
/// bytes a member) stays within 128 bytes per allowed state.
pub const MEMBERS_PER_STATE: usize = 32;

/// Why the projection `P` is not an `Lm(G)`-observer: after `string`
/// (seen as `projected`), the projection promises `continuation` to a
/// marked string, but `G`, in `state`, can reach no marked state along a
/// string whose projection is `continuation` (for the `L(G)`-observer
/// property: cannot follow `continuation` at all).
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct ObserverWitness {
    /// The string `s` of `G`, a shortest one.
    pub string: Vec<String>,
    /// Its projection `P(s)`.
    pub projected: Vec<String>,
    /// The state of `G` after `s`.
    pub state: String,
    /// The kept events `t`, a shortest such continuation for `s`.
    pub continuation: Vec<String>,
}

/// The projection of `a` onto the events `keep` (names, each in the
/// alphabet of `a`), as a deterministic automaton over those events with
/// their controllability; see the module docs. At most `max_states`
/// states (see there for the bound on their sets).
pub fn project(a: &Automaton, keep: &[impl AsRef<str>], max_states: usize) -> Result<Automaton> {
    let kept = Kept::new(a, keep)?;
    let name = format!("project({})", a.name());
    let Some(sub) = SubsetAutomaton::build_for(a, &kept, LanguageKind::Marked, true, max_states)?
    else {
        return Ok(Automaton::empty(name, kept.alphabet));
    };
    let n = sub.num_states();
    let mut marked = FixedBitSet::with_capacity(n);
    for i in 0..n {
        if sub.subsets.marked[i] {
            marked.insert(i);
        }
    }
    let names = set_names(a, &sub.subsets, n);
    let SubsetAutomaton { offsets, edges, .. } = sub;
    Ok(Automaton::from_parts(
        name,
        kept.alphabet,
        StateNames::Stored(names),
        Some(StateId(0)),
        marked,
        offsets,
        edges,
    ))
}

/// The projection of `a` onto the events where `kept` holds (a mask over
/// `a`'s event ids), states unnamed (numbered in breadth-first order), for
/// the operations of partial observation. Without `expand_marked`, a set
/// holding a marked state gets no outgoing transitions: for callers that
/// cut there, which spares the subset construction most of its states.
/// Bounded by `max_states` as [`project`] is.
pub(crate) fn project_mask(
    a: &Automaton,
    kept: &[bool],
    expand_marked: bool,
    max_states: usize,
) -> Result<Automaton> {
    let kept = Kept::from_mask(a, kept);
    let name = format!("P({})", a.name());
    let sub =
        SubsetAutomaton::build_for(a, &kept, LanguageKind::Marked, expand_marked, max_states)?;
    let Some(sub) = sub else {
        return Ok(Automaton::empty(name, kept.alphabet));
    };
    let n = sub.num_states();
    let mut marked = FixedBitSet::with_capacity(n);
    marked.extend((0..n).filter(|&i| sub.subsets.marked[i]));
    Ok(Automaton::from_parts(
        name,
        kept.alphabet,
        StateNames::Indices,
        Some(StateId(0)),
        marked,
        sub.offsets,
        sub.edges,
    ))
}

/// Decides whether the projection of `a` onto `keep` is an
/// `Lm(a)`-observer (`language` [`LanguageKind::Marked`]) or an
/// `L(a)`-observer ([`LanguageKind::Closed`]); see the module docs.
/// `Ok(None)` means it is; otherwise a shortest string after which the
/// projection promises what `a` cannot do, with a shortest such promise.
/// Bounded by `max_states` as [`project`] is.
pub fn check_observer(
    a: &Automaton,
    keep: &[impl AsRef<str>],
    language: LanguageKind,
    max_states: usize,
) -> Result<Option<ObserverWitness>> {
    let kept = Kept::new(a, keep)?;
    let Some(mut sub) = SubsetAutomaton::build_for(a, &kept, language, true, max_states)? else {
        return Ok(None);
    };
    let init = a
        .initial()
        .expect("a projection with states has an initial state");
    // Breadth-first over (state of `a`, state of the projection).
    let mut index: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    let mut pairs: Vec<(u32, u32)> = vec![(init.0, 0)];
    let mut parent: Vec<(u32, EventId)> = vec![(u32::MAX, EventId(0))];
    index.insert((init.0, 0), 0);
    let mut inclusion = Inclusion::new(a, &kept, &mut sub, max_states);
    let mut i = 0;
    while i < pairs.len() {
        let (x, big_x) = pairs[i];
        if let Some(t) = inclusion.failure(&mut sub, x, big_x)? {
            let mut string = Vec::new();
            let mut j = i;
            while parent[j].0 != u32::MAX {
                string.push(parent[j].1);
                j = parent[j].0 as usize;
            }
            string.reverse();
            let al = a.alphabet();
            return Ok(Some(ObserverWitness {
                projected: string
                    .iter()
                    .filter(|e| kept.map[e.index()].is_some())
                    .map(|&e| al.name(e).to_owned())
                    .collect(),
                string: string.iter().map(|&e| al.name(e).to_owned()).collect(),
                state: a.state_name(StateId(x)).into_owned(),
                continuation: t
                    .iter()
                    .map(|&e| kept.alphabet.name(e).to_owned())
                    .collect(),
            }));
        }
        for t in a.transitions(StateId(x)) {
            let next_x = match kept.map[t.event.index()] {
                Some(e) => sub.successor(big_x, e).expect("x is in X"),
                None => big_x,
            };
            let pair = (t.target.0, next_x);
            if let std::collections::hash_map::Entry::Vacant(v) = index.entry(pair) {
                v.insert(pairs.len() as u32);
                pairs.push(pair);
                parent.push((i as u32, t.event));
            }
        }
        i += 1;
    }
    Ok(None)
}

/// The kept events: for each event of the automaton, its id in the
/// projection's alphabet.
struct Kept {
    map: Vec<Option<EventId>>,
    alphabet: Alphabet,
}

impl Kept {
    /// The events where `mask` holds (indexed by `a`'s event ids).
    fn from_mask(a: &Automaton, mask: &[bool]) -> Kept {
        let mut alphabet = Alphabet::new();
        alphabet.set_controllability_stated(a.alphabet().controllability_stated());
        let map = a
            .alphabet()
            .iter()
            .map(|(id, e)| {
                mask[id.index()].then(|| {
                    alphabet
                        .insert(&e.name, e.controllable)
                        .expect("from one alphabet")
                })
            })
            .collect();
        Kept { map, alphabet }
    }

    fn new(a: &Automaton, keep: &[impl AsRef<str>]) -> Result<Kept> {
        let mut wanted = FxHashSet::default();
        for name in keep {
            let name = name.as_ref();
            if !a.alphabet().contains(name) {
                return Err(Error::Incompatible(format!(
                    "projection: event `{name}` is not in the alphabet of `{}`",
                    a.name()
                )));
            }
            wanted.insert(name);
        }
        let mask: Vec<bool> = a
            .alphabet()
            .iter()
            .map(|(_, e)| wanted.contains(e.name.as_str()))
            .collect();
        Ok(Kept::from_mask(a, &mask))
    }
}

/// Interned sets of states (sorted member lists, stored end to end), with
/// whether each holds a marked state.
#[derive(Default)]
struct Subsets {
    /// Every non-empty set counts as marked (the closed language).
    closed: bool,
    members: Vec<u32>,
    starts: Vec<usize>,
    marked: Vec<bool>,
    table: HashTable<u32>,
    hasher: FxBuildHasher,
}

impl Subsets {
    fn len(&self) -> usize {
        self.marked.len()
    }

    fn get(&self, i: u32) -> &[u32] {
        &self.members[self.starts[i as usize]..self.starts[i as usize + 1]]
    }

    /// The id of `set`, and whether it is new.
    fn intern(&mut self, set: &[u32], a: &Automaton) -> (u32, bool) {
        if self.starts.is_empty() {
            self.starts.push(0);
        }
        let hash = self.hasher.hash_one(set);
        let (members, starts) = (&self.members, &self.starts);
        let slice = |i: u32| &members[starts[i as usize]..starts[i as usize + 1]];
        if let Some(&found) = self.table.find(hash, |&i| slice(i) == set) {
            return (found, false);
        }
        let id = self.len() as u32;
        self.members.extend_from_slice(set);
        self.starts.push(self.members.len());
        let marked = if self.closed {
            !set.is_empty()
        } else {
            set.iter().any(|&s| a.is_marked(StateId(s)))
        };
        self.marked.push(marked);
        let (members, starts, hasher) = (&self.members, &self.starts, &self.hasher);
        self.table.insert_unique(hash, id, |&i| {
            hasher.hash_one(&members[starts[i as usize]..starts[i as usize + 1]])
        });
        (id, true)
    }

    /// Refuses more than `max_states` sets or more members than they may
    /// list together.
    fn check(&self, what: &str, max_states: usize) -> Result<()> {
        if self.len() > max_states
            || self.members.len() > max_states.saturating_mul(MEMBERS_PER_STATE)
        {
            return Err(Error::StateLimit {
                max_states,
                message: format!("{what} exceeds the limit of {max_states} states"),
            });
        }
        Ok(())
    }
}

/// The closure of sets of states under the erased events.
struct Closure<'a> {
    a: &'a Automaton,
    kept: &'a Kept,
    seen: FixedBitSet,
    stack: Vec<StateId>,
    out: Vec<u32>,
}

impl<'a> Closure<'a> {
    fn new(a: &'a Automaton, kept: &'a Kept) -> Self {
        Closure {
            a,
            kept,
            seen: FixedBitSet::with_capacity(a.num_states()),
            stack: Vec::new(),
            out: Vec::new(),
        }
    }

    /// The states reachable from `seeds` by erased events, sorted.
    fn of(&mut self, seeds: impl IntoIterator<Item = StateId>) -> &[u32] {
        self.out.clear();
        for s in seeds {
            if !self.seen.put(s.index()) {
                self.stack.push(s);
                self.out.push(s.0);
            }
        }
        while let Some(s) = self.stack.pop() {
            for t in self.a.transitions(s) {
                if self.kept.map[t.event.index()].is_none() && !self.seen.put(t.target.index()) {
                    self.stack.push(t.target);
                    self.out.push(t.target.0);
                }
            }
        }
        for &s in &self.out {
            self.seen.set(s as usize, false);
        }
        self.out.sort_unstable();
        &self.out
    }

    /// The closure of the states that `set` reaches on kept event `e` (an
    /// id of the projection's alphabet).
    fn step(&mut self, set: &[u32], e: EventId, a_event: EventId) -> &[u32] {
        debug_assert_eq!(self.kept.map[a_event.index()], Some(e));
        let a = self.a;
        let targets: Vec<StateId> = set
            .iter()
            .filter_map(|&s| a.successor(StateId(s), a_event))
            .collect();
        self.of(targets)
    }
}

/// The subset construction's result: sets `0..n` are its states, in
/// breadth-first order; further sets may be interned by the observer
/// check.
struct SubsetAutomaton {
    subsets: Subsets,
    offsets: Vec<u32>,
    edges: Vec<Transition>,
}

impl SubsetAutomaton {
    /// `None` when `a` has no initial state. Sets are marked as `language`
    /// says: by a marked member, or (closed) always. Without
    /// `expand_marked`, marked sets get no transitions.
    fn build_for(
        a: &Automaton,
        kept: &Kept,
        language: LanguageKind,
        expand_marked: bool,
        max_states: usize,
    ) -> Result<Option<SubsetAutomaton>> {
        let Some(init) = a.initial() else {
            return Ok(None);
        };
        let what = format!("projection of `{}`", a.name());
        let mut closure = Closure::new(a, kept);
        let mut subsets = Subsets {
            closed: language == LanguageKind::Closed,
            ..Subsets::default()
        };
        subsets.intern(closure.of([init]), a);
        subsets.check(&what, max_states)?;
        // Targets per kept event, gathered over the members of one set.
        let mut buckets: Vec<Vec<StateId>> = vec![Vec::new(); kept.alphabet.len()];
        let mut offsets = vec![0u32];
        let mut edges = Vec::new();
        let mut s = 0;
        while s < subsets.len() {
            if !expand_marked && subsets.marked[s] {
                offsets.push(edges.len() as u32);
                s += 1;
                continue;
            }
            for &x in subsets.get(s as u32) {
                for t in a.transitions(StateId(x)) {
                    if let Some(e) = kept.map[t.event.index()] {
                        buckets[e.index()].push(t.target);
                    }
                }
            }
            for (e, bucket) in buckets.iter_mut().enumerate() {
                if bucket.is_empty() {
                    continue;
                }
                let (target, fresh) = subsets.intern(closure.of(bucket.drain(..)), a);
                if fresh {
                    subsets.check(&what, max_states)?;
                }
                edges.push(Transition {
                    event: EventId(e as u32),
                    target: StateId(target),
                });
            }
            super::sync::check_transitions(&edges, &what)?;
            offsets.push(edges.len() as u32);
            s += 1;
        }
        Ok(Some(SubsetAutomaton {
            subsets,
            offsets,
            edges,
        }))
    }

    fn num_states(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The successor of state `s` on kept event `e`, if any.
    fn successor(&self, s: u32, e: EventId) -> Option<u32> {
        let row =
            &self.edges[self.offsets[s as usize] as usize..self.offsets[s as usize + 1] as usize];
        row.binary_search_by_key(&e, |t| t.event)
            .ok()
            .map(|k| row[k].target.0)
    }
}

/// `{a,b}` for each of the first `n` sets, after the states' names, or
/// after their numbers when names with commas would make two sets look
/// alike.
fn set_names(a: &Automaton, subsets: &Subsets, n: usize) -> Vec<String> {
    let write = |by_name: bool| -> Vec<String> {
        (0..n as u32)
            .map(|i| {
                let mut name = String::from("{");
                for (k, &s) in subsets.get(i).iter().enumerate() {
                    if k > 0 {
                        name.push(',');
                    }
                    if by_name {
                        a.write_state_name(StateId(s), &mut name);
                    } else {
                        name.push_str(&s.to_string());
                    }
                }
                name.push('}');
                name
            })
            .collect()
    };
    let names = write(true);
    let distinct: FxHashSet<&str> = names.iter().map(String::as_str).collect();
    if distinct.len() == names.len() {
        names
    } else {
        write(false)
    }
}

/// The inclusions of the observer check, sharing what they explored.
struct Inclusion<'a> {
    a: &'a Automaton,
    closure: Closure<'a>,
    /// The event of `a` behind each kept event.
    a_event: Vec<EventId>,
    max_states: usize,
    /// Pairs (state of the projection, set of states of `a`) explored.
    index: FxHashMap<(u32, u32), u32>,
    pairs: Vec<(u32, u32)>,
    parent: Vec<(u32, EventId)>,
    /// Successors of sets that are no states of the projection.
    steps: FxHashMap<(u32, EventId), u32>,
    /// The empty set, where `a` cannot follow.
    empty: u32,
}

impl<'a> Inclusion<'a> {
    fn new(a: &'a Automaton, kept: &'a Kept, sub: &mut SubsetAutomaton, max_states: usize) -> Self {
        let mut a_event = vec![EventId(0); kept.alphabet.len()];
        for (e, k) in kept.map.iter().enumerate() {
            if let Some(k) = k {
                a_event[k.index()] = EventId(e as u32);
            }
        }
        Inclusion {
            a,
            closure: Closure::new(a, kept),
            a_event,
            max_states,
            index: FxHashMap::default(),
            pairs: Vec::new(),
            parent: Vec::new(),
            steps: FxHashMap::default(),
            empty: sub.subsets.intern(&[], a).0,
        }
    }

    /// The set that set `y` reaches on kept event `e` (possibly empty).
    fn step(&mut self, sub: &mut SubsetAutomaton, y: u32, e: EventId) -> Result<u32> {
        // A state of the projection steps as the projection does: its
        // transitions are these very successor sets.
        if (y as usize) < sub.num_states() {
            return Ok(sub.successor(y, e).unwrap_or(self.empty));
        }
        if let Some(&t) = self.steps.get(&(y, e)) {
            return Ok(t);
        }
        let set = sub.subsets.get(y).to_vec();
        let next = self.closure.step(&set, e, self.a_event[e.index()]).to_vec();
        let t = self.intern(sub, next)?;
        self.steps.insert((y, e), t);
        Ok(t)
    }

    /// The id of `set`, within the bound on sets.
    fn intern(&self, sub: &mut SubsetAutomaton, set: Vec<u32>) -> Result<u32> {
        let (id, fresh) = sub.subsets.intern(&set, self.a);
        if fresh {
            let what = format!("the observer check of projection of `{}`", self.a.name());
            sub.subsets.check(&what, self.max_states)?;
        }
        Ok(id)
    }

    /// A shortest kept string `t` that the projection marks from state
    /// `big_x` and the projection of `a` from `x` does not, if any.
    fn failure(
        &mut self,
        sub: &mut SubsetAutomaton,
        x: u32,
        big_x: u32,
    ) -> Result<Option<Vec<EventId>>> {
        let start_set = self.closure.of([StateId(x)]).to_vec();
        let y = self.intern(sub, start_set)?;
        let fails = |sub: &SubsetAutomaton, (hx, hy): (u32, u32)| {
            sub.subsets.marked[hx as usize] && !sub.subsets.marked[hy as usize]
        };
        let Some(start) = self.visit((big_x, y), None)? else {
            // Explored from an earlier pair, without failure.
            return Ok(None);
        };
        let mut queue = VecDeque::from([start]);
        let mut found = fails(sub, (big_x, y)).then_some(start);
        while let (None, Some(p)) = (found, queue.pop_front()) {
            let (hx, hy) = self.pairs[p as usize];
            let row = sub.offsets[hx as usize] as usize..sub.offsets[hx as usize + 1] as usize;
            for k in row {
                let t = sub.edges[k];
                let next_y = self.step(sub, hy, t.event)?;
                let pair = (t.target.0, next_y);
                if let Some(q) = self.visit(pair, Some((p, t.event)))? {
                    if fails(sub, pair) {
                        found = Some(q);
                        break;
                    }
                    queue.push_back(q);
                }
            }
        }
        Ok(found.map(|mut q| {
            let mut t = Vec::new();
            while self.parent[q as usize].0 != u32::MAX {
                t.push(self.parent[q as usize].1);
                q = self.parent[q as usize].0;
            }
            t.reverse();
            t
        }))
    }

    /// Records `pair` as explored (reached from `from`), or `None` if it
    /// was already.
    fn visit(&mut self, pair: (u32, u32), from: Option<(u32, EventId)>) -> Result<Option<u32>> {
        if self.index.contains_key(&pair) {
            return Ok(None);
        }
        let id = self.pairs.len() as u32;
        if self.pairs.len() >= self.max_states {
            return Err(Error::StateLimit {
                max_states: self.max_states,
                message: format!(
                    "the observer check of projection of `{}` exceeds the limit of {} states",
                    self.a.name(),
                    self.max_states
                ),
            });
        }
        self.index.insert(pair, id);
        self.pairs.push(pair);
        self.parent.push(from.unwrap_or((u32::MAX, EventId(0))));
        Ok(Some(id))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::language_equal;
    use crate::ops::sync::DEFAULT_MAX_STATES as LIMIT;
    use crate::testing::auto;
    use LanguageKind::{Closed, Marked};

    #[test]
    fn a_mask_projection_erases_and_merges_and_may_stop_at_marked_sets() {
        // 0 -u-> 1 -a-> 2, 0 -a-> 3 -b-> 4 (marked) -a-> 0; u unobservable.
        let g = auto(
            "G",
            &[("u", false), ("a", true), ("b", true)],
            &[
                ("0", "u", "1"),
                ("1", "a", "2"),
                ("0", "a", "3"),
                ("3", "b", "4"),
                ("4", "a", "0"),
            ],
            &["4"],
        );
        let mask = [false, true, true];
        let p = project_mask(&g, &mask, true, 100).unwrap();
        assert_eq!(p.alphabet().len(), 2);
        // {0,1} -a-> {2,3} -b-> {4} -a-> {0,1}.
        assert_eq!((p.num_states(), p.num_transitions()), (3, 3));
        assert_eq!(p.marked_states().count(), 1);
        // Not expanded beyond the marked set: its `a` is gone.
        let cut = project_mask(&g, &mask, false, 100).unwrap();
        assert_eq!((cut.num_states(), cut.num_transitions()), (3, 2));
        assert!(project_mask(&g, &mask, true, 2).is_err());
        // The same language as the named projection.
        let named = project(&g, &["a", "b"], 100).unwrap();
        assert!(language_equal(&p, &named));
    }

    /// A machine that starts (`go`), works silently (`tick`) and then
    /// either finishes (`done`, marked) or breaks (`jam`), and is repaired
    /// (`fix`).
    fn machine() -> Automaton {
        auto(
            "M",
            &[
                ("go", true),
                ("tick", false),
                ("done", false),
                ("jam", false),
                ("fix", true),
            ],
            &[
                ("0", "go", "1"),
                ("1", "tick", "2"),
                ("2", "done", "0"),
                ("1", "jam", "3"),
                ("3", "fix", "0"),
            ],
            &["0"],
        )
    }

    #[test]
    fn erased_events_merge_the_states_they_connect() {
        let p = project(&machine(), &["go", "done", "jam", "fix"], LIMIT).unwrap();
        assert_eq!((p.num_states(), p.num_transitions()), (3, 4));
        assert_eq!(p.state_name(StateId(0)), "{0}");
        assert_eq!(p.state_name(StateId(1)), "{1,2}");
        assert!(p.is_marked(StateId(0)) && !p.is_marked(StateId(1)));
        assert_eq!(p.alphabet().len(), 4);
        assert!(!p
            .alphabet()
            .is_controllable(p.alphabet().id("jam").unwrap()));
        assert_eq!(p.name(), "project(M)");
        // The same languages as the machine with `tick` made a self-loop-free step.
        let expected = auto(
            "E",
            &[("go", true), ("done", false), ("jam", false), ("fix", true)],
            &[
                ("0", "go", "1"),
                ("1", "done", "0"),
                ("1", "jam", "3"),
                ("3", "fix", "0"),
            ],
            &["0"],
        );
        assert!(language_equal(&p, &expected));
    }

    #[test]
    fn projection_is_deterministic_where_erasing_made_a_choice() {
        // a then b or a hidden c then b: both `b`s go to different states.
        let g = auto(
            "G",
            &[("a", true), ("b", true), ("c", true)],
            &[
                ("0", "a", "1"),
                ("0", "c", "2"),
                ("2", "a", "3"),
                ("1", "b", "4"),
                ("3", "b", "5"),
            ],
            &["5"],
        );
        let p = project(&g, &["a", "b"], LIMIT).unwrap();
        assert_eq!(p.state_name(StateId(0)), "{0,2}");
        assert_eq!(p.state_name(StateId(1)), "{1,3}");
        assert_eq!(p.state_name(StateId(2)), "{4,5}");
        assert!(p.is_marked(StateId(2)));
        assert_eq!(p.num_transitions(), 2);
    }

    #[test]
    fn keeping_nothing_leaves_the_empty_string() {
        let p = project(&machine(), &[] as &[&str], LIMIT).unwrap();
        assert_eq!((p.num_states(), p.num_transitions()), (1, 0));
        assert!(p.is_marked(StateId(0)));
        assert_eq!(p.state_name(StateId(0)), "{0,1,2,3}");
        let none = Automaton::empty("E", Alphabet::new());
        assert!(project(&none, &[] as &[&str], LIMIT).unwrap().is_empty());
    }

    #[test]
    fn unknown_events_and_the_state_limit_are_errors() {
        let err = project(&machine(), &["go", "stop"], LIMIT).unwrap_err();
        assert_eq!(
            err.to_string(),
            "projection: event `stop` is not in the alphabet of `M`"
        );
        let err = project(&machine(), &["go", "done", "jam", "fix"], 2).unwrap_err();
        assert!(
            matches!(err, Error::StateLimit { max_states: 2, .. }),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "projection of `M` exceeds the limit of 2 states"
        );
        let err = check_observer(&machine(), &["go"], Marked, 1).unwrap_err();
        assert!(
            matches!(err, Error::StateLimit { max_states: 1, .. }),
            "{err:?}"
        );
    }

    #[test]
    fn sets_are_named_by_number_when_names_would_collide() {
        // {"x,y", "z"} and {"x", "y,z"} would both read {x,y,z}.
        let g = auto(
            "G",
            &[("a", true), ("c", true), ("h", true)],
            &[
                ("0", "a", "x,y"),
                ("x,y", "h", "z"),
                ("0", "c", "x"),
                ("x", "h", "y,z"),
            ],
            &[],
        );
        let p = project(&g, &["a", "c"], LIMIT).unwrap();
        let names: Vec<_> = p.states().map(|s| p.state_name(s).into_owned()).collect();
        assert_eq!(names, ["{0}", "{1,2}", "{3,4}"]);
    }

    #[test]
    fn a_hidden_choice_that_decides_the_future_breaks_the_observer_property() {
        // After `go`, a silent `tick` commits the machine to `done`; `jam`
        // is possible only before it. The abstraction still offers `jam`
        // after go·tick.
        let g = machine();
        let keep = ["go", "done", "jam", "fix"];
        let w = check_observer(&g, &keep, Marked, LIMIT).unwrap().unwrap();
        assert_eq!(w.string, ["go", "tick"]);
        assert_eq!(w.projected, ["go"]);
        assert_eq!(w.state, "2");
        assert_eq!(w.continuation, ["jam", "fix"]);
        // Keeping `tick` shows the commitment: an observer.
        let all = ["go", "tick", "done", "jam", "fix"];
        assert_eq!(check_observer(&g, &all, Marked, LIMIT).unwrap(), None);
        // Hiding all but `go`: every state reaches the marked one silently.
        assert_eq!(check_observer(&g, &["go"], Marked, LIMIT).unwrap(), None);
    }

    #[test]
    fn a_blocking_string_fails_when_the_abstraction_promises_a_marked_future() {
        // 0 -a-> 1 (marked), 0 -b-> 2 (dead): with only `a` kept, after
        // `b` the projection still promises `a`.
        let g = auto(
            "G",
            &[("a", true), ("b", true)],
            &[("0", "a", "1"), ("0", "b", "2")],
            &["1"],
        );
        let w = check_observer(&g, &["a"], Marked, LIMIT).unwrap().unwrap();
        assert_eq!(
            (w.string, w.continuation),
            (vec!["b".to_owned()], vec!["a".to_owned()])
        );
        assert_eq!(
            check_observer(&g, &["a", "b"], Marked, LIMIT).unwrap(),
            None
        );
    }

    #[test]
    fn the_empty_continuation_counts() {
        // A marked state reached silently from 0 but not from 1.
        let g = auto(
            "G",
            &[("h", true), ("k", true)],
            &[("0", "h", "1"), ("0", "k", "2")],
            &["2"],
        );
        // Keeping `k`: after the silent `h` the projection still offers `k`.
        let w = check_observer(&g, &["k"], Marked, LIMIT).unwrap().unwrap();
        assert_eq!(
            (w.string, w.continuation),
            (vec!["h".to_owned()], vec!["k".to_owned()])
        );
        // Keeping nothing: after `h` the projection is marked at once.
        let w = check_observer(&g, &[] as &[&str], Marked, LIMIT)
            .unwrap()
            .unwrap();
        assert_eq!(w.string, ["h"]);
        assert!(w.continuation.is_empty());
    }

    #[test]
    fn the_closed_language_observer_asks_that_g_can_follow_what_is_shown() {
        // 0 -e0-> 0, 0 -e1-> 1, nothing marked: vacuously an
        // Lm-observer; but after the hidden e1 the abstraction still
        // shows e0, which G cannot do.
        let g = auto(
            "G",
            &[("e0", false), ("e1", false)],
            &[("0", "e0", "0"), ("0", "e1", "1")],
            &[],
        );
        assert_eq!(check_observer(&g, &["e0"], Marked, LIMIT).unwrap(), None);
        let w = check_observer(&g, &["e0"], Closed, LIMIT).unwrap().unwrap();
        assert_eq!(
            (w.string, w.continuation),
            (vec!["e1".to_owned()], vec!["e0".to_owned()])
        );
    }
}
