//! The reachability graph of a net, as an automaton.
//!
//! Markings are explored breadth-first from the initial one, transitions
//! in file order, so the state numbers are reproducible. Each marking is
//! a state named by [`PetriNet::marking_name`], which is injective, so
//! two markings are never merged into one state; markings are told apart
//! by their token vectors (hashed), not by their names. Each transition
//! is an event of the same id and controllability (an unobservable
//! transition stays an event: hiding it is a later step's choice). The
//! initial marking is the one marked state: a batch returns to where it
//! started.
//!
//! **Unboundedness.** An unbounded net has no finite graph. It is
//! recognised when a new marking covers one of its ancestors on its
//! breadth-first parent chain (at least as many tokens everywhere, more
//! somewhere: the firings between them can repeat forever, the
//! Karp–Miller argument) and refused with the place that grows and the
//! firing sequence. Comparing with every ancestor would cost the depth of
//! the graph per marking (quadratic on a long chain), so a new marking is
//! compared with its [`NEAR_ANCESTORS`] nearest ancestors one by one and
//! then with `O(log depth)` further ones reached through skew-binary
//! jump pointers (each marking keeps one pointer to an ancestor, chosen
//! so that following pointers from depth `d` reaches the initial marking
//! in `O(log d)` steps); the initial marking is always among them. The
//! test is sound (what it finds is a growth cycle) but may miss a cycle
//! whose ends the window does not compare: the exploration then stops at
//! a limit or at a place of 2^32 − 1 tokens, which is refused as well.
//! Each new marking thus costs `O(places · log depth)` besides hashing.
//!
//! **Limits.** A limit of `n` states bounds the work and what is kept and
//! written, not only the markings ([`Limits::states`]): at most `n`
//! markings; at most `max(n ×` [`CELLS_PER_STATE`]`, 2^22)` stored token
//! counts (markings × places: the memory the markings take) and as many
//! firings (the graph's transitions); and at most `max(n ×`
//! [`NAME_BYTES_PER_STATE`]`, 2^24)` bytes of state names as a written
//! graph holds them (a file names a state once, and again for every
//! firing into or out of it: the bulk of what is written). Each is checked before the marking, firing or name
//! that would pass it is stored, and refused naming the limit.

use super::constraints::Constraint;
use super::{Marking, PetriNet};
use crate::automaton::{Automaton, AutomatonBuilder};
use crate::error::{Error, Result};
use hashbrown::HashTable;
use rustc_hash::FxBuildHasher;
use std::hash::BuildHasher;

/// The default state limit, as for compositions.
pub const DEFAULT_MAX_STATES: usize = crate::ops::sync::DEFAULT_MAX_STATES;

/// Stored token counts (markings × places) and firings allowed per
/// allowed marking: a limit of `n` markings allows `n ×` this many of
/// each (and at least 2^22).
pub const CELLS_PER_STATE: usize = 64;

/// Bytes of written state names allowed per allowed marking (and at
/// least 2^24 in all): each name counted once for its state and once per
/// firing into or out of it, as a written graph repeats it.
pub const NAME_BYTES_PER_STATE: usize = 1024;

/// What an exploration may hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Markings (states).
    pub markings: usize,
    /// Token counts stored: markings × places.
    pub token_counts: usize,
    /// Firings (the graph's transitions).
    pub firings: usize,
    /// Bytes of state names as written: each name once for its state and
    /// once per firing into or out of it.
    pub name_bytes: usize,
}

impl Limits {
    /// The limits a limit of `n` states means: `n` markings,
    /// `max(n ×` [`CELLS_PER_STATE`]`, 2^22)` token counts and firings,
    /// `max(n ×` [`NAME_BYTES_PER_STATE`]`, 2^24)` bytes of names (the
    /// floors keep a small `n` from refusing a wide net's few markings).
    pub fn states(n: usize) -> Limits {
        let cells = n.saturating_mul(CELLS_PER_STATE).max(1 << 22);
        Limits {
            markings: n,
            token_counts: cells,
            firings: cells,
            name_bytes: n.saturating_mul(NAME_BYTES_PER_STATE).max(1 << 24),
        }
    }
}

/// The ancestors compared one by one before the jump pointers take over.
pub const NEAR_ANCESTORS: usize = 16;

/// What the exploration found.
#[derive(Debug, Clone)]
pub struct Reachability {
    /// The graph as an automaton.
    pub automaton: Automaton,
    /// The reachable markings, by state index.
    pub markings: Vec<Marking>,
    /// The largest number of tokens each place holds in any reachable
    /// marking (1 or 0 everywhere: the net is safe).
    pub bounds: Vec<u32>,
    /// The reachable markings in which no transition is enabled.
    pub dead: Vec<usize>,
    /// For each marking: the marking it was first reached from and the
    /// transition that led there (`None` for the initial one).
    parent: Vec<Option<(usize, usize)>>,
    /// Every firing: (marking, transition, marking).
    edges: Vec<(usize, usize, usize)>,
}

impl Reachability {
    /// For each transition, whether it is live: from every reachable
    /// marking some firing sequence leads to a marking that enables it
    /// (computed backwards from the markings where it fires).
    pub fn live(&self, transitions: usize) -> Vec<bool> {
        let n = self.markings.len();
        let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
        for &(from, _, to) in &self.edges {
            into[to].push(from);
        }
        (0..transitions)
            .map(|t| {
                let mut reaches = vec![false; n];
                let mut stack: Vec<usize> = self
                    .edges
                    .iter()
                    .filter(|&&(_, u, _)| u == t)
                    .map(|&(from, _, _)| from)
                    .collect();
                for &m in &stack {
                    reaches[m] = true;
                }
                while let Some(m) = stack.pop() {
                    for &p in &into[m] {
                        if !reaches[p] {
                            reaches[p] = true;
                            stack.push(p);
                        }
                    }
                }
                reaches.iter().all(|&r| r)
            })
            .collect()
    }

    /// A shortest firing sequence (transition indices) from the initial
    /// marking to marking `k`.
    pub fn firing_sequence(&self, k: usize) -> Vec<usize> {
        path_to(&self.parent, k)
    }

    /// Whether no place ever holds more than one token.
    pub fn is_safe(&self) -> bool {
        self.bounds.iter().all(|&b| b <= 1)
    }
}

/// Which states of the graph are marked.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Marked {
    /// The initial marking only (a batch returns to where it started).
    #[default]
    Initial,
    /// Every marking (no nonblocking requirement: for comparing closed
    /// languages).
    All,
}

/// Why an exploration has no finite result within its limits.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Stopped {
    /// The net is unbounded: the message names the place that grows and
    /// a firing sequence.
    Unbounded(String),
    /// A limit that the bound on states sets was reached ([`Limits`]: the
    /// markings, or the token counts, firings or name bytes it allows):
    /// a larger bound may give the graph.
    Limit {
        /// The bound on states in force ([`Limits::markings`]).
        max_states: usize,
        /// What exceeded which limit.
        message: String,
    },
    /// A place would hold more than 2^32 − 1 tokens, the most a marking
    /// holds, whatever the bound: the message names the place and the
    /// firing sequence.
    Overflow(String),
}

impl std::fmt::Display for Stopped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stopped::Unbounded(m) | Stopped::Limit { message: m, .. } | Stopped::Overflow(m) => {
                f.write_str(m)
            }
        }
    }
}

/// A limit of the bound on states becomes [`Error::StateLimit`] (the
/// caller says how to raise the bound); the others
/// [`Error::Incompatible`].
impl From<Stopped> for Error {
    fn from(stopped: Stopped) -> Error {
        match stopped {
            Stopped::Limit {
                max_states,
                message,
            } => Error::StateLimit {
                max_states,
                message,
            },
            Stopped::Unbounded(message) | Stopped::Overflow(message) => {
                Error::Incompatible(message)
            }
        }
    }
}

/// The markings an exploration goes through.
#[derive(Clone, Copy)]
pub enum Region<'a> {
    /// Every marking.
    All,
    /// The markings within linear constraints `L·m ≤ b`. A marking that
    /// covers an ancestor proves growth within the region only when the
    /// growth `Δ` keeps every constraint (`L·Δ ≤ 0`): then each marking of
    /// the cycle, plus `Δ` again, is still within.
    Constraints(&'a [Constraint]),
    /// The markings a predicate accepts. Growth within an opaque region
    /// cannot be told from growth out of it, so there is no growth test:
    /// the limits stop an infinite region.
    Kept(&'a dyn Fn(&[u32]) -> bool),
}

impl Region<'_> {
    /// Whether `m` is within.
    pub fn contains(&self, m: &[u32]) -> bool {
        match self {
            Region::All => true,
            Region::Constraints(cs) => cs.iter().all(|c| c.weighted(m) <= i128::from(c.bound)),
            Region::Kept(keep) => keep(m),
        }
    }

    /// Whether the firings from `from` to `to` (both within, `to`
    /// covering `from`) can repeat forever within the region.
    fn repeats(&self, from: &[u32], to: &[u32]) -> bool {
        match self {
            Region::All => true,
            Region::Constraints(cs) => cs.iter().all(|c| c.weighted(to) <= c.weighted(from)),
            Region::Kept(_) => false,
        }
    }
}

/// What becomes of a firing into a marking outside the explored region.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// It is left out.
    Drop,
    /// The marking is a state, but is not explored further (nor counted
    /// dead, nor tested for growth): the region and one firing out of it,
    /// which is all supcon needs of a plant to judge a specification
    /// within the region.
    Frontier,
}

/// Explores the markings of `net` reachable from its initial marking, at
/// most `max_states` of them; the initial marking is the marked state.
pub fn reachability(net: &PetriNet, max_states: usize) -> Result<Reachability> {
    Ok(explore(
        net,
        Limits::states(max_states),
        Marked::Initial,
        Region::All,
        Beyond::Drop,
    )??)
}

/// [`reachability`] with a choice of marked states, and only through
/// markings `keep` accepts (a transition into another one is left out):
/// with a constraint as `keep`, the legal part of the graph.
pub fn reachability_with(
    net: &PetriNet,
    max_states: usize,
    marked: Marked,
    keep: &dyn Fn(&[u32]) -> bool,
) -> Result<Reachability> {
    Ok(explore(
        net,
        Limits::states(max_states),
        marked,
        Region::Kept(keep),
        Beyond::Drop,
    )??)
}

/// The exploration itself: within `region`, the firings out of it
/// treated as `beyond` says. The outer `Err` is an
/// error (a limit of 0, the initial marking outside the region, an
/// automaton that cannot be built); the inner one says why there is no
/// finite graph within the limits.
pub fn explore(
    net: &PetriNet,
    limits: Limits,
    marked: Marked,
    region: Region<'_>,
    beyond: Beyond,
) -> Result<std::result::Result<Reachability, Stopped>> {
    if limits.markings == 0 {
        return Err(Error::Incompatible(
            "a limit of 0 markings leaves nothing to explore".to_owned(),
        ));
    }
    if !region.contains(net.initial()) {
        return Err(Error::Incompatible(format!(
            "the initial marking of `{}` is not among the markings kept",
            net.name()
        )));
    }
    let places = net.places().len();
    let max_states = limits.markings;
    let limit = |message: String| {
        Ok(Err(Stopped::Limit {
            max_states,
            message,
        }))
    };
    if places > limits.token_counts {
        return limit(cells_limit(net, &limits));
    }
    let hasher = FxBuildHasher;
    let mut markings: Vec<Marking> = vec![net.initial().clone()];
    let mut tree = Tree::default();
    tree.push(None);
    // Marking → index, by the token vector itself: one copy, in `markings`.
    let mut index: HashTable<usize> = HashTable::new();
    index.insert_unique(hasher.hash_one(net.initial()), 0, |_| 0);
    let mut expand = vec![true];
    let mut edges: Vec<(usize, usize, usize)> = Vec::new();
    let mut dead = Vec::new();
    let mut next = 0;
    while next < markings.len() {
        if !expand[next] {
            next += 1;
            continue;
        }
        let mut enabled = false;
        for t in 0..net.transitions().len() {
            if !net.is_enabled(&markings[next], t) {
                continue;
            }
            enabled = true;
            let Some(after) = net.fire(&markings[next], t) else {
                return Ok(Err(token_limit(
                    net,
                    &tree.parent,
                    &markings[next],
                    next,
                    t,
                )));
            };
            let inside = region.contains(&after);
            if !inside && beyond == Beyond::Drop {
                continue;
            }
            let hash = hasher.hash_one(&after);
            let target = match index.find(hash, |&k| markings[k] == after) {
                Some(&k) => k,
                None => {
                    if inside {
                        if let Some(place) = tree.covered_ancestor(&markings, next, &after, &region)
                        {
                            return Ok(Err(unbounded(net, &tree.parent, next, t, place)));
                        }
                    }
                    if markings.len() == max_states {
                        return limit(format!(
                            "the reachability graph of `{}` exceeds the limit of {max_states} states",
                            net.name()
                        ));
                    }
                    if (markings.len() + 1).saturating_mul(places) > limits.token_counts {
                        return limit(cells_limit(net, &limits));
                    }
                    let k = markings.len();
                    index.insert_unique(hash, k, |&i| hasher.hash_one(&markings[i]));
                    markings.push(after);
                    tree.push(Some((next, t)));
                    expand.push(inside);
                    k
                }
            };
            if edges.len() == limits.firings {
                return limit(format!(
                    "the reachability graph of `{}` has more than {} firings (the limit with \
                     {max_states} states)",
                    net.name(),
                    limits.firings
                ));
            }
            edges.push((next, t, target));
        }
        if !enabled {
            dead.push(next);
        }
        next += 1;
    }
    drop(index);

    let mut b = AutomatonBuilder::new(net.name());
    let events: Vec<_> = net
        .transitions()
        .iter()
        .map(|t| {
            let id = b.add_event(&t.id, t.controllable)?;
            if !t.observable {
                b.set_unobservable(id);
            }
            Ok(id)
        })
        .collect::<std::result::Result<_, crate::automaton::BuildError>>()
        .map_err(|e| Error::Incompatible(format!("net `{}`: {e}", net.name())))?;
    // How often a written graph names each state: once, and once per
    // firing into or out of it.
    let mut mentions = vec![1usize; markings.len()];
    for &(source, _, target) in &edges {
        mentions[source] += 1;
        mentions[target] += 1;
    }
    let mut name_bytes = 0usize;
    let mut states = Vec::with_capacity(markings.len());
    for (m, &times) in markings.iter().zip(&mentions) {
        let name = net.marking_name(m);
        name_bytes = name_bytes.saturating_add(name.len().saturating_mul(times));
        if name_bytes > limits.name_bytes {
            return limit(format!(
                "the state names of the reachability graph of `{}`, as written, exceed {} bytes \
                 (the limit with {max_states} states)",
                net.name(),
                limits.name_bytes
            ));
        }
        states.push(b.add_state(&name));
    }
    b.set_initial(states[0])
        .map_err(|e| Error::Incompatible(e.to_string()))?;
    match marked {
        Marked::Initial => b.mark(states[0]),
        Marked::All => states.iter().for_each(|&s| b.mark(s)),
    }
    for &(source, t, target) in &edges {
        b.add_transition(states[source], events[t], states[target], 0);
    }
    let automaton = b
        .build()
        .map_err(|e| Error::Incompatible(format!("net `{}`: {e}", net.name())))?;
    let mut bounds = vec![0u32; places];
    for m in &markings {
        for (b, &k) in bounds.iter_mut().zip(m) {
            *b = (*b).max(k);
        }
    }
    Ok(Ok(Reachability {
        automaton,
        markings,
        bounds,
        dead,
        parent: tree.parent,
        edges,
    }))
}

fn cells_limit(net: &PetriNet, limits: &Limits) -> String {
    format!(
        "the reachability graph of `{}` would hold more than {} token counts (markings × {} \
         places; the limit with {} states)",
        net.name(),
        limits.token_counts,
        net.places().len(),
        limits.markings
    )
}

/// The breadth-first tree: each marking's parent, depth and jump pointer.
#[derive(Debug, Default)]
struct Tree {
    parent: Vec<Option<(usize, usize)>>,
    depth: Vec<usize>,
    /// An ancestor (the initial marking for itself): the parent, or the
    /// parent's jump's jump when the parent's two jumps span equal
    /// depths (skew-binary jump pointers, after Myers), so that jumping
    /// from depth `d` reaches depth 0 in `O(log d)` steps.
    jump: Vec<usize>,
}

impl Tree {
    fn push(&mut self, parent: Option<(usize, usize)>) {
        match parent {
            None => {
                self.parent.push(None);
                self.depth.push(0);
                self.jump.push(self.jump.len());
            }
            Some((u, t)) => {
                let ju = self.jump[u];
                let jju = self.jump[ju];
                let equal = self.depth[u] - self.depth[ju] == self.depth[ju] - self.depth[jju];
                self.parent.push(Some((u, t)));
                self.depth.push(self.depth[u] + 1);
                self.jump.push(if equal { jju } else { u });
            }
        }
    }

    /// A place that grows when `after`, a successor of `at`, covers `at`
    /// or one of the ancestors compared (see the module documentation).
    fn covered_ancestor(
        &self,
        markings: &[Marking],
        at: usize,
        after: &[u32],
        region: &Region<'_>,
    ) -> Option<usize> {
        let mut k = at;
        let mut near = 0;
        loop {
            let m = &markings[k];
            if m.iter().zip(after).all(|(a, b)| a <= b) && region.repeats(m, after) {
                if let Some(p) = m.iter().zip(after).position(|(a, b)| a < b) {
                    return Some(p);
                }
            }
            let (from, _) = self.parent[k]?;
            k = if near < NEAR_ANCESTORS {
                near += 1;
                from
            } else {
                self.jump[k]
            };
        }
    }
}

/// The transitions that first reached marking `k` from the initial one,
/// following `parent` back.
fn path_to(parent: &[Option<(usize, usize)>], k: usize) -> Vec<usize> {
    let mut sequence = Vec::new();
    let mut at = k;
    while let Some((from, t)) = parent[at] {
        sequence.push(t);
        at = from;
    }
    sequence.reverse();
    sequence
}

/// The firing sequence from the initial marking to marking `at`, then `last`.
fn sequence(net: &PetriNet, parent: &[Option<(usize, usize)>], at: usize, last: usize) -> String {
    path_to(parent, at)
        .into_iter()
        .chain([last])
        .map(|t| net.transitions()[t].id.as_str())
        .collect::<Vec<_>>()
        .join(" ")
}

/// The refusal of an unbounded net: the place that grows and the firing
/// sequence from the initial marking.
fn unbounded(
    net: &PetriNet,
    parent: &[Option<(usize, usize)>],
    at: usize,
    last: usize,
    place: usize,
) -> Stopped {
    Stopped::Unbounded(format!(
        "net `{}` is unbounded: place `{}` grows without bound (the firing sequence {} can \
         repeat its cycle forever); it has no finite reachability graph",
        net.name(),
        net.places()[place].id,
        sequence(net, parent, at, last)
    ))
}

/// The refusal of a firing that would put more than 2^32 − 1 tokens in a
/// place (`t` fired in marking `m`, number `at`).
fn token_limit(
    net: &PetriNet,
    parent: &[Option<(usize, usize)>],
    m: &[u32],
    at: usize,
    t: usize,
) -> Stopped {
    let tr = &net.transitions()[t];
    let over = tr.output.iter().find(|&&(p, w)| {
        let consumed = tr
            .input
            .iter()
            .find(|&&(q, _)| q == p)
            .map_or(0, |&(_, v)| v);
        u64::from(m[p]) - u64::from(consumed) + u64::from(w) > u64::from(u32::MAX)
    });
    let place = over.map_or("a place", |&(p, _)| net.places()[p].id.as_str());
    Stopped::Overflow(format!(
        "net `{}`: place `{place}` would hold more than 2^32 − 1 tokens (the most a marking \
         holds) after the firing sequence {}",
        net.name(),
        sequence(net, parent, at, t)
    ))
}

#[cfg(test)]
mod tests {
    use super::super::toml;
    use super::*;
    use std::path::Path;

    fn net(text: &str) -> PetriNet {
        toml::read(text, Path::new("n.toml")).unwrap()
    }

    /// The seed's oracle net (SEEDS.md D): two mixers sharing a supply
    /// valve `m3`; without a supervisor both can fill at once.
    const MIXERS: &str = r#"name = "mixers"
places = [
  { id = "ma1", tokens = 1 }, { id = "ma2" }, { id = "m3" }, { id = "ma4" }, { id = "ma5" },
  { id = "mb1", tokens = 1 }, { id = "mb2" }, { id = "mb4" }, { id = "mb5" },
]
transitions = [
  { id = "t1", controllable = true, input = { ma1 = 1 }, output = { ma2 = 1, m3 = 1 } },
  { id = "t2", controllable = true, input = { ma2 = 1, m3 = 1 }, output = { ma4 = 1 } },
  { id = "t3", controllable = true, input = { ma4 = 1 }, output = { ma5 = 1 } },
  { id = "t4", controllable = true, input = { ma5 = 1 }, output = { ma1 = 1 } },
  { id = "t5", controllable = true, input = { mb1 = 1 }, output = { mb2 = 1, m3 = 1 } },
  { id = "t6", controllable = true, input = { mb2 = 1, m3 = 1 }, output = { mb4 = 1 } },
  { id = "t7", controllable = true, input = { mb4 = 1 }, output = { mb5 = 1 } },
  { id = "t8", controllable = true, input = { mb5 = 1 }, output = { mb1 = 1 } },
]
"#;

    #[test]
    fn the_mixers_have_the_seeds_incidence_and_a_graph_where_both_fill_at_once() {
        let n = net(MIXERS);
        // SEEDS.md D, the row of the shared place m3.
        assert_eq!(n.incidence()[2], [1, -1, 0, 0, 1, -1, 0, 0]);
        let r = reachability(&n, 1000).unwrap();
        // Each mixer cycles through 4 stages independently: 4 × 4 states.
        assert_eq!(r.automaton.num_states(), 16);
        assert!(r.dead.is_empty(), "no dead marking");
        assert_eq!(r.live(8), [true; 8], "each mixer can always cycle");
        assert_eq!(r.bounds[2], 2, "m3 holds two tokens when both fill");
        assert!(!r.is_safe());
        let both = n.marking_name(&[0, 1, 2, 0, 0, 0, 1, 0, 0]);
        assert_eq!(both, "ma2+2·m3+mb2");
        assert!(r.automaton.state_by_name(&both).is_some());
        assert_eq!(
            r.automaton.state_name(r.automaton.initial().unwrap()),
            "ma1+mb1"
        );
    }

    #[test]
    fn an_unbounded_net_is_refused_with_the_growing_place_and_a_firing_sequence() {
        let n = net(r#"name = "leak"
places = [{ id = "idle", tokens = 1 }, { id = "busy" }, { id = "waste" }]
transitions = [
  { id = "go", controllable = true, input = { idle = 1 }, output = { busy = 1 } },
  { id = "done", controllable = false, input = { busy = 1 }, output = { idle = 1, waste = 1 } },
]
"#);
        let err = reachability(&n, 1000).unwrap_err().to_string();
        assert_eq!(
            err,
            "net `leak` is unbounded: place `waste` grows without bound (the firing sequence \
             go done can repeat its cycle forever); it has no finite reachability graph"
        );
    }

    #[test]
    fn a_dead_marking_comes_with_a_shortest_firing_sequence_into_it() {
        let n = net(r#"name = "one shot"
places = [{ id = "a", tokens = 1 }, { id = "b" }, { id = "c" }]
transitions = [
  { id = "go", controllable = true, input = { a = 1 }, output = { b = 1 } },
  { id = "stop", controllable = false, input = { b = 1 }, output = { c = 1 } },
]
"#);
        let r = reachability(&n, 10).unwrap();
        assert_eq!(r.dead.len(), 1);
        let dead = r.dead[0];
        assert_eq!(n.marking_name(&r.markings[dead]), "c");
        assert_eq!(r.firing_sequence(dead), [0, 1]);
        assert_eq!(r.firing_sequence(0), Vec::<usize>::new());
        assert_eq!(
            r.live(2),
            [false, false],
            "a one-shot net has no live transition"
        );
    }

    #[test]
    fn a_transition_is_live_when_every_marking_can_still_lead_to_it() {
        // a ⇄ b until t3 moves the token to c for good, where t4 loops.
        let n = net(r#"name = "choice"
places = [{ id = "a", tokens = 1 }, { id = "b" }, { id = "c" }]
transitions = [
  { id = "t1", controllable = true, input = { a = 1 }, output = { b = 1 } },
  { id = "t2", controllable = true, input = { b = 1 }, output = { a = 1 } },
  { id = "t3", controllable = true, input = { a = 1 }, output = { c = 1 } },
  { id = "t4", controllable = true, input = { c = 1 }, output = { c = 1 } },
]
"#);
        let r = reachability(&n, 10).unwrap();
        assert!(r.dead.is_empty(), "t4 always fires in c");
        assert_eq!(r.live(4), [false, false, false, true]);
    }

    #[test]
    fn a_graph_beyond_the_limit_is_refused_naming_it() {
        let err = reachability(&net(MIXERS), 15).unwrap_err();
        assert!(
            matches!(err, Error::StateLimit { max_states: 15, .. }),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "the reachability graph of `mixers` exceeds the limit of 15 states"
        );
    }

    #[test]
    fn a_place_past_its_counter_is_no_limit_a_bound_raises() {
        let n = net(r#"name = "full"
places = [{ id = "p", tokens = 4294967295 }]
transitions = [{ id = "t", controllable = true, input = { p = 1 }, output = { p = 2 } }]
"#);
        let stopped = explore(
            &n,
            Limits::states(10),
            Marked::Initial,
            Region::All,
            Beyond::Drop,
        )
        .unwrap()
        .unwrap_err();
        assert!(matches!(stopped, Stopped::Overflow(_)), "{stopped:?}");
        let err = reachability(&n, 10).unwrap_err();
        assert!(matches!(err, Error::Incompatible(_)), "{err:?}");
        assert_eq!(
            err.to_string(),
            "net `full`: place `p` would hold more than 2^32 − 1 tokens (the most a marking \
             holds) after the firing sequence t"
        );
    }

    #[test]
    fn markings_whose_plain_names_coincide_stay_two_states() {
        // Places `a`, `b` and `a+b`: one token in `a+b` and one each in `a`
        // and `b` both read `a+b` plainly; they were merged into one state
        // with a self-loop, and the dead marking was lost.
        let n = net(r#"name = "collide"
places = [{ id = "a" }, { id = "b" }, { id = "a+b", tokens = 1 }]
transitions = [{ id = "split", controllable = true, input = { "a+b" = 1 }, output = { a = 1, b = 1 } }]
"#);
        let r = reachability(&n, 10).unwrap();
        assert_eq!(r.automaton.num_states(), 2);
        assert_eq!(r.automaton.num_transitions(), 1);
        assert_eq!(r.dead, [1]);
        let names: Vec<String> = (0..2)
            .map(|k| {
                r.automaton
                    .state_name(crate::automaton::StateId(k))
                    .into_owned()
            })
            .collect();
        assert_eq!(names, ["\"a+b\"", "a+b"]);
        // A place called `empty` is not the empty marking.
        let n = net(r#"name = "e"
places = [{ id = "empty", tokens = 1 }, { id = "x·y\\z\"" }]
transitions = [{ id = "drain", controllable = true, input = { empty = 1 }, output = {} }]
"#);
        let r = reachability(&n, 10).unwrap();
        assert_eq!(r.automaton.num_states(), 2);
        assert_eq!(n.marking_name(&[1, 0]), "\"empty\"");
        assert_eq!(n.marking_name(&[0, 0]), "empty");
        assert_eq!(n.marking_name(&[2, 3]), "2·\"empty\"+3·\"x·y\\\\z\\\"\"");
    }

    #[test]
    fn a_long_chain_is_explored_without_walking_every_ancestor() {
        // 80,000 tokens moved one at a time: 80,001 markings in a chain
        // (comparing each with all its ancestors was quadratic).
        let n = net(r#"name = "tokens"
places = [{ id = "src", tokens = 80000 }, { id = "dst" }]
transitions = [{ id = "move", controllable = true, input = { src = 1 }, output = { dst = 1 } }]
"#);
        let r = reachability(&n, 100_000).unwrap();
        assert_eq!(r.markings.len(), 80_001);
        assert_eq!(r.dead, [80_000]);
        assert_eq!(r.firing_sequence(80_000).len(), 80_000);
    }

    #[test]
    fn a_growth_cycle_longer_than_the_near_window_is_still_found() {
        // A token goes round 40 places and leaves one in `waste` each lap:
        // the marking after a lap covers the initial one, which the jump
        // pointers always reach.
        let k = 40;
        let mut text = String::from("name = \"lap\"\nplaces = [{ id = \"waste\" }");
        for i in 0..k {
            text.push_str(&format!(
                ", {{ id = \"p{i}\", tokens = {} }}",
                u32::from(i == 0)
            ));
        }
        text.push_str("]\ntransitions = [\n");
        for i in 0..k {
            let out = if i + 1 == k {
                "p0 = 1, waste = 1".to_owned()
            } else {
                format!("p{} = 1", i + 1)
            };
            text.push_str(&format!(
                "  {{ id = \"t{i}\", controllable = true, input = {{ p{i} = 1 }}, output = {{ {out} }} }},\n"
            ));
        }
        text.push_str("]\n");
        let n = net(&text);
        let err = reachability(&n, 1000).unwrap_err().to_string();
        assert!(
            err.starts_with("net `lap` is unbounded: place `waste` grows without bound"),
            "{err}"
        );
    }

    #[test]
    fn the_state_limit_also_bounds_token_counts_and_names() {
        // Four toggles and 100 places always marked: 16 markings of 108
        // places hold 1,728 token counts, more than 16 × 64.
        let mut text = String::from("name = \"wide\"\nplaces = [\n");
        for i in 0..4 {
            text.push_str(&format!(
                "  {{ id = \"a{i}\", tokens = 1 }}, {{ id = \"b{i}\" }},\n"
            ));
        }
        for k in 0..100 {
            text.push_str(&format!("  {{ id = \"f{k}\", tokens = 1 }},\n"));
        }
        text.push_str("]\ntransitions = [\n");
        for i in 0..4 {
            text.push_str(&format!(
                "  {{ id = \"on{i}\", controllable = true, input = {{ a{i} = 1 }}, output = {{ b{i} = 1 }} }},\n\
                 \x20 {{ id = \"off{i}\", controllable = true, input = {{ b{i} = 1 }}, output = {{ a{i} = 1 }} }},\n"
            ));
        }
        text.push_str("]\n");
        let n = net(&text);
        let limits = |token_counts, firings, name_bytes| Limits {
            markings: 100,
            token_counts,
            firings,
            name_bytes,
        };
        let run = |l: Limits| {
            explore(&n, l, Marked::Initial, Region::All, Beyond::Drop)
                .unwrap()
                .map(|r| r.markings.len())
                .map_err(|s| s.to_string())
        };
        assert_eq!(
            run(limits(16 * 64, 1000, 100_000)).unwrap_err(),
            "the reachability graph of `wide` would hold more than 1024 token counts \
             (markings × 108 places; the limit with 100 states)"
        );
        assert!(matches!(
            explore(
                &n,
                limits(16 * 64, 1000, 100_000),
                Marked::Initial,
                Region::All,
                Beyond::Drop
            )
            .unwrap(),
            Err(Stopped::Limit {
                max_states: 100,
                ..
            })
        ));
        assert_eq!(run(limits(16 * 108, 1000, 100_000)), Ok(16));
        // 16 markings, 4 toggles each: 64 firings.
        assert_eq!(
            run(limits(16 * 108, 63, 100_000)).unwrap_err(),
            "the reachability graph of `wide` has more than 63 firings (the limit with 100 states)"
        );
        // The names: the fillers alone take 390 bytes a name, and each
        // name is written 9 times (its state, 4 firings out, 4 in).
        assert_eq!(
            run(limits(16 * 108, 64, 16 * 9 * 390)).unwrap_err(),
            "the state names of the reachability graph of `wide`, as written, exceed 56160 bytes \
             (the limit with 100 states)"
        );
        assert_eq!(run(limits(16 * 108, 64, 16 * 9 * 420)), Ok(16));
        // What `--max-states n` means, with its floors.
        assert_eq!(
            Limits::states(500_000),
            limits_of(500_000, 32_000_000, 32_000_000, 512_000_000)
        );
        assert_eq!(Limits::states(16), limits_of(16, 1 << 22, 1 << 22, 1 << 24));
        // And 0 is no limit to mean.
        let err = reachability(&net(MIXERS), 0).unwrap_err().to_string();
        assert_eq!(err, "a limit of 0 markings leaves nothing to explore");
    }

    #[test]
    fn a_region_of_an_unbounded_net_is_explored_when_it_is_finite() {
        // Two machines and a buffer `B` that grows without bound; within
        // `B ≤ 3` the plant is finite, and one firing out of it is kept.
        let n = net(BUFFER);
        assert!(matches!(
            explore(
                &n,
                Limits::states(1000),
                Marked::All,
                Region::All,
                Beyond::Drop
            )
            .unwrap(),
            Err(Stopped::Unbounded(_))
        ));
        let cs = super::super::constraints::read(
            "[[constraint]]\nname = \"capacity\"\nweights = { B = 1 }\nbound = 3\n",
            Path::new("c.toml"),
            &n,
        )
        .unwrap();
        let within = explore(
            &n,
            Limits::states(1000),
            Marked::All,
            Region::Constraints(&cs),
            Beyond::Drop,
        )
        .unwrap()
        .unwrap();
        assert!(within.markings.iter().all(|m| m[2] <= 3));
        let frontier = explore(
            &n,
            Limits::states(1000),
            Marked::All,
            Region::Constraints(&cs),
            Beyond::Frontier,
        )
        .unwrap()
        .unwrap();
        let beyond: Vec<&Marking> = frontier.markings.iter().filter(|m| m[2] > 3).collect();
        assert!(!beyond.is_empty() && beyond.iter().all(|m| m[2] == 4));
        assert!(
            frontier.dead.iter().all(|&k| frontier.markings[k][2] <= 3),
            "a frontier marking is not explored, so not dead"
        );
        // A constraint the growth keeps (here `W2 ≤ 1`) does not stop it.
        let cs = super::super::constraints::read(
            "[[constraint]]\nname = \"w2\"\nweights = { W2 = 1 }\nbound = 1\n",
            Path::new("c.toml"),
            &n,
        )
        .unwrap();
        assert!(matches!(
            explore(
                &n,
                Limits::states(1000),
                Marked::All,
                Region::Constraints(&cs),
                Beyond::Drop
            )
            .unwrap(),
            Err(Stopped::Unbounded(_))
        ));
    }

    fn limits_of(
        markings: usize,
        token_counts: usize,
        firings: usize,
        name_bytes: usize,
    ) -> Limits {
        Limits {
            markings,
            token_counts,
            firings,
            name_bytes,
        }
    }

    /// Two machines and a buffer: M1 (`start1` controllable, `finish1`
    /// not) puts a part in `B`; M2 takes one from it.
    pub(crate) const BUFFER: &str = r#"name = "two machines"
places = [{ id = "I1", tokens = 1 }, { id = "W1" }, { id = "B" }, { id = "I2", tokens = 1 }, { id = "W2" }]
transitions = [
  { id = "start1", controllable = true, input = { I1 = 1 }, output = { W1 = 1 } },
  { id = "finish1", controllable = false, input = { W1 = 1 }, output = { I1 = 1, B = 1 } },
  { id = "start2", controllable = true, input = { I2 = 1, B = 1 }, output = { W2 = 1 } },
  { id = "finish2", controllable = false, input = { W2 = 1 }, output = { I2 = 1 } },
]
"#;
}
