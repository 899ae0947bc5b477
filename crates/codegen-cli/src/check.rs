//! `codegen check`: controllability, nonblocking, nonconflict; with
//! `--spec`, whether the closed loop stays within the specification and
//! is the supremal controllable one (supcon's languages).
//!
//! Every composite state in the report comes with its key: the state of
//! each component, plant components first (in command-line order), then
//! the supervisors.

use super::error::CliError;
use super::key::Key;
use super::lang::Counterexample;
use super::output::{outln, Out};
use super::{load, Outcome, Role};
use des::ops::{self, BlockingWitness, UncontrollableWitness};
use des::Automaton;
use std::path::PathBuf;

/// An uncontrollable event the supervisor disables, and where.
#[derive(Debug, serde::Serialize)]
struct Uncontrollable {
    #[serde(flatten)]
    witness: UncontrollableWitness,
    /// The plant components' states in `plant_state`.
    #[serde(skip_serializing_if = "Option::is_none")]
    plant_components: Option<Key>,
}

/// A state from which no marked state can be reached, and its key.
#[derive(Debug, serde::Serialize)]
struct Blocking {
    #[serde(flatten)]
    witness: BlockingWitness,
    /// The components' states in `state`: plant components, then
    /// supervisors.
    #[serde(skip_serializing_if = "Option::is_none")]
    components: Option<Key>,
}

impl Blocking {
    fn new(witness: BlockingWitness, components: &[&Automaton]) -> Blocking {
        Blocking {
            components: Key::after(components, &witness.path),
            witness,
        }
    }
}

#[derive(Debug, serde::Serialize)]
struct SupervisorReport {
    name: String,
    controllable: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    uncontrollable: Option<Uncontrollable>,
    nonblocking: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    blocking: Option<Blocking>,
}

#[derive(Debug, serde::Serialize)]
struct Report {
    supervisors: Vec<SupervisorReport>,
    /// Only for two or more supervisors.
    #[serde(skip_serializing_if = "Option::is_none")]
    nonconflicting: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    conflict: Option<Blocking>,
    /// With `--spec` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    specification: Option<SpecReport>,
    holds: bool,
}

/// The closed loop of the plant with every supervisor against the
/// specification and against supcon(plant, specification).
#[derive(Debug, serde::Serialize)]
struct SpecReport {
    /// The specification components.
    specs: Vec<String>,
    /// L and Lm of the closed loop within those of plant ‖ specification.
    within: bool,
    /// A shortest string of the closed loop that plant ‖ specification
    /// lacks.
    #[serde(skip_serializing_if = "Option::is_none")]
    outside: Option<Counterexample>,
    /// The closed loop has supcon's closed and marked languages.
    supremal: bool,
    /// A shortest string that one of them has (`in`: `supcon` or
    /// `closed_loop`) and the other lacks.
    #[serde(skip_serializing_if = "Option::is_none")]
    difference: Option<Counterexample>,
    supcon_states: usize,
}

/// Decides the `--spec` questions for the closed loop of `plant` with
/// `sups`.
fn check_spec(
    plant: &Automaton,
    sups: &[Automaton],
    spec_files: &[PathBuf],
) -> Result<SpecReport, CliError> {
    let specs = load(spec_files, Role::Spec)?;
    let spec_refs: Vec<&Automaton> = specs.iter().collect();
    let spec = ops::sync(&spec_refs)?;
    // Refuses specification events the plant lacks, as synth does.
    let supcon = ops::supcon(plant, &spec)?;
    let mut parts = vec![plant];
    parts.extend(sups);
    let closed_loop = ops::sync(&parts)?;
    // The specification's own events only: self-looped by the plant's.
    let legal = ops::sync(&[plant, &spec])?;
    let outside = ops::inclusion_counterexample(&closed_loop, &legal).map(|d| Counterexample {
        string: d.string,
        language: d.language,
        r#in: None,
    });
    let difference = ops::language_difference(&closed_loop, &supcon)
        .map(|d| Counterexample::of(d, "closed_loop", "supcon"));
    Ok(SpecReport {
        specs: specs.iter().map(|s| s.name().to_owned()).collect(),
        within: outside.is_none(),
        outside,
        supremal: difference.is_none(),
        difference,
        supcon_states: supcon.num_states(),
    })
}

/// An event string as printed: its events spaced, or `(the empty string)`.
pub(crate) fn path(p: &[String]) -> String {
    if p.is_empty() {
        "(the empty string)".to_owned()
    } else {
        p.join(" ")
    }
}

/// `0.1 = (MACH1 0, MACH2 1)`, or the name alone when there is no key.
fn keyed(state: &str, key: Option<&Key>) -> String {
    match key {
        Some(key) => format!("{state} = {}", key.describe()),
        None => state.to_owned(),
    }
}

pub fn run(
    plant_files: &[PathBuf],
    sup_files: &[PathBuf],
    spec_files: &[PathBuf],
    json: bool,
    out: &mut Out,
) -> Result<Outcome, CliError> {
    let components = load(plant_files, Role::Plant)?;
    let component_refs: Vec<&Automaton> = components.iter().collect();
    let plant = ops::sync(&component_refs)?;
    let sups = load(sup_files, Role::Supervisor)?;
    let mut reports = Vec::new();
    for sup in &sups {
        let mut closed_loop = component_refs.clone();
        closed_loop.push(sup);
        let uncontrollable = ops::check_controllable(&plant, sup)?.map(|witness| {
            Uncontrollable {
                // A single component's state names are its own.
                plant_components: (components.len() > 1)
                    .then(|| Key::after(&component_refs, &witness.path))
                    .flatten(),
                witness,
            }
        });
        let blocking =
            ops::check_nonconflicting(&[&plant, sup])?.map(|w| Blocking::new(w, &closed_loop));
        reports.push(SupervisorReport {
            name: sup.name().to_owned(),
            controllable: uncontrollable.is_none(),
            uncontrollable,
            nonblocking: blocking.is_none(),
            blocking,
        });
    }
    let (nonconflicting, conflict) = if sups.len() > 1 {
        let mut all: Vec<&Automaton> = vec![&plant];
        all.extend(sups.iter());
        let mut keyed_by = component_refs.clone();
        keyed_by.extend(sups.iter());
        let w = ops::check_nonconflicting(&all)?;
        (Some(w.is_none()), w.map(|w| Blocking::new(w, &keyed_by)))
    } else {
        (None, None)
    };
    let specification = if spec_files.is_empty() {
        None
    } else {
        Some(check_spec(&plant, &sups, spec_files)?)
    };
    let holds = reports.iter().all(|r| r.controllable && r.nonblocking)
        && nonconflicting != Some(false)
        && specification
            .as_ref()
            .is_none_or(|s| s.within && s.supremal);
    let report = Report {
        supervisors: reports,
        nonconflicting,
        conflict,
        specification,
        holds,
    };
    if json {
        out.json(&report);
    } else {
        print_text(out, &report);
    }
    Ok(if holds {
        Outcome::Holds
    } else {
        Outcome::Fails
    })
}

fn print_text(out: &mut Out, report: &Report) {
    for r in &report.supervisors {
        outln!(out, "{}:", r.name);
        match &r.uncontrollable {
            None => outln!(out, "  controllable: yes"),
            Some(u) => outln!(
                out,
                "  controllable: NO: after {}, the plant (in state {}) can do \
                 uncontrollable `{}` but the supervisor (in state {}) disables it",
                path(&u.witness.path),
                keyed(&u.witness.plant_state, u.plant_components.as_ref()),
                u.witness.event,
                u.witness.supervisor_state
            ),
        }
        match &r.blocking {
            None => outln!(out, "  nonblocking:  yes (closed loop with the plant)"),
            Some(b) => outln!(
                out,
                "  nonblocking:  NO: after {}, the closed loop is in state {} \
                 from which no marked state can be reached",
                path(&b.witness.path),
                keyed(&b.witness.state, b.components.as_ref())
            ),
        }
    }
    match (&report.nonconflicting, &report.conflict) {
        (Some(true), _) => outln!(
            out,
            "nonconflicting: yes ({} supervisors)",
            report.supervisors.len()
        ),
        (Some(false), Some(b)) => outln!(
            out,
            "nonconflicting: NO: after {}, plant and supervisors together are in \
             state {} from which no marked state can be reached",
            path(&b.witness.path),
            keyed(&b.witness.state, b.components.as_ref())
        ),
        _ => {}
    }
    if let Some(spec) = &report.specification {
        print_spec(out, spec, report.supervisors.len());
    }
}

fn print_spec(out: &mut Out, spec: &SpecReport, supervisors: usize) {
    outln!(
        out,
        "specification {}: the closed loop of the plant with {}",
        spec.specs.join(", "),
        if supervisors == 1 {
            "the supervisor".to_owned()
        } else {
            format!("the {supervisors} supervisors")
        }
    );
    match &spec.outside {
        None => outln!(
            out,
            "  within:       yes (closed and marked languages within plant ‖ specification)"
        ),
        Some(c) => outln!(
            out,
            "  within:       NO: {} is in {l}(closed loop) but not in {l}(plant ‖ specification)",
            path(&c.string),
            l = c.letter()
        ),
    }
    match &spec.difference {
        None => outln!(
            out,
            "  supremal:     yes (supcon's closed and marked languages, {} states)",
            spec.supcon_states
        ),
        Some(d) => {
            let (has, lacks) = if d.r#in == Some("supcon") {
                ("supcon", "closed loop")
            } else {
                ("closed loop", "supcon")
            };
            outln!(
                out,
                "  supremal:     NO: {} is in {l}({has}) but not in {l}({lacks})",
                path(&d.string),
                l = d.letter()
            );
        }
    }
}
