//! Discrete-event operations on automata.
//!
//! | module | operations |
//! |---|---|
//! | [`reach`] | reachable, coreachable, accessible, coaccessible, trim |
//! | [`sync`](mod@sync) | sync (parallel composition), meet (product) |
//! | [`selfloop`](mod@selfloop) | selfloop, inverse projection |
//! | [`supcon`](mod@supcon) | supremal controllable nonblocking sublanguage |
//! | [`minstate`](mod@minstate) | language-preserving minimisation |
//! | [`condat`](mod@condat) | control data: disabled events per supervisor state |
//! | [`verify`] | controllability, nonblocking, nonconflict, with witnesses |
//! | [`modular`] | controllability of one modular supervisor on its reduced plant |
//! | [`equivalence`] | language equality and inclusion, isomorphism |
//! | [`partial`] | normality, supremal normal and controllable-normal sublanguages, observability |
//! | [`projection`] | natural projection, the observer property |
//! | [`reduce`](mod@reduce) | supervisor reduction and localization (control covers) |
//! | [`synthesis`](mod@synthesis) | the pipeline supcon(sync(plants), sync(specs)), minstate |

pub mod condat;
pub mod equivalence;
pub mod minstate;
pub mod modular;
pub mod partial;
pub mod projection;
pub mod reach;
pub mod reduce;
pub mod selfloop;
pub mod supcon;
pub mod sync;
pub mod synthesis;
pub mod verify;

pub use condat::{condat, Condat};
pub use equivalence::{
    inclusion_counterexample, isomorphic, language_difference, language_equal, language_included,
    LanguageDifference, LanguageKind,
};
pub use minstate::minstate;
pub use modular::{
    check_controllable_modular, reduced_plant, ModularCounterexample, ModularVerdict,
};
pub use partial::{
    check_observable, is_normal, is_normal_closed, sup_con_normal, sup_con_normal_closed,
    sup_normal, sup_normal_closed,
};
pub use projection::{check_observer, project, ObserverWitness};
pub use reach::{accessible, coaccessible, coreachable, is_trim, reachable, restrict, trim};
pub use reduce::{check_closed_loop, check_localized, localize, reduce, Localization, Reduction};
pub use selfloop::{inverse_projection, selfloop};
pub use supcon::{supcon, supcon_with};
pub use sync::{compose, meet, sync, ComposeOptions, Composition, Product};
pub use synthesis::{synthesize, Synthesis, SynthesisOptions};
pub use verify::{
    check_controllable, check_controllable_with, check_nonblocking, check_nonconflicting,
    BlockingWitness, UncontrollableWitness,
};

/// Receives progress reports of long operations.
pub trait Progress {
    /// `done` units (states, usually) of `phase` are finished.
    fn report(&self, phase: &str, done: usize);
}

/// No progress reporting.
impl Progress for () {
    fn report(&self, _phase: &str, _done: usize) {}
}
