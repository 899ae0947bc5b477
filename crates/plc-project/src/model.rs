//! A validated PLC project: signals, events with their bindings and
//! actions, and the supervisors that run them.
//!
//! Everything here has been checked against everything else (names
//! resolve, outputs are driven once, controllability agrees with the
//! automata, …), so backends can index without further checks. Indices
//! are positions in declaration order.

use des::automaton::{Automaton, EventId, StateId};
use std::ops::Range;
use std::path::PathBuf;

// A pin of `[board]` and its pull are the board data's (crate `boards`).
pub use boards::{PinId, Pull};

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
    /// Moore output of Petri nets: 1 while some listed place of a listed
    /// net holds a token (net index into [`Project::nets`], place indices).
    Places(Vec<(usize, Vec<usize>)>),
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

/// Who causes an uncontrollable event (informational, docs/semantics.md).
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
        /// Reduced (supervisor reduction, closed loop checked).
        reduced: bool,
        /// With `localize`: the controllable event this local controller
        /// decides (the local controllers together, closed loop checked).
        local: Option<String>,
    },
    /// A plant component of `reduced`, a supervisor synthesised with
    /// `reduce = true`, read from `file`: it runs beside the reduced
    /// supervisor, which needs the plant to say what can happen (it was
    /// reduced against it), so that the pair commands and expects exactly
    /// what supcon's supervisor would.
    Plant {
        /// The reduced supervisor.
        reduced: String,
        /// The component's model file.
        file: PathBuf,
    },
    /// A component of the symbolic supervisor `guarded`, read from `file`.
    Component {
        /// The symbolic supervisor.
        guarded: String,
        /// The component's model file.
        file: PathBuf,
    },
}

/// Where a symbolic supervisor's components and guards come from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum GuardedSource {
    /// A guard file (`guards = …`), which names its components' files.
    File(PathBuf),
    /// Synthesised on BDDs at build time (`synthesize = { …, symbolic =
    /// true }`).
    Synthesized {
        /// Plant files.
        plants: Vec<PathBuf>,
        /// Specification files.
        specs: Vec<PathBuf>,
    },
}

/// The guard of one controllable event of a [`Guarded`] supervisor: a
/// decision diagram over [`Guarded::bits`] (docs/formats.md, "Guard
/// files").
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EventGuard {
    /// The event (controllable).
    pub event: usize,
    /// The guard over component states, for people (`M1 = idle ∧ …`).
    pub text: String,
    /// The root: 0 false, 1 true, `k ≥ 2` the node `nodes[k − 2]`.
    pub root: u32,
    /// Decision nodes `[bit, low, high]`, children first; `bit` indexes
    /// [`Guarded::bits`].
    pub nodes: Vec<[u32; 3]>,
}

impl EventGuard {
    /// The guard's value when the supervisors are in `states` (indexed as
    /// [`Project::supervisors`]), its bits placed by `bits`.
    pub fn holds(&self, bits: &[(usize, u32)], states: &[u32]) -> bool {
        des_symbolic::guard_file::walk(self.root, &self.nodes, |b| {
            let (component, shift) = bits[b as usize];
            states[component] >> shift & 1 == 1
        })
    }
}

/// A symbolic supervisor (`[[supervisor]]` with `guards = …` or a symbolic
/// `synthesize`): its components run as the ordinary supervisors
/// `components` of [`Project::supervisors`] (named `name.component`), and
/// a controllable event with a guard may occur only while its guard holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Guarded {
    /// Its name (each component's is `name.component`).
    pub name: String,
    /// Its components, as supervisors of the project.
    pub components: Range<usize>,
    /// The state bits the guards read, in the guard file's bit order:
    /// (supervisor, shift of the bit in its state number).
    pub bits: Vec<(usize, u32)>,
    /// The guards, in event order.
    pub guards: Vec<EventGuard>,
    /// States of the closed loop (exact, decimal), as the guard file says.
    pub closed_loop_states: String,
    /// Where it comes from.
    pub source: GuardedSource,
    /// Line of the `[[supervisor]]` table.
    pub line: u32,
}

impl Guarded {
    /// Whether the guards allow event `e` when the supervisors are in
    /// `states` (an event without a guard is always allowed).
    pub fn allows(&self, e: usize, states: &[u32]) -> bool {
        self.guards
            .iter()
            .find(|g| g.event == e)
            .is_none_or(|g| g.holds(&self.bits, states))
    }
}

/// Where a `[[net]]` comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum NetSource {
    /// A net file run as it is (its control places, if any, included).
    File(PathBuf),
    /// A plant net and constraints, synthesised into control places at
    /// build time (`constraints = …`).
    Synthesized {
        /// The plant net's file.
        plant: PathBuf,
        /// The constraints file.
        constraints: PathBuf,
        /// Whether inadmissible constraints were transformed.
        transform: bool,
    },
}

/// A Petri net run as a supervisor (`[[net]]`): each place a counter
/// wide enough for its bound ([`Net::counter_widths`]), each transition the
/// project's event of the same name. How the counters are packed into
/// executor supervisors is lowering's business (`codegen::lower::nets`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Net {
    /// Its name.
    pub name: String,
    /// The net run: the plant's places and transitions, then the control
    /// places when synthesised.
    pub net: des::petri::PetriNet,
    /// The project event of each transition, in transition order.
    pub events: Vec<usize>,
    /// The largest number of tokens each place reaches.
    pub bounds: Vec<u32>,
    /// Reachable markings of the net.
    pub markings: usize,
    /// The control places (the last ones), 0 for a net run as it is.
    pub control_places: usize,
    /// Where it comes from.
    pub source: NetSource,
    /// Line of the `[[net]]` table.
    pub line: u32,
}

/// The widest counter a place may need: the executor packs counters into
/// words of this many bits ([`executor::table::NET_GROUP_BITS`]), so a
/// counter holds at most 2^31 − 1 tokens.
pub const COUNTER_BITS: u32 = executor::table::NET_GROUP_BITS;

impl Net {
    /// The bits of each place's counter in `net`, whose reachable markings
    /// have `bounds`: enough for the bound and for the weight of every arc
    /// on the place (an input arc heavier than the bound is what keeps its
    /// transition from ever firing, so the counter's `PRE` must hold it),
    /// at least 1. Validation refuses a net whose counters need more than
    /// [`COUNTER_BITS`].
    pub fn counter_widths(net: &des::petri::PetriNet, bounds: &[u32]) -> Vec<u32> {
        let mut largest = bounds.to_vec();
        for t in net.transitions() {
            for &(p, w) in t.input.iter().chain(&t.output) {
                largest[p] = largest[p].max(w);
            }
        }
        largest
            .iter()
            .map(|&x| (u32::BITS - x.leading_zeros()).max(1))
            .collect()
    }

    /// The bits of each of its places' counters ([`Net::counter_widths`]).
    pub fn widths(&self) -> Vec<u32> {
        Net::counter_widths(&self.net, &self.bounds)
    }
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
    /// The most minimisation effort the logic backend may spend on it, as
    /// the project states it; `None`: the backend's default
    /// (`codegen::backend::logic::DEFAULT_MAX_EFFORT`).
    pub max_logic_effort: Option<u64>,
}

impl Supervisor {
    /// Global event `e`'s column in this supervisor (its position among
    /// the local events) and the automaton's id for it; `None` when `e` is
    /// not in its alphabet.
    pub fn local(&self, e: usize) -> Option<(usize, EventId)> {
        let k = self.local_events.iter().position(|&(g, _)| g == e)?;
        Some((k, self.local_events[k].1))
    }
}

/// A warning of validation (the project is still usable).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// Line in the project file.
    pub line: u32,
    /// What is odd.
    pub message: String,
}

/// Why an input's changes are or are not latched between samples by an
/// edge interrupt (both edges of its EXTI line, [`boards::Chip::exti_line`]),
/// which is what detects lost edges (docs/semantics.md, `LostEdge`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeLatch {
    /// Every change is counted; more than one between two samples is a
    /// lost edge.
    Latched,
    /// Not latched: the input is debounced (`debounce_scans > 1`), so short
    /// pulses are meant to be filtered out, not reported.
    Debounced,
    /// Not latched: an earlier input (this index) owns the EXTI line of
    /// the same pin number on another port (one port per line).
    LineTaken(usize),
}

/// The pin of an input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputPin {
    /// The MCU pin.
    pub pin: PinId,
    /// Internal pull resistor.
    pub pull: Pull,
    /// The signal is 1 while the pin is low.
    pub active_low: bool,
    /// Edge-interrupt latching (lost-edge detection).
    pub edge_latch: EdgeLatch,
    /// Line of the mapping in the project file.
    pub line: u32,
}

/// The pin of an output (push-pull).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputPin {
    /// The MCU pin.
    pub pin: PinId,
    /// The pin is driven low while the signal is 1.
    pub active_low: bool,
    /// Line of the mapping in the project file.
    pub line: u32,
}

/// The `[board]` section: the MCU and the pin of each signal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Board {
    /// The chip, as probe-rs names it (default `STM32F411RETx`,
    /// [`boards::DEFAULT_CHIP`]).
    pub chip: String,
    /// What the board data knows about that chip: its pins, the EXTI rule,
    /// the watchdog.
    pub mcu: &'static boards::Chip,
    /// Pin of each input, by input index (`None`: not wired, reads 0).
    pub inputs: Vec<Option<InputPin>>,
    /// Pin of each output, by output index (`None`: not driven).
    pub outputs: Vec<Option<OutputPin>>,
    /// Line of the section header.
    pub line: u32,
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
    /// Bytes of the program image the background test checks per scan.
    pub rom_test_bytes_per_scan: u16,
    /// The most flash one supervisor's stored allowed sets may take (its
    /// index and the sets it adds); a supervisor needing more computes
    /// them when it moves (docs/formats.md, `[plc]`). 0: none stored.
    pub stored_sets_bytes: u32,
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
    /// Petri nets in declaration order; their groups run as supervisors
    /// after [`Project::supervisors`].
    pub nets: Vec<Net>,
    /// Symbolic supervisors, in declaration order: their components are
    /// among [`Project::supervisors`], their guards restrict commands.
    pub guarded: Vec<Guarded>,
    /// The board wiring (`[board]`), if the project has one.
    pub board: Option<Board>,
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
