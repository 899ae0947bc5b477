//! The reachability graph of a net, as an automaton.
//!
//! Markings are explored breadth-first from the initial one, transitions
//! in file order, so the state numbers are reproducible. Each marking is a
//! state named by [`PetriNet::marking_name`]; each transition an event of
//! the same id and controllability (an unobservable transition stays an
//! event: hiding it is a later step's choice). The initial marking is the
//! one marked state: a batch returns to where it started.
//!
//! An unbounded net has no finite graph. It is recognised as soon as a
//! new marking covers one of its ancestors (at least as many tokens
//! everywhere, more somewhere: the firings between them can repeat
//! forever, the Karp–Miller argument) and refused with the place that
//! grows and the firing sequence. A bounded net whose graph exceeds the
//! state limit is refused too, naming the limit.

use super::{Marking, PetriNet};
use crate::automaton::{Automaton, AutomatonBuilder};
use crate::error::{Error, Result};
use rustc_hash::FxHashMap;

/// The default state limit, as for compositions.
pub const DEFAULT_MAX_STATES: usize = crate::ops::sync::DEFAULT_MAX_STATES;

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

/// Explores the markings of `net` reachable from its initial marking, at
/// most `max_states` of them; the initial marking is the marked state.
pub fn reachability(net: &PetriNet, max_states: usize) -> Result<Reachability> {
    reachability_with(net, max_states, Marked::Initial, &|_| true)
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
    if !keep(net.initial()) {
        return Err(Error::Incompatible(format!(
            "the initial marking of `{}` is not among the markings kept",
            net.name()
        )));
    }
    let mut markings: Vec<Marking> = vec![net.initial().clone()];
    // For each marking: the marking it was first reached from, and how.
    let mut parent: Vec<Option<(usize, usize)>> = vec![None];
    let mut index: FxHashMap<Marking, usize> = FxHashMap::default();
    index.insert(net.initial().clone(), 0);
    let mut edges: Vec<(usize, usize, usize)> = Vec::new();
    let mut dead = Vec::new();
    let mut next = 0;
    while next < markings.len() {
        let m = markings[next].clone();
        let mut enabled = false;
        for t in 0..net.transitions().len() {
            if !net.is_enabled(&m, t) {
                continue;
            }
            enabled = true;
            let Some(after) = net.fire(&m, t) else {
                return Err(unbounded(net, &parent, next, t, None));
            };
            if !keep(&after) {
                continue;
            }
            let target = match index.get(&after) {
                Some(&k) => k,
                None => {
                    if let Some(place) = covered_ancestor(&markings, &parent, next, &after) {
                        return Err(unbounded(net, &parent, next, t, Some(place)));
                    }
                    if markings.len() == max_states {
                        return Err(Error::Incompatible(format!(
                            "the reachability graph of `{}` exceeds the limit of {max_states} states",
                            net.name()
                        )));
                    }
                    index.insert(after.clone(), markings.len());
                    markings.push(after);
                    parent.push(Some((next, t)));
                    markings.len() - 1
                }
            };
            edges.push((next, t, target));
        }
        if !enabled {
            dead.push(next);
        }
        next += 1;
    }

    let mut b = AutomatonBuilder::new(net.name());
    let events: Vec<_> = net
        .transitions()
        .iter()
        .map(|t| b.add_event(&t.id, t.controllable))
        .collect::<std::result::Result<_, _>>()
        .map_err(|e| Error::Incompatible(format!("net `{}`: {e}", net.name())))?;
    let states: Vec<_> = markings
        .iter()
        .map(|m| b.add_state(&net.marking_name(m)))
        .collect();
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
    let mut bounds = vec![0u32; net.places().len()];
    for m in &markings {
        for (b, &k) in bounds.iter_mut().zip(m) {
            *b = (*b).max(k);
        }
    }
    Ok(Reachability {
        automaton,
        markings,
        bounds,
        dead,
        parent,
        edges,
    })
}

/// A place that grows when `after` covers `at` or one of its ancestors
/// (`after` ≥ it everywhere, and differs).
fn covered_ancestor(
    markings: &[Marking],
    parent: &[Option<(usize, usize)>],
    at: usize,
    after: &[u32],
) -> Option<usize> {
    let mut k = Some(at);
    while let Some(i) = k {
        let m = &markings[i];
        if m.iter().zip(after).all(|(a, b)| a <= b) {
            if let Some(p) = m.iter().zip(after).position(|(a, b)| a < b) {
                return Some(p);
            }
        }
        k = parent[i].map(|(from, _)| from);
    }
    None
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

/// The refusal of an unbounded net: the place that grows (`None`: a
/// count beyond `u32`) and the firing sequence from the initial marking.
fn unbounded(
    net: &PetriNet,
    parent: &[Option<(usize, usize)>],
    at: usize,
    last: usize,
    place: Option<usize>,
) -> Error {
    let sequence: Vec<&str> = path_to(parent, at)
        .into_iter()
        .chain([last])
        .map(|t| net.transitions()[t].id.as_str())
        .collect();
    let what = match place {
        Some(p) => format!("place `{}` grows without bound", net.places()[p].id),
        None => "a place's tokens exceed 2^32 - 1".to_owned(),
    };
    Error::Incompatible(format!(
        "net `{}` is unbounded: {what} (the firing sequence {} can repeat its cycle forever); \
         it has no finite reachability graph",
        net.name(),
        sequence.join(" ")
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
        let err = reachability(&net(MIXERS), 15).unwrap_err().to_string();
        assert_eq!(
            err,
            "the reachability graph of `mixers` exceeds the limit of 15 states"
        );
    }
}
