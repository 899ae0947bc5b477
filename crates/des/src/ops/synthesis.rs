//! The synthesis pipeline: `supcon(sync(plants), sync(specs))`, then
//! optionally supervisor reduction (its closed loop checked equal to
//! supcon's), then optionally `minstate`.
//!
//! Under partial observation (a plant event declared unobservable),
//! supcon becomes the supremal controllable and normal sublanguage
//! ([`sup_con_normal`], alternated with supcon to a fixpoint when the plant
//! blocks, so that the result is controllable with respect to the whole
//! plant), and the supervisor is its projection onto the observable
//! events, checked to give the plant the same closed loop and to command
//! only what every look-alike string allows ([`observed_supervisor`]).
//! Reduction is refused there: it assumes a supervisor that sees every
//! event.
//!
//! One function for every caller: `codegen synth` on the command line and
//! the `synthesize = { … }` supervisors of a PLC project both go through
//! [`synthesize`], so a project and the CLI give the same supervisor for
//! the same files.

use super::partial::observed::unobservable_names;
use super::partial::{name_after, observable_events, observed_supervisor, sup_con_normal};
use super::verify::check_controllable_with;
use super::{compose, minstate, reduce, supcon_with, ComposeOptions, Composition};
use crate::automaton::Automaton;
use crate::error::{Error, Result};
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
    /// Projection onto the observable events and its checks (zero when
    /// every event is observable).
    pub observe: Duration,
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
    /// The plant's unobservable events (the supervisor is then supconnorm's
    /// result projected onto the others; `supcon_size` is supconnorm's).
    pub unobservable: Vec<String>,
    /// The projected supervisor's size (before minstate), under partial
    /// observation.
    pub observed_size: Option<Size>,
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
/// Errors: [`Error::Incompatible`] when the
/// automata disagree on an event's controllability, a specification event
/// is not in the plant's alphabet or no plant is given;
/// [`Error::StateLimit`] when a composition
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
    let mut plant = compose_all(plants, options.compose)?;
    timings.compose_plant = mark.elapsed();
    // An event a specification says is unobservable is unobservable.
    for spec in specs {
        for (_, e) in spec.alphabet().unobservable() {
            plant.set_unobservable(&e.name);
        }
    }

    progress.report("composing the specification", 0);
    let mark = Instant::now();
    // No specification composes to the one-state automaton with no events,
    // which self-loops extend to everything the plant can do.
    let spec = compose_all(specs, options.compose)?;
    timings.compose_spec = mark.elapsed();

    let unobservable: Vec<String> = plant
        .alphabet()
        .unobservable()
        .map(|(_, e)| e.name.clone())
        .collect();
    if options.reduce && !unobservable.is_empty() {
        return Err(Error::Incompatible(format!(
            "supervisor reduction assumes a supervisor that sees every event, and the plant's \
             events {} are unobservable: synthesise without reduction",
            unobservable_names(&plant)
        )));
    }

    let mark = Instant::now();
    let mut supervisor = if unobservable.is_empty() {
        progress.report("supcon", 0);
        supcon_with(&plant, &spec, options.compose)?
    } else {
        progress.report("supconnorm", 0);
        sup_con_normal_of(&plant, &spec, options.compose)?
    };
    timings.supcon = mark.elapsed();
    let supcon_size = Size::of(&supervisor);

    let mut observed_size = None;
    if !unobservable.is_empty() && !supervisor.is_empty() {
        progress.report("projection onto the observable events", 0);
        let mark = Instant::now();
        supervisor = observed_supervisor(&plant, &supervisor, options.compose)?;
        if options.compose.name_states {
            // Named after what the controller knows: the states of plant
            // and specification it may be in.
            let reference = compose(&[&plant, &spec], Composition::Sync, options.compose)?;
            name_after(&reference.automaton, &mut supervisor);
        }
        timings.observe = mark.elapsed();
        observed_size = Some(Size::of(&supervisor));
    }

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
        unobservable,
        observed_size,
        timings,
    })
}

/// The supremal controllable and normal sublanguage for `plant` (with
/// unobservable events) and `spec`: [`sup_con_normal`], which answers for
/// the plant's nonblocking part, alternated with supcon until the result
/// is also controllable with respect to the whole plant (at once when the
/// plant is nonblocking).
fn sup_con_normal_of(
    plant: &Automaton,
    spec: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<Automaton> {
    let observable = observable_events(plant)?;
    let al = plant.alphabet();
    let controllable: Vec<&str> = al
        .iter()
        .filter(|(_, e)| e.controllable)
        .map(|(_, e)| e.name.as_str())
        .collect();
    let max = options.max_states;
    let name = format!("supconnorm({},{})", plant.name(), spec.name());
    let mut k = sup_con_normal(plant, spec, &controllable, &observable, max)?;
    for _ in 0..max.max(1) {
        if k.is_empty() || check_controllable_with(plant, &k, options)?.is_none() {
            k.set_name(name);
            return Ok(k);
        }
        let controlled = supcon_with(plant, &k, options)?;
        // Each round removes strings (supcon's result is strictly inside an
        // uncontrollable k), so the rounds end.
        k = sup_con_normal(plant, &controlled, &controllable, &observable, max)?;
    }
    Err(Error::StateLimit {
        max_states: max,
        message: format!("{name} has not reached its fixpoint after {max} rounds"),
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

    /// M1 breaks down (`b1`, unobservable when `silent`) and is repaired
    /// (`r1`, seen); a two-slot buffer; M2 may not start while M1 is down.
    fn breakdown(silent: bool) -> (Vec<Automaton>, Vec<Automaton>) {
        let mut m1 = auto(
            "M1",
            &[("s1", true), ("f1", false), ("b1", false), ("r1", false)],
            &[
                ("0", "s1", "work"),
                ("work", "f1", "0"),
                ("work", "b1", "down"),
                ("down", "r1", "0"),
            ],
            &["0"],
        );
        assert!(!silent || m1.set_unobservable("b1"));
        let m2 = auto(
            "M2",
            &[("s2", true), ("f2", false)],
            &[("0", "s2", "1"), ("1", "f2", "0")],
            &["0"],
        );
        let buffer = auto(
            "B",
            &[("f1", false), ("s2", true)],
            &[
                ("0", "f1", "1"),
                ("1", "f1", "2"),
                ("1", "s2", "0"),
                ("2", "s2", "1"),
            ],
            &["0"],
        );
        let zone = auto(
            "Z",
            &[("b1", false), ("r1", false), ("s2", true)],
            &[("0", "b1", "down"), ("down", "r1", "0"), ("0", "s2", "0")],
            &["0", "down"],
        );
        (vec![m1, m2], vec![buffer, zone])
    }

    #[test]
    fn an_unseen_breakdown_gives_the_projected_supconnorm() {
        let (plants, specs) = breakdown(true);
        let result = synthesize(&plants, &specs, SynthesisOptions::default()).unwrap();
        assert_eq!(result.unobservable, ["b1"]);
        let sup = &result.supervisor;
        assert!(!sup.alphabet().contains("b1"));
        assert_eq!(result.observed_size, Some(Size::of(sup)));
        // With a part in the buffer, M2 may start while M1 is idle, not
        // once M1 has started (it may be down).
        let id = |e: &str| sup.alphabet().id(e).unwrap();
        let after = |path: &[&str]| {
            path.iter()
                .try_fold(sup.initial().unwrap(), |s, e| sup.successor(s, id(e)))
                .unwrap()
        };
        assert!(sup.successor(after(&["s1", "f1"]), id("s2")).is_some());
        assert!(sup
            .successor(after(&["s1", "f1", "s1"]), id("s2"))
            .is_none());
        // Full observation allows it.
        let full = synthesize(&breakdown(false).0, &specs, SynthesisOptions::default()).unwrap();
        assert!(full.unobservable.is_empty());
        let f = &full.supervisor;
        let path = ["s1", "f1", "s1", "s2"];
        let fid = |e: &str| f.alphabet().id(e).unwrap();
        assert!(path
            .iter()
            .try_fold(f.initial().unwrap(), |s, e| f.successor(s, fid(e)))
            .is_some());
        // Minimised, the same language.
        let options = SynthesisOptions {
            minstate: true,
            ..SynthesisOptions::default()
        };
        let min = synthesize(&plants, &specs, options).unwrap();
        assert!(language_equal(&min.supervisor, sup));
    }

    #[test]
    fn reduction_under_partial_observation_is_refused() {
        let (plants, specs) = breakdown(true);
        let options = SynthesisOptions {
            reduce: true,
            ..SynthesisOptions::default()
        };
        let err = synthesize(&plants, &specs, options)
            .unwrap_err()
            .to_string();
        assert!(err.contains("`b1` are unobservable"), "{err}");
    }
}
