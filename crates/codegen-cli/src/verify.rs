//! `codegen verify`: modular controllability, each supervisor decided on
//! its reduced plant (`des::ops::modular`), never the whole plant; with
//! `--nonblocking`, the closed loop of the plant with every supervisor,
//! composed as one, checked nonblocking; with `--symbolic` as well, that
//! closed loop is decided on BDDs (`des_symbolic::verify`) and never built.

use super::check::path;
use super::error::CliError;
use super::key::Key;
use super::output::{outln, Out};
use super::progress::Spinner;
use super::{load, Outcome, Role};
use des::ops::{self, ComposeOptions, ModularVerdict};
use des::Automaton;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `codegen verify`.
#[derive(Debug, clap::Args)]
pub struct VerifyArgs {
    /// Plant component files; the plant is their synchronous composition,
    /// which is never built.
    #[arg(long = "plant", required = true, num_args = 1..)]
    plants: Vec<PathBuf>,
    /// Supervisor files, each checked on its own reduced plant.
    #[arg(long = "sup", required = true, num_args = 1..)]
    sups: Vec<PathBuf>,
    /// Refuse a reduced plant or closed loop beyond this many states.
    #[arg(long, default_value_t = ops::sync::DEFAULT_MAX_STATES)]
    max_states: usize,
    /// Also compose the plant components with all the supervisors (the
    /// closed loop, never the plant alone) and check it nonblocking.
    #[arg(long)]
    nonblocking: bool,
    /// With `--nonblocking`: decide the closed loop on BDDs, without
    /// building it (exact state count; no transition count).
    #[arg(long, requires = "nonblocking")]
    symbolic: bool,
}

/// A state count: a JSON number while it fits one, else a decimal string.
#[derive(Debug, serde::Serialize)]
#[serde(untagged)]
enum Count {
    Number(u64),
    Decimal(String),
}

impl Count {
    fn of(n: &des_symbolic::BigUint) -> Count {
        u64::try_from(n).map_or_else(|_| Count::Decimal(n.to_string()), Count::Number)
    }
}

impl std::fmt::Display for Count {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Count::Number(n) => write!(f, "{n}"),
            Count::Decimal(n) => f.write_str(n),
        }
    }
}

/// The closed loop of the plant with every supervisor.
#[derive(Debug, serde::Serialize)]
struct ClosedLoop {
    /// `explicit` or `symbolic`.
    method: &'static str,
    states: Count,
    /// Explicit only.
    #[serde(skip_serializing_if = "Option::is_none")]
    transitions: Option<usize>,
    nonblocking: bool,
    /// A shortest string to a state from which no marked state can be
    /// reached.
    #[serde(skip_serializing_if = "Option::is_none")]
    blocking_path: Option<Vec<String>>,
    /// Every component's state there: plant components, then
    /// supervisors.
    #[serde(skip_serializing_if = "Option::is_none")]
    blocking_state: Option<Key>,
    milliseconds: f64,
}

#[derive(Debug, serde::Serialize)]
struct SupervisorReport {
    #[serde(flatten)]
    verdict: ModularVerdict,
    controllable: bool,
    /// The reduced plant's components' states after the counterexample.
    #[serde(skip_serializing_if = "Option::is_none")]
    plant_components: Option<Key>,
    milliseconds: f64,
}

#[derive(Debug, serde::Serialize)]
struct Report {
    plant_components: usize,
    supervisors: Vec<SupervisorReport>,
    /// With `--nonblocking` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    closed_loop: Option<ClosedLoop>,
    holds: bool,
    milliseconds: f64,
}

pub fn run(args: &VerifyArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let start = Instant::now();
    let spinner = Spinner::new("loading");
    let components = load(&args.plants, Role::Plant)?;
    let refs: Vec<&Automaton> = components.iter().collect();
    let sups = load(&args.sups, Role::Supervisor)?;
    let options = ComposeOptions {
        name_states: false,
        max_states: args.max_states,
        progress: &spinner,
    };
    let mut reports = Vec::new();
    for sup in &sups {
        spinner.phase(sup.name());
        let mark = Instant::now();
        let verdict =
            ops::check_controllable_modular(&refs, sup, options).map_err(CliError::max_states)?;
        let milliseconds = mark.elapsed().as_secs_f64() * 1e3;
        let plant_components = verdict.counterexample.as_ref().and_then(|c| {
            let reduced: Vec<&Automaton> = verdict.reduced.iter().map(|&i| refs[i]).collect();
            Key::after(&reduced, &c.witness.path)
        });
        reports.push(SupervisorReport {
            controllable: verdict.controllable(),
            verdict,
            plant_components,
            milliseconds,
        });
    }
    let closed_loop = match (args.nonblocking, args.symbolic) {
        (false, _) => None,
        (true, false) => {
            spinner.phase("closed loop");
            let mark = Instant::now();
            let mut all = refs.clone();
            all.extend(sups.iter());
            let product = ops::compose(&all, ops::Composition::Sync, options)
                .map_err(CliError::max_states)?;
            let a = &product.automaton;
            let blocking = ops::check_nonblocking(a);
            Some(ClosedLoop {
                method: "explicit",
                states: Count::Number(a.num_states() as u64),
                transitions: Some(a.num_transitions()),
                nonblocking: blocking.is_none(),
                blocking_state: blocking.as_ref().and_then(|w| Key::after(&all, &w.path)),
                blocking_path: blocking.map(|w| w.path),
                milliseconds: mark.elapsed().as_secs_f64() * 1e3,
            })
        }
        (true, true) => {
            spinner.phase("closed loop on BDDs");
            let mark = Instant::now();
            let model = des_symbolic::Model::new(&components, &sups)?;
            let verdict = des_symbolic::verify::nonblocking(&model);
            let mut all = refs.clone();
            all.extend(sups.iter());
            let path = verdict.counterexample.as_ref().map(|c| c.events.clone());
            Some(ClosedLoop {
                method: "symbolic",
                states: Count::of(&verdict.reachable),
                transitions: None,
                nonblocking: verdict.holds(),
                blocking_state: path.as_ref().and_then(|p| Key::after(&all, p)),
                blocking_path: path,
                milliseconds: mark.elapsed().as_secs_f64() * 1e3,
            })
        }
    };
    drop(spinner);
    let holds = reports.iter().all(|r| r.controllable)
        && closed_loop.as_ref().is_none_or(|c| c.nonblocking);
    let report = Report {
        plant_components: components.len(),
        supervisors: reports,
        closed_loop,
        holds,
        milliseconds: start.elapsed().as_secs_f64() * 1e3,
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
        let v = &r.verdict;
        outln!(
            out,
            "{}: {} ({:.1} ms)",
            v.supervisor,
            if r.controllable {
                "controllable"
            } else {
                "NOT controllable"
            },
            r.milliseconds
        );
        outln!(
            out,
            "  reduced plant: {} states, {} of {} components: {}{}",
            v.reduced_states,
            v.reduced.len(),
            report.plant_components,
            v.reduced_names.join(" "),
            if v.rounds > 1 {
                format!(
                    " (grown {} times: counterexamples that were no strings of the whole plant)",
                    v.rounds - 1
                )
            } else {
                String::new()
            }
        );
        if let Some(c) = &v.counterexample {
            let w = &c.witness;
            let state = match &r.plant_components {
                Some(key) => key.describe(),
                None => w.plant_state.clone(),
            };
            outln!(
                out,
                "  after {}, the reduced plant (in state {}) can do uncontrollable `{}` \
                 but the supervisor (in state {}) disables it",
                path(&w.path),
                state,
                w.event,
                w.supervisor_state
            );
            if c.plant_path != w.path {
                outln!(
                    out,
                    "  as a string of the whole plant: {}",
                    path(&c.plant_path)
                );
            }
        }
    }
    if let Some(c) = &report.closed_loop {
        let size = match c.transitions {
            Some(t) => format!("{} states, {t} transitions", c.states),
            None => format!("{} states (on BDDs)", c.states),
        };
        match (&c.blocking_path, &c.blocking_state) {
            (None, _) => outln!(
                out,
                "closed loop (plant and {} supervisors): {size}, nonblocking ({:.1} ms)",
                report.supervisors.len(),
                c.milliseconds
            ),
            (Some(p), key) => outln!(
                out,
                "closed loop (plant and {} supervisors): {size}, BLOCKING: after {}, \
                 no marked state can be reached{} ({:.1} ms)",
                report.supervisors.len(),
                path(p),
                key.as_ref()
                    .map_or(String::new(), |k| format!(" from {}", k.describe())),
                c.milliseconds
            ),
        }
    }
    let good = report.supervisors.iter().filter(|r| r.controllable).count();
    outln!(
        out,
        "{} supervisors on {} plant components: {} controllable, {} not ({:.1} ms)",
        report.supervisors.len(),
        report.plant_components,
        good,
        report.supervisors.len() - good,
        report.milliseconds
    );
}
