//! Seeded random input sequences that drive a project through its
//! supervisors (`host-sim record` without `--inputs`).

use crate::inputs::InputRow;
use crate::rng::Rng;
use crate::sim::{Sim, SimError};
use plc_project::{Project, Trigger};

/// Rows of inputs that mostly make things happen, one per scan, without
/// end: each scan, with probability 1/4, one uncontrollable event bound to
/// an input edge that every supervisor having it can take is provoked (its
/// inputs moved, its `when`/`unless` conditions met); request inputs flip
/// now and then; with probability 1/`noise_one_in` a random input toggles
/// (which may raise an unexpected event); after a fault, reset is pressed
/// a few scans later. Inputs are held between changes, so debouncing lets
/// edges through. The generator runs its own simulation (table backend,
/// keeping only its last trace row) to know the current states, so it
/// holds constant memory however many rows it gives.
pub struct GuidedInputs {
    /// Its own simulation, which holds its copy of the project.
    sim: Sim,
    rng: Rng,
    values: Vec<bool>,
    period: u64,
    requests: Vec<usize>,
    noise_one_in: u64,
    scan: u64,
}

impl GuidedInputs {
    /// The generator for `project`, seeded with `seed`.
    pub fn new(project: &Project, seed: u64, noise_one_in: u64) -> Result<Self, SimError> {
        let mut sim = Sim::new(project.clone(), codegen::backend::Backend::Table)?;
        sim.retain_trace(false);
        let period = u64::from(sim.config().scan_period_ms.max(1));
        Ok(GuidedInputs {
            sim,
            rng: Rng::new(seed),
            values: vec![false; project.inputs.len()],
            period,
            requests: project.events.iter().filter_map(|e| e.request).collect(),
            noise_one_in,
            scan: 0,
        })
    }

    /// The next row (and the generator's own scan of it).
    pub fn next_row(&mut self) -> Result<InputRow, SimError> {
        let (project, rng, values) = (self.sim.project(), &mut self.rng, &mut self.values);
        let faulted = self.sim.controller().fault().is_some();
        if let Some(r) = project.reset {
            values[r] = faulted && !values[r] && rng.one_in(8);
        }
        if !faulted && rng.one_in(4) {
            let states = self.sim.controller().states();
            let supervisors = self.sim.supervisors();
            let feasible: Vec<usize> = (0..project.events.len())
                .filter(|&e| {
                    let ev = &project.events[e];
                    matches!(ev.trigger, Trigger::Rising(_) | Trigger::Falling(_))
                        && supervisors.event_feasible(e, states)
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
        if !self.requests.is_empty() && rng.one_in(10) {
            let r = self.requests[(rng.next_u64() % self.requests.len() as u64) as usize];
            values[r] = !values[r];
        }
        if !values.is_empty() && rng.one_in(self.noise_one_in) {
            let i = (rng.next_u64() % values.len() as u64) as usize;
            values[i] = !values[i];
        }
        let row = InputRow {
            time_ms: self.scan * self.period,
            values: values.clone(),
        };
        self.scan += 1;
        self.sim.scan_with(row.time_ms, &row.values)?;
        Ok(row)
    }
}

impl Iterator for GuidedInputs {
    type Item = Result<InputRow, SimError>;

    fn next(&mut self) -> Option<Self::Item> {
        Some(self.next_row())
    }
}

/// The first `scans` rows of [`GuidedInputs`].
pub fn guided_inputs(
    project: &Project,
    scans: usize,
    seed: u64,
    noise_one_in: u64,
) -> Result<Vec<InputRow>, SimError> {
    GuidedInputs::new(project, seed, noise_one_in)?
        .take(scans)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use codegen::backend::Backend;
    use std::path::Path;

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
