//! `cargo xtask qemu [PROJECT] [SCENARIO]`: the firmware's replay harness
//! under QEMU (mps2-an386, Cortex-M4), for every model of `budgets.toml`
//! or just PROJECT.
//!
//! Per model: record a scenario with host-sim (guided random inputs, the
//! inputs of the closed-loop run its `inputs_from` names, or SCENARIO: an
//! `inputs.csv` or a recorded `.scenario`), build the harness
//! for each backend (table and logic: ours; match: the baseline a
//! hand-written state machine would be), run it under `-icount shift=9`,
//! and read its last line. Fails unless every run has zero mismatches and
//! the table backend stays within the model's budgets. Prints our figures
//! as ratios to the baseline measured in the same run.

use crate::budgets::{self, Budgets, ModelBudget};
use crate::size::llvm_size;
use crate::{cargo, root, run, sysdeps, Result};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// Longest a QEMU run may take.
const TIMEOUT: Duration = Duration::from_secs(180);

/// Scans of the default scenario.
const SCANS: &str = "3000";

/// What the harness printed last.
#[derive(Debug, Clone, Copy, Default)]
pub struct Figures {
    /// Scans replayed.
    pub scans: u64,
    /// Records that differ from host-sim.
    pub mismatches: u64,
    /// Instructions per scan.
    pub median: u64,
    /// 99th percentile.
    pub p99: u64,
    /// Largest.
    pub max: u64,
    /// Flash of the image without the scenario.
    pub flash: u64,
    /// Static RAM.
    pub ram: u64,
    /// Quiet scans (no input change, nothing executed).
    pub quiet_scans: u64,
    /// Median instructions of a quiet scan.
    pub quiet_median: u64,
    /// Largest quiet scan.
    pub quiet_max: u64,
    /// Mean instructions of the background image share of a scan.
    pub share_mean: u64,
    /// Largest image share.
    pub share_max: u64,
}

impl Figures {
    fn parse(line: &str) -> Option<Figures> {
        let mut f = Figures::default();
        let mut seen = 0;
        for pair in line.split_whitespace() {
            let (key, value) = pair.split_once('=')?;
            let value: u64 = value.parse().ok()?;
            let slot = match key {
                "scans" => &mut f.scans,
                "mismatches" => &mut f.mismatches,
                "instr_median" => &mut f.median,
                "instr_p99" => &mut f.p99,
                "instr_max" => &mut f.max,
                "flash" => &mut f.flash,
                "ram" => &mut f.ram,
                "quiet_scans" => {
                    f.quiet_scans = value;
                    continue;
                }
                "quiet_median" => {
                    f.quiet_median = value;
                    continue;
                }
                "quiet_max" => {
                    f.quiet_max = value;
                    continue;
                }
                "share_mean" => {
                    f.share_mean = value;
                    continue;
                }
                "share_max" => {
                    f.share_max = value;
                    continue;
                }
                _ => continue,
            };
            *slot = value;
            seen += 1;
        }
        (seen == 7).then_some(f)
    }
}

/// Violations of `budget`'s QEMU limits by the table backend's figures.
fn over_budget(model: &str, budget: &ModelBudget, f: &Figures) -> Vec<String> {
    [
        (
            "instructions per scan (median)",
            f.median,
            budget.instr_median,
        ),
        ("instructions per scan (max)", f.max, budget.instr_max),
        ("harness flash", f.flash, budget.qemu_flash),
        ("harness static RAM", f.ram, budget.qemu_ram),
    ]
    .into_iter()
    .filter_map(|(what, got, limit)| budgets::over(model, what, got, limit))
    .collect()
}

/// Models to run, by name, with their budgets.
type Models = Vec<(String, ModelBudget)>;

pub fn run_task(args: &[String]) -> Result {
    let qemu = sysdeps::ensure_qemu()?;
    let budgets = Budgets::load()?;
    let (models, scenario) = select(&budgets, args)?;
    let dir = crate::target_dir().join("qemu");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;

    let mut failures = Vec::new();
    let mut rows = Vec::new();
    for (name, model) in &models {
        let scenario = match &scenario {
            Some(s) if is_recorded(s) => s.clone(),
            Some(csv) => record(name, &model.project, Some(csv.as_path()), &dir)?,
            None if !model.inputs_from.is_empty() => {
                let csv = closed_loop_inputs(name, model, &dir)?;
                record(name, &model.project, Some(&csv), &dir)?
            }
            None => record(name, &model.project, None, &dir)?,
        };
        let mut per_backend = Vec::new();
        let backends = model
            .backends
            .iter()
            .map(String::as_str)
            .filter(|b| *b != "match")
            .chain(model.baseline.then_some("match"));
        for backend in backends {
            let elf = build(
                &model.project,
                backend,
                &scenario,
                model,
                "thumbv7em-none-eabihf",
            )?;
            let copy = dir.join(format!("{name}-{backend}.elf"));
            std::fs::copy(&elf, &copy).map_err(|e| format!("{}: {e}", copy.display()))?;
            let figures = run_qemu(&qemu, &copy)?;
            if figures.mismatches > 0 {
                failures.push(format!(
                    "{name} ({backend}): {} mismatches",
                    figures.mismatches
                ));
            }
            per_backend.push((backend, figures));
        }
        match per_backend.iter().find(|(b, _)| *b == "table") {
            Some((_, table)) => failures.extend(over_budget(name, model, table)),
            None => failures.push(format!("{name}: budgets need the table backend")),
        }
        rows.push((name.clone(), per_backend));
    }
    if let Some(v6m) = thumbv6m_size(&qemu, &models, &scenario, &dir)? {
        eprintln!("{v6m}");
    }
    print_report(&rows, &budgets);
    if failures.is_empty() {
        eprintln!("xtask: qemu passed");
        Ok(())
    } else {
        Err(format!("qemu: {}", failures.join("; ")))
    }
}

/// The models to run and the scenario given, from the arguments.
fn select(budgets: &Budgets, args: &[String]) -> Result<(Models, Option<PathBuf>)> {
    let scenario = args.get(1).map(|s| root().join(s));
    let Some(project) = args.first() else {
        return Ok((budgets.models.clone().into_iter().collect(), None));
    };
    let found: Vec<_> = budgets
        .models
        .iter()
        .filter(|(name, m)| *name == project || m.project == *project)
        .map(|(n, m)| (n.clone(), m.clone()))
        .collect();
    if found.is_empty() {
        // A project without budgets: run it, check mismatches only.
        let name = Path::new(project)
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| n.split('.').next())
            .unwrap_or("project")
            .to_owned();
        return Ok((vec![(name, ModelBudget::unbounded(project))], scenario));
    }
    Ok((found, scenario))
}

fn is_recorded(path: &Path) -> bool {
    path.extension().is_some_and(|e| e == "scenario")
}

/// The inputs of `model`'s closed-loop run (`inputs_from`), written by
/// host-sim as `<name>.inputs.csv` in `dir`.
fn closed_loop_inputs(name: &str, model: &ModelBudget, dir: &Path) -> Result<PathBuf> {
    let csv = dir.join(format!("{name}.inputs.csv"));
    let mut cmd = cargo();
    cmd.args(["run", "-q", "--release", "-p", "host-sim", "--"])
        .args(&model.inputs_from)
        .args(["--project", &model.project, "--inputs-csv"])
        .arg(&csv)
        .stdout(Stdio::null());
    run(&mut cmd)?;
    Ok(csv)
}

/// Records the scenario of `project` with host-sim.
pub(crate) fn record(
    name: &str,
    project: &str,
    inputs: Option<&Path>,
    dir: &Path,
) -> Result<PathBuf> {
    let out = dir.join(format!("{name}.scenario"));
    let mut cmd = cargo();
    cmd.args([
        "run",
        "-q",
        "--release",
        "-p",
        "host-sim",
        "--",
        "record",
        project,
        "--out",
    ])
    .arg(&out);
    match inputs {
        Some(csv) => {
            cmd.arg("--inputs").arg(csv);
        }
        None => {
            cmd.args(["--random", SCANS, "--seed", "1"]);
        }
    }
    run(&mut cmd)?;
    Ok(out)
}

/// Builds the harness for `project` and `backend`; the ELF's path.
pub(crate) fn build(
    project: &str,
    backend: &str,
    scenario: &Path,
    budget: &ModelBudget,
    target: &str,
) -> Result<PathBuf> {
    let features = if backend == "logic" {
        "qemu,logic"
    } else {
        "qemu"
    };
    let mut cmd = firmware_build(features, "qemu-replay", target);
    cmd.env("PLC_PROJECT", project)
        .env("PLC_BACKEND", backend)
        .env("PLC_SCENARIO", scenario);
    // Budgets are checked by the harness itself for our table backend.
    if backend == "table" && target.starts_with("thumbv7em") {
        for (var, value) in budget.harness_env() {
            cmd.env(var, value.to_string());
        }
    } else {
        for var in ModelBudget::HARNESS_VARS {
            cmd.env_remove(var);
        }
    }
    run(&mut cmd)?;
    Ok(crate::target_dir().join(format!("{target}/release/qemu-replay")))
}

/// `cargo build --release` of the firmware's QEMU binary `bin` with
/// `features` (the board's left out) for `target`.
pub fn firmware_build(features: &str, bin: &str, target: &str) -> Command {
    let mut cmd = cargo();
    cmd.args([
        "build",
        "--release",
        "-p",
        "firmware",
        "--no-default-features",
    ])
    .args(["--features", features, "--bin", bin, "--target", target]);
    cmd
}

/// Runs `elf` in QEMU with a timeout; the harness's figures.
pub(crate) fn run_qemu(qemu: &str, elf: &Path) -> Result<Figures> {
    let (status, stdout) = run_elf(qemu, elf)?;
    let figures = stdout
        .lines()
        .rev()
        .find_map(Figures::parse)
        .ok_or_else(|| format!("{}: no result line (exit {status})", elf.display()))?;
    if !status.success() && figures.mismatches == 0 {
        eprintln!("  (harness exit {status}: a budget does not hold)");
    }
    Ok(figures)
}

/// Runs `elf` on QEMU's mps2-an386 (Cortex-M4, `-icount shift=9`,
/// semihosting) with a timeout, echoing what it prints: its exit status
/// and standard output.
pub fn run_elf(qemu: &str, elf: &Path) -> Result<(ExitStatus, String)> {
    let mut cmd = Command::new(qemu);
    cmd.args([
        "-M",
        "mps2-an386",
        "-cpu",
        "cortex-m4",
        "-icount",
        "shift=9",
        "-semihosting-config",
        "enable=on,target=native",
        "-nographic",
        "-monitor",
        "none",
        "-serial",
        "none",
        "-kernel",
    ])
    .arg(elf)
    .stdin(Stdio::null())
    .stdout(Stdio::piped())
    .stderr(Stdio::piped());
    eprintln!("$ {} … -kernel {}", qemu, elf.display());
    let mut child = cmd
        .spawn()
        .map_err(|e| format!("cannot start {qemu}: {e}"))?;
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "{}: QEMU timed out after {TIMEOUT:?}",
                elf.display()
            ));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let out = child.wait_with_output().map_err(|e| e.to_string())?;
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    for line in stdout.lines() {
        eprintln!("  {line}");
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !stderr.trim().is_empty() {
        eprintln!("  stderr: {}", stderr.trim());
    }
    Ok((status, stdout))
}

/// Builds the harness of the first model for Cortex-M0+ (size only: QEMU
/// has no M0+ board with this memory map).
/// The first model's table harness built for Cortex-M0+ (ARMv6-M): its
/// size, and its instructions per scan. ARMv6-M is a subset of the
/// ARMv7-M instruction set, so the same image runs on the Cortex-M4
/// machine and counts the instructions an M0+ would execute (its cycles
/// per instruction differ; the count does not).
fn thumbv6m_size(
    qemu: &str,
    models: &[(String, ModelBudget)],
    scenario: &Option<PathBuf>,
    dir: &Path,
) -> Result<Option<String>> {
    let Some((name, model)) = models.first() else {
        return Ok(None);
    };
    let recorded = match scenario {
        Some(s) if is_recorded(s) => s.clone(),
        _ => dir.join(format!("{name}.scenario")),
    };
    let elf = build(
        &model.project,
        "table",
        &recorded,
        model,
        "thumbv6m-none-eabi",
    )?;
    let (flash, ram) = llvm_size(&elf)?;
    let scenario_bytes = std::fs::metadata(&recorded).map(|m| m.len()).unwrap_or(0);
    let copy = dir.join(format!("{name}-table-thumbv6m.elf"));
    std::fs::copy(&elf, &copy).map_err(|e| format!("{}: {e}", copy.display()))?;
    let f = run_qemu(qemu, &copy)?;
    if f.mismatches > 0 {
        return Err(format!(
            "{name} (table, thumbv6m): {} mismatches",
            f.mismatches
        ));
    }
    Ok(Some(format!(
        "thumbv6m-none-eabi (Cortex-M0+) harness of {name}: flash {} bytes without the scenario, static RAM {ram} bytes; instructions per scan median {}, p99 {}, max {}, quiet median {} ({} scans, 0 mismatches)",
        flash.saturating_sub(scenario_bytes),
        f.median,
        f.p99,
        f.max,
        f.quiet_median,
        f.scans
    )))
}

fn ratio(ours: u64, base: u64) -> String {
    if base == 0 {
        "-".into()
    } else {
        format!("{:.2}x", ours as f64 / base as f64)
    }
}

fn print_report(rows: &[(String, Vec<(&str, Figures)>)], budgets: &Budgets) {
    println!(
        "\n{:<12} {:<6} {:>6} {:>5} {:>8} {:>8} {:>8} {:>8} {:>6} {:>8} {:>6}  {:>13} {:>13}",
        "model",
        "backend",
        "scans",
        "mism",
        "instr_md",
        "instr_99",
        "instr_mx",
        "quiet_md",
        "share",
        "flash",
        "ram",
        "instr vs match",
        "flash vs match"
    );
    for (name, per) in rows {
        let base = per
            .iter()
            .find(|(b, _)| *b == "match")
            .map(|(_, f)| *f)
            .unwrap_or_default();
        for (backend, f) in per {
            println!(
                "{:<12} {:<6} {:>6} {:>5} {:>8} {:>8} {:>8} {:>8} {:>6} {:>8} {:>6}  {:>13} {:>13}",
                name,
                backend,
                f.scans,
                f.mismatches,
                f.median,
                f.p99,
                f.max,
                f.quiet_median,
                f.share_mean,
                f.flash,
                f.ram,
                ratio(f.median, base.median),
                ratio(f.flash, base.flash)
            );
        }
        if let Some(b) = budgets.models.get(name) {
            println!("{:<12} budget {}", "", b.describe_qemu());
        }
    }
}
