//! `codegen check`: controllability, nonblocking, nonconflict.
//!
//! Every composite state in the report comes with its key: the state of
//! each component, plant components first (in command-line order), then
//! the supervisors.

use super::error::CliError;
use super::key::Key;
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
    holds: bool,
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
    let holds =
        reports.iter().all(|r| r.controllable && r.nonblocking) && nonconflicting != Some(false);
    let report = Report {
        supervisors: reports,
        nonconflicting,
        conflict,
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
}
