//! Supremal normal sublanguages (Brandt et al. 1990), and the cut they
//! share with the supremal controllable and normal closed sublanguage.
//!
//! Both read the *closed* languages L of the plant and K of the second
//! automaton, as libFAUDES's `SupNorm` and `SupNormClosed` do, and compute
//!
//! - `sup_normal`: K − P⁻¹P(L − K), marked (in general not closed);
//! - `sup_normal_closed`: K − P⁻¹P(L − K)Σ*, closed.
//!
//! libFAUDES requires Km ⊆ Lm, respectively K ⊆ L, and throws otherwise;
//! we take K ∩ L for K, which is the same when K ⊆ L and keeps the result
//! normal otherwise (normality implies K ⊆ L).
//!
//! Construction: the product A of G and the complement of K has the
//! states of K ∩ L and, marked, those of L − K. The projection P(A),
//! made deterministic, tells after each observation whether some string
//! of L − K looks the same: such observations are *tainted*. The result is
//! the product of the K ∩ L part of A with P(A), marked where the
//! observation is clean (and, for the closed variant, cut at the first
//! tainted one).

use super::{closure, complement, event_mask, keep_states, over_plant_alphabet, product, remark};
use crate::automaton::Automaton;
use crate::error::Result;
use crate::ops::projection::project_mask;
use crate::ops::reach::{trim, Reverse};
use fixedbitset::FixedBitSet;

/// The supremal normal sublanguage K − P⁻¹P(L − K) of the closed
/// language K of `k` (∩ L) with respect to the closed language L of
/// `plant` and the projection onto `observable`: a trim automaton marking
/// it (libFAUDES's `SupNorm`).
pub fn sup_normal(
    plant: &Automaton,
    k: &Automaton,
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Automaton> {
    let observable = event_mask(plant, observable, "observable")?;
    named_cut("supnorm", plant, k, None, &observable, false, max_states)
}

/// The supremal closed normal sublanguage K − P⁻¹P(L − K)Σ* of the closed
/// language K of `k` (∩ L) with respect to the closed language L of
/// `plant`: an automaton with every state marked (libFAUDES's
/// `SupNormClosed`).
pub fn sup_normal_closed(
    plant: &Automaton,
    k: &Automaton,
    observable: &[impl AsRef<str>],
    max_states: usize,
) -> Result<Automaton> {
    let observable = event_mask(plant, observable, "observable")?;
    named_cut(
        "supnormclosed",
        plant,
        k,
        None,
        &observable,
        true,
        max_states,
    )
}

/// [`cut`] of `k` (read over the plant's alphabet), named
/// `what(plant,k)`.
pub(super) fn named_cut(
    what: &str,
    plant: &Automaton,
    k: &Automaton,
    spread: Option<&[bool]>,
    observable: &[bool],
    closed: bool,
    max_states: usize,
) -> Result<Automaton> {
    let k = over_plant_alphabet(plant, k)?;
    let mut r = cut(plant, &k, spread, observable, closed, max_states)?;
    r.set_name(format!("{what}({},{})", plant.name(), k.name()));
    Ok(r)
}

/// (K ∩ L) − P⁻¹P((L − K)/Σu*), followed by Σ* when `closed`, on the
/// closed languages of `plant` and `k` (over the plant's alphabet), where
/// Σu are the events of `spread` (none when `None`). Closed: every state
/// marked; else trim.
pub(super) fn cut(
    plant: &Automaton,
    k: &Automaton,
    spread: Option<&[bool]>,
    observable: &[bool],
    closed: bool,
    max_states: usize,
) -> Result<Automaton> {
    let not_k = complement(k, plant.alphabet(), |_| false, true);
    let a = product(&closure(plant), &not_k, max_states)?;
    let bad = match spread {
        None => a.marked().clone(),
        Some(spread) => backward(&a, a.marked(), spread),
    };
    let seen = project_mask(&remark(&a, bad), observable, !closed, max_states)?;
    let inside = closure(&keep_states(&a, |s| !a.is_marked(s)));
    if closed {
        let clean = closure(&keep_states(&seen, |s| !seen.is_marked(s)));
        product(&inside, &clean, max_states)
    } else {
        let mut clean = seen.marked().clone();
        clean.toggle_range(..);
        Ok(trim(&product(&inside, &remark(&seen, clean), max_states)?))
    }
}

/// `from` and the states that reach it by events where `along` holds.
fn backward(a: &Automaton, from: &FixedBitSet, along: &[bool]) -> FixedBitSet {
    let rev = Reverse::new(a);
    let mut set = from.clone();
    let mut stack: Vec<_> = from.ones().map(|s| crate::StateId(s as u32)).collect();
    while let Some(s) = stack.pop() {
        for &(p, e) in rev.predecessors(s) {
            if along[e.index()] && !set.put(p.index()) {
                stack.push(p);
            }
        }
    }
    set
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::language_equal;
    use crate::testing::auto;

    const EV: [(&str, bool); 2] = [("a", true), ("u", false)];

    #[test]
    fn the_supremal_normal_sublanguage_is_marked_and_not_closed() {
        // L = {ε, a, au, aa}, K = {ε, a, aa}; u unobservable. au ∈ L − K
        // looks like a, so a is cut from the marked result; aa stays.
        let g = auto(
            "G",
            &EV,
            &[("0", "a", "1"), ("1", "u", "2"), ("1", "a", "3")],
            &[],
        );
        let k = auto("K", &EV, &[("0", "a", "1"), ("1", "a", "2")], &[]);
        let n = sup_normal(&g, &k, &["a"], 100).unwrap();
        let expected = auto("N", &EV, &[("0", "a", "1"), ("1", "a", "2")], &["0", "2"]);
        assert!(language_equal(&n, &expected));
        let c = sup_normal_closed(&g, &k, &["a"], 100).unwrap();
        let expected = auto("N", &EV, &[], &["0"]);
        assert!(language_equal(&c, &expected));
    }

    #[test]
    fn a_normal_language_is_its_own_supremal_normal_sublanguage() {
        let g = auto("G", &EV, &[("0", "a", "1"), ("1", "u", "2")], &["2"]);
        let n = sup_normal_closed(&g, &g, &["a"], 100).unwrap();
        assert!(language_equal(&n, &closure(&g)));
    }
}
