//! `host-sim`: run PLC projects on the PC.

use clap::{Parser, Subcommand, ValueEnum};
use codegen::emit::Backend;
use host_sim::{inputs, replay, scenario, trace, vcd, Sim};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Run PLC projects on a virtual clock.
#[derive(Debug, Parser)]
#[command(name = "host-sim", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
enum BackendArg {
    Table,
    Logic,
}

impl From<BackendArg> for Backend {
    fn from(b: BackendArg) -> Backend {
        match b {
            BackendArg::Table => Backend::Table,
            BackendArg::Logic => Backend::Logic,
        }
    }
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Replay an inputs file through a project and write the trace.
    Replay {
        /// The project file (`*.plc.toml`).
        project: PathBuf,
        /// Inputs, one row per scan (`scan,time_ms,<inputs…>`).
        #[arg(long)]
        inputs: PathBuf,
        /// Trace output (`trace.csv`).
        #[arg(long)]
        out: PathBuf,
        /// Also write a waveform.
        #[arg(long)]
        vcd: Option<PathBuf>,
        /// How supervisors are represented.
        #[arg(long, value_enum, default_value_t = BackendArg::Table)]
        backend: BackendArg,
    },
    /// Record a scenario for the QEMU harness: inputs per scan and the
    /// expected trace, as postcard records.
    Record {
        /// The project file (`*.plc.toml`).
        project: PathBuf,
        /// Inputs, one row per scan; without it, random inputs.
        #[arg(long, conflicts_with = "random")]
        inputs: Option<PathBuf>,
        /// Number of scans of random inputs.
        #[arg(long, default_value_t = 2000)]
        random: usize,
        /// Seed of the random inputs.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// A random input toggles with probability 1/N per scan (noise that
        /// may raise unexpected events); the rest of the random inputs
        /// provoke events the supervisors expect.
        #[arg(long, default_value_t = 200)]
        noise_one_in: u64,
        /// Where to write the scenario.
        #[arg(long)]
        out: PathBuf,
        /// Also write the inputs and the expected trace as CSV next to it.
        #[arg(long)]
        csv: bool,
    },
}

fn read(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))
}

fn write(path: &Path, text: &[u8]) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Replay {
            project,
            inputs: inputs_path,
            out,
            vcd: vcd_path,
            backend,
        } => {
            let mut sim = Sim::load(&project, backend.into()).map_err(|e| e.to_string())?;
            for w in &sim.project().warnings {
                eprintln!("warning: {}:{}: {}", project.display(), w.line, w.message);
            }
            let rows = inputs::parse(&read(&inputs_path)?, &inputs_path, sim.project())
                .map_err(|e| e.to_string())?;
            let trace_rows = replay::replay(&mut sim, &rows).map_err(|e| e.to_string())?;
            write(&out, trace::to_csv(sim.project(), &trace_rows).as_bytes())?;
            if let Some(path) = vcd_path {
                let mut buf = Vec::new();
                vcd::write(&mut buf, sim.project(), &rows, &trace_rows)
                    .map_err(|e| e.to_string())?;
                write(&path, &buf)?;
            }
            let faults = trace_rows.iter().filter(|r| r.fault.is_some()).count();
            eprintln!(
                "replayed {} scans: {} events executed, {} scans in fault mode",
                trace_rows.len(),
                trace_rows.iter().map(|r| r.events.len()).sum::<usize>(),
                faults
            );
            Ok(())
        }
        Command::Record {
            project,
            inputs: inputs_path,
            random,
            seed,
            noise_one_in,
            out,
            csv,
        } => {
            let mut sim = Sim::load(&project, Backend::Table).map_err(|e| e.to_string())?;
            let rows = match &inputs_path {
                Some(path) => {
                    inputs::parse(&read(path)?, path, sim.project()).map_err(|e| e.to_string())?
                }
                None => scenario::guided_inputs(sim.project(), random, seed, noise_one_in)
                    .map_err(|e| e.to_string())?,
            };
            let bytes = scenario::record(&mut sim, &rows).map_err(|e| e.to_string())?;
            write(&out, &bytes)?;
            if csv {
                write(
                    &out.with_extension("inputs.csv"),
                    inputs::to_csv(sim.project(), &rows).as_bytes(),
                )?;
                write(
                    &out.with_extension("trace.csv"),
                    trace::to_csv(sim.project(), sim.trace()).as_bytes(),
                )?;
            }
            let t = sim.trace();
            eprintln!(
                "recorded {} scans ({} bytes): {} events executed, {} scans in fault mode",
                t.len(),
                bytes.len(),
                t.iter().map(|r| r.events.len()).sum::<usize>(),
                t.iter().filter(|r| r.fault.is_some()).count()
            );
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
