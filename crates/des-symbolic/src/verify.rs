//! Nonblocking of a closed loop decided on BDDs: plant components and
//! supervisors (given as the model's specifications) run together, and
//! every state they reach must be able to reach a marked one. For modular
//! supervisors this is their nonconflict: each may be nonblocking with
//! the plant alone while together they block.
//!
//! A blocking closed loop comes with a shortest event string into a
//! blocking state, and that state's components.

use crate::reach::{search, Direction};
use crate::relation::Model;
use biodivine_lib_bdd::{Bdd, BddPartialValuation, BddVariable};
use num_bigint::BigUint;

/// What [`nonblocking`] found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verdict {
    /// States the closed loop reaches (exact).
    pub reachable: BigUint,
    /// Reachable states from which no marked state can be reached.
    pub blocking: BigUint,
    /// When blocking: a shortest event string from the initial state into
    /// a blocking state, and that state's component states (input order,
    /// by name).
    pub counterexample: Option<Counterexample>,
}

/// A shortest way into a blocking state.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Counterexample {
    /// The events, in order.
    pub events: Vec<String>,
    /// `(component, state)` of the blocking state, in input order.
    pub state: Vec<(String, u32)>,
}

impl Verdict {
    /// Whether every reachable state can reach a marked one.
    pub fn holds(&self) -> bool {
        self.counterexample.is_none()
    }
}

/// The current-state variables of `model`.
fn current_vars(model: &Model) -> Vec<BddVariable> {
    model
        .layout()
        .components
        .iter()
        .flat_map(|c| (0..c.bits).map(|k| BddVariable::from_index(c.current_var(k))))
        .collect()
}

/// One state of the non-empty `set`, as a set of its own.
fn one_of(set: &Bdd, vars: &[BddVariable]) -> Bdd {
    let v = set.first_valuation().expect("a non-empty set");
    let fixed: Vec<(BddVariable, bool)> = vars.iter().map(|&x| (x, v.value(x))).collect();
    set.select_valuation(&BddPartialValuation::from_values(&fixed))
}

/// The component states of the single state `state`.
fn decode(model: &Model, state: &Bdd) -> Vec<(String, u32)> {
    let v = state.first_valuation().expect("a state");
    model
        .layout()
        .components
        .iter()
        .map(|c| {
            let s = (0..c.bits).fold(0u32, |x, k| {
                (x << 1) | u32::from(v.value(BddVariable::from_index(c.current_var(k))))
            });
            (c.name.clone(), s)
        })
        .collect()
}

/// Decides whether the components of `model` together are nonblocking.
pub fn nonblocking(model: &Model) -> Verdict {
    let reached = search(
        model,
        model.initial(),
        &model.mk_true(),
        Direction::Forward,
        |_| true,
    );
    let coreachable = search(model, model.marked(), &reached, Direction::Backward, |_| {
        true
    });
    let blocking = reached.and_not(&coreachable);
    let counterexample = (!blocking.is_false()).then(|| shortest_into(model, &blocking));
    Verdict {
        reachable: model.count(&reached),
        blocking: model.count(&blocking),
        counterexample,
    }
}

/// A shortest string from the initial state into the (reachable,
/// non-empty) set `target`: breadth-first layers until one meets it, then
/// back through the layers one predecessor at a time.
fn shortest_into(model: &Model, target: &Bdd) -> Counterexample {
    let events = model.layout().events.len();
    let vars = current_vars(model);
    let mut layers = vec![model.initial().clone()];
    let mut reached = model.initial().clone();
    while layers.last().expect("a layer").and(target).is_false() {
        let last = layers.last().expect("a layer");
        let mut next = model.mk_false();
        for e in 0..events {
            next = next.or(&model.post(last, e));
        }
        let next = next.and_not(&reached);
        assert!(!next.is_false(), "the target is reachable");
        reached = reached.or(&next);
        layers.push(next);
    }
    let k = layers.len() - 1;
    let mut state = one_of(&layers[k].and(target), &vars);
    let at = decode(model, &state);
    let mut trail = Vec::new();
    for i in (1..=k).rev() {
        let (e, before) = (0..events)
            .find_map(|e| {
                let p = model.pre(&state, e).and(&layers[i - 1]);
                (!p.is_false()).then_some((e, p))
            })
            .expect("every state of layer i has a predecessor in layer i - 1");
        trail.push(model.layout().events[e].name.clone());
        state = one_of(&before, &vars);
    }
    trail.reverse();
    Counterexample {
        events: trail,
        state: at,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use des::AutomatonBuilder;

    /// `name` over `events` (name, controllable): states `q0`, `q1`, …
    /// in order, `q0` initial and the only marked one, `path` the
    /// transitions `(from, event, to)`.
    fn automaton(
        name: &str,
        events: &[(&str, bool)],
        states: usize,
        path: &[(usize, &str, usize)],
    ) -> des::Automaton {
        let mut b = AutomatonBuilder::new(name);
        for &(e, c) in events {
            b.add_event(e, c).unwrap();
        }
        for i in 0..states {
            b.add_state(&format!("q{i}"));
        }
        b.set_initial_by_name("q0").unwrap();
        b.mark_by_name("q0");
        for &(from, e, to) in path {
            b.add_transition_by_name(&format!("q{from}"), e, &format!("q{to}"), 1)
                .unwrap();
        }
        b.build().unwrap()
    }

    const EVENTS: [(&str, bool); 3] = [("take", true), ("left", false), ("right", false)];

    /// A machine that takes a part (`take`) and puts it out on one of two
    /// sides (`left`, `right`); marked when idle.
    fn machine() -> des::Automaton {
        automaton(
            "M",
            &EVENTS,
            2,
            &[(0, "take", 1), (1, "left", 0), (1, "right", 0)],
        )
    }

    #[test]
    fn a_closed_loop_that_can_always_finish_is_nonblocking() {
        let m = machine();
        let model = Model::new(&[m], &[]).unwrap();
        let v = nonblocking(&model);
        assert!(v.holds());
        assert_eq!(v.reachable, 2u32.into());
        assert_eq!(v.blocking, 0u32.into());
    }

    #[test]
    fn conflicting_supervisors_block_with_a_shortest_string() {
        // Each supervisor alone lets the machine finish; together, after
        // `take` one forbids `left` and the other `right`, and the part
        // never comes out.
        let s1 = automaton("S1", &EVENTS, 2, &[(0, "take", 1), (1, "right", 0)]);
        let s2 = automaton("S2", &EVENTS, 2, &[(0, "take", 1), (1, "left", 0)]);
        for s in [&s1, &s2] {
            let alone = Model::new(&[machine()], std::slice::from_ref(s)).unwrap();
            assert!(nonblocking(&alone).holds(), "{} alone", s.name());
        }
        let model = Model::new(&[machine()], &[s1, s2]).unwrap();
        let v = nonblocking(&model);
        assert!(!v.holds());
        let c = v.counterexample.unwrap();
        assert_eq!(c.events, ["take"]);
        assert_eq!(
            c.state,
            [
                ("M".to_owned(), 1),
                ("S1".to_owned(), 1),
                ("S2".to_owned(), 1)
            ]
        );
        assert_eq!(v.reachable, 2u32.into());
        assert_eq!(v.blocking, 1u32.into());
    }
}
