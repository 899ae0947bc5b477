//! The logic backend's lowered form: every supervisor as minimised CMSSM
//! covers, evaluated directly on the host; the image is the configuration.

use super::config::ConfigPools;
use super::table_only;
use crate::backend::logic::{Encoding, LogicError, LogicSupervisor, Minimisation, Settings};
use crate::backend::Backend;
use crate::error::{Error, Result};
use des::error::Location;
use des::ops::Progress;
use executor::image::config_crc;
use executor::program::{Config, Index, Program};
use executor::table::SupervisorTable;
use plc_project::Project;

/// A project as CMSSM logic (the minimised covers evaluated directly),
/// runnable on the host. States are binary codes equal to the state
/// indices, so traces match [`TableImage`](super::TableImage).
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
        table_only(project, Backend::Logic)?;
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
                .map_err(|e| refusal(e, Location::new(&project.path, s.line, 0), &s.name))
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

/// The logic backend's refusal of `supervisor` (its entry at `location`):
/// a build without the minimiser is no fault of the supervisor's, so it
/// has no location.
fn refusal(error: LogicError, location: Location, supervisor: &str) -> Error {
    match error {
        LogicError::Unavailable => Error::LogicUnavailable,
        source => Error::Logic {
            location,
            supervisor: supervisor.to_owned(),
            source,
        },
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::logic::UNAVAILABLE;

    #[test]
    fn a_build_without_the_minimiser_is_no_supervisors_fault() {
        let at = Location::new("p.plc.toml", 7, 0);
        let err = refusal(LogicError::Unavailable, at.clone(), "cell");
        assert!(matches!(err, Error::LogicUnavailable), "{err:?}");
        assert_eq!(err.to_string(), UNAVAILABLE);
        let err = refusal(LogicError::Empty("cell".into()), at, "cell");
        assert!(
            matches!(
                &err,
                Error::Logic { location, supervisor, source: LogicError::Empty(_) }
                    if location.line == 7 && supervisor == "cell"
            ),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "p.plc.toml:7: supervisor `cell`: supervisor `cell` has no states"
        );
    }
}
