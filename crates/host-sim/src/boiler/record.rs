//! The record of a closed-loop run: per scan, what the controller read,
//! wrote and did, and the true state of the plant, with a CSV form for
//! timelines and plots.

use super::invariants::{Checker, Invariants, Violation};
use super::physics::BoilerState;
use super::signals::{Input, Inputs, IoMap, Output, Outputs};
use crate::inputs::InputRow;
use crate::trace::field;
use std::fmt::Write as _;

/// One scan of a closed-loop run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRow {
    /// Scan number within the run (from 0).
    pub scan: u64,
    /// Time of the scan on the controller's clock.
    pub time_ms: u64,
    /// The input image the controller read (sensor faults applied).
    pub inputs: Inputs,
    /// The output image it wrote.
    pub outputs: Outputs,
    /// Executed events in order.
    pub events: Vec<String>,
    /// `(supervisor, state)` after the scan.
    pub states: Vec<(String, String)>,
    /// Fault cause on a scan spent in fault mode.
    pub fault: Option<String>,
    /// The controller left fault mode in this scan and re-initialised.
    pub reinitialised: bool,
    /// The true plant state when the inputs were read.
    pub plant: BoilerState,
}

impl RunRow {
    /// The state of supervisor `name` after this scan.
    pub fn state(&self, supervisor: &str) -> Option<&str> {
        self.states
            .iter()
            .find(|(s, _)| s == supervisor)
            .map(|(_, x)| x.as_str())
    }
}

/// A closed-loop run.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The controller's scan period.
    pub scan_period_ms: u32,
    /// The controller's input filtering (`debounce_scans` by
    /// [`Input::index`]), for checks.
    pub debounce: [u8; Input::ALL.len()],
    /// One row per scan.
    pub rows: Vec<RunRow>,
}

impl Run {
    /// The safety violations of this run under `invariants`, judged on
    /// the inputs as the controller filtered them.
    pub fn violations(&self, invariants: &Invariants) -> Vec<Violation> {
        let mut checker = Checker::with_debounce(invariants.clone(), self.debounce);
        for row in &self.rows {
            if row.reinitialised {
                checker.reinitialised();
            }
            checker.observe(row.time_ms, &row.inputs, &row.outputs);
        }
        checker.finish()
    }

    /// The input image the controller read in each scan, as rows of the
    /// project's raw inputs mapped by `io` (to replay the run open loop).
    pub fn input_rows(&self, io: &IoMap) -> Vec<InputRow> {
        self.rows
            .iter()
            .map(|r| InputRow {
                time_ms: r.time_ms,
                values: io.raw_inputs(&r.inputs),
            })
            .collect()
    }

    /// The first row where `f` holds.
    pub fn first(&self, f: impl Fn(&RunRow) -> bool) -> Option<&RunRow> {
        self.rows.iter().find(|r| f(r))
    }

    /// The run as CSV: `scan,time_ms`, the inputs and outputs by name
    /// (0/1), then `bath_c,flue_c,pilot_lit,main_lit,firing_kw,load_kw`
    /// (the true plant state), `events`, `states` and `fault`.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("scan,time_ms");
        for i in Input::ALL {
            let _ = write!(out, ",{}", i.name());
        }
        for o in Output::ALL {
            let _ = write!(out, ",{}", o.name());
        }
        out.push_str(",bath_c,flue_c,pilot_lit,main_lit,firing_kw,load_kw,events,states,fault\n");
        for r in &self.rows {
            let _ = write!(out, "{},{}", r.scan, r.time_ms);
            for i in Input::ALL {
                let _ = write!(out, ",{}", u8::from(r.inputs.get(i)));
            }
            for o in Output::ALL {
                let _ = write!(out, ",{}", u8::from(r.outputs.get(o)));
            }
            let p = &r.plant;
            let states: Vec<String> = r.states.iter().map(|(s, x)| format!("{s}={x}")).collect();
            let _ = writeln!(
                out,
                ",{:.2},{:.1},{},{},{:.1},{:.1},{},{},{}",
                p.bath_c,
                p.flue_c,
                u8::from(p.pilot_flame),
                u8::from(p.main_flame),
                p.firing_kw,
                p.load_kw,
                field(&r.events.join(" ")),
                field(&states.join(" ")),
                field(r.fault.as_deref().unwrap_or(""))
            );
        }
        out
    }
}
