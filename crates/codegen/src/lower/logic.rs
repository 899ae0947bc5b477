//! The logic backend's lowered form: every supervisor as minimised CMSSM
//! covers, evaluated directly on the host; the image is the configuration.

use super::config::ConfigPools;
use super::table_only;
use crate::backend::logic::{Encoding, LogicError, LogicSupervisor, Minimisation, Settings};
use des::error::{Error, Location, Result};
use des::ops::Progress;
use executor::image::config_crc;
use executor::program::{Config, Index, Program};
use executor::table::SupervisorTable;
use plc_project::Project;

/// A project as CMSSM logic (the minimised covers evaluated directly),
/// runnable on the host. States are binary codes equal to the state
/// indices, so traces match [`TableImage`].
#[derive(Debug, Clone)]
pub struct LogicImage {
    /// The configuration.
    pub pools: ConfigPools,
    /// One CMSSM per supervisor.
    pub supervisors: Vec<LogicSupervisor>,
    /// The configuration CRC recorded at generation.
    pub crc: u32,
}

impl LogicImage {
    /// Synthesises (and verifies) the logic of every supervisor.
    pub fn new(project: &Project) -> Result<LogicImage> {
        Self::with_progress(project, &())
    }

    /// [`LogicImage::new`], telling `progress` which supervisor and phase
    /// it is working on.
    pub fn with_progress(project: &Project, progress: &dyn Progress) -> Result<LogicImage> {
        table_only(project, "logic")?;
        let pools = ConfigPools::from_project(project)?;
        let supervisors = project
            .supervisors
            .iter()
            .map(|s| {
                let local: Vec<_> = s.local_events.iter().map(|&(_, id)| id).collect();
                let settings = Settings {
                    minimisation: Minimisation::PerFunction,
                    max_effort: crate::backend::logic::effort_limit(s.max_logic_effort),
                };
                LogicSupervisor::synthesize_reporting(
                    &s.automaton,
                    &local,
                    Encoding::binary(s.automaton.num_states()),
                    &settings,
                    progress,
                )
                .map_err(|e| match e {
                    LogicError::Unavailable => Error::Incompatible(e.to_string()),
                    e => Error::model(
                        Location::new(&project.path, s.line, 0),
                        format!("supervisor `{}`: {e}", s.name),
                    ),
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let crc = config_crc(&pools.config());
        Ok(LogicImage {
            pools,
            supervisors,
            crc,
        })
    }
}

impl Program for LogicImage {
    fn config(&self) -> Config<'_> {
        self.pools.config()
    }

    #[inline]
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        self.supervisors
            .get(supervisor as usize)?
            .next_state(state, local)
    }

    /// The φ functions alone, without computing the next states.
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        let Some(s) = self.supervisors.get(supervisor as usize) else {
            return 0;
        };
        (0..u16::from(len.min(32))).fold(0, |row, k| {
            row | u32::from(s.is_defined(state, from.wrapping_add(k))) << k
        })
    }

    fn table(&self, _supervisor: Index) -> Option<SupervisorTable<'_>> {
        None
    }

    fn recorded_crc(&self) -> u32 {
        self.crc
    }
}
