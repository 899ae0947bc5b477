//! `cargo xtask example`: the user's-crate example (`examples/my-plc/`),
//! a crate outside the workspace that depends on `executor` (and
//! `codegen`, for its build script) by path, built as its README tells a
//! user to, with every warning an error (`RUSTFLAGS=-D warnings` on top of
//! the crate's own `#![deny(warnings)]`):
//!
//! 1. its `rust-toolchain.toml` is the workspace's (a copy of the
//!    directory builds with the pinned toolchain), and `cargo fmt
//!    --check`: it is what a user copies;
//! 2. `cargo run`: the generated program compiles warning-free in a
//!    foreign crate that uses only some of its items, and the trace the
//!    run prints is the one the example's README shows;
//! 3. `cargo clippy --all-targets -- -D warnings`: clippy's default lints
//!    on the generated file too;
//! 4. the board binary (`--features board --bin board`) for the
//!    Cortex-M4.
//!
//! Its own target directory (`target/my-plc`): the flags differ from the
//! workspace's, so sharing one would rebuild both each time.

use crate::{describe, root, target_dir, Result};
use std::path::Path;
use std::process::Command;

/// The example crate, from the workspace root.
pub const DIR: &str = "examples/my-plc";

/// The header line of the trace the example prints, which starts the
/// trace its README shows.
const TRACE_HEADER: &str = "scan  time_ms  ls  events          belt";

/// Runs the task.
pub fn run_task(args: &[String]) -> Result {
    if !args.is_empty() {
        return Err("usage: cargo xtask example".into());
    }
    let dir = root().join(DIR);
    let target = target_dir().join("my-plc");
    let readme = std::fs::read_to_string(dir.join("README.md"))
        .map_err(|e| format!("{DIR}/README.md: {e}"))?;
    let expected = shown_trace(&readme)?;

    same_toolchain(&dir)?;
    crate::run(crate::cargo().current_dir(&dir).args(["fmt", "--check"]))?;
    let out = output(&mut cargo(&dir, &target, "run"))?;
    print!("{out}");
    let printed: Vec<&str> = out.lines().map(str::trim_end).collect();
    if printed != expected {
        return Err(format!(
            "the example printed\n{}\nbut {DIR}/README.md shows\n{}",
            printed.join("\n"),
            expected.join("\n")
        ));
    }
    crate::run(cargo(&dir, &target, "clippy").args(["--all-targets", "--", "-D", "warnings"]))?;
    crate::run(cargo(&dir, &target, "build").args([
        "--features",
        "board",
        "--bin",
        "board",
        "--target",
        "thumbv7em-none-eabihf",
    ]))?;
    eprintln!(
        "xtask: {DIR} builds warning-free (host and board) and prints the trace its README shows"
    );
    Ok(())
}

/// Fails unless the example pins the workspace's toolchain: its
/// `rust-toolchain.toml` is a copy of the root's.
fn same_toolchain(dir: &Path) -> Result {
    let read =
        |path: &Path| std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()));
    if read(&root().join("rust-toolchain.toml"))? == read(&dir.join("rust-toolchain.toml"))? {
        Ok(())
    } else {
        Err(format!(
            "{DIR}/rust-toolchain.toml differs from the workspace's: copy rust-toolchain.toml there"
        ))
    }
}

/// `cargo <command>` in the example's directory (so that its
/// `.cargo/config.toml` applies, as for a user), with its lock file as
/// committed, every warning an error.
fn cargo(dir: &Path, target: &Path, command: &str) -> Command {
    let mut cmd = crate::cargo();
    cmd.current_dir(dir)
        .env("RUSTFLAGS", "-D warnings")
        .args([command, "--quiet", "--locked", "--target-dir"])
        .arg(target);
    cmd
}

/// The standard output of `cmd`, failing on a non-zero exit.
fn output(cmd: &mut Command) -> Result<String> {
    eprintln!("$ {}", describe(cmd));
    let out = cmd
        .stderr(std::process::Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot start {}: {e}", describe(cmd)))?;
    if !out.status.success() {
        return Err(format!("`{}` failed ({})", describe(cmd), out.status));
    }
    String::from_utf8(out.stdout).map_err(|e| format!("`{}`: {e}", describe(cmd)))
}

/// The trace `readme` shows: the lines from [`TRACE_HEADER`] to the end
/// of its code block.
fn shown_trace(readme: &str) -> Result<Vec<&str>> {
    let start = readme
        .find(TRACE_HEADER)
        .ok_or_else(|| format!("{DIR}/README.md shows no trace (`{TRACE_HEADER}`)"))?;
    let block = &readme[start..];
    let end = block
        .find("\n```")
        .ok_or_else(|| format!("{DIR}/README.md: the trace's code block does not end"))?;
    Ok(block[..end].lines().map(str::trim_end).collect())
}

#[cfg(test)]
mod tests {
    use super::shown_trace;

    #[test]
    fn the_shown_trace_runs_from_its_header_to_the_end_of_its_block() {
        let readme = "intro\n```text\n$ cargo run\nscan  time_ms  ls  events          belt\n   6  60  1  re_ls start  on  \n```\nafter\n";
        assert_eq!(
            shown_trace(readme).unwrap(),
            [
                "scan  time_ms  ls  events          belt",
                "   6  60  1  re_ls start  on"
            ]
        );
    }

    #[test]
    fn a_readme_without_the_trace_or_its_end_is_an_error() {
        assert!(shown_trace("no trace here").is_err());
        assert!(shown_trace("scan  time_ms  ls  events          belt\n 1 2 3").is_err());
    }
}
