//! Controllability of one modular supervisor on a reduced plant.
//!
//! A plant given as components `G1 … Gn` (its behaviour is their
//! synchronous composition `G`) is often far too large to compose: the
//! manufacturing testbed of Leduc and Wonham (docs/seeds.md B) is of the
//! order of 10^16 states. A modular supervisor `S` mentions few events,
//! and its controllability can be decided on the components that share
//! events with it (their Theorem 2 of "Discrete event systems modeling
//! and control of a manufacturing testbed", 1995, as the testbed paper
//! cites it).
//!
//! **The rule.** The *reduced plant* of `S` is the synchronous
//! composition `G_R` of every component whose alphabet shares at least
//! one event with `S` ([`reduced_plant`]); the others make up `G_O`.
//! Every event of `S` must belong to some component, so `Σ_S ⊆ Σ_R`.
//!
//! - *Sufficient:* if `S` is controllable with respect to `G_R`, it is
//!   controllable with respect to `G = G_R ‖ G_O`. Take a string `s` of
//!   the closed loop `G ‖ S` and an uncontrollable `σ` with `sσ ∈ L(G)`.
//!   If `σ ∉ Σ_S`, `S` does not restrict it. Otherwise `σ ∈ Σ_R`, the
//!   projection `P_R(s)` is a string of `G_R ‖ S`, `P_R(s)σ ∈ L(G_R)`,
//!   so `S` accepts `σ` after `P_S(s)`, and `sσ` is a string of the
//!   closed loop.
//! - *Not necessary* when `G_O` shares events with `G_R`: `G_O` may then
//!   forbid the string the reduced check complains about. So a
//!   counterexample `w` of the reduced check is *lifted*: a shortest
//!   string `s` of the whole plant with `P_R(s) = w` is searched for
//!   (composing `w` as a chain with the components of `G_O` that are
//!   connected to `Σ_R` through shared events; the others cannot
//!   constrain it). If there is one, `s` is a string of `G ‖ S` after
//!   which the plant can do `σ` (no component of `G_O` has `σ`, which
//!   is an event of `S`) and `S` cannot: `S` is not controllable with
//!   respect to `G`. If there is none, the reduced plant grows by every
//!   component that shares an event with it, and the check repeats. Once
//!   no component outside shares an event with the reduced plant, every
//!   counterexample lifts, so the verdict is always the whole plant's.
//!
//! The counterexample `w` is a shortest string of the reduced closed loop
//! that ends where `S` disables an uncontrollable event the reduced plant
//! enables; every counterexample of the whole plant projects onto one of
//! the final reduced plant, so none has fewer events of `Σ_R`.

use super::reach::shortest_path_to;
use super::sync::{compose, ComposeOptions, Composition};
use super::verify::{check_controllable_with, UncontrollableWitness};
use crate::automaton::{Automaton, AutomatonBuilder, StateId};
use crate::error::{Error, Result};

/// The verdict on one supervisor, and the reduced plant it was reached on.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct ModularVerdict {
    /// The supervisor's name.
    pub supervisor: String,
    /// Indices (into the components given) of the reduced plant the
    /// verdict was reached on, in the order given.
    pub reduced: Vec<usize>,
    /// Their names, in the same order.
    pub reduced_names: Vec<String>,
    /// Reachable states of the reduced plant's composition (0 when a
    /// component has no initial state: the plant then has no behaviour).
    pub reduced_states: usize,
    /// Reduced plants tried: 1 when the components sharing events with
    /// the supervisor decide; each further round added the components
    /// sharing events with the previous reduced plant, because its
    /// counterexample was no string of the whole plant.
    pub rounds: usize,
    /// `None`: controllable with respect to the whole plant.
    pub counterexample: Option<ModularCounterexample>,
}

impl ModularVerdict {
    /// The supervisor is controllable with respect to the whole plant.
    pub fn controllable(&self) -> bool {
        self.counterexample.is_none()
    }
}

/// Why a supervisor is not controllable, on the reduced plant and in the
/// whole plant.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct ModularCounterexample {
    /// A shortest string of the reduced closed loop after which the
    /// supervisor disables an uncontrollable event the reduced plant
    /// enables; `plant_state` is the reduced plant's state.
    pub witness: UncontrollableWitness,
    /// A string of the whole plant (and of its closed loop with the
    /// supervisor) whose projection onto the reduced plant's events is
    /// `witness.path`: after it, the whole plant enables `witness.event`.
    pub plant_path: Vec<String>,
}

/// Indices of the components whose alphabets share an event with `sup`:
/// its reduced plant, in the order given.
pub fn reduced_plant(components: &[&Automaton], sup: &Automaton) -> Vec<usize> {
    sharing(components, |name| sup.alphabet().contains(name))
}

fn sharing(components: &[&Automaton], has: impl Fn(&str) -> bool) -> Vec<usize> {
    components
        .iter()
        .enumerate()
        .filter(|(_, c)| c.alphabet().iter().any(|(_, e)| has(&e.name)))
        .map(|(i, _)| i)
        .collect()
}

/// Whether any of `set` has event `name`.
fn in_any(components: &[&Automaton], set: &[usize], name: &str) -> bool {
    set.iter().any(|&i| components[i].alphabet().contains(name))
}

/// Decides whether `sup` is controllable with respect to the synchronous
/// composition of `components`, composing only its reduced plant (see
/// the [module documentation](self) for the rule and why the verdict is
/// the whole plant's). `options` bound every composition (the reduced
/// plant, the closed loop and the lifting search); state names are never
/// built.
///
/// Errors: an event of `sup` that no component has, or whose
/// controllability differs from the plant's, and a composition beyond
/// `options.max_states` ([`Error::StateLimit`]).
pub fn check_controllable_modular(
    components: &[&Automaton],
    sup: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<ModularVerdict> {
    let options = ComposeOptions {
        name_states: false,
        ..options
    };
    for (_, e) in sup.alphabet().iter() {
        if !components.iter().any(|c| c.alphabet().contains(&e.name)) {
            return Err(Error::Incompatible(format!(
                "event `{}` of the supervisor `{}` is in no plant component",
                e.name,
                sup.name()
            )));
        }
    }
    let verdict = |reduced: Vec<usize>, states, rounds, counterexample| ModularVerdict {
        supervisor: sup.name().to_owned(),
        reduced_names: reduced
            .iter()
            .map(|&i| components[i].name().to_owned())
            .collect(),
        reduced,
        reduced_states: states,
        rounds,
        counterexample,
    };
    // A component without behaviour leaves the whole plant without any:
    // nothing can be disabled.
    if let Some(i) = components.iter().position(|c| c.initial().is_none()) {
        return Ok(verdict(vec![i], 0, 1, None));
    }
    let mut reduced = reduced_plant(components, sup);
    let mut rounds = 1;
    loop {
        let parts: Vec<&Automaton> = reduced.iter().map(|&i| components[i]).collect();
        let plant = compose(&parts, Composition::Sync, options)?.automaton;
        let states = plant.num_states();
        let Some(witness) = check_controllable_with(&plant, sup, options)? else {
            return Ok(verdict(reduced, states, rounds, None));
        };
        let grown = sharing(components, |name| in_any(components, &reduced, name));
        if let Some(plant_path) = lift(components, &reduced, &witness.path, options)? {
            let counterexample = ModularCounterexample {
                witness,
                plant_path,
            };
            return Ok(verdict(reduced, states, rounds, Some(counterexample)));
        }
        if grown == reduced {
            // Unreachable: with nothing outside sharing an event, the
            // chain alone is the lifting. Keep the witness as it is.
            let plant_path = witness.path.clone();
            let counterexample = ModularCounterexample {
                witness,
                plant_path,
            };
            return Ok(verdict(reduced, states, rounds, Some(counterexample)));
        }
        reduced = grown;
        rounds += 1;
    }
}

/// A shortest string of the whole plant whose projection onto the events
/// of the `reduced` components is `path`, if there is one.
fn lift(
    components: &[&Automaton],
    reduced: &[usize],
    path: &[String],
    options: ComposeOptions<'_>,
) -> Result<Option<Vec<String>>> {
    // The chain 0 -path[0]-> 1 … -> n over the reduced plant's alphabet.
    let mut b = AutomatonBuilder::new("counterexample");
    for &i in reduced {
        for (_, e) in components[i].alphabet().iter() {
            b.add_event_like(e)
                .map_err(|e| Error::Incompatible(e.to_string()))?;
        }
    }
    let mut states: Vec<StateId> = (0..=path.len()).map(|_| b.add_anonymous_state()).collect();
    b.set_initial(states[0])
        .map_err(|e| Error::Incompatible(e.to_string()))?;
    for (k, name) in path.iter().enumerate() {
        let event = b
            .alphabet()
            .id(name)
            .ok_or_else(|| Error::Incompatible(format!("event `{name}` left the reduced plant")))?;
        b.add_transition(states[k], event, states[k + 1], 0);
    }
    let end = states.pop().expect("at least the initial state");
    b.mark(end);
    let chain = b.build().map_err(|e| Error::Incompatible(e.to_string()))?;

    // The other components that can constrain it: connected to the
    // reduced plant's events through shared events.
    let mut outside: Vec<usize> = Vec::new();
    let mut inside: Vec<usize> = reduced.to_vec();
    loop {
        let more: Vec<usize> = sharing(components, |name| in_any(components, &inside, name))
            .into_iter()
            .filter(|i| !inside.contains(i))
            .collect();
        if more.is_empty() {
            break;
        }
        inside.extend(&more);
        outside.extend(more);
    }
    outside.sort_unstable();
    let mut parts: Vec<&Automaton> = vec![&chain];
    parts.extend(outside.iter().map(|&i| components[i]));
    let product = compose(&parts, Composition::Sync, options)?;
    let p = &product.automaton;
    Ok(
        shortest_path_to(p, |s| product.component_state(s, 0) == end).map(|(_, events)| {
            events
                .iter()
                .map(|&e| p.alphabet().name(e).to_owned())
                .collect()
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::{check_controllable, sync};
    use crate::testing::auto;

    fn check(components: &[&Automaton], sup: &Automaton) -> ModularVerdict {
        check_controllable_modular(components, sup, ComposeOptions::default()).unwrap()
    }

    /// The whole plant's verdict, composed monolithically.
    fn full(components: &[&Automaton], sup: &Automaton) -> Option<UncontrollableWitness> {
        check_controllable(&sync(components).unwrap(), sup).unwrap()
    }

    /// A machine: `s` (controllable) starts it, `f` (uncontrollable)
    /// finishes.
    fn machine(name: &str, s: &str, f: &str) -> Automaton {
        auto(
            name,
            &[(s, true), (f, false)],
            &[("0", s, "1"), ("1", f, "0")],
            &["0"],
        )
    }

    #[test]
    fn the_reduced_plant_holds_the_components_sharing_an_event() {
        let m1 = machine("M1", "s1", "f1");
        let m2 = machine("M2", "s2", "f2");
        let m3 = machine("M3", "s3", "f3");
        let sup = auto("S", &[("s1", true), ("f2", false)], &[], &["0"]);
        assert_eq!(reduced_plant(&[&m1, &m2, &m3], &sup), [0, 1]);
    }

    #[test]
    fn a_supervisor_that_only_disables_starts_is_controllable_on_a_smaller_plant() {
        // S lets M1 start only after M2 finished, alternating. M3 does
        // not matter: the reduced plant is M1 || M2 (4 states of 8).
        let m1 = machine("M1", "s1", "f1");
        let m2 = machine("M2", "s2", "f2");
        let m3 = machine("M3", "s3", "f3");
        let sup = auto(
            "S",
            &[("s1", true), ("f2", false)],
            &[("0", "f2", "1"), ("1", "s1", "0"), ("1", "f2", "1")],
            &["0"],
        );
        let v = check(&[&m1, &m2, &m3], &sup);
        assert!(v.controllable(), "{v:?}");
        assert_eq!(v.reduced_names, ["M1", "M2"]);
        assert_eq!((v.reduced_states, v.rounds), (4, 1));
        assert_eq!(full(&[&m1, &m2, &m3], &sup), None);
    }

    #[test]
    fn disabling_an_uncontrollable_event_gives_the_shortest_counterexample() {
        // S forgets the f2 self-loop in state 1: a second f2 is refused.
        let m1 = machine("M1", "s1", "f1");
        let m2 = machine("M2", "s2", "f2");
        let m3 = machine("M3", "s3", "f3");
        let sup = auto(
            "S",
            &[("s1", true), ("f2", false)],
            &[("0", "f2", "1"), ("1", "s1", "0")],
            &["0"],
        );
        let v = check(&[&m1, &m2, &m3], &sup);
        let c = v.counterexample.expect("f2 twice is refused");
        assert_eq!(c.witness.path, ["s2", "f2", "s2"]);
        assert_eq!(c.witness.event, "f2");
        assert_eq!(c.plant_path, c.witness.path);
        let whole = full(&[&m1, &m2, &m3], &sup).expect("the whole plant agrees");
        assert_eq!(whole.path.len(), c.witness.path.len());
        assert_eq!(whole.event, "f2");
    }

    #[test]
    fn a_counterexample_the_rest_of_the_plant_forbids_grows_the_reduced_plant() {
        // S refuses f1 after s1 (not controllable on M1 alone), but a
        // lock L, which shares no event with S, never lets M1 start: the
        // whole plant never starts M1, so S is controllable.
        let m1 = machine("M1", "s1", "f1");
        let lock = auto("L", &[("s1", true), ("go", true)], &[], &["0"]);
        let sup = auto("S", &[("f1", false)], &[], &["0"]);
        assert_eq!(reduced_plant(&[&m1, &lock], &sup), [0]);
        let v = check(&[&m1, &lock], &sup);
        assert!(v.controllable(), "{v:?}");
        assert_eq!((v.rounds, v.reduced_names.len()), (2, 2));
        assert_eq!(full(&[&m1, &lock], &sup), None);
    }

    #[test]
    fn a_counterexample_is_lifted_through_events_the_reduced_plant_does_not_have() {
        // M1 may start only after a token `t` of T, which shares nothing
        // with S. The reduced string `s1` becomes `t s1` in the plant.
        let m1 = machine("M1", "s1", "f1");
        let token = auto(
            "T",
            &[("t", true), ("s1", true)],
            &[("0", "t", "1"), ("1", "s1", "0")],
            &["0"],
        );
        let sup = auto("S", &[("f1", false)], &[], &["0"]);
        let v = check(&[&m1, &token], &sup);
        let c = v.counterexample.expect("f1 is refused");
        assert_eq!(v.rounds, 1);
        assert_eq!(c.witness.path, ["s1"]);
        assert_eq!(c.plant_path, ["t", "s1"]);
        assert!(full(&[&m1, &token], &sup).is_some());
    }

    #[test]
    fn an_event_in_no_component_is_an_error() {
        let m1 = machine("M1", "s1", "f1");
        let sup = auto("S", &[("zz", true)], &[], &["0"]);
        let err = check_controllable_modular(&[&m1], &sup, ComposeOptions::default())
            .unwrap_err()
            .to_string();
        assert!(err.contains("`zz`") && err.contains("`S`"), "{err}");
    }

    #[test]
    fn a_component_without_behaviour_makes_everything_controllable() {
        let m1 = machine("M1", "s1", "f1");
        let none = Automaton::empty("E", crate::Alphabet::new());
        let sup = auto("S", &[("f1", false)], &[], &["0"]);
        let v = check(&[&m1, &none], &sup);
        assert!(v.controllable());
        assert_eq!(full(&[&m1, &none], &sup), None);
    }
}
