//! `codegen check`: controllability, nonblocking, nonconflict.

use super::{load, print_json, Outcome, Role};
use codegen::ops::{self, BlockingWitness, UncontrollableWitness};
use codegen::{Automaton, Error};
use std::path::PathBuf;

#[derive(Debug, serde::Serialize)]
struct SupervisorReport {
    name: String,
    controllable: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    uncontrollable: Option<UncontrollableWitness>,
    nonblocking: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    blocking: Option<BlockingWitness>,
}

#[derive(Debug, serde::Serialize)]
struct Report {
    supervisors: Vec<SupervisorReport>,
    /// Only for two or more supervisors.
    #[serde(skip_serializing_if = "Option::is_none")]
    nonconflicting: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    conflict: Option<BlockingWitness>,
    holds: bool,
}

fn plant_of(plants: &[Automaton]) -> Result<Automaton, Error> {
    let refs: Vec<&Automaton> = plants.iter().collect();
    ops::sync(&refs)
}

fn path(p: &[String]) -> String {
    if p.is_empty() {
        "(the empty string)".to_owned()
    } else {
        p.join(" ")
    }
}

pub fn run(plants: &[PathBuf], sups: &[PathBuf], json: bool) -> Result<Outcome, Error> {
    let plant = plant_of(&load(plants, Role::Plant)?)?;
    let sups = load(sups, Role::Supervisor)?;
    let mut reports = Vec::new();
    for sup in &sups {
        let uncontrollable = ops::check_controllable(&plant, sup)?;
        let blocking = ops::check_nonconflicting(&[&plant, sup])?;
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
        let w = ops::check_nonconflicting(&all)?;
        (Some(w.is_none()), w)
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
        print_json(&report);
    } else {
        for r in &report.supervisors {
            println!("{}:", r.name);
            match &r.uncontrollable {
                None => println!("  controllable: yes"),
                Some(w) => println!(
                    "  controllable: NO: after {}, the plant (in state {}) can do \
                     uncontrollable `{}` but the supervisor (in state {}) disables it",
                    path(&w.path),
                    w.plant_state,
                    w.event,
                    w.supervisor_state
                ),
            }
            match &r.blocking {
                None => println!("  nonblocking:  yes (closed loop with the plant)"),
                Some(w) => println!(
                    "  nonblocking:  NO: after {}, the closed loop is in state {} \
                     from which no marked state can be reached",
                    path(&w.path),
                    w.state
                ),
            }
        }
        match (&report.nonconflicting, &report.conflict) {
            (Some(true), _) => println!("nonconflicting: yes ({} supervisors)", sups.len()),
            (Some(false), Some(w)) => println!(
                "nonconflicting: NO: after {}, plant and supervisors together are in \
                 state {} from which no marked state can be reached",
                path(&w.path),
                w.state
            ),
            _ => {}
        }
    }
    Ok(if holds {
        Outcome::Holds
    } else {
        Outcome::Fails
    })
}
