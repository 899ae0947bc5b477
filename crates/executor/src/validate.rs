//! The structure check of a program image, done once when a
//! [`crate::Controller`] is built (docs/semantics.md, "Image check").
//!
//! The CRC proves that an image is the one the generator wrote; it says
//! nothing about an image written wrong, by a faulty generator or by hand
//! with a CRC computed to match. [`validate`] proves what the scan relies
//! on to index without a check: every index is in range, every span lies
//! inside its pool and has the length its kind needs, sets have no bits
//! past their last member, every table has the sizes of its supervisor.
//! A controller whose image fails it starts in fault mode (`Corrupt`) and
//! no reset can leave it; it is what an image loaded as words
//! ([`crate::parse`]) needs, and it is kept small for the target.
//!
//! What a generator proves of its own output is [`validate_generated`],
//! run at generation and by host tools, not by the controller: that the
//! memberships and the alphabets agree, that each `outside` set and the
//! command sets are the ones the events give, that an alphabet marked
//! `contiguous` is consecutive event numbers in increasing order, that
//! every defined table entry is a state of its supervisor (the scan
//! checks each state it moves to as well, so a flipped table word is a `Corrupt` fault, never
//! a state out of range) and that stored allowed sets are their
//! supervisors' ([`validate_allowed_sets`]). Host tools call both to print
//! where an image is wrong.

use core::fmt;

use crate::bits;
use crate::pacing::SCAN_PERIOD_MS;
use crate::program::{
    words, Action, Config, EventSpec, GuardNode, Index, Membership, Program, Span, StateBit,
    StateMapEntry, SupervisorSpec, Trigger,
};
use crate::table::{
    bit, keyed_record, keyed_stride, ones_between, read_bits, Rows, SupervisorTable,
};

/// Where in the image a flaw lies: a field, or an item of a list or pool
/// by its index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Part {
    /// The number of inputs, outputs, timers, events or supervisors.
    Counts,
    /// `Config::scan_period_ms`.
    ScanPeriod,
    /// `Config::reset`.
    Reset,
    /// `Config::debounced[k]`.
    Debounced(usize),
    /// `Config::debounce_mask`.
    DebounceMask,
    /// `Config::inputs[i]`.
    Input(usize),
    /// `Config::outputs[o]`.
    Output(usize),
    /// `Config::timers[t]`.
    Timer(usize),
    /// `Config::events[e]`.
    Event(usize),
    /// `Config::supervisors[j]`.
    Supervisor(usize),
    /// `Config::commands`.
    Commands,
    /// `Config::requested`.
    Requested,
    /// `Config::actions[k]`.
    Action(usize),
    /// `Config::memberships[k]`.
    Membership(usize),
    /// `Config::state_map[k]`.
    StateMap(usize),
    /// `Config::guards.events[k]`.
    Guard(usize),
    /// `Config::guards.bits[k]`.
    StateBit(usize),
    /// The tables as a whole.
    Tables,
    /// The table of supervisor `j`.
    Table(usize),
}

/// What is wrong there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Flaw {
    /// More items than an [`Index`] can number.
    TooMany,
    /// A span reaches past the end of its pool.
    SpanPastPool,
    /// A mask or event set whose span is neither empty nor one word per
    /// 32 members.
    SetLength,
    /// A mask or event set with a bit past its last member.
    StrayBits,
    /// An index (of an input, output, timer, event, supervisor, local
    /// event or state) at or above the number of them.
    OutOfRange {
        /// The index.
        index: u32,
        /// The number of items it indexes.
        count: u32,
    },
    /// A timer preset of 0 or of 2^31 ms or more.
    Preset,
    /// A scan period of 0 or of 2^31 ms or more (outside
    /// [`SCAN_PERIOD_MS`]).
    Period,
    /// An event's memberships and the alphabets disagree: a membership
    /// names a local event that is another event, or an alphabet lists an
    /// event without exactly one membership for it.
    Membership,
    /// A supervisor's `outside` set is not the events outside its alphabet.
    Outside,
    /// A supervisor marked `contiguous` whose alphabet is not consecutive
    /// event numbers in increasing order.
    Contiguous,
    /// `commands` or `requested` holds an event that does not belong there
    /// or leaves out one that does.
    Commands,
    /// Tables for some supervisors but not all.
    TableCount,
    /// A table's local events are not its supervisor's alphabet's length.
    TableEvents,
    /// A table's state width cannot hold its supervisor's states, or
    /// exceeds 32 bits.
    StateBits,
    /// A table's words are too few for its entries.
    TableLength,
    /// A sparse table's row start is not the number of defined pairs
    /// before the row.
    RowStart {
        /// The state whose row start is wrong.
        state: u32,
    },
    /// A state-map entry's state has bits outside its mask.
    StateMask,
    /// A net group's fields overlap, are empty or not contiguous, or do
    /// not cover exactly the bits of its states.
    Fields,
    /// A net transition's `PRE` or `POST` has bits outside the fields.
    Arcs {
        /// The local transition.
        local: u32,
    },
    /// A guard on an event that is not a command, or guards out of
    /// increasing event order (an event guarded twice).
    Guarded,
    /// A guard's root or node points to itself, to a later node or past
    /// its nodes, or a node reads a state bit that does not exist.
    GuardNode {
        /// The node (0 and 1 are the constants, `k ≥ 2` node `k − 2`).
        node: u32,
    },
    /// A state bit's shift is 32 or more.
    Shift,
    /// A supervisor's stored allowed sets: an entry width outside 1..=16,
    /// an index of the wrong length, a set number past the event sets, or
    /// a set with a bit past the last event.
    AllowedIndex,
    /// A supervisor's stored allowed set in `state` is not the events
    /// outside its alphabet plus those its program enables there
    /// ([`validate_allowed_sets`]).
    AllowedSet {
        /// The state.
        state: u32,
    },
}

/// An image that fails the structure check: where, and what.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Invalid {
    /// Where.
    pub part: Part,
    /// What.
    pub flaw: Flaw,
}

impl Flaw {
    /// A number per kind of flaw, 1 to 24, fixed once given: how a
    /// refusal names it in a byte-sized report (`field_update`'s
    /// `Rejected::Structure`).
    pub const fn code(&self) -> u16 {
        match self {
            Flaw::TooMany => 1,
            Flaw::SpanPastPool => 2,
            Flaw::SetLength => 3,
            Flaw::StrayBits => 4,
            Flaw::OutOfRange { .. } => 5,
            Flaw::Preset => 6,
            Flaw::Period => 7,
            Flaw::Membership => 8,
            Flaw::Outside => 9,
            Flaw::Commands => 10,
            Flaw::TableCount => 11,
            Flaw::TableEvents => 12,
            Flaw::StateBits => 13,
            Flaw::TableLength => 14,
            Flaw::RowStart { .. } => 15,
            Flaw::StateMask => 16,
            Flaw::Fields => 17,
            Flaw::Arcs { .. } => 18,
            Flaw::Guarded => 19,
            Flaw::GuardNode { .. } => 20,
            Flaw::Shift => 21,
            Flaw::AllowedIndex => 22,
            Flaw::AllowedSet { .. } => 23,
            Flaw::Contiguous => 24,
        }
    }
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Part::Counts => f.write_str("the numbers of signals, events and supervisors"),
            Part::ScanPeriod => f.write_str("the scan period"),
            Part::Reset => f.write_str("the reset input"),
            Part::Debounced(k) => write!(f, "debounced input {k}"),
            Part::DebounceMask => f.write_str("the debounce mask"),
            Part::Input(i) => write!(f, "input {i}"),
            Part::Output(o) => write!(f, "output {o}"),
            Part::Timer(t) => write!(f, "timer {t}"),
            Part::Event(e) => write!(f, "event {e}"),
            Part::Supervisor(j) => write!(f, "supervisor {j}"),
            Part::Commands => f.write_str("the commands without a request input"),
            Part::Requested => f.write_str("the commands with a request input"),
            Part::Action(k) => write!(f, "action {k}"),
            Part::Membership(k) => write!(f, "membership {k}"),
            Part::StateMap(k) => write!(f, "state-map entry {k}"),
            Part::Guard(k) => write!(f, "guard {k}"),
            Part::StateBit(k) => write!(f, "state bit {k}"),
            Part::Tables => f.write_str("the tables"),
            Part::Table(j) => write!(f, "the table of supervisor {j}"),
        }
    }
}

impl fmt::Display for Flaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Flaw::TooMany => f.write_str("more than 65,536 items"),
            Flaw::SpanPastPool => f.write_str("a span past the end of its pool"),
            Flaw::SetLength => f.write_str("a set span of the wrong length"),
            Flaw::StrayBits => f.write_str("a set with bits past its last member"),
            Flaw::OutOfRange { index, count } => {
                write!(f, "index {index} out of range (there are {count})")
            }
            Flaw::Preset => f.write_str("a preset outside 1 ms .. 2^31 ms"),
            Flaw::Period => f.write_str("a period outside 1 ms .. 2^31 ms"),
            Flaw::Membership => f.write_str("memberships and alphabet disagree"),
            Flaw::Outside => f.write_str("`outside` is not the events outside the alphabet"),
            Flaw::Contiguous => f.write_str("an alphabet marked contiguous that is not"),
            Flaw::Commands => f.write_str("the command sets disagree with the events"),
            Flaw::TableCount => f.write_str("tables for some supervisors only"),
            Flaw::TableEvents => f.write_str("local events differ from the alphabet's"),
            Flaw::StateBits => f.write_str("a state width that cannot hold the states"),
            Flaw::TableLength => f.write_str("fewer words than its entries need"),
            Flaw::RowStart { state } => write!(f, "a wrong row start for state {state}"),
            Flaw::StateMask => f.write_str("a state with bits outside its mask"),
            Flaw::Fields => f.write_str("net fields that overlap, are empty or not contiguous, or leave bits of the state out"),
            Flaw::Arcs { local } => write!(f, "arcs of transition {local} outside the fields"),
            Flaw::Guarded => f.write_str("a guard on an event that is not a command, or out of event order"),
            Flaw::GuardNode { node } => write!(f, "node {node} points up, past the table or to a missing bit"),
            Flaw::Shift => f.write_str("a shift of 32 bits or more"),
            Flaw::AllowedIndex => f.write_str("stored allowed sets with a wrong width, length or set number"),
            Flaw::AllowedSet { state } => write!(f, "the stored allowed set of state {state} differs from its program's"),
        }
    }
}

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.part, self.flaw)
    }
}

/// Checks the structure of `program`'s image that the scan relies on (see
/// the module docs). Linear in the configuration; a table costs a count
/// of its defined-bits.
pub fn validate<P: Program + ?Sized>(program: &P) -> Result<(), Invalid> {
    // Opaque to the optimiser: a generated configuration is a constant,
    // and folding it into the check would unroll every loop over its pools
    // (kilobytes of flash for a check that runs once).
    let config = core::hint::black_box(program.config());
    validate_config(&config)?;
    let supervisors = config.supervisors.len();
    // One past the supervisors: a table too many is a flaw too.
    let tables = (0..=supervisors)
        .take_while(|&j| Index::try_from(j).is_ok_and(|j| program.table(j).is_some()))
        .count();
    if tables != 0 && tables != supervisors {
        return Err(Invalid {
            part: Part::Tables,
            flaw: Flaw::TableCount,
        });
    }
    for j in 0..tables {
        if let Some(table) = Index::try_from(j).ok().and_then(|j| program.table(j)) {
            validate_table(&config, j, &core::hint::black_box(table))?;
        }
    }
    Ok(())
}

/// Everything a generator proves of its image: [`validate`], then the
/// agreement of memberships, alphabets, `outside` sets and command sets,
/// every defined table entry a state of its supervisor (and a sparse
/// table's row starts), and [`validate_allowed_sets`]. Run at generation
/// and by host tools; the controller runs [`validate`] alone.
pub fn validate_generated<P: Program + ?Sized>(program: &P) -> Result<(), Invalid> {
    validate(program)?;
    let c = program.config();
    agreement(&c)?;
    for j in 0..c.supervisors.len() {
        if let Some(table) = Index::try_from(j).ok().and_then(|j| program.table(j)) {
            table_entries(&c, j, &table)?;
        }
    }
    validate_allowed_sets(program)
}

/// Whether every stored allowed set of `program` is its supervisor's: in
/// every state, the events outside its alphabet and exactly the local
/// events its program enables ([`Program::enabled`]). Checked when a
/// program is generated and by host tools, not by the controller: a wrong
/// set can only hold an event back (an unexpected event, a command not
/// chosen) or let the controller choose one its program refuses (a
/// `Corrupt` fault), never move a supervisor its program does not; and
/// the CRC guards the sets a generator checked. Assumes a program that
/// passes [`validate`].
pub fn validate_allowed_sets<P: Program + ?Sized>(program: &P) -> Result<(), Invalid> {
    let c = program.config();
    for (j, spec) in c.supervisor_specs().enumerate() {
        if spec.allowed.is_stored() {
            allowed_sets_of(program, &c, j)?;
        }
    }
    Ok(())
}

/// [`validate_allowed_sets`] for supervisor `j`.
fn allowed_sets_of<P: Program + ?Sized>(
    program: &P,
    c: &Config<'_>,
    j: usize,
) -> Result<(), Invalid> {
    let spec = &c.supervisor(j);
    let part = Part::Supervisor(j);
    let w = words(c.events.len());
    let outside = spec.outside.of(c.event_masks);
    let alphabet = spec.alphabet.of(c.event_lists);
    for state in 0..spec.states {
        let set = (c.stored_set(spec, state))
            .and_then(|k| c.event_set(k))
            .unwrap_or_default();
        let wrong = fail(part, Flaw::AllowedSet { state });
        let keeps_outside = (0..w).all(|i| {
            let o = outside.get(i).copied().unwrap_or(0);
            set.get(i).is_some_and(|&s| s & o == o)
        });
        if !keeps_outside {
            return wrong;
        }
        for (chunk, local) in alphabet.chunks(32).enumerate() {
            let row = program.enabled(j as Index, state, (chunk * 32) as Index, local.len() as u8);
            for (k, &e) in local.iter().enumerate() {
                if bits::contains(set, e as usize) != (row >> k & 1 == 1) {
                    return wrong;
                }
            }
        }
    }
    Ok(())
}

/// The configuration's part of [`validate`]: everything but the tables
/// (the whole check for a program whose supervisors are code).
#[inline(never)]
pub fn validate_config(c: &Config<'_>) -> Result<(), Invalid> {
    let (inputs, outputs, timers) = (c.inputs.len(), c.outputs.len(), c.timers.len());
    let (events, supervisors) = (c.events.len(), c.supervisors.len());
    let limit = usize::from(Index::MAX) + 1;
    if [inputs, outputs, timers, events, supervisors]
        .iter()
        .any(|&n| n > limit)
    {
        return fail(Part::Counts, Flaw::TooMany);
    }
    if !SCAN_PERIOD_MS.contains(&c.scan_period_ms) {
        return fail(Part::ScanPeriod, Flaw::Period);
    }
    if let Some(r) = c.reset {
        in_range(Part::Reset, r.into(), inputs)?;
    }
    for (k, &i) in c.debounced.iter().enumerate() {
        in_range(Part::Debounced(k), i as usize, inputs)?;
    }
    mask(Part::DebounceMask, c.debounce_mask, c)?;
    for (i, spec) in c.input_specs().enumerate() {
        event_list(Part::Input(i), spec.raises, c)?;
    }
    for (o, spec) in c.output_specs().enumerate() {
        pool(Part::Output(o), spec.state_map, c.state_map)?;
    }
    for (t, spec) in c.timer_specs().enumerate() {
        if !crate::timers::PRESET_MS.contains(&spec.preset_ms) {
            return fail(Part::Timer(t), Flaw::Preset);
        }
        event_list(Part::Timer(t), spec.raises, c)?;
    }
    for (k, action) in c.actions.iter().map(|&a| Action::from_word(a)).enumerate() {
        match action {
            Action::Set(o) | Action::Clear(o) => in_range(Part::Action(k), o.into(), outputs)?,
            Action::Start(t) | Action::Reset(t) => in_range(Part::Action(k), t.into(), timers)?,
        }
    }
    for (k, &m) in c.memberships.iter().enumerate() {
        let m = Membership::from_word(m);
        let part = Part::Membership(k);
        in_range(part, m.supervisor.into(), supervisors)?;
        let alphabet = c.supervisor(usize::from(m.supervisor)).alphabet;
        in_range(part, m.local.into(), alphabet.len.into())?;
    }
    for (k, entry) in c
        .state_map
        .iter()
        .map(StateMapEntry::from_words)
        .enumerate()
    {
        let part = Part::StateMap(k);
        in_range(part, entry.supervisor.into(), supervisors)?;
        let states = c.supervisor(usize::from(entry.supervisor)).states;
        if entry.state >= states {
            return fail(part, out_of_range(entry.state, states));
        }
        if entry.state & !entry.mask != 0 {
            return fail(part, Flaw::StateMask);
        }
    }
    for (e, spec) in c.event_specs().enumerate() {
        let part = Part::Event(e);
        match spec.trigger {
            Trigger::Rising(m) | Trigger::Falling(m) => mask(part, m, c)?,
            Trigger::Expired(t) => in_range(part, t.into(), timers)?,
            Trigger::Command => {}
        }
        mask(part, spec.when, c)?;
        mask(part, spec.unless, c)?;
        if let Some(r) = spec.request {
            in_range(part, r.into(), inputs)?;
        }
        pool(part, spec.actions, c.actions)?;
        pool(part, spec.members, c.memberships)?;
    }
    for (j, spec) in c.supervisor_specs().enumerate() {
        let part = Part::Supervisor(j);
        if spec.initial >= spec.states {
            return fail(part, out_of_range(spec.initial, spec.states));
        }
        event_list(part, spec.alphabet, c)?;
        event_set(part, spec.outside, c)?;
        allowed_index(part, &spec, c)?;
    }
    event_set(Part::Commands, c.commands, c)?;
    event_list(Part::Requested, c.requested, c)?;
    validate_guards(c)
}

/// The agreement [`validate_generated`] adds to [`validate_config`]: each
/// alphabet entry with exactly one membership, its own; each membership
/// its alphabet's; each `outside` set the events outside the alphabet;
/// an alphabet marked `contiguous` consecutive and increasing;
/// the command sets exactly the controllable events without and with a
/// request input. Assumes a configuration that passes
/// [`validate_config`].
fn agreement(c: &Config<'_>) -> Result<(), Invalid> {
    for (j, spec) in c.supervisor_specs().enumerate() {
        let part = Part::Supervisor(j);
        let alphabet = spec.alphabet.of(c.event_lists);
        let outside = spec.outside.of(c.event_masks);
        let first = alphabet.first().copied().unwrap_or(0);
        let consecutive = (alphabet.iter().enumerate()).all(|(k, &e)| e == first + k as u32);
        if spec.contiguous && !consecutive {
            return fail(part, Flaw::Contiguous);
        }
        for (local, &e) in alphabet.iter().enumerate() {
            let mut theirs = members(&c.event(e as usize), c).filter(|m| m.0 == j);
            match (theirs.next(), theirs.next()) {
                (Some((_, l)), None) if l == local => {}
                _ => return fail(part, Flaw::Membership),
            }
        }
        for (e, event) in c.event_specs().enumerate() {
            let member = members(&event, c).any(|m| m.0 == j);
            if member == bits::contains(outside, e) {
                return fail(part, Flaw::Outside);
            }
        }
    }
    for (e, spec) in c.event_specs().enumerate() {
        for (j, local) in members(&spec, c) {
            let alphabet = c.supervisor(j).alphabet.of(c.event_lists);
            if alphabet.get(local).map(|&x| x as usize) != Some(e) {
                return fail(Part::Event(e), Flaw::Membership);
            }
        }
    }
    let commands = c.commands.of(c.event_masks);
    let requested = c.requested.of(c.event_lists);
    for (e, spec) in c.event_specs().enumerate() {
        let command = spec.is_controllable();
        let listed = bits::contains(commands, e);
        if listed != (command && spec.request.is_none()) {
            return fail(Part::Commands, Flaw::Commands);
        }
        let listed = requested.iter().filter(|&&x| x as usize == e).count();
        if listed != usize::from(command && spec.request.is_some()) {
            return fail(Part::Requested, Flaw::Commands);
        }
    }
    Ok(())
}

/// The guards: each on a command, in increasing event order, its nodes
/// inside the pool, every node pointing down to an earlier node or a
/// constant and reading a state bit that exists, every state bit a
/// supervisor's with a shift below 32. Then no walk can loop or read out
/// of range ([`crate::guards`]).
fn validate_guards(c: &Config<'_>) -> Result<(), Invalid> {
    let guards = &c.guards;
    for (k, b) in guards.bits.iter().map(StateBit::from_words).enumerate() {
        in_range(Part::StateBit(k), b.component.into(), c.supervisors.len())?;
        if b.shift >= 32 {
            return fail(Part::StateBit(k), Flaw::Shift);
        }
    }
    let mut previous: Option<Index> = None;
    for (k, guard) in guards.guards().enumerate() {
        let part = Part::Guard(k);
        in_range(part, guard.event.into(), c.events.len())?;
        let command = c.event(usize::from(guard.event)).is_controllable();
        if !command || previous.is_some_and(|p| p >= guard.event) {
            return fail(part, Flaw::Guarded);
        }
        previous = Some(guard.event);
        let nodes = pool(part, guard.nodes, guards.nodes)?;
        let bad = |node: usize| fail(part, Flaw::GuardNode { node: node as u32 });
        if usize::from(guard.root) >= nodes.len() + 2 {
            return bad(usize::from(guard.root));
        }
        for (i, node) in nodes.iter().map(GuardNode::from_words).enumerate() {
            let at = i + 2;
            if usize::from(node.low) >= at
                || usize::from(node.high) >= at
                || usize::from(node.bit) >= guards.bits.len()
            {
                return bad(at);
            }
        }
    }
    Ok(())
}

/// Table `j` against supervisor `j`: sizes, lengths, row starts, and
/// every defined entry a state of the supervisor.
#[inline(never)]
fn validate_table(c: &Config<'_>, j: usize, table: &SupervisorTable<'_>) -> Result<(), Invalid> {
    let part = Part::Table(j);
    let spec = &c.supervisor(j);
    if table.events != spec.alphabet.len {
        return fail(part, Flaw::TableEvents);
    }
    if let Rows::Net { fields } = table.rows {
        return validate_net(part, spec.states, table, fields);
    }
    let states = u64::from(spec.states);
    let width = table.state_bits;
    if !(1..=32).contains(&width) || states.saturating_sub(1) >> width != 0 {
        return fail(part, Flaw::StateBits);
    }
    let m = u64::from(table.events);
    let pairs = states * m;
    if let Rows::Keyed {
        states: records,
        key_bits,
        start_bits,
    } = table.rows
    {
        let entries =
            keyed_entries(spec.states, table, records, key_bits, start_bits).ok_or(Invalid {
                part,
                flaw: Flaw::TableLength,
            })?;
        return if bits_of(table.targets) < entries * u64::from(width) {
            fail(part, Flaw::TableLength)
        } else {
            Ok(())
        };
    }
    if bits_of(table.defined) < pairs {
        return fail(part, Flaw::TableLength);
    }
    let entries = match table.rows {
        Rows::Sparse {
            row_starts,
            start_bits,
        } => {
            if !(1..=32).contains(&start_bits)
                || bits_of(row_starts) < states * u64::from(start_bits)
            {
                return fail(part, Flaw::TableLength);
            }
            // `pairs` fits in the defined words, so in a usize.
            (0..pairs as usize)
                .filter(|&p| bit(table.defined, p))
                .count() as u64
        }
        _ => pairs,
    };
    if bits_of(table.targets) < entries * u64::from(width) {
        return fail(part, Flaw::TableLength);
    }
    Ok(())
}

/// The keyed layout's sizes ([`Rows::Keyed`]): widths of at least 1 bit
/// and at most 32 together, a record per state, and a dictionary of
/// exactly `⌈k·w / 32⌉` words for `k` one more than the largest key and
/// the row stride `w` ([`keyed_stride`]), so that every key names a row
/// inside it. The number of targets its rows
/// give, `None` when a size is wrong.
fn keyed_entries(
    states: u32,
    table: &SupervisorTable<'_>,
    records: &[u32],
    key_bits: u8,
    start_bits: u8,
) -> Option<u64> {
    let record_bits = u32::from(key_bits) + u32::from(start_bits);
    if key_bits == 0
        || start_bits == 0
        || record_bits > 32
        || bits_of(records) < u64::from(states) * u64::from(record_bits)
    {
        return None;
    }
    let m = usize::from(table.events);
    let stride = keyed_stride(m);
    let key = |s: u32| keyed_record(records, key_bits, start_bits, s).0;
    let rows = (0..states).map(key).max().map_or(0, |k| k as u64 + 1);
    if table.defined.len() as u64 != (rows * stride as u64).div_ceil(32) {
        return None;
    }
    // Every row lies inside the dictionary, so in a usize.
    let first = |s: u32| key(s) * stride;
    let ones = |s: u32| ones_between(table.defined, first(s), first(s) + m) as u64;
    Some((0..states).map(ones).sum())
}

/// Every defined pair's target of table `j` a state of supervisor `j`, in
/// the layout's entry order (pair order when dense, the count of defined
/// pairs before it when sparse or keyed), and a sparse or keyed table's
/// row starts those counts. Assumes a table that passes
/// [`validate_table`].
fn table_entries(c: &Config<'_>, j: usize, table: &SupervisorTable<'_>) -> Result<(), Invalid> {
    let part = Part::Table(j);
    let spec = &c.supervisor(j);
    let m = usize::from(table.events);
    // Each state's row of defined-bits (its first bit) and row start.
    let row = |state: u32| -> (usize, Option<usize>) {
        match table.rows {
            Rows::Sparse {
                row_starts,
                start_bits,
            } => (
                state as usize * m,
                Some(read_bits(row_starts, state as usize, start_bits) as usize),
            ),
            Rows::Keyed {
                states,
                key_bits,
                start_bits,
            } => {
                let (key, start) = keyed_record(states, key_bits, start_bits, state);
                (key * keyed_stride(m), Some(start))
            }
            Rows::Dense | Rows::Net { .. } => (state as usize * m, None),
        }
    };
    if let Rows::Net { .. } = table.rows {
        return Ok(());
    }
    let width = table.state_bits;
    let mut before = 0usize;
    for state in 0..spec.states {
        let (first, start) = row(state);
        if start.is_some_and(|start| start != before) {
            return fail(part, Flaw::RowStart { state });
        }
        for e in 0..m {
            if !bit(table.defined, first + e) {
                continue;
            }
            let entry = if start.is_some() {
                before
            } else {
                state as usize * m + e
            };
            let target = read_bits(table.targets, entry, width);
            if target >= spec.states {
                return fail(part, out_of_range(target, spec.states));
            }
            before += 1;
        }
    }
    Ok(())
}

/// A net group (`table.rs`, "Petri nets"): `2^b` states for `b ≤ 31`,
/// contiguous disjoint non-empty fields that cover exactly the state's `b`
/// bits, one `PRE` and one `POST` word per local transition, both within
/// the fields.
fn validate_net(
    part: Part,
    states: u32,
    table: &SupervisorTable<'_>,
    fields: &[u32],
) -> Result<(), Invalid> {
    let width = table.state_bits;
    if !(1..=crate::table::NET_GROUP_BITS).contains(&u32::from(width)) || states != 1 << width {
        return fail(part, Flaw::StateBits);
    }
    let mut covered = 0u32;
    for &field in fields {
        let shifted = field >> field.trailing_zeros().min(31);
        let contiguous = field != 0 && shifted & shifted.wrapping_add(1) == 0;
        if !contiguous || covered & field != 0 {
            return fail(part, Flaw::Fields);
        }
        covered |= field;
    }
    if covered != states - 1 {
        return fail(part, Flaw::Fields);
    }
    let m = usize::from(table.events);
    if table.defined.len() != m || table.targets.len() != m {
        return fail(part, Flaw::TableLength);
    }
    for (local, (&pre, &post)) in table.defined.iter().zip(table.targets).enumerate() {
        if (pre | post) & !covered != 0 {
            return fail(
                part,
                Flaw::Arcs {
                    local: local as u32,
                },
            );
        }
    }
    Ok(())
}

/// The memberships of `event` as (supervisor, local) pairs; its span is
/// checked against the pool by the caller, the supervisors by the pool's
/// check.
fn members<'c>(event: &EventSpec, c: &Config<'c>) -> impl Iterator<Item = (usize, usize)> + 'c {
    c.members_of(event.members)
        .map(|m| (usize::from(m.supervisor), usize::from(m.local)))
}

fn fail<T>(part: Part, flaw: Flaw) -> Result<T, Invalid> {
    Err(Invalid { part, flaw })
}

fn out_of_range(index: u32, count: u32) -> Flaw {
    Flaw::OutOfRange { index, count }
}

fn in_range(part: Part, index: usize, count: usize) -> Result<(), Invalid> {
    if index < count {
        Ok(())
    } else {
        fail(part, out_of_range(index as u32, count as u32))
    }
}

/// A supervisor's index of stored allowed sets: none, or entries of 1 to
/// 16 bits, exactly one word per 32 bits of entries (one per state), each
/// the number of an event set inside `event_masks` with no bit past the
/// last event (the controller may choose any command of the set).
/// Whether the sets are the supervisor's is [`validate_allowed_sets`].
fn allowed_index(part: Part, spec: &SupervisorSpec, c: &Config<'_>) -> Result<(), Invalid> {
    let sets = spec.allowed;
    if !sets.is_stored() {
        return if sets.bits == 0 {
            Ok(())
        } else {
            fail(part, Flaw::AllowedIndex)
        };
    }
    let index = pool(part, sets.index, c.allowed_index)?;
    let entries = u64::from(spec.states) * u64::from(sets.bits);
    let w = words(c.events.len());
    let spare = w * 32 - c.events.len();
    // Read from the checked `index` and `w` directly: through
    // `Config::stored_set` and `Config::event_set` this check took 270
    // bytes more of the target's flash.
    let named = |x: u32| {
        let k = read_bits(index, x as usize, sets.bits) as usize;
        let set = c.event_masks.get(k * w..k * w + w).unwrap_or_default();
        set.len() == w && (spare == 0 || set.last().is_some_and(|&last| last >> (32 - spare) == 0))
    };
    let fits = (1..=16).contains(&sets.bits)
        && index.len() as u64 == entries.div_ceil(32)
        && (0..spec.states).all(named);
    if fits {
        Ok(())
    } else {
        fail(part, Flaw::AllowedIndex)
    }
}

/// Bits in `words`.
fn bits_of(words: &[u32]) -> u64 {
    32 * words.len() as u64
}

/// The items of `pool` that `span` covers, all of them.
fn pool<T>(part: Part, span: Span, pool: &[T]) -> Result<&[T], Invalid> {
    let start = usize::from(span.start);
    pool.get(start..start + usize::from(span.len))
        .ok_or(Invalid {
            part,
            flaw: Flaw::SpanPastPool,
        })
}

/// A list of events in `event_lists`, every one in range.
fn event_list<'c>(part: Part, span: Span, c: &Config<'c>) -> Result<&'c [u32], Invalid> {
    let list = pool(part, span, c.event_lists)?;
    for &e in list {
        in_range(part, e as usize, c.events.len())?;
    }
    Ok(list)
}

/// A set of `members` members in `sets`: empty, or one word per 32
/// members with no bit past the last.
fn set(part: Part, span: Span, sets: &[u32], members: usize) -> Result<&[u32], Invalid> {
    let words_of_set = pool(part, span, sets)?;
    if !words_of_set.is_empty() && words_of_set.len() != words(members) {
        return fail(part, Flaw::SetLength);
    }
    let spare = words(members) * 32 - members;
    let stray = match words_of_set.last() {
        Some(&last) if spare != 0 => last >> (32 - spare) != 0,
        _ => false,
    };
    if stray {
        return fail(part, Flaw::StrayBits);
    }
    Ok(words_of_set)
}

/// An input mask.
fn mask(part: Part, span: Span, c: &Config<'_>) -> Result<(), Invalid> {
    set(part, span, c.input_masks, c.inputs.len()).map(|_| ())
}

/// An event set.
fn event_set<'c>(part: Part, span: Span, c: &Config<'c>) -> Result<&'c [u32], Invalid> {
    set(part, span, c.event_masks, c.events.len())
}
