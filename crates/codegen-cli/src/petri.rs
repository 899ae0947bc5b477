//! `codegen petri`: place/transition nets (`.pnml`, `.toml`).
//!
//! - `petri info NET`: places, transitions, the incidence matrix, what
//!   the reachability graph says (states, bounds, safeness, dead
//!   markings) and the minimal place and transition invariants; exit 1
//!   when the net is not safe (an unbounded net is not) or has a dead
//!   marking. The invariants are algebra and are given for any net; the
//!   graph's properties only where it is finite within `--max-states`
//!   (otherwise the output says why they were not checked).
//! - `petri reach NET -o AUTOMATON`: the reachability graph written in any
//!   automaton format, to feed supcon.
//! - `petri synth NET --constraints FILE -o OUT`: place-invariant
//!   synthesis, one control place per constraint (for any plant, bounded
//!   or not), and the closed loop's properties and the supcon comparison
//!   where their graphs are finite (said, with the reason, when they are
//!   skipped); exit 1 when the closed loop can deadlock.
//! - `petri convert NET OUT`: between PNML and the native TOML.
//!
//! Every verb takes `--uncontrollable`, `--unobservable` or `--control`
//! for a net whose file does not say which transitions a supervisor can
//! prevent or see ([`super::net_control`]).

use super::error::CliError;
use super::net_control::ControlArgs;
use super::output::{outln, Out};
use super::Outcome;
use des::petri::compare::Comparison;
use des::petri::constraints::Constraint;
use des::petri::invariants::{self, Semiflow};
use des::petri::reach::{Beyond, Marked, Region, Stopped};
use des::petri::synth::Supervised;
use des::petri::{self, reach, PetriNet};
use des::{formats, Error};
use std::path::PathBuf;

/// `codegen petri …`
#[derive(Debug, clap::Subcommand)]
pub enum PetriCommand {
    /// Places, transitions, incidence matrix, and the reachability graph's
    /// properties (exit 1 when the net is not safe or can deadlock).
    Info {
        /// The net (`.pnml` or `.toml`).
        net: PathBuf,
        /// Explore at most this many markings; also at most 64 token counts
        /// (markings × places) and 64 firings per marking allowed, and 1024
        /// bytes of written state names (floors: 2^22 counts and firings,
        /// 16 MiB of names).
        #[arg(long, default_value_t = reach::DEFAULT_MAX_STATES, value_parser = positive)]
        max_states: usize,
        #[command(flatten)]
        control: ControlArgs,
    },
    /// The reachability graph as an automaton (one event per transition,
    /// the initial marking marked).
    Reach {
        /// The net (`.pnml` or `.toml`).
        net: PathBuf,
        /// Output automaton file; its extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
        /// Explore at most this many markings; also at most 64 token counts
        /// (markings × places) and 64 firings per marking allowed, and 1024
        /// bytes of written state names (floors: 2^22 counts and firings,
        /// 16 MiB of names).
        #[arg(long, default_value_t = reach::DEFAULT_MAX_STATES, value_parser = positive)]
        max_states: usize,
        #[command(flatten)]
        control: ControlArgs,
    },
    /// Place-invariant synthesis: one control place per constraint
    /// `L·m ≤ b` (D_c = −L·D_p, m_c0 = b − L·m_p0), the controlled net
    /// written (`.pnml` or `.toml`), and its closed loop checked (exit 1
    /// when it can deadlock).
    Synth {
        /// The plant net (`.pnml` or `.toml`).
        net: PathBuf,
        /// The constraints (`[[constraint]]` tables, TOML).
        #[arg(long)]
        constraints: PathBuf,
        /// The controlled net to write; its extension picks the format.
        #[arg(short, long)]
        output: PathBuf,
        /// Explore at most this many markings of the closed loop (and of the
        /// plant within the constraints, for the supcon comparison); the
        /// same bounds on token counts, firings and names as `petri reach`.
        #[arg(long, default_value_t = reach::DEFAULT_MAX_STATES, value_parser = positive)]
        max_states: usize,
        /// Enforce an inadmissible constraint through an admissible one
        /// that implies it (more places counted upstream of the
        /// uncontrollable transitions) instead of refusing it.
        #[arg(long)]
        transform: bool,
        #[command(flatten)]
        control: ControlArgs,
    },
    /// Convert a net between PNML and the native TOML (by extension).
    Convert {
        /// The net to read.
        input: PathBuf,
        /// The file to write.
        output: PathBuf,
        #[command(flatten)]
        control: ControlArgs,
    },
}

/// A positive number of markings (`0` is refused: it is no limit to mean).
fn positive(text: &str) -> Result<usize, String> {
    match text.parse::<usize>() {
        Ok(0) => Err("the limit must be at least 1 marking".to_owned()),
        Ok(n) => Ok(n),
        Err(e) => Err(e.to_string()),
    }
}

#[derive(Debug, serde::Serialize)]
struct Info {
    name: String,
    places: Vec<String>,
    transitions: Vec<TransitionInfo>,
    /// Rows by place, columns by transition.
    incidence: Vec<Vec<i64>>,
    initial: Vec<u32>,
    /// `None` when the graph was not explored (`not_explored` says why).
    reachable_markings: Option<usize>,
    /// Why the reachability graph was not explored (unbounded, or beyond
    /// `--max-states`); `None` when it was.
    not_explored: Option<String>,
    /// Largest token count of each place over the reachable markings.
    bounds: Option<Vec<u32>>,
    /// `None`: not known (the graph is beyond the limit); an unbounded
    /// net is not safe.
    safe: Option<bool>,
    dead_markings: Vec<String>,
    /// Transitions that can become dead for good (empty: the net is live).
    not_live: Option<Vec<String>>,
    /// Minimal P-semiflows with `y·m0`.
    place_invariants: Vec<PlaceInvariant>,
    /// Minimal T-semiflows (firing counts).
    transition_invariants: Vec<Vec<Term>>,
}

/// One weighted place or transition of an invariant.
#[derive(Debug, serde::Serialize)]
struct Term {
    id: String,
    weight: u128,
}

#[derive(Debug, serde::Serialize)]
struct PlaceInvariant {
    /// In place order.
    weights: Vec<Term>,
    /// `y·m` in every reachable marking.
    value: u128,
}

#[derive(Debug, serde::Serialize)]
struct TransitionInfo {
    id: String,
    controllable: bool,
    observable: bool,
}

/// Runs a `petri` command.
pub fn run(command: &PetriCommand, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    match command {
        PetriCommand::Info {
            net,
            max_states,
            control,
        } => {
            let net = control.read_net(net)?;
            info(&net, *max_states, json, out)
        }
        PetriCommand::Reach {
            net,
            output,
            max_states,
            control,
        } => {
            let net = control.read_net(net)?;
            let r = reach::reachability(&net, *max_states).map_err(CliError::max_states)?;
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
        PetriCommand::Synth {
            net,
            constraints,
            output,
            max_states,
            transform,
            control,
        } => {
            let plant = control.read_net(net)?;
            let cs = petri::constraints::read_file(constraints, &plant)?;
            let enforced = petri::admissible::enforced(&plant, &cs, *transform)?;
            let s = petri::synth::synthesize(&plant, &enforced)?;
            petri::write_file(output, &s.net)?;
            // The control places are algebra; the closed loop and the
            // comparison need finite graphs, and are skipped (with the
            // reason) where there are none within the limit.
            let r = reach::explore(
                &s.net,
                reach::Limits::states(*max_states),
                Marked::Initial,
                Region::All,
                Beyond::Drop,
            )?;
            let cmp = match &r {
                Ok(_) => petri::compare::against_supcon(&plant, &cs, &s, *max_states)?,
                Err(stopped) => Err(Stopped::Limit {
                    max_states: *max_states,
                    message: format!(
                        "the closed loop was not explored ({})",
                        match stopped {
                            Stopped::Unbounded(_) => "it is unbounded",
                            Stopped::Limit { .. } | Stopped::Overflow(_) => {
                                "it is beyond the limit"
                            }
                        }
                    ),
                }),
            };
            synth_report(&plant, &cs, &enforced, &s, &r, &cmp, output, json, out)
        }
        PetriCommand::Convert {
            input,
            output,
            control,
        } => {
            let net = control.read_net(input)?;
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

fn info(net: &PetriNet, max_states: usize, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let explored = reach::explore(
        net,
        reach::Limits::states(max_states),
        Marked::Initial,
        Region::All,
        Beyond::Drop,
    )?;
    let weights = |s: &Semiflow, id: &dyn Fn(usize) -> String| -> Vec<Term> {
        s.iter()
            .map(|&(i, w)| Term {
                id: id(i),
                weight: w,
            })
            .collect()
    };
    let place_id = |p: usize| net.places()[p].id.clone();
    let transition_id = |t: usize| net.transitions()[t].id.clone();
    let place_invariants = invariants::place_invariants(net)?
        .iter()
        .map(|y| {
            let value = invariants::value(y, net.initial()).ok_or_else(|| {
                Error::Incompatible(format!(
                    "net `{}`: the value y·m0 of a place invariant exceeds 2^128 − 1",
                    net.name()
                ))
            })?;
            Ok(PlaceInvariant {
                weights: weights(y, &place_id),
                value,
            })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let transition_invariants = invariants::transition_invariants(net)?
        .iter()
        .map(|x| weights(x, &transition_id))
        .collect();
    let (reachable_markings, not_explored, bounds, safe, dead_markings, not_live) = match &explored
    {
        Ok(r) => (
            Some(r.markings.len()),
            None,
            Some(r.bounds.clone()),
            Some(r.is_safe()),
            r.dead
                .iter()
                .map(|&k| net.marking_name(&r.markings[k]))
                .collect(),
            Some(
                r.live(net.transitions().len())
                    .iter()
                    .zip(net.transitions())
                    .filter(|&(&live, _)| !live)
                    .map(|(_, t)| t.id.clone())
                    .collect(),
            ),
        ),
        Err(stopped) => (
            None,
            Some(stopped.to_string()),
            None,
            matches!(stopped, Stopped::Unbounded(_)).then_some(false),
            Vec::new(),
            None,
        ),
    };
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
        reachable_markings,
        not_explored,
        bounds,
        safe,
        dead_markings,
        not_live,
        place_invariants,
        transition_invariants,
    };
    let outcome = if info.safe != Some(false) && info.dead_markings.is_empty() {
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
    let cell = info
        .incidence
        .iter()
        .flatten()
        .map(|d| d.to_string().len() + 1)
        .max()
        .unwrap_or(0)
        .max(3);
    for (p, row) in info.places.iter().zip(&info.incidence) {
        let cells: Vec<String> = row.iter().map(|d| format!("{d:>cell$}")).collect();
        outln!(out, "    {p:<width$} [{} ]", cells.join(""));
    }
    outln!(
        out,
        "  initial marking:    {}",
        net.marking_name(&info.initial)
    );
    match (&info.reachable_markings, &info.not_explored) {
        (Some(n), _) => outln!(out, "  reachable markings: {n}"),
        (None, Some(why)) => outln!(out, "  reachable markings: not explored: {why}"),
        (None, None) => {}
    }
    match (&info.bounds, info.safe) {
        (Some(bounds), _) => {
            let over: Vec<String> = info
                .places
                .iter()
                .zip(bounds)
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
        }
        (None, Some(false)) => outln!(out, "  safe:               no (unbounded)"),
        (None, _) => outln!(
            out,
            "  safe:               not checked (the graph was not explored)"
        ),
    }
    let sum = |terms: &[Term]| {
        terms
            .iter()
            .map(|t| match t.weight {
                1 => t.id.clone(),
                w => format!("{w}·{}", t.id),
            })
            .collect::<Vec<_>>()
            .join(" + ")
    };
    match &info.not_live {
        None => outln!(
            out,
            "  live:               not checked (the graph was not explored)"
        ),
        Some(not_live) if not_live.is_empty() => outln!(
            out,
            "  live:               yes (every transition can always fire again)"
        ),
        Some(not_live) => outln!(
            out,
            "  live:               no ({} can become dead)",
            not_live.join(", ")
        ),
    }
    outln!(out, "  place invariants:");
    for y in &info.place_invariants {
        outln!(out, "    {} = {}", sum(&y.weights), y.value);
    }
    if info.place_invariants.is_empty() {
        outln!(out, "    none");
    }
    outln!(out, "  transition invariants:");
    for x in &info.transition_invariants {
        outln!(out, "    {}", sum(x));
    }
    if info.transition_invariants.is_empty() {
        outln!(out, "    none");
    }
    if info.reachable_markings.is_none() {
        outln!(
            out,
            "  deadlock-free:      not checked (the graph was not explored)"
        );
    } else if info.dead_markings.is_empty() {
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

#[derive(Debug, serde::Serialize)]
struct ControlInfo {
    constraint: String,
    id: String,
    /// `D_c` by transition id, zero entries left out.
    incidence: serde_json::Map<String, serde_json::Value>,
    initial: u32,
    /// The admissible constraint enforced instead (`--transform`), if any.
    enforced_as: Option<String>,
}

#[derive(Debug, serde::Serialize)]
struct DeadInfo {
    marking: String,
    firing_sequence: Vec<String>,
}

#[allow(clippy::too_many_arguments)]
fn synth_report(
    plant: &PetriNet,
    constraints: &[Constraint],
    enforced: &[Constraint],
    s: &Supervised,
    r: &Result<reach::Reachability, Stopped>,
    cmp: &Result<Comparison, Stopped>,
    output: &std::path::Path,
    json: bool,
    out: &mut Out,
) -> Result<Outcome, CliError> {
    let ids: Vec<&str> = plant.transitions().iter().map(|t| t.id.as_str()).collect();
    let dead: Vec<DeadInfo> = match r {
        Ok(r) => r
            .dead
            .iter()
            .map(|&k| DeadInfo {
                marking: s.net.marking_name(&r.markings[k]),
                firing_sequence: r
                    .firing_sequence(k)
                    .into_iter()
                    .map(|t| ids[t].to_owned())
                    .collect(),
            })
            .collect(),
        Err(_) => Vec::new(),
    };
    let outcome = if dead.is_empty() {
        Outcome::Holds
    } else {
        Outcome::Fails
    };
    let written = |c: &Constraint| {
        let l: Vec<String> = c
            .weights
            .iter()
            .map(|&(p, w)| match w {
                1 => plant.places()[p].id.clone(),
                w => format!("{w}·{}", plant.places()[p].id),
            })
            .collect();
        format!("{} ≤ {}", l.join(" + "), c.bound)
    };
    if json {
        let control: Vec<ControlInfo> = s
            .control
            .iter()
            .zip(constraints.iter().zip(enforced))
            .map(|(c, (original, constraint))| ControlInfo {
                enforced_as: (constraint.weights != original.weights).then(|| written(constraint)),
                constraint: c.constraint.clone(),
                id: c.id.clone(),
                incidence: ids
                    .iter()
                    .zip(&c.incidence)
                    .filter(|&(_, &w)| w != 0)
                    .map(|(t, &w)| ((*t).to_owned(), serde_json::json!(w)))
                    .collect(),
                initial: c.initial,
            })
            .collect();
        let supcon = match cmp {
            Ok(cmp) => serde_json::json!({
                "states": cmp.supcon_states,
                "same_language": cmp.difference.is_none(),
                "difference": cmp.difference,
                "skipped": null,
            }),
            Err(why) => serde_json::json!({
                "states": null,
                "same_language": null,
                "difference": null,
                "skipped": why.to_string(),
            }),
        };
        out.json(&serde_json::json!({
            "output": output.display().to_string(),
            "control_places": control,
            "reachable_markings": r.as_ref().ok().map(|r| r.markings.len()),
            "safe": r.as_ref().ok().map(|r| r.is_safe()),
            "dead_markings": dead,
            "closed_loop_skipped": r.as_ref().err().map(|why| why.to_string()),
            "supcon": supcon,
        }));
        return Ok(outcome);
    }
    outln!(
        out,
        "{}: {} control place(s), columns {}",
        plant.name(),
        s.control.len(),
        ids.join(" ")
    );
    for ((c, original), constraint) in s.control.iter().zip(constraints).zip(enforced) {
        outln!(
            out,
            "  {} \"{}\": {}",
            c.id,
            c.constraint,
            written(original)
        );
        if constraint.weights != original.weights {
            outln!(
                out,
                "    not admissible; enforced as {} (implies it)",
                written(constraint)
            );
        }
        let cell = c
            .incidence
            .iter()
            .map(|d| d.to_string().len() + 1)
            .max()
            .unwrap_or(0)
            .max(3);
        let row: Vec<String> = c.incidence.iter().map(|d| format!("{d:>cell$}")).collect();
        outln!(out, "    D_c  = [{} ]", row.join(""));
        outln!(out, "    m_c0 = {}", c.initial);
    }
    match r {
        Ok(r) => {
            let over: Vec<String> = s
                .net
                .places()
                .iter()
                .zip(&r.bounds)
                .filter(|&(_, &b)| b > 1)
                .map(|(p, b)| format!("{} holds up to {b}", p.id))
                .collect();
            outln!(
                out,
                "  closed loop: {} reachable markings, {}, {}",
                r.markings.len(),
                if over.is_empty() {
                    "safe".to_owned()
                } else {
                    format!("not safe ({})", over.join(", "))
                },
                if dead.is_empty() {
                    "deadlock-free"
                } else {
                    "can deadlock"
                }
            );
        }
        Err(why) => outln!(
            out,
            "  closed loop: not checked (safeness, dead markings): {why}"
        ),
    }
    for d in &dead {
        outln!(
            out,
            "    dead in {} after {}",
            d.marking,
            if d.firing_sequence.is_empty() {
                "no firing".to_owned()
            } else {
                d.firing_sequence.join(" ")
            }
        );
    }
    match cmp {
        Err(why) => outln!(out, "  supcon on the reachability graph: not compared: {why}"),
        Ok(cmp) => match &cmp.difference {
            None => outln!(
                out,
                "  supcon on the reachability graph: the same language ({} states)",
                cmp.supcon_states
            ),
            Some(d) => outln!(
                out,
                "  supcon on the reachability graph ({} states) differs: `{}` is allowed only by {}",
                cmp.supcon_states,
                d.string.join(" "),
                if d.in_first {
                    "the control places"
                } else {
                    "supcon (the control places are more restrictive)"
                }
            ),
        },
    }
    outln!(out, "wrote {}", output.display());
    Ok(outcome)
}
