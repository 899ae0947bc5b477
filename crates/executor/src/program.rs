//! What a controller runs: the project's signals, events and supervisors.
//!
//! A [`Config`] is plain data (slices and small integers), so the code
//! generator can emit it as a `static` in flash and a host can build it at
//! run time from vectors. Lists that vary in length (an event's actions,
//! the events an input's edges can raise, …) live in shared pools and are
//! referred to by [`Span`]s. Sets of inputs (the OR of an edge binding,
//! `when` and `unless` conditions) are *masks*: one `u32` per input word,
//! bit `i % 32` of word `i / 32` standing for input `i`, so the scan tests
//! a whole set with one AND per word. Supervisor dynamics come through the
//! [`Program`] trait, implemented by bit-packed tables ([`crate::table`])
//! and by generated CMSSM logic functions alike.

/// Index of an input, output, timer, event or supervisor.
pub type Index = u16;

/// Words of a bit set of `n` members (32 per `u32`): the length of an
/// input mask for `n` inputs, of an event set for `n` events.
pub const fn words(n: usize) -> usize {
    n.div_ceil(32)
}

/// Word `word` of the bit set of `members`: bit `i % 32` set for every
/// member `i` with `i / 32 == word`. `const`, so generated code writes
/// masks by name (`mask_word(0, &[input::A, input::B])`) and the compiler
/// folds them into constants.
pub const fn mask_word(word: u16, members: &[Index]) -> u32 {
    let mut bits = 0u32;
    let mut k = 0;
    while k < members.len() {
        if members[k] / 32 == word {
            bits |= 1 << (members[k] % 32);
        }
        k += 1;
    }
    bits
}

/// Word `word` of the set of every one of the first `count` members but
/// `members`: [`mask_word`]'s complement among `count` members, which
/// names a set that holds most of them by what it leaves out
/// (`mask_word_except(0, event::COUNT, &[event::STOP])`).
pub const fn mask_word_except(word: u16, count: usize, members: &[Index]) -> u32 {
    let first = word as usize * 32;
    let all = if count <= first {
        0
    } else if count - first >= 32 {
        u32::MAX
    } else {
        (1 << (count - first)) - 1
    };
    all & !mask_word(word, members)
}

/// A range `start..start + len` of one of the [`Config`] pools.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Span {
    /// First element.
    pub start: u16,
    /// Number of elements.
    pub len: u16,
}

impl Span {
    /// The empty span.
    pub const EMPTY: Span = Span { start: 0, len: 0 };

    /// A span of `len` elements from `start`.
    pub const fn new(start: u16, len: u16) -> Span {
        Span { start, len }
    }

    /// The elements of `pool` this span covers (empty if out of range,
    /// which validation of the program rules out).
    #[inline]
    pub fn of<T>(self, pool: &[T]) -> &[T] {
        let start = self.start as usize;
        pool.get(start..start + self.len as usize).unwrap_or(&[])
    }

    /// `true` when the span has no elements.
    pub const fn is_empty(self) -> bool {
        self.len == 0
    }

    /// Its word in the image: `start | len << 16`.
    pub const fn to_word(self) -> u32 {
        self.start as u32 | (self.len as u32) << 16
    }

    /// The span of a word written by [`Span::to_word`].
    #[inline]
    pub const fn from_word(word: u32) -> Span {
        Span {
            start: word as u16,
            len: (word >> 16) as u16,
        }
    }
}

/// A value stored in the image as a record of `N` words (the encoding of
/// each kind: [`crate::image`]). [`Record::from_words`] reads any words
/// without panicking, and ignores bits no field uses; the values it reads
/// are what the structure check ([`crate::validate::validate`]) checks.
pub trait Record<const N: usize>: Sized {
    /// The record's words.
    fn to_words(&self) -> [u32; N];
    /// The value of a record's words.
    fn from_words(words: &[u32; N]) -> Self;
}

/// Implements [`Record`] by the type's own `const fn`s, which generated
/// code calls in constants.
macro_rules! record {
    ($ty:ty, $n:literal) => {
        impl $ty {
            /// The records of `items`, in order: how generated code
            /// writes a pool of them (`const` items, so the typed values
            /// are not in the image, only their words).
            pub const fn records<const K: usize>(items: &[$ty; K]) -> [[u32; $n]; K] {
                let mut out = [[0; $n]; K];
                let mut k = 0;
                while k < K {
                    out[k] = items[k].to_words();
                    k += 1;
                }
                out
            }
        }

        impl Record<$n> for $ty {
            #[inline]
            fn to_words(&self) -> [u32; $n] {
                <$ty>::to_words(self)
            }
            #[inline]
            fn from_words(words: &[u32; $n]) -> Self {
                <$ty>::from_words(words)
            }
        }
    };
}

/// Indices as words, in order: how generated code writes the event
/// lists and the debounced inputs.
pub const fn indices<const K: usize>(items: &[Index; K]) -> [u32; K] {
    let mut out = [0; K];
    let mut k = 0;
    while k < K {
        out[k] = items[k] as u32;
        k += 1;
    }
    out
}

/// Implements `words` for a kind whose record is one word, the pool
/// holding plain words.
macro_rules! one_word {
    ($ty:ty) => {
        impl $ty {
            /// The words of `items`, in order: how generated code writes
            /// a pool of them.
            pub const fn words<const K: usize>(items: &[$ty; K]) -> [u32; K] {
                let mut out = [0; K];
                let mut k = 0;
                while k < K {
                    out[k] = items[k].to_word();
                    k += 1;
                }
                out
            }
        }
    };
}
one_word!(Action);
one_word!(Membership);

/// The records of `items`, in a vector (hosts building images).
#[cfg(feature = "alloc")]
pub fn encode<T: Record<N>, const N: usize>(items: &[T]) -> alloc::vec::Vec<[u32; N]> {
    items.iter().map(Record::to_words).collect()
}

/// An input signal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InputSpec {
    /// Scans a new raw value must persist before the filtered value
    /// follows it; 0 and 1 mean no filtering. A debounced input
    /// (`debounce_scans ≥ 2`) is also listed in [`Config::debounced`] and
    /// [`Config::debounce_mask`].
    pub debounce_scans: u8,
    /// The events bound to an edge of this input, alone or in an OR (span
    /// of [`Config::event_lists`]): the only events a change of this input can
    /// raise.
    pub raises: Span,
}

impl InputSpec {
    /// Its record: `debounce_scans`; `raises`.
    pub const fn to_words(&self) -> [u32; 2] {
        [self.debounce_scans as u32, self.raises.to_word()]
    }

    /// The input of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 2]) -> InputSpec {
        InputSpec {
            debounce_scans: w[0] as u8,
            raises: Span::from_word(w[1]),
        }
    }
}
record!(InputSpec, 2);

/// An output signal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutputSpec {
    /// Level in fault mode.
    pub safe: bool,
    /// Level at start and after reset (action-driven outputs).
    pub initial: bool,
    /// Moore output: entries of [`Config::state_map`]; empty for an
    /// action-driven output.
    pub state_map: Span,
}

impl OutputSpec {
    /// Its record: `safe | initial << 1`; `state_map`.
    pub const fn to_words(&self) -> [u32; 2] {
        [
            self.safe as u32 | (self.initial as u32) << 1,
            self.state_map.to_word(),
        ]
    }

    /// The output of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 2]) -> OutputSpec {
        OutputSpec {
            safe: w[0] & 1 != 0,
            initial: w[0] & 2 != 0,
            state_map: Span::from_word(w[1]),
        }
    }
}
record!(OutputSpec, 2);

/// A timer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TimerSpec {
    /// Preset in milliseconds, `0 < preset < 2^31`.
    pub preset_ms: u32,
    /// The events bound to this timer's expiry (span of
    /// [`Config::event_lists`]).
    pub raises: Span,
}

impl TimerSpec {
    /// Its record: `preset_ms`; `raises`.
    pub const fn to_words(&self) -> [u32; 2] {
        [self.preset_ms, self.raises.to_word()]
    }

    /// The timer of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 2]) -> TimerSpec {
        TimerSpec {
            preset_ms: w[0],
            raises: Span::from_word(w[1]),
        }
    }
}
record!(TimerSpec, 2);

/// What makes an uncontrollable event occur.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trigger {
    /// A controllable event: the controller chooses it.
    Command,
    /// Rising edge of the OR of the inputs of a mask (span of
    /// [`Config::input_masks`]): the OR was 0 in F\[k-1\] and is 1 in
    /// F\[k\].
    Rising(Span),
    /// Falling edge of the OR of the inputs of a mask.
    Falling(Span),
    /// Expiry of the timer.
    Expired(Index),
}

/// One change an executed event makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Raise an action-driven output.
    Set(Index),
    /// Lower an action-driven output.
    Clear(Index),
    /// Start (or restart) a timer: deadline = this scan's time + preset.
    Start(Index),
    /// Stop a timer without expiry.
    Reset(Index),
}

impl Action {
    /// Its word: kind (0 set, 1 clear, 2 start, 3 reset) `<< 16 |` its
    /// output or timer.
    pub const fn to_word(&self) -> u32 {
        let (kind, index) = match *self {
            Action::Set(o) => (0, o),
            Action::Clear(o) => (1, o),
            Action::Start(t) => (2, t),
            Action::Reset(t) => (3, t),
        };
        kind << 16 | index as u32
    }

    /// The action of a word (kinds above 3 read as 3).
    #[inline]
    pub const fn from_word(word: u32) -> Action {
        let index = word as u16;
        match word >> 16 {
            0 => Action::Set(index),
            1 => Action::Clear(index),
            2 => Action::Start(index),
            _ => Action::Reset(index),
        }
    }

    /// [`Action::to_word`] as a record.
    pub const fn to_words(&self) -> [u32; 1] {
        [self.to_word()]
    }

    /// [`Action::from_word`] of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 1]) -> Action {
        Action::from_word(w[0])
    }
}
record!(Action, 1);

/// A supervisor that has an event in its alphabet, with the event's local
/// index there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Membership {
    /// The supervisor.
    pub supervisor: Index,
    /// The event's index in that supervisor's local alphabet.
    pub local: Index,
}

impl Membership {
    /// Its word: `supervisor | local << 16`.
    pub const fn to_word(&self) -> u32 {
        self.supervisor as u32 | (self.local as u32) << 16
    }

    /// The membership of a word.
    #[inline]
    pub const fn from_word(word: u32) -> Membership {
        Membership {
            supervisor: word as u16,
            local: (word >> 16) as u16,
        }
    }

    /// [`Membership::to_word`] as a record.
    pub const fn to_words(&self) -> [u32; 1] {
        [self.to_word()]
    }

    /// [`Membership::from_word`] of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 1]) -> Membership {
        Membership::from_word(w[0])
    }
}
record!(Membership, 1);

/// An event of the global alphabet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EventSpec {
    /// What makes it occur ([`Trigger::Command`] for controllable events).
    pub trigger: Trigger,
    /// Mask of inputs (span of [`Config::input_masks`]) that must all be
    /// 1; empty for none.
    pub when: Span,
    /// Mask of inputs that must all be 0; empty for none.
    pub unless: Span,
    /// Controllable events: an input that must be 1 for the event to be
    /// chosen (manual mode).
    pub request: Option<Index>,
    /// Its actions (span of [`Config::actions`]).
    pub actions: Span,
    /// The supervisors that have it (span of [`Config::memberships`]).
    pub members: Span,
}

impl EventSpec {
    /// `true` for controllable events.
    #[inline]
    pub fn is_controllable(&self) -> bool {
        matches!(self.trigger, Trigger::Command)
    }

    /// Its record: trigger (0 command, 1 rising, 2 falling, 3 expired);
    /// its mask span or timer (0 for a command); `when`; `unless`;
    /// `request` (`0xFFFF_FFFF` for none); `actions`; `members`.
    pub const fn to_words(&self) -> [u32; 7] {
        let (kind, binding) = match self.trigger {
            Trigger::Command => (0, 0),
            Trigger::Rising(mask) => (1, mask.to_word()),
            Trigger::Falling(mask) => (2, mask.to_word()),
            Trigger::Expired(timer) => (3, timer as u32),
        };
        [
            kind,
            binding,
            self.when.to_word(),
            self.unless.to_word(),
            match self.request {
                Some(i) => i as u32,
                None => u32::MAX,
            },
            self.actions.to_word(),
            self.members.to_word(),
        ]
    }

    /// The event of a record (a trigger kind above 3 reads as 3, a
    /// request that is no [`Index`] as none). Always inline: the scan
    /// reads one or two fields of it, a load and a shift each.
    #[inline(always)]
    pub const fn from_words(w: &[u32; 7]) -> EventSpec {
        EventSpec {
            trigger: Trigger::from_words(w[0], w[1]),
            when: Span::from_word(w[2]),
            unless: Span::from_word(w[3]),
            request: if w[4] <= Index::MAX as u32 {
                Some(w[4] as Index)
            } else {
                None
            },
            actions: Span::from_word(w[5]),
            members: Span::from_word(w[6]),
        }
    }
}
record!(EventSpec, 7);

impl Trigger {
    /// The trigger of an event record's first two words.
    #[inline(always)]
    pub const fn from_words(kind: u32, binding: u32) -> Trigger {
        match kind {
            0 => Trigger::Command,
            1 => Trigger::Rising(Span::from_word(binding)),
            2 => Trigger::Falling(Span::from_word(binding)),
            _ => Trigger::Expired(binding as Index),
        }
    }
}

/// One entry of a Moore output's state map: the output is 1 while the
/// supervisor's state `x` has `x & mask == state`. An automaton's entry
/// names a whole state (`mask` all ones, [`StateMapEntry::in_state`]); a
/// Petri net's names a count of tokens in one place, the bits of its
/// counter in the packed marking ([`StateMapEntry::marked`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateMapEntry {
    /// The supervisor.
    pub supervisor: Index,
    /// The state, or the masked bits of the state.
    pub state: u32,
    /// The bits of the state compared.
    pub mask: u32,
}

impl StateMapEntry {
    /// While `supervisor` is in `state`.
    pub const fn in_state(supervisor: Index, state: u32) -> StateMapEntry {
        StateMapEntry {
            supervisor,
            state,
            mask: u32::MAX,
        }
    }

    /// While the counter in bits `mask` of net group `supervisor` holds
    /// `count` (the counter's lowest bit is `mask`'s lowest set bit).
    pub const fn marked(supervisor: Index, mask: u32, count: u32) -> StateMapEntry {
        StateMapEntry {
            supervisor,
            state: match count.checked_shl(mask.trailing_zeros()) {
                Some(bits) => bits & mask,
                None => 0,
            },
            mask,
        }
    }

    /// `true` when a supervisor in `state` drives the output through this
    /// entry.
    #[inline]
    pub fn holds(&self, state: u32) -> bool {
        state & self.mask == self.state
    }

    /// Its record: `supervisor`; `state`; `mask`.
    pub const fn to_words(&self) -> [u32; 3] {
        [self.supervisor as u32, self.state, self.mask]
    }

    /// The entry of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 3]) -> StateMapEntry {
        StateMapEntry {
            supervisor: w[0] as Index,
            state: w[1],
            mask: w[2],
        }
    }
}
record!(StateMapEntry, 3);

/// A supervisor's size, initial state and alphabet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SupervisorSpec {
    /// Number of states; a state index at or above it is corrupt.
    pub states: u32,
    /// The initial state.
    pub initial: u32,
    /// Its events in local order (span of [`Config::event_lists`]): local
    /// event `k` is event `event_lists[alphabet.start + k]`.
    pub alphabet: Span,
    /// The events outside its alphabet, which it never blocks (span of
    /// [`Config::event_masks`]).
    pub outside: Span,
    /// Its allowed set in each state, stored ([`AllowedSets`]), or
    /// [`AllowedSets::COMPUTED`] from its program when it moves.
    pub allowed: AllowedSets,
    /// Its alphabet is consecutive event numbers in increasing order
    /// (local event `k` is event `event_lists[alphabet.start] + k`): an
    /// enabled row then maps to its events by one shift (and an OR per
    /// word) instead of a loop over its bits. Computed at generation
    /// (`false` is always correct) and proved by
    /// [`crate::validate::validate_generated`].
    pub contiguous: bool,
}

impl SupervisorSpec {
    /// Its record: `states`; `initial`; `alphabet`; `outside`;
    /// `allowed.index`; `allowed.bits | contiguous << 8`.
    pub const fn to_words(&self) -> [u32; 6] {
        [
            self.states,
            self.initial,
            self.alphabet.to_word(),
            self.outside.to_word(),
            self.allowed.index.to_word(),
            self.allowed.bits as u32 | (self.contiguous as u32) << 8,
        ]
    }

    /// The supervisor of a record (always inline, as an event's).
    #[inline(always)]
    pub const fn from_words(w: &[u32; 6]) -> SupervisorSpec {
        SupervisorSpec {
            states: w[0],
            initial: w[1],
            alphabet: Span::from_word(w[2]),
            outside: Span::from_word(w[3]),
            allowed: AllowedSets {
                index: Span::from_word(w[4]),
                bits: w[5] as u8,
            },
            contiguous: w[5] >> 8 & 1 != 0,
        }
    }
}
record!(SupervisorSpec, 6);

/// A supervisor's *allowed set* in each of its states, stored in the form
/// the scan reads: the events outside its alphabet and the local events it
/// enables there, in event numbering. Entry `x` of the packed array
/// [`AllowedSets::index`] (`bits` bits an entry, [`crate::table::read_bits`])
/// is the number `k` of state `x`'s set in [`Config::event_masks`], which
/// holds it in words `k·w .. (k + 1)·w` (`w` = [`words`]`(events)`). A
/// supervisor's states share few distinct sets, each stored once.
///
/// A move then copies `w` words instead of scattering its enabled row
/// over the event numbers, and changes none when the new state's set
/// holds the events already in RAM (docs/semantics.md, "Feasible").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AllowedSets {
    /// Packed set numbers, one per state (span of [`Config::allowed_index`]).
    pub index: Span,
    /// Bits per entry, `1..=16` when stored.
    pub bits: u8,
}

impl AllowedSets {
    /// Not stored: computed from [`Program::enabled`] when the supervisor
    /// moves.
    pub const COMPUTED: AllowedSets = AllowedSets {
        index: Span::EMPTY,
        bits: 0,
    };

    /// Whether the sets are stored.
    #[inline]
    pub const fn is_stored(&self) -> bool {
        !self.index.is_empty()
    }
}

/// What to do with an uncontrollable event no supervisor can explain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnexpectedPolicy {
    /// Enter fault mode (the default).
    Fault,
    /// Drop the event, count it and record it.
    Ignore,
}

/// The static description of a controller.
#[derive(Debug, Clone, Copy)]
pub struct Config<'a> {
    /// Project name.
    pub name: &'a str,
    /// Nominal scan period.
    pub scan_period_ms: u32,
    /// Controllable events per scan; 0 = no limit.
    pub max_commands_per_scan: u16,
    /// Unexpected uncontrollable events.
    pub unexpected: UnexpectedPolicy,
    /// Input whose rising edge leaves fault mode.
    pub reset: Option<Index>,
    /// Scans late beyond which a scan counts as overrun (board only).
    pub overrun_limit: u16,
    /// Overruns are faults rather than just counted.
    pub overrun_fault: bool,
    /// Lost edges are faults rather than just counted.
    pub lost_edge_fault: bool,
    /// Bytes of the program image the background test checks per scan
    /// (whole 32-bit words: a multiple of 4, at least 4; smaller values
    /// count as 4). See [`crate::image`].
    pub rom_test_bytes_per_scan: u16,
    /// Inputs in declaration order ([`InputSpec`] records; read them with
    /// [`Config::input`]).
    pub inputs: &'a [[u32; 2]],
    /// The debounced inputs (`debounce_scans ≥ 2`) in declaration order,
    /// one word each: filter counter `k` belongs to input `debounced[k]`.
    pub debounced: &'a [u32],
    /// Mask (span of [`Config::input_masks`]) of the debounced inputs.
    pub debounce_mask: Span,
    /// Outputs in declaration order ([`OutputSpec`] records,
    /// [`Config::output`]).
    pub outputs: &'a [[u32; 2]],
    /// Timers in declaration order ([`TimerSpec`] records,
    /// [`Config::timer`]).
    pub timers: &'a [[u32; 2]],
    /// Events in declaration (priority) order ([`EventSpec`] records,
    /// [`Config::event`]).
    pub events: &'a [[u32; 7]],
    /// Supervisors in declaration order ([`SupervisorSpec`] records,
    /// [`Config::supervisor`]).
    pub supervisors: &'a [[u32; 6]],
    /// Pool of input masks (edge bindings, `when`, `unless`, the debounced
    /// inputs), each [`words`]`(inputs.len())` long.
    pub input_masks: &'a [u32],
    /// Pool of event lists: the events each input's edges and each timer's
    /// expiry can raise (each in declaration order), and each
    /// supervisor's alphabet (in its local order); one word an event.
    pub event_lists: &'a [u32],
    /// Pool of event sets, each [`words`]`(events.len())` long: what each
    /// supervisor never blocks, [`Config::commands`], and the stored
    /// allowed sets ([`AllowedSets`]).
    pub event_masks: &'a [u32],
    /// The controllable events without a request input (span of
    /// [`Config::event_masks`]): the controller may choose them whenever
    /// every supervisor enables them.
    pub commands: Span,
    /// The controllable events with a request input, in declaration order
    /// (span of [`Config::event_lists`]).
    pub requested: Span,
    /// Pool of actions, one word each ([`Action::to_word`]).
    pub actions: &'a [u32],
    /// Pool of event memberships, one word each
    /// ([`Membership::to_word`]).
    pub memberships: &'a [u32],
    /// Pool of state-map entries ([`StateMapEntry`] records).
    pub state_map: &'a [[u32; 3]],
    /// Guards of controllable events (symbolic supervisors:
    /// [`crate::guards`]); [`Guards::NONE`] without.
    pub guards: Guards<'a>,
    /// Pool of the packed set numbers of stored allowed sets
    /// ([`AllowedSets::index`]).
    pub allowed_index: &'a [u32],
}

/// Past the end of its pool, a record accessor reads a record of zeros
/// (the structure check rules such indices out): no panic path, whose
/// message formatting would cost the target's flash.
impl<'a> Config<'a> {
    /// Input `i`.
    #[inline]
    pub fn input(&self, i: usize) -> InputSpec {
        InputSpec::from_words(self.inputs.get(i).unwrap_or(&[0; 2]))
    }

    /// Output `o`.
    #[inline]
    pub fn output(&self, o: usize) -> OutputSpec {
        OutputSpec::from_words(self.outputs.get(o).unwrap_or(&[0; 2]))
    }

    /// Timer `t`.
    #[inline]
    pub fn timer(&self, t: usize) -> TimerSpec {
        TimerSpec::from_words(self.timers.get(t).unwrap_or(&[0; 2]))
    }

    /// Event `e`.
    #[inline]
    pub fn event(&self, e: usize) -> EventSpec {
        EventSpec::from_words(self.events.get(e).unwrap_or(&[0; 7]))
    }

    /// Supervisor `j`.
    #[inline]
    pub fn supervisor(&self, j: usize) -> SupervisorSpec {
        SupervisorSpec::from_words(self.supervisors.get(j).unwrap_or(&[0; 6]))
    }

    /// Every input, in order.
    pub fn input_specs(&self) -> impl ExactSizeIterator<Item = InputSpec> + 'a {
        self.inputs.iter().map(InputSpec::from_words)
    }

    /// Every output, in order.
    pub fn output_specs(&self) -> impl ExactSizeIterator<Item = OutputSpec> + 'a {
        self.outputs.iter().map(OutputSpec::from_words)
    }

    /// Every timer, in order.
    pub fn timer_specs(&self) -> impl ExactSizeIterator<Item = TimerSpec> + 'a {
        self.timers.iter().map(TimerSpec::from_words)
    }

    /// Every event, in order.
    pub fn event_specs(&self) -> impl ExactSizeIterator<Item = EventSpec> + 'a {
        self.events.iter().map(EventSpec::from_words)
    }

    /// Every supervisor, in order.
    pub fn supervisor_specs(&self) -> impl ExactSizeIterator<Item = SupervisorSpec> + 'a {
        self.supervisors.iter().map(SupervisorSpec::from_words)
    }

    /// The debounced inputs, in order.
    pub fn debounced_inputs(&self) -> impl ExactSizeIterator<Item = Index> + 'a {
        self.debounced.iter().map(|&i| i as Index)
    }

    /// The events of a span of [`Config::event_lists`].
    pub fn event_list(&self, span: Span) -> impl ExactSizeIterator<Item = Index> + 'a {
        span.of(self.event_lists).iter().map(|&e| e as Index)
    }

    /// The actions of a span of [`Config::actions`].
    pub fn actions_of(&self, span: Span) -> impl ExactSizeIterator<Item = Action> + 'a {
        span.of(self.actions).iter().map(|&a| Action::from_word(a))
    }

    /// The memberships of a span of [`Config::memberships`].
    pub fn members_of(&self, span: Span) -> impl ExactSizeIterator<Item = Membership> + 'a {
        span.of(self.memberships)
            .iter()
            .map(|&m| Membership::from_word(m))
    }

    /// The state-map entries of a span of [`Config::state_map`].
    pub fn state_map_of(&self, span: Span) -> impl ExactSizeIterator<Item = StateMapEntry> + 'a {
        span.of(self.state_map)
            .iter()
            .map(StateMapEntry::from_words)
    }
}

/// Where one state bit comes from: a supervisor (a component of a
/// symbolic supervisor) and the bit's place in its state number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateBit {
    /// The supervisor (its index in the state vector).
    pub component: Index,
    /// The bit's shift in the supervisor's state.
    pub shift: u8,
}

impl StateBit {
    /// Its record: `component | shift << 16`.
    pub const fn to_words(&self) -> [u32; 1] {
        [self.component as u32 | (self.shift as u32) << 16]
    }

    /// The state bit of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 1]) -> StateBit {
        StateBit {
            component: w[0] as Index,
            shift: (w[0] >> 16) as u8,
        }
    }
}
record!(StateBit, 1);

/// One decision node of a guard: read state bit `bit`, continue at `high`
/// if it is 1, at `low` if 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GuardNode {
    /// The state bit read (an index into [`Guards::bits`]).
    pub bit: u16,
    /// Where to go when the bit is 0.
    pub low: u16,
    /// Where to go when the bit is 1.
    pub high: u16,
}

impl GuardNode {
    /// Its record: `bit | low << 16`; `high`.
    pub const fn to_words(&self) -> [u32; 2] {
        [self.bit as u32 | (self.low as u32) << 16, self.high as u32]
    }

    /// The node of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 2]) -> GuardNode {
        GuardNode {
            bit: w[0] as u16,
            low: (w[0] >> 16) as u16,
            high: w[1] as u16,
        }
    }
}
record!(GuardNode, 2);

/// The guard of one controllable event: a decision diagram over state
/// bits, which must hold for the event to be feasible.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GuardSpec {
    /// The event guarded (controllable).
    pub event: Index,
    /// The root: 0 false, 1 true, `k ≥ 2` the node `nodes[k − 2]`.
    pub root: u16,
    /// Its nodes, children first (span of [`Guards::nodes`]); node
    /// indices are relative to the span.
    pub nodes: Span,
}

impl GuardSpec {
    /// Its record: `event`; `root`; `nodes`.
    pub const fn to_words(&self) -> [u32; 3] {
        [self.event as u32, self.root as u32, self.nodes.to_word()]
    }

    /// The guard of a record.
    #[inline]
    pub const fn from_words(w: &[u32; 3]) -> GuardSpec {
        GuardSpec {
            event: w[0] as Index,
            root: w[1] as u16,
            nodes: Span::from_word(w[2]),
        }
    }
}
record!(GuardSpec, 3);

/// The guards of a program's symbolic supervisors ([`crate::guards`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Guards<'a> {
    /// One per guarded event, in increasing event order ([`GuardSpec`]
    /// records).
    pub events: &'a [[u32; 3]],
    /// Pool of the state bits the nodes read ([`StateBit`] records).
    pub bits: &'a [[u32; 1]],
    /// Pool of decision nodes ([`GuardNode`] records).
    pub nodes: &'a [[u32; 2]],
}

impl<'a> Guards<'a> {
    /// Guard `k`.
    #[inline]
    pub fn guard(&self, k: usize) -> GuardSpec {
        GuardSpec::from_words(&self.events[k])
    }

    /// Every guard, in order.
    pub fn guards(&self) -> impl ExactSizeIterator<Item = GuardSpec> + 'a {
        self.events.iter().map(GuardSpec::from_words)
    }

    /// State bit `k`, `None` past the pool.
    #[inline]
    pub fn bit(&self, k: usize) -> Option<StateBit> {
        self.bits.get(k).map(StateBit::from_words)
    }

    /// Node `k`, `None` past the pool.
    #[inline]
    pub fn node(&self, k: usize) -> Option<GuardNode> {
        self.nodes.get(k).map(GuardNode::from_words)
    }
}

impl Guards<'static> {
    /// No guards: a program without symbolic supervisors.
    pub const NONE: Guards<'static> = Guards {
        events: &[],
        bits: &[],
        nodes: &[],
    };
}

/// How the targets of a [`SupervisorTable`] are laid out (the encoding:
/// [`crate::table`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rows<'a> {
    /// Entry `s·m + e` for every pair.
    Dense,
    /// Only defined pairs, with a packed row start per state.
    Sparse {
        /// `n` packed entries of `start_bits` bits.
        row_starts: &'a [u32],
        /// Width of a row start.
        start_bits: u8,
    },
    /// A group of places of a Petri net: `defined` holds `PRE[t]` and
    /// `targets` `POST[t]`, one word per local transition ([`crate::table`],
    /// "Petri nets").
    Net {
        /// The mask of each place's counter, in place order.
        fields: &'a [u32],
    },
    /// A dictionary of rows ([`crate::table`], "Keyed rows"): `defined`
    /// holds the distinct rows of defined-bits, `m` bits each, row `r` at
    /// bits `r·m .. r·m + m`; `targets` holds only defined pairs, as in
    /// [`Rows::Sparse`].
    Keyed {
        /// `n` packed records of `key_bits + start_bits` bits (at most
        /// 32), one per state: the low `key_bits` its row in `defined`,
        /// the high `start_bits` its row start in `targets`.
        states: &'a [u32],
        /// Width of a row key (1 to 31).
        key_bits: u8,
        /// Width of a row start (1 to 31).
        start_bits: u8,
    },
}

/// The layouts a program's tables use, as a set: what a program compiled
/// into the firmware knows at build time ([`Layouts::of`] its tables), so
/// that the decoder of a layout it does not use is left out of its code
/// (a keyed or net arm inlined into every lookup costs flash and, through
/// register pressure, instructions). A loaded image may use any:
/// [`Layouts::ALL`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layouts(pub(crate) u8);

impl Layouts {
    /// No table (supervisors that are code).
    pub const NONE: Layouts = Layouts(0);
    /// [`Rows::Dense`].
    pub const DENSE: Layouts = Layouts(1);
    /// [`Rows::Sparse`].
    pub const SPARSE: Layouts = Layouts(2);
    /// [`Rows::Net`].
    pub const NET: Layouts = Layouts(4);
    /// [`Rows::Keyed`].
    pub const KEYED: Layouts = Layouts(8);
    /// Every layout.
    pub const ALL: Layouts = Layouts(15);

    /// The layouts of `tables`.
    pub const fn of(tables: &[SupervisorTable<'_>]) -> Layouts {
        let mut bits = 0;
        let mut i = 0;
        while i < tables.len() {
            bits |= Layouts::of_rows(&tables[i].rows).0;
            i += 1;
        }
        Layouts(bits)
    }

    /// The layout of one table's rows.
    pub const fn of_rows(rows: &Rows<'_>) -> Layouts {
        match rows {
            Rows::Dense => Layouts::DENSE,
            Rows::Sparse { .. } => Layouts::SPARSE,
            Rows::Net { .. } => Layouts::NET,
            Rows::Keyed { .. } => Layouts::KEYED,
        }
    }

    /// Every layout of `other` is in the set.
    #[inline(always)]
    pub const fn has(self, other: Layouts) -> bool {
        self.0 & other.0 == other.0
    }
}

/// One supervisor's transition function, bit-packed (the encoding and
/// the decoder: [`crate::table`]). Plain data, like [`Config`]: the
/// generator emits it as constants, and [`Program::table`] hands it out
/// for the image CRC and validation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SupervisorTable<'a> {
    /// Number of local events `m`.
    pub events: Index,
    /// Bits per state `b`.
    pub state_bits: u8,
    /// `n·m` defined-bits (the distinct rows of them when keyed).
    pub defined: &'a [u32],
    /// Packed `b`-bit targets.
    pub targets: &'a [u32],
    /// Layout of `targets`.
    pub rows: Rows<'a>,
}

/// The row of defined-bits of `len` (at most 32) local events, event `k`
/// asked of `defined(k)`: what [`Program::enabled`] is for supervisors
/// that are code.
#[inline]
pub(crate) fn enabled_by_steps(len: u8, defined: impl Fn(Index) -> bool) -> u32 {
    (0..u16::from(len.min(32))).fold(0, |row, k| row | u32::from(defined(k)) << k)
}

/// Supervisor dynamics plus the static description: what a
/// [`crate::Controller`] runs.
pub trait Program {
    /// The static description (a handful of slices, cheap to copy).
    fn config(&self) -> Config<'_>;

    /// δ of supervisor `supervisor` in `state` on its local event `local`,
    /// `None` when undefined. Called only with `state` in range.
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32>;

    /// Which of the local events `from..from + len` (`len ≤ 32`) of
    /// supervisor `supervisor` are defined in `state`: bit `k` for local
    /// event `from + k` (the φ functions of the CMSSM, one row). Called
    /// only with `state` in range, when the state changes. The default asks
    /// [`Program::next_state`] for each event; tables read their row of
    /// defined-bits.
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        enabled_by_steps(len, |k| {
            self.next_state(supervisor, state, from.wrapping_add(k))
                .is_some()
        })
    }

    /// The transition table of supervisor `supervisor`, part of the
    /// program image ([`crate::image`]); `None` past the last table, and
    /// for every supervisor of a program whose supervisors are code.
    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>>;

    /// The layouts its tables may use ([`Layouts`]): every
    /// one unless the program knows its tables at build time.
    #[inline]
    fn layouts(&self) -> Layouts {
        Layouts::ALL
    }

    /// The CRC of the program image ([`crate::image::crc`]) recorded at
    /// generation.
    fn recorded_crc(&self) -> u32;
}

impl<P: Program + ?Sized> Program for &P {
    fn config(&self) -> Config<'_> {
        (**self).config()
    }

    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        (**self).next_state(supervisor, state, local)
    }

    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        (**self).enabled(supervisor, state, from, len)
    }

    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>> {
        (**self).table(supervisor)
    }

    fn layouts(&self) -> Layouts {
        (**self).layouts()
    }

    fn recorded_crc(&self) -> u32 {
        (**self).recorded_crc()
    }
}

/// Records for tests, leaked to `'static` like a generated constant.
#[cfg(test)]
pub(crate) mod leak {
    extern crate std;
    use super::Record;
    use std::boxed::Box;
    use std::vec::Vec;

    /// The records of `items`.
    pub(crate) fn records<T: Record<N>, const N: usize>(items: &[T]) -> &'static [[u32; N]] {
        Box::leak(
            items
                .iter()
                .map(Record::to_words)
                .collect::<Vec<_>>()
                .into_boxed_slice(),
        )
    }

    /// The one-word records of `items`, as plain words.
    pub(crate) fn words<T: Record<1>>(items: &[T]) -> &'static [u32] {
        records(items).as_flattened()
    }
}
