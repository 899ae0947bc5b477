//! `host-sim`: run PLC projects on the PC.

use clap::{Parser, Subcommand, ValueEnum};
use codegen::backend::Backend;
use host_sim::serve::{http, PlantChoice, Session};
use host_sim::{inputs, random_inputs, replay, scenario, Sim};
use std::fmt;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Standard output as Unix tools use it: once its reader has gone
/// (`host-sim boiler | head`), the rest of the report is dropped instead
/// of a panic, and the command carries on (its files written, its exit
/// status its own outcome).
struct Report {
    out: io::StdoutLock<'static>,
    closed: bool,
}

impl Report {
    fn new() -> Report {
        Report {
            out: io::stdout().lock(),
            closed: false,
        }
    }

    /// Writes one line; an error other than a closed pipe ends the command.
    fn line(&mut self, args: fmt::Arguments<'_>) -> Result<(), String> {
        if self.closed {
            return Ok(());
        }
        match writeln!(self.out, "{args}") {
            Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
                self.closed = true;
                Ok(())
            }
            result => result.map_err(|e| format!("standard output: {e}")),
        }
    }

    /// `text` on one line if `wide`, else wrapped by words within
    /// [`host_sim::columns::TERMINAL`] columns.
    fn paragraph(&mut self, text: &str, wide: bool) -> Result<(), String> {
        if wide {
            return self.line(format_args!("{text}"));
        }
        let words: Vec<&str> = text.split(' ').collect();
        for line in host_sim::columns::wrap(&words, host_sim::columns::TERMINAL) {
            self.line(format_args!("{line}"))?;
        }
        Ok(())
    }
}

/// One line of the report (see [`Report`]).
macro_rules! say {
    ($report:expr, $($arg:tt)*) => {
        $report.line(format_args!($($arg)*))?
    };
}

/// One line on standard error, dropped if nobody reads it (the exit status
/// still tells).
macro_rules! note {
    ($($arg:tt)*) => {
        let _ = writeln!(io::stderr(), $($arg)*);
    };
}

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

/// What simulates the machine in `serve`.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum PlantArg {
    /// The boiler's or the cell's physics when the project has their
    /// signals, else the project's plant automata, else none.
    Auto,
    /// The plant automata the project's supervisors are synthesised from.
    Automata,
    /// No plant model: you move the inputs.
    Supervisors,
    /// The gas-fired boiler's physics.
    Boiler,
    /// The batch cell's physics.
    Cell,
}

impl From<PlantArg> for PlantChoice {
    fn from(p: PlantArg) -> PlantChoice {
        match p {
            PlantArg::Auto => PlantChoice::Auto,
            PlantArg::Automata => PlantChoice::Automata,
            PlantArg::Supervisors => PlantChoice::Supervisors,
            PlantArg::Boiler => PlantChoice::Boiler,
            PlantArg::Cell => PlantChoice::Cell,
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
        /// Also draw the run as an SVG picture: inputs, outputs, events,
        /// supervisor states and fault mode over time.
        #[arg(long)]
        svg: Option<PathBuf>,
        /// How supervisors are represented.
        #[arg(long, value_enum, default_value_t = BackendArg::Table)]
        backend: BackendArg,
    },
    /// The boiler in closed loop with its plant simulation: a timeline on
    /// stdout, a VCD, optionally an SVG picture; fails on a safety
    /// violation.
    Boiler {
        /// A named scenario (`--list`), or `random-<seed>`.
        #[arg(long, default_value = "cold-start-high")]
        scenario: String,
        /// The project [default: models/boiler/boiler.plc.toml, from the
        /// working directory or else from this repository].
        #[arg(long)]
        project: Option<PathBuf>,
        /// Where to write the waveform.
        #[arg(long, default_value = "boiler.vcd")]
        vcd: PathBuf,
        /// Also draw the run as an SVG picture.
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Seed of the plant's random ignition failures.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Print the timeline one line per row, however long, instead of
        /// within 120 columns.
        #[arg(long)]
        wide: bool,
        /// List the scenarios and exit.
        #[arg(long)]
        list: bool,
    },
    /// The manufacturing testbed (two trains, three cranes, 29 modular
    /// supervisors) in closed loop with its plant simulation: a timeline
    /// of the executed events on stdout; fails on a broken invariant.
    Testbed {
        /// A named scenario (`--list`).
        #[arg(default_value = "laps")]
        scenario: String,
        /// The project [default: models/testbed/testbed.plc.toml, from the
        /// working directory or else from this repository].
        #[arg(long)]
        project: Option<PathBuf>,
        /// Also write the run's inputs as an `inputs.csv` (one row per
        /// scan: for `host-sim replay`, `record` and the QEMU harness).
        #[arg(long)]
        inputs_csv: Option<PathBuf>,
        /// Print the totals on one line, however long, instead of within
        /// 120 columns.
        #[arg(long)]
        wide: bool,
        /// List the scenarios and exit.
        #[arg(long)]
        list: bool,
    },
    /// Simulate a project in the browser: a local web page showing and
    /// steering it in closed loop with a simulated machine (its plant
    /// automata, the boiler's or the batch cell's physics).
    Serve {
        /// The project file (`*.plc.toml`).
        project: PathBuf,
        /// The port on 127.0.0.1 (0: any free port; the URL is printed).
        #[arg(long, default_value_t = 8080)]
        port: u16,
        /// What simulates the machine.
        #[arg(long, value_enum, default_value_t = PlantArg::Auto)]
        plant: PlantArg,
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
        /// Also draw the run as an SVG picture, as `replay --svg` does.
        #[arg(long)]
        svg: Option<PathBuf>,
    },
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
            svg,
            backend,
        } => {
            let mut sim = Sim::load(&project, backend.into()).map_err(|e| e.to_string())?;
            for w in &sim.project().warnings {
                note!("warning: {}:{}: {}", project.display(), w.line, w.message);
            }
            // Rows are read, and the trace and waveform written, scan by
            // scan: constant memory however long the inputs file.
            let extras = replay::Extras {
                vcd: vcd_path.as_deref(),
                svg: svg.as_deref(),
            };
            let totals = replay::stream(&mut sim, &inputs_path, &out, extras)?;
            note!(
                "replayed {} scans: {} events executed, {} scans in fault mode",
                totals.scans,
                totals.events,
                totals.faults
            );
            Ok(())
        }
        Command::Boiler {
            scenario,
            project,
            vcd: vcd_path,
            svg,
            seed,
            wide,
            list,
        } => {
            let project = project.unwrap_or_else(default_boiler);
            let outputs = BoilerOutputs {
                vcd: &vcd_path,
                svg: svg.as_deref(),
                wide,
            };
            boiler(&scenario, &project, outputs, seed, list, &mut Report::new())
        }
        Command::Testbed {
            scenario,
            project,
            inputs_csv,
            wide,
            list,
        } => {
            let project =
                project.unwrap_or_else(|| in_repository("models/testbed/testbed.plc.toml"));
            testbed(
                &scenario,
                &project,
                inputs_csv.as_deref(),
                wide,
                list,
                &mut Report::new(),
            )
        }
        Command::Serve {
            project,
            port,
            plant,
            backend,
        } => serve(&project, port, plant.into(), backend.into()),
        Command::Record {
            project,
            inputs: inputs_path,
            random,
            seed,
            noise_one_in,
            out,
            csv,
            svg,
        } => {
            // Rows are generated or read as they are recorded, and every
            // file is written as it goes: constant memory however many scans.
            let mut sim = Sim::load(&project, Backend::Table).map_err(|e| e.to_string())?;
            let totals = match &inputs_path {
                Some(path) => {
                    let open = || {
                        let file = inputs::open(path)?;
                        inputs::InputRows::new(file, path, sim.project()).map_err(|e| e.to_string())
                    };
                    // A first pass counts (and checks) the rows: the
                    // scenario's header gives their number.
                    let mut scans = 0u64;
                    for row in open()? {
                        row.map_err(|e| e.to_string())?;
                        scans += 1;
                    }
                    let rows = open()?;
                    scenario::record_files(&mut sim, scans, rows, &out, csv, svg.as_deref())?
                }
                None => {
                    let rows = random_inputs::GuidedInputs::new(sim.project(), seed, noise_one_in)
                        .map_err(|e| e.to_string())?
                        .take(random);
                    scenario::record_files(
                        &mut sim,
                        random as u64,
                        rows,
                        &out,
                        csv,
                        svg.as_deref(),
                    )?
                }
            };
            note!(
                "recorded {} scans ({} bytes): {} events executed, {} scans in fault mode",
                totals.scans,
                std::fs::metadata(&out).map_or(0, |m| m.len()),
                totals.events,
                totals.faults
            );
            Ok(())
        }
    }
}

/// `host-sim boiler`: runs a scenario, prints the timeline, writes the
/// waveforms, checks the safety invariants.
/// `models/boiler/boiler.plc.toml` from the working directory, or else
/// the repository's copy (the main job run from elsewhere).
fn default_boiler() -> PathBuf {
    in_repository("models/boiler/boiler.plc.toml")
}

/// `relative` from the working directory, or else the repository's copy.
fn in_repository(relative: &str) -> PathBuf {
    let relative = Path::new(relative);
    let repository = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(relative);
    if relative.exists() || !repository.exists() {
        relative.to_path_buf()
    } else {
        repository
    }
}

/// What `host-sim boiler` writes besides its safety verdict.
struct BoilerOutputs<'a> {
    /// The waveform (and its GTKWave save file next to it).
    vcd: &'a Path,
    /// The picture, if asked for.
    svg: Option<&'a Path>,
    /// The timeline's old layout, one line per row however long.
    wide: bool,
}

fn boiler(
    name: &str,
    project_path: &Path,
    BoilerOutputs {
        vcd: vcd_path,
        svg,
        wide,
    }: BoilerOutputs<'_>,
    seed: u64,
    list: bool,
    out: &mut Report,
) -> Result<(), String> {
    use host_sim::boiler::{self, scenarios, BoilerParams, BoilerPlant, Invariants};
    if list {
        for n in scenarios::NAMES.into_iter().chain(["random-<seed>"]) {
            say!(out, "{n:<24} {}", scenarios::about(n).unwrap_or_default());
        }
        return Ok(());
    }
    let (script, duration) = scenarios::named(name).ok_or_else(|| {
        format!(
            "unknown scenario `{name}` (one of: {}, random-<seed>)",
            scenarios::NAMES.join(", ")
        )
    })?;
    let mut sim = Sim::load(project_path, Backend::Table).map_err(|e| e.to_string())?;
    let mut plant = BoilerPlant::new(BoilerParams::default(), seed);
    let run = boiler::run(&mut sim, &mut plant, &script, duration).map_err(|e| e.to_string())?;

    let heading = format!(
        "boiler, scenario {name} ({} s), project {}",
        duration / 1000,
        project_path.display()
    );
    out.paragraph(&heading, wide)?;
    for line in boiler::timeline::lines(&run, wide) {
        say!(out, "{line}");
    }

    let mut buf = Vec::new();
    boiler::waveform::write(&mut buf, sim.supervisors(), &run).map_err(|e| e.to_string())?;
    write(vcd_path, &buf)?;
    note!("wrote {}", vcd_path.display());
    let save_file = boiler::waveform::save_file(vcd_path, sim.supervisors(), &run);
    if let Some(path) = host_sim::gtkw::write_next_to(vcd_path, &save_file)? {
        note!("wrote {}", path.display());
    }
    if let Some(path) = svg {
        write(
            path,
            boiler::svg::render(&run, &format!("boiler: {name}")).as_bytes(),
        )?;
        note!("wrote {}", path.display());
    }
    let violations = run.violations(&Invariants::default());
    for v in &violations {
        say!(out, "SAFETY VIOLATION {v}");
    }
    if violations.is_empty() {
        say!(
            out,
            "safety invariants: held on all {} scans",
            run.rows.len()
        );
        Ok(())
    } else {
        Err(format!("{} safety violations", violations.len()))
    }
}

/// `host-sim testbed`: runs a scenario, prints its timeline and totals,
/// checks the invariants.
fn testbed(
    name: &str,
    project_path: &Path,
    inputs_csv: Option<&Path>,
    wide: bool,
    list: bool,
    out: &mut Report,
) -> Result<(), String> {
    use host_sim::testbed::{self, scenarios};
    if list {
        for n in scenarios::NAMES {
            say!(out, "{n:<16} {}", scenarios::about(n).unwrap_or_default());
        }
        return Ok(());
    }
    let mut sim = Sim::load(project_path, Backend::Table).map_err(|e| e.to_string())?;
    let run = testbed::run_named(&mut sim, name)
        .ok_or_else(|| {
            format!(
                "unknown scenario `{name}` (one of: {})",
                scenarios::NAMES.join(", ")
            )
        })?
        .map_err(|e| e.to_string())?;
    let heading = format!(
        "testbed, scenario {name}, project {}",
        project_path.display()
    );
    out.paragraph(&heading, wide)?;
    for line in run.timeline().lines() {
        say!(out, "{line}");
    }
    let totals = format!(
        "{} scans, {} events; laps: train 1 {}, train 2 {}; loads (train 1, train 2): crane 1 {}/{}, crane 2 {}/{}, crane 3 {}/{}; fault: {}",
        run.scans,
        run.events.len(),
        run.laps(0),
        run.laps(1),
        run.loads(1, 0),
        run.loads(1, 1),
        run.loads(2, 0),
        run.loads(2, 1),
        run.loads(3, 0),
        run.loads(3, 1),
        run.fault.as_ref().map_or("none".to_owned(), |(t, f)| format!("{f} at {:.2} s", *t as f64 / 1000.0))
    );
    out.paragraph(&totals, wide)?;
    if let Some(path) = inputs_csv {
        let csv = run
            .inputs_csv(sim.project())
            .map_err(|missing| format!("the project lacks {}", missing.join(", ")))?;
        write(path, csv.as_bytes())?;
        note!("wrote {}", path.display());
    }
    for v in &run.violations {
        say!(out, "VIOLATION {v}");
    }
    if run.violations.is_empty() {
        say!(out, "invariants: held on all {} scans", run.scans);
        Ok(())
    } else {
        Err(format!("{} violations", run.violations.len()))
    }
}

/// `host-sim serve`: loads the project, binds 127.0.0.1:`port`, prints
/// the URL and serves until killed.
fn serve(project: &Path, port: u16, plant: PlantChoice, backend: Backend) -> Result<(), String> {
    let session = Session::load(project, backend, plant)?;
    let server = tiny_http::Server::http(("127.0.0.1", port))
        .map_err(|e| format!("127.0.0.1:{port}: {e}"))?;
    let addr = server
        .server_addr()
        .to_ip()
        .ok_or("the server has no IP address")?;
    let mut out = io::stdout();
    let _ = writeln!(out, "http://{addr}/");
    let _ = out.flush();
    note!(
        "host-sim serve: {} ({} plant); Ctrl-C stops",
        session.project().name,
        session.machine().kind()
    );
    let mut app = http::App {
        session,
        file: project.display().to_string(),
    };
    app.serve(&server).map_err(|e| format!("serving: {e}"))
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            note!("error: {e}");
            ExitCode::from(2)
        }
    }
}
