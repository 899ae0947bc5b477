//! Trace rows (docs/formats.md, "trace.csv"): one per scan, with names instead of
//! indices, and their CSV form.

use codegen::lower::Supervisors;
use executor::{Fault, ScanRecord};
use plc_project::Project;
use std::fmt::Write as _;

/// One scan of a trace, as written to `trace.csv`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TraceRow {
    /// Scan number.
    pub scan: u64,
    /// Time as given in the input (the executor saw it modulo 2^32).
    pub time_ms: u64,
    /// Executed events in order.
    pub events: Vec<String>,
    /// Unexpected (not executed) events in order.
    pub ignored: Vec<String>,
    /// `(supervisor, state)` in declaration order.
    pub states: Vec<(String, String)>,
    /// Output levels in declaration order.
    pub outputs: Vec<bool>,
    /// Fault cause on scans spent in fault mode.
    pub fault: Option<String>,
}

/// The text of a fault cause: `Unexpected:<event>`, `Corrupt`, …
pub fn fault_text(fault: Fault, project: &Project) -> String {
    match fault {
        Fault::Unexpected { event } => format!(
            "Unexpected:{}",
            project
                .events
                .get(event as usize)
                .map_or("?", |e| e.name.as_str())
        ),
        Fault::Corrupt => "Corrupt".to_owned(),
        Fault::Overrun => "Overrun".to_owned(),
        Fault::LostEdge => "LostEdge".to_owned(),
    }
}

impl TraceRow {
    /// The row for `record`, names from `supervisors` and their project;
    /// `time_ms` is the time as the caller gave it (before the modulo).
    pub fn from_record(
        record: &ScanRecord<'_>,
        time_ms: u64,
        supervisors: Supervisors<'_>,
    ) -> TraceRow {
        let project = supervisors.project();
        let event = |e: &u16| {
            project
                .events
                .get(*e as usize)
                .map_or_else(|| format!("#{e}"), |ev| ev.name.clone())
        };
        TraceRow {
            scan: u64::from(record.scan),
            time_ms,
            events: record.executed.iter().map(event).collect(),
            ignored: record.unexpected.iter().map(event).collect(),
            states: record
                .states
                .iter()
                .enumerate()
                .map(|(j, &x)| (supervisors.name(j), supervisors.state_name(j, x)))
                .collect(),
            outputs: record.outputs.to_vec(),
            fault: record.fault.map(|f| fault_text(f, project)),
        }
    }

    /// The state of supervisor `name` in this row.
    pub fn state(&self, supervisor: &str) -> Option<&str> {
        self.states
            .iter()
            .find(|(s, _)| s == supervisor)
            .map(|(_, x)| x.as_str())
    }
}

/// Quotes a CSV field when it needs it (RFC 4180).
pub(crate) fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

/// The CSV header of a trace of `project`.
pub fn header(project: &Project) -> String {
    let mut h = String::from("scan,time_ms,events,ignored,states");
    for o in &project.outputs {
        h.push(',');
        h.push_str(&field(&o.name));
    }
    h.push_str(",fault");
    h
}

/// One CSV line (no newline).
pub fn csv_line(row: &TraceRow) -> String {
    let mut line = format!(
        "{},{},{},{},",
        row.scan,
        row.time_ms,
        field(&row.events.join(" ")),
        field(&row.ignored.join(" "))
    );
    let states: Vec<String> = row.states.iter().map(|(s, x)| format!("{s}={x}")).collect();
    line.push_str(&field(&states.join(" ")));
    for &o in &row.outputs {
        let _ = write!(line, ",{}", u8::from(o));
    }
    line.push(',');
    line.push_str(&field(row.fault.as_deref().unwrap_or("")));
    line
}

/// A whole trace as CSV text.
pub fn to_csv(project: &Project, rows: &[TraceRow]) -> String {
    let mut out = header(project);
    out.push('\n');
    for r in rows {
        out.push_str(&csv_line(r));
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_with_commas_or_quotes_are_quoted() {
        assert_eq!(field("a b"), "a b");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"x\""), "\"say \"\"x\"\"\"");
    }

    #[test]
    fn a_row_prints_in_the_documented_column_order() {
        let row = TraceRow {
            scan: 3,
            time_ms: 30,
            events: vec!["a".into(), "c_hi".into()],
            ignored: vec![],
            states: vec![("sup".into(), "2".into()), ("other".into(), "idle".into())],
            outputs: vec![true, false],
            fault: None,
        };
        assert_eq!(csv_line(&row), "3,30,a c_hi,,sup=2 other=idle,1,0,");
        let faulted = TraceRow {
            fault: Some("Unexpected:e".into()),
            ..row
        };
        assert!(csv_line(&faulted).ends_with(",1,0,Unexpected:e"));
    }
}
