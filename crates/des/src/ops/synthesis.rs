//! The synthesis pipeline: `supcon(sync(plants), sync(specs))`, then
//! optionally supervisor reduction (its closed loop checked equal to
//! supcon's), then optionally `minstate`.
//!
//! One function for every caller: `codegen synth` on the command line and
//! the `synthesize = { … }` supervisors of a PLC project both go through
//! [`synthesize`], so a project and the CLI give the same supervisor for
//! the same files.

use super::{compose, minstate, reduce, supcon_with, ComposeOptions, Composition};
use crate::automaton::Automaton;
use crate::error::Result;
use std::time::{Duration, Instant};

/// Choices of [`synthesize`].
#[derive(Clone, Copy, Default)]
pub struct SynthesisOptions<'a> {
    /// State naming, state limit and progress of every composition (and of
    /// supcon's own product with the specification).
    pub compose: ComposeOptions<'a>,
    /// Minimise the supervisor's states (language preserved).
    pub minstate: bool,
    /// Reduce the supervisor ([`reduce::reduce`]): a smaller one with the
    /// same closed loop, which is checked.
    pub reduce: bool,
}

/// How long each phase of [`synthesize`] took.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Timings {
    /// Composing the plants.
    pub compose_plant: Duration,
    /// Composing the specifications.
    pub compose_spec: Duration,
    /// supcon.
    pub supcon: Duration,
    /// minstate (zero when not asked for).
    pub minstate: Duration,
    /// Supervisor reduction and its check (zero when not asked for).
    pub reduce: Duration,
}

/// Number of states and transitions of an automaton.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Size {
    /// States.
    pub states: usize,
    /// Transitions.
    pub transitions: usize,
}

impl Size {
    /// The size of `a`.
    pub fn of(a: &Automaton) -> Size {
        Size {
            states: a.num_states(),
            transitions: a.num_transitions(),
        }
    }
}

/// What [`synthesize`] produced.
#[derive(Debug, Clone)]
pub struct Synthesis {
    /// The plant: the synchronous composition of the plant components.
    pub plant: Automaton,
    /// The specification's composition; `None` without specifications.
    pub spec: Option<Automaton>,
    /// The supervisor (reduced and minimised when asked for). Empty when no
    /// controllable, nonblocking behaviour of the plant meets the
    /// specification.
    pub supervisor: Automaton,
    /// The supervisor's size as supcon gave it, before reduction and
    /// minstate.
    pub supcon_size: Size,
    /// Its size after reduction (before minstate), when asked for.
    pub reduced_size: Option<Size>,
    /// Time per phase.
    pub timings: Timings,
}

/// The synchronous composition of `parts` (the part itself when there is
/// one).
fn compose_all(parts: &[Automaton], options: ComposeOptions<'_>) -> Result<Automaton> {
    if let [one] = parts {
        return Ok(one.clone());
    }
    let refs: Vec<&Automaton> = parts.iter().collect();
    Ok(compose(&refs, Composition::Sync, options)?.automaton)
}

/// The supremal controllable, nonblocking supervisor of the composition of
/// `plants` for the composition of `specs` (extended to the plant's
/// alphabet by self-loops); with no specification, the plant's own
/// nonblocking, controllable part. `plants` must not be empty.
///
/// Errors: [`Error::Incompatible`](crate::Error::Incompatible) when the
/// automata disagree on an event's controllability, a specification event
/// is not in the plant's alphabet or no plant is given;
/// [`Error::StateLimit`](crate::Error::StateLimit) when a composition
/// exceeds `options.compose.max_states`.
pub fn synthesize(
    plants: &[Automaton],
    specs: &[Automaton],
    options: SynthesisOptions<'_>,
) -> Result<Synthesis> {
    if plants.is_empty() {
        return Err(crate::Error::Incompatible(
            "synthesis needs at least one plant".into(),
        ));
    }
    let progress = options.compose.progress;
    let mut timings = Timings::default();

    progress.report("composing the plant", 0);
    let mark = Instant::now();
    let plant = compose_all(plants, options.compose)?;
    timings.compose_plant = mark.elapsed();

    progress.report("composing the specification", 0);
    let mark = Instant::now();
    // No specification composes to the one-state automaton with no events,
    // which self-loops extend to everything the plant can do.
    let spec = compose_all(specs, options.compose)?;
    timings.compose_spec = mark.elapsed();

    progress.report("supcon", 0);
    let mark = Instant::now();
    let mut supervisor = supcon_with(&plant, &spec, options.compose)?;
    timings.supcon = mark.elapsed();
    let supcon_size = Size::of(&supervisor);

    if options.reduce && !supervisor.is_empty() {
        progress.report("supervisor reduction", 0);
        let mark = Instant::now();
        let reduced = reduce::reduce(&plant, &supervisor, options.compose.max_states)?.automaton;
        reduce::check_closed_loop(&plant, &supervisor, &reduced, options.compose)?;
        supervisor = reduced;
        timings.reduce = mark.elapsed();
    }
    let reduced_size = options.reduce.then(|| Size::of(&supervisor));
    if options.minstate && !supervisor.is_empty() {
        progress.report("minstate", 0);
        let mark = Instant::now();
        supervisor = minstate(&supervisor);
        timings.minstate = mark.elapsed();
    }
    Ok(Synthesis {
        plant,
        spec: (!specs.is_empty()).then_some(spec),
        supervisor,
        supcon_size,
        reduced_size,
        timings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::{language_equal, supcon};
    use crate::testing::auto;

    /// Two machines and a one-slot buffer between them (the small factory).
    fn factory() -> (Vec<Automaton>, Vec<Automaton>) {
        let mach = |i: &str| {
            let (s, f) = (format!("s{i}"), format!("f{i}"));
            auto(
                &format!("M{i}"),
                &[(s.as_str(), true), (f.as_str(), false)],
                &[("0", s.as_str(), "1"), ("1", f.as_str(), "0")],
                &["0"],
            )
        };
        let buffer = auto(
            "B",
            &[("f1", false), ("s2", true)],
            &[("0", "f1", "1"), ("1", "s2", "0")],
            &["0"],
        );
        (vec![mach("1"), mach("2")], vec![buffer])
    }

    #[test]
    fn the_pipeline_is_supcon_of_the_compositions() {
        let (plants, specs) = factory();
        let result = synthesize(&plants, &specs, SynthesisOptions::default()).unwrap();
        let plant = crate::ops::sync(&[&plants[0], &plants[1]]).unwrap();
        let expected = supcon(&plant, &specs[0]).unwrap();
        assert!(language_equal(&result.supervisor, &expected));
        assert_eq!(result.plant.num_states(), 4);
        assert_eq!(result.spec.as_ref().map(Automaton::num_states), Some(2));
        assert_eq!(result.supcon_size, Size::of(&expected));
    }

    #[test]
    fn minstate_keeps_the_language_and_the_supcon_size() {
        let (plants, specs) = factory();
        let options = SynthesisOptions {
            minstate: true,
            ..SynthesisOptions::default()
        };
        let min = synthesize(&plants, &specs, options).unwrap();
        let full = synthesize(&plants, &specs, SynthesisOptions::default()).unwrap();
        assert!(language_equal(&min.supervisor, &full.supervisor));
        assert_eq!(min.supcon_size, full.supcon_size);
        assert!(min.supervisor.num_states() <= full.supervisor.num_states());
    }

    #[test]
    fn without_a_specification_the_plant_is_its_own() {
        let (plants, _) = factory();
        let result = synthesize(&plants, &[], SynthesisOptions::default()).unwrap();
        assert!(result.spec.is_none());
        assert!(language_equal(&result.supervisor, &result.plant));
    }

    #[test]
    fn no_plant_is_an_error() {
        let err = synthesize(&[], &[], SynthesisOptions::default()).unwrap_err();
        assert!(err.to_string().contains("at least one plant"), "{err}");
    }
}
