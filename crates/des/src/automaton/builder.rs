//! Incremental construction of an [`Automaton`] from names, with checks.

use super::{Alphabet, Automaton, ControllabilityConflict, Event, EventId, StateId, Transition};
use fixedbitset::FixedBitSet;
use rustc_hash::FxHashMap;

/// What can make a builder refuse its input. File readers attach the
/// file name; `line` fields come from the `line` arguments given to the
/// builder (0 = unknown).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    /// Two transitions leave the same state on the same event for
    /// different targets.
    #[error("nondeterministic: state `{state}` has two transitions on `{event}` (to `{first}` and to `{second}`)")]
    Nondeterministic {
        /// The source state.
        state: String,
        /// The event.
        event: String,
        /// The target of the transition seen first.
        first: String,
        /// The target of the other.
        second: String,
        /// Line of the transition seen first.
        first_line: u32,
        /// Line of the other.
        line: u32,
    },
    /// More than one initial state (a nondeterministic automaton).
    #[error("nondeterministic: two initial states, `{first}` and `{second}`")]
    TwoInitialStates {
        /// The first initial state.
        first: String,
        /// The second.
        second: String,
    },
    /// A transition names an event missing from the alphabet.
    #[error("event `{event}` is not in the alphabet")]
    UnknownEvent {
        /// The event name.
        event: String,
        /// Line of the transition.
        line: u32,
    },
    /// The states were declared explicitly and this one is not among them.
    #[error("state `{state}` is not declared")]
    UnknownState {
        /// The state name.
        state: String,
        /// Line of the reference.
        line: u32,
    },
    /// Controllability disagrees between two declarations.
    #[error(transparent)]
    Controllability(#[from] ControllabilityConflict),
    /// More states or transitions than 32-bit ids can count.
    #[error("too large: more than 2^32 - 1 states or transitions")]
    TooLarge,
}

impl BuildError {
    /// The line the error refers to, 0 if unknown.
    pub fn line(&self) -> u32 {
        match self {
            BuildError::Nondeterministic { line, .. }
            | BuildError::UnknownEvent { line, .. }
            | BuildError::UnknownState { line, .. } => *line,
            _ => 0,
        }
    }
}

/// Builds an automaton from states, events and transitions given in any
/// order; [`AutomatonBuilder::build`] sorts the transitions, drops exact
/// duplicates and rejects nondeterminism.
#[derive(Debug, Clone, Default)]
pub struct AutomatonBuilder {
    name: String,
    alphabet: Alphabet,
    state_names: Vec<String>,
    state_index: FxHashMap<String, StateId>,
    /// When set, states must be declared before they are referenced by
    /// name (formats with an explicit state list).
    closed_states: bool,
    any_named: bool,
    initial: Option<StateId>,
    marked: Vec<StateId>,
    /// (source, event, target, line)
    transitions: Vec<(u32, u32, u32, u32)>,
}

impl AutomatonBuilder {
    /// A builder for an automaton called `name`.
    pub fn new(name: impl Into<String>) -> Self {
        AutomatonBuilder {
            name: name.into(),
            ..Self::default()
        }
    }

    /// Renames the automaton under construction.
    pub fn set_name(&mut self, name: impl Into<String>) {
        self.name = name.into();
    }

    /// The alphabet so far.
    pub fn alphabet(&self) -> &Alphabet {
        &self.alphabet
    }

    /// Number of states so far.
    pub fn num_states(&self) -> usize {
        self.state_names.len()
    }

    /// From now on, referring to an undeclared state name is an error.
    pub fn close_states(&mut self) {
        self.closed_states = true;
    }

    /// Records that the source does not state controllability (see
    /// [`Alphabet`]).
    pub fn set_controllability_stated(&mut self, stated: bool) {
        self.alphabet.set_controllability_stated(stated);
    }

    /// Adds an event (or finds it; the controllability must agree).
    pub fn add_event(&mut self, name: &str, controllable: bool) -> Result<EventId, BuildError> {
        Ok(self.alphabet.insert(name, controllable)?)
    }

    /// Adds `event` with its controllability and observability
    /// ([`Alphabet::insert_event`]).
    pub fn add_event_like(&mut self, event: &Event) -> Result<EventId, BuildError> {
        Ok(self.alphabet.insert_event(event)?)
    }

    /// Makes event `id` unobservable.
    pub fn set_unobservable(&mut self, id: EventId) {
        self.alphabet.set_unobservable(id);
    }

    /// Adds the state `name` or returns the existing one.
    pub fn add_state(&mut self, name: &str) -> StateId {
        if let Some(&s) = self.state_index.get(name) {
            return s;
        }
        let s = StateId(self.state_names.len() as u32);
        self.state_names.push(name.to_owned());
        self.state_index.insert(name.to_owned(), s);
        self.any_named = true;
        s
    }

    /// Adds a state without a name of its own (it is named by its index
    /// unless other states carry names).
    pub fn add_anonymous_state(&mut self) -> StateId {
        let s = StateId(self.state_names.len() as u32);
        self.state_names.push(s.0.to_string());
        s
    }

    /// The state called `name`; creates it unless states are closed.
    pub fn state(&mut self, name: &str, line: u32) -> Result<StateId, BuildError> {
        if let Some(&s) = self.state_index.get(name) {
            return Ok(s);
        }
        if self.closed_states {
            return Err(BuildError::UnknownState {
                state: name.to_owned(),
                line,
            });
        }
        Ok(self.add_state(name))
    }

    /// The state called `name` if it exists.
    pub fn find_state(&self, name: &str) -> Option<StateId> {
        self.state_index.get(name).copied()
    }

    /// Sets the initial state; a second, different one is an error.
    pub fn set_initial(&mut self, s: StateId) -> Result<(), BuildError> {
        match self.initial {
            Some(first) if first != s => Err(BuildError::TwoInitialStates {
                first: self.state_names[first.index()].clone(),
                second: self.state_names[s.index()].clone(),
            }),
            _ => {
                self.initial = Some(s);
                Ok(())
            }
        }
    }

    /// Sets the initial state by name.
    pub fn set_initial_by_name(&mut self, name: &str) -> Result<(), BuildError> {
        let s = self.state(name, 0)?;
        self.set_initial(s)
    }

    /// Marks `s`.
    pub fn mark(&mut self, s: StateId) {
        self.marked.push(s);
    }

    /// Marks the state `name`, creating it if needed.
    pub fn mark_by_name(&mut self, name: &str) {
        let s = self.add_state(name);
        self.mark(s);
    }

    /// Adds δ(source, event) = target; `line` is for error messages.
    pub fn add_transition(&mut self, source: StateId, event: EventId, target: StateId, line: u32) {
        self.transitions.push((source.0, event.0, target.0, line));
    }

    /// Adds a transition by names; the event must be in the alphabet.
    pub fn add_transition_by_name(
        &mut self,
        source: &str,
        event: &str,
        target: &str,
        line: u32,
    ) -> Result<(), BuildError> {
        let e = self
            .alphabet
            .id(event)
            .ok_or_else(|| BuildError::UnknownEvent {
                event: event.to_owned(),
                line,
            })?;
        let s = self.state(source, line)?;
        let t = self.state(target, line)?;
        self.add_transition(s, e, t, line);
        Ok(())
    }

    /// Sorts and checks the transitions and produces the automaton.
    pub fn build(mut self) -> Result<Automaton, BuildError> {
        let n = self.state_names.len();
        if n >= u32::MAX as usize || self.transitions.len() >= u32::MAX as usize {
            return Err(BuildError::TooLarge);
        }
        self.transitions.sort_unstable();
        // Exact duplicates (same source, event, target) collapse; two
        // targets for one (source, event) is nondeterminism.
        let mut edges = Vec::with_capacity(self.transitions.len());
        let mut counts = vec![0u32; n + 1];
        let mut prev: Option<(u32, u32, u32, u32)> = None;
        for &(s, e, t, line) in &self.transitions {
            if let Some((ps, pe, pt, pline)) = prev {
                if ps == s && pe == e {
                    if pt == t {
                        continue;
                    }
                    let (first, second, first_line, line) = if pline <= line {
                        (pt, t, pline, line)
                    } else {
                        (t, pt, line, pline)
                    };
                    return Err(BuildError::Nondeterministic {
                        state: self.state_names[s as usize].clone(),
                        event: self.alphabet.name(EventId(e)).to_owned(),
                        first: self.state_names[first as usize].clone(),
                        second: self.state_names[second as usize].clone(),
                        first_line,
                        line,
                    });
                }
            }
            prev = Some((s, e, t, line));
            counts[s as usize + 1] += 1;
            edges.push(Transition {
                event: EventId(e),
                target: StateId(t),
            });
        }
        for i in 0..n {
            counts[i + 1] += counts[i];
        }
        let mut marked = FixedBitSet::with_capacity(n);
        for s in self.marked {
            marked.insert(s.index());
        }
        let names = super::StateNames::from_option(self.any_named.then_some(self.state_names));
        Ok(Automaton::from_parts(
            self.name,
            self.alphabet,
            names,
            self.initial,
            marked,
            counts,
            edges,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nondeterminism_is_reported_with_both_lines() {
        let mut b = AutomatonBuilder::new("g");
        b.add_event("a", true).unwrap();
        b.add_transition_by_name("s", "a", "t", 7).unwrap();
        b.add_transition_by_name("s", "a", "u", 3).unwrap();
        match b.build().unwrap_err() {
            BuildError::Nondeterministic {
                state,
                event,
                first,
                second,
                first_line,
                line,
            } => {
                assert_eq!((state.as_str(), event.as_str()), ("s", "a"));
                assert_eq!((first.as_str(), second.as_str()), ("u", "t"));
                assert_eq!((first_line, line), (3, 7));
            }
            other => panic!("unexpected {other:?}"),
        }
    }

    #[test]
    fn exact_duplicate_transitions_collapse() {
        let mut b = AutomatonBuilder::new("g");
        b.add_event("a", true).unwrap();
        b.add_transition_by_name("s", "a", "t", 1).unwrap();
        b.add_transition_by_name("s", "a", "t", 2).unwrap();
        assert_eq!(b.build().unwrap().num_transitions(), 1);
    }

    #[test]
    fn two_initial_states_are_rejected_but_repeating_one_is_fine() {
        let mut b = AutomatonBuilder::new("g");
        b.set_initial_by_name("p").unwrap();
        b.set_initial_by_name("p").unwrap();
        assert!(matches!(
            b.set_initial_by_name("q"),
            Err(BuildError::TwoInitialStates { .. })
        ));
    }

    #[test]
    fn closed_state_sets_reject_undeclared_states_and_unknown_events() {
        let mut b = AutomatonBuilder::new("g");
        b.add_event("a", false).unwrap();
        b.add_state("p");
        b.close_states();
        let err = b.add_transition_by_name("p", "a", "q", 9).unwrap_err();
        assert_eq!(err.line(), 9);
        assert!(matches!(err, BuildError::UnknownState { .. }));
        let err = b.add_transition_by_name("p", "b", "p", 4).unwrap_err();
        assert!(matches!(err, BuildError::UnknownEvent { line: 4, .. }));
    }

    #[test]
    fn anonymous_states_leave_the_automaton_unnamed() {
        let mut b = AutomatonBuilder::new("g");
        let s0 = b.add_anonymous_state();
        let s1 = b.add_anonymous_state();
        let a = b.add_event("a", true).unwrap();
        b.add_transition(s0, a, s1, 0);
        b.set_initial(s0).unwrap();
        let g = b.build().unwrap();
        assert!(!g.has_state_names());
        assert_eq!(g.state_name(s1), "1");
    }
}
