//! `cargo xtask qemu-update`: the field-update harness in QEMU
//! (mps2-an386; `crates/firmware/src/bin/qemu_update/`), built for the
//! Cortex-M4 and for the Cortex-M0+ (both boards' instruction sets).
//!
//! The press is built in; the press with the lesson's state 7 is the
//! update (`codegen image --version 1.1.0`). Each records its scenario
//! with host-sim. The harness loads images over a simulated serial link
//! while the PLC scans (a corrupt one, a hostile one, the update, the
//! built-in image again), switches, restarts and rolls back, and prints
//! the transcript; it fails unless every step gives what it should and
//! every replayed scan matches host-sim.

use crate::qemu::{firmware_build, record, run_elf};
use crate::{codegen_cli, run, sysdeps, Result};

/// The built-in project and the update's.
const BUILT_IN: &str = "models/press.plc.toml";
const UPDATE: &str = "models/press7.plc.toml";

pub fn run_task(_args: &[String]) -> Result {
    let qemu = sysdeps::ensure_qemu()?;
    let dir = crate::target_dir().join("qemu-update");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let built_in = record("press", BUILT_IN, None, &dir)?;
    let update = record("press7", UPDATE, None, &dir)?;
    let slot = dir.join("press7.slot");
    run(codegen_cli(&[])
        .args(["image", UPDATE, "-o"])
        .arg(&slot)
        .args(["--version", "1.1.0"]))?;
    // The Cortex-M4 build (the Nucleo's instruction set), then the
    // Cortex-M0+ one (the Pico's): ARMv6-M is a subset of ARMv7-M, so its
    // image runs on the same machine.
    for target in ["thumbv7em-none-eabihf", "thumbv6m-none-eabi"] {
        let mut cmd = firmware_build("qemu-update", "qemu-update", target);
        cmd.env("PLC_PROJECT", BUILT_IN)
            .env("PLC_BACKEND", "table")
            .env("PLC_SCENARIO", &built_in)
            .env("PLC_UPDATE_SCENARIO", &update)
            .env("PLC_UPDATE_IMAGE", &slot);
        run(&mut cmd)?;
        let elf = crate::target_dir().join(format!("{target}/release/qemu-update"));
        let copy = dir.join(format!("qemu-update-{target}.elf"));
        std::fs::copy(&elf, &copy).map_err(|e| format!("{}: {e}", copy.display()))?;
        let (status, stdout) = run_elf(&qemu, &copy)?;
        let last = stdout
            .lines()
            .rev()
            .find(|l| l.starts_with("update: loads="))
            .ok_or_else(|| format!("{}: no result line (exit {status})", copy.display()))?;
        if !(status.success() && last.contains(" mismatches=0 ") && last.ends_with(" failures=0")) {
            return Err(format!("qemu-update ({target}): {last} (exit {status})"));
        }
        eprintln!("xtask: qemu-update passed on {target}");
    }
    Ok(())
}

/// The environment the harness's build needs, for a clippy run after
/// [`run_task`] wrote the files.
pub fn harness_env() -> [(&'static str, std::path::PathBuf); 4] {
    let dir = crate::target_dir().join("qemu-update");
    [
        ("PLC_PROJECT", BUILT_IN.into()),
        ("PLC_SCENARIO", dir.join("press.scenario")),
        ("PLC_UPDATE_SCENARIO", dir.join("press7.scenario")),
        ("PLC_UPDATE_IMAGE", dir.join("press7.slot")),
    ]
}
