//! The supremal controllable, nonblocking supervisor as a set of states of
//! plant ∥ specifications, by the standard fixpoint.
//!
//! 1. `R`: the states reachable from the initial state.
//! 2. Bad: states of `R` where a plant component set enables an
//!    uncontrollable event (every plant participant has it) that a
//!    specification disables (a specification with the event in its
//!    alphabet lacks it in its current state).
//! 3. Good = `R` minus the states that reach a bad one through
//!    uncontrollable events. Then repeat: keep the good states that reach
//!    a marked good state through good states; remove from `R` the states
//!    that reach a removed one through uncontrollable events; until
//!    nothing changes.
//! 4. The supervisor: the good states reachable from the initial state
//!    through good states (empty if the initial state is not good).

use crate::reach::{reachable, search, Direction};
use crate::relation::Model;
use biodivine_lib_bdd::Bdd;

/// The sets the fixpoint produced.
#[derive(Debug, Clone)]
pub struct Fixpoint {
    /// States of plant ∥ specifications reachable without control.
    pub reachable: Bdd,
    /// The largest controllable, coreachable subset of `reachable`.
    pub good: Bdd,
    /// `good` reachable from the initial state: the closed loop's states.
    pub supervisor: Bdd,
    /// Rounds of the nonblocking/controllability loop.
    pub rounds: usize,
}

/// Runs the fixpoint on `model`.
pub fn fixpoint(model: &Model) -> Fixpoint {
    let reach = reachable(model);
    let events = &model.layout().events;
    let uncontrollable = |e: usize| !events[e].controllable;
    let mut bad = model.mk_false();
    for (e, r) in model.relations.iter().enumerate() {
        if uncontrollable(e) {
            bad = bad.or(&r.plant_enabled.and_not(&r.spec_enabled));
        }
    }
    let bad = bad.and(&reach);
    let closure = |from: &Bdd| search(model, from, &reach, Direction::Backward, uncontrollable);
    let mut good = reach.and_not(&closure(&bad));
    let mut rounds = 0;
    loop {
        rounds += 1;
        let target = model.marked().and(&good);
        let coreach = search(model, &target, &good, Direction::Backward, |_| true);
        if good.and_not(&coreach).is_false() {
            break;
        }
        good = reach.and_not(&closure(&reach.and_not(&coreach)));
    }
    let supervisor = search(model, model.initial(), &good, Direction::Forward, |_| true);
    Fixpoint {
        reachable: reach,
        good,
        supervisor,
        rounds,
    }
}
