//! What one scan did: the trace record, and fault causes.

use crate::program::Index;

/// Why the controller is in fault mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Fault {
    /// An uncontrollable event occurred that some supervisor having it
    /// could not take in the current state vector (recorded with it).
    Unexpected {
        /// The event.
        event: Index,
    },
    /// The program image fails its structure check or its checksum, a
    /// supervisor state is out of range, or a table contradicts the
    /// enabled sets in RAM.
    Corrupt,
    /// A scan started too late (board only, when configured as a fault).
    Overrun,
    /// An input changed more than once between two samples (board only,
    /// when configured as a fault).
    LostEdge,
}

/// The trace record of one scan (docs/semantics.md, "One scan", step 7), borrowed from the
/// controller until its next scan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScanRecord<'a> {
    /// Scan number k, from 0.
    pub scan: u32,
    /// The scan's time in ms (wrapping).
    pub time_ms: u32,
    /// Executed events: uncontrollable first, then controllable, each in
    /// execution order.
    pub executed: &'a [Index],
    /// Unexpected events (not executed, under either policy).
    pub unexpected: &'a [Index],
    /// The state of every supervisor after the scan.
    pub states: &'a [u32],
    /// The output image written by the scan.
    pub outputs: &'a [bool],
    /// The fault cause on every scan spent in fault mode.
    pub fault: Option<Fault>,
}

/// Counts kept across scans (never reset by a fault reset).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Counters {
    /// Unexpected events dropped under policy `ignore`.
    pub ignored: u32,
    /// Overruns reported.
    pub overruns: u32,
    /// Scan periods skipped because a scan started late (see
    /// [`crate::pacing`]).
    pub skipped_periods: u32,
    /// Lost edges reported.
    pub lost_edges: u32,
    /// Faults entered.
    pub faults: u32,
}
