//! Normality of a language with respect to a plant and the observable
//! events, with a shortest counterexample.
//!
//! K is normal with respect to (L, Σo) when L ∩ P⁻¹P(K) = K. The test
//! has two halves, each a breadth-first search of a product, so each finds
//! a shortest counterexample:
//!
//! 1. K ⊆ L: a string of K that the plant lacks
//!    ([`NormalityViolation::NotInPlant`]);
//! 2. L ∩ P⁻¹P(K) ⊆ K: the product of G, the complement of K and the
//!    projection P(K) (made deterministic) reaches a state that is marked
//!    in all three ([`NormalityViolation::LooksLike`]).

use super::{closure, complement, event_mask, names, over_plant_alphabet, product};
use crate::automaton::{Alphabet, Automaton, EventId, StateId, StateNames, Transition};
use crate::error::Result;
use crate::ops::projection::project_mask;
use crate::ops::reach::shortest_path_to;
use fixedbitset::FixedBitSet;

/// Why a language is not normal.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalityViolation {
    /// A shortest string of K that is not in L (normality implies K ⊆ L).
    NotInPlant {
        /// The string.
        string: Vec<String>,
    },
    /// A shortest string of L that is not in K but has the projection of
    /// `look_alike`, a string of K: an observer cannot tell them apart.
    LooksLike {
        /// The string of L outside K.
        string: Vec<String>,
        /// A shortest string of K with the same projection.
        look_alike: Vec<String>,
    },
}

/// Is the *marked* language Km of `k` normal with respect to the marked
/// language Lm of `plant` and the projection onto `observable`:
/// Lm ∩ P⁻¹P(Km) = Km? `None` when it is, else a shortest counterexample.
///
/// This is libFAUDES's `IsNormal`, which reads marked languages too;
/// libFAUDES refuses (throws) where Km ⊄ Lm, we answer
/// [`NormalityViolation::NotInPlant`].
pub fn is_normal(
    plant: &Automaton,
    k: &Automaton,
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Option<NormalityViolation>> {
    let k = over_plant_alphabet(plant, k)?;
    normality(plant, &k, observable, max_states)
}

/// Is the *closed* language K of `k` normal with respect to the closed
/// language L of `plant`: L ∩ P⁻¹P(K) = K? `None` when it is, else a
/// shortest counterexample. This is the normality that supervision under
/// partial observation asks of the closed-loop behaviour.
pub fn is_normal_closed(
    plant: &Automaton,
    k: &Automaton,
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Option<NormalityViolation>> {
    let k = closure(&over_plant_alphabet(plant, k)?);
    normality(&closure(plant), &k, observable, max_states)
}

/// Normality of Lm(k) with respect to Lm(g); `k` is over g's alphabet.
fn normality(
    g: &Automaton,
    k: &Automaton,
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Option<NormalityViolation>> {
    let alphabet = g.alphabet();
    let observable = event_mask(g, observable, "observable")?;
    let not_g = complement(g, alphabet, |s| !g.is_marked(s), true);
    let outside = product(k, &not_g, max_states)?;
    if let Some((_, path)) = shortest_path_to(&outside, |s| outside.is_marked(s)) {
        return Ok(Some(NormalityViolation::NotInPlant {
            string: names(&outside, &path),
        }));
    }
    let not_k = complement(k, alphabet, |s| !k.is_marked(s), true);
    let seen = project_mask(k, &observable, true, max_states)?;
    let g_not_k = product(g, &not_k, max_states)?;
    let suspects = product(&g_not_k, &seen, max_states)?;
    let Some((_, path)) = shortest_path_to(&suspects, |s| suspects.is_marked(s)) else {
        return Ok(None);
    };
    let observed: Vec<EventId> = path
        .iter()
        .filter(|e| observable[e.index()])
        .map(|&e| seen.alphabet().id(alphabet.name(e)).expect("observable"))
        .collect();
    let alike = product(k, &chain(seen.alphabet(), &observed), max_states)?;
    let (_, alike_path) =
        shortest_path_to(&alike, |s| alike.is_marked(s)).expect("the projection came from K");
    Ok(Some(NormalityViolation::LooksLike {
        string: names(&suspects, &path),
        look_alike: names(&alike, &alike_path),
    }))
}

/// The automaton over `alphabet` whose only string is `word`, marked.
fn chain(alphabet: &Alphabet, word: &[EventId]) -> Automaton {
    let n = word.len() + 1;
    let offsets = (0..=n as u32).map(|i| i.min(word.len() as u32)).collect();
    let edges = word
        .iter()
        .enumerate()
        .map(|(i, &event)| Transition {
            event,
            target: StateId(i as u32 + 1),
        })
        .collect();
    let mut marked = FixedBitSet::with_capacity(n);
    marked.insert(n - 1);
    Automaton::from_parts(
        "observation".into(),
        alphabet.clone(),
        StateNames::Indices,
        Some(StateId(0)),
        marked,
        offsets,
        edges,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    /// 0 -a-> 1 -u-> 2, everything marked; u unobservable.
    fn plant() -> Automaton {
        auto(
            "G",
            &[("a", true), ("u", false)],
            &[("0", "a", "1"), ("1", "u", "2")],
            &["0", "1", "2"],
        )
    }

    fn strings(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn a_language_that_stops_before_an_unobservable_event_is_not_normal() {
        let k = auto(
            "K",
            &[("a", true), ("u", false)],
            &[("0", "a", "1")],
            &["0", "1"],
        );
        let v = is_normal(&plant(), &k, &["a"], 100).unwrap();
        assert_eq!(
            v,
            Some(NormalityViolation::LooksLike {
                string: strings(&["a", "u"]),
                look_alike: strings(&["a"]),
            })
        );
        assert!(is_normal(&plant(), &k, &["a", "u"], 100).unwrap().is_none());
        assert!(is_normal_closed(&plant(), &k, &["a"], 100)
            .unwrap()
            .is_some());
    }

    #[test]
    fn marked_and_closed_normality_differ() {
        // K = {ε, a} closed but marks ε only: {ε} is normal, {ε, a} not.
        let k = auto(
            "K",
            &[("a", true), ("u", false)],
            &[("0", "a", "1")],
            &["0"],
        );
        assert!(is_normal(&plant(), &k, &["a"], 100).unwrap().is_none());
        assert!(is_normal_closed(&plant(), &k, &["a"], 100)
            .unwrap()
            .is_some());
    }

    #[test]
    fn strings_outside_the_plant_are_reported() {
        let k = auto(
            "K",
            &[("a", true)],
            &[("0", "a", "1"), ("1", "a", "2")],
            &["2"],
        );
        let v = is_normal(&plant(), &k, &["a"], 100).unwrap();
        assert_eq!(
            v,
            Some(NormalityViolation::NotInPlant {
                string: strings(&["a", "a"])
            })
        );
    }

    #[test]
    fn unknown_observable_events_are_refused() {
        let err = is_normal(&plant(), &plant(), &["zz"], 100).unwrap_err();
        assert!(err.to_string().contains("`zz`"), "{err}");
    }
}
