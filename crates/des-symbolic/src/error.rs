//! What can go wrong building or solving a symbolic model.

use thiserror::Error;

/// An error of this crate: bad input, never a panic.
#[derive(Debug, Error)]
pub enum Error {
    /// Two components disagree on an event's controllability.
    #[error("event `{event}` is controllable in `{first}` but uncontrollable in `{second}`")]
    Controllability {
        /// The event.
        event: String,
        /// The component where it is controllable.
        first: String,
        /// The component where it is uncontrollable.
        second: String,
    },
    /// A specification uses an event no plant component has.
    #[error("event `{event}` of the specification `{spec}` is in no plant component's alphabet")]
    SpecEvent {
        /// The event.
        event: String,
        /// The specification.
        spec: String,
    },
    /// No plant component was given.
    #[error("no plant component")]
    NoPlant,
    /// The model needs more BDD variables than the library offers.
    #[error("{needed} BDD variables needed, at most {limit} supported")]
    TooManyVariables {
        /// Variables the encoding needs.
        needed: usize,
        /// The library's limit.
        limit: usize,
    },
    /// A family was asked for with a size it is not defined for.
    #[error("family `{family}` needs n >= {min}, got {n}")]
    FamilySize {
        /// The family.
        family: &'static str,
        /// The smallest size.
        min: usize,
        /// The size asked for.
        n: usize,
    },
    /// A component state tuple had the wrong length or an out-of-range state.
    #[error("state tuple does not fit the model: {0}")]
    StateTuple(String),
    /// An event name the model does not know.
    #[error("unknown event `{0}`")]
    UnknownEvent(String),
    /// An automaton could not be built (e.g. it is nondeterministic).
    #[error(transparent)]
    Build(#[from] des::automaton::BuildError),
    /// An error of the `des` crate.
    #[error(transparent)]
    Des(#[from] des::Error),
}

/// Result with this crate's [`enum@Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
