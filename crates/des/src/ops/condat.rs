//! Control data (`condat`): which controllable events a supervisor
//! disables in each of its states.

use super::supcon::check_spec_alphabet;
use super::sync::{compose, ComposeOptions, Composition};
use crate::automaton::{Automaton, EventId, StateId};
use crate::error::Result;

/// For each state of a supervisor, the controllable events it disables.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Condat {
    /// Indexed by supervisor state; event ids of the supervisor's alphabet,
    /// sorted.
    pub disabled: Vec<Vec<EventId>>,
}

/// The control data of `sup` for `plant`: event σ is disabled in
/// supervisor state x when some reachable closed-loop state (g, x) has
/// δ_G(g, σ) defined, σ controllable and in the supervisor's alphabet,
/// and δ_S(x, σ) undefined. States that the closed loop never reaches
/// disable nothing.
pub fn condat(plant: &Automaton, sup: &Automaton) -> Result<Condat> {
    check_spec_alphabet(plant, sup)?;
    let options = ComposeOptions {
        name_states: false,
        ..ComposeOptions::default()
    };
    let closed_loop = compose(&[plant, sup], Composition::Sync, options)?;
    let mut disabled = vec![Vec::new(); sup.num_states()];
    for s in closed_loop.automaton.states() {
        let g = closed_loop.component_state(s, 0);
        let x = closed_loop.component_state(s, 1);
        for t in plant.transitions(g) {
            if !plant.alphabet().is_controllable(t.event) {
                continue;
            }
            let Some(e) = sup.alphabet().id(plant.alphabet().name(t.event)) else {
                continue;
            };
            if sup.successor(x, e).is_none() {
                disabled[x.index()].push(e);
            }
        }
    }
    for d in &mut disabled {
        d.sort_unstable();
        d.dedup();
    }
    Ok(Condat { disabled })
}

impl Condat {
    /// The disabled events of supervisor state `x`.
    pub fn at(&self, x: StateId) -> &[EventId] {
        &self.disabled[x.index()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    #[test]
    fn a_supervisor_that_forbids_a_restart_disables_it() {
        // Plant: 0 -start-> 1 -stop-> 0 (start controllable).
        // Supervisor allows one start only: 0 -start-> 1 -stop-> 2.
        let plant = auto(
            "G",
            &[("start", true), ("stop", false)],
            &[("0", "start", "1"), ("1", "stop", "0")],
            &["0"],
        );
        let sup = auto(
            "S",
            &[("start", true), ("stop", false)],
            &[("0", "start", "1"), ("1", "stop", "2")],
            &["2"],
        );
        let c = condat(&plant, &sup).unwrap();
        let start = sup.alphabet().id("start").unwrap();
        assert!(c.at(StateId(0)).is_empty());
        assert!(c.at(StateId(1)).is_empty());
        assert_eq!(c.at(sup.state_by_name("2").unwrap()), [start]);
    }
}
