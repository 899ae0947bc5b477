//! Helpers for the end-to-end tests: build the real binaries once and run
//! them on the repository's models, as a user would.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The repository root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ sits in the repository root")
        .to_path_buf()
}

/// A model file of the repository, by path relative to the root.
pub fn model(relative: &str) -> PathBuf {
    repo().join(relative)
}

/// The `codegen` command, built once per test run.
pub fn codegen() -> Command {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    let bin = BIN.get_or_init(|| {
        escargot::CargoBuild::new()
            .manifest_path(repo().join("Cargo.toml"))
            .package("codegen-cli")
            .bin("codegen")
            .features("espresso")
            .run()
            .expect("codegen builds")
            .path()
            .to_path_buf()
    });
    let mut cmd = Command::new(bin);
    cmd.current_dir(repo());
    cmd
}

/// What a finished command printed, decoded.
pub struct Run {
    /// Exit code (-1 if killed by a signal).
    pub code: i32,
    /// Standard output.
    pub stdout: String,
    /// Standard error.
    pub stderr: String,
}

impl From<Output> for Run {
    fn from(o: Output) -> Run {
        Run {
            code: o.status.code().unwrap_or(-1),
            stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
        }
    }
}

/// Runs `codegen` with `args`.
pub fn run_codegen<I, S>(args: I) -> Run
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    codegen()
        .args(args)
        .output()
        .expect("codegen starts")
        .into()
}

/// Runs `codegen --json` with `args` and parses standard output.
pub fn run_json<I, S>(args: I) -> (i32, serde_json::Value)
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let run: Run = codegen()
        .arg("--json")
        .args(args)
        .output()
        .expect("codegen starts")
        .into();
    let value = serde_json::from_str(&run.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}):\n{}\nstderr:\n{}", run.stdout, run.stderr));
    (run.code, value)
}

/// Runs `codegen` with `args` as `codegen … | head -0` would: the reader
/// of its standard output is gone before it prints anything.
pub fn run_with_closed_stdout<I, S>(args: I) -> Run
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let mut child = codegen()
        .args(args)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("codegen starts");
    // Closing the only read end makes every write to the pipe fail with
    // EPIPE (Rust programs ignore SIGPIPE, so they see the error).
    drop(child.stdout.take());
    child.wait_with_output().expect("codegen finishes").into()
}
