//! Partial observation: normality, supremal normal sublanguages,
//! supremal controllable and normal sublanguages, observability.
//!
//! # Definitions
//!
//! Σ is the plant's alphabet, Σo ⊆ Σ the observable events (a parameter
//! of every operation), Σuo = Σ − Σo, and P: Σ* → Σo* the natural
//! projection, which erases the unobservable events; P⁻¹ is its set-valued
//! inverse. L and Lm are the closed and marked languages of the plant G,
//! K and Km those of the second automaton, L̄ the prefix closure.
//!
//! - K is *normal* with respect to (L, Σo) when L ∩ P⁻¹P(K) = K (Lin and
//!   Wonham 1988; Cieslak et al. 1988): a string of the plant that looks
//!   like a string of K is in K. Normality implies K ⊆ L.
//! - K is *observable* with respect to (L, Σc, Σo) (Lin and Wonham 1988)
//!   when for all s, s' ∈ K with P(s) = P(s') and every controllable σ:
//!   sσ ∈ K and s'σ ∈ L imply s'σ ∈ K, on closed languages.
//! - The supremal normal sublanguage of a closed K ⊆ L is
//!   K − P⁻¹P(L − K), and the supremal closed normal one is
//!   K − P⁻¹P(L − K)Σ* (Brandt et al. 1990).
//! - The supremal closed sublanguage of a closed E ∩ L that is controllable
//!   and normal is (E ∩ L) − P⁻¹P((L − E)/Σu*)Σ*, where Σu = Σuc ∪ Σuo
//!   and X/Σu* = {t | tu ∈ X for some u ∈ Σu*}: a normal closed language
//!   can never disable an unobservable event, so unobservable events act
//!   as uncontrollable ones (the formula generalises Brandt et al. 1990 to
//!   Σc ⊄ Σo; see [`sup_con_normal_closed`]).
//! - On marked languages, [`sup_con_normal`] iterates that closed
//!   operation with the intersection with Lm ∩ Em to a fixpoint, as
//!   libFAUDES's `SupConNorm` does.
//!
//! Which language of an automaton each operation reads (closed or marked)
//! follows libFAUDES 2.34, against which `tests/faudes_diff.rs` checks
//! every operation on random cases; each function says which.
//!
//! # Conventions
//!
//! An automaton whose alphabet lacks some plant events stands for its
//! inverse projection onto the plant's alphabet (those events self-looped
//! everywhere), as specifications do in [`supcon`](mod@super::supcon); its
//! events must all be plant events. Event sets are given by name, and every
//! name must be a plant event.
//!
//! # Cost
//!
//! The operations compose the inputs (products of states) and determinise
//! the projection of a product by subset construction, which is
//! exponential in the worst case. Both are bounded by `max_states`:
//! beyond it an operation gives up with [`Error::StateLimit`] naming
//! which construction grew, instead of exhausting memory.
//! [`check_observable`] needs no subset construction: it searches triples
//! of states (|K|²·|G| at most).

mod normal;
mod observable;
pub(crate) mod observed;
mod supconnorm;
mod supnorm;

pub use normal::{is_normal, is_normal_closed, NormalityViolation};
pub use observable::{check_observable, ObservabilityViolation};
pub use observed::{check_observed, name_after, observable_events, observed_supervisor};
pub use supconnorm::{sup_con_normal, sup_con_normal_closed};
pub use supnorm::{sup_normal, sup_normal_closed};

use super::supcon::check_spec_alphabet;
use super::sync::{compose, ComposeOptions, Composition};
use crate::automaton::{Alphabet, Automaton, EventId, StateId, Transition};
use crate::error::{Error, Result};
use fixedbitset::FixedBitSet;

/// The events of `plant` named in `names`, as a mask over its event ids;
/// `what` says which set it is in the error for an unknown name.
fn event_mask(plant: &Automaton, names: &[impl AsRef<str>], what: &str) -> Result<Vec<bool>> {
    let mut mask = vec![false; plant.alphabet().len()];
    for name in names {
        let name = name.as_ref();
        let id = plant.alphabet().id(name).ok_or_else(|| {
            Error::Incompatible(format!(
                "{what} event `{name}` is not an event of the plant `{}`",
                plant.name()
            ))
        })?;
        mask[id.index()] = true;
    }
    Ok(mask)
}

/// `a` with the marked states `marked`.
fn remark(a: &Automaton, marked: FixedBitSet) -> Automaton {
    let (name, alphabet, names, initial, _, offsets, edges) = a.clone().into_parts();
    Automaton::from_parts(name, alphabet, names, initial, marked, offsets, edges)
}

/// `a` with every state marked: its marked language is its closed one.
fn closure(a: &Automaton) -> Automaton {
    let mut all = FixedBitSet::with_capacity(a.num_states());
    all.insert_range(..);
    remark(a, all)
}

/// The sub-automaton of `a` on the states where `keep` holds.
fn keep_states(a: &Automaton, keep: impl Fn(StateId) -> bool) -> Automaton {
    let mut set = FixedBitSet::with_capacity(a.num_states());
    set.extend(a.states().filter(|&s| keep(s)).map(StateId::index));
    super::reach::restrict(a, &set)
}

/// `k` over the plant alphabet `alphabet`, self-looped with the events it
/// lacks and completed by a dump state that every undefined transition
/// leads to. A state of `k` is marked where `marked` holds, the dump state
/// when `dump_marked`. With `marked` false and the dump marked, the marked
/// language is Σ* − K̄; with `marked` the complement of `k`'s marking,
/// Σ* − Km.
fn complement(
    k: &Automaton,
    alphabet: &Alphabet,
    marked: impl Fn(StateId) -> bool,
    dump_marked: bool,
) -> Automaton {
    let n = k.num_states();
    let dump = StateId(n as u32);
    let local: Vec<Option<EventId>> = alphabet
        .iter()
        .map(|(_, e)| k.alphabet().id(&e.name))
        .collect();
    let mut offsets = Vec::with_capacity(n + 2);
    let mut edges = Vec::with_capacity((n + 1) * alphabet.len());
    offsets.push(0u32);
    for s in k.states() {
        for (e, l) in alphabet.ids().zip(&local) {
            let target = match l {
                None => s,
                Some(l) => k.successor(s, *l).unwrap_or(dump),
            };
            edges.push(Transition { event: e, target });
        }
        offsets.push(edges.len() as u32);
    }
    edges.extend(alphabet.ids().map(|event| Transition {
        event,
        target: dump,
    }));
    offsets.push(edges.len() as u32);
    let mut marks = FixedBitSet::with_capacity(n + 1);
    marks.extend(k.states().filter(|&s| marked(s)).map(StateId::index));
    marks.set(n, dump_marked);
    Automaton::from_parts(
        format!("co({})", k.name()),
        alphabet.clone(),
        crate::automaton::StateNames::Indices,
        Some(k.initial().unwrap_or(dump)),
        marks,
        offsets,
        edges,
    )
}

/// `k` as an automaton over the plant's alphabet with the plant's event
/// ids, the events it lacks self-looped everywhere; refused when `k` has
/// events the plant lacks or disagrees on an event's controllability.
fn over_plant_alphabet(plant: &Automaton, k: &Automaton) -> Result<Automaton> {
    check_spec_alphabet(plant, k)?;
    let n = k.num_states();
    let full = complement(k, plant.alphabet(), |s| k.is_marked(s), false);
    let mut extended = keep_states(&full, |s| s.index() < n);
    extended.set_name(k.name());
    Ok(extended)
}

/// The synchronous composition of `a` and `b`, states unnamed, refused
/// beyond `max_states` states.
fn product(a: &Automaton, b: &Automaton, max_states: usize) -> Result<Automaton> {
    let options = ComposeOptions {
        name_states: false,
        max_states,
        progress: &(),
    };
    Ok(compose(&[a, b], Composition::Sync, options)?.automaton)
}

/// The names of the events `path` spells in `a`.
fn names(a: &Automaton, path: &[EventId]) -> Vec<String> {
    path.iter()
        .map(|&e| a.alphabet().name(e).to_owned())
        .collect()
}
