//! Replay: every row of an inputs file through a project, one scan each.

use crate::inputs::{InputRow, InputRows};
use crate::sim::{Sim, SimError};
use crate::trace::{self, TraceRow};
use std::io::{BufWriter, Write};
use std::path::Path;

/// Runs `rows` through `sim` (one scan per row at the row's time) and
/// returns the trace rows of those scans.
pub fn replay(sim: &mut Sim, rows: &[InputRow]) -> Result<Vec<TraceRow>, SimError> {
    let mut out = Vec::with_capacity(rows.len());
    for row in rows {
        out.push(sim.scan_with(row.time_ms, &row.values)?.clone());
    }
    Ok(out)
}

/// What a streamed replay did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Totals {
    /// Scans replayed.
    pub scans: u64,
    /// Events executed.
    pub events: u64,
    /// Scans spent in fault mode.
    pub faults: u64,
}

impl Totals {
    /// Counts one scan.
    pub fn add(&mut self, row: &TraceRow) {
        self.scans += 1;
        self.events += row.events.len() as u64;
        self.faults += u64::from(row.fault.is_some());
    }

    /// The totals of `rows`.
    pub fn of(rows: &[TraceRow]) -> Totals {
        let mut totals = Totals::default();
        rows.iter().for_each(|row| totals.add(row));
        totals
    }
}

/// Replays the inputs file at `inputs` through `sim` one row at a time and
/// writes the trace to `out` as each scan produces it: memory stays
/// constant however long the file. The trace goes to a temporary file
/// next to `out`, renamed when the whole file has replayed, so that bad
/// input leaves no trace behind. `sim` keeps only its last trace row.
pub fn stream(sim: &mut Sim, inputs: &Path, out: &Path) -> Result<Totals, String> {
    let io = |path: &Path, e: std::io::Error| format!("{}: {e}", path.display());
    let file = std::fs::File::open(inputs).map_err(|e| io(inputs, e))?;
    let rows = InputRows::new(file, inputs, sim.project()).map_err(|e| e.to_string())?;
    let partial = out.with_extension("partial");
    let result = (|| {
        let mut w = BufWriter::new(std::fs::File::create(&partial).map_err(|e| io(&partial, e))?);
        writeln!(w, "{}", trace::header(sim.project())).map_err(|e| io(&partial, e))?;
        sim.retain_trace(false);
        let mut totals = Totals::default();
        for row in rows {
            let row = row.map_err(|e| e.to_string())?;
            let scanned = sim
                .scan_with(row.time_ms, &row.values)
                .map_err(|e| e.to_string())?;
            totals.add(scanned);
            writeln!(w, "{}", trace::csv_line(scanned)).map_err(|e| io(&partial, e))?;
        }
        w.flush().map_err(|e| io(&partial, e))?;
        Ok(totals)
    })();
    match result {
        Ok(totals) => {
            std::fs::rename(&partial, out).map_err(|e| io(out, e))?;
            Ok(totals)
        }
        Err(e) => {
            let _ = std::fs::remove_file(&partial);
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use codegen::emit::Backend;

    fn repo(path: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path)
    }

    #[test]
    fn a_streamed_replay_writes_the_trace_an_in_memory_one_gives_and_keeps_one_row() {
        let project = repo("models/press.plc.toml");
        let inputs = repo("models/press/cycle.inputs.csv");
        let mut sim = Sim::load(&project, Backend::Table).unwrap();
        let text = std::fs::read_to_string(&inputs).unwrap();
        let rows = crate::inputs::parse(&text, &inputs, sim.project()).unwrap();
        let traced = replay(&mut sim, &rows).unwrap();
        let expected = trace::to_csv(sim.project(), &traced);

        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("t.csv");
        let mut sim = Sim::load(&project, Backend::Table).unwrap();
        let totals = stream(&mut sim, &inputs, &out).unwrap();
        assert_eq!(std::fs::read_to_string(&out).unwrap(), expected);
        assert_eq!(totals.scans, rows.len() as u64);
        assert_eq!(sim.trace().len(), 1, "only the last row is kept");
        assert!(!out.with_extension("partial").exists());
    }
}
