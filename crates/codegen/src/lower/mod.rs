//! Lowering: a validated project ([`plc_project::Project`]) to the
//! executor's program image, once per generation.
//!
//! [`Lowered::new`] is the one place that says what a backend means:
//!
//! | backend | supervisors in the image | recorded CRC | on the host |
//! |---|---|---|---|
//! | table | bit-packed tables ([`TableImage`]) | configuration and tables | the tables, through the executor's decoder |
//! | logic | code: minimised CMSSM covers ([`LogicImage`]) | configuration | the covers, evaluated |
//! | match | code: one `match` per supervisor ([`MatchImage`]) | configuration | the same automata as tables, outside the image |
//!
//! Everything after lowering reads the lowered form: the Rust emitter
//! (`crate::emit`), `codegen gen --stats` ([`ImageCheck`], [`ScanSets`]),
//! and host runs (`host-sim`), which run a [`Lowered`] as the executor's
//! [`Program`].
//!
//! - [`config`]: the configuration pools ([`ConfigPools`]);
//! - [`nets`]: Petri nets' counters packed into executor supervisors
//!   ([`NetLayout`]);
//! - [`supervisors`]: the executor's supervisors, named ([`Supervisors`]);
//! - `table`, `logic`, `matches`: each backend's lowered supervisors;
//! - `figures`: the image check's and the scan sets' figures.

pub mod config;
mod figures;
mod logic;
mod matches;
pub mod nets;
pub mod supervisors;
mod table;

pub use config::{ConfigPools, GuardPools, GuardTable};
pub use figures::{GuardFigures, ImageCheck, ScanSets};
pub use logic::LogicImage;
pub use matches::MatchImage;
pub use nets::{NetGroups, NetLayout, PlaceField};
pub use supervisors::Supervisors;
pub use table::TableImage;

use crate::backend::Backend;
use crate::error::{Error, Result};
use des::error::Location;
use des::ops::Progress;
use executor::program::{Config, Index, Program};
use executor::table::SupervisorTable;
use plc_project::Project;
use std::cell::Cell;

thread_local! {
    /// Configuration lay-outs run on this thread ([`passes`]).
    static PASSES: Cell<usize> = const { Cell::new(0) };
}

fn count_pass() {
    PASSES.with(|p| p.set(p.get() + 1));
}

/// How many times this thread has laid a project out as the executor's
/// configuration ([`ConfigPools::from_project`]), the pass every lowering
/// starts with. A generation lowers its project once: the tests check it
/// by the difference of two readings.
pub fn passes() -> usize {
    PASSES.with(Cell::get)
}

/// A project lowered for one backend: the configuration pools and every
/// supervisor's lowered form, built once and read by everything after.
#[derive(Debug, Clone)]
pub enum Lowered {
    /// Bit-packed tables.
    Table(TableImage),
    /// CMSSM logic.
    Logic(LogicImage),
    /// `match` code.
    Match(MatchImage),
}

impl Lowered {
    /// Lowers `project` for `backend`, telling `progress` what the logic
    /// backend is minimising.
    /// Its image is checked for everything generation proves
    /// ([`executor::validate::validate_generated`]: the agreement of its
    /// pools, its table entries, its stored allowed sets), which the
    /// controller leaves to generation.
    pub fn new(project: &Project, backend: Backend, progress: &dyn Progress) -> Result<Lowered> {
        let lowered = match backend {
            Backend::Table => Lowered::Table(TableImage::new(project)?),
            Backend::Logic => Lowered::Logic(LogicImage::with_progress(project, progress)?),
            Backend::Match => Lowered::Match(MatchImage::new(project)?),
        };
        executor::validate::validate_generated(&lowered).map_err(|invalid| {
            Error::GeneratedImage {
                project: project.path.clone(),
                invalid,
            }
        })?;
        Ok(lowered)
    }

    /// The backend it was lowered for.
    pub fn backend(&self) -> Backend {
        match self {
            Lowered::Table(_) => Backend::Table,
            Lowered::Logic(_) => Backend::Logic,
            Lowered::Match(_) => Backend::Match,
        }
    }

    /// The configuration pools.
    pub fn pools(&self) -> &ConfigPools {
        match self {
            Lowered::Table(t) => &t.pools,
            Lowered::Logic(l) => &l.pools,
            Lowered::Match(m) => &m.pools,
        }
    }

    /// Its supervisors, named; `project` is the one it was lowered from.
    pub fn supervisors<'a>(&'a self, project: &'a Project) -> Supervisors<'a> {
        Supervisors::new(project, &self.pools().nets)
    }

    /// The image's size and the background check's figures.
    pub fn image_check(&self) -> ImageCheck {
        ImageCheck::of(self)
    }

    /// The sizes of the enabled-event sets.
    pub fn scan_sets(&self) -> ScanSets {
        ScanSets::of(self.pools())
    }
}

/// `$body` with `$p` bound to the lowered program, whichever it is
/// (static dispatch: host runs call it every scan).
macro_rules! each {
    ($lowered:expr, $p:ident => $body:expr) => {
        match $lowered {
            Lowered::Table($p) => $body,
            Lowered::Logic($p) => $body,
            Lowered::Match($p) => $body,
        }
    };
}

impl Program for Lowered {
    fn config(&self) -> Config<'_> {
        self.pools().config()
    }

    #[inline]
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        each!(self, p => p.next_state(supervisor, state, local))
    }

    #[inline]
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        each!(self, p => p.enabled(supervisor, state, from, len))
    }

    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>> {
        each!(self, p => p.table(supervisor))
    }

    fn recorded_crc(&self) -> u32 {
        each!(self, p => p.recorded_crc())
    }
}

/// Refuses a project with Petri nets on a backend other than the table
/// backend ([`Error::TableOnly`]), at the first net's line: a net's groups
/// run in the net layout of the executor's tables (its counters are not
/// an automaton the logic and `match` backends could write as code).
pub fn table_only(project: &Project, backend: Backend) -> Result<()> {
    match project.nets.first() {
        Some(net) if backend != Backend::Table => Err(Error::TableOnly {
            location: Location::new(&project.path, net.line, 0),
            net: net.name.clone(),
            backend,
        }),
        _ => Ok(()),
    }
}
