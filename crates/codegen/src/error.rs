//! Errors of code generation: what lowering, the backends, emission and
//! the build-script API refuse, each with its own variant and the
//! location it is about attached once, where it is found.
//!
//! A project that cannot be read or is invalid, or an automaton operation
//! that fails, is the front end's and the automaton layer's
//! [`des::Error`], carried unchanged in [`Error::Model`].

use crate::backend::logic::{LogicError, UNAVAILABLE};
use crate::backend::Backend;
use des::error::Location;
use plc_project::paths::UnprintablePath;
use std::path::PathBuf;

/// Everything generation can refuse.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The project or one of its model files cannot be read or is
    /// invalid, an automaton operation failed, or a file could not be
    /// written: the automaton layer's error, its message unchanged (it
    /// names its file, and its line where there is one).
    #[error(transparent)]
    Model(#[from] des::Error),

    /// A count or pool of the executor's configuration does not fit its
    /// 16-bit indices. No one line is to blame, so the project file is
    /// named.
    #[error("{}: too many {what} for the executor (at most {limit})", project.display())]
    TooMany {
        /// The project file.
        project: PathBuf,
        /// What there are too many of (`inputs`, `event lists`, `input
        /// masks`, …).
        what: &'static str,
        /// The most the executor can index.
        limit: usize,
    },

    /// A supervisor of the project has no initial state, so it cannot be
    /// laid out (validation refuses such a supervisor; a project built
    /// otherwise may still have one).
    #[error("{}: supervisor `{supervisor}` has no initial state", project.display())]
    NoInitialState {
        /// The project file.
        project: PathBuf,
        /// The supervisor's name.
        supervisor: String,
    },

    /// The project has Petri nets and the backend is not the table
    /// backend: a net's groups run in the net layout of the executor's
    /// tables, its counters are no automaton the other backends could
    /// write as code.
    #[error(
        "{location}: net `{net}`: Petri nets run on the table backend only, not the {} backend \
         (use `--backend table`)",
        .backend.name()
    )]
    TableOnly {
        /// The line of the first net's `[[net]]` entry.
        location: Location,
        /// The net's name.
        net: String,
        /// The backend asked for.
        backend: Backend,
    },

    /// The logic backend was asked for in a build without its minimiser
    /// (Espresso, the `espresso` feature); the message says how to build
    /// it.
    #[error("{UNAVAILABLE}")]
    LogicUnavailable,

    /// The logic backend could not produce (trustworthy) equations for a
    /// supervisor: too large, beyond its effort limit, or the minimiser
    /// failed.
    #[error("{location}: supervisor `{supervisor}`: {source}")]
    Logic {
        /// The supervisor's entry in the project file.
        location: Location,
        /// The supervisor's name.
        supervisor: String,
        /// What the logic backend says.
        source: LogicError,
    },

    /// The project file's own path cannot be named to cargo in a
    /// `cargo:rerun-if-changed` line ([`crate::build::printable_path`]).
    #[error(
        "the project file {file:?} cannot be named to cargo (`cargo:rerun-if-changed`): \
         {reason}; rename it"
    )]
    UnprintableProject {
        /// The project file.
        file: PathBuf,
        /// Why cargo would misread it.
        reason: UnprintablePath,
    },

    /// A model file of the project cannot be named to cargo in a
    /// `cargo:rerun-if-changed` line ([`crate::build::printable_path`]).
    #[error(
        "{project:?}: the model file {file:?} cannot be named to cargo \
         (`cargo:rerun-if-changed`): {reason}; rename it"
    )]
    UnprintableModel {
        /// The project file.
        project: PathBuf,
        /// The model file.
        file: PathBuf,
        /// Why cargo would misread it.
        reason: UnprintablePath,
    },

    /// [`crate::build::Build::generate`] has no directory to write to:
    /// not run from a build script (no `OUT_DIR`) and no
    /// [`crate::build::Build::out_dir`] given.
    #[error("OUT_DIR is not set: call Build::generate from a build script or set out_dir")]
    NoOutDir,

    /// The emitted Rust does not parse: a bug in the emitters, never the
    /// project's fault.
    #[error(
        "internal error: generated code does not parse ({source}); please report it with the \
         project file"
    )]
    Unparsable {
        /// The parser's complaint.
        source: syn::Error,
    },
    /// The image fails what generation proves of it
    /// ([`executor::validate::validate_generated`]: its structure, the
    /// agreement of its pools, its table entries, its stored allowed
    /// sets): a bug in the lowering, never the project's fault.
    #[error(
        "{}: internal error: {invalid}; please report it with the project file",
        project.display()
    )]
    GeneratedImage {
        /// The project file.
        project: std::path::PathBuf,
        /// Where and what.
        invalid: executor::validate::Invalid,
    },
    /// A build that needs a pin map ([`crate::build::Build::require_board`])
    /// of a project without a `[board]` section.
    #[error(
        "{}: no [board] section: the board firmware needs the pin of each signal (see docs/board.md)",
        project.display()
    )]
    NoBoard {
        /// The project file.
        project: PathBuf,
    },
}

/// Result with generation's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
