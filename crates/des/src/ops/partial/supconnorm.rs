//! Supremal controllable and normal sublanguages: supervision under
//! partial observation.
//!
//! - [`sup_con_normal_closed`], on closed languages, in one pass: the
//!   supremal closed K ⊆ E ∩ L, controllable with respect to (L, Σuc) and
//!   normal with respect to (L, Σo), is
//!   (E ∩ L) − P⁻¹P((L − E)/Σu*)Σ* with Σu = Σuc ∪ Σuo. A normal closed
//!   K never disables an unobservable event (s ∈ K, sτ ∈ L, P(sτ) = P(s)
//!   give sτ ∈ K), so every string that unobservable or uncontrollable
//!   events lead out of E must go, and with it every string that looks
//!   like it, and everything after. The result is the same as libFAUDES's
//!   `SupConNormClosed` (which projects, solves a controllability problem
//!   on the projected plant and maps back: Brandt et al. 1990).
//! - [`sup_con_normal`], on marked languages: the iteration that
//!   libFAUDES's `SupConNorm` performs (after Cieslak et al. 1988 and
//!   Lin and Wonham 1988's fixpoint view): K₀ = trim(Lm ∩ Em), then
//!   Kᵢ₊₁ = trim(K₀ ∩ supconnormclosed(closure(Lm), closure(Kᵢ))) until
//!   Kᵢ₊₁ = Kᵢ. The sequence decreases; its limit is nonblocking (trim),
//!   controllable with respect to closure(Lm) and its closure is normal
//!   with respect to closure(Lm). When G is nonblocking closure(Lm) = L;
//!   when it blocks, libFAUDES (and so we) answer for G's nonblocking
//!   part, which the differential tests confirm: the result may then let
//!   an uncontrollable or unobservable event lead into G's blocking part.
//!   When Em is relatively closed with respect to Lm the result is the
//!   supremal such sublanguage of Lm ∩ Em.

use super::supnorm::{cut, named_cut};
use super::{event_mask, over_plant_alphabet, product};
use crate::automaton::Automaton;
use crate::error::{Error, Result};
use crate::ops::equivalence::language_equal;
use crate::ops::minstate::minstate;
use crate::ops::reach::trim;

/// The supremal closed sublanguage of the closed languages E ∩ L of
/// `spec` and `plant` that is controllable with respect to L and the
/// events not in `controllable`, and normal with respect to L and the
/// projection onto `observable`; every state marked (libFAUDES's
/// `SupConNormClosed`).
pub fn sup_con_normal_closed(
    plant: &Automaton,
    spec: &Automaton,
    controllable: &[impl AsRef<str>],
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Automaton> {
    let (spread, observable) = masks(plant, controllable, observable)?;
    let what = "supconnormclosed";
    named_cut(
        what,
        plant,
        spec,
        Some(&spread),
        &observable,
        true,
        max_states,
    )
}

/// The supremal controllable and normal sublanguage of Lm ∩ Em for the
/// plant `plant` and specification `spec`, as libFAUDES's `SupConNorm`
/// computes it: K₀ = trim(Lm ∩ Em), then
/// Kᵢ₊₁ = trim(K₀ ∩ supconnormclosed(closure(Lm), closure(Kᵢ))) until
/// Kᵢ₊₁ = Kᵢ; a trim automaton, empty when nothing is left.
/// Controllability (events not in `controllable`) and normality of the
/// closure (projection onto `observable`) hold with respect to the
/// plant's nonblocking part closure(Lm), which is L when the plant is
/// nonblocking; trim a blocking plant first if that is not what you mean.
/// When Em is relatively closed with respect to Lm, the result is the
/// supremal such sublanguage.
///
/// Errors beyond `max_states` states in any product or subset
/// construction, or when the iteration has not reached its fixpoint after
/// `max_states` rounds.
pub fn sup_con_normal(
    plant: &Automaton,
    spec: &Automaton,
    controllable: &[impl AsRef<str>],
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Automaton> {
    let (spread, observable) = masks(plant, controllable, observable)?;
    let spec = over_plant_alphabet(plant, spec)?;
    let start = trim(&product(plant, &spec, max_states)?);
    let nonblocking = trim(plant);
    let mut k = start.clone();
    for _ in 0..max_states.max(1) {
        let allowed = cut(
            &nonblocking,
            &k,
            Some(&spread),
            &observable,
            true,
            max_states,
        )?;
        // Minimal, or the products of the next round grow with every
        // round's observer states (past 100,000 subsets on 12-state
        // plants).
        let next = minstate(&trim(&product(&start, &allowed, max_states)?));
        if language_equal(&next, &k) {
            let mut k = next;
            k.set_name(format!("supconnorm({},{})", plant.name(), spec.name()));
            return Ok(k);
        }
        k = next;
    }
    Err(Error::StateLimit {
        max_states,
        message: format!(
            "supconnorm({},{}) has not reached its fixpoint after {max_states} rounds",
            plant.name(),
            spec.name()
        ),
    })
}

/// The events along which a closed normal controllable language cannot
/// stop the plant (uncontrollable or unobservable), and the observable
/// ones, as masks over the plant's event ids.
fn masks(
    plant: &Automaton,
    controllable: &[impl AsRef<str>],
    observable: &[impl AsRef<str>],
) -> Result<(Vec<bool>, Vec<bool>)> {
    let controllable = event_mask(plant, controllable, "controllable")?;
    let observable = event_mask(plant, observable, "observable")?;
    let spread = controllable
        .iter()
        .zip(&observable)
        .map(|(&c, &o)| !c || !o)
        .collect();
    Ok((spread, observable))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::{check_controllable, is_normal_closed, supcon};
    use crate::testing::auto;

    /// Two machines, M1 (a1 start, b1 finish) and M2 (a2, b2), through a
    /// one-slot buffer: a2 only after b1, a1 again only after a2.
    fn machines() -> (Automaton, Automaton) {
        let ev = [("a1", true), ("b1", false), ("a2", true), ("b2", false)];
        let g = auto(
            "G",
            &ev,
            &[
                ("0", "a1", "1"),
                ("1", "b1", "0"),
                ("0", "a2", "2"),
                ("2", "b2", "0"),
                ("1", "a2", "3"),
                ("3", "b1", "2"),
                ("2", "a1", "3"),
                ("3", "b2", "1"),
            ],
            &["0"],
        );
        let buffer = auto(
            "B",
            &[("b1", false), ("a2", true)],
            &[("0", "b1", "1"), ("1", "a2", "0")],
            &["0"],
        );
        (g, buffer)
    }

    #[test]
    fn with_everything_observed_it_is_supcon() {
        let (g, b) = machines();
        let all = ["a1", "b1", "a2", "b2"];
        let ours = sup_con_normal(&g, &b, &["a1", "a2"], &all, 1000).unwrap();
        assert!(language_equal(&ours, &supcon(&g, &b).unwrap()));
    }

    #[test]
    fn an_unobserved_finish_leaves_only_the_first_start_closed() {
        // b1 unobservable: the supervisor never learns that the buffer
        // filled, so it can never enable a2; then it must not enable a1
        // twice either. The closed result is {ε, a1, a1 b1}.
        let (g, b) = machines();
        let obs = ["a1", "a2", "b2"];
        let c = sup_con_normal_closed(&g, &b, &["a1", "a2"], &obs, 1000).unwrap();
        let expected = auto(
            "K",
            &[("a1", true), ("b1", false)],
            &[("0", "a1", "1"), ("1", "b1", "2")],
            &["0", "1", "2"],
        );
        assert!(language_equal(&c, &expected));
        assert!(is_normal_closed(&g, &c, &obs, 1000).unwrap().is_none());
        assert!(check_controllable(&g, &c).unwrap().is_none());
        // Marked, the buffer must empty again: nothing but ε is left.
        let m = sup_con_normal(&g, &b, &["a1", "a2"], &obs, 1000).unwrap();
        assert_eq!(m.num_states(), 1);
        assert_eq!(m.num_transitions(), 0);
    }
}
