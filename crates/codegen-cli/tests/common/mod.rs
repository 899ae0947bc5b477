//! What the CLI tests share: the repository root, running the `codegen`
//! binary there, and the small factory's files and supervisor.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

pub const MACH1: &str = "models/bench/smallfactory/MACH1.gen";
pub const MACH2: &str = "models/bench/smallfactory/MACH2.gen";
pub const BUFSPEC: &str = "models/bench/smallfactory/BUFSPEC.gen";
pub const BRSPEC: &str = "models/bench/smallfactory/BRSPEC.gen";

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Exit code, standard output and standard error of `codegen args…`, run
/// from the repository root.
pub fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_codegen"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("the codegen binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The small factory's supcon supervisor, written into `dir`.
pub fn supervisor(dir: &Path) -> String {
    let out = dir.join("sup.gen").display().to_string();
    let args = [
        "synth", "--plant", MACH1, MACH2, "--spec", BUFSPEC, BRSPEC, "-o", &out,
    ];
    assert_eq!(run(&args).0, 0);
    out
}
