//! `codegen gen`: the generated Rust source of a project, for humans.

use super::{print_json, Outcome};
use codegen::emit::{generate, Backend};
use codegen::{project, Error};
use std::path::{Path, PathBuf};

/// Arguments of `codegen gen`.
#[derive(Debug, clap::Args)]
pub struct GenArgs {
    /// The project file (`*.plc.toml`).
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
}

pub fn run(args: &GenArgs, json: bool) -> Result<Outcome, Error> {
    let project = project::load(&args.project)?;
    for w in &project.warnings {
        eprintln!(
            "warning: {}:{}: {}",
            args.project.display(),
            w.line,
            w.message
        );
    }
    let (backend, name) = match args.backend {
        BackendArg::Table => (Backend::Table, "table"),
        BackendArg::Logic => (Backend::Logic, "logic"),
    };
    let regenerate = format!("codegen gen {} --backend {name}", args.project.display());
    let generated = generate(&project, backend, &regenerate)?;
    if args.stats {
        if json {
            print_json(&generated.stats);
            return Ok(Outcome::Holds);
        }
        print_stats(&args.project, &generated.stats, backend);
        return Ok(Outcome::Holds);
    }
    match &args.output {
        Some(path) => write(path, &generated.code)?,
        None => print!("{}", generated.code),
    }
    Ok(Outcome::Holds)
}

fn write(path: &Path, code: &str) -> Result<(), Error> {
    std::fs::write(path, code).map_err(|e| Error::io(path, e))
}

fn print_stats(project: &Path, stats: &[codegen::emit::SupervisorStats], backend: Backend) {
    println!("{}:", project.display());
    match backend {
        Backend::Table => {
            println!(
                "  {:<24} {:>7} {:>7} {:>7} {:>10} {:>10} {:>7}",
                "supervisor", "states", "events", "layout", "bytes", "naive", "ratio"
            );
            let (mut ours, mut naive) = (0, 0);
            for s in stats {
                ours += s.table_bytes;
                naive += s.naive_bytes;
                println!(
                    "  {:<24} {:>7} {:>7} {:>7} {:>10} {:>10} {:>6.2}x",
                    s.name,
                    s.states,
                    s.events,
                    match s.layout {
                        Some(codegen::backend::table::Layout::Sparse) => "sparse",
                        _ => "dense",
                    },
                    s.table_bytes,
                    s.naive_bytes,
                    s.naive_bytes as f64 / s.table_bytes.max(1) as f64
                );
            }
            println!(
                "  {:<24} {:>7} {:>7} {:>7} {:>10} {:>10} {:>6.2}x",
                "total",
                "",
                "",
                "",
                ours,
                naive,
                naive as f64 / ours.max(1) as f64
            );
            println!("  (naive: one u16 per state × event pair)");
        }
        Backend::Logic => {
            println!(
                "  {:<24} {:>7} {:>7} {:>7} {:>9}",
                "supervisor", "states", "events", "cubes", "literals"
            );
            for s in stats {
                println!(
                    "  {:<24} {:>7} {:>7} {:>7} {:>9}",
                    s.name, s.states, s.events, s.cubes, s.literals
                );
            }
        }
    }
}
