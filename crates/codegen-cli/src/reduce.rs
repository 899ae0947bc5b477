//! `codegen reduce` and `codegen localize`: a smaller supervisor, or one
//! local controller per controllable event, with the same closed loop
//! (checked before anything is written).
//!
//! Both need the plant the supervisor was designed for: what can happen
//! is the plant's to say, and a reduced or local controller knows only
//! what it disables. Run them beside the plant components (as a project
//! with `reduce = true` or `localize = true` does).

use super::error::CliError;
use super::output::{outln, Out};
use super::{load, output_name, Outcome, Role, Size};
use des::formats::{self, Component, Kind};
use des::ops::sync::DEFAULT_MAX_STATES;
use des::ops::{self, ComposeOptions};
use des::Automaton;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The plant, the supervisor and the limits, shared by both verbs.
#[derive(Debug, clap::Args)]
pub struct Inputs {
    /// Plant component files; the plant is their synchronous composition.
    #[arg(long = "plant", required = true, num_args = 1..)]
    plants: Vec<PathBuf>,
    /// The supervisor file (a module: its one supervisor or spec).
    #[arg(long = "sup", required = true)]
    sup: PathBuf,
    /// Refuse a composition (plant, closed loop) beyond this many states.
    #[arg(long, default_value_t = DEFAULT_MAX_STATES)]
    max_states: usize,
}

/// Arguments of `codegen reduce`.
#[derive(Debug, clap::Args)]
pub struct ReduceArgs {
    #[command(flatten)]
    inputs: Inputs,
    /// Output file; its extension picks the format.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Name of the reduced supervisor (default: the output file's stem).
    #[arg(long)]
    name: Option<String>,
}

/// Arguments of `codegen localize`.
#[derive(Debug, clap::Args)]
pub struct LocalizeArgs {
    #[command(flatten)]
    inputs: Inputs,
    /// A file for all local controllers (a format holding several:
    /// `.wmod`).
    #[arg(
        short = 'o',
        long = "output",
        conflicts_with = "output_dir",
        required_unless_present = "output_dir"
    )]
    output: Option<PathBuf>,
    /// Or a directory: one `NAME.EVENT.toml` per local controller.
    #[arg(long)]
    output_dir: Option<PathBuf>,
    /// Name of the local controllers' supervisor (default: the
    /// supervisor's name); each is `NAME.EVENT`.
    #[arg(long)]
    name: Option<String>,
}

fn load_inputs(inputs: &Inputs) -> Result<(Automaton, Automaton), CliError> {
    let plants = load(&inputs.plants, Role::Plant)?;
    let refs: Vec<&Automaton> = plants.iter().collect();
    let options = ComposeOptions {
        name_states: false,
        max_states: inputs.max_states,
        ..ComposeOptions::default()
    };
    let plant = ops::compose(&refs, ops::Composition::Sync, options)
        .map_err(CliError::max_states)?
        .automaton;
    let mut sups = load(std::slice::from_ref(&inputs.sup), Role::Supervisor)?;
    if sups.len() != 1 {
        return Err(CliError::Usage(format!(
            "{}: holds {} supervisors; give a file with one",
            inputs.sup.display(),
            sups.len()
        )));
    }
    Ok((plant, sups.remove(0)))
}

fn compose_options(inputs: &Inputs) -> ComposeOptions<'static> {
    ComposeOptions {
        max_states: inputs.max_states,
        ..ComposeOptions::default()
    }
}

#[derive(Debug, serde::Serialize)]
struct ReduceReport {
    supervisor: Size,
    reduced: Size,
    closed_loop_states: usize,
    closed_loop_checked: bool,
    milliseconds: f64,
    output: String,
}

/// `codegen reduce`.
pub fn reduce(args: &ReduceArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let (plant, sup) = load_inputs(&args.inputs)?;
    let start = Instant::now();
    let reduction =
        ops::reduce(&plant, &sup, args.inputs.max_states).map_err(CliError::max_states)?;
    let mut reduced = reduction.automaton;
    ops::check_closed_loop(&plant, &sup, &reduced, compose_options(&args.inputs))
        .map_err(CliError::max_states)?;
    let milliseconds = start.elapsed().as_secs_f64() * 1e3;
    reduced.set_name(output_name(&args.output, args.name.as_deref(), sup.name()));
    let report = ReduceReport {
        supervisor: Size::of(&sup),
        reduced: Size::of(&reduced),
        closed_loop_states: reduction.closed_loop_states,
        closed_loop_checked: true,
        milliseconds,
        output: args.output.display().to_string(),
    };
    formats::write_file(
        &args.output,
        &[Component {
            kind: Kind::Supervisor,
            automaton: reduced,
        }],
    )?;
    if json {
        out.json(&report);
    } else {
        outln!(out, "supervisor: {}", report.supervisor);
        outln!(
            out,
            "reduced:    {} ({:.1} ms; the closed loop, {} states, checked equal)",
            report.reduced,
            report.milliseconds,
            report.closed_loop_states
        );
        outln!(
            out,
            "wrote {}: run it beside the plant components, which say what can happen",
            report.output
        );
    }
    Ok(Outcome::Holds)
}

#[derive(Debug, serde::Serialize)]
struct LocalReport {
    event: String,
    name: String,
    #[serde(flatten)]
    size: Size,
}

#[derive(Debug, serde::Serialize)]
struct LocalizeReport {
    supervisor: Size,
    controllers: Vec<LocalReport>,
    total_states: usize,
    closed_loop_states: usize,
    closed_loop_checked: bool,
    milliseconds: f64,
    written: Vec<String>,
}

/// `codegen localize`.
pub fn localize(args: &LocalizeArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let (plant, sup) = load_inputs(&args.inputs)?;
    if let Some(path) = &args.output {
        if !formats::Format::from_path(path)?.holds_many() {
            return Err(CliError::Usage(format!(
                "{}: one file for all local controllers needs a format holding several (.wmod); or give --output-dir",
                path.display()
            )));
        }
    }
    let start = Instant::now();
    let mut localization =
        ops::localize(&plant, &sup, args.inputs.max_states).map_err(CliError::max_states)?;
    ops::check_localized(&plant, &sup, &localization, compose_options(&args.inputs))
        .map_err(CliError::max_states)?;
    let milliseconds = start.elapsed().as_secs_f64() * 1e3;
    let base = args.name.clone().unwrap_or_else(|| sup.name().to_owned());
    for (event, a) in &mut localization.controllers {
        a.set_name(format!("{base}.{event}"));
    }
    let components: Vec<Component> = localization
        .controllers
        .iter()
        .map(|(_, a)| Component {
            kind: Kind::Supervisor,
            automaton: a.clone(),
        })
        .collect();
    let mut written = Vec::new();
    match (&args.output, &args.output_dir) {
        (Some(path), _) => {
            formats::write_file(path, &components)?;
            written.push(path.display().to_string());
        }
        (None, Some(dir)) => {
            std::fs::create_dir_all(dir)
                .map_err(|e| CliError::Usage(format!("{}: {e}", dir.display())))?;
            for c in &components {
                let path: PathBuf = Path::new(dir).join(format!("{}.toml", c.automaton.name()));
                formats::write_file(&path, std::slice::from_ref(c))?;
                written.push(path.display().to_string());
            }
        }
        (None, None) => unreachable!("clap requires one of them"),
    }
    let controllers: Vec<LocalReport> = localization
        .controllers
        .iter()
        .map(|(event, a)| LocalReport {
            event: event.clone(),
            name: a.name().to_owned(),
            size: Size::of(a),
        })
        .collect();
    let report = LocalizeReport {
        supervisor: Size::of(&sup),
        total_states: controllers.iter().map(|c| c.size.states).sum(),
        controllers,
        closed_loop_states: localization.closed_loop_states,
        closed_loop_checked: true,
        milliseconds,
        written,
    };
    if json {
        out.json(&report);
    } else {
        outln!(out, "supervisor: {}", report.supervisor);
        for c in &report.controllers {
            outln!(out, "  {:<24} {}", c.name, c.size);
        }
        outln!(
            out,
            "{} local controllers, {} states in all ({:.1} ms; with the plant, the closed loop of {} states checked equal)",
            report.controllers.len(),
            report.total_states,
            report.milliseconds,
            report.closed_loop_states
        );
        for w in &report.written {
            outln!(out, "wrote {w}");
        }
    }
    Ok(Outcome::Holds)
}
