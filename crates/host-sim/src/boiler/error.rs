//! What can go wrong running the boiler against a controller, checking a
//! record or writing one out.

use crate::sim::SimError;

/// A problem running a plant against a controller, checking a record or
/// writing it out.
#[derive(Debug, thiserror::Error)]
pub enum BoilerError {
    /// The project lacks some of the boiler's signals.
    #[error("project `{project}` lacks the boiler's {}", missing.join(", "))]
    MissingSignals {
        /// The project's name.
        project: String,
        /// `input `name`` or `output `name`` for each one missing.
        missing: Vec<String>,
    },
    /// Driving the simulation failed (backends diverged, say).
    #[error(transparent)]
    Sim(#[from] SimError),
    /// A raw image of the wrong width.
    #[error("expected {expected} {what} values, got {got}")]
    ImageWidth {
        /// `input` or `output`.
        what: &'static str,
        /// Signals of the project.
        expected: usize,
        /// Values given.
        got: usize,
    },
    /// A replay with more input rows than trace rows or the reverse.
    #[error("{inputs} input rows but {trace} trace rows")]
    RowCount {
        /// Input rows.
        inputs: usize,
        /// Trace rows.
        trace: usize,
    },
    /// Writing a record (its waveform, say) failed.
    #[error("writing the record: {0}")]
    Write(#[from] std::io::Error),
}
