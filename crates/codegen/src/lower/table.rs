//! The table backend's lowered form: every supervisor (and every group of
//! a Petri net) as a bit-packed table, under the image CRC.

use super::config::ConfigPools;
use crate::backend::table::EncodedTable;
use crate::error::Result;
use executor::image::table_image_crc;
use executor::program::{Config, Index, Program};
use executor::table::SupervisorTable;
use plc_project::Project;

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
            .map(|s| {
                let local: Vec<_> = s.local_events.iter().map(|&(_, id)| id).collect();
                EncodedTable::encode(&s.automaton, &local)
            })
            .chain(
                project
                    .nets
                    .iter()
                    .flat_map(|net| (0..net.groups()).map(|g| EncodedTable::encode_net(net, g))),
            )
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

impl Program for TableImage {
    fn config(&self) -> Config<'_> {
        self.pools.config()
    }

    #[inline]
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        self.tables
            .get(supervisor as usize)?
            .view()
            .next_state(state, local)
    }

    #[inline]
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        self.tables
            .get(supervisor as usize)
            .map_or(0, |t| t.view().enabled(state, from, len))
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
