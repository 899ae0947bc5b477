//! The testbed's PLC signals by name (`models/testbed/testbed.plc.toml`):
//! what the plant shows the controller ([`Inputs`]), what the controller
//! drives ([`Commands`]), and where each is in a project ([`TestbedIo`]).

use super::track::SENSORS;
use crate::sim::{Sim, SimError};
use plc_project::Project;

/// The input image of the testbed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Inputs {
    /// `sK_tI`: sensor K (index K − 1) reports train I (index I − 1).
    pub at: [[bool; 2]; SENSORS as usize],
    /// `doneU`: crane U finished loading.
    pub done: [bool; 3],
}

/// The output image of the testbed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Commands {
    /// `go_tI`: train I may leave its sensor.
    pub go: [bool; 2],
    /// `pointW_s`, `pointW_d`: the coils of switch W's motor.
    pub points: [[bool; 2]; 6],
    /// `loadU`: crane U loads.
    pub load: [bool; 3],
}

impl Commands {
    /// The names of the outputs that are on.
    pub fn on(&self) -> Vec<String> {
        let mut on = Vec::new();
        for (i, g) in self.go.iter().enumerate() {
            if *g {
                on.push(format!("go_t{}", i + 1));
            }
        }
        for (w, coils) in self.points.iter().enumerate() {
            for (c, x) in coils.iter().zip(['s', 'd']) {
                if *c {
                    on.push(format!("point{}_{x}", w + 1));
                }
            }
        }
        for (u, l) in self.load.iter().enumerate() {
            if *l {
                on.push(format!("load{}", u + 1));
            }
        }
        on
    }
}

/// Where the testbed's signals are in a project: input indices in the
/// order of [`TestbedIo::input_names`], output indices in the order of
/// [`TestbedIo::output_names`].
#[derive(Debug, Clone)]
pub struct TestbedIo {
    names: Vec<String>,
    inputs: Vec<usize>,
    outputs: Vec<usize>,
}

impl TestbedIo {
    /// The testbed's signals in `project`, or the names it lacks.
    pub fn new(project: &Project) -> Result<TestbedIo, Vec<String>> {
        let mut missing = Vec::new();
        let mut find = |names: Vec<String>, look: &dyn Fn(&str) -> Option<usize>, what: &str| {
            names
                .iter()
                .filter_map(|n| {
                    let i = look(n);
                    if i.is_none() {
                        missing.push(format!("{what} `{n}`"));
                    }
                    i
                })
                .collect::<Vec<usize>>()
        };
        let inputs = find(Self::input_names(), &|n| project.input(n), "input");
        let outputs = find(Self::output_names(), &|n| project.output(n), "output");
        if missing.is_empty() {
            Ok(TestbedIo {
                names: Self::input_names(),
                inputs,
                outputs,
            })
        } else {
            Err(missing)
        }
    }

    /// The inputs: `s1_t1`, `s1_t2`, … `s26_t2`, then `done1` … `done3`.
    pub fn input_names() -> Vec<String> {
        let mut names: Vec<String> = (1..=SENSORS)
            .flat_map(|k| [format!("s{k}_t1"), format!("s{k}_t2")])
            .collect();
        names.extend((1..=3).map(|u| format!("done{u}")));
        names
    }

    /// The outputs: `go_t1`, `go_t2`, `point1_s`, `point1_d`, …
    /// `point6_d`, `load1` … `load3`.
    pub fn output_names() -> Vec<String> {
        let mut names = vec!["go_t1".to_owned(), "go_t2".to_owned()];
        names.extend((1..=6).flat_map(|w| [format!("point{w}_s"), format!("point{w}_d")]));
        names.extend((1..=3).map(|u| format!("load{u}")));
        names
    }

    /// The values of `inputs` in the order of [`TestbedIo::input_names`].
    fn values(inputs: &Inputs) -> impl Iterator<Item = bool> + '_ {
        inputs.at.iter().flatten().chain(&inputs.done).copied()
    }

    /// Writes `inputs` into the raw image of `sim` (other inputs keep
    /// their values).
    pub fn write_inputs(&self, inputs: &Inputs, sim: &mut Sim) -> Result<(), SimError> {
        for (name, v) in self.names.iter().zip(Self::values(inputs)) {
            sim.set(name, v)?;
        }
        Ok(())
    }

    /// The raw input image of `inputs` for a project of `width` inputs
    /// (the others 0: reset released).
    pub fn raw_image(&self, inputs: &Inputs, width: usize) -> Vec<bool> {
        let mut raw = vec![false; width];
        for (&i, v) in self.inputs.iter().zip(Self::values(inputs)) {
            if let Some(slot) = raw.get_mut(i) {
                *slot = v;
            }
        }
        raw
    }

    /// The testbed's commands in the output image `outputs`.
    pub fn read_outputs(&self, outputs: &[bool]) -> Commands {
        let v: Vec<bool> = self
            .outputs
            .iter()
            .map(|&i| outputs.get(i).copied().unwrap_or(false))
            .collect();
        let mut c = Commands {
            go: [v[0], v[1]],
            ..Commands::default()
        };
        for (w, coils) in c.points.iter_mut().enumerate() {
            *coils = [v[2 + 2 * w], v[3 + 2 * w]];
        }
        c.load = [v[14], v[15], v[16]];
        c
    }
}
