//! Symbolic (BDD) supervisor synthesis over plant and specification
//! components, without building their product.
//!
//! - [`encoding`]: the variable layout (component order, bits per state).
//! - [`relation`]: the [`Model`]: one partitioned transition relation per
//!   event, images and pre-images.
//! - [`reach`]: forward and backward reachability.
//! - [`supcon`]: the supremal controllable, nonblocking fixpoint.
//! - [`guards`]: one guard per controllable event.
//! - [`families`]: parametric families (ring, transfer line, dining
//!   philosophers).
//!
//! ```
//! let f = des_symbolic::families::ring(4).unwrap();
//! let s = des_symbolic::synthesize(&f.plants, &f.specs).unwrap();
//! assert!(s.supervisor_states() > 0u32.into());
//! ```

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod encoding;
pub mod error;
pub mod families;
pub mod guards;
pub mod reach;
pub mod relation;
pub mod supcon;

pub use biodivine_lib_bdd::Bdd;
pub use error::{Error, Result};
pub use guards::{Guard, GuardForm};
pub use num_bigint::BigUint;
pub use relation::Model;

use des::{Automaton, StateId};
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
}

/// Synthesises the supremal controllable, nonblocking supervisor of
/// `plants` ∥ `specs` symbolically.
pub fn synthesize(plants: &[Automaton], specs: &[Automaton]) -> Result<Synthesis> {
    let model = Model::new(plants, specs)?;
    let fixpoint = supcon::fixpoint(&model);
    let guards = guards::guards(&model, &fixpoint);
    Ok(Synthesis {
        model,
        fixpoint,
        guards,
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
