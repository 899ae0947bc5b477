//! PLC projects (`*.plc.toml`): which supervisors run and how their events
//! meet inputs, outputs and timers.
//!
//! [`load`] reads a project file, [`from_str`] parses one given as text;
//! both return a validated [`Project`] or the first error, located at its
//! line and column in the project file; [`load_shrunk`] loads one with its
//! synthesised supervisors reduced or localized ([`Shrink`]). Three
//! stages:
//!
//! 1. parsing: the TOML text into raw declarations that keep their spans;
//! 2. [`sources`]: the model file of every supervisor read, or the
//!    supervisor synthesised (every file recorded for `rerun-if-changed`);
//! 3. [`validate`]: the declarations and the supervisors' automata checked
//!    against each other (every rule, by topic).
//!
//! This is the front end: it reads and checks, and knows nothing of how a
//! project is lowered, generated or exported (`codegen`, `iec-export`).

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod ident;
mod locate;
mod model;
mod parse;
pub mod paths;
mod shrink;
pub mod sources;
pub mod validate;

pub use model::*;
pub use shrink::Shrink;

use des::error::Result;
use std::path::Path;

/// Project files as [`des::files`] reads them: a regular file of at most
/// 16 MiB (the largest project the executor's 16-bit indices allow, 65,535
/// events with their bindings, takes a few MiB).
pub const PROJECT_FILE: des::files::FileKind = des::files::FileKind::new("project file", 16 << 20);

/// Reads and validates the project file at `path` ([`PROJECT_FILE`]);
/// model paths in it are relative to its directory.
pub fn load(path: &Path) -> Result<Project> {
    let text = des::files::read_text(path, PROJECT_FILE)?;
    from_str(&text, path)
}

/// Parses and validates `text` as the project file at `path`: `path` names
/// the file in errors and [`Project::files`], and model paths in the text
/// are relative to its directory (the file itself need not exist).
pub fn from_str(text: &str, path: &Path) -> Result<Project> {
    build(parse::parse(text, path)?, text, path)
}

/// Reads the project file at `path` as [`load`] does, with every
/// supervisor that synthesises one automaton without `reduce` or
/// `localize` (and not `symbolic`) shrunk the `shrink` way, as if its
/// `synthesize` said so ([`Shrink`]). `None` when the project has no
/// such supervisor (loading it would give the project [`load`] gives).
pub fn load_shrunk(path: &Path, shrink: Shrink) -> Result<Option<Project>> {
    let text = des::files::read_text(path, PROJECT_FILE)?;
    from_str_shrunk(&text, path, shrink)
}

/// [`load_shrunk`] of `text` as the project file at `path` (as
/// [`from_str`]).
pub fn from_str_shrunk(text: &str, path: &Path, shrink: Shrink) -> Result<Option<Project>> {
    let mut raw = parse::parse(text, path)?;
    if shrink::apply(&mut raw, shrink) == 0 {
        return Ok(None);
    }
    build(raw, text, path).map(Some)
}

/// Stages 2 and 3 of a parsed project.
fn build(raw: parse::RawProject, text: &str, path: &Path) -> Result<Project> {
    let file = locate::ProjectFile::new(path, text);
    let sources = sources::load(&raw.supervisor, &raw.net, &file)?;
    validate::validate(raw, sources, &file)
}
