//! Discrete-event systems: automata, their file formats and the
//! Ramadge–Wonham operations on them.
//!
//! - [`automaton`]: the automaton model (interned events, dense state ids,
//!   transitions in compressed sparse rows).
//! - [`formats`]: native TOML, libFAUDES `.gen`, TCT `.ads`, Waters `.wmod`.
//! - [`ops`]: synchronous composition, supcon, minstate, control data,
//!   controllability / nonblocking / nonconflict checks with witnesses,
//!   language equivalence, and the synthesis pipeline that chains them.
//! - [`petri`]: place/transition Petri nets (native TOML and PNML), their
//!   incidence matrix and reachability graph as an automaton.
//! - [`dot`]: DOT strings and the Graphviz layout engines.
//! - [`error`]: errors located by file, line and column.
//! - [`files`]: reading the files a user names: regular files only, each
//!   kind within its size limit.
//!
//! The crate knows nothing of PLCs, code generation or the executor: the
//! `codegen` crate builds on it.
//!
//! ```
//! use des::{ops, AutomatonBuilder};
//!
//! // A machine that starts (controllable) and finishes (uncontrollable).
//! let mut b = AutomatonBuilder::new("machine");
//! b.add_event("start", true).unwrap();
//! b.add_event("finish", false).unwrap();
//! b.set_initial_by_name("idle").unwrap();
//! b.add_transition_by_name("idle", "start", "working", 0).unwrap();
//! b.add_transition_by_name("working", "finish", "idle", 0).unwrap();
//! b.mark_by_name("idle");
//! let machine = b.build().unwrap();
//!
//! // With no specification the supervisor is the plant's nonblocking part.
//! let sup = ops::supcon(&machine, &machine).unwrap();
//! assert_eq!(sup.num_states(), 2);
//! ```

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod automaton;
pub mod dot;
pub mod error;
pub mod files;
pub mod formats;
pub mod ops;
pub mod petri;
#[cfg(any(test, feature = "testing"))]
pub mod testing;

pub use automaton::{Alphabet, Automaton, AutomatonBuilder, EventId, StateId};
pub use error::{Error, Location, Result};
