//! The program image: what the image CRC covers, as a stream of 32-bit
//! words in a fixed order.
//!
//! The image of a [`Program`] is everything the controller trusts that is
//! data rather than code: every field of its [`Config`] and every word of
//! every supervisor table ([`Program::table`]). The logic and `match`
//! backends have no tables (their supervisors are code), so their image is
//! the configuration alone.
//!
//! # The stream
//!
//! The image is a sequence of *runs* of words. Scalars are one word each
//! (zero-extended; `None` is `0xFFFF_FFFF`); a [`Span`] is one word,
//! `start | len << 16`; a record is a fixed number of words, so word `k` of
//! a run can be computed without reading the words before it (the
//! background test resumes in the middle of a run: [`crate::Controller`],
//! `docs/semantics.md`, "Image check").
//!
//! | run | words per item | content |
//! |---|---|---|
//! | header | 29 | name length in bytes, `scan_period_ms`, `max_commands_per_scan`, `unexpected` (0 fault, 1 ignore), `reset`, `overrun_limit`, `overrun_fault`, `lost_edge_fault`, `rom_test_bytes_per_scan`, the spans `debounce_mask`, `commands` and `requested`; the lengths of the sixteen pools below (inputs … allowed index) and the number of tables |
//! | name | ⌈bytes / 4⌉ | the name's UTF-8 bytes, four per word, first byte least significant, the last word padded with zeros |
//! | inputs | 2 | `debounce_scans`; `raises` |
//! | debounced | 1 | the input |
//! | outputs | 2 | `safe \| initial << 1`; `state_map` |
//! | timers | 2 | `preset_ms`; `raises` |
//! | events | 7 | trigger (0 command, 1 rising, 2 falling, 3 expired); its mask span or timer (0 for a command); `when`; `unless`; `request`; `actions`; `members` |
//! | supervisors | 6 | `states`; `initial`; `alphabet`; `outside`; `allowed.index`; `allowed.bits` |
//! | input masks | 1 | the word as stored |
//! | event lists | 1 | the event |
//! | event masks | 1 | the word as stored |
//! | actions | 1 | kind (0 set, 1 clear, 2 start, 3 reset) `<< 16 \|` its output or timer |
//! | memberships | 1 | `supervisor \| local << 16` |
//! | state map | 3 | `supervisor`; `state`; `mask` |
//! | guards | 3 | `event`; `root`; `nodes` |
//! | state bits | 1 | `component \| shift << 16` |
//! | guard nodes | 2 | `bit \| low << 16`; `high` |
//! | allowed index | 1 | the word as stored |
//!
//! then, per table in supervisor order, four runs: a 7-word header
//! (events, state bits, layout (0 dense, 1 sparse, 2 net), row-start bits
//! (0 when dense or net), and the word counts of `defined`, `targets` and
//! `row_starts` (a net's `fields`)), then the words of `defined`,
//! `targets` and `row_starts` (`fields`) as stored.
//!
//! # The CRC
//!
//! CRC-32/MPEG-2 (polynomial `0x04C11DB7`, initial value `0xFFFF_FFFF`, no
//! reflection, no final XOR) over the stream, each word fed as its four
//! bytes most significant first. That is what the CRC unit of STM32 chips
//! computes from the same words written to its data register, so a board
//! can check the image in hardware and get the value the generator
//! recorded; and since the register is the result, a check can stop after
//! any word and resume from the 32-bit value alone.
//!
//! # Cost
//!
//! Measured in QEMU (Cortex-M4, `cargo xtask qemu`): a table word costs 4
//! instructions per byte (the monolithic boiler's whole image, 125,156
//! bytes, 508,000 instructions), a configuration record up to three times
//! that (it is encoded as it is read); a background share adds about 110
//! instructions per scan to that.

use crate::program::{
    Action, Config, EventSpec, GuardNode, GuardSpec, Index, InputSpec, Membership, OutputSpec,
    Program, Span, StateBit, StateMapEntry, SupervisorSpec, TimerSpec, Trigger, UnexpectedPolicy,
};
use crate::table::{Rows, SupervisorTable, TableProgram};
use crc::{Crc, CRC_32_MPEG_2};

/// The CRC algorithm of program images, with the `crc` crate's table (256
/// words, 1 KiB of flash). A `static`, so the table is in flash once.
pub static IMAGE_CRC: Crc<u32> = Crc::<u32>::new(&CRC_32_MPEG_2);

// Resuming a check from the CRC value alone needs a CRC whose value is its
// register: 32 bits, no reflection, no final XOR.
const _: () = assert!(
    CRC_32_MPEG_2.width == 32
        && !CRC_32_MPEG_2.refin
        && !CRC_32_MPEG_2.refout
        && CRC_32_MPEG_2.xorout == 0
);

/// The CRC register before the first word.
pub(crate) const CRC_START: u32 = CRC_32_MPEG_2.init;

/// Runs of the configuration, before the tables.
const CONFIG_RUNS: usize = 18;
/// Runs per table: header, `defined`, `targets`, `row_starts`.
const TABLE_RUNS: usize = 4;
/// Words of the header run.
const HEADER_WORDS: usize = 29;
/// Words of an event's record.
const EVENT_WORDS: usize = 7;
/// Words of a supervisor's record.
const SUPERVISOR_WORDS: usize = 6;
/// Words of a table's header run.
const TABLE_HEADER_WORDS: usize = 7;

/// Where a check of the stream stands: the next word to feed and the CRC of
/// the words before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Cursor {
    /// The run.
    run: usize,
    /// The word within the run.
    word: usize,
    /// Words fed since the start of the stream.
    fed: usize,
    /// The CRC register after every word before this one.
    crc: u32,
}

impl Cursor {
    /// At the first word of the stream.
    pub(crate) const START: Cursor = Cursor {
        run: 0,
        word: 0,
        fed: 0,
        crc: CRC_START,
    };

    /// The CRC register after every word before the cursor.
    pub(crate) fn crc(&self) -> u32 {
        self.crc
    }

    /// Words fed since the start of the stream.
    pub(crate) fn fed(&self) -> usize {
        self.fed
    }
}

/// The CRC of `program`'s whole image.
pub fn crc<P: Program + ?Sized>(program: &P) -> u32 {
    let mut cursor = Cursor::START;
    advance(program, &mut cursor, usize::MAX);
    cursor.crc
}

/// The length of `program`'s image in bytes (a multiple of 4).
pub fn bytes<P: Program + ?Sized>(program: &P) -> usize {
    let stream = Stream::of(program);
    let mut words = 0;
    let mut r = 0;
    while let Some(run) = stream.run(r) {
        words += run.len();
        r += 1;
    }
    4 * words
}

/// The CRC of a configuration alone: the image of a program without
/// tables, and how recorded scenarios name the project they belong to.
pub fn config_crc(config: &Config<'_>) -> u32 {
    table_image_crc(config, &[])
}

/// The CRC of the image of `config` with `tables` (what a generator
/// records for a [`TableProgram`]).
pub fn table_image_crc(config: &Config<'_>, tables: &[SupervisorTable<'_>]) -> u32 {
    crc(&TableProgram {
        config: *config,
        tables,
        crc: 0,
    })
}

/// Feeds up to `budget` words of `program`'s image from `cursor` on into
/// its CRC. Returns `true` when the stream has ended: then `cursor.crc` is
/// the image's CRC, and `cursor` is left at the end (the caller starts the
/// next pass). The end is found in the call that feeds the last word.
///
/// Out of line, and reading the configuration itself: a generated
/// program's configuration is a constant, so its fields fold into the code
/// rather than being copied in every scan.
#[inline(never)]
pub(crate) fn advance<P: Program + ?Sized>(
    program: &P,
    cursor: &mut Cursor,
    mut budget: usize,
) -> bool {
    let stream = Stream::of(program);
    let mut feeder = Feeder::new(cursor.crc);
    let ended = loop {
        let Some(run) = stream.run(cursor.run) else {
            break true;
        };
        let len = run.len();
        if cursor.word >= len {
            cursor.run += 1;
            cursor.word = 0;
            continue;
        }
        if budget == 0 {
            break false;
        }
        let end = len.min(cursor.word.saturating_add(budget));
        stream.feed(&run, cursor.word, end, &mut feeder);
        budget -= end - cursor.word;
        cursor.fed += end - cursor.word;
        cursor.word = end;
    };
    cursor.crc = feeder.finish();
    ended
}

/// A program's image as runs of words.
struct Stream<'a, P: ?Sized> {
    program: &'a P,
    config: Config<'a>,
}

impl<'a, P: Program + ?Sized> Stream<'a, P> {
    fn of(program: &'a P) -> Self {
        Stream {
            program,
            config: program.config(),
        }
    }

    /// The number of tables: they are numbered from 0 without a gap.
    fn tables(&self) -> usize {
        (0..).take_while(|&t| self.table(t).is_some()).count()
    }

    fn table(&self, t: usize) -> Option<SupervisorTable<'a>> {
        self.program.table(Index::try_from(t).ok()?)
    }

    /// Run `r` of the stream, `None` past the last.
    fn run(&self, r: usize) -> Option<Run<'a>> {
        let c = &self.config;
        Some(match r {
            0 => Run::Header,
            1 => Run::Name(c.name.as_bytes()),
            2 => Run::Inputs(c.inputs),
            3 => Run::Indices(c.debounced),
            4 => Run::Outputs(c.outputs),
            5 => Run::Timers(c.timers),
            6 => Run::Events(c.events),
            7 => Run::Supervisors(c.supervisors),
            8 => Run::Stored(c.input_masks),
            9 => Run::Indices(c.event_lists),
            10 => Run::Stored(c.event_masks),
            11 => Run::Actions(c.actions),
            12 => Run::Memberships(c.memberships),
            13 => Run::StateMap(c.state_map),
            14 => Run::Guards(c.guards.events),
            15 => Run::StateBits(c.guards.bits),
            16 => Run::GuardNodes(c.guards.nodes),
            17 => Run::Stored(c.allowed_index),
            _ => {
                let r = r - CONFIG_RUNS;
                let table = self.table(r / TABLE_RUNS)?;
                match r % TABLE_RUNS {
                    0 => Run::TableHeader(table),
                    1 => Run::Stored(table.defined),
                    2 => Run::Stored(table.targets),
                    _ => Run::Stored(match table.rows {
                        Rows::Dense => &[],
                        Rows::Sparse { row_starts, .. } => row_starts,
                        Rows::Net { fields } => fields,
                    }),
                }
            }
        })
    }

    /// Feeds words `from..to` of `run`. Stored words go as they are; the
    /// other runs are encoded a record (an item's few words) at a time, so
    /// a share that starts or ends inside a record encodes it once.
    fn feed(&self, run: &Run<'_>, from: usize, to: usize, feeder: &mut Feeder) {
        match *run {
            Run::Stored(words) => feeder.push(&words[from..to]),
            Run::Header => (from..to).for_each(|k| feeder.push(&[self.header_word(k)])),
            Run::Name(bytes) => feed_records(bytes.chunks(4), from, to, feeder, |chunk| {
                let mut word = [0u8; 4];
                word[..chunk.len()].copy_from_slice(chunk);
                [u32::from_le_bytes(word)]
            }),
            Run::Inputs(inputs) => feed_records(inputs, from, to, feeder, |i| {
                [i.debounce_scans.into(), span(i.raises)]
            }),
            Run::Indices(indices) => feed_records(indices, from, to, feeder, |&i| [i.into()]),
            Run::Outputs(outputs) => feed_records(outputs, from, to, feeder, |o| {
                let levels = u32::from(o.safe) | u32::from(o.initial) << 1;
                [levels, span(o.state_map)]
            }),
            Run::Timers(timers) => {
                feed_records(timers, from, to, feeder, |t| [t.preset_ms, span(t.raises)])
            }
            Run::Events(events) => feed_records(events, from, to, feeder, |e| {
                let (kind, binding) = match e.trigger {
                    Trigger::Command => (0, 0),
                    Trigger::Rising(mask) => (1, span(mask)),
                    Trigger::Falling(mask) => (2, span(mask)),
                    Trigger::Expired(timer) => (3, timer.into()),
                };
                [
                    kind,
                    binding,
                    span(e.when),
                    span(e.unless),
                    e.request.map_or(u32::MAX, u32::from),
                    span(e.actions),
                    span(e.members),
                ]
            }),
            Run::Supervisors(supervisors) => feed_records(supervisors, from, to, feeder, |s| {
                [
                    s.states,
                    s.initial,
                    span(s.alphabet),
                    span(s.outside),
                    span(s.allowed.index),
                    s.allowed.bits.into(),
                ]
            }),
            Run::Actions(actions) => feed_records(actions, from, to, feeder, |a| {
                [match *a {
                    Action::Set(o) => u32::from(o),
                    Action::Clear(o) => 1 << 16 | u32::from(o),
                    Action::Start(t) => 2 << 16 | u32::from(t),
                    Action::Reset(t) => 3 << 16 | u32::from(t),
                }]
            }),
            Run::Memberships(members) => feed_records(members, from, to, feeder, |m| {
                [u32::from(m.supervisor) | u32::from(m.local) << 16]
            }),
            Run::StateMap(entries) => feed_records(entries, from, to, feeder, |e| {
                [e.supervisor.into(), e.state, e.mask]
            }),
            Run::Guards(guards) => feed_records(guards, from, to, feeder, |g| {
                [g.event.into(), g.root.into(), span(g.nodes)]
            }),
            Run::StateBits(bits) => feed_records(bits, from, to, feeder, |b| {
                [u32::from(b.component) | u32::from(b.shift) << 16]
            }),
            Run::GuardNodes(nodes) => feed_records(nodes, from, to, feeder, |n| {
                [u32::from(n.bit) | u32::from(n.low) << 16, n.high.into()]
            }),
            Run::TableHeader(ref t) => {
                let (layout, start_bits, row_starts) = match t.rows {
                    Rows::Dense => (0, 0, 0),
                    Rows::Net { fields } => (2, 0, fields.len()),
                    Rows::Sparse {
                        row_starts,
                        start_bits,
                    } => (1, start_bits, row_starts.len()),
                };
                let header = [
                    t.events.into(),
                    t.state_bits.into(),
                    layout,
                    start_bits.into(),
                    t.defined.len() as u32,
                    t.targets.len() as u32,
                    row_starts as u32,
                ];
                feeder.push(&header[from..to]);
            }
        }
    }

    /// Word `k` of the header run.
    fn header_word(&self, k: usize) -> u32 {
        let c = &self.config;
        match k {
            0 => c.name.len() as u32,
            1 => c.scan_period_ms,
            2 => c.max_commands_per_scan.into(),
            3 => match c.unexpected {
                UnexpectedPolicy::Fault => 0,
                UnexpectedPolicy::Ignore => 1,
            },
            4 => c.reset.map_or(u32::MAX, u32::from),
            5 => c.overrun_limit.into(),
            6 => c.overrun_fault.into(),
            7 => c.lost_edge_fault.into(),
            8 => c.rom_test_bytes_per_scan.into(),
            9 => span(c.debounce_mask),
            10 => span(c.commands),
            11 => span(c.requested),
            12 => c.inputs.len() as u32,
            13 => c.debounced.len() as u32,
            14 => c.outputs.len() as u32,
            15 => c.timers.len() as u32,
            16 => c.events.len() as u32,
            17 => c.supervisors.len() as u32,
            18 => c.input_masks.len() as u32,
            19 => c.event_lists.len() as u32,
            20 => c.event_masks.len() as u32,
            21 => c.actions.len() as u32,
            22 => c.memberships.len() as u32,
            23 => c.state_map.len() as u32,
            24 => c.guards.events.len() as u32,
            25 => c.guards.bits.len() as u32,
            26 => c.guards.nodes.len() as u32,
            27 => c.allowed_index.len() as u32,
            _ => self.tables() as u32,
        }
    }
}

/// One run of the stream.
#[derive(Debug, Clone, Copy)]
enum Run<'a> {
    /// Words fed as stored (masks, table parts).
    Stored(&'a [u32]),
    /// The configuration's scalars and lengths.
    Header,
    /// The project name.
    Name(&'a [u8]),
    /// Inputs.
    Inputs(&'a [InputSpec]),
    /// Outputs.
    Outputs(&'a [OutputSpec]),
    /// Timers.
    Timers(&'a [TimerSpec]),
    /// Events.
    Events(&'a [EventSpec]),
    /// Supervisors.
    Supervisors(&'a [SupervisorSpec]),
    /// A pool of indices (debounced inputs, event lists).
    Indices(&'a [Index]),
    /// The pool of actions.
    Actions(&'a [Action]),
    /// The pool of memberships.
    Memberships(&'a [Membership]),
    /// The pool of state-map entries.
    StateMap(&'a [StateMapEntry]),
    /// The guarded events.
    Guards(&'a [GuardSpec]),
    /// The pool of state bits guards read.
    StateBits(&'a [StateBit]),
    /// The pool of guard nodes.
    GuardNodes(&'a [GuardNode]),
    /// A table's sizes and layout.
    TableHeader(SupervisorTable<'a>),
}

impl Run<'_> {
    /// Its length in words.
    fn len(&self) -> usize {
        match *self {
            Run::Stored(words) => words.len(),
            Run::Header => HEADER_WORDS,
            Run::Name(bytes) => bytes.len().div_ceil(4),
            Run::Inputs(x) => 2 * x.len(),
            Run::Outputs(x) => 2 * x.len(),
            Run::Timers(x) => 2 * x.len(),
            Run::Events(x) => EVENT_WORDS * x.len(),
            Run::Supervisors(x) => SUPERVISOR_WORDS * x.len(),
            Run::Indices(x) => x.len(),
            Run::Actions(x) => x.len(),
            Run::Memberships(x) => x.len(),
            Run::StateMap(x) => 3 * x.len(),
            Run::Guards(x) => 3 * x.len(),
            Run::StateBits(x) => x.len(),
            Run::GuardNodes(x) => 2 * x.len(),
            Run::TableHeader(_) => TABLE_HEADER_WORDS,
        }
    }
}

/// The word of a span.
fn span(s: Span) -> u32 {
    u32::from(s.start) | u32::from(s.len) << 16
}

/// Feeds words `from..to` of a run of `N`-word records, each encoded by
/// `encode`.
#[inline]
fn feed_records<T, const N: usize>(
    items: impl IntoIterator<Item = T>,
    from: usize,
    to: usize,
    feeder: &mut Feeder,
    encode: impl Fn(T) -> [u32; N],
) {
    let first = from / N;
    for (k, item) in items.into_iter().enumerate().skip(first) {
        let start = k * N;
        if start >= to {
            break;
        }
        let record = encode(item);
        let words = &record[from.max(start) - start..N.min(to - start)];
        feeder.push(words);
    }
}

/// The CRC register, fed whole words: each word's four bytes, most
/// significant first, one step of the `crc` crate's table each
/// ([`IMAGE_CRC`]`.table()`, the table its own `update` uses). The crate's
/// `update` takes bytes: feeding it words would copy them byte-swapped into
/// a buffer first, which costs more than the table steps themselves (in
/// QEMU, Cortex-M4, the monolithic boiler's whole image: 6.8 instructions
/// per byte through a buffer, 4.1 this way).
struct Feeder {
    crc: u32,
}

impl Feeder {
    fn new(crc: u32) -> Feeder {
        Feeder { crc }
    }

    /// Out of line: every run pushes its records here, and one copy of the
    /// loop is kilobytes of flash less than one per kind of record.
    #[inline(never)]
    fn push(&mut self, words: &[u32]) {
        let table = &IMAGE_CRC.table()[0];
        let mut crc = self.crc;
        for &word in words {
            crc ^= word;
            for _ in 0..4 {
                crc = table[(crc >> 24) as usize] ^ (crc << 8);
            }
        }
        self.crc = crc;
    }

    /// The CRC register after every word pushed.
    fn finish(&self) -> u32 {
        self.crc
    }
}
