//! `cargo xtask matiec`: the exported programs compiled by matiec, the
//! IEC 61131-3 compiler of OpenPLC's runtime and of the Beremiz IDE, and
//! run in lockstep with host-sim (`tests/matiec_lockstep.rs`).
//!
//! matiec is a test tool the project runs but never contains: it is built
//! once into `target/matiec` from `../shared/tools/matiec` (OpenPLC's copy
//! of the compiler, with its `build.sh`, which installs flex, bison, the
//! autotools and g++ with apt when they are missing), then the ignored
//! tests of `matiec_lockstep` run with `MATIEC_DIR` naming the build.

use crate::{cargo, root, run, sysdeps, target_dir, Result};
use std::path::PathBuf;
use std::process::Command;

/// The folder of the matiec sources and their build script, beside the
/// repository.
fn shared_tool() -> PathBuf {
    root().join("../shared/tools/matiec")
}

pub fn run_task(args: &[String]) -> Result {
    if !args.is_empty() {
        return Err("usage: cargo xtask matiec".into());
    }
    let started = std::time::Instant::now();
    let dir = build()?;
    if Command::new("gcc").arg("--version").output().is_err() {
        sysdeps::apt_install(&["gcc", "libc6-dev"])?;
    }
    run(cargo()
        .args([
            "test",
            "-p",
            "e2e",
            "--test",
            "matiec_lockstep",
            "--",
            "--include-ignored",
            "--nocapture",
            "--test-threads",
            "2",
        ])
        .env("MATIEC_DIR", &dir))?;
    eprintln!(
        "xtask: matiec compiled and ran every project in {:.0} s",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// matiec built into `target/matiec` (kept between runs), its folder.
fn build() -> Result<PathBuf> {
    let dir = target_dir().join("matiec");
    if dir.join("iec2c").is_file() {
        return Ok(dir);
    }
    let script = shared_tool().join("build.sh");
    if !script.is_file() {
        return Err(format!(
            "{}: missing; matiec's sources and build script come with the team's shared/ folder beside the repository",
            script.display()
        ));
    }
    // A half-built folder from an interrupted run would be taken as done
    // by nothing, but would make the unpacking fail: start clean.
    if dir.exists() {
        std::fs::remove_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    run(Command::new("bash").arg(&script).arg(&dir))?;
    if dir.join("iec2c").is_file() {
        Ok(dir)
    } else {
        Err(format!("{}: the build left no iec2c", dir.display()))
    }
}
