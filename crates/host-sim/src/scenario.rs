//! Scenarios for replay harnesses (`host-sim record`): inputs per scan plus
//! the trace host-sim expects, as postcard records (docs/formats.md,
//! "Recorded scenario").

use crate::inputs::InputRow;
use crate::sim::{Sim, SimError};
use executor::replay::{RecordedScan, ScenarioHeader};
use executor::Program;

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
}

/// Runs `rows` through `sim` and returns the scenario bytes: a
/// [`ScenarioHeader`] then one [`RecordedScan`] per row.
pub fn record(sim: &mut Sim, rows: &[InputRow]) -> Result<Vec<u8>, RecordError> {
    let config = sim.controller().program().config();
    let header = ScenarioHeader {
        config_crc: executor::image::config_crc(&config),
        inputs: config.inputs.len() as u16,
        outputs: config.outputs.len() as u16,
        scans: rows.len() as u32,
    };
    let inputs = config.inputs.len();
    let mut out = postcard::to_stdvec(&header)?;
    for (k, row) in rows.iter().enumerate() {
        if row.values.len() != inputs {
            return Err(SimError::InputCount {
                expected: inputs,
                got: row.values.len(),
            }
            .into());
        }
        sim.scan_with(row.time_ms, &row.values)?;
        let record = sim.controller().record();
        let scan = RecordedScan::new(&row.values, &record).map_err(|_| RecordError::Capacity(k))?;
        out.extend(postcard::to_stdvec(&scan)?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random_inputs::guided_inputs;
    use codegen::emit::Backend;
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
}
