//! `codegen include`, `equal`, `compose` and `project`: language operations
//! on model files, every failed check with a shortest counterexample.
//!
//! A file holding several automata (a Waters module) gives the one
//! `--component` names; `compose` takes every automaton of its files, or
//! with `--component` the named ones of files holding several.

use super::check::path;
use super::error::CliError;
use super::output::{outln, Out};
use super::{load_components, output_name, Outcome, Size};
use des::formats::{self, Component, Kind};
use des::ops::sync::DEFAULT_MAX_STATES;
use des::ops::ObserverWitness;
use des::ops::{self, ComposeOptions, Composition, LanguageDifference, LanguageKind};
use des::Automaton;
use std::path::PathBuf;

/// Arguments of `codegen include` and `codegen equal`.
#[derive(Debug, clap::Args)]
pub struct PairArgs {
    /// The first model file (A).
    first: PathBuf,
    /// The second model file (B).
    second: PathBuf,
    /// The component to use of a file holding several: given once, for
    /// both files; twice, for A and B in turn.
    #[arg(long, value_name = "NAME")]
    component: Vec<String>,
}

/// Arguments of `codegen compose`.
#[derive(Debug, clap::Args)]
pub struct ComposeArgs {
    /// Model files; every automaton in them is a component.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Output file; its extension picks the format.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Of a file holding several automata, only these (repeatable).
    #[arg(long, value_name = "NAME")]
    component: Vec<String>,
    /// Name of the composition (default: the output file's stem).
    #[arg(long)]
    name: Option<String>,
    /// Refuse a composition beyond this many states.
    #[arg(long, default_value_t = DEFAULT_MAX_STATES)]
    max_states: usize,
}

/// Arguments of `codegen project`.
#[derive(Debug, clap::Args)]
pub struct ProjectArgs {
    /// The model file.
    file: PathBuf,
    /// The events to keep, comma-separated (`''` for none); the others
    /// are erased.
    #[arg(long, required = true, value_delimiter = ',', value_name = "EVENTS")]
    keep: Vec<String>,
    /// Output file; its extension picks the format.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Only this component (for files holding several).
    #[arg(long)]
    component: Option<String>,
    /// Name of the projection (default: the output file's stem).
    #[arg(long)]
    name: Option<String>,
    /// Also check that the projection is an Lm- and an L-observer (exit 1
    /// with a shortest counterexample when not).
    #[arg(long)]
    observer: bool,
    /// Refuse a projection (or an observer check) beyond this many states.
    #[arg(long, default_value_t = DEFAULT_MAX_STATES)]
    max_states: usize,
}

/// One automaton named on the command line.
#[derive(Debug, serde::Serialize)]
struct Side {
    file: String,
    name: String,
    #[serde(flatten)]
    size: Size,
}

/// A string in one language and not in another.
#[derive(Debug, serde::Serialize)]
pub(crate) struct Counterexample {
    /// The string.
    pub string: Vec<String>,
    /// `closed` or `marked`.
    pub language: LanguageKind,
    /// Which side has it (`equal`, `check --spec`); A for `include`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub r#in: Option<&'static str>,
}

impl Counterexample {
    /// `d`, its string said to be in `first` or `second`.
    pub(crate) fn of(d: LanguageDifference, first: &'static str, second: &'static str) -> Self {
        Counterexample {
            string: d.string,
            language: d.language,
            r#in: Some(if d.in_first { first } else { second }),
        }
    }

    /// `L` or `Lm`.
    pub(crate) fn letter(&self) -> &'static str {
        match self.language {
            LanguageKind::Closed => "L",
            LanguageKind::Marked => "Lm",
        }
    }
}

/// The one automaton of `path` that `component` names (or its only one).
fn load_one(path: &std::path::Path, component: Option<&str>) -> Result<Component, CliError> {
    let mut components = load_components(path, component)?;
    if components.len() != 1 {
        let names: Vec<&str> = components.iter().map(|c| c.automaton.name()).collect();
        return Err(CliError::Usage(format!(
            "{}: holds {} automata ({}): choose one with --component NAME",
            path.display(),
            names.len(),
            names.join(", ")
        )));
    }
    Ok(components.remove(0))
}

/// A and B, each with the component chosen for it.
fn load_pair(args: &PairArgs) -> Result<(Side, Automaton, Side, Automaton), CliError> {
    let names: [Option<&str>; 2] = match args.component.as_slice() {
        [] => [None, None],
        [both] => [Some(both), Some(both)],
        [a, b] => [Some(a), Some(b)],
        more => {
            return Err(CliError::Usage(format!(
                "--component given {} times: once names the component of both files, \
                 twice those of A and B",
                more.len()
            )))
        }
    };
    let a = load_one(&args.first, names[0])?.automaton;
    let b = load_one(&args.second, names[1])?.automaton;
    let side = |file: &PathBuf, x: &Automaton| Side {
        file: file.display().to_string(),
        name: x.name().to_owned(),
        size: Size::of(x),
    };
    Ok((side(&args.first, &a), a, side(&args.second, &b), b))
}

/// How A and B are called in text: their names, or with their files
/// when the names are the same.
fn labels(a: &Side, b: &Side) -> (String, String) {
    if a.name == b.name {
        (
            format!("{} ({})", a.name, a.file),
            format!("{} ({})", b.name, b.file),
        )
    } else {
        (a.name.clone(), b.name.clone())
    }
}

#[derive(Debug, serde::Serialize)]
struct InclusionReport {
    first: Side,
    second: Side,
    included: bool,
    /// A shortest string of A's closed or marked language that B's lacks.
    #[serde(skip_serializing_if = "Option::is_none")]
    counterexample: Option<Counterexample>,
    holds: bool,
}

/// `codegen include A B`: L(A) ⊆ L(B) and Lm(A) ⊆ Lm(B).
pub fn include(args: &PairArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let (first, a, second, b) = load_pair(args)?;
    let counterexample = ops::inclusion_counterexample(&a, &b).map(|d| Counterexample {
        string: d.string,
        language: d.language,
        r#in: None,
    });
    let holds = counterexample.is_none();
    let report = InclusionReport {
        first,
        second,
        included: holds,
        counterexample,
        holds,
    };
    if json {
        out.json(&report);
    } else {
        let (la, lb) = labels(&report.first, &report.second);
        match &report.counterexample {
            None => outln!(out, "{la} ⊆ {lb}: yes (closed and marked languages)"),
            Some(c) => outln!(
                out,
                "{la} ⊆ {lb}: NO: {} is in {l}({la}) but not in {l}({lb})",
                path(&c.string),
                l = c.letter()
            ),
        }
    }
    Ok(outcome(holds))
}

#[derive(Debug, serde::Serialize)]
struct EqualityReport {
    first: Side,
    second: Side,
    equal: bool,
    /// A shortest string in one language and not the other, and which
    /// side (`first`, `second`) has it.
    #[serde(skip_serializing_if = "Option::is_none")]
    difference: Option<Counterexample>,
    holds: bool,
}

/// `codegen equal A B`: the same closed and marked languages.
pub fn equal(args: &PairArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let (first, a, second, b) = load_pair(args)?;
    let difference =
        ops::language_difference(&a, &b).map(|d| Counterexample::of(d, "first", "second"));
    let holds = difference.is_none();
    let report = EqualityReport {
        first,
        second,
        equal: holds,
        difference,
        holds,
    };
    if json {
        out.json(&report);
    } else {
        let (la, lb) = labels(&report.first, &report.second);
        match &report.difference {
            None => outln!(out, "{la} = {lb}: yes (closed and marked languages)"),
            Some(d) => {
                let (has, lacks) = if d.r#in == Some("first") {
                    (&la, &lb)
                } else {
                    (&lb, &la)
                };
                outln!(
                    out,
                    "{la} = {lb}: NO: {} is in {l}({has}) but not in {l}({lacks})",
                    path(&d.string),
                    l = d.letter()
                );
            }
        }
    }
    Ok(outcome(holds))
}

fn outcome(holds: bool) -> Outcome {
    if holds {
        Outcome::Holds
    } else {
        Outcome::Fails
    }
}

/// Writes `a` to `output` as one component of `kind`.
fn write(output: &std::path::Path, kind: Kind, a: Automaton) -> Result<Automaton, CliError> {
    let written = [Component { kind, automaton: a }];
    formats::write_file(output, &written)?;
    let [Component { automaton, .. }] = written;
    Ok(automaton)
}

#[derive(Debug, serde::Serialize)]
struct CompositionReport {
    components: Vec<String>,
    result: Size,
    /// `a.b.c` is the state of the first component, then of the second, …
    state_names: Vec<String>,
    output: String,
}

/// `codegen compose F… -o OUT`: the synchronous composition.
pub fn compose(args: &ComposeArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let mut components: Vec<Component> = Vec::new();
    for file in &args.files {
        let mut found = formats::read_file(file)?;
        if found.len() > 1 && !args.component.is_empty() {
            found.retain(|c| args.component.iter().any(|n| n == c.automaton.name()));
        }
        components.extend(found);
    }
    for name in &args.component {
        if !components.iter().any(|c| c.automaton.name() == name) {
            return Err(CliError::Usage(format!(
                "no component `{name}` in a file holding several"
            )));
        }
    }
    let refs: Vec<&Automaton> = components.iter().map(|c| &c.automaton).collect();
    let options = ComposeOptions {
        max_states: args.max_states,
        ..ComposeOptions::default()
    };
    let mut result = ops::compose(&refs, Composition::Sync, options)
        .map_err(CliError::max_states)?
        .automaton;
    result.set_name(output_name(
        &args.output,
        args.name.as_deref(),
        "composition",
    ));
    let kind = match components.first() {
        Some(c) if components.iter().all(|d| d.kind == c.kind) => c.kind,
        _ => Kind::Unspecified,
    };
    let result = write(&args.output, kind, result)?;
    let names: Vec<String> = refs.iter().map(|a| a.name().to_owned()).collect();
    let report = CompositionReport {
        components: names.clone(),
        result: Size::of(&result),
        state_names: names,
        output: args.output.display().to_string(),
    };
    if json {
        out.json(&report);
    } else {
        outln!(out, "composed:   {}", report.components.join(", "));
        outln!(out, "result:     {}", report.result);
        outln!(out, "states:     named {}", report.state_names.join("."));
        outln!(out, "wrote {}", report.output);
    }
    Ok(Outcome::Holds)
}

/// One observer property: whether it holds, and why not.
#[derive(Debug, serde::Serialize)]
struct ObserverCheck {
    holds: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    witness: Option<ObserverWitness>,
}

impl ObserverCheck {
    fn of(witness: Option<ObserverWitness>) -> Self {
        ObserverCheck {
            holds: witness.is_none(),
            witness,
        }
    }
}

#[derive(Debug, serde::Serialize)]
struct Observer {
    /// The Lm(G)-observer property (Wong–Wonham).
    marked: ObserverCheck,
    /// The L(G)-observer property.
    closed: ObserverCheck,
}

#[derive(Debug, serde::Serialize)]
struct ProjectionReport {
    input: Side,
    keep: Vec<String>,
    projection: Size,
    output: String,
    /// With `--observer` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    observer: Option<Observer>,
    holds: bool,
}

/// `codegen project F --keep … -o OUT [--observer]`.
pub fn project(args: &ProjectArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let Component { kind, automaton: a } = load_one(&args.file, args.component.as_deref())?;
    let keep: Vec<&str> = args
        .keep
        .iter()
        .map(String::as_str)
        .filter(|e| !e.is_empty())
        .collect();
    let mut projection = ops::project(&a, &keep, args.max_states).map_err(CliError::max_states)?;
    projection.set_name(output_name(
        &args.output,
        args.name.as_deref(),
        "projection",
    ));
    let projection = write(&args.output, kind, projection)?;
    let observer = if args.observer {
        let check = |language| {
            ops::check_observer(&a, &keep, language, args.max_states)
                .map(ObserverCheck::of)
                .map_err(CliError::max_states)
        };
        Some(Observer {
            marked: check(LanguageKind::Marked)?,
            closed: check(LanguageKind::Closed)?,
        })
    } else {
        None
    };
    let holds = observer
        .as_ref()
        .is_none_or(|o| o.marked.holds && o.closed.holds);
    let report = ProjectionReport {
        input: Side {
            file: args.file.display().to_string(),
            name: a.name().to_owned(),
            size: Size::of(&a),
        },
        keep: projection
            .alphabet()
            .iter()
            .map(|(_, e)| e.name.clone())
            .collect(),
        projection: Size::of(&projection),
        output: args.output.display().to_string(),
        observer,
        holds,
    };
    if json {
        out.json(&report);
    } else {
        print_projection(out, &report);
    }
    Ok(outcome(holds))
}

fn print_projection(out: &mut Out, report: &ProjectionReport) {
    let name = &report.input.name;
    outln!(out, "input:       {name}: {}", report.input.size);
    outln!(
        out,
        "projection:  onto {}: {}",
        if report.keep.is_empty() {
            "no events".to_owned()
        } else {
            report.keep.join(", ")
        },
        report.projection
    );
    if let Some(o) = &report.observer {
        for (label, check, promise, reach) in [
            (
                "Lm-observer:",
                &o.marked,
                "to a marked state",
                "reach a marked state along it",
            ),
            ("L-observer: ", &o.closed, "next", "follow it"),
        ] {
            match &check.witness {
                None => outln!(out, "{label} yes"),
                // Only the marked property fails with nothing to add: G
                // itself is somewhere after `s`.
                Some(w) if w.continuation.is_empty() => outln!(
                    out,
                    "{label} NO: after {} (seen as {}), the projection is marked, but {name} \
                     (in state {}) cannot reach a marked state by erased events alone",
                    path(&w.string),
                    path(&w.projected),
                    w.state
                ),
                Some(w) => outln!(
                    out,
                    "{label} NO: after {} (seen as {}), the projection promises {} {promise}, \
                     but {name} (in state {}) cannot {reach}",
                    path(&w.string),
                    path(&w.projected),
                    path(&w.continuation),
                    w.state
                ),
            }
        }
    }
    outln!(out, "wrote {}", report.output);
}
