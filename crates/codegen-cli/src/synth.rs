//! `codegen synth`: supervisor synthesis from plants and specifications.

use super::error::CliError;
use super::output::{outln, Out};
use super::progress::Spinner;
use super::{load, output_name, Outcome, Role, Size};
use des::formats::{self, Component, Kind};
use des::ops::synthesis::Synthesis;
use des::ops::{self, ComposeOptions, SynthesisOptions};
use des::Automaton;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `codegen synth`.
#[derive(Debug, clap::Args)]
pub struct SynthArgs {
    /// Plant component files; the plant is their synchronous composition.
    #[arg(long = "plant", required = true, num_args = 1..)]
    pub(crate) plants: Vec<PathBuf>,
    /// Specification files; composed, then extended to the plant alphabet.
    /// Without any, the result is the plant's nonblocking supervisor.
    #[arg(long = "spec", num_args = 1..)]
    pub(crate) specs: Vec<PathBuf>,
    /// Minimise the supervisor's states (language preserved).
    #[arg(long, conflicts_with = "symbolic")]
    minstate: bool,
    /// Reduce the supervisor (supervisor reduction, control-consistent
    /// classes): a smaller one with the same closed loop, checked; before
    /// `--minstate` when both are given.
    #[arg(long, conflicts_with = "symbolic")]
    reduce: bool,
    /// Synthesise on BDDs without building the product of plants and
    /// specifications, and write one guard per controllable event to a
    /// guard file (`-o NAME.guards.toml`, docs/formats.md).
    #[arg(long)]
    symbolic: bool,
    /// Output file; its extension picks the format.
    #[arg(short = 'o', long = "output")]
    pub(crate) output: PathBuf,
    /// Name of the supervisor (default: the output file's stem).
    #[arg(long)]
    pub(crate) name: Option<String>,
    /// Number the states instead of naming them after plant and spec
    /// states. Names cost little memory (they are composed from the
    /// component states when the file is written), but writing them takes
    /// time on very large models.
    #[arg(long, conflicts_with = "symbolic")]
    no_state_names: bool,
    /// Refuse a composition beyond this many states (memory grows with
    /// them: on the benchmark families about 30 bytes per transition of
    /// the largest product, names included).
    #[arg(long, default_value_t = ops::sync::DEFAULT_MAX_STATES, conflicts_with = "symbolic")]
    max_states: usize,
}

#[derive(Debug, serde::Serialize)]
struct Report {
    plant: Size,
    spec: Option<Size>,
    supervisor: Size,
    empty: bool,
    minimised: Option<Size>,
    /// After supervisor reduction (before minstate).
    reduced: Option<Size>,
    /// The plant's unobservable events: `supervisor` is then supconnorm's
    /// result and `observed` its projection onto the other events.
    unobservable: Vec<String>,
    /// The projected supervisor (before minstate), under partial
    /// observation.
    observed: Option<Size>,
    /// The components the supervisor's state names are made of, in order
    /// (plants, then specifications): `0.1.2` is the state of the first
    /// component, then of the second, … `None` with `--no-state-names`.
    state_names: Option<Vec<String>>,
    output: String,
    milliseconds: Timings,
    /// Peak resident memory of this process (Linux only).
    peak_rss_kib: Option<u64>,
}

/// The process's peak resident set size, from `/proc/self/status`.
pub(crate) fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

#[derive(Debug, Default, serde::Serialize)]
struct Timings {
    load: f64,
    compose_plant: f64,
    compose_spec: f64,
    supcon: f64,
    minstate: f64,
    reduce: f64,
    observe: f64,
    write: f64,
    total: f64,
}

pub(crate) fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// The components whose states make up the supervisor's state names:
/// `supcon` names its states `plant.spec` after the two compositions,
/// which name theirs after their components (a lone automaton keeps its
/// own names; no specification is one state named `0`).
fn state_name_key(plants: &[Automaton], specs: &[Automaton]) -> Vec<String> {
    let mut key: Vec<String> = plants.iter().map(|a| a.name().to_owned()).collect();
    if specs.is_empty() {
        key.push("(no specification)".to_owned());
    }
    key.extend(specs.iter().map(|a| a.name().to_owned()));
    key
}

pub fn run(args: &SynthArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    if args.symbolic {
        return super::symbolic::run(args, json, out);
    }
    let start = Instant::now();
    let mut t = Timings::default();
    let spinner = Spinner::new("loading");
    let options = SynthesisOptions {
        compose: ComposeOptions {
            name_states: !args.no_state_names,
            max_states: args.max_states,
            progress: &spinner,
        },
        minstate: args.minstate,
        reduce: args.reduce,
    };

    let mark = Instant::now();
    let plants = load(&args.plants, Role::Plant)?;
    let specs = load(&args.specs, Role::Spec)?;
    t.load = ms(mark);
    let state_names = (!args.no_state_names).then(|| state_name_key(&plants, &specs));

    let Synthesis {
        plant,
        spec,
        supervisor: mut sup,
        supcon_size,
        reduced_size,
        unobservable,
        observed_size,
        timings,
    } = ops::synthesize(&plants, &specs, options).map_err(CliError::max_states)?;
    t.compose_plant = timings.compose_plant.as_secs_f64() * 1e3;
    t.compose_spec = timings.compose_spec.as_secs_f64() * 1e3;
    t.supcon = timings.supcon.as_secs_f64() * 1e3;
    t.minstate = timings.minstate.as_secs_f64() * 1e3;
    t.reduce = timings.reduce.as_secs_f64() * 1e3;
    t.observe = timings.observe.as_secs_f64() * 1e3;
    let supervisor = Size {
        states: supcon_size.states,
        transitions: supcon_size.transitions,
        ..Size::of(&sup)
    };
    let minimised = args.minstate.then(|| Size::of(&sup));
    let reduced = reduced_size.map(|r| Size {
        states: r.states,
        transitions: r.transitions,
        ..Size::of(&sup)
    });
    let observed = observed_size.map(|o| Size {
        states: o.states,
        transitions: o.transitions,
        ..Size::of(&sup)
    });

    sup.set_name(output_name(
        &args.output,
        args.name.as_deref(),
        "supervisor",
    ));
    spinner.phase("writing");
    let mark = Instant::now();
    // Written from the supervisor itself, not a copy of it.
    let written = [Component {
        kind: Kind::Supervisor,
        automaton: sup,
    }];
    formats::write_file(&args.output, &written)?;
    let [Component { automaton: sup, .. }] = written;
    t.write = ms(mark);
    t.total = ms(start);
    drop(spinner);

    let report = Report {
        plant: Size::of(&plant),
        spec: spec.as_ref().map(Size::of),
        supervisor,
        empty: sup.is_empty(),
        minimised,
        reduced,
        unobservable,
        observed,
        state_names,
        output: args.output.display().to_string(),
        milliseconds: t,
        peak_rss_kib: peak_rss_kib(),
    };
    if json {
        out.json(&report);
        return Ok(Outcome::Holds);
    }
    outln!(
        out,
        "plant:      {} ({:.1} ms)",
        report.plant,
        report.milliseconds.compose_plant
    );
    if let Some(s) = &report.spec {
        outln!(
            out,
            "spec:       {} ({:.1} ms)",
            s,
            report.milliseconds.compose_spec
        );
    }
    let partial = !report.unobservable.is_empty();
    outln!(
        out,
        "{} {} ({:.1} ms)",
        if partial {
            "supconnorm:"
        } else {
            "supervisor:"
        },
        report.supervisor,
        report.milliseconds.supcon
    );
    if let Some(o) = &report.observed {
        let unseen: Vec<String> = report
            .unobservable
            .iter()
            .map(|e| format!("`{e}`"))
            .collect();
        outln!(
            out,
            "observed:   {} ({:.1} ms, projected onto the observable events, {} unobservable; \
             closed loop and commands checked)",
            o,
            report.milliseconds.observe,
            unseen.join(", ")
        );
    }
    if let Some(r) = &report.reduced {
        outln!(
            out,
            "reduced:    {} ({:.1} ms, closed loop checked equal)",
            r,
            report.milliseconds.reduce
        );
    }
    if let Some(m) = &report.minimised {
        outln!(
            out,
            "minstate:   {} ({:.1} ms)",
            m,
            report.milliseconds.minstate
        );
    }
    if let (Some(key), true, false) = (&report.state_names, partial, report.empty) {
        outln!(
            out,
            "states:     named {{{},…}}: the states a string the controller sees may lead to",
            key.join(".")
        );
    } else if let (Some(key), false) = (&report.state_names, report.empty) {
        outln!(
            out,
            "states:     named {}{}",
            key.join("."),
            if args.minstate {
                " (a merged state: {…,…} of such names)"
            } else {
                ""
            }
        );
    }
    if report.empty {
        outln!(
            out,
            "the supervisor is EMPTY: no controllable, nonblocking behaviour of the plant \
             meets the specification (written anyway, an automaton with no states)"
        );
    }
    outln!(
        out,
        "wrote {} ({:.1} ms total)",
        report.output,
        report.milliseconds.total
    );
    Ok(Outcome::Holds)
}
