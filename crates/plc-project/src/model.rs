//! A validated PLC project: signals, events with their bindings and
//! actions, and the supervisors that run them.
//!
//! Everything here has been checked against everything else (names
//! resolve, outputs are driven once, controllability agrees with the
//! automata, …), so backends can index without further checks. Indices
//! are positions in declaration order.

use des::automaton::{Automaton, EventId, StateId};
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
    },
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

/// A place's counter: which group of the net holds it, and where.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlaceField {
    /// The group (an executor supervisor of the net), from 0.
    pub group: usize,
    /// Its lowest bit in the group's packed marking.
    pub shift: u8,
    /// Its width in bits (enough for the place's bound, at least 1).
    pub width: u8,
}

impl PlaceField {
    /// The mask of the counter's bits.
    pub fn mask(&self) -> u32 {
        (((1u64 << self.width) - 1) as u32) << self.shift
    }
}

/// A Petri net run as a supervisor (`[[net]]`): its places as counters
/// packed into groups of at most 31 bits, each group one executor
/// supervisor, its transitions the project's events of the same names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Net {
    /// Its name.
    pub name: String,
    /// The net run: the plant's places and transitions, then the control
    /// places when synthesised.
    pub net: des::petri::PetriNet,
    /// The project event of each transition, in transition order.
    pub events: Vec<usize>,
    /// The counter of each place, in place order.
    pub fields: Vec<PlaceField>,
    /// The largest number of tokens each place reaches.
    pub bounds: Vec<u32>,
    /// The bits of each group.
    pub group_bits: Vec<u8>,
    /// Reachable markings of the net.
    pub markings: usize,
    /// The control places (the last ones), 0 for a net run as it is.
    pub control_places: usize,
    /// Where it comes from.
    pub source: NetSource,
    /// Line of the `[[net]]` table.
    pub line: u32,
}

/// Bits of a group's packed marking: the most the executor's net layout
/// holds ([`executor::table::NET_GROUP_BITS`]).
pub const GROUP_BITS: u32 = executor::table::NET_GROUP_BITS;

impl Net {
    /// The counters of `net`'s places, whose reachable markings have
    /// `bounds`: each wide enough for its bound and for the weight of every
    /// arc on it (an input arc heavier than the bound is what keeps its
    /// transition from ever firing, so its `PRE` must hold it), at least
    /// one bit, packed in place order into groups of at most
    /// [`GROUP_BITS`] bits; the fields and each group's bits. `Err` names
    /// the first place that needs a wider counter.
    pub fn pack_fields(
        net: &des::petri::PetriNet,
        bounds: &[u32],
    ) -> Result<(Vec<PlaceField>, Vec<u8>), usize> {
        let mut largest = bounds.to_vec();
        for t in net.transitions() {
            for &(p, w) in t.input.iter().chain(&t.output) {
                largest[p] = largest[p].max(w);
            }
        }
        let mut fields = Vec::with_capacity(bounds.len());
        let mut group_bits: Vec<u8> = Vec::new();
        for (p, &bound) in largest.iter().enumerate() {
            let width = (u32::BITS - bound.leading_zeros()).max(1);
            if width > GROUP_BITS {
                return Err(p);
            }
            let fits = group_bits
                .last()
                .is_some_and(|&used| u32::from(used) + width <= GROUP_BITS);
            if !fits {
                group_bits.push(0);
            }
            let group = group_bits.len() - 1;
            fields.push(PlaceField {
                group,
                shift: group_bits[group],
                width: width as u8,
            });
            group_bits[group] += width as u8;
        }
        Ok((fields, group_bits))
    }

    /// Number of groups (executor supervisors).
    pub fn groups(&self) -> usize {
        self.group_bits.len()
    }

    /// The name of group `g`: the net's name when it has one group,
    /// `name.1`, `name.2`, … otherwise.
    pub fn group_name(&self, g: usize) -> String {
        if self.groups() == 1 {
            self.name.clone()
        } else {
            format!("{}.{}", self.name, g + 1)
        }
    }

    /// The places of group `g`, in place order.
    pub fn group_places(&self, g: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.fields.len()).filter(move |&p| self.fields[p].group == g)
    }

    /// The transitions with an arc to a place of group `g`, in transition
    /// order: the group's local events.
    pub fn group_transitions(&self, g: usize) -> Vec<usize> {
        let touches = |arcs: &[(usize, u32)]| arcs.iter().any(|&(p, _)| self.fields[p].group == g);
        (0..self.net.transitions().len())
            .filter(|&t| {
                let tr = &self.net.transitions()[t];
                touches(&tr.input) || touches(&tr.output)
            })
            .collect()
    }

    /// A marking packed into group `g`'s state.
    pub fn pack(&self, g: usize, marking: &[u32]) -> u32 {
        self.group_places(g)
            .map(|p| (marking[p] << self.fields[p].shift) & self.fields[p].mask())
            .fold(0, |x, bits| x | bits)
    }

    /// The marking of the net from the states of its groups, in group
    /// order.
    pub fn unpack(&self, groups: &[u32]) -> des::petri::Marking {
        self.fields
            .iter()
            .map(|f| {
                groups
                    .get(f.group)
                    .map_or(0, |&x| (x & f.mask()) >> f.shift)
            })
            .collect()
    }

    /// The state of group `g` named by [`Net::state_name`], `None` if
    /// the name is not a marking of the group's places.
    pub fn parse_state(&self, g: usize, name: &str) -> Option<u32> {
        use des::petri::read_marking_term;
        if name == "0" {
            return Some(0);
        }
        let mut x = 0u32;
        let mut rest = name;
        loop {
            // A count `k·` before the id, when more than one token.
            let (count, after) = match rest.split_once('·') {
                Some((k, after)) if !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()) => {
                    (k.parse::<u32>().ok()?, after)
                }
                _ => (1, rest),
            };
            let (id, tail) = read_marking_term(after, " + ")?;
            let p = self.net.place(&id)?;
            let f = self.fields[p];
            if f.group != g || count > f.mask() >> f.shift {
                return None;
            }
            x |= count << f.shift;
            match tail.strip_prefix(" + ") {
                Some(next) => rest = next,
                None if tail.is_empty() => return Some(x),
                None => return None,
            }
        }
    }

    /// Group `g`'s state read as the marking of its places: `p_1 + 2·p_3`
    /// style, `0` for no token; an id that could be misread (`a + b`, `0`)
    /// quoted, so that [`Net::parse_state`] reads every name back.
    pub fn state_name(&self, g: usize, state: u32) -> String {
        let terms: Vec<String> = self
            .group_places(g)
            .filter_map(|p| {
                let f = self.fields[p];
                let count = (state & f.mask()) >> f.shift;
                let id = des::petri::marking_term(&self.net.places()[p].id, "0");
                match count {
                    0 => None,
                    1 => Some(id),
                    k => Some(format!("{k}·{id}")),
                }
            })
            .collect();
        if terms.is_empty() {
            "0".to_owned()
        } else {
            terms.join(" + ")
        }
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

    /// The number of supervisors the executor runs: the automata, then
    /// the groups of every net.
    pub fn executor_supervisors(&self) -> usize {
        self.supervisors.len() + self.nets.iter().map(Net::groups).sum::<usize>()
    }

    /// The net and group of executor supervisor `j`, `None` for an
    /// automaton.
    pub fn net_group(&self, j: usize) -> Option<(usize, usize)> {
        let mut first = self.supervisors.len();
        for (n, net) in self.nets.iter().enumerate() {
            if (first..first + net.groups()).contains(&j) {
                return Some((n, j - first));
            }
            first += net.groups();
        }
        None
    }

    /// The executor supervisor named `name`: an automaton's, or a net
    /// group's ([`Net::group_name`]).
    pub fn executor_supervisor(&self, name: &str) -> Option<usize> {
        self.supervisor(name).or_else(|| {
            (self.supervisors.len()..self.executor_supervisors())
                .find(|&j| self.supervisor_name(j) == name)
        })
    }

    /// Whether every supervisor and net group in `states` (the executor's
    /// state vector) lets event `e` occur.
    pub fn event_feasible(&self, e: usize, states: &[u32]) -> bool {
        let automata = self.supervisors.iter().enumerate().all(|(j, sup)| {
            sup.local(e).is_none_or(|(_, id)| {
                states.get(j).is_some_and(|&x| {
                    (x as usize) < sup.automaton.num_states()
                        && sup.automaton.successor(StateId(x), id).is_some()
                })
            })
        });
        automata
            && self.nets.iter().enumerate().all(|(n, net)| {
                let first = self.group_supervisor(n, 0);
                let groups = states.get(first..first + net.groups()).unwrap_or(&[]);
                let marking = net.unpack(groups);
                (0..net.events.len())
                    .filter(|&t| net.events[t] == e)
                    .all(|t| net.net.is_enabled(&marking, t))
            })
    }

    /// The executor supervisor of group `g` of net `n`.
    pub fn group_supervisor(&self, n: usize, g: usize) -> usize {
        self.supervisors.len() + self.nets[..n].iter().map(Net::groups).sum::<usize>() + g
    }

    /// The name of executor supervisor `j` (a net group's:
    /// [`Net::group_name`]).
    pub fn supervisor_name(&self, j: usize) -> String {
        match self.net_group(j) {
            Some((n, g)) => self.nets[n].group_name(g),
            None => self.supervisors[j].name.clone(),
        }
    }

    /// The name of state `state` of executor supervisor `j`: an
    /// automaton's state name (`#state` past its states), a net group's
    /// marking.
    pub fn state_name(&self, j: usize, state: u32) -> String {
        match self.net_group(j) {
            Some((n, g)) => self.nets[n].state_name(g, state),
            None => {
                let a = &self.supervisors[j].automaton;
                if (state as usize) < a.num_states() {
                    a.state_name(StateId(state)).into_owned()
                } else {
                    format!("#{state}")
                }
            }
        }
    }
}
