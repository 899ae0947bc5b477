//! Project automation: `cargo xtask <task>`.
//!
//! - `ci`: everything CI checks, in order, failing fast (the README's test
//!   command).
//! - `bench-faudes [--runs N] [MODEL|FAMILY:N…]`: our compose + supcon
//!   (explicit and symbolic) against libFAUDES on the benchmark models or
//!   family instances (`tline:9`), in one run, as ratios.
//! - `qemu [PROJECT] [SCENARIO]`: the firmware replay harness in QEMU for
//!   every model (zero mismatches against host-sim, instructions per scan,
//!   budgets, ratios to a `match` baseline).
//! - `qemu-update`: field update in QEMU: images loaded over a simulated
//!   serial link while the PLC scans, switched in, refused (corrupt,
//!   hostile), rolled back at restart; every scan against host-sim.
//! - `reduction [MODEL…]`: the synthesised supervisors of models in full,
//!   reduced and localized form, measured as `qemu` measures a model
//!   (tables, flash, instructions per scan): a report, no budgets.
//! - `size [MODEL…]`: flash and static RAM of the board firmware.
//! - `deps`: no build a new user starts with needs libclang (bindgen).
//! - `example`: `examples/my-plc/`, a user's own crate using the executor
//!   and a generated program, built and run warning-free (host and board).
//! - `layers`: the one-way rules: workspace crates depend only on lower
//!   stages, and no crate has an import circle between its modules.
//! - `iec [--all]`: the Structured Text and PLCopen XML exports of every
//!   seed project parsed by blark and validated against the TC6 schema.
//! - `matiec`: the same exports compiled by matiec (OpenPLC's and
//!   Beremiz's IEC compiler) and gcc, run in lockstep with host-sim.
//! - `browser [--no-build]`: the simulator page of `host-sim serve` driven
//!   in headless Chromium (press cycle, fault and reset against the trace
//!   and a replay, boiler fast-forward, mixers' net, the testbed's long
//!   lists); screenshots in `target/browser/`.
//! - `guard-bench`: the guards of symbolic supervisors evaluated in QEMU
//!   as node tables and as sums of products (instructions, bytes).

use std::path::PathBuf;
use std::process::{Command, ExitCode};

mod bench;
mod browser;
mod budgets;
mod code_share;
mod deps;
mod example;
mod guard_bench;
mod iec;
mod layers;
mod matiec;
mod qemu;
mod qemu_update;
mod reduction;
mod size;
mod sysdeps;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("ci") => ci(),
        Some("bench-faudes") => bench::run(&args[1..]),
        Some("qemu") => qemu::run_task(&args[1..]),
        Some("qemu-update") => qemu_update::run_task(&args[1..]),
        Some("reduction") => reduction::run_task(&args[1..]),
        Some("size") => size::run_task(&args[1..]),
        Some("deps") => deps::run_task(&args[1..]),
        Some("example") => example::run_task(&args[1..]),
        Some("layers") => layers::run_task(&args[1..]),
        Some("iec") => iec::run_task(&args[1..]),
        Some("matiec") => matiec::run_task(&args[1..]),
        Some("guard-bench") => guard_bench::run_task(&args[1..]),
        Some("browser") => browser::run_task(&args[1..]),
        _ => {
            eprintln!(
                "usage: cargo xtask <task>\n\
                 tasks:\n  \
                 ci                         fmt, clippy, all tests, differential tests vs libFAUDES\n  \
                 bench-faudes [--runs N] [MODEL|FAMILY:N…]  supcon (explicit, symbolic) vs libFAUDES\n  \
                 qemu [PROJECT] [SCENARIO]  replay in QEMU: zero mismatches, instructions per scan, budgets\n  \
                 qemu-update                field update in QEMU: loads over a serial link, switch, refusals, rollback\n  \
                 reduction [MODEL…]         full, reduced and localized supervisors in QEMU: flash, instructions per scan\n  \
                 size [MODEL…]              flash and static RAM of the board firmware, budgets\n  \
                 deps                       the README's commands and the firmware build without libclang (cargo tree)\n  \
                 example                    examples/my-plc (a user's crate) built and run with -D warnings, host and board\n  \
                 layers [--edges]           crates depend on lower stages only; no import circle inside a crate\n  \
                 iec [--all]                ST and PLCopen XML of every seed: blark parse, TC6 schema (--all: the largest ST too)\n  \
                 matiec                     ST and PLCopen XML of every seed compiled by matiec and gcc, run in lockstep with host-sim\n  \
                 guard-bench                guards in QEMU as node tables and as sums of products: instructions, bytes\n  \
                 browser [--no-build]       the simulator page (host-sim serve) in headless Chromium: clicks, trace, replay, screenshots"
            );
            Err("no task given".into())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Errors of a task, as text for the user.
pub type Result<T = ()> = std::result::Result<T, String>;

/// The workspace root: that of the `xtask` cargo runs (`cargo xtask`
/// sets `CARGO_MANIFEST_DIR` when it starts us), else that of the sources
/// this binary was built from. Two working trees that share a
/// `CARGO_TARGET_DIR` share the uplifted `target/debug/xtask`, which can
/// be the other tree's build: the tree is taken from the command, not
/// from the binary.
pub fn root() -> PathBuf {
    let manifest = std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")));
    manifest
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

/// Cargo's target directory (`CARGO_TARGET_DIR`, else `target/` at the
/// root).
pub fn target_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => root().join(dir),
        None => root().join("target"),
    }
}

/// The `cargo` that runs us.
pub fn cargo() -> Command {
    let mut cmd = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    cmd.current_dir(root());
    cmd
}

/// `cargo run -q -p codegen-cli OPTIONS --`: the generator's CLI (or,
/// with `--example NAME`, one of its examples), its arguments to follow.
pub fn codegen_cli(options: &[&str]) -> Command {
    let mut cmd = cargo();
    cmd.args(["run", "-q", "-p", "codegen-cli"])
        .args(options)
        .arg("--");
    cmd
}

/// Runs `cmd`, echoing it, and fails on a non-zero exit.
pub fn run(cmd: &mut Command) -> Result {
    eprintln!("$ {}", describe(cmd));
    let status = cmd
        .status()
        .map_err(|e| format!("cannot start {}: {e}", describe(cmd)))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("`{}` failed ({status})", describe(cmd)))
    }
}

/// `cmd` as a shell line, for echoes and errors.
pub fn describe(cmd: &Command) -> String {
    let mut s = cmd.get_program().to_string_lossy().into_owned();
    for a in cmd.get_args() {
        s.push(' ');
        s.push_str(&a.to_string_lossy());
    }
    s
}

/// A Python interpreter that can `import faudes`, installing the package
/// with pip when it is missing.
pub fn python_with_faudes() -> Result<String> {
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    let has = |py: &str| {
        Command::new(py)
            .args(["-c", "import faudes"])
            .stderr(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if has(&python) {
        return Ok(python);
    }
    eprintln!("xtask: libFAUDES (pip package `faudes`) is missing; installing it");
    run(Command::new(&python).args(["-m", "pip", "install", "--quiet", "faudes"]))?;
    if has(&python) {
        Ok(python)
    } else {
        Err(format!(
            "`{python} -c 'import faudes'` still fails after pip install; \
             install the `faudes` package for {python} by hand"
        ))
    }
}

/// The pinned toolchain with the targets and components
/// `rust-toolchain.toml` lists. Under `cargo xtask`, `RUSTUP_TOOLCHAIN`
/// names the active toolchain and `rustup toolchain install` then only
/// says it exists (leaving a toolchain provisioned without the Cortex-M
/// targets as it is), so they are added by name.
fn toolchain() -> Result {
    #[derive(serde::Deserialize)]
    struct File {
        toolchain: Pinned,
    }
    #[derive(serde::Deserialize)]
    struct Pinned {
        #[serde(default)]
        targets: Vec<String>,
        #[serde(default)]
        components: Vec<String>,
    }
    let path = root().join("rust-toolchain.toml");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let pinned: File = toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let rustup = || {
        let mut cmd = Command::new("rustup");
        cmd.current_dir(root());
        cmd
    };
    run(rustup().arg("toolchain").arg("install"))?;
    run(rustup()
        .args(["target", "add"])
        .args(&pinned.toolchain.targets))?;
    run(rustup()
        .args(["component", "add"])
        .args(&pinned.toolchain.components))
}

/// The whole CI pipeline.
fn ci() -> Result {
    // Installs the pinned toolchain's targets and components when missing
    // (rustup does not do that on its own for an installed toolchain).
    toolchain()?;
    // Before anything installs libclang: the commands a new user starts
    // with must not need it.
    deps::run_task(&[])?;
    // The logic backend's tests need Espresso, hence libclang.
    sysdeps::ensure_libclang()?;
    run(cargo().args(["fmt", "--all", "--", "--check"]))?;
    // The one-way rules (crate stages, no import circle inside a crate):
    // manifests and source text only, so before anything compiles.
    layers::run_task(&[])?;
    // Host crates; the firmware is checked for its own targets below.
    run(cargo().args([
        "clippy",
        "--workspace",
        "--exclude",
        "firmware",
        "--all-targets",
        "--",
        "-D",
        "warnings",
    ]))?;
    // The tests turn Espresso on; the builds users start with leave it
    // out, and that configuration must be warning-free too.
    run(cargo().args([
        "clippy",
        "-p",
        "codegen",
        "-p",
        "codegen-cli",
        "-p",
        "host-sim",
        "--lib",
        "--bins",
        "--",
        "-D",
        "warnings",
    ]))?;
    run(cargo().args(["test", "--workspace", "--exclude", "firmware"]))?;
    // Doc comments are part of the product: no broken or ambiguous links.
    run(cargo()
        .args(["doc", "--workspace", "--exclude", "firmware", "--no-deps"])
        .env("RUSTDOCFLAGS", "-D warnings"))?;
    // The executor is no_std: prove it builds for the board's instruction
    // set (with defmt, as the firmware uses it) and for Cortex-M0+.
    for (target, features) in [
        ("thumbv7em-none-eabihf", "defmt"),
        ("thumbv6m-none-eabi", ""),
    ] {
        run(cargo().args([
            "build",
            "--release",
            "-p",
            "executor",
            "--target",
            target,
            "--features",
            features,
        ]))?;
    }
    // A user's own crate (examples/my-plc): the executor and a generated
    // program outside the workspace, warning-free under -D warnings (host,
    // clippy, the board binary), its trace the one its README shows (8 s
    // once built).
    example::run_task(&[])?;
    let python = python_with_faudes()?;
    run(cargo().env("PYTHON", &python).args([
        "test",
        "--release",
        "-p",
        "des",
        "--test",
        "faudes_diff",
        "--",
        "--ignored",
    ]))?;
    // The IEC 61131-3 export, checked by tools written by others: parsed
    // by blark, validated against the TC6 schema, compiled by matiec and
    // run.
    iec::run_task(&[])?;
    matiec::run_task(&[])?;
    // The ignored host-sim tests CI runs in release: the boiler's
    // randomized campaign (1000 runs of ten simulated minutes, every scan
    // checked by the safety invariants), and the testbed's guard
    // supervisor of the whole synthesised anew and compared with the
    // committed guard file (13 to 26 s).
    for (test, filter) in [
        ("boiler_campaign", Some("random_campaign")),
        ("testbed", None),
    ] {
        run(cargo()
            .args(["test", "--release", "-p", "host-sim", "--test", test])
            .args(["--", "--ignored"])
            .args(filter))?;
    }
    // The simulator page in headless Chromium, on the release host-sim
    // the tests above just built (a few seconds once Chromium is there).
    browser::run_task(&["--no-build".into()])?;
    // The firmware: QEMU replay of every model against host-sim (zero
    // mismatches, instruction budgets), then the board builds' sizes
    // (Nucleo-F411RE and Raspberry Pi Pico), then clippy on the firmware
    // builds for their targets.
    qemu::run_task(&[])?;
    // Field update in QEMU: loads, refusals, switches and rollbacks while
    // the PLC scans (about a minute once built).
    qemu_update::run_task(&[])?;
    // The guard forms on the target: node tables and sums of products
    // must agree on every evaluation (15 s once built).
    guard_bench::run_task(&[])?;
    size::run_task(&[])?;
    run(cargo().args([
        "clippy",
        "--release",
        "-p",
        "firmware",
        "--target",
        "thumbv7em-none-eabihf",
        "--",
        "-D",
        "warnings",
    ]))?;
    // The Nucleo's firmware with field update (slots in flash, the serial
    // link), on the press.
    run(size::Firmware::NUCLEO_FIELD_UPDATE
        .cargo("clippy")
        .args(["--", "-D", "warnings"])
        .env("PLC_PROJECT", "models/press.plc.toml"))?;
    // The Raspberry Pi Pico's firmware (RP2040, thumbv6m), on its press,
    // without and with field update.
    for pico in [size::Firmware::PICO, size::Firmware::PICO_FIELD_UPDATE] {
        run(pico
            .cargo("clippy")
            .args(["--", "-D", "warnings"])
            .env("PLC_PROJECT", "models/press_pico.plc.toml"))?;
    }
    run(cargo()
        .args([
            "clippy",
            "--release",
            "-p",
            "firmware",
            "--no-default-features",
            "--features",
            "qemu-update",
            "--target",
            "thumbv7em-none-eabihf",
            "--",
            "-D",
            "warnings",
        ])
        .envs(qemu_update::harness_env()))?;
    eprintln!("xtask: ci passed");
    Ok(())
}
