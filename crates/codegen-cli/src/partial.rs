//! `codegen normal`, `observable`, `supnorm` and `supconnorm`: partial
//! observation (`des::ops::partial`).
//!
//! The observable events are those `--observable` lists, or else every
//! event of the plant its files do not declare unobservable (TOML
//! `unobservable`, `.gen` `+o+`, `.wmod` `Observable="false"`); the
//! controllable ones are the plant's.

use super::error::CliError;
use super::output::{outln, Out};
use super::{load, output_name, Outcome, Role, Size};
use des::formats::{self, Component, Kind};
use des::ops::sync::DEFAULT_MAX_STATES;
use des::ops::{self, ComposeOptions, Composition};
use des::Automaton;
use std::path::PathBuf;

/// The plant, the observable events and the limit, shared by the verbs.
#[derive(Debug, clap::Args)]
pub struct Common {
    /// Plant component files; the plant is their synchronous composition.
    #[arg(long = "plant", required = true, num_args = 1..)]
    plants: Vec<PathBuf>,
    /// The observable events, comma-separated (`''` for none); default:
    /// every plant event its files do not declare unobservable.
    #[arg(long, value_delimiter = ',', value_name = "EVENTS")]
    observable: Option<Vec<String>>,
    /// Refuse a composition or subset construction beyond this many
    /// states.
    #[arg(long, default_value_t = DEFAULT_MAX_STATES)]
    max_states: usize,
}

/// Arguments of `codegen normal` and `codegen observable`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    #[command(flatten)]
    common: Common,
    /// The language K: a supervisor or specification file (its closed
    /// loop with the plant for `observable`).
    #[arg(long = "sup", required = true)]
    sup: PathBuf,
    /// `normal`: the closed (generated) languages instead of the marked
    /// ones.
    #[arg(long)]
    closed: bool,
}

/// Arguments of `codegen supnorm` and `codegen supconnorm`.
#[derive(Debug, clap::Args)]
pub struct SupArgs {
    #[command(flatten)]
    common: Common,
    /// Specification files, composed.
    #[arg(long = "spec", required = true, num_args = 1..)]
    specs: Vec<PathBuf>,
    /// The closed-language operation (`SupNormClosed`,
    /// `SupConNormClosed`).
    #[arg(long)]
    closed: bool,
    /// Output file; its extension picks the format.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Name of the result (default: the output file's stem).
    #[arg(long)]
    name: Option<String>,
}

fn compose(parts: &[Automaton], max_states: usize) -> Result<Automaton, CliError> {
    let refs: Vec<&Automaton> = parts.iter().collect();
    let options = ComposeOptions {
        name_states: false,
        max_states,
        ..ComposeOptions::default()
    };
    Ok(ops::compose(&refs, Composition::Sync, options)
        .map_err(CliError::max_states)?
        .automaton)
}

/// The plant and its observable and controllable events.
fn plant(common: &Common) -> Result<(Automaton, Vec<String>, Vec<String>), CliError> {
    let plant = compose(&load(&common.plants, Role::Plant)?, common.max_states)?;
    let alphabet = plant.alphabet();
    let observable = match &common.observable {
        Some(list) => list.iter().filter(|e| !e.is_empty()).cloned().collect(),
        None => alphabet
            .iter()
            .filter(|(_, e)| e.observable)
            .map(|(_, e)| e.name.clone())
            .collect(),
    };
    let controllable = alphabet
        .iter()
        .filter(|(_, e)| e.controllable)
        .map(|(_, e)| e.name.clone())
        .collect();
    Ok((plant, observable, controllable))
}

fn one(path: &PathBuf) -> Result<Automaton, CliError> {
    let mut sups = load(std::slice::from_ref(path), Role::Supervisor)?;
    if sups.len() != 1 {
        return Err(CliError::Usage(format!(
            "{}: holds {} supervisors or specifications; give a file with one",
            path.display(),
            sups.len()
        )));
    }
    Ok(sups.remove(0))
}

#[derive(Debug, serde::Serialize)]
struct NormalReport {
    observable: Vec<String>,
    language: &'static str,
    normal: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    violation: Option<ops::partial::NormalityViolation>,
    holds: bool,
}

/// `codegen normal`: is K normal with respect to the plant and the
/// projection onto the observable events?
pub fn normal(args: &CheckArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let (plant, observable, _) = plant(&args.common)?;
    let k = one(&args.sup)?;
    let max = args.common.max_states;
    let violation = if args.closed {
        ops::is_normal_closed(&plant, &k, &observable, max)
    } else {
        ops::is_normal(&plant, &k, &observable, max)
    }
    .map_err(CliError::max_states)?;
    let holds = violation.is_none();
    let report = NormalReport {
        observable,
        language: if args.closed { "closed" } else { "marked" },
        normal: holds,
        violation,
        holds,
    };
    if json {
        out.json(&report);
    } else {
        outln!(out, "observable: {}", report.observable.join(", "));
        match &report.violation {
            None => outln!(out, "normal ({} languages): yes", report.language),
            Some(ops::partial::NormalityViolation::NotInPlant { string }) => outln!(
                out,
                "normal ({} languages): no: `{}` is in K but not in the plant's language",
                report.language,
                string.join(" ")
            ),
            Some(ops::partial::NormalityViolation::LooksLike { string, look_alike }) => outln!(
                out,
                "normal ({} languages): no: `{}` is the plant's and not K's, yet it looks like `{}` of K",
                report.language,
                string.join(" "),
                look_alike.join(" ")
            ),
        }
    }
    Ok(if holds {
        Outcome::Holds
    } else {
        Outcome::Fails
    })
}

#[derive(Debug, serde::Serialize)]
struct ObservableReport {
    observable: Vec<String>,
    is_observable: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    violation: Option<ops::partial::ObservabilityViolation>,
    holds: bool,
}

/// `codegen observable`: is the closed loop's language observable
/// (Lin–Wonham) with respect to the plant?
pub fn observable(args: &CheckArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let (plant, observable, controllable) = plant(&args.common)?;
    let k = one(&args.sup)?;
    let violation = ops::check_observable(
        &plant,
        &k,
        &controllable,
        &observable,
        args.common.max_states,
    )
    .map_err(CliError::max_states)?;
    let holds = violation.is_none();
    let report = ObservableReport {
        observable,
        is_observable: holds,
        violation,
        holds,
    };
    if json {
        out.json(&report);
    } else {
        outln!(out, "observable events: {}", report.observable.join(", "));
        match &report.violation {
            None => outln!(out, "observable: yes"),
            Some(v) => outln!(
                out,
                "observable: no: after `{}` K allows `{}`, after `{}`, which looks the same, it forbids it",
                v.allowed_after.join(" "),
                v.event,
                v.forbidden_after.join(" ")
            ),
        }
    }
    Ok(if holds {
        Outcome::Holds
    } else {
        Outcome::Fails
    })
}

#[derive(Debug, serde::Serialize)]
struct SupReport {
    observable: Vec<String>,
    result: Size,
    empty: bool,
    output: String,
}

/// `codegen supnorm` (`controllable` false) and `codegen supconnorm`.
pub fn supremal(
    args: &SupArgs,
    controllable_too: bool,
    json: bool,
    out: &mut Out,
) -> Result<Outcome, CliError> {
    let (plant, observable, controllable) = plant(&args.common)?;
    let spec = compose(&load(&args.specs, Role::Spec)?, args.common.max_states)?;
    let max = args.common.max_states;
    let mut result = match (controllable_too, args.closed) {
        (false, false) => ops::sup_normal(&plant, &spec, &observable, max),
        (false, true) => ops::sup_normal_closed(&plant, &spec, &observable, max),
        (true, false) => ops::sup_con_normal(&plant, &spec, &controllable, &observable, max),
        (true, true) => ops::sup_con_normal_closed(&plant, &spec, &controllable, &observable, max),
    }
    .map_err(CliError::max_states)?;
    let fallback = if controllable_too {
        "supconnorm"
    } else {
        "supnorm"
    };
    result.set_name(output_name(&args.output, args.name.as_deref(), fallback));
    let report = SupReport {
        observable,
        result: Size::of(&result),
        empty: result.is_empty(),
        output: args.output.display().to_string(),
    };
    formats::write_file(
        &args.output,
        &[Component {
            kind: Kind::Supervisor,
            automaton: result,
        }],
    )?;
    if json {
        out.json(&report);
    } else {
        outln!(out, "observable: {}", report.observable.join(", "));
        outln!(
            out,
            "{}: {}{}",
            fallback,
            report.result,
            if report.empty { " (empty)" } else { "" }
        );
        outln!(out, "wrote {}", report.output);
    }
    Ok(Outcome::Holds)
}
