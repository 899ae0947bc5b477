//! The `match` backend's lowered form: the supervisors are code on the
//! target (one `match` per supervisor, written from the automata), so the
//! image is the configuration alone. On the host the same automata run as
//! tables kept outside the image.

use super::config::ConfigPools;
use super::table::{self, encode_supervisor};
use super::table_only;
use crate::backend::table::EncodedTable;
use crate::backend::Backend;
use crate::error::Result;
use executor::image::config_crc;
use executor::program::{Config, Index, Program};
use executor::table::SupervisorTable;
use plc_project::Project;

/// A project for the `match` backend, runnable on the host.
#[derive(Debug, Clone)]
pub struct MatchImage {
    /// The configuration.
    pub pools: ConfigPools,
    /// Each supervisor's transition function, as a table the host runs;
    /// not part of the image (on the target it is code).
    pub automata: Vec<EncodedTable>,
    /// The configuration CRC recorded at generation.
    pub crc: u32,
}

impl MatchImage {
    /// Lowers `project` (refused if it has Petri nets: [`table_only`]).
    pub fn new(project: &Project) -> Result<MatchImage> {
        table_only(project, Backend::Match)?;
        let pools = ConfigPools::from_project(project)?;
        let automata = project.supervisors.iter().map(encode_supervisor).collect();
        let crc = config_crc(&pools.config());
        Ok(MatchImage {
            pools,
            automata,
            crc,
        })
    }
}

impl Program for MatchImage {
    fn config(&self) -> Config<'_> {
        self.pools.config()
    }

    #[inline]
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        table::next_state(&self.automata, supervisor, state, local)
    }

    #[inline]
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        table::enabled(&self.automata, supervisor, state, from, len)
    }

    /// None: the supervisors are code, outside the image.
    fn table(&self, _supervisor: Index) -> Option<SupervisorTable<'_>> {
        None
    }

    fn recorded_crc(&self) -> u32 {
        self.crc
    }
}
