//! The variable layout: which BDD variables hold which component's state.
//!
//! Component `c` with `n` states takes `⌈log2 n⌉` bits; state `s` is the
//! binary number `s` (most significant bit first). Every bit has a
//! current-state variable `2k` and a next-state variable `2k + 1`, so the
//! two copies are interleaved. Components are laid out in the order of
//! [`component_order`], which keeps components that share events close.
//!
//! This module knows no BDD library: it says where the bits go, and the
//! relations are built from it in [`crate::relation`].

use crate::error::{Error, Result};
use des::{Automaton, StateId};
use std::collections::{BTreeMap, VecDeque};

/// Whether a component is a plant or a specification.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// A plant component: its alphabet is what can happen.
    Plant,
    /// A specification: its alphabet is what it constrains.
    Spec,
}

/// One event of the model, shared by every component that has it.
#[derive(Debug, Clone)]
pub struct EventInfo {
    /// The event's name.
    pub name: String,
    /// Controllable or not.
    pub controllable: bool,
    /// The components (input indices) with the event in their alphabet.
    pub participants: Vec<usize>,
}

/// One component: its place in the layout and its transitions.
#[derive(Debug, Clone)]
pub struct ComponentInfo {
    /// The automaton's name.
    pub name: String,
    /// Plant or specification.
    pub role: Role,
    /// Number of states.
    pub num_states: usize,
    /// Bits of its state code.
    pub bits: usize,
    /// Index of its first bit among all bits (current var `2 * (offset + k)`).
    pub offset: usize,
    /// The initial state (`None`: the component has no state).
    pub initial: Option<u32>,
    /// The marked states.
    pub marked: Vec<u32>,
    /// Transitions `(source, model event, target)`.
    pub transitions: Vec<(u32, usize, u32)>,
}

impl ComponentInfo {
    /// The current-state variable index of bit `k` (0 = most significant).
    pub fn current_var(&self, k: usize) -> usize {
        2 * (self.offset + k)
    }

    /// The next-state variable index of bit `k`.
    pub fn next_var(&self, k: usize) -> usize {
        2 * (self.offset + k) + 1
    }

    /// The value of bit `k` in the code of `state`.
    pub fn bit(&self, state: u32, k: usize) -> bool {
        (state >> (self.bits - 1 - k)) & 1 == 1
    }
}

/// Components (plants first, then specifications, in input order), the
/// events and the variable layout.
#[derive(Debug, Clone)]
pub struct Layout {
    /// All components in input order: plants, then specifications.
    pub components: Vec<ComponentInfo>,
    /// Component indices in variable order.
    pub order: Vec<usize>,
    /// The events, sorted by name.
    pub events: Vec<EventInfo>,
    /// Number of BDD variables (current and next).
    pub num_vars: usize,
}

/// Bits needed for `n` states: `⌈log2 n⌉` (0 for one state or none).
pub fn bits_for(n: usize) -> usize {
    if n <= 1 {
        0
    } else {
        (usize::BITS - (n - 1).leading_zeros()) as usize
    }
}

impl Layout {
    /// Lays out `plants` and `specs`. Fails when components disagree on an
    /// event's controllability or a specification has an event no plant
    /// has.
    pub fn new(plants: &[Automaton], specs: &[Automaton]) -> Result<Layout> {
        if plants.is_empty() {
            return Err(Error::NoPlant);
        }
        let all: Vec<(&Automaton, Role)> = plants
            .iter()
            .map(|a| (a, Role::Plant))
            .chain(specs.iter().map(|a| (a, Role::Spec)))
            .collect();
        // Events by name: controllability and the component that stated
        // it, and the participants. A component whose file does not state
        // controllability (a `.gen` specification) takes it from the
        // others; an event no component states it for is uncontrollable,
        // as everywhere in `des`.
        type Entry = (Option<(bool, usize)>, Vec<usize>);
        let mut by_name: BTreeMap<&str, Entry> = BTreeMap::new();
        for (c, (a, _)) in all.iter().enumerate() {
            let stated = a.alphabet().controllability_stated();
            for (_, e) in a.alphabet().iter() {
                let entry = by_name.entry(e.name.as_str()).or_default();
                entry.1.push(c);
                if !stated {
                    continue;
                }
                match entry.0 {
                    None => entry.0 = Some((e.controllable, c)),
                    Some((controllable, by)) if controllable != e.controllable => {
                        let (first, second) = if controllable {
                            (all[by].0.name(), a.name())
                        } else {
                            (a.name(), all[by].0.name())
                        };
                        return Err(Error::Controllability {
                            event: e.name.clone(),
                            first: first.to_owned(),
                            second: second.to_owned(),
                        });
                    }
                    Some(_) => {}
                }
            }
        }
        for spec in specs {
            for (_, e) in spec.alphabet().iter() {
                let in_plant = plants.iter().any(|p| p.alphabet().contains(&e.name));
                if !in_plant {
                    return Err(Error::SpecEvent {
                        event: e.name.clone(),
                        spec: spec.name().to_owned(),
                    });
                }
            }
        }
        let events: Vec<EventInfo> = by_name
            .iter()
            .map(|(name, (stated, p))| EventInfo {
                name: (*name).to_owned(),
                controllable: stated.is_some_and(|(c, _)| c),
                participants: p.clone(),
            })
            .collect();
        let index: BTreeMap<&str, usize> =
            by_name.keys().enumerate().map(|(i, n)| (*n, i)).collect();
        let mut components: Vec<ComponentInfo> = all
            .iter()
            .map(|(a, role)| ComponentInfo {
                name: a.name().to_owned(),
                role: *role,
                num_states: a.num_states(),
                bits: bits_for(a.num_states()),
                offset: 0,
                initial: a.initial().map(|s| s.0),
                marked: a.marked_states().map(|s| s.0).collect(),
                transitions: a
                    .iter_transitions()
                    .map(|(s, e, t)| (s.0, index[a.alphabet().name(e)], t.0))
                    .collect(),
            })
            .collect();
        let order = component_order(components.len(), &events);
        let mut offset = 0;
        for &c in &order {
            components[c].offset = offset;
            offset += components[c].bits;
        }
        let num_vars = 2 * offset;
        const LIMIT: usize = u16::MAX as usize - 2;
        if num_vars > LIMIT {
            return Err(Error::TooManyVariables {
                needed: num_vars,
                limit: LIMIT,
            });
        }
        Ok(Layout {
            components,
            order,
            events,
            num_vars,
        })
    }

    /// The index of the event named `name`.
    pub fn event(&self, name: &str) -> Option<usize> {
        self.events
            .binary_search_by(|e| e.name.as_str().cmp(name))
            .ok()
    }

    /// Checks a tuple of component states (input order).
    pub fn check_tuple(&self, states: &[StateId]) -> Result<()> {
        if states.len() != self.components.len() {
            return Err(Error::StateTuple(format!(
                "{} states for {} components",
                states.len(),
                self.components.len()
            )));
        }
        for (c, s) in self.components.iter().zip(states) {
            if s.index() >= c.num_states {
                return Err(Error::StateTuple(format!(
                    "state {s} of `{}`, which has {} states",
                    c.name, c.num_states
                )));
            }
        }
        Ok(())
    }
}

/// A variable order of the components: a Cuthill–McKee walk over the
/// graph whose edges join components sharing an event. Each connected
/// part starts at a component of least degree; neighbours are visited in
/// order of degree, then of the number of shared events (more first).
pub fn component_order(n: usize, events: &[EventInfo]) -> Vec<usize> {
    let mut weight: Vec<BTreeMap<usize, usize>> = vec![BTreeMap::new(); n];
    for e in events {
        for &a in &e.participants {
            for &b in &e.participants {
                if a != b {
                    *weight[a].entry(b).or_insert(0) += 1;
                }
            }
        }
    }
    let degree: Vec<usize> = weight.iter().map(BTreeMap::len).collect();
    let mut placed = vec![false; n];
    let mut order = Vec::with_capacity(n);
    while order.len() < n {
        let Some(start) = (0..n).filter(|&c| !placed[c]).min_by_key(|&c| degree[c]) else {
            break;
        };
        placed[start] = true;
        let mut queue = VecDeque::from([start]);
        while let Some(c) = queue.pop_front() {
            order.push(c);
            let mut next: Vec<(usize, usize)> = weight[c]
                .iter()
                .filter(|(d, _)| !placed[**d])
                .map(|(&d, &w)| (d, w))
                .collect();
            next.sort_by_key(|&(d, w)| (degree[d], usize::MAX - w, d));
            for (d, _) in next {
                placed[d] = true;
                queue.push_back(d);
            }
        }
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits() {
        assert_eq!(
            [0, 1, 2, 3, 4, 5, 8, 9].map(bits_for),
            [0, 0, 1, 2, 2, 3, 3, 4]
        );
    }

    #[test]
    fn ring_order_keeps_neighbours_close() {
        let f = crate::families::ring(6).unwrap();
        let l = Layout::new(&f.plants, &f.specs).unwrap();
        let pos: Vec<usize> = {
            let mut p = vec![0; l.order.len()];
            for (i, &c) in l.order.iter().enumerate() {
                p[c] = i;
            }
            p
        };
        // Every event's participants lie within a window of 4 positions.
        for e in &l.events {
            let ps: Vec<usize> = e.participants.iter().map(|&c| pos[c]).collect();
            let span = ps.iter().max().unwrap() - ps.iter().min().unwrap();
            assert!(span <= 4, "{}: {ps:?}", e.name);
        }
    }

    #[test]
    fn a_component_that_does_not_state_controllability_takes_the_others() {
        let one = |name: &str, controllable: bool, stated: bool| {
            let mut b = des::AutomatonBuilder::new(name);
            let a = b.add_event("a", controllable).unwrap();
            let s = b.add_state("s");
            b.set_initial(s).unwrap();
            b.mark(s);
            b.add_transition(s, a, s, 1);
            b.set_controllability_stated(stated);
            b.build().unwrap()
        };
        let plant = [one("P", true, true)];
        // A `.gen` specification reads its events as uncontrollable
        // without saying so: the plant's word stands.
        let l = Layout::new(&plant, &[one("S", false, false)]).unwrap();
        assert!(l.events[0].controllable);
        // Stated on both sides, a disagreement is an error.
        let err = Layout::new(&plant, &[one("S", false, true)]).unwrap_err();
        assert!(matches!(err, Error::Controllability { .. }), "{err}");
        // Stated nowhere: uncontrollable, as everywhere in `des`.
        let l = Layout::new(&[one("P", true, false)], &[]).unwrap();
        assert!(!l.events[0].controllable);
    }
}
