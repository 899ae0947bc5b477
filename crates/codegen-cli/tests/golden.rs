//! Golden files: the generated Rust of every seed project on every
//! backend, exactly as `codegen gen models/<project>.plc.toml --backend
//! <backend>` prints it, pinned in `tests/golden/<project>.<backend>.rs`.
//!
//! Any change to the emitted text (code, doc comments or layout) fails
//! here with a unified diff of the golden file against the new output.
//! When the change is intended, rewrite the files and review their diff
//! in version control:
//!
//! ```text
//! UPDATE_GOLDEN=1 cargo test -p codegen-cli --test golden
//! ```
//!
//! The golden files are data for a reader to open: no target compiles
//! them (cargo builds only `tests/*.rs` and `tests/*/main.rs`) and no
//! `mod` reaches them, so `cargo fmt` leaves them alone. The same
//! programs are compiled and run by `tests/generated.rs` of package `e2e`.

use similar::TextDiff;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository root, where the README's commands run.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The output of `codegen gen models/<project>.plc.toml --backend
/// <backend>`, run from the repository root.
fn codegen_gen(project: &str, backend: &str) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_codegen"))
        .current_dir(root())
        .args(["gen", &format!("models/{project}.plc.toml")])
        .args(["--backend", backend])
        .output()
        .expect("the codegen binary runs");
    assert!(
        output.status.success(),
        "codegen gen {project} --backend {backend} failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("generated code is UTF-8")
}

/// Checks `actual` against the golden file `name`, or with
/// `UPDATE_GOLDEN` set writes it there.
fn check_golden(name: &str, actual: &str) {
    let relative = format!("crates/codegen-cli/tests/golden/{name}");
    let path = root().join(&relative);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, actual).expect("the golden file is writable");
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    if expected != actual {
        let diff = TextDiff::from_lines(&expected, actual);
        panic!(
            "the generated code differs from {relative}:\n\n{}\n\
             If the change is intended: UPDATE_GOLDEN=1 cargo test -p codegen-cli --test golden",
            diff.unified_diff()
                .header(&relative, "generated")
                .context_radius(3)
        );
    }
}

/// One test per (project, backend): the generated code is byte for byte
/// its golden file.
macro_rules! golden {
    ($($test:ident: $project:literal, $backend:literal;)*) => {$(
        #[test]
        fn $test() {
            check_golden(
                concat!($project, ".", $backend, ".rs"),
                &codegen_gen($project, $backend),
            );
        }
    )*};
}

golden! {
    motivating_table: "motivating", "table";
    motivating_logic: "motivating", "logic";
    motivating_match: "motivating", "match";
    press_table: "press", "table";
    press_logic: "press", "logic";
    press_match: "press", "match";
    press7_table: "press7", "table";
    press7_logic: "press7", "logic";
    press7_match: "press7", "match";
    conveyor_table: "conveyor", "table";
    conveyor_logic: "conveyor", "logic";
    conveyor_match: "conveyor", "match";
    crane_table: "crane", "table";
    crane_logic: "crane", "logic";
    crane_match: "crane", "match";
}

/// A Petri net (seed D's mixing tanks, its control place synthesised at
/// build time) in the table backend's net layout.
#[test]
fn mixers_table() {
    check_golden("mixers.table.rs", &codegen_gen("petri/mixers", "table"));
}

/// Seed D's batch process cell: 47 places in two groups, 24 place maps.
#[test]
fn cell_table() {
    check_golden("cell.table.rs", &codegen_gen("petri/cell/cell", "table"));
}

/// The output of `codegen <args>`, run from the repository root.
fn codegen(args: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_codegen"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("the codegen binary runs");
    assert!(
        output.status.success(),
        "codegen {args:?} failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("UTF-8")
}

/// The Structured Text export (`codegen st`) of the motivating example,
/// the press (timers, debounce, a state map) and the mixers (a net).
#[test]
fn structured_text() {
    for project in ["motivating", "press", "petri/mixers"] {
        let name = project.rsplit('/').next().expect("a name");
        check_golden(
            &format!("{name}.st"),
            &codegen(&["st", &format!("models/{project}.plc.toml")]),
        );
    }
}
