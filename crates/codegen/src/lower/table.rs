//! The table backend's lowered form: every supervisor (and every group of
//! a Petri net) as a bit-packed table, under the image CRC.

use super::config::ConfigPools;
use super::nets::NetGroups;
use crate::backend::table::EncodedTable;
use crate::error::Result;
use executor::image::table_image_crc;
use executor::program::{Config, Index, Program};
use executor::table::SupervisorTable;
use plc_project::{Project, Supervisor};

/// A project as bit-packed tables, runnable on the host.
#[derive(Debug, Clone)]
pub struct TableImage {
    /// The configuration.
    pub pools: ConfigPools,
    /// One table per supervisor.
    pub tables: Vec<EncodedTable>,
    /// The image CRC recorded at generation.
    pub crc: u32,
}

impl TableImage {
    /// Encodes `project`.
    pub fn new(project: &Project) -> Result<TableImage> {
        let pools = ConfigPools::from_project(project)?;
        let tables: Vec<EncodedTable> = project
            .supervisors
            .iter()
            .map(encode_supervisor)
            .chain((0..project.nets.len()).flat_map(|n| {
                let net = NetGroups {
                    net: &project.nets[n],
                    layout: &pools.nets[n],
                };
                (0..net.groups()).map(move |g| net.encode(g))
            }))
            .collect();
        let views: Vec<SupervisorTable<'_>> = tables.iter().map(EncodedTable::view).collect();
        let crc = table_image_crc(&pools.config(), &views);
        Ok(TableImage { pools, tables, crc })
    }

    /// Recomputes the CRC of the current contents.
    pub fn computed_crc(&self) -> u32 {
        executor::image::crc(self)
    }
}

/// The table of supervisor `s`: its automaton, events in local order.
pub(super) fn encode_supervisor(s: &Supervisor) -> EncodedTable {
    let local: Vec<_> = s.local_events.iter().map(|&(_, id)| id).collect();
    EncodedTable::encode(&s.automaton, &local)
}

/// δ of supervisor `supervisor` read from `tables` ([`Program::next_state`]
/// of every lowered form that runs tables on the host).
#[inline]
pub(super) fn next_state(
    tables: &[EncodedTable],
    supervisor: Index,
    state: u32,
    local: Index,
) -> Option<u32> {
    tables
        .get(usize::from(supervisor))?
        .view()
        .next_state(state, local)
}

/// The row of defined-bits of supervisor `supervisor` read from `tables`
/// ([`Program::enabled`]); 0 past the last table.
#[inline]
pub(super) fn enabled(
    tables: &[EncodedTable],
    supervisor: Index,
    state: u32,
    from: Index,
    len: u8,
) -> u32 {
    tables
        .get(usize::from(supervisor))
        .map_or(0, |t| t.view().enabled(state, from, len))
}

impl Program for TableImage {
    fn config(&self) -> Config<'_> {
        self.pools.config()
    }

    #[inline]
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        next_state(&self.tables, supervisor, state, local)
    }

    #[inline]
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        enabled(&self.tables, supervisor, state, from, len)
    }

    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>> {
        self.tables
            .get(usize::from(supervisor))
            .map(EncodedTable::view)
    }

    fn recorded_crc(&self) -> u32 {
        self.crc
    }
}
