//! Scenarios for replay harnesses: inputs per scan plus the trace host-sim
//! expects, as postcard records (docs/formats.md, "Recorded scenario"), and seeded random input
//! sequences that drive a project through its supervisors.

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
        config_crc: executor::table::config_crc(&config),
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

/// A small deterministic generator (xorshift64*), so a seed names the same
/// sequence on every machine.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator from `seed` (any value, 0 included).
    pub fn new(seed: u64) -> Rng {
        // SplitMix64 of the seed: distinct seeds give unrelated, non-zero
        // states (xorshift must not start at 0).
        let mut z = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        Rng((z ^ (z >> 31)) | 1)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// `true` with probability 1/`n`.
    pub fn one_in(&mut self, n: u64) -> bool {
        self.next_u64() % n.max(1) == 0
    }
}

/// `scans` rows of inputs that mostly make things happen: each scan, with
/// probability 1/4, one uncontrollable event bound to an input edge that
/// every supervisor having it can take is provoked (its inputs moved, its
/// `when`/`unless` conditions met); request inputs flip now and then; with
/// probability 1/`noise_one_in` a random input toggles (which may raise
/// an unexpected event); after a fault, reset is pressed a few scans
/// later. Inputs are held between changes, so debouncing lets edges
/// through. The generator runs its own simulation (table backend) to know
/// the current states.
pub fn guided_inputs(
    project: &codegen::project::Project,
    scans: usize,
    seed: u64,
    noise_one_in: u64,
) -> Result<Vec<InputRow>, SimError> {
    use codegen::project::Trigger;
    let mut sim = Sim::new(project.clone(), codegen::emit::Backend::Table)?;
    let mut rng = Rng::new(seed);
    let mut values = vec![false; project.inputs.len()];
    let period = u64::from(project.scan_period_ms.max(1));
    let mut rows = Vec::with_capacity(scans);
    let requests: Vec<usize> = project.events.iter().filter_map(|e| e.request).collect();
    for k in 0..scans {
        let faulted = sim.controller().fault().is_some();
        if let Some(r) = project.reset {
            values[r] = faulted && !values[r] && rng.one_in(8);
        }
        if !faulted && rng.one_in(4) {
            let states = sim.controller().states();
            let feasible: Vec<usize> = (0..project.events.len())
                .filter(|&e| {
                    let ev = &project.events[e];
                    matches!(ev.trigger, Trigger::Rising(_) | Trigger::Falling(_))
                        && project.supervisors.iter().enumerate().all(|(j, sup)| {
                            sup.local_events.iter().all(|&(g, id)| {
                                g != e
                                    || sup
                                        .automaton
                                        .successor(codegen::StateId(states[j]), id)
                                        .is_some()
                            })
                        })
                })
                .collect();
            if !feasible.is_empty() {
                let ev =
                    &project.events[feasible[(rng.next_u64() % feasible.len() as u64) as usize]];
                match &ev.trigger {
                    Trigger::Rising(list) if list.iter().all(|&i| !values[i]) => {
                        values[list[(rng.next_u64() % list.len() as u64) as usize]] = true;
                    }
                    Trigger::Falling(list) => list.iter().for_each(|&i| values[i] = false),
                    Trigger::Rising(list) => list.iter().for_each(|&i| values[i] = false),
                    _ => {}
                }
                ev.when.iter().for_each(|&i| values[i] = true);
                ev.unless.iter().for_each(|&i| values[i] = false);
            }
        }
        if !requests.is_empty() && rng.one_in(10) {
            let r = requests[(rng.next_u64() % requests.len() as u64) as usize];
            values[r] = !values[r];
        }
        if !values.is_empty() && rng.one_in(noise_one_in) {
            let i = (rng.next_u64() % values.len() as u64) as usize;
            values[i] = !values[i];
        }
        let row = InputRow {
            time_ms: k as u64 * period,
            values: values.clone(),
        };
        sim.scan_with(row.time_ms, &row.values)?;
        rows.push(row);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
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

    #[test]
    fn random_inputs_are_reproducible() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/press.plc.toml");
        let sim = Sim::load(&path, Backend::Table).unwrap();
        let p = sim.project();
        assert_eq!(
            guided_inputs(p, 300, 1, 10).unwrap(),
            guided_inputs(p, 300, 1, 10).unwrap()
        );
        assert_ne!(
            guided_inputs(p, 300, 1, 10).unwrap(),
            guided_inputs(p, 300, 2, 10).unwrap()
        );
    }
}
