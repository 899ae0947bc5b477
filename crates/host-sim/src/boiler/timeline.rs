//! The timeline `host-sim boiler` prints: a row per scan that executed
//! events or changed fault mode, with the outputs on and the bath and
//! flue-gas temperatures, then the supervisors whose state changed and the
//! fault.
//!
//! By default every line keeps within [`TERMINAL`] columns: events and
//! outputs wrap within their columns, state changes and faults wrap under
//! them. `wide` gives one line per row and per change, however long.

use super::record::{Run, RunRow};
use super::signals::Output;
use crate::columns::{row, wrap, TERMINAL};

/// Width of the time column (`   26.01s`).
const TIME: usize = 9;
/// Width of the events column.
const EVENTS: usize = 44;
/// Width of the outputs column.
const OUTPUTS: usize = 40;
/// Width of a temperature column (` 20.0°C`).
const TEMPERATURE: usize = 7;
/// Indent of the lines under a row (state changes, fault).
const INDENT: usize = TIME + 2;

/// The timeline of `run`, line by line.
pub fn lines(run: &Run, wide: bool) -> Vec<String> {
    let mut out = vec![if wide {
        format!(
            "{:>9}  {:<48} {:<40} {:>7} {:>7}",
            "time", "events", "outputs on", "bath", "flue"
        )
    } else {
        let cell = |text: &str, width| (vec![format!("{text:>width$}")], width);
        row(&[
            cell("time", TIME),
            (vec!["events".into()], EVENTS),
            (vec!["outputs on".into()], OUTPUTS),
            cell("bath", TEMPERATURE),
            cell("flue", TEMPERATURE),
        ])
        .concat()
    }];
    let mut last_states: Vec<(String, String)> = Vec::new();
    let mut last_fault = None;
    for r in &run.rows {
        if r.events.is_empty() && r.fault == last_fault {
            continue;
        }
        let on: Vec<&str> = Output::ALL
            .iter()
            .filter(|o| r.outputs.get(**o))
            .map(|o| o.name())
            .collect();
        let changed: Vec<String> = r
            .states
            .iter()
            .filter(|s| !last_states.contains(s))
            .map(|(sup, state)| format!("{sup}={state}"))
            .collect();
        let fault = (r.fault != last_fault)
            .then(|| format!("fault: {}", r.fault.as_deref().unwrap_or("cleared")));
        let entry = Entry {
            row: r,
            on,
            changed,
            fault,
        };
        if wide {
            entry.wide(&mut out);
        } else {
            entry.narrow(&mut out);
        }
        last_states.clone_from(&r.states);
        last_fault.clone_from(&r.fault);
    }
    out
}

/// What the timeline says of one row.
struct Entry<'a> {
    row: &'a RunRow,
    /// Outputs on.
    on: Vec<&'static str>,
    /// `supervisor=state` of the supervisors whose state changed.
    changed: Vec<String>,
    /// `fault: <cause>` or `fault: cleared` when fault mode changed.
    fault: Option<String>,
}

impl Entry<'_> {
    /// As it always was: one line each, however long.
    fn wide(self, out: &mut Vec<String>) {
        let r = self.row;
        out.push(format!(
            "{:>8.2}s  {:<48} {:<40} {:>5.1}°C {:>5.0}°C",
            r.time_ms as f64 / 1000.0,
            r.events.join(" "),
            self.on.join(" "),
            r.plant.bath_c,
            r.plant.flue_c
        ));
        if !self.changed.is_empty() {
            out.push(format!("{:>11}{}", "", self.changed.join("  ")));
        }
        if let Some(fault) = self.fault {
            out.push(format!("{:>11}{fault}", ""));
        }
    }

    /// Within [`TERMINAL`] columns.
    fn narrow(self, out: &mut Vec<String>) {
        let r = self.row;
        out.extend(row(&[
            (vec![format!("{:>8.2}s", r.time_ms as f64 / 1000.0)], TIME),
            (wrap(&r.events, EVENTS), EVENTS),
            (wrap(&self.on, OUTPUTS), OUTPUTS),
            (vec![format!("{:>5.1}°C", r.plant.bath_c)], TEMPERATURE),
            (vec![format!("{:>5.0}°C", r.plant.flue_c)], TEMPERATURE),
        ]));
        // State changes, then the fault on lines of its own.
        let fault: Vec<String> = self.fault.into_iter().collect();
        for words in [&self.changed, &fault] {
            for line in wrap(words, TERMINAL - INDENT) {
                out.push(format!("{:INDENT$}{line}", ""));
            }
        }
    }
}
