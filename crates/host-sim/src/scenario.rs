//! Scenarios for replay harnesses (`host-sim record`): inputs per scan plus
//! the trace host-sim expects, as postcard records (docs/formats.md,
//! "Recorded scenario").

use crate::inputs::InputRow;
use crate::partial::Partial;
use crate::plot::Plot;
use crate::replay::Totals;
use crate::sim::{Sim, SimError};
use crate::trace::TraceRow;
use executor::replay::{RecordedScan, ScenarioHeader};
use executor::Program;
use std::io::Write;
use std::path::Path;

/// A problem recording a scenario.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// Driving the simulation failed.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// The project exceeds what a recorded scan can hold.
    #[error(
        "scan {0} does not fit a recorded scan (at most {max_io} inputs and outputs, {max_sup} supervisors, {max_ev} events per scan)",
        max_io = executor::replay::MAX_INPUTS,
        max_sup = executor::replay::MAX_SUPERVISORS,
        max_ev = executor::replay::MAX_EVENTS
    )]
    Capacity(usize),
    /// Serialisation failed.
    #[error("postcard: {0}")]
    Encode(#[from] postcard::Error),
    /// The inputs could not be read.
    #[error(transparent)]
    Inputs(#[from] crate::inputs::InputsError),
    /// Writing failed.
    #[error("writing the scenario: {0}")]
    Io(#[from] std::io::Error),
    /// More scans than a scenario header counts.
    #[error("{0} scans: a scenario holds at most 2^32 - 1")]
    TooLong(u64),
    /// The rows ran out before the announced number of scans, or went on.
    #[error("{got} rows for the {expected} scans announced")]
    Count {
        /// Scans announced in the header.
        expected: u64,
        /// Rows given.
        got: u64,
    },
}

/// Runs `rows` through `sim` and returns the scenario bytes: a
/// [`ScenarioHeader`] then one [`RecordedScan`] per row.
pub fn record(sim: &mut Sim, rows: &[InputRow]) -> Result<Vec<u8>, RecordError> {
    let mut out = Vec::new();
    let rows = rows.iter().map(|r| Ok::<_, RecordError>(r.clone()));
    write(sim, rows.len() as u64, rows, &mut out, |_, _| Ok(()))?;
    Ok(out)
}

/// Runs the `scans` rows `rows` through `sim` and writes the scenario to
/// `out` as each scan produces it (a [`ScenarioHeader`], then one
/// [`RecordedScan`] per row), telling `each` every row and its trace row:
/// memory stays constant however many rows (call
/// [`Sim::retain_trace`]`(false)` first). Fails if `rows` gives fewer or
/// more than `scans` rows.
pub fn write<E>(
    sim: &mut Sim,
    scans: u64,
    rows: impl IntoIterator<Item = Result<InputRow, E>>,
    out: &mut impl Write,
    mut each: impl FnMut(&InputRow, &TraceRow) -> Result<(), RecordError>,
) -> Result<Totals, RecordError>
where
    RecordError: From<E>,
{
    let config = sim.controller().program().config();
    let header = ScenarioHeader {
        config_crc: executor::image::config_crc(&config),
        inputs: config.inputs.len() as u16,
        outputs: config.outputs.len() as u16,
        scans: u32::try_from(scans).map_err(|_| RecordError::TooLong(scans))?,
    };
    let inputs = config.inputs.len();
    out.write_all(&postcard::to_stdvec(&header)?)?;
    let mut totals = Totals::default();
    for (k, row) in rows.into_iter().enumerate() {
        let row = row?;
        if row.values.len() != inputs {
            return Err(SimError::InputCount {
                expected: inputs,
                got: row.values.len(),
            }
            .into());
        }
        sim.scan_with(row.time_ms, &row.values)?;
        let traced = sim.last().expect("a scan leaves its trace row");
        totals.add(traced);
        let record = sim.controller().record();
        let scan = RecordedScan::new(&row.values, &record).map_err(|_| RecordError::Capacity(k))?;
        out.write_all(&postcard::to_stdvec(&scan)?)?;
        each(&row, traced)?;
    }
    if totals.scans != scans {
        return Err(RecordError::Count {
            expected: scans,
            got: totals.scans,
        });
    }
    Ok(totals)
}

/// `host-sim record`: runs the `scans` rows `rows` through `sim` and
/// writes the scenario to `out`, with `csv` also the inputs and the trace
/// as CSV next to it (`.inputs.csv`, `.trace.csv`), each row as it is
/// produced: memory stays constant however many rows (but for the picture
/// at `svg`, if given, which holds every change of every signal,
/// [`crate::plot`]). The files appear only once complete ([`Partial`]).
pub fn record_files<E>(
    sim: &mut Sim,
    scans: u64,
    rows: impl IntoIterator<Item = Result<InputRow, E>>,
    out: &Path,
    csv: bool,
    svg: Option<&Path>,
) -> Result<Totals, String>
where
    RecordError: From<E>,
{
    let mut plot = svg.map(|_| {
        let title = format!("{}: {}", sim.project().name, out.display());
        Plot::for_project(&title, sim.supervisors())
    });
    sim.retain_trace(false);
    let mut scenario = Partial::create(out)?;
    let mut tables = if csv {
        let mut inputs = Partial::create(&out.with_extension("inputs.csv"))?;
        inputs.line(&crate::inputs::csv_header(sim.project()))?;
        let mut trace = Partial::create(&out.with_extension("trace.csv"))?;
        trace.line(&crate::trace::header(sim.project()))?;
        Some((inputs, trace))
    } else {
        None
    };
    let mut scan = 0;
    let totals = write(sim, scans, rows, scenario.writer(), |row, traced| {
        if let Some((inputs, trace)) = &mut tables {
            inputs
                .line(&crate::inputs::csv_line(scan, row))
                .and_then(|()| trace.line(&crate::trace::csv_line(traced)))
                .map_err(|e| RecordError::Io(std::io::Error::other(e)))?;
        }
        if let Some((plot, lanes)) = &mut plot {
            plot.trace_row(lanes, Some(&row.values), traced);
        }
        scan += 1;
        Ok(())
    })
    .map_err(|e| e.to_string())?;
    let picture = match (svg, plot) {
        (Some(path), Some((plot, _))) => Some(Partial::holding(path, plot.to_svg().as_bytes())?),
        _ => None,
    };
    scenario.commit()?;
    if let Some(file) = picture {
        file.commit()?;
    }
    if let Some((inputs, trace)) = tables {
        inputs.commit()?;
        trace.commit()?;
    }
    Ok(totals)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random_inputs::guided_inputs;
    use codegen::backend::Backend;
    use executor::replay::RecordedScan;
    use std::path::Path;

    #[test]
    fn recorded_scenario_decodes_to_the_trace() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/crane.plc.toml");
        let mut sim = Sim::load(&path, Backend::Table).unwrap();
        let rows = guided_inputs(sim.project(), 500, 7, 50).unwrap();
        let bytes = record(&mut sim, &rows).unwrap();
        let (header, mut rest): (ScenarioHeader, &[u8]) =
            postcard::take_from_bytes(&bytes).unwrap();
        assert_eq!(header.scans, 500);
        assert_eq!(header.inputs as usize, sim.project().inputs.len());
        let mut events = 0;
        for (k, row) in sim.trace().iter().enumerate() {
            let (scan, tail): (RecordedScan, &[u8]) = postcard::take_from_bytes(rest).unwrap();
            rest = tail;
            assert_eq!(u64::from(scan.time_ms), rows[k].time_ms);
            assert_eq!(scan.executed.len(), row.events.len(), "scan {k}");
            assert_eq!(scan.fault.is_some(), row.fault.is_some(), "scan {k}");
            events += scan.executed.len();
        }
        assert!(rest.is_empty());
        assert!(events > 100, "guided inputs drive events ({events})");
    }

    #[test]
    fn recorded_files_hold_what_an_in_memory_recording_gives_and_the_sim_keeps_one_row() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/press.plc.toml");
        let mut sim = Sim::load(&path, Backend::Table).unwrap();
        let rows = guided_inputs(sim.project(), 400, 3, 40).unwrap();
        let bytes = record(&mut sim, &rows).unwrap();
        let inputs_csv = crate::inputs::to_csv(sim.project(), &rows);
        let trace_csv = crate::trace::to_csv(sim.project(), sim.trace());

        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("s.scenario");
        let mut sim = Sim::load(&path, Backend::Table).unwrap();
        let generated = crate::random_inputs::GuidedInputs::new(sim.project(), 3, 40)
            .unwrap()
            .take(400);
        let totals = record_files(&mut sim, 400, generated, &out, true, None).unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), bytes);
        let read = |ext: &str| std::fs::read_to_string(out.with_extension(ext)).unwrap();
        assert_eq!(read("inputs.csv"), inputs_csv);
        assert_eq!(read("trace.csv"), trace_csv);
        assert_eq!(totals.scans, 400);
        assert_eq!(sim.trace().len(), 1, "only the last row is kept");

        // Fewer rows than announced: an error, and no file left behind.
        let short = dir.path().join("short.scenario");
        let rows = rows
            .iter()
            .take(10)
            .map(|r| Ok::<_, RecordError>(r.clone()));
        let err = record_files(&mut sim, 11, rows, &short, true, None).unwrap_err();
        assert!(err.contains("10 rows for the 11 scans"), "{err}");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            3,
            "s.scenario and its two CSV files"
        );
    }
}
