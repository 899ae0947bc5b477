//! A validated PLC project: signals, events with their bindings and
//! actions, and the supervisors that run them.
//!
//! Everything here has been checked against everything else (names
//! resolve, outputs are driven once, controllability agrees with the
//! automata, …), so backends can index without further checks. Indices
//! are positions in declaration order.

use crate::automaton::{Automaton, EventId, StateId};
use std::path::PathBuf;

/// What to do with an uncontrollable event no supervisor can explain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Unexpected {
    /// Fault mode until reset (default).
    #[default]
    Fault,
    /// Drop, count and trace it.
    Ignore,
}

/// An input signal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Input {
    /// Name as written in the project.
    pub name: String,
    /// Debounce (0 and 1: none).
    pub debounce_scans: u8,
    /// Line of the declaration.
    pub line: u32,
}

/// How an output is driven.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Drive {
    /// Latched by event actions; level at start and after reset.
    Actions {
        /// Initial level.
        initial: bool,
    },
    /// Moore output: 1 while some listed supervisor is in a listed state.
    States(Vec<(usize, Vec<StateId>)>),
}

/// An output signal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Output {
    /// Name.
    pub name: String,
    /// Level in fault mode.
    pub safe: bool,
    /// How it is driven.
    pub drive: Drive,
    /// Line of the declaration.
    pub line: u32,
}

/// A timer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Timer {
    /// Name.
    pub name: String,
    /// Preset, `0 < preset < 2^31` ms.
    pub preset_ms: u32,
    /// Line of the declaration.
    pub line: u32,
}

/// An (n+1)-state switch: named positions, each raising one output.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Switch {
    /// Name.
    pub name: String,
    /// (position, output index), in declaration order; `off` is implicit.
    pub positions: Vec<(String, usize)>,
    /// Line of the declaration.
    pub line: u32,
}

/// What makes an uncontrollable event occur.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Trigger {
    /// Controllable: chosen by the controller.
    Command,
    /// Rising edge of the OR of these inputs.
    Rising(Vec<usize>),
    /// Falling edge of the OR of these inputs.
    Falling(Vec<usize>),
    /// Expiry of this timer.
    Expired(usize),
}

/// One change an executed event makes (switch positions are already
/// expanded into sets and clears).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Raise an output.
    Set(usize),
    /// Lower an output.
    Clear(usize),
    /// Start or restart a timer.
    Start(usize),
    /// Stop a timer.
    Reset(usize),
}

/// Who causes an uncontrollable event (informational, SEMANTICS.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Origin {
    /// The controller (controllable events).
    #[default]
    Controller,
    /// An operator input (Σu,i).
    Operator,
    /// A plant response (Σu,p).
    Plant,
}

/// An event of the global alphabet.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Event {
    /// Name (also its name in the automata).
    pub name: String,
    /// `true` for Σc.
    pub controllable: bool,
    /// Operator or plant for uncontrollable events.
    pub origin: Origin,
    /// Source of an uncontrollable event; `Command` for controllable ones.
    pub trigger: Trigger,
    /// Inputs that must be 1 in the same scan.
    pub when: Vec<usize>,
    /// Inputs that must be 0.
    pub unless: Vec<usize>,
    /// Manual-mode request input (controllable events).
    pub request: Option<usize>,
    /// Actions, in application order.
    pub actions: Vec<Action>,
    /// Line of the declaration.
    pub line: u32,
}

/// Where a supervisor came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SupervisorSource {
    /// Read from a file (any supported format).
    File(PathBuf),
    /// Synthesised at build time.
    Synthesized {
        /// Plant files.
        plants: Vec<PathBuf>,
        /// Specification files.
        specs: Vec<PathBuf>,
        /// Minimised with `minstate`.
        minimized: bool,
    },
}

/// A supervisor of the project.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Supervisor {
    /// Unique name (trace column `states`, state-map keys).
    pub name: String,
    /// The automaton (deterministic, with an initial state).
    pub automaton: Automaton,
    /// Local alphabet: the automaton's events in global declaration order,
    /// as (global event index, automaton event id).
    pub local_events: Vec<(usize, EventId)>,
    /// Where it came from.
    pub source: SupervisorSource,
    /// Line of the declaration.
    pub line: u32,
}

/// A warning of validation (the project is still usable).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// Line in the project file.
    pub line: u32,
    /// What is odd.
    pub message: String,
}

/// A validated PLC project.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Project {
    /// The project file.
    pub path: PathBuf,
    /// Project name.
    pub name: String,
    /// Nominal scan period.
    pub scan_period_ms: u32,
    /// Controllable events per scan; 0 = no limit.
    pub max_commands_per_scan: u16,
    /// Policy for unexpected events.
    pub unexpected: Unexpected,
    /// Reset input (index into `inputs`).
    pub reset: Option<usize>,
    /// Periods late before a scan counts as overrun.
    pub overrun_limit: u16,
    /// Overruns are faults.
    pub overrun_fault: bool,
    /// Lost edges are faults.
    pub lost_edge_fault: bool,
    /// Inputs in declaration order.
    pub inputs: Vec<Input>,
    /// Outputs in declaration order.
    pub outputs: Vec<Output>,
    /// Timers in declaration order.
    pub timers: Vec<Timer>,
    /// Switches in declaration order.
    pub switches: Vec<Switch>,
    /// Events in declaration (priority) order.
    pub events: Vec<Event>,
    /// Supervisors in declaration order.
    pub supervisors: Vec<Supervisor>,
    /// Validation warnings.
    pub warnings: Vec<Warning>,
    /// Every file the project was built from (for `rerun-if-changed`).
    pub files: Vec<PathBuf>,
}

impl Project {
    /// The index of the input called `name`.
    pub fn input(&self, name: &str) -> Option<usize> {
        self.inputs.iter().position(|i| i.name == name)
    }

    /// The index of the output called `name`.
    pub fn output(&self, name: &str) -> Option<usize> {
        self.outputs.iter().position(|o| o.name == name)
    }

    /// The index of the event called `name`.
    pub fn event(&self, name: &str) -> Option<usize> {
        self.events.iter().position(|e| e.name == name)
    }

    /// The index of the supervisor called `name`.
    pub fn supervisor(&self, name: &str) -> Option<usize> {
        self.supervisors.iter().position(|s| s.name == name)
    }
}
