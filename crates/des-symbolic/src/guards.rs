//! One guard per controllable event: where the supervisor lets it fire.
//!
//! The exact set is `allowed_e`: closed-loop states with an `e` transition
//! into a good state. A guard only has to agree with it where the question
//! arises: on the closed loop's states where plant ∥ specifications
//! enable `e` (the care set); elsewhere either value will do. Two
//! candidates are simplified against the care set and the smaller kept:
//! - `allowed_e` with whole components abstracted (`∃`) while the result
//!   still excludes every forbidden care state;
//! - the complement of the forbidden states (care set minus `allowed_e`),
//!   abstracted the same way while it still excludes every allowed one.

use crate::relation::Model;
use crate::supcon::Fixpoint;
use biodivine_lib_bdd::{Bdd, BddVariable};

/// How a guard is stated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GuardForm {
    /// The states where the event may fire (over-approximated off the
    /// care set).
    Allowed,
    /// The complement of the states where it is forbidden.
    NotForbidden,
}

/// The guard of one controllable event.
#[derive(Debug, Clone)]
pub struct Guard {
    /// Index of the event in the model's layout.
    pub event: usize,
    /// The guard, over current-state variables.
    pub bdd: Bdd,
    /// Which candidate it is.
    pub form: GuardForm,
}

/// The guards of every controllable event, in event order.
pub fn guards(model: &Model, fix: &Fixpoint) -> Vec<Guard> {
    let events = &model.layout().events;
    (0..events.len())
        .filter(|&e| events[e].controllable)
        .map(|e| {
            let allowed = model.pre(&fix.good, e).and(&fix.supervisor);
            let care = model.enabled(e).and(&fix.supervisor);
            let forbidden = care.and_not(&allowed);
            let allowed_care = care.and(&allowed);
            let a = abstract_components(model, &allowed_care, &forbidden);
            let f = abstract_components(model, &forbidden, &allowed_care).not();
            let (bdd, form) = if f.size() < a.size() {
                (f, GuardForm::NotForbidden)
            } else {
                (a, GuardForm::Allowed)
            };
            Guard {
                event: e,
                bdd,
                form,
            }
        })
        .collect()
}

/// `set` with the variables of as many components as possible quantified
/// away (`∃`), one component at a time in layout order, as long as the
/// result stays disjoint from `avoid`.
fn abstract_components(model: &Model, set: &Bdd, avoid: &Bdd) -> Bdd {
    let layout = model.layout();
    let mut result = set.clone();
    for &c in &layout.order {
        let comp = &layout.components[c];
        if comp.bits == 0 {
            continue;
        }
        let vars: Vec<BddVariable> = (0..comp.bits)
            .map(|k| BddVariable::from_index(comp.current_var(k)))
            .collect();
        let wider = result.exists(&vars);
        if wider.and(avoid).is_false() {
            result = wider;
        }
    }
    result
}
