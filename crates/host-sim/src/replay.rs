//! Replay: every row of an inputs file through a project, one scan each.

use crate::inputs::{InputRow, InputRows};
use crate::partial::Partial;
use crate::plot::Plot;
use crate::sim::{Sim, SimError};
use crate::trace::{self, TraceRow};
use crate::vcd::Waveform;
use codegen::lower::Supervisors;
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

/// The files a streamed replay writes besides its trace (and the VCD's
/// GTKWave save file next to it, [`crate::gtkw`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct Extras<'a> {
    /// The waveform (VCD).
    pub vcd: Option<&'a Path>,
    /// The picture (SVG, [`crate::plot`]).
    pub svg: Option<&'a Path>,
}

/// Replays the inputs file at `inputs` through `sim` one row at a time and
/// writes the trace to `out` (and the waveform and picture of `extras`, if
/// given) as each scan produces it: memory stays constant however long the
/// file, but for the picture, which holds every change of every signal
/// (not every scan). The files appear only once the whole file has
/// replayed ([`Partial`]), so that bad input leaves nothing behind. `sim`
/// keeps only its last trace row.
pub fn stream(
    sim: &mut Sim,
    inputs: &Path,
    out: &Path,
    extras: Extras<'_>,
) -> Result<Totals, String> {
    let vcd = extras.vcd;
    let file = crate::inputs::open(inputs)?;
    let project = sim.project().clone();
    let nets = sim.nets().to_vec();
    let rows = InputRows::new(file, inputs, &project).map_err(|e| e.to_string())?;
    let mut trace_file = Partial::create(out)?;
    trace_file.line(&trace::header(&project))?;
    let mut vcd_file = vcd.map(Partial::create).transpose()?;
    let vcd_error = |e: std::io::Error| format!("{}: {e}", vcd.unwrap_or(out).display());
    let mut waveform = match &mut vcd_file {
        Some(file) => {
            Some(Waveform::new(file, Supervisors::new(&project, &nets)).map_err(vcd_error)?)
        }
        None => None,
    };
    let mut plot = extras.svg.map(|_| {
        let title = format!("{}: {}", project.name, inputs.display());
        Plot::for_project(&title, Supervisors::new(&project, &nets))
    });
    sim.retain_trace(false);
    let mut totals = Totals::default();
    for row in rows {
        let row = row.map_err(|e| e.to_string())?;
        let scanned = sim
            .scan_with(row.time_ms, &row.values)
            .map_err(|e| e.to_string())?;
        totals.add(scanned);
        trace_file.line(&trace::csv_line(scanned))?;
        if let Some(w) = &mut waveform {
            w.scan(Some(&row), scanned).map_err(vcd_error)?;
        }
        if let Some((plot, lanes)) = &mut plot {
            plot.trace_row(lanes, Some(&row.values), scanned);
        }
    }
    if let Some(w) = waveform {
        w.finish().map_err(vcd_error)?;
    }
    let svg_file = match (extras.svg, &plot) {
        (Some(path), Some((plot, _))) => Some(Partial::holding(path, plot.to_svg().as_bytes())?),
        _ => None,
    };
    trace_file.commit()?;
    if let (Some(file), Some(path)) = (vcd_file, vcd) {
        file.commit()?;
        let save_file = crate::gtkw::replay(path, Supervisors::new(&project, &nets));
        crate::gtkw::write_next_to(path, &save_file)?;
    }
    if let Some(file) = svg_file {
        file.commit()?;
    }
    Ok(totals)
}

#[cfg(test)]
mod tests {
    use super::*;
    use codegen::backend::Backend;

    fn repo(path: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path)
    }

    #[test]
    fn a_streamed_replay_writes_the_trace_and_waveform_an_in_memory_one_gives_and_keeps_one_row() {
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
        let mut waveform = Vec::new();
        crate::vcd::write(&mut waveform, sim.supervisors(), &rows, &traced).unwrap();
        let vcd = dir.path().join("t.vcd");
        let extras = Extras {
            vcd: Some(&vcd),
            svg: None,
        };
        let totals = stream(&mut sim, &inputs, &out, extras).unwrap();
        assert_eq!(std::fs::read_to_string(&out).unwrap(), expected);
        assert_eq!(std::fs::read(&vcd).unwrap(), waveform);
        assert_eq!(totals.scans, rows.len() as u64);
        assert_eq!(sim.trace().len(), 1, "only the last row is kept");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(
            names.len(),
            3,
            "t.csv, t.vcd and its t.gtkw, no partial file: {names:?}"
        );
    }
}
