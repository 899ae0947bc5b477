//! The cell's PLC signals by name (`models/petri/cell/cell.plc.toml`):
//! what the plant shows the controller ([`Sensors`]) and what the
//! controller drives ([`Commands`]), and where each is in a project
//! ([`CellIo`]).

use crate::sim::{Sim, SimError};
use plc_project::Project;

/// A mixing tank: `a` or `b` in the paper's subscripts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// Mixing tank a, reactor a.
    A = 0,
    /// Mixing tank b, reactor b.
    B = 1,
}

impl Unit {
    /// Both, in order.
    pub const BOTH: [Unit; 2] = [Unit::A, Unit::B];

    /// The other one.
    pub fn other(self) -> Unit {
        match self {
            Unit::A => Unit::B,
            Unit::B => Unit::A,
        }
    }

    /// `a` or `b`.
    pub fn letter(self) -> char {
        match self {
            Unit::A => 'a',
            Unit::B => 'b',
        }
    }
}

/// What a mixing tank's valves and stirrer are told.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MixerCommands {
    /// V_ma, the filling valve.
    pub fill: bool,
    /// V_sa, V_sb, V_sc: the supply valves of components a, b, c.
    pub supply: [bool; 3],
    /// The stirrer.
    pub stirrer: bool,
    /// V_mb, the discharge valve.
    pub discharge: bool,
}

/// What a reactor's valves, stirrer and temperature controller are told.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReactorCommands {
    /// V_ra, the inlet of chemical A (from its own mixing tank).
    pub inlet_a: bool,
    /// V_rb, the inlet of chemical B (from the other mixing tank).
    pub inlet_b: bool,
    /// The stirrer.
    pub stirrer: bool,
    /// The temperature controller runs.
    pub tc_on: bool,
    /// Its setpoint is the output temperature (cooling), not the reaction
    /// temperature.
    pub tc_cool: bool,
    /// V_rc, the discharge valve.
    pub drain: bool,
}

/// The output image of the cell, by unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Commands {
    /// Mixing tanks a, b.
    pub mixers: [MixerCommands; 2],
    /// Reactors a, b.
    pub reactors: [ReactorCommands; 2],
}

/// The mixing tank's switches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MixerSensors {
    /// Level of component a or b reached.
    pub level1: bool,
    /// Full: component c added.
    pub full: bool,
    /// Empty.
    pub empty: bool,
}

/// The reactor's switches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReactorSensors {
    /// Temperature within the band of the reaction temperature.
    pub setpoint: bool,
    /// Temperature down to the output temperature (within the band).
    pub output_temp: bool,
    /// Level at or below the minimum switch.
    pub empty: bool,
    /// V_ra's open limit switch.
    pub inlet_a_open: bool,
    /// V_rb's open limit switch.
    pub inlet_b_open: bool,
}

/// The input image of the cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sensors {
    /// The operator's start buttons, by reactor.
    pub start: [bool; 2],
    /// Mixing tanks a, b.
    pub mixers: [MixerSensors; 2],
    /// Reactors a, b.
    pub reactors: [ReactorSensors; 2],
}

const MIXER_OUTPUTS: [&str; 6] = [
    "fill",
    "supply_a",
    "supply_b",
    "supply_c",
    "stirrer",
    "discharge",
];
const REACTOR_OUTPUTS: [&str; 6] = ["inlet_a", "inlet_b", "stirrer", "tc_on", "tc_cool", "drain"];
const MIXER_INPUTS: [&str; 3] = ["level1", "full", "empty"];
const REACTOR_INPUTS: [&str; 5] = [
    "setpoint",
    "output_temp",
    "empty",
    "inlet_a_open",
    "inlet_b_open",
];

/// Where the cell's signals are in a project: the input names of
/// [`CellIo::input_names`] (all declared), output indices in the order of
/// [`CellIo::output_names`].
#[derive(Debug, Clone)]
pub struct CellIo {
    inputs: Vec<(String, usize)>,
    outputs: Vec<usize>,
}

impl CellIo {
    /// The cell's signals in `project`, or the names it lacks.
    pub fn new(project: &Project) -> Result<CellIo, Vec<String>> {
        let mut missing = Vec::new();
        let mut find = |names: Vec<String>, look: &dyn Fn(&str) -> Option<usize>, what: &str| {
            let found: Vec<usize> = names
                .iter()
                .filter_map(|n| {
                    let i = look(n);
                    if i.is_none() {
                        missing.push(format!("{what} `{n}`"));
                    }
                    i
                })
                .collect();
            found
        };
        let inputs = Self::input_names()
            .into_iter()
            .zip(find(Self::input_names(), &|n| project.input(n), "input"))
            .collect();
        let outputs = find(Self::output_names(), &|n| project.output(n), "output");
        if missing.is_empty() {
            Ok(CellIo { inputs, outputs })
        } else {
            Err(missing)
        }
    }

    /// The inputs: the start buttons, then each mixing tank's switches,
    /// then each reactor's.
    pub fn input_names() -> Vec<String> {
        let mut names = vec!["start_ra".to_owned(), "start_rb".to_owned()];
        for u in Unit::BOTH {
            names.extend(MIXER_INPUTS.iter().map(|s| format!("m{}_{s}", u.letter())));
        }
        for u in Unit::BOTH {
            names.extend(
                REACTOR_INPUTS
                    .iter()
                    .map(|s| format!("r{}_{s}", u.letter())),
            );
        }
        names
    }

    /// The outputs: each mixing tank's, then each reactor's.
    pub fn output_names() -> Vec<String> {
        let mut names = Vec::new();
        for u in Unit::BOTH {
            names.extend(MIXER_OUTPUTS.iter().map(|s| format!("m{}_{s}", u.letter())));
        }
        for u in Unit::BOTH {
            names.extend(
                REACTOR_OUTPUTS
                    .iter()
                    .map(|s| format!("r{}_{s}", u.letter())),
            );
        }
        names
    }

    /// Sets `sensors` as the inputs of `sim` (other inputs keep their
    /// values).
    pub fn write_inputs(&self, sensors: &Sensors, sim: &mut Sim) -> Result<(), SimError> {
        for ((name, _), v) in self.inputs.iter().zip(Self::values(sensors)) {
            sim.set(name, v)?;
        }
        Ok(())
    }

    /// The raw input image of `sensors` for a project of `width` inputs
    /// (the others 0).
    pub fn raw_image(&self, sensors: &Sensors, width: usize) -> Vec<bool> {
        let mut raw = vec![false; width];
        for (&(_, i), v) in self.inputs.iter().zip(Self::values(sensors)) {
            raw[i] = v;
        }
        raw
    }

    /// The values of `sensors` in the order of [`CellIo::input_names`].
    fn values(sensors: &Sensors) -> Vec<bool> {
        let mut values = sensors.start.to_vec();
        for m in &sensors.mixers {
            values.extend([m.level1, m.full, m.empty]);
        }
        for r in &sensors.reactors {
            values.extend([
                r.setpoint,
                r.output_temp,
                r.empty,
                r.inlet_a_open,
                r.inlet_b_open,
            ]);
        }
        values
    }

    /// The cell's commands in the output image `outputs`.
    pub fn read_outputs(&self, outputs: &[bool]) -> Commands {
        let v: Vec<bool> = self.outputs.iter().map(|&i| outputs[i]).collect();
        let mixer = |o: &[bool]| MixerCommands {
            fill: o[0],
            supply: [o[1], o[2], o[3]],
            stirrer: o[4],
            discharge: o[5],
        };
        let reactor = |o: &[bool]| ReactorCommands {
            inlet_a: o[0],
            inlet_b: o[1],
            stirrer: o[2],
            tc_on: o[3],
            tc_cool: o[4],
            drain: o[5],
        };
        Commands {
            mixers: [mixer(&v[0..6]), mixer(&v[6..12])],
            reactors: [reactor(&v[12..18]), reactor(&v[18..24])],
        }
    }
}
