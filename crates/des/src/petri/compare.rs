//! The invariant supervisor against supcon: the controlled net's
//! language is compared with the supremal controllable sublanguage of the
//! same constraints taken as a specification.
//!
//! The plant is the net's reachability graph, every marking marked (an
//! invariant supervisor promises no nonblocking, so only the closed
//! languages are compared); the specification is the part of that graph
//! that stays within every constraint. For admissible constraints and
//! observable transitions both are the same language; where the
//! invariant supervisor is more restrictive (or supcon is), a shortest
//! string in one language and not the other says so.
//!
//! The plant need not be bounded: supcon only looks at the plant within
//! the specification and one firing out of it (where an uncontrollable
//! firing would leave it), so the plant is explored within the
//! constraints and the markings one firing beyond them are kept as
//! states without being explored ([`Beyond::Frontier`]). What must be
//! finite is that region and the controlled net; when either is not
//! (or is beyond the limit) the comparison says why it was not made.

use super::constraints::Constraint;
use super::reach::{explore, Beyond, Limits, Marked, Region, Stopped};
use super::synth::Supervised;
use super::PetriNet;
use crate::error::Result;
use crate::ops::{self, LanguageDifference};

/// What the comparison found.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// States of supcon's supervisor.
    pub supcon_states: usize,
    /// States of the controlled net's reachability graph.
    pub controlled_states: usize,
    /// `None`: the same language; otherwise a shortest string in one and
    /// not the other (`in_first`: in the controlled net's).
    pub difference: Option<LanguageDifference>,
}

/// Compares `supervised` (synthesised from `constraints` for `plant`)
/// with supcon on the reachability graphs, exploring at most
/// `max_states` markings each; the inner `Err` says why a graph has no
/// finite form within that limit (and so the comparison was not made).
pub fn against_supcon(
    plant: &PetriNet,
    constraints: &[Constraint],
    supervised: &Supervised,
    max_states: usize,
) -> Result<std::result::Result<Comparison, Stopped>> {
    let legal = Region::Constraints(constraints);
    let limits = Limits::states(max_states);
    let controlled = match explore(
        &supervised.net,
        limits,
        Marked::All,
        Region::All,
        Beyond::Drop,
    )? {
        Ok(r) => r.automaton,
        Err(stopped) => return Ok(Err(stopped)),
    };
    let graph = match explore(plant, limits, Marked::All, legal, Beyond::Frontier)? {
        Ok(r) => r.automaton,
        Err(stopped) => return Ok(Err(stopped)),
    };
    let spec = match explore(plant, limits, Marked::All, legal, Beyond::Drop)? {
        Ok(r) => r.automaton,
        Err(stopped) => return Ok(Err(stopped)),
    };
    let sup = ops::supcon(&graph, &spec)?;
    Ok(Ok(Comparison {
        supcon_states: sup.num_states(),
        controlled_states: controlled.num_states(),
        difference: ops::language_difference(&controlled, &sup),
    }))
}

#[cfg(test)]
mod tests {
    use super::super::{constraints, synth, toml};
    use super::*;
    use std::path::Path;

    fn net(text: &str) -> PetriNet {
        toml::read(text, Path::new("n.toml")).unwrap()
    }

    const MIXERS: &str = include_str!("../../../../models/petri/mixers.toml");
    const SUPPLY: &str = include_str!("../../../../models/petri/mixers.constraints.toml");

    #[test]
    fn the_mixers_supervisor_is_supcons_language() {
        let plant = net(MIXERS);
        let cs = constraints::read(SUPPLY, Path::new("c.toml"), &plant).unwrap();
        let s = synth::synthesize(&plant, &cs).unwrap();
        let c = against_supcon(&plant, &cs, &s, 1000).unwrap().unwrap();
        assert_eq!(c.difference, None);
        assert_eq!((c.controlled_states, c.supcon_states), (15, 15));
    }

    #[test]
    fn a_difference_comes_with_a_shortest_string() {
        // With t2 ("A full") uncontrollable the constraint stays admissible;
        // supcon and the invariant agree. Made to compare against a
        // different constraint, the difference is a string.
        let plant = net(MIXERS);
        let cs = constraints::read(SUPPLY, Path::new("c.toml"), &plant).unwrap();
        let s = synth::synthesize(&plant, &cs).unwrap();
        let looser = constraints::read(
            "[[constraint]]\nname = \"two\"\nweights = { m3 = 1 }\nbound = 2\n",
            Path::new("l.toml"),
            &plant,
        )
        .unwrap();
        let c = against_supcon(&plant, &looser, &s, 1000).unwrap().unwrap();
        let d = c.difference.expect("m3 ≤ 2 allows both mixers to fill");
        assert!(
            !d.in_first,
            "the string is supcon's, beyond the invariant supervisor"
        );
        assert_eq!(d.string.len(), 2, "{:?}", d.string);
        assert_eq!(c.supcon_states, 16);
    }
}
