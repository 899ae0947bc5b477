//! What a closed-loop run of the cell leaves: the events the controller
//! executed, the output image whenever it changed, the violations, the
//! extremes of the plant, and the batches read off the events.

use super::invariants::Violation;
use super::physics::CellState;
use super::signals::{CellIo, Commands, Sensors, Unit};
use crate::inputs::{self, InputRow};
use plc_project::Project;

/// A finished run.
#[derive(Debug, Clone, Default)]
pub struct CellRun {
    /// Scans run.
    pub scans: u64,
    /// Executed events with the time of their scan, in order.
    pub events: Vec<(u64, String)>,
    /// The cell's output image at the first scan and whenever it changed.
    pub commands: Vec<(u64, Commands)>,
    /// The switches and buttons the controller read, at the first scan
    /// and whenever they changed.
    pub sensors: Vec<(u64, Sensors)>,
    /// The scan period, ms.
    pub scan_period_ms: u64,
    /// Every broken invariant, scan by scan.
    pub violations: Vec<Violation>,
    /// The plant at the end.
    pub last: CellState,
    /// The controlled net's marking at the end (its name).
    pub marking: String,
    /// Highest levels reached: mixing tanks, then reactors.
    pub max_levels: [f64; 4],
    /// Highest temperature of each reactor while its controller held the
    /// reaction temperature (the PI's overshoot shows here).
    pub max_reaction_temps: [f64; 2],
}

/// One batch of a reactor: from its start (t_r8) to its end (t_r7,
/// reactor empty).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Batch {
    /// Time of t_r8, ms.
    pub start_ms: u64,
    /// Time of t_r7, ms.
    pub end_ms: u64,
}

impl Batch {
    /// How long it took, ms.
    pub fn duration_ms(&self) -> u64 {
        self.end_ms - self.start_ms
    }
}

impl CellRun {
    /// The times at which `event` executed.
    pub fn times_of(&self, event: &str) -> Vec<u64> {
        self.events
            .iter()
            .filter(|(_, e)| e == event)
            .map(|&(t, _)| t)
            .collect()
    }

    /// The completed batches of `reactor`, in order.
    pub fn batches(&self, reactor: Unit) -> Vec<Batch> {
        let r = reactor.letter();
        let starts = self.times_of(&format!("t_r{r}8"));
        let ends = self.times_of(&format!("t_r{r}7"));
        starts
            .iter()
            .zip(ends)
            .map(|(&start_ms, end_ms)| Batch { start_ms, end_ms })
            .collect()
    }

    /// The run's inputs as an `inputs.csv` for `project` (one row per
    /// scan), to replay it elsewhere: `host-sim replay`, the QEMU harness.
    pub fn inputs_csv(&self, project: &Project) -> Result<String, Vec<String>> {
        let io = CellIo::new(project)?;
        let mut rows = Vec::with_capacity(self.scans as usize);
        let mut change = 0;
        for k in 0..self.scans {
            let time_ms = k * self.scan_period_ms;
            while self
                .sensors
                .get(change + 1)
                .is_some_and(|&(t, _)| t <= time_ms)
            {
                change += 1;
            }
            let values = io.raw_image(&self.sensors[change].1, project.inputs.len());
            rows.push(InputRow { time_ms, values });
        }
        Ok(inputs::to_csv(project, &rows))
    }

    /// Time of the last executed event, 0 without one.
    pub fn last_event_ms(&self) -> u64 {
        self.events.last().map_or(0, |&(t, _)| t)
    }
}
