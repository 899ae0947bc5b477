//! `codegen petri`: place/transition nets (`.pnml`, `.toml`).
//!
//! - `petri info NET`: places, transitions, the incidence matrix, and
//!   what the reachability graph says (states, bounds, safeness, dead
//!   markings); exit 1 when the net is not safe or has a dead marking.
//! - `petri reach NET -o AUTOMATON`: the reachability graph written in any
//!   automaton format, to feed supcon.
//! - `petri convert NET OUT`: between PNML and the native TOML.

use super::output::{outln, Out};
use super::Outcome;
use codegen::des::petri::{self, reach, PetriNet};
use codegen::{formats, Error};
use std::path::PathBuf;

/// `codegen petri …`
#[derive(Debug, clap::Subcommand)]
pub enum PetriCommand {
    /// Places, transitions, incidence matrix, and the reachability graph's
    /// properties (exit 1 when the net is not safe or can deadlock).
    Info {
        /// The net (`.pnml` or `.toml`).
        net: PathBuf,
        /// Explore at most this many markings.
        #[arg(long, default_value_t = reach::DEFAULT_MAX_STATES)]
        max_states: usize,
    },
    /// The reachability graph as an automaton (one event per transition,
    /// the initial marking marked).
    Reach {
        /// The net (`.pnml` or `.toml`).
        net: PathBuf,
        /// Output automaton file; its extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
        /// Explore at most this many markings.
        #[arg(long, default_value_t = reach::DEFAULT_MAX_STATES)]
        max_states: usize,
    },
    /// Convert a net between PNML and the native TOML (by extension).
    Convert {
        /// The net to read.
        input: PathBuf,
        /// The file to write.
        output: PathBuf,
    },
}

#[derive(Debug, serde::Serialize)]
struct Info {
    name: String,
    places: Vec<String>,
    transitions: Vec<TransitionInfo>,
    /// Rows by place, columns by transition.
    incidence: Vec<Vec<i64>>,
    initial: Vec<u32>,
    reachable_markings: usize,
    /// Largest token count of each place over the reachable markings.
    bounds: Vec<u32>,
    safe: bool,
    dead_markings: Vec<String>,
}

#[derive(Debug, serde::Serialize)]
struct TransitionInfo {
    id: String,
    controllable: bool,
    observable: bool,
}

/// Runs a `petri` command.
pub fn run(command: &PetriCommand, json: bool, out: &mut Out) -> Result<Outcome, Error> {
    match command {
        PetriCommand::Info { net, max_states } => {
            let net = petri::read_file(net)?;
            info(&net, *max_states, json, out)
        }
        PetriCommand::Reach {
            net,
            output,
            max_states,
        } => {
            let net = petri::read_file(net)?;
            let r = reach::reachability(&net, *max_states)?;
            let component = formats::Component {
                kind: formats::Kind::Plant,
                automaton: r.automaton,
            };
            formats::write_file(output, std::slice::from_ref(&component))?;
            let a = &component.automaton;
            if json {
                out.json(&serde_json::json!({
                    "output": output.display().to_string(),
                    "states": a.num_states(),
                    "transitions": a.num_transitions(),
                    "safe": r.bounds.iter().all(|&b| b <= 1),
                }));
            } else {
                outln!(
                    out,
                    "wrote {}: {} states, {} transitions (the reachability graph of `{}`)",
                    output.display(),
                    a.num_states(),
                    a.num_transitions(),
                    net.name()
                );
            }
            Ok(Outcome::Holds)
        }
        PetriCommand::Convert { input, output } => {
            let net = petri::read_file(input)?;
            petri::write_file(output, &net)?;
            if json {
                out.json(&serde_json::json!({ "output": output.display().to_string() }));
            } else {
                outln!(out, "wrote {}: net `{}`", output.display(), net.name());
            }
            Ok(Outcome::Holds)
        }
    }
}

fn info(net: &PetriNet, max_states: usize, json: bool, out: &mut Out) -> Result<Outcome, Error> {
    let r = reach::reachability(net, max_states)?;
    let info = Info {
        name: net.name().to_owned(),
        places: net.places().iter().map(|p| p.id.clone()).collect(),
        transitions: net
            .transitions()
            .iter()
            .map(|t| TransitionInfo {
                id: t.id.clone(),
                controllable: t.controllable,
                observable: t.observable,
            })
            .collect(),
        incidence: net.incidence(),
        initial: net.initial().clone(),
        reachable_markings: r.markings.len(),
        bounds: r.bounds.clone(),
        safe: r.is_safe(),
        dead_markings: r
            .dead
            .iter()
            .map(|&k| net.marking_name(&r.markings[k]))
            .collect(),
    };
    let outcome = if info.safe && info.dead_markings.is_empty() {
        Outcome::Holds
    } else {
        Outcome::Fails
    };
    if json {
        out.json(&info);
        return Ok(outcome);
    }
    outln!(
        out,
        "{}: {} places, {} transitions ({} uncontrollable, {} unobservable)",
        info.name,
        info.places.len(),
        info.transitions.len(),
        info.transitions.iter().filter(|t| !t.controllable).count(),
        info.transitions.iter().filter(|t| !t.observable).count(),
    );
    let width = info
        .places
        .iter()
        .map(|p| p.chars().count())
        .max()
        .unwrap_or(0);
    outln!(
        out,
        "  incidence (rows: places, columns: {}):",
        info.transitions
            .iter()
            .map(|t| t.id.as_str())
            .collect::<Vec<_>>()
            .join(" ")
    );
    for (p, row) in info.places.iter().zip(&info.incidence) {
        let cells: Vec<String> = row.iter().map(|d| format!("{d:>3}")).collect();
        outln!(out, "    {p:<width$} [{} ]", cells.join(""));
    }
    outln!(
        out,
        "  initial marking:    {}",
        net.marking_name(&info.initial)
    );
    outln!(out, "  reachable markings: {}", info.reachable_markings);
    let over: Vec<String> = info
        .places
        .iter()
        .zip(&info.bounds)
        .filter(|&(_, &b)| b > 1)
        .map(|(p, b)| format!("{p} holds up to {b}"))
        .collect();
    if over.is_empty() {
        outln!(
            out,
            "  safe:               yes (no place ever holds two tokens)"
        );
    } else {
        outln!(out, "  safe:               no ({})", over.join(", "));
    }
    if info.dead_markings.is_empty() {
        outln!(out, "  deadlock-free:      yes");
    } else {
        outln!(
            out,
            "  deadlock-free:      no, dead in {}",
            info.dead_markings.join(", ")
        );
    }
    Ok(outcome)
}
