//! The boiler's signals as the PLC sees them: seven inputs, eight outputs,
//! typed images of both, and their binding to a project by name.
//!
//! The names are fixed (docs/seeds.md A and the boiler project): a project runs
//! in closed loop with the boiler plant exactly when it declares all of
//! them. Other inputs and outputs of the project are left alone.

use super::error::BoilerError;
use executor::program::Config;
use plc_project::Project;

/// One of the boiler's PLC inputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Input {
    /// Selector contact "high fire" (`sel_high`).
    SelHigh,
    /// Selector contact "low fire" (`sel_low`); both contacts open = off.
    SelLow,
    /// Pilot flame detector (`pilot_flame`).
    PilotFlame,
    /// Main flame detector (`main_flame`).
    MainFlame,
    /// Water-bath over-temperature limit switch (`bath_hot`).
    BathHot,
    /// Flue-gas over-temperature limit switch (`flue_hot`).
    FlueHot,
    /// Operator reset push-button (`reset`).
    Reset,
}

impl Input {
    /// Every input, in image order.
    pub const ALL: [Input; 7] = [
        Input::SelHigh,
        Input::SelLow,
        Input::PilotFlame,
        Input::MainFlame,
        Input::BathHot,
        Input::FlueHot,
        Input::Reset,
    ];

    /// The signal name in the project.
    pub fn name(self) -> &'static str {
        match self {
            Input::SelHigh => "sel_high",
            Input::SelLow => "sel_low",
            Input::PilotFlame => "pilot_flame",
            Input::MainFlame => "main_flame",
            Input::BathHot => "bath_hot",
            Input::FlueHot => "flue_hot",
            Input::Reset => "reset",
        }
    }

    /// The position in [`Input::ALL`] (for per-input arrays).
    pub fn index(self) -> usize {
        self as usize
    }
}

/// One of the boiler's PLC outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Output {
    /// Pilot gas valve (`pilot_valve`).
    PilotValve,
    /// Ignition transformer, the spark (`ignition`).
    Ignition,
    /// Main gas valve, low-fire position (`main_valve_lo`).
    MainValveLo,
    /// Main gas valve, high-fire position (`main_valve_hi`).
    MainValveHi,
    /// Air damper, low position (`damper_lo`).
    DamperLo,
    /// Air damper, high position (`damper_hi`).
    DamperHi,
    /// Combustion-air blower (`blower`).
    Blower,
    /// Lock-out alarm lamp (`alarm`).
    Alarm,
}

impl Output {
    /// Every output, in image order.
    pub const ALL: [Output; 8] = [
        Output::PilotValve,
        Output::Ignition,
        Output::MainValveLo,
        Output::MainValveHi,
        Output::DamperLo,
        Output::DamperHi,
        Output::Blower,
        Output::Alarm,
    ];

    /// The fuel valves: gas reaches the burner while one of them is open.
    pub const FUEL: [Output; 3] = [Output::PilotValve, Output::MainValveLo, Output::MainValveHi];

    /// The signal name in the project.
    pub fn name(self) -> &'static str {
        match self {
            Output::PilotValve => "pilot_valve",
            Output::Ignition => "ignition",
            Output::MainValveLo => "main_valve_lo",
            Output::MainValveHi => "main_valve_hi",
            Output::DamperLo => "damper_lo",
            Output::DamperHi => "damper_hi",
            Output::Blower => "blower",
            Output::Alarm => "alarm",
        }
    }
}

/// The operator's selector switch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Selector {
    /// Both contacts open: the boiler is off.
    #[default]
    Off,
    /// Low fire (`sel_low` closed).
    Low,
    /// High fire (`sel_high` closed).
    High,
}

impl Selector {
    /// `off`, `low` or `high`.
    pub fn name(self) -> &'static str {
        match self {
            Selector::Off => "off",
            Selector::Low => "low",
            Selector::High => "high",
        }
    }
}

/// The boiler's input image (one level per [`Input`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Inputs {
    /// `sel_high`.
    pub sel_high: bool,
    /// `sel_low`.
    pub sel_low: bool,
    /// `pilot_flame`.
    pub pilot_flame: bool,
    /// `main_flame`.
    pub main_flame: bool,
    /// `bath_hot`.
    pub bath_hot: bool,
    /// `flue_hot`.
    pub flue_hot: bool,
    /// `reset`.
    pub reset: bool,
}

impl Inputs {
    /// The level of `input`.
    pub fn get(&self, input: Input) -> bool {
        match input {
            Input::SelHigh => self.sel_high,
            Input::SelLow => self.sel_low,
            Input::PilotFlame => self.pilot_flame,
            Input::MainFlame => self.main_flame,
            Input::BathHot => self.bath_hot,
            Input::FlueHot => self.flue_hot,
            Input::Reset => self.reset,
        }
    }

    /// Sets the level of `input`.
    pub fn set(&mut self, input: Input, value: bool) {
        *match input {
            Input::SelHigh => &mut self.sel_high,
            Input::SelLow => &mut self.sel_low,
            Input::PilotFlame => &mut self.pilot_flame,
            Input::MainFlame => &mut self.main_flame,
            Input::BathHot => &mut self.bath_hot,
            Input::FlueHot => &mut self.flue_hot,
            Input::Reset => &mut self.reset,
        } = value;
    }

    /// The selector is on (either contact closed).
    pub fn selector_on(&self) -> bool {
        self.sel_high || self.sel_low
    }

    /// The selector position; both contacts closed (a wiring fault) reads
    /// as high.
    pub fn selector(&self) -> Selector {
        match (self.sel_high, self.sel_low) {
            (true, _) => Selector::High,
            (false, true) => Selector::Low,
            (false, false) => Selector::Off,
        }
    }
}

/// The boiler's output image (one level per [`Output`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Outputs {
    /// `pilot_valve`.
    pub pilot_valve: bool,
    /// `ignition`.
    pub ignition: bool,
    /// `main_valve_lo`.
    pub main_valve_lo: bool,
    /// `main_valve_hi`.
    pub main_valve_hi: bool,
    /// `damper_lo`.
    pub damper_lo: bool,
    /// `damper_hi`.
    pub damper_hi: bool,
    /// `blower`.
    pub blower: bool,
    /// `alarm`.
    pub alarm: bool,
}

impl Outputs {
    /// The level of `output`.
    pub fn get(&self, output: Output) -> bool {
        match output {
            Output::PilotValve => self.pilot_valve,
            Output::Ignition => self.ignition,
            Output::MainValveLo => self.main_valve_lo,
            Output::MainValveHi => self.main_valve_hi,
            Output::DamperLo => self.damper_lo,
            Output::DamperHi => self.damper_hi,
            Output::Blower => self.blower,
            Output::Alarm => self.alarm,
        }
    }

    /// Sets the level of `output`.
    pub fn set(&mut self, output: Output, value: bool) {
        *match output {
            Output::PilotValve => &mut self.pilot_valve,
            Output::Ignition => &mut self.ignition,
            Output::MainValveLo => &mut self.main_valve_lo,
            Output::MainValveHi => &mut self.main_valve_hi,
            Output::DamperLo => &mut self.damper_lo,
            Output::DamperHi => &mut self.damper_hi,
            Output::Blower => &mut self.blower,
            Output::Alarm => &mut self.alarm,
        } = value;
    }

    /// A main valve position is open.
    pub fn main_open(&self) -> bool {
        self.main_valve_lo || self.main_valve_hi
    }

    /// Some fuel valve (pilot or main) is open.
    pub fn fuel_open(&self) -> bool {
        self.pilot_valve || self.main_open()
    }

    /// A damper position is open.
    pub fn damper_open(&self) -> bool {
        self.damper_lo || self.damper_hi
    }

    /// Combustion air reaches the burner: blower on and a damper open.
    pub fn air(&self) -> bool {
        self.blower && self.damper_open()
    }
}

/// Where the boiler's signals are in a project's input and output images.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IoMap {
    inputs: [usize; Input::ALL.len()],
    outputs: [usize; Output::ALL.len()],
    input_count: usize,
    output_count: usize,
}

impl IoMap {
    /// Looks every boiler signal up in `project` by name; the error lists
    /// all the missing ones.
    pub fn new(project: &Project) -> Result<IoMap, BoilerError> {
        let mut missing = Vec::new();
        let mut inputs = [0; Input::ALL.len()];
        for input in Input::ALL {
            match project.input(input.name()) {
                Some(i) => inputs[input.index()] = i,
                None => missing.push(format!("input `{}`", input.name())),
            }
        }
        let mut outputs = [0; Output::ALL.len()];
        for (k, output) in Output::ALL.into_iter().enumerate() {
            match project.output(output.name()) {
                Some(o) => outputs[k] = o,
                None => missing.push(format!("output `{}`", output.name())),
            }
        }
        if !missing.is_empty() {
            return Err(BoilerError::MissingSignals {
                project: project.name.clone(),
                missing,
            });
        }
        Ok(IoMap {
            inputs,
            outputs,
            input_count: project.inputs.len(),
            output_count: project.outputs.len(),
        })
    }

    /// The project's index of `input`.
    pub fn input(&self, input: Input) -> usize {
        self.inputs[input.index()]
    }

    /// The project's index of `output`.
    pub fn output(&self, output: Output) -> usize {
        self.outputs[output as usize]
    }

    /// The `debounce_scans` of every boiler input in `config` (the
    /// lowered configuration of the project), by [`Input::index`].
    pub fn debounce(&self, config: &Config<'_>) -> [u8; Input::ALL.len()] {
        Input::ALL.map(|input| {
            config.inputs.get(self.input(input)).map_or(0, |spec| {
                executor::program::InputSpec::from_words(spec).debounce_scans
            })
        })
    }

    /// The boiler inputs in a raw image of the project.
    pub fn inputs_of(&self, raw: &[bool]) -> Result<Inputs, BoilerError> {
        check_width(raw, self.input_count, "input")?;
        let mut image = Inputs::default();
        for input in Input::ALL {
            image.set(input, raw[self.input(input)]);
        }
        Ok(image)
    }

    /// The project's raw input image holding the boiler's `inputs` at
    /// their indices, every other input 0: the inverse of
    /// [`IoMap::inputs_of`].
    pub fn raw_inputs(&self, inputs: &Inputs) -> Vec<bool> {
        let mut raw = vec![false; self.input_count];
        for input in Input::ALL {
            raw[self.input(input)] = inputs.get(input);
        }
        raw
    }

    /// The boiler outputs in a raw output image of the project.
    pub fn outputs_of(&self, raw: &[bool]) -> Result<Outputs, BoilerError> {
        check_width(raw, self.output_count, "output")?;
        let mut image = Outputs::default();
        for output in Output::ALL {
            image.set(output, raw[self.output(output)]);
        }
        Ok(image)
    }
}

fn check_width(raw: &[bool], expected: usize, what: &'static str) -> Result<(), BoilerError> {
    if raw.len() == expected {
        Ok(())
    } else {
        Err(BoilerError::ImageWidth {
            what,
            expected,
            got: raw.len(),
        })
    }
}
