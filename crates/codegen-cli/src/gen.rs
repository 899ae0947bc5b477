//! `codegen gen`: the generated Rust source of a project, for humans.

use super::error::CliError;
use super::output::{outln, Out};
use super::progress::load_project;
use super::Outcome;
use codegen::backend::table::EncodedTable;
use codegen::backend::Backend;
use codegen::emit::{generate_with_progress, SupervisorStats};
use codegen::lower::ImageCheck;
use des::formats;
use des::Error;
use std::path::{Path, PathBuf};

/// Arguments of `codegen gen`.
#[derive(Debug, clap::Args)]
pub struct GenArgs {
    /// The project file (`*.plc.toml`); with `--stats` also any automaton
    /// file, each of its automata measured as one supervisor over its own
    /// alphabet.
    project: PathBuf,
    /// How supervisors are represented.
    #[arg(long, value_enum, default_value_t = BackendArg::Table)]
    backend: BackendArg,
    /// Print sizes per supervisor (table bytes next to a naive encoding)
    /// instead of the code.
    #[arg(long)]
    stats: bool,
    /// Write the code to this file instead of stdout.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, clap::ValueEnum)]
enum BackendArg {
    Table,
    Logic,
    /// Baseline: plain `match` statements (for measurements).
    Match,
}

/// `true` for a PLC project file name (`*.plc.toml`).
fn is_project(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.ends_with(".plc.toml"))
}

pub fn run(args: &GenArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    if !is_project(&args.project) {
        return automaton_stats(args, json, out);
    }
    let (project, spinner) = load_project(&args.project)?;
    let (backend, name) = match args.backend {
        BackendArg::Table => (Backend::Table, "table"),
        BackendArg::Logic => (Backend::Logic, "logic"),
        BackendArg::Match => (Backend::Match, "match"),
    };
    let regenerate = format!("codegen gen {} --backend {name}", args.project.display());
    spinner.phase("generating");
    let generated = generate_with_progress(&project, backend, &regenerate, &spinner)?;
    drop(spinner);
    if args.stats {
        if json {
            out.json(&generated.stats);
            return Ok(Outcome::Holds);
        }
        print_stats(out, &args.project, &generated.stats, backend);
        print_image_check(out, &generated.image);
        print_scan_sets(out, &generated.sets);
        return Ok(Outcome::Holds);
    }
    match &args.output {
        Some(path) => write(path, &generated.code)?,
        None => out.push_str(&generated.code),
    }
    Ok(Outcome::Holds)
}

/// `--stats` of a plain automaton file: the table each automaton would
/// get as a supervisor of a project.
fn automaton_stats(args: &GenArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    if !args.stats || !matches!(args.backend, BackendArg::Table) {
        return Err(CliError::Usage(format!(
            "{}: not a project file (`*.plc.toml`); automaton files only take `--stats` with the table backend",
            args.project.display()
        )));
    }
    let stats: Vec<SupervisorStats> = formats::read_file(&args.project)?
        .iter()
        .map(|c| {
            let a = &c.automaton;
            let local: Vec<_> = a.alphabet().ids().collect();
            SupervisorStats::of_table(a.name(), &EncodedTable::encode(a, &local))
        })
        .collect();
    if json {
        out.json(&stats);
    } else {
        print_stats(out, &args.project, &stats, Backend::Table);
    }
    Ok(Outcome::Holds)
}

fn write(path: &Path, code: &str) -> Result<(), Error> {
    std::fs::write(path, code).map_err(|e| Error::io(path, e))
}

/// The image's size and how fast the background test covers it.
fn print_image_check(out: &mut Out, check: &ImageCheck) {
    outln!(
        out,
        "  image: {} bytes under the CRC; background check {} bytes per scan: a pass every {} scans, a flipped bit found within {} scans ({} ms at {} ms a scan)",
        check.image_bytes,
        check.bytes_per_scan,
        check.pass_scans(),
        check.bound_scans(),
        check.bound_ms(),
        check.scan_period_ms
    );
}

/// What the enabled-event sets cost.
fn print_scan_sets(out: &mut Out, sets: &codegen::lower::ScanSets) {
    outln!(
        out,
        "  enabled-event sets: {} word(s) per set; flash {} bytes of alphabets and {} bytes of masks (the enabled events are the rows above); RAM {} bytes",
        sets.event_words,
        sets.alphabet_bytes,
        sets.mask_bytes,
        sets.ram_bytes
    );
    outln!(
        out,
        "  allowed sets: stored for {} of {} supervisor(s), a move copies {} word(s) (index {} bytes, the sets among the masks); the others scatter their enabled row (`[plc] stored_sets_bytes`)",
        sets.stored,
        sets.supervisors,
        sets.event_words,
        sets.index_bytes
    );
    let g = &sets.guards;
    if g.guards != 0 {
        outln!(
            out,
            "  guards: {} command(s) guarded, {} decision node(s) over {} state bit(s), {} bytes of flash; a guard reads at most {} node(s)",
            g.guards,
            g.nodes,
            g.state_bits,
            g.bytes,
            g.longest_walk
        );
    }
}

fn print_stats(out: &mut Out, project: &Path, stats: &[SupervisorStats], backend: Backend) {
    outln!(out, "{}:", project.display());
    match backend {
        Backend::Table => {
            outln!(
                out,
                "  {:<24} {:>7} {:>7} {:>7} {:>10} {:>10} {:>7}",
                "supervisor",
                "states",
                "events",
                "layout",
                "bytes",
                "naive",
                "ratio"
            );
            use codegen::backend::table::Layout;
            // The naive size and its ratio to ours, `-` where there is no
            // naive table (a net group's counters; a total of net groups).
            let columns = |naive: Option<usize>, ours: usize| match naive {
                None => ("-".to_owned(), "-".to_owned()),
                Some(naive) => (
                    naive.to_string(),
                    format!("{:.2}x", naive as f64 / ours.max(1) as f64),
                ),
            };
            let (mut ours, mut naive) = (0, 0);
            for s in stats {
                ours += s.table_bytes;
                naive += s.naive_bytes;
                let is_net = s.layout == Some(Layout::Net);
                let (naive_text, ratio) =
                    columns((!is_net).then_some(s.naive_bytes), s.table_bytes);
                outln!(
                    out,
                    "  {:<24} {:>7} {:>7} {:>7} {:>10} {:>10} {:>7}",
                    s.name,
                    s.states,
                    s.events,
                    match s.layout {
                        Some(Layout::Sparse) => "sparse",
                        Some(Layout::Keyed) => "keyed",
                        Some(Layout::Net) => "net",
                        _ => "dense",
                    },
                    s.table_bytes,
                    naive_text,
                    ratio
                );
            }
            let only_nets =
                !stats.is_empty() && stats.iter().all(|s| s.layout == Some(Layout::Net));
            let (naive_text, ratio) = columns((!only_nets).then_some(naive), ours);
            outln!(
                out,
                "  {:<24} {:>7} {:>7} {:>7} {:>10} {:>10} {:>7}",
                "total",
                "",
                "",
                "",
                ours,
                naive_text,
                ratio
            );
            outln!(out, "  (naive: one u16 per state × event pair)");
            if stats.iter().any(|s| s.layout == Some(Layout::Net)) {
                outln!(
                    out,
                    "  (net: a Petri net's group of place counters; states: the net's reachable markings)"
                );
            }
        }
        Backend::Logic | Backend::Match => {
            // The logic backend adds its minimisation effort and limit.
            let effort = |e: Option<(u64, u64)>, text: &dyn Fn(u64, u64) -> String| {
                e.map(|(e, l)| text(e, l)).unwrap_or_default()
            };
            outln!(
                out,
                "  {:<24} {:>7} {:>7} {:>7} {:>9}{}",
                "supervisor",
                "states",
                "events",
                "cubes",
                "literals",
                effort(stats.first().and_then(|s| s.logic_effort), &|_, _| {
                    format!(" {:>12} {:>12}", "effort", "limit")
                })
            );
            for s in stats {
                outln!(
                    out,
                    "  {:<24} {:>7} {:>7} {:>7} {:>9}{}",
                    s.name,
                    s.states,
                    s.events,
                    s.cubes,
                    s.literals,
                    effort(s.logic_effort, &|e, l| format!(" {e:>12} {l:>12}"))
                );
            }
        }
    }
}
