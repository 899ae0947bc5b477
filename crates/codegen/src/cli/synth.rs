//! `codegen synth`: supervisor synthesis from plants and specifications.

use super::progress::Spinner;
use super::{load, print_json, Outcome, Role, Size};
use codegen::formats::{self, Component, Kind};
use codegen::ops::synthesis::Synthesis;
use codegen::ops::{self, ComposeOptions, SynthesisOptions};
use codegen::Error;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `codegen synth`.
#[derive(Debug, clap::Args)]
pub struct SynthArgs {
    /// Plant component files; the plant is their synchronous composition.
    #[arg(long = "plant", required = true, num_args = 1..)]
    plants: Vec<PathBuf>,
    /// Specification files; composed, then extended to the plant alphabet.
    /// Without any, the result is the plant's nonblocking supervisor.
    #[arg(long = "spec", num_args = 1..)]
    specs: Vec<PathBuf>,
    /// Minimise the supervisor's states (language preserved).
    #[arg(long)]
    minstate: bool,
    /// Output file; its extension picks the format.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Name of the supervisor (default: the output file's stem).
    #[arg(long)]
    name: Option<String>,
    /// Number the states instead of naming them after plant and spec
    /// states (saves memory on very large models).
    #[arg(long)]
    no_state_names: bool,
}

#[derive(Debug, serde::Serialize)]
struct Report {
    plant: Size,
    spec: Option<Size>,
    supervisor: Size,
    empty: bool,
    minimised: Option<Size>,
    output: String,
    milliseconds: Timings,
    /// Peak resident memory of this process (Linux only).
    peak_rss_kib: Option<u64>,
}

/// The process's peak resident set size, from `/proc/self/status`.
fn peak_rss_kib() -> Option<u64> {
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
    write: f64,
    total: f64,
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

pub fn run(args: &SynthArgs, json: bool) -> Result<Outcome, Error> {
    let start = Instant::now();
    let mut t = Timings::default();
    let spinner = Spinner::new("loading");
    let options = SynthesisOptions {
        compose: ComposeOptions {
            name_states: !args.no_state_names,
            progress: &spinner,
            ..ComposeOptions::default()
        },
        minstate: args.minstate,
    };

    let mark = Instant::now();
    let plants = load(&args.plants, Role::Plant)?;
    let specs = load(&args.specs, Role::Spec)?;
    t.load = ms(mark);

    let Synthesis {
        plant,
        spec,
        supervisor: mut sup,
        supcon_size,
        timings,
    } = ops::synthesize(&plants, &specs, options)?;
    t.compose_plant = timings.compose_plant.as_secs_f64() * 1e3;
    t.compose_spec = timings.compose_spec.as_secs_f64() * 1e3;
    t.supcon = timings.supcon.as_secs_f64() * 1e3;
    t.minstate = timings.minstate.as_secs_f64() * 1e3;
    let supervisor = Size {
        states: supcon_size.states,
        transitions: supcon_size.transitions,
        ..Size::of(&sup)
    };
    let minimised = args.minstate.then(|| Size::of(&sup));

    let name = args.name.clone().unwrap_or_else(|| {
        args.output.file_stem().map_or_else(
            || "supervisor".to_owned(),
            |s| s.to_string_lossy().into_owned(),
        )
    });
    sup.set_name(name);
    spinner.phase("writing");
    let mark = Instant::now();
    formats::write_file(
        &args.output,
        &[Component {
            kind: Kind::Supervisor,
            automaton: sup.clone(),
        }],
    )?;
    t.write = ms(mark);
    t.total = ms(start);
    drop(spinner);

    let report = Report {
        plant: Size::of(&plant),
        spec: spec.as_ref().map(Size::of),
        supervisor,
        empty: sup.is_empty(),
        minimised,
        output: args.output.display().to_string(),
        milliseconds: t,
        peak_rss_kib: peak_rss_kib(),
    };
    if json {
        print_json(&report);
        return Ok(Outcome::Holds);
    }
    println!(
        "plant:      {} ({:.1} ms)",
        report.plant, report.milliseconds.compose_plant
    );
    if let Some(s) = &report.spec {
        println!(
            "spec:       {} ({:.1} ms)",
            s, report.milliseconds.compose_spec
        );
    }
    println!(
        "supervisor: {} ({:.1} ms)",
        report.supervisor, report.milliseconds.supcon
    );
    if let Some(m) = &report.minimised {
        println!("minstate:   {} ({:.1} ms)", m, report.milliseconds.minstate);
    }
    if report.empty {
        println!(
            "the supervisor is EMPTY: no controllable, nonblocking behaviour of the plant \
             meets the specification (written anyway, an automaton with no states)"
        );
    }
    println!(
        "wrote {} ({:.1} ms total)",
        report.output, report.milliseconds.total
    );
    Ok(Outcome::Holds)
}
