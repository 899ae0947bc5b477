//! `codegen st` and `codegen plcopen`: a project for industrial PLCs.

use super::error::CliError;
use super::output::{outln, warn, Out};
use super::Outcome;
use des::Error;
use iec_export::{self as iec, IoMap};
use plc_project as project;
use std::path::PathBuf;

/// Arguments of `codegen st` and `codegen plcopen`.
#[derive(Debug, clap::Args)]
pub struct PlcArgs {
    /// The project file (`*.plc.toml`).
    project: PathBuf,
    /// I/O map: the `%I`/`%Q` address of every input and output
    /// (docs/formats.md, "I/O map"); default `%IX0.0`, `%IX0.1`, … and
    /// `%QX0.0`, … in declaration order.
    #[arg(long = "io")]
    io: Option<PathBuf>,
    /// Write the file here instead of stdout.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// `codegen st`: end the file with a `CONFIGURATION` that runs the
    /// program in a cyclic task of the scan period (OpenPLC's runtime
    /// compiles such a file as it is).
    #[arg(long)]
    configuration: bool,
    /// `codegen plcopen`: add the ladder (LD) rendering of the
    /// supervisors as a further function block (docs/ladder.md).
    #[arg(long)]
    ladder: bool,
    /// The most rungs `--ladder` may write; a larger ladder is refused.
    #[arg(long, default_value_t = iec::ladder::DEFAULT_RUNG_LIMIT)]
    max_rungs: usize,
    /// Print the sizes (lines, constant array bytes, POUs) instead of the
    /// file.
    #[arg(long)]
    stats: bool,
}

/// Which file to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flavour {
    /// IEC 61131-3 Structured Text.
    St,
    /// PLCopen XML with ST bodies.
    PlcOpen,
}

#[derive(serde::Serialize)]
struct Stats {
    lines: usize,
    bytes: usize,
    array_bytes: usize,
    pous: Vec<String>,
    renamed: usize,
}

pub fn run(
    args: &PlcArgs,
    flavour: Flavour,
    json: bool,
    out: &mut Out,
) -> Result<Outcome, CliError> {
    if args.ladder && flavour == Flavour::St {
        return Err(CliError::Usage(
            "--ladder is for `codegen plcopen`: ladder diagrams are graphical, PLCopen XML holds them"
                .into(),
        ));
    }
    if args.configuration && flavour == Flavour::PlcOpen {
        return Err(CliError::Usage(
            "--configuration is for `codegen st`: PLCopen XML always holds its configuration and task"
                .into(),
        ));
    }
    let project = project::load(&args.project)?;
    for w in &project.warnings {
        warn(format_args!(
            "warning: {}:{}: {}",
            args.project.display(),
            w.line,
            w.message
        ));
    }
    let io = match &args.io {
        Some(path) => IoMap::load(path)?,
        None => IoMap::sequential(),
    };
    let verb = match flavour {
        Flavour::St => "st",
        Flavour::PlcOpen => "plcopen",
    };
    let mut regenerate = format!("codegen {verb} {}", args.project.display());
    if let Some(path) = &args.io {
        regenerate.push_str(&format!(" --io {}", path.display()));
    }
    if args.ladder {
        regenerate.push_str(" --ladder");
    }
    // The ladder first: when only a reduced or localized form of the
    // synthesised supervisors fits its rung limit, the whole file exports
    // that form, so that the controller and the ladder run the same
    // supervisors.
    let fitted = match flavour {
        Flavour::PlcOpen if args.ladder => Some(iec::ladder::render_fitting(
            &project,
            args.max_rungs,
            |shrink| project::load_shrunk(&args.project, shrink),
        )?),
        _ => None,
    };
    let exported = match fitted.as_ref().and_then(|f| f.shrunk.as_ref()) {
        Some(shrunk) => {
            warn(format_args!(
                "{}: the ladder and the program export the {} form (`{} = true`): {}",
                args.project.display(),
                shrunk.shrink.adjective(),
                shrunk.shrink.key(),
                shrunk.summary
            ));
            &shrunk.project
        }
        None => &project,
    };
    let export = iec::export(exported, &io, &regenerate)?;
    let text = match (flavour, fitted) {
        (Flavour::St, _) if args.configuration => {
            iec::st::print(&export) + &iec::st::configuration(&export)
        }
        (Flavour::St, _) => iec::st::print(&export),
        (Flavour::PlcOpen, Some(fitted)) => {
            iec::plcopen::print_with(&export, &[fitted.ladder.pou_xml])
        }
        (Flavour::PlcOpen, None) => iec::plcopen::print(&export),
    };
    if args.stats {
        let stats = Stats {
            lines: text.lines().count(),
            bytes: text.len(),
            array_bytes: export.array_bytes(),
            pous: export.pous.iter().map(|p| p.name.clone()).collect(),
            renamed: export.renamed.len(),
        };
        if json {
            out.json(&stats);
        } else {
            outln!(
                out,
                "{}: {} lines, {} bytes; constant arrays {} bytes; POUs {}; {} names changed",
                args.project.display(),
                stats.lines,
                stats.bytes,
                stats.array_bytes,
                stats.pous.join(", "),
                stats.renamed
            );
        }
        return Ok(Outcome::Holds);
    }
    match &args.output {
        Some(path) => std::fs::write(path, &text).map_err(|e| Error::io(path, e))?,
        None => out.push_str(&text),
    }
    Ok(Outcome::Holds)
}
