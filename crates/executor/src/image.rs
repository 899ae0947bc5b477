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
//! The image is a sequence of *runs* of words. The configuration's pools
//! are stored as words already ([`Config`]: a record of a fixed number of
//! words per item, `[[u32; N]]`, or one word per item), so every run but
//! three is fed as stored: the background test needs no encoder, and
//! resumes at any word of a run (run, word, CRC: [`crate::Controller`],
//! `docs/semantics.md`, "Image check"). The three computed runs are the
//! header (from [`Config`]'s scalars and its pools' lengths), the name
//! (from its `&str`) and each table's header. In the header, scalars are
//! one word each (zero-extended; `None` is `0xFFFF_FFFF`); a [`Span`]
//! is one word, `start | len << 16` ([`Span::to_word`]). Each kind's
//! `to_words` writes its record, `from_words` reads it.
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
//! | supervisors | 6 | `states`; `initial`; `alphabet`; `outside`; `allowed.index`; `allowed.bits \| contiguous << 8` |
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
//! (events, state bits, layout (0 dense, 1 sparse, 2 net, 3 keyed), the
//! widths (a sparse table's row-start bits; a keyed table's `start_bits |
//! key_bits << 8`; 0 when dense or net), and the word counts of
//! `defined`, `targets` and `row_starts` (a net's `fields`, a keyed
//! table's `states`)), then the words of `defined`, `targets` and
//! `row_starts` (`fields`, `states`) as stored.
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
//! Measured in QEMU (Cortex-M4, `cargo xtask qemu`): a word costs 4
//! instructions per byte, a configuration record's as a table's (the
//! monolithic boiler's whole image, 125,156 bytes, 508,000 instructions);
//! a background share adds about 110 instructions per scan to that.

#[cfg(doc)]
use crate::program::Span;
use crate::program::{Config, Index, Layouts, Program, UnexpectedPolicy};
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
pub const CRC_START: u32 = CRC_32_MPEG_2.init;

/// What computes the image CRC: the register after whole words fed most
/// significant byte first ([`IMAGE_CRC`]'s algorithm). [`TableCrc`] in
/// software, the default; a board with a CRC unit computing the same (an
/// STM32's) may give the controller its own
/// ([`crate::Controller::new_proven_with_crc`], or
/// [`crate::Controller::new_with_crc`] for a program whose structure is
/// checked at start-up too): the image check then takes neither the
/// software's 1 KiB table nor its instructions.
pub trait CrcEngine {
    /// The register after `words` fed to a register holding `crc`. An
    /// engine whose register cannot be loaded with `crc` (an STM32F4's
    /// CRC unit can only be reset to [`CRC_START`]) computes the words
    /// another way when its register does not hold `crc`
    /// ([`feed_bitwise`]): the value must not depend on what else used
    /// the unit.
    fn feed(&mut self, crc: u32, words: &[u32]) -> u32;
}

/// An engine lent rather than given: a firmware that makes one controller
/// after another (field update) lends each its CRC unit in turn.
impl<E: CrcEngine + ?Sized> CrcEngine for &mut E {
    #[inline]
    fn feed(&mut self, crc: u32, words: &[u32]) -> u32 {
        (**self).feed(crc, words)
    }
}

/// The software [`CrcEngine`]: one step of the `crc` crate's table
/// ([`IMAGE_CRC`]`.table()`, the table its own `update` uses) per byte.
/// The crate's `update` takes bytes: feeding it words would copy them
/// byte-swapped into a buffer first, which costs more than the table
/// steps themselves (in QEMU, Cortex-M4, the monolithic boiler's whole
/// image: 6.8 instructions per byte through a buffer, 4.1 this way).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TableCrc;

impl CrcEngine for TableCrc {
    #[inline]
    fn feed(&mut self, mut crc: u32, words: &[u32]) -> u32 {
        let table = &IMAGE_CRC.table()[0];
        for &word in words {
            crc ^= word;
            for _ in 0..4 {
                crc = table[(crc >> 24) as usize] ^ (crc << 8);
            }
        }
        crc
    }
}

/// The image CRC of `words` fed to a register holding `crc`, one bit at
/// a time (no table): the fallback of a CRC unit whose register cannot be
/// loaded, 274 bytes of code on a Cortex-M4 beside a board's unit where
/// [`TableCrc`] would add its 1 KiB table. LLVM would turn a bit-by-bit
/// CRC of a constant polynomial into a table of its own, and unroll the
/// 32 steps of a word: the polynomial and the step count go through
/// `black_box`, which it cannot see through.
#[inline(never)]
pub fn feed_bitwise(mut crc: u32, words: &[u32]) -> u32 {
    let poly = core::hint::black_box(CRC_32_MPEG_2.poly);
    let steps = core::hint::black_box(32u32);
    for &word in words {
        crc ^= word;
        for _ in 0..steps {
            crc = if crc & 0x8000_0000 != 0 {
                crc << 1 ^ poly
            } else {
                crc << 1
            };
        }
    }
    crc
}

/// Runs of the configuration, before the tables.
const CONFIG_RUNS: usize = 18;
/// Runs per table: header, `defined`, `targets`, `row_starts` (`states`).
const TABLE_RUNS: usize = 4;
/// Words of the header run.
pub(crate) const HEADER_WORDS: usize = 29;
/// Words of a table's header run.
pub(crate) const TABLE_HEADER_WORDS: usize = 7;

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
    crc_with(program, &mut TableCrc)
}

/// [`crc()`] computed by `engine`.
pub fn crc_with<P: Program + ?Sized, E: CrcEngine + ?Sized>(program: &P, engine: &mut E) -> u32 {
    let mut cursor = Cursor::START;
    advance(program, &mut cursor, usize::MAX, engine);
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

/// Calls `f` with every word of `program`'s image, in order: the image as
/// one run of words, which [`crate::parse::Blob::parse`] reads back.
pub fn for_each_word<P: Program + ?Sized>(program: &P, mut f: impl FnMut(u32)) {
    let stream = Stream::of(program);
    let mut r = 0;
    while let Some(run) = stream.run(r) {
        match run {
            Run::Words(words) => words.iter().for_each(|&w| f(w)),
            Run::TableHeader(header) => header.iter().for_each(|&w| f(w)),
            Run::Header => (0..HEADER_WORDS).for_each(|k| f(stream.header_word(k))),
            Run::Name(bytes) => (0..run.len()).for_each(|k| f(name_word(bytes, k))),
        }
        r += 1;
    }
}

/// `program`'s image as one vector of words (hosts writing an image file).
#[cfg(feature = "alloc")]
pub fn words<P: Program + ?Sized>(program: &P) -> alloc::vec::Vec<u32> {
    let mut words = alloc::vec::Vec::new();
    for_each_word(program, |w| words.push(w));
    words
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
pub(crate) fn advance<P: Program + ?Sized, E: CrcEngine + ?Sized>(
    program: &P,
    cursor: &mut Cursor,
    mut budget: usize,
    engine: &mut E,
) -> bool {
    let stream = Stream::of(program);
    let mut feeder = Feeder {
        engine,
        crc: cursor.crc,
    };
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

    /// Run `r` of the stream, `None` past the last. Every run but the
    /// header, the name and a table's header is words as stored.
    fn run(&self, r: usize) -> Option<Run<'a>> {
        let c = &self.config;
        let layouts = self.program.layouts();
        Some(Run::Words(match r {
            0 => return Some(Run::Header),
            1 => return Some(Run::Name(c.name.as_bytes())),
            2 => c.inputs.as_flattened(),
            3 => c.debounced,
            4 => c.outputs.as_flattened(),
            5 => c.timers.as_flattened(),
            6 => c.events.as_flattened(),
            7 => c.supervisors.as_flattened(),
            8 => c.input_masks,
            9 => c.event_lists,
            10 => c.event_masks,
            11 => c.actions,
            12 => c.memberships,
            13 => c.state_map.as_flattened(),
            14 => c.guards.events.as_flattened(),
            15 => c.guards.bits.as_flattened(),
            16 => c.guards.nodes.as_flattened(),
            17 => c.allowed_index,
            _ => {
                let r = r - CONFIG_RUNS;
                let table = self.table(r / TABLE_RUNS)?;
                match r % TABLE_RUNS {
                    0 => return Some(Run::TableHeader(table_header(&table, layouts))),
                    1 => table.defined,
                    2 => table.targets,
                    // Only the layouts the program uses: a compiled
                    // program links no arm of the others.
                    _ => match table.rows {
                        Rows::Sparse { row_starts, .. } if layouts.has(Layouts::SPARSE) => {
                            row_starts
                        }
                        Rows::Net { fields } if layouts.has(Layouts::NET) => fields,
                        Rows::Keyed { states, .. } if layouts.has(Layouts::KEYED) => states,
                        _ => &[],
                    },
                }
            }
        }))
    }

    /// Feeds words `from..to` of `run`.
    fn feed<E: CrcEngine + ?Sized>(
        &self,
        run: &Run<'_>,
        from: usize,
        to: usize,
        feeder: &mut Feeder<'_, E>,
    ) {
        match *run {
            // In range by construction (`to` is at most the run's length);
            // `get` keeps the panic path, and its formatting, out of the
            // target's flash.
            Run::Words(words) => feeder.push(words.get(from..to).unwrap_or_default()),
            Run::TableHeader(ref header) => feeder.push(header.get(from..to).unwrap_or_default()),
            Run::Header => (from..to).for_each(|k| feeder.push(&[self.header_word(k)])),
            Run::Name(bytes) => (from..to).for_each(|k| feeder.push(&[name_word(bytes, k)])),
        }
    }

    /// Word `k` of the header run.
    fn header_word(&self, k: usize) -> u32 {
        let c = &self.config;
        (match k {
            0 => c.name.len(),
            1 => return c.scan_period_ms,
            2 => c.max_commands_per_scan.into(),
            3 => match c.unexpected {
                UnexpectedPolicy::Fault => 0,
                UnexpectedPolicy::Ignore => 1,
            },
            4 => return c.reset.map_or(u32::MAX, u32::from),
            5 => c.overrun_limit.into(),
            6 => c.overrun_fault.into(),
            7 => c.lost_edge_fault.into(),
            8 => c.rom_test_bytes_per_scan.into(),
            9 => return c.debounce_mask.to_word(),
            10 => return c.commands.to_word(),
            11 => return c.requested.to_word(),
            12 => c.inputs.len(),
            13 => c.debounced.len(),
            14 => c.outputs.len(),
            15 => c.timers.len(),
            16 => c.events.len(),
            17 => c.supervisors.len(),
            18 => c.input_masks.len(),
            19 => c.event_lists.len(),
            20 => c.event_masks.len(),
            21 => c.actions.len(),
            22 => c.memberships.len(),
            23 => c.state_map.len(),
            24 => c.guards.events.len(),
            25 => c.guards.bits.len(),
            26 => c.guards.nodes.len(),
            27 => c.allowed_index.len(),
            _ => self.tables(),
        }) as u32
    }
}

/// Word `k` of the name run: bytes `4k..4k + 4`, the first least
/// significant, zeros past the end.
fn name_word(bytes: &[u8], k: usize) -> u32 {
    let mut word = [0u8; 4];
    let chunk = bytes.get(4 * k..).unwrap_or(&[]);
    let n = chunk.len().min(4);
    word[..n].copy_from_slice(&chunk[..n]);
    u32::from_le_bytes(word)
}

/// A table's header run: events, state bits, layout (0 dense, 1 sparse,
/// 2 net, 3 keyed), widths (row-start bits; `start_bits | key_bits << 8`
/// when keyed), and the word counts of `defined`, `targets` and
/// `row_starts` (`fields`, `states`).
fn table_header(t: &SupervisorTable<'_>, layouts: Layouts) -> [u32; TABLE_HEADER_WORDS] {
    // Only the arms of `layouts` ([`Stream::run`]); a table of another
    // layout is not in the program.
    let (layout, widths, row_starts) = match t.rows {
        Rows::Net { fields } if layouts.has(Layouts::NET) => (2, 0, fields.len()),
        Rows::Sparse {
            row_starts,
            start_bits,
        } if layouts.has(Layouts::SPARSE) => (1, u32::from(start_bits), row_starts.len()),
        Rows::Keyed {
            states,
            key_bits,
            start_bits,
        } if layouts.has(Layouts::KEYED) => (
            3,
            u32::from(start_bits) | u32::from(key_bits) << 8,
            states.len(),
        ),
        _ => (0, 0, 0),
    };
    [
        t.events.into(),
        t.state_bits.into(),
        layout,
        widths,
        t.defined.len() as u32,
        t.targets.len() as u32,
        row_starts as u32,
    ]
}

/// One run of the stream.
#[derive(Debug, Clone, Copy)]
enum Run<'a> {
    /// Words fed as stored (every pool, table parts).
    Words(&'a [u32]),
    /// The configuration's scalars and lengths.
    Header,
    /// The project name.
    Name(&'a [u8]),
    /// A table's sizes and layout.
    TableHeader([u32; TABLE_HEADER_WORDS]),
}

impl Run<'_> {
    /// Its length in words.
    fn len(&self) -> usize {
        match *self {
            Run::Words(words) => words.len(),
            Run::Header => HEADER_WORDS,
            Run::Name(bytes) => bytes.len().div_ceil(4),
            Run::TableHeader(_) => TABLE_HEADER_WORDS,
        }
    }
}

/// The CRC register, fed whole words by `engine`.
struct Feeder<'e, E: ?Sized> {
    engine: &'e mut E,
    crc: u32,
}

impl<E: CrcEngine + ?Sized> Feeder<'_, E> {
    /// Out of line: every run pushes its records here, and one copy of the
    /// loop is kilobytes of flash less than one per kind of record.
    #[inline(never)]
    fn push(&mut self, words: &[u32]) {
        self.crc = self.engine.feed(self.crc, words);
    }

    /// The CRC register after every word pushed.
    fn finish(&self) -> u32 {
        self.crc
    }
}
