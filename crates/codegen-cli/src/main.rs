//! The `codegen` command: synthesis, checks and conversions on automata,
//! and PLC projects as Rust, Structured Text and PLCopen XML. Argument
//! parsing, model loading and output.
//!
//! Exit codes: 0 = done and every checked property holds; 1 = a checked
//! property fails; 2 = bad input or usage. A closed standard output (`|
//! head`) ends the output quietly and keeps the exit code (see [`output`]).

mod check;
mod condat;
mod convert;
mod dot;
mod error;
mod gen;
mod image;
mod info;
mod key;
mod lang;
mod load;
mod net_control;
mod output;
mod partial;
mod petri;
mod plc;
mod progress;
mod reduce;
mod symbolic;
mod synth;
mod verify;
mod wiring;

use clap::{Parser, Subcommand};
use des::formats::{self, Component, Kind};
use des::Automaton;
use error::CliError;
use output::{warn, Out};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Supervisor synthesis and checks for discrete-event models.
///
/// Model files: native `.toml`, libFAUDES `.gen`, TCT `.ads`, Supremica
/// `.wmod` (chosen by extension).
#[derive(Debug, Parser)]
#[command(name = "codegen", version, about)]
pub struct Cli {
    /// Print machine-readable JSON on stdout instead of text.
    #[arg(long, global = true)]
    json: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Sizes and properties of every automaton in the files.
    Info {
        /// Model files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// Synthesise a supervisor: supcon(sync(plants), sync(specs)).
    Synth(synth::SynthArgs),
    /// Check supervisors against a plant: controllable, nonblocking,
    /// and (for several) nonconflicting; with `--spec`, also whether the
    /// closed loop stays within the specification and is supcon's.
    Check {
        /// Plant component files (their synchronous composition is the plant).
        #[arg(long = "plant", required = true, num_args = 1..)]
        plants: Vec<PathBuf>,
        /// Supervisor files.
        #[arg(long = "sup", required = true, num_args = 1..)]
        sups: Vec<PathBuf>,
        /// Specification files (composed, extended to the plant alphabet,
        /// as `synth` does): the closed loop of the plant with every
        /// supervisor must stay within plant ‖ specification and have
        /// supcon's languages.
        #[arg(long = "spec", num_args = 1..)]
        specs: Vec<PathBuf>,
    },
    /// Language inclusion: L(A) ⊆ L(B) and Lm(A) ⊆ Lm(B), else a shortest
    /// string of A that B lacks.
    Include(lang::PairArgs),
    /// Language equality of A and B, else a shortest string in one and
    /// not the other.
    Equal(lang::PairArgs),
    /// Synchronous composition of the automata in the files.
    Compose(lang::ComposeArgs),
    /// Natural projection onto the events kept; with `--observer`, the
    /// observer properties with a shortest counterexample.
    Project(lang::ProjectArgs),
    /// Normality of K (`--sup`) with respect to the plant and the
    /// projection onto the observable events, else a shortest string of
    /// the plant outside K that looks like one of K.
    Normal(partial::CheckArgs),
    /// Observability (Lin–Wonham) of K (`--sup`) with respect to the
    /// plant, else two strings that look alike after which K allows and
    /// forbids one controllable event.
    Observable(partial::CheckArgs),
    /// The supremal normal sublanguage of the specification (libFAUDES
    /// `SupNorm`, `--closed`: `SupNormClosed`).
    Supnorm(partial::SupArgs),
    /// The supremal controllable and normal sublanguage (libFAUDES
    /// `SupConNorm`, `--closed`: `SupConNormClosed`).
    Supconnorm(partial::SupArgs),
    /// Supervisor reduction: a smaller supervisor with the same closed
    /// loop with the plant (checked), to run beside the plant components.
    Reduce(reduce::ReduceArgs),
    /// Supervisor localization: one local controller per controllable
    /// event, together with the plant the same closed loop (checked).
    Localize(reduce::LocalizeArgs),
    /// Modular controllability: each supervisor decided on its reduced
    /// plant (the plant components sharing events with it), the whole
    /// plant never composed; a shortest counterexample when one fails.
    Verify(verify::VerifyArgs),
    /// Control data: the controllable events each supervisor state disables.
    Condat {
        /// Plant component files.
        #[arg(long = "plant", required = true, num_args = 1..)]
        plants: Vec<PathBuf>,
        /// The supervisor file.
        #[arg(long = "sup", required = true)]
        sup: PathBuf,
    },
    /// Convert between formats (by extension), keeping each component's
    /// kind.
    Convert(convert::ConvertArgs),
    /// Rust source of a PLC project (what the build script writes), or
    /// its sizes with `--stats`.
    Gen(gen::GenArgs),
    /// The board wiring of a PLC project (its `[board]` section) as a
    /// Markdown table: signal, direction, pin, pull, active level, notes.
    Wiring {
        /// The project file (`*.plc.toml`).
        project: PathBuf,
    },
    /// Graphviz drawing of an automaton or a Petri net: DOT text on
    /// stdout or in files.
    Dot(dot::DotArgs),
    /// Place/transition Petri nets (`.pnml`, `.toml`): properties,
    /// reachability graph, conversion.
    #[command(subcommand)]
    Petri(petri::PetriCommand),
    /// A project as an IEC 61131-3 Structured Text function block and
    /// program (`.st`) for industrial PLCs.
    St(plc::PlcArgs),
    /// A project as PLCopen XML (TC6 v2.01) with ST bodies, for PLC tools
    /// that import it.
    Plcopen(plc::PlcArgs),
    /// A project's program image (table backend) as a slot file for a
    /// field update: what `codegen load` sends (docs/field-update.md).
    Image(image::ImageArgs),
    /// A slot file (`codegen image`) into a running PLC over a serial
    /// port, checked by the PLC before it runs; without a file, what the
    /// PLC runs (docs/field-update.md).
    Load(load::LoadArgs),
}

/// How a command ended when it did not fail outright.
pub enum Outcome {
    /// Everything holds.
    Holds,
    /// A checked property fails (exit code 1).
    Fails,
}

/// Parses the arguments, runs the command, prints its output and errors
/// (exit codes above).
fn main() -> ExitCode {
    let cli = Cli::parse();
    let json = cli.json;
    let mut out = Out::default();
    let result = match cli.command {
        Command::Info { files } => info::run(&files, json, &mut out),
        Command::Synth(args) => synth::run(&args, json, &mut out),
        Command::Check {
            plants,
            sups,
            specs,
        } => check::run(&plants, &sups, &specs, json, &mut out),
        Command::Include(args) => lang::include(&args, json, &mut out),
        Command::Equal(args) => lang::equal(&args, json, &mut out),
        Command::Compose(args) => lang::compose(&args, json, &mut out),
        Command::Project(args) => lang::project(&args, json, &mut out),
        Command::Normal(args) => partial::normal(&args, json, &mut out),
        Command::Observable(args) => partial::observable(&args, json, &mut out),
        Command::Supnorm(args) => partial::supremal(&args, false, json, &mut out),
        Command::Supconnorm(args) => partial::supremal(&args, true, json, &mut out),
        Command::Reduce(args) => reduce::reduce(&args, json, &mut out),
        Command::Localize(args) => reduce::localize(&args, json, &mut out),
        Command::Verify(args) => verify::run(&args, json, &mut out),
        Command::Condat { plants, sup } => condat::run(&plants, &sup, json, &mut out),
        Command::Convert(args) => convert::run(&args, json, &mut out),
        Command::Gen(args) => gen::run(&args, json, &mut out),
        Command::Dot(args) => dot::run(&args, json, &mut out),
        Command::Wiring { project } => wiring::run(&project, json, &mut out),
        Command::Petri(command) => petri::run(&command, json, &mut out),
        Command::St(args) => plc::run(&args, plc::Flavour::St, json, &mut out),
        Command::Plcopen(args) => plc::run(&args, plc::Flavour::PlcOpen, json, &mut out),
        Command::Image(args) => image::run(&args, json, &mut out),
        Command::Load(args) => load::run(&args, json, &mut out),
    };
    let code = match &result {
        Ok(Outcome::Holds) => ExitCode::SUCCESS,
        Ok(Outcome::Fails) => ExitCode::from(1),
        Err(e) => {
            out.clear();
            if json {
                out.json(&serde_json::json!({ "error": e.to_string() }));
            }
            warn(format_args!("error: {e}"));
            ExitCode::from(2)
        }
    };
    if let Err(e) = out.flush_to_stdout() {
        warn(format_args!("error: writing standard output: {e}"));
        return ExitCode::from(2);
    }
    code
}

/// The role a file plays on the command line; for files that hold several
/// components (Waters modules) it selects the components of that kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// `--plant`
    Plant,
    /// `--spec`
    Spec,
    /// `--sup`
    Supervisor,
}

impl Role {
    fn accepts(self, kind: Kind) -> bool {
        match self {
            Role::Plant => kind == Kind::Plant,
            Role::Spec => matches!(kind, Kind::Spec | Kind::Property),
            Role::Supervisor => matches!(kind, Kind::Supervisor | Kind::Spec),
        }
    }
}

/// Loads the automata of `paths` that play `role`: every automaton of a
/// single-automaton file, the components of matching kind of a module.
pub fn load(paths: &[PathBuf], role: Role) -> Result<Vec<Automaton>, CliError> {
    let mut out = Vec::new();
    for path in paths {
        let components = formats::read_file(path)?;
        if components.len() == 1 {
            out.push(components.into_iter().next().expect("one").automaton);
            continue;
        }
        let before = out.len();
        let kinds: Vec<String> = components
            .iter()
            .map(|c| format!("{} `{}`", c.kind, c.automaton.name()))
            .collect();
        out.extend(
            components
                .into_iter()
                .filter(|c| role.accepts(c.kind))
                .map(|c| c.automaton),
        );
        if out.len() == before {
            return Err(CliError::Usage(format!(
                "{}: no component to use as {role:?} (the file has: {})",
                path.display(),
                if kinds.is_empty() {
                    "nothing".to_owned()
                } else {
                    kinds.join(", ")
                }
            )));
        }
    }
    Ok(out)
}

/// Reads `path` and keeps the component called `name`, or all.
pub fn load_components(path: &Path, name: Option<&str>) -> Result<Vec<Component>, CliError> {
    let components = formats::read_file(path)?;
    let Some(name) = name else {
        return Ok(components);
    };
    let names: Vec<String> = components
        .iter()
        .map(|c| c.automaton.name().to_owned())
        .collect();
    let chosen: Vec<Component> = components
        .into_iter()
        .filter(|c| c.automaton.name() == name)
        .collect();
    if chosen.is_empty() {
        return Err(CliError::Usage(format!(
            "{}: no component `{name}` (components: {})",
            path.display(),
            names.join(", ")
        )));
    }
    Ok(chosen)
}

/// The name of an automaton written to `output`: `name` if given, else
/// the file's stem, else `fallback`.
pub fn output_name(output: &Path, name: Option<&str>, fallback: &str) -> String {
    name.map(str::to_owned).unwrap_or_else(|| {
        output
            .file_stem()
            .map_or_else(|| fallback.to_owned(), |s| s.to_string_lossy().into_owned())
    })
}

/// `states/transitions` plus event counts, for reports.
#[derive(Debug, serde::Serialize)]
pub struct Size {
    pub states: usize,
    pub transitions: usize,
    pub events: usize,
    pub controllable: usize,
    /// The file says which events are controllable (a plain libFAUDES
    /// generator may not; its events then take the controllability of the
    /// automata they meet).
    pub controllability_stated: bool,
}

impl Size {
    /// The size of `a`.
    pub fn of(a: &Automaton) -> Size {
        Size {
            states: a.num_states(),
            transitions: a.num_transitions(),
            events: a.alphabet().len(),
            controllable: a.alphabet().controllable_count(),
            controllability_stated: a.alphabet().controllability_stated(),
        }
    }
}

impl std::fmt::Display for Size {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} states, {} transitions, {} events",
            self.states, self.transitions, self.events
        )?;
        if self.controllability_stated || self.controllable > 0 {
            write!(f, " ({} controllable)", self.controllable)
        } else {
            f.write_str(" (controllability not stated)")
        }
    }
}
