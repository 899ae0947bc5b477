//! What a closed-loop run of the testbed leaves: the events the
//! controller executed, the input image whenever it changed, the
//! violations, the fault, and the trains' and cranes' counts at the end;
//! its timeline as text, and its inputs as an `inputs.csv`.

use super::invariants::Violation;
use super::plant::{CraneState, TrainState};
use super::signals::{Commands, Inputs, TestbedIo};
use crate::inputs::{self, InputRow};
use plc_project::Project;
use std::fmt::Write as _;

/// A finished run.
#[derive(Debug, Clone, Default)]
pub struct TestbedRun {
    /// Scans run.
    pub scans: u64,
    /// The scan period, ms.
    pub scan_period_ms: u64,
    /// Executed events with the time of their scan, in order.
    pub events: Vec<(u64, String)>,
    /// The input image at the first scan and whenever it changed.
    pub inputs: Vec<(u64, Inputs)>,
    /// Every broken invariant, scan by scan.
    pub violations: Vec<Violation>,
    /// The controller's first fault: time and cause.
    pub fault: Option<(u64, String)>,
    /// The output image of the last scan.
    pub last_commands: Commands,
    /// Trains 1 and 2 at the end.
    pub trains: Vec<TrainState>,
    /// Cranes 1 … 3 at the end.
    pub cranes: Vec<CraneState>,
}

impl TestbedRun {
    /// Laps train `t` (0 or 1) completed.
    pub fn laps(&self, t: usize) -> u32 {
        self.trains.get(t).map_or(0, |s| s.laps)
    }

    /// Loads crane `u` (1 … 3) completed for train `t` (0 or 1).
    pub fn loads(&self, u: usize, t: usize) -> u32 {
        self.cranes
            .get(u.wrapping_sub(1))
            .map_or(0, |c| c.loads.get(t).copied().unwrap_or(0))
    }

    /// How many times `event` executed.
    pub fn count(&self, event: &str) -> usize {
        self.events.iter().filter(|(_, e)| e == event).count()
    }

    /// The timeline: one line per executed event, `time  event`, and a
    /// line for the fault.
    pub fn timeline(&self) -> String {
        let mut out = String::new();
        let mut fault = self.fault.as_ref();
        for (t, e) in &self.events {
            if let Some((ft, cause)) = fault.filter(|(ft, _)| ft < t) {
                let _ = writeln!(out, "{:>9.2} s  FAULT {cause}", *ft as f64 / 1000.0);
                fault = None;
            }
            let _ = writeln!(out, "{:>9.2} s  {e}", *t as f64 / 1000.0);
        }
        if let Some((ft, cause)) = fault {
            let _ = writeln!(out, "{:>9.2} s  FAULT {cause}", *ft as f64 / 1000.0);
        }
        out
    }

    /// The run's inputs as an `inputs.csv` for `project` (one row per
    /// scan), to replay it elsewhere: `host-sim replay`, the QEMU harness.
    pub fn inputs_csv(&self, project: &Project) -> Result<String, Vec<String>> {
        let io = TestbedIo::new(project)?;
        let mut rows = Vec::with_capacity(usize::try_from(self.scans).unwrap_or(0));
        let mut change = 0;
        for k in 0..self.scans {
            let time_ms = k * self.scan_period_ms;
            while self
                .inputs
                .get(change + 1)
                .is_some_and(|&(t, _)| t <= time_ms)
            {
                change += 1;
            }
            let Some((_, image)) = self.inputs.get(change) else {
                break;
            };
            let values = io.raw_image(image, project.inputs.len());
            rows.push(InputRow { time_ms, values });
        }
        Ok(inputs::to_csv(project, &rows))
    }
}
