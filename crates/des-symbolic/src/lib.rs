//! Symbolic (BDD) supervisor synthesis over plant and specification
//! components, without building their product.
//!
//! - [`encoding`]: the variable layout: `⌈log2 n⌉` bits per component,
//!   current and next copies interleaved, components in a Cuthill–McKee
//!   order of the component–event graph.
//! - [`relation`]: the [`Model`]: one partitioned transition relation per
//!   event over its participants only, images and pre-images.
//! - [`reach`]: forward and backward reachability (chained).
//! - [`supcon`]: the supremal controllable, nonblocking fixpoint.
//! - [`guards`]: one guard per controllable event, simplified against the
//!   closed loop's states.
//! - [`families`]: parametric families (ring, ring with breakdowns,
//!   transfer line, dining philosophers, a Prenzel–Provost-class module).
//! - [`verify`]: nonblocking (nonconflict) of plants and supervisors, with
//!   a shortest string into a blocking state.
//! - [`guard_file`]: the guards as a file a target runs (`*.guards.toml`).
//!
//! State counts are exact ([`BigUint`], from the library's exact
//! cardinality); node counts are the library's, terminals included.
//!
//! ```
//! let f = des_symbolic::families::ring(4).unwrap();
//! let s = des_symbolic::synthesize(&f.plants, &f.specs).unwrap();
//! assert!(s.supervisor_states() > 0u32.into());
//! ```
//!
//! # The BDD library
//!
//! biodivine-lib-bdd 0.6, chosen over oxidd 0.13 by measurement:
//! `examples/bddlibs.rs` (feature `compare-bdd`) runs the same forward
//! reachability (partitioned relations, chaining, fused and-exists, then
//! renaming) on both, one library per process, release build, one
//! thread, on 2 cores (oxidd: default features, manager of 2^22 nodes and
//! 2^20 cache entries). Time as printed, peak RSS from `/usr/bin/time -v`:
//!
//! | instance | reachable states | nodes | biodivine | oxidd |
//! |---|---:|---:|---|---|
//! | ring20 | 847,660,528 | 342 | 0.22 s, 3.1 MB | 0.33 s, 39 MB |
//! | ring40 | 3.5·10^18 | 1,282 | 11.7 s, 5.8 MB | 37.3 s, 164 MB |
//! | ringb13 | 10,215,348 | 301 | 0.07 s, 2.8 MB | 0.08 s, 32 MB |
//! | ringb20 | 42,872,967,012 | 650 | 0.78 s, 3.3 MB | 1.84 s, 80 MB |
//! | ringb40 | 8.9·10^21 | 2,502 | 43.8 s, 10 MB | 64.0 s, 160 MB |
//! | phil40 | 2.0·10^15 | 704 | 0.015 s, 3.1 MB | 0.026 s, 30 MB |
//! | tline40 | 6.7·10^30 | 82 | 3.7 s, 4.1 MB | 8.7 s, 161 MB |
//!
//! biodivine was faster on every instance and an order of magnitude
//! leaner; both APIs do the relational product (biodivine's
//! `binary_op_with_exists`, oxidd's `apply_exists`). biodivine has no
//! shared node table, so renaming is a relabelling of the nodes (safe:
//! `to_nodes`/`from_nodes`), which the interleaved order makes exact.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod encoding;
pub mod error;
pub mod families;
pub mod guard_file;
pub mod guards;
pub mod reach;
pub mod relation;
pub mod supcon;
pub mod verify;

pub use biodivine_lib_bdd::Bdd;
pub use error::{Error, Result};
pub use guards::{Guard, GuardForm};
pub use num_bigint::BigUint;
pub use relation::Model;

use des::{Automaton, StateId};
use std::time::{Duration, Instant};
use supcon::Fixpoint;

/// The result of [`synthesize`]: the model, the fixpoint's sets and the
/// guards.
#[derive(Debug, Clone)]
pub struct Synthesis {
    /// The symbolic model of plants ∥ specifications.
    pub model: Model,
    /// Reachable, good and closed-loop states.
    pub fixpoint: Fixpoint,
    /// One guard per controllable event.
    pub guards: Vec<Guard>,
    /// Time per phase.
    pub timings: Timings,
}

/// How long each phase of [`synthesize`] took.
#[derive(Debug, Clone, Copy, Default)]
pub struct Timings {
    /// Building the relations.
    pub model: Duration,
    /// Reachability and the fixpoint.
    pub fixpoint: Duration,
    /// Computing and simplifying the guards.
    pub guards: Duration,
}

/// Synthesises the supremal controllable, nonblocking supervisor of
/// `plants` ∥ `specs` symbolically.
pub fn synthesize(plants: &[Automaton], specs: &[Automaton]) -> Result<Synthesis> {
    let start = Instant::now();
    let model = Model::new(plants, specs)?;
    let built = Instant::now();
    let fixpoint = supcon::fixpoint(&model);
    let solved = Instant::now();
    let guards = guards::guards(&model, &fixpoint);
    let timings = Timings {
        model: built - start,
        fixpoint: solved - built,
        guards: solved.elapsed(),
    };
    Ok(Synthesis {
        model,
        fixpoint,
        guards,
        timings,
    })
}

impl Synthesis {
    /// States of plant ∥ specifications reachable without control.
    pub fn reachable_states(&self) -> BigUint {
        self.model.count(&self.fixpoint.reachable)
    }

    /// States of the closed loop (0 when the supervisor is empty).
    pub fn supervisor_states(&self) -> BigUint {
        self.model.count(&self.fixpoint.supervisor)
    }

    /// Whether the supervisor is empty (no controllable, nonblocking
    /// behaviour meets the specifications).
    pub fn is_empty(&self) -> bool {
        self.fixpoint.supervisor.is_false()
    }

    /// Nodes of the guards' BDDs, summed.
    pub fn guard_nodes(&self) -> usize {
        self.guards.iter().map(|g| g.bdd.size()).sum()
    }

    /// The guard of the event named `event` (`None` for an uncontrollable
    /// event, which needs none).
    pub fn guard(&self, event: &str) -> Result<Option<&Guard>> {
        let e = self
            .model
            .layout()
            .event(event)
            .ok_or_else(|| Error::UnknownEvent(event.to_owned()))?;
        Ok(self.guards.iter().find(|g| g.event == e))
    }

    /// May `event` fire in the component states `states` (plants, then
    /// specifications, in input order)? Uncontrollable events always may;
    /// whether the components enable it is not asked.
    pub fn allows(&self, event: &str, states: &[StateId]) -> Result<bool> {
        match self.guard(event)? {
            None => {
                self.model.layout().check_tuple(states)?;
                Ok(true)
            }
            Some(g) => self.model.contains(&g.bdd, states),
        }
    }
}
