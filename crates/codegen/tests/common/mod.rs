//! Project files given as text in the tests (`project.rs`, `board.rs`):
//! loading them as if they were `tests/fixtures/project/t.plc.toml`, and
//! checking that each error names the line marked `# <-`.

#![allow(dead_code)] // each test crate uses its own part

use des::Error;
use plc_project::{self as project, Project};
use std::path::{Path, PathBuf};

/// The fixture directory of the project tests.
pub fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project")
}

/// A file of the fixture directory.
pub fn fixture(name: &str) -> PathBuf {
    dir().join(name)
}

/// A project given as text, placed (virtually) in the fixture directory.
pub fn load_text(text: &str) -> Result<Project, Error> {
    project::from_str(text, &fixture("t.plc.toml"))
}

/// [`load_text`] that must succeed.
pub fn load_ok(text: &str) -> Project {
    load_text(text).unwrap_or_else(|e| panic!("{e}\n---\n{text}"))
}

/// [`load_text`] that must fail; the error message.
pub fn load_err(text: &str) -> String {
    match load_text(text) {
        Ok(_) => panic!("expected an error for\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// The line marked `# <-` in `text` (1-based).
pub fn marked_line(text: &str) -> usize {
    text.lines()
        .position(|l| l.contains("# <-"))
        .map(|i| i + 1)
        .unwrap_or_else(|| panic!("no `# <-` marker in\n{text}"))
}

/// Each `(text, expected)` must fail to load with an error that names
/// `t.plc.toml` at the line marked `# <-` and contains `expected`; all
/// the cases that do not are reported together.
pub fn assert_errors_at_marked_lines<'a>(cases: impl IntoIterator<Item = (String, &'a str)>) {
    let mut failures = Vec::new();
    for (text, expected) in cases {
        let line = marked_line(&text);
        let msg = load_err(&text);
        let at = format!("t.plc.toml:{line}:");
        if !msg.contains(&at) || !msg.contains(expected) {
            failures.push(format!(
                "expected `{at}` and `{expected}`\n     got `{msg}`\n---\n{text}---"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
