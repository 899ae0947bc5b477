//! Supremal controllable, nonblocking sublanguage (`supcon`).
//!
//! Given a plant `G` and a specification `E` whose alphabet is a subset of
//! the plant's, `supcon(G, E)` is a trim automaton recognising the largest
//! sublanguage `K ⊆ Lm(G) ∩ Lm(E')` (`E'` = `E` self-looped with the plant
//! events it does not mention) that is controllable with respect to `G`
//! and whose prefix closure is nonblocking.
//!
//! Algorithm:
//! 1. Build the reachable product `P = G ‖ E` (its states are pairs),
//!    pruned as it is built (`supcon/product.rs`):
//! 2. a product state is *bad* when the plant can do an uncontrollable
//!    event there that the specification forbids; it is not expanded.
//! 3. Repeat until nothing changes: every state with an uncontrollable
//!    transition into a bad state becomes bad (backwards search over the
//!    reversed transitions); then every good state that cannot reach a good
//!    marked state through good states becomes bad.
//! 4. The result is the good part, restricted to what the initial state
//!    reaches through good states, in the product's (breadth-first) order.
//!    If the initial state is bad the result is empty.
//!
//! State names (`plant.spec`) are composed on demand from the pairs.
//!
//! Each round is linear in the size of the product; rounds repeat only
//! while the blocking and controllability cuts feed each other, which is
//! a handful of times on real models.

mod preds;
mod product;

use super::reach::restrict_owned;
use super::sync::ComposeOptions;
use crate::automaton::{Automaton, StateId};
use crate::error::{Error, Result};
use fixedbitset::FixedBitSet;

/// `supcon(plant, spec)` with state names composed from the inputs.
pub fn supcon(plant: &Automaton, spec: &Automaton) -> Result<Automaton> {
    supcon_with(plant, spec, ComposeOptions::default())
}

/// Checks that `spec` only uses plant events, with the same
/// controllability.
pub(crate) fn check_spec_alphabet(plant: &Automaton, spec: &Automaton) -> Result<()> {
    for (_, e) in spec.alphabet().iter() {
        match plant.alphabet().id(&e.name) {
            None => {
                return Err(Error::Incompatible(format!(
                    "event `{}` of `{}` is not in the alphabet of the plant `{}`",
                    e.name,
                    spec.name(),
                    plant.name()
                )))
            }
            Some(id)
                if spec.alphabet().controllability_stated()
                    && plant.alphabet().is_controllable(id) != e.controllable =>
            {
                return Err(Error::Incompatible(format!(
                    "event `{}` is {} in the plant `{}` but {} in `{}`",
                    e.name,
                    controllability(plant.alphabet().is_controllable(id)),
                    plant.name(),
                    controllability(e.controllable),
                    spec.name()
                )))
            }
            Some(_) => {}
        }
    }
    Ok(())
}

fn controllability(c: bool) -> &'static str {
    if c {
        "controllable"
    } else {
        "uncontrollable"
    }
}

/// `supcon(plant, spec)`; `options` control naming, limits and progress.
pub fn supcon_with(
    plant: &Automaton,
    spec: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<Automaton> {
    check_spec_alphabet(plant, spec)?;
    let product::Pruned {
        automaton: product,
        mut bad,
    } = product::pruned_product(plant, spec, options)?;
    let p = &product;
    let uncontrollable: Vec<bool> = p
        .alphabet()
        .ids()
        .map(|e| !p.alphabet().is_controllable(e))
        .collect();
    // Step 2: the states where the spec disables an uncontrollable plant
    // event, found while building the product.
    let mut frontier: Vec<StateId> = bad.ones().map(|s| StateId(s as u32)).collect();

    // Step 3.
    let preds = preds::Predecessors::new(p, &uncontrollable);
    loop {
        preds.spread_bad(&mut bad, &mut frontier);
        let co = preds.coreachable_good(p, &bad);
        // Good states that block: neither bad nor coreachable.
        let mut blocking = co;
        blocking.union_with(&bad);
        blocking.toggle_range(..);
        for s in blocking.ones() {
            bad.insert(s);
            frontier.push(StateId(s as u32));
        }
        if frontier.is_empty() {
            break;
        }
        options.progress.report("supcon", bad.count_ones(..));
    }

    // Step 4.
    let name = format!("supcon({},{})", plant.name(), spec.name());
    drop(preds);
    let Some(init) = p.initial().filter(|s| !bad.contains(s.index())) else {
        return Ok(Automaton::empty(name, p.alphabet().clone()));
    };
    // The good states the initial state reaches through good states.
    let mut keep = FixedBitSet::with_capacity(p.num_states());
    keep.insert(init.index());
    let mut stack = vec![init];
    while let Some(s) = stack.pop() {
        for t in p.transitions(s) {
            if !bad.contains(t.target.index()) && !keep.put(t.target.index()) {
                stack.push(t.target);
            }
        }
    }
    drop(bad);
    let mut result = restrict_owned(product, &keep);
    result.set_name(name);
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::{is_trim, sync};
    use crate::testing::auto;

    /// The small factory of Wonham's textbook: two machines and a buffer
    /// of one slot; breakdowns of M2 have repair priority.
    fn small_factory() -> (Automaton, Automaton) {
        let ev1 = [("11", true), ("10", false), ("12", false), ("13", true)];
        let m1 = auto(
            "M1",
            &ev1,
            &[
                ("0", "11", "1"),
                ("1", "10", "0"),
                ("1", "12", "2"),
                ("2", "13", "0"),
            ],
            &["0"],
        );
        let ev2 = [("21", true), ("20", false), ("22", false), ("23", true)];
        let m2 = auto(
            "M2",
            &ev2,
            &[
                ("0", "21", "1"),
                ("1", "20", "0"),
                ("1", "22", "2"),
                ("2", "23", "0"),
            ],
            &["0"],
        );
        let buf = auto(
            "BUF",
            &[("10", false), ("21", true)],
            &[("0", "10", "1"), ("1", "21", "0")],
            &["0"],
        );
        let br = auto(
            "BR",
            &[("22", false), ("23", true), ("13", true)],
            &[("0", "22", "1"), ("1", "23", "0"), ("0", "13", "0")],
            &["0"],
        );
        (sync(&[&m1, &m2]).unwrap(), sync(&[&buf, &br]).unwrap())
    }

    #[test]
    fn small_factory_gives_the_textbook_12_states_24_transitions() {
        let (plant, spec) = small_factory();
        assert_eq!((plant.num_states(), plant.num_transitions()), (9, 24));
        let sup = supcon(&plant, &spec).unwrap();
        assert_eq!((sup.num_states(), sup.num_transitions()), (12, 24));
        assert!(is_trim(&sup));
    }

    #[test]
    fn an_uncontrollable_violation_propagates_back_to_the_last_controllable_choice() {
        // 0 -c-> 1 -u-> 2 -u-> 3 ; spec forbids the second u.
        let ev = [("c", true), ("u", false), ("v", false)];
        let plant = auto(
            "G",
            &ev,
            &[
                ("0", "c", "1"),
                ("1", "u", "2"),
                ("2", "v", "3"),
                ("0", "v", "0"),
            ],
            &["0", "3"],
        );
        let spec = auto(
            "E",
            &[("u", false), ("v", false)],
            &[("0", "u", "b"), ("0", "v", "0")],
            &["0", "b"],
        );
        // After c, u and then v are uncontrollable, and v after u is
        // forbidden: c must be disabled. What is left is v-loops at 0.
        let sup = supcon(&plant, &spec).unwrap();
        assert_eq!((sup.num_states(), sup.num_transitions()), (1, 1));
        let only = sup.transitions(sup.initial().unwrap())[0];
        assert_eq!(sup.alphabet().name(only.event), "v");
    }

    #[test]
    fn a_forced_violation_from_the_start_gives_the_empty_supervisor() {
        let plant = auto("G", &[("u", false)], &[("0", "u", "1")], &["0", "1"]);
        let spec = auto("E", &[("u", false)], &[], &["0"]);
        let sup = supcon(&plant, &spec).unwrap();
        assert!(sup.is_empty());
        assert_eq!(sup.initial(), None);
    }

    #[test]
    fn blocking_states_are_removed_even_without_a_spec_restriction() {
        // 0 -a-> 1 (dead end), 0 -b-> 2 marked. a controllable: cut.
        let plant = auto(
            "G",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("0", "b", "2")],
            &["2"],
        );
        let spec = auto("E", &[], &[], &["0"]);
        let sup = supcon(&plant, &spec).unwrap();
        assert_eq!((sup.num_states(), sup.num_transitions()), (2, 1));
    }

    #[test]
    fn spec_events_outside_the_plant_are_rejected() {
        let plant = auto("G", &[("a", true)], &[("0", "a", "0")], &["0"]);
        let spec = auto("E", &[("z", true)], &[("0", "z", "0")], &["0"]);
        let err = supcon(&plant, &spec).unwrap_err().to_string();
        assert!(
            err.contains("`z`") && err.contains("`E`") && err.contains("`G`"),
            "{err}"
        );
    }

    #[test]
    fn controllability_disagreement_is_rejected() {
        let plant = auto("G", &[("a", true)], &[("0", "a", "0")], &["0"]);
        let spec = auto("E", &[("a", false)], &[("0", "a", "0")], &["0"]);
        assert!(supcon(&plant, &spec).is_err());
    }

    #[test]
    fn a_spec_without_stated_controllability_takes_the_plants() {
        // Plant: c (controllable) leads to a state where u (uncontrollable)
        // is possible; the spec forbids u. Read as stated, the spec's `c`
        // would conflict; unstated, c is cut as the plant says.
        let plant = auto(
            "G",
            &[("c", true), ("u", false)],
            &[("0", "c", "1"), ("1", "u", "0")],
            &["0"],
        );
        let mut b = crate::automaton::AutomatonBuilder::new("E");
        b.set_controllability_stated(false);
        b.add_event("c", false).unwrap();
        b.add_event("u", false).unwrap();
        b.set_initial_by_name("0").unwrap();
        b.mark_by_name("0");
        b.add_transition_by_name("0", "c", "1", 0).unwrap();
        let spec = b.build().unwrap();
        let sup = supcon(&plant, &spec).unwrap();
        assert_eq!((sup.num_states(), sup.num_transitions()), (1, 0));
        assert!(sup
            .alphabet()
            .is_controllable(sup.alphabet().id("c").unwrap()));
    }
}
