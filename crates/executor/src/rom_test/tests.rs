//! The background image test on a real table program: a ring of
//! `STATES` states that a rising edge of input `step` moves one state on,
//! with a `reset` input; corruption is a bit flipped in a copy of its
//! table words or configuration, swapped in between two scans.

extern crate std;

use crate::image::{self, IMAGE_CRC};
use crate::memory::StaticMemory;
use crate::program::leak::{records, words};
use crate::program::*;
use crate::table::{read_bits, Rows, SupervisorTable, TableProgram};
use crate::{Controller, Fault};
use core::cell::Cell;
use std::boxed::Box;
use std::vec;
use std::vec::Vec;

/// States of the ring: enough table words for passes of many scans.
const STATES: u32 = 300;
/// Local events: `step`, the only one.
const EVENTS: u16 = 1;
/// Inputs.
const STEP: usize = 0;
const RESET: usize = 1;
/// An output that is 1 in the initial state, 0 in the safe image.
const HOME_LAMP: usize = 0;

fn leak<T>(v: Vec<T>) -> &'static [T] {
    Box::leak(v.into_boxed_slice())
}

/// A pool of one record.
fn one<T: Record<N>, const N: usize>(item: T) -> &'static [[u32; N]] {
    records(&[item])
}

/// The ring's table in the dense layout, packed as the module docs of
/// [`crate::table`] say.
fn ring_table() -> SupervisorTable<'static> {
    let (n, m) = (STATES as usize, EVENTS as usize);
    let bits = 9; // ⌈log2 300⌉
    let mut defined = vec![0u32; (n * m).div_ceil(32)];
    let mut targets = vec![0u32; (n * m * bits).div_ceil(32)];
    for s in 0..n {
        let pair = s * m;
        defined[pair / 32] |= 1 << (pair % 32);
        let target = ((s + 1) % n) as u64;
        let bit = pair * bits;
        let wide = target << (bit % 32);
        targets[bit / 32] |= wide as u32;
        if (wide >> 32) != 0 {
            targets[bit / 32 + 1] |= (wide >> 32) as u32;
        }
    }
    let table = SupervisorTable {
        events: EVENTS,
        state_bits: bits as u8,
        defined: leak(defined),
        targets: leak(targets),
        rows: Rows::Dense,
    };
    for s in 0..STATES {
        assert_eq!(table.next_state(s, 0), Some((s + 1) % STATES));
        assert_eq!(table.next_state(s, 1), None);
    }
    assert_eq!(read_bits(table.targets, 0, 9), 1);
    table
}

/// The ring's table in the keyed layout: every state has the one row of
/// defined-bits `1` (a dictionary of one word, 1-bit keys), and targets
/// as sparse, which for one event defined everywhere are the dense ones.
fn ring_table_keyed() -> SupervisorTable<'static> {
    let dense = ring_table();
    let (key_bits, start_bits) = (1u8, 9u8);
    let width = usize::from(key_bits + start_bits);
    let mut records = vec![0u32; (STATES as usize * width).div_ceil(32)];
    for s in 0..STATES as usize {
        // Key 0, row start s.
        let (bit, value) = (s * width, (s as u64) << key_bits);
        let wide = value << (bit % 32);
        records[bit / 32] |= wide as u32;
        if let Some(next) = records.get_mut(bit / 32 + 1) {
            *next |= (wide >> 32) as u32;
        }
    }
    let table = SupervisorTable {
        defined: leak(vec![1]),
        rows: Rows::Keyed {
            states: leak(records),
            key_bits,
            start_bits,
        },
        ..dense
    };
    for s in 0..STATES {
        assert_eq!(table.next_state(s, 0), Some((s + 1) % STATES));
        assert_eq!(table.next_state(s, 1), None);
        assert_eq!(table.enabled(s, 0, 32), 1);
    }
    table
}

/// The ring with its keyed table ([`ring_table_keyed`]), the CRC a
/// generator would record.
pub(crate) fn ring_keyed(rom_test_bytes_per_scan: u16) -> TableProgram<'static> {
    let config = ring_config(rom_test_bytes_per_scan);
    let tables = leak(vec![ring_table_keyed()]);
    TableProgram {
        config,
        tables,
        crc: image::table_image_crc(&config, tables),
    }
}

const OUTPUTS: [OutputSpec; 1] = [OutputSpec {
    safe: false,
    initial: false,
    state_map: Span::new(0, 1),
}];
const EVENT_SPECS: [EventSpec; 1] = [EventSpec {
    trigger: Trigger::Rising(Span::new(0, 1)),
    when: Span::EMPTY,
    unless: Span::EMPTY,
    request: None,
    actions: Span::EMPTY,
    members: Span::new(0, 1),
}];

/// `step` raises the event (event_lists[0..1]); `reset` nothing.
const INPUTS: [InputSpec; 2] = [
    InputSpec {
        debounce_scans: 0,
        raises: Span::new(0, 1),
    },
    InputSpec {
        debounce_scans: 0,
        raises: Span::EMPTY,
    },
];
/// The event is local event 0 (event_lists[1..2]).
const SUPERVISORS: [SupervisorSpec; 1] = [SupervisorSpec {
    states: STATES,
    initial: 0,
    alphabet: Span::new(1, 1),
    outside: Span::EMPTY,
    allowed: AllowedSets::COMPUTED,
    contiguous: false,
}];
/// The event's binding: `step` alone.
const INPUT_MASKS: [u32; 1] = [mask_word(0, &[STEP as Index])];

fn ring_config(rom_test_bytes_per_scan: u16) -> Config<'static> {
    Config {
        name: "ring",
        scan_period_ms: 10,
        max_commands_per_scan: 1,
        unexpected: UnexpectedPolicy::Fault,
        reset: Some(RESET as Index),
        overrun_limit: 1,
        overrun_fault: false,
        lost_edge_fault: false,
        rom_test_bytes_per_scan,
        inputs: records(&INPUTS),
        debounced: &[],
        debounce_mask: Span::EMPTY,
        outputs: records(&OUTPUTS),
        timers: &[],
        events: records(&EVENT_SPECS),
        supervisors: records(&SUPERVISORS),
        input_masks: &INPUT_MASKS,
        event_lists: &[0, 0],
        event_masks: &[],
        commands: Span::EMPTY,
        requested: Span::EMPTY,
        actions: &[],
        memberships: words(&[Membership {
            supervisor: 0,
            local: 0,
        }]),
        state_map: records(&[StateMapEntry {
            supervisor: 0,
            state: 0,
            mask: u32::MAX,
        }]),
        guards: Guards::NONE,
        allowed_index: &[],
    }
}

/// The ring as a table program, with the CRC a generator would record.
pub(crate) fn ring(rom_test_bytes_per_scan: u16) -> TableProgram<'static> {
    with_config(ring_config(rom_test_bytes_per_scan))
}

/// The ring's table under `config`, with the CRC a generator would record.
fn with_config(config: Config<'static>) -> TableProgram<'static> {
    let tables = leak(vec![ring_table()]);
    TableProgram {
        config,
        tables,
        crc: image::table_image_crc(&config, tables),
    }
}

/// A program whose image can be corrupted between two scans: it runs
/// `intact` until [`Flippable::flip`], then `corrupt` (same recorded CRC).
struct Flippable {
    intact: TableProgram<'static>,
    corrupt: TableProgram<'static>,
    flipped: Cell<bool>,
}

impl Flippable {
    fn new(intact: TableProgram<'static>, corrupt: TableProgram<'static>) -> Self {
        Flippable {
            intact,
            corrupt: TableProgram {
                crc: intact.crc,
                ..corrupt
            },
            flipped: Cell::new(false),
        }
    }

    fn now(&self) -> &TableProgram<'static> {
        if self.flipped.get() {
            &self.corrupt
        } else {
            &self.intact
        }
    }

    fn flip(&self) {
        self.flipped.set(true);
    }

    fn restore(&self) {
        self.flipped.set(false);
    }
}

impl Program for Flippable {
    fn config(&self) -> Config<'_> {
        self.now().config
    }
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        self.now().next_state(supervisor, state, local)
    }
    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>> {
        self.now().table(supervisor)
    }
    fn recorded_crc(&self) -> u32 {
        self.intact.crc
    }
}

/// Which words of the ring's table to corrupt.
#[derive(Debug, Clone, Copy)]
enum Part {
    Defined,
    Targets,
}

/// `program` with bit `bit` of word `word` of a table part flipped.
fn with_table_bit_flipped(
    program: TableProgram<'static>,
    part: Part,
    word: usize,
    bit: u32,
) -> TableProgram<'static> {
    let mut table = program.tables[0];
    let words = match part {
        Part::Defined => &mut table.defined,
        Part::Targets => &mut table.targets,
    };
    let mut copy = words.to_vec();
    copy[word] ^= 1 << bit;
    *words = leak(copy);
    TableProgram {
        tables: leak(vec![table]),
        ..program
    }
}

/// The stream position of a table word: the ring's table comes last, a
/// 7-word header, `defined`, then `targets` (dense: no row starts).
fn position(program: &TableProgram<'_>, part: Part, word: usize) -> usize {
    let table = program.tables[0];
    let words = image::bytes(program) / 4;
    match part {
        Part::Defined => words - table.targets.len() - table.defined.len() + word,
        Part::Targets => words - table.targets.len() + word,
    }
}

/// 1 input word, no debounced input, 1 output, no timer, 1 supervisor,
/// 1 event in 1 word, 1 word of event set.
type Mem = StaticMemory<1, 0, 1, 0, 1, 1, 1, 1>;

/// Words per scan and scans per pass of `program`.
fn shares(program: &TableProgram<'_>) -> (usize, usize) {
    let words = usize::from(program.config.rom_test_bytes_per_scan / 4);
    (words, (image::bytes(program) / 4).div_ceil(words))
}

/// The scan in which a corruption of stream word `p`, made just before
/// scan `k`, is found: the end of the pass under way if that pass has yet
/// to read the word, else the end of the next pass.
fn predicted(p: usize, k: usize, words_per_scan: usize, pass: usize) -> usize {
    let start = k / pass * pass;
    let reads_at = start + p / words_per_scan;
    if reads_at >= k {
        start + pass - 1
    } else {
        start + 2 * pass - 1
    }
}

/// Runs scans `0..` with constant inputs until a fault or `limit` scans;
/// corrupts the image just before scan `flip_at`. The scan of the fault.
fn scan_of_fault(program: &Flippable, flip_at: usize, limit: usize) -> Option<usize> {
    let mut c = Controller::new(program, Mem::new()).unwrap();
    assert_eq!(c.fault(), None);
    for k in 0..limit {
        if k == flip_at {
            program.flip();
        }
        let r = c.scan(10 * k as u32, &[false, false]);
        if let Some(fault) = r.fault {
            assert_eq!(fault, Fault::Corrupt);
            assert!(!r.outputs[HOME_LAMP], "safe image in that scan");
            return Some(k);
        }
    }
    None
}

/// A tiny program with one item in every pool and no two fields alike.
pub(crate) fn every_pool() -> TableProgram<'static> {
    let config = Config {
        name: "abcde",
        debounce_mask: Span::new(1, 1),
        commands: Span::new(2, 1),
        requested: Span::new(3, 1),
        inputs: records(&[InputSpec {
            debounce_scans: 3,
            raises: Span::new(0, 2),
        }]),
        debounced: &[0],
        outputs: records(&[OutputSpec {
            safe: true,
            initial: false,
            state_map: Span::new(0, 1),
        }]),
        timers: records(&[TimerSpec {
            preset_ms: 500,
            raises: Span::new(2, 1),
        }]),
        events: records(&[EventSpec {
            trigger: Trigger::Rising(Span::new(0, 1)),
            when: Span::new(1, 1),
            unless: Span::EMPTY,
            request: None,
            actions: Span::new(0, 1),
            members: Span::new(0, 1),
        }]),
        supervisors: records(&[SupervisorSpec {
            states: 3,
            initial: 2,
            alphabet: Span::new(3, 1),
            outside: Span::new(0, 1),
            allowed: AllowedSets {
                index: Span::new(0, 1),
                bits: 19,
            },
            contiguous: false,
        }]),
        input_masks: &[0x11, 0x22],
        event_lists: &[5, 6, 7, 8],
        event_masks: &[0x33, 0x44, 0x55],
        actions: words(&[Action::Start(0)]),
        memberships: words(&[Membership {
            supervisor: 9,
            local: 10,
        }]),
        state_map: records(&[StateMapEntry {
            supervisor: 11,
            state: 12,
            mask: u32::MAX,
        }]),
        guards: Guards {
            events: records(&[GuardSpec {
                event: 13,
                root: 2,
                nodes: Span::new(0, 1),
            }]),
            bits: records(&[StateBit {
                component: 14,
                shift: 15,
            }]),
            nodes: records(&[GuardNode {
                bit: 16,
                low: 17,
                high: 18,
            }]),
        },
        allowed_index: &[20],
        ..ring_config(8)
    };
    let table = SupervisorTable {
        events: 2,
        state_bits: 2,
        defined: &[0x19],
        targets: &[0x09],
        rows: Rows::Sparse {
            row_starts: &[0x24],
            start_bits: 2,
        },
    };
    TableProgram {
        config,
        tables: leak(vec![table]),
        crc: 0,
    }
}

#[test]
fn the_crc_is_crc32_mpeg2_over_the_documented_words() {
    // The stream of `every_pool` written out by hand from the module docs
    // of `image`, fed to the `crc` crate as big-endian bytes.
    let program = every_pool();
    let span = |start: u32, len: u32| start | len << 16;
    #[rustfmt::skip]
    let words: Vec<u32> = vec![
        // header: name length, period, commands, unexpected, reset,
        // overrun limit and fault, lost-edge fault, ROM test share, the
        // spans debounce_mask, commands, requested
        5, 10, 1, 0, RESET as u32, 1, 0, 0, 8, span(1, 1), span(2, 1), span(3, 1),
        // pool lengths: inputs, debounced, outputs, timers, events,
        // supervisors, input masks, event lists, event masks, actions,
        // memberships, state map, guards, state bits, guard nodes;
        // allowed index; tables
        1, 1, 1, 1, 1, 1, 2, 4, 3, 1, 1, 1, 1, 1, 1, 1, 1,
        // name, four bytes a word, least significant first
        u32::from_le_bytes(*b"abcd"), u32::from_le_bytes([b'e', 0, 0, 0]),
        // the input: debounce, raises
        3, span(0, 2),
        // debounced
        0,
        // the output: safe | initial << 1, state map
        1, span(0, 1),
        // the timer: preset, raises
        500, span(2, 1),
        // the event: rising, its mask, when, unless, no request,
        // actions, members
        1, span(0, 1), span(1, 1), 0, u32::MAX, span(0, 1), span(0, 1),
        // the supervisor: states, initial, alphabet, outside, allowed
        // index and bits
        3, 2, span(3, 1), span(0, 1), span(0, 1), 19,
        // input masks, event lists, event masks
        0x11, 0x22, 5, 6, 7, 8, 0x33, 0x44, 0x55,
        // start timer 0; supervisor 9's local event 10; state map
        // (supervisor, state, mask)
        2 << 16, 9 | 10 << 16, 11, 12, u32::MAX,
        // the guard (event, root, nodes); its state bit (component |
        // shift << 16); its node (bit | low << 16, high)
        13, 2, span(0, 1), 14 | 15 << 16, 16 | 17 << 16, 18,
        // the allowed index
        20,
        // table header: events, state bits, sparse, start bits, lengths
        2, 2, 1, 2, 1, 1, 1,
        // defined, targets, row starts
        0x19, 0x09, 0x24,
    ];
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_be_bytes()).collect();
    assert_eq!(image::bytes(&program), bytes.len());
    assert_eq!(image::crc(&program), IMAGE_CRC.checksum(&bytes));
    // The algorithm's published check value.
    assert_eq!(IMAGE_CRC.checksum(b"123456789"), 0x0376_e6e7);
}

#[test]
fn every_field_of_the_configuration_and_tables_is_in_the_image() {
    // One change per field of `Config` (and of what its slices hold) and
    // per field of a table: each gives another CRC, and no two the same.
    let p = every_pool();
    let c = p.config;
    let (input, output, timer) = (c.input(0), c.output(0), c.timer(0));
    let (event, supervisor, table) = (c.event(0), c.supervisor(0), p.tables[0]);
    let other = Span::new(7, 3);
    let with = |config: Config<'static>| TableProgram { config, ..p };
    let with_table = |table: SupervisorTable<'static>| TableProgram {
        tables: leak(vec![table]),
        ..p
    };
    #[rustfmt::skip]
    let changed: Vec<(&str, TableProgram<'static>)> = vec![
        ("name", with(Config { name: "abcdf", ..c })),
        ("scan period", with(Config { scan_period_ms: 11, ..c })),
        ("commands per scan", with(Config { max_commands_per_scan: 2, ..c })),
        ("unexpected", with(Config { unexpected: UnexpectedPolicy::Ignore, ..c })),
        ("reset", with(Config { reset: None, ..c })),
        ("overrun limit", with(Config { overrun_limit: 2, ..c })),
        ("overrun fault", with(Config { overrun_fault: true, ..c })),
        ("lost-edge fault", with(Config { lost_edge_fault: true, ..c })),
        ("ROM test share", with(Config { rom_test_bytes_per_scan: 12, ..c })),
        ("debounce mask", with(Config { debounce_mask: other, ..c })),
        ("commands", with(Config { commands: other, ..c })),
        ("requested", with(Config { requested: other, ..c })),
        ("debounce", with(Config { inputs: one(InputSpec { debounce_scans: 4, ..input }), ..c })),
        ("input raises", with(Config { inputs: one(InputSpec { raises: other, ..input }), ..c })),
        ("debounced", with(Config { debounced: &[1], ..c })),
        ("safe level", with(Config { outputs: one(OutputSpec { safe: false, ..output }), ..c })),
        ("initial level", with(Config { outputs: one(OutputSpec { initial: true, ..output }), ..c })),
        ("output state map", with(Config { outputs: one(OutputSpec { state_map: other, ..output }), ..c })),
        ("preset", with(Config { timers: one(TimerSpec { preset_ms: 501, ..timer }), ..c })),
        ("timer raises", with(Config { timers: one(TimerSpec { raises: other, ..timer }), ..c })),
        ("trigger kind", with(Config { events: one(EventSpec { trigger: Trigger::Falling(Span::new(0, 1)), ..event }), ..c })),
        ("trigger mask", with(Config { events: one(EventSpec { trigger: Trigger::Rising(other), ..event }), ..c })),
        ("when", with(Config { events: one(EventSpec { when: other, ..event }), ..c })),
        ("unless", with(Config { events: one(EventSpec { unless: other, ..event }), ..c })),
        ("request", with(Config { events: one(EventSpec { request: Some(0), ..event }), ..c })),
        ("actions", with(Config { events: one(EventSpec { actions: other, ..event }), ..c })),
        ("members", with(Config { events: one(EventSpec { members: other, ..event }), ..c })),
        ("states", with(Config { supervisors: one(SupervisorSpec { states: 4, ..supervisor }), ..c })),
        ("initial state", with(Config { supervisors: one(SupervisorSpec { initial: 1, ..supervisor }), ..c })),
        ("alphabet", with(Config { supervisors: one(SupervisorSpec { alphabet: other, ..supervisor }), ..c })),
        ("outside", with(Config { supervisors: one(SupervisorSpec { outside: other, ..supervisor }), ..c })),
        ("allowed index", with(Config { supervisors: one(SupervisorSpec { allowed: AllowedSets { index: other, ..supervisor.allowed }, ..supervisor }), ..c })),
        ("allowed bits", with(Config { supervisors: one(SupervisorSpec { allowed: AllowedSets { bits: 3, ..supervisor.allowed }, ..supervisor }), ..c })),
        ("allowed index pool", with(Config { allowed_index: leak(vec![21]), ..c })),
        ("input masks", with(Config { input_masks: leak(vec![0x11, 0x23]), ..c })),
        ("event lists", with(Config { event_lists: leak(vec![5, 6, 7, 9]), ..c })),
        ("event masks", with(Config { event_masks: leak(vec![0x33, 0x44, 0x56]), ..c })),
        ("action", with(Config { actions: words(&[Action::Reset(0)]), ..c })),
        ("membership", with(Config { memberships: words(&[Membership { supervisor: 9, local: 11 }]), ..c })),
        ("state map", with(Config { state_map: one(StateMapEntry { supervisor: 11, state: 13, mask: u32::MAX }), ..c })),
        ("state map mask", with(Config { state_map: one(StateMapEntry { supervisor: 11, state: 12, mask: 14 }), ..c })),
        ("table events", with_table(SupervisorTable { events: 3, ..table })),
        ("state bits", with_table(SupervisorTable { state_bits: 3, ..table })),
        ("defined", with_table(SupervisorTable { defined: &[0x1b], ..table })),
        ("targets", with_table(SupervisorTable { targets: &[0x0b], ..table })),
        ("row starts", with_table(SupervisorTable { rows: Rows::Sparse { row_starts: &[0x25], start_bits: 2 }, ..table })),
        ("start bits", with_table(SupervisorTable { rows: Rows::Sparse { row_starts: &[0x24], start_bits: 3 }, ..table })),
        ("layout", with_table(SupervisorTable { rows: Rows::Dense, ..table })),
        ("net layout", with_table(SupervisorTable { rows: Rows::Net { fields: &[0x24] }, ..table })),
        ("keyed layout", with_table(SupervisorTable { rows: Rows::Keyed { states: &[0x24], key_bits: 2, start_bits: 0 }, ..table })),
        ("key bits", with_table(SupervisorTable { rows: Rows::Keyed { states: &[0x24], key_bits: 1, start_bits: 1 }, ..table })),
        ("keyed start bits", with_table(SupervisorTable { rows: Rows::Keyed { states: &[0x24], key_bits: 1, start_bits: 2 }, ..table })),
        ("keyed records", with_table(SupervisorTable { rows: Rows::Keyed { states: &[0x25], key_bits: 1, start_bits: 1 }, ..table })),
        ("no table", TableProgram { tables: &[], ..p }),
    ];
    let mut seen = std::collections::BTreeMap::new();
    seen.insert(image::crc(&p), "none");
    for (field, program) in &changed {
        if let Some(before) = seen.insert(image::crc(program), field) {
            panic!("changing {field} gives the CRC of changing {before}");
        }
    }
}

#[test]
fn an_intact_image_never_faults_and_passes_take_the_scans_they_should() {
    for share in [4, 12, 64, 1000, 65532] {
        let program = ring(share);
        let (_, pass) = shares(&program);
        let mut c = Controller::new(&program, Mem::new()).unwrap();
        let scans = 20 * pass + 3;
        for k in 0..scans {
            // The step input toggles: the ring turns every other scan.
            let r = c.scan(10 * k as u32, &[k % 2 == 1, false]);
            assert_eq!(r.fault, None, "share {share}, scan {k}");
        }
        let status = c.image_test();
        assert!(status.verified);
        assert_eq!(status.passes as usize, scans / pass, "share {share}");
        let words = scans % pass * usize::from(share / 4);
        assert_eq!(status.checked_bytes, 4 * words);
    }
}

/// A scan record's executed events, states, outputs and fault, owned (a
/// record borrows its controller).
fn owned(r: &crate::ScanRecord<'_>) -> (Vec<Index>, Vec<u32>, Vec<bool>, Option<Fault>) {
    (
        r.executed.to_vec(),
        r.states.to_vec(),
        r.outputs.to_vec(),
        r.fault,
    )
}

#[test]
fn the_background_test_does_not_change_the_trace() {
    // Same inputs, shares of one word and of the whole image per scan:
    // every record but the configuration's share is the same.
    let (slow, fast) = (ring(4), ring(65532));
    let mut a = Controller::new(&slow, Mem::new()).unwrap();
    let mut b = Controller::new(&fast, Mem::new()).unwrap();
    for k in 0..5000u32 {
        let inputs = [k % 3 == 0, k % 997 == 5];
        let ra = owned(&a.scan(10 * k, &inputs));
        assert_eq!(ra, owned(&b.scan(10 * k, &inputs)), "scan {k}");
    }
}

#[test]
fn a_flipped_table_bit_is_found_in_the_scan_the_bound_predicts() {
    let program = ring(16);
    let (n, pass) = shares(&program);
    assert!(pass > 20, "passes of many scans: {pass}");
    let table = program.tables[0];
    // Every word of both parts, flipped at three moments: at the start of
    // a pass, in its middle, and on its last scan.
    for (part, len) in [
        (Part::Defined, table.defined.len()),
        (Part::Targets, table.targets.len()),
    ] {
        for word in 0..len {
            let corrupt = with_table_bit_flipped(program, part, word, (word % 32) as u32);
            let p = position(&program, part, word);
            for k in [pass, pass + pass / 2, 2 * pass - 1] {
                let flippable = Flippable::new(program, corrupt);
                let expected = predicted(p, k, n, pass);
                assert_eq!(
                    scan_of_fault(&flippable, k, 4 * pass),
                    Some(expected),
                    "{part:?} word {word} (stream word {p}) flipped before scan {k}"
                );
                // The documented bound: at the latest the (2P - 1)-th scan
                // from the flip on.
                assert!(expected - k < 2 * pass - 1);
            }
        }
    }
}

#[test]
fn the_bound_is_reached_by_a_word_read_just_before_it_flips() {
    // The scan period is word 1 of the header, read in the first scan of
    // every pass. Flipped right after that scan, the pass under way ends
    // on the old value and the next one finds it: 2P - 1 scans from the
    // flip, the documented bound, exactly.
    let program = ring(16);
    let (_, pass) = shares(&program);
    let corrupt = TableProgram {
        config: Config {
            scan_period_ms: program.config.scan_period_ms ^ 0x0100,
            ..program.config
        },
        ..program
    };
    let flippable = Flippable::new(program, corrupt);
    let k = 3 * pass + 1;
    assert_eq!(
        scan_of_fault(&flippable, k, 8 * pass),
        Some(k + 2 * pass - 2)
    );
}

#[test]
fn a_flipped_configuration_byte_is_found() {
    // The high byte of the length of the event's `members` span: word 6
    // of the event, after the header (28 words), the name (1), the inputs
    // (2 × 2), no debounced input, the output (2) and no timer: stream
    // word 41.
    let program = ring(16);
    let (n, pass) = shares(&program);
    let mut event = program.config.event(0);
    event.members = Span::new(0, 1 ^ 0x80);
    let corrupt = TableProgram {
        config: Config {
            events: records(&[event]),
            ..program.config
        },
        ..program
    };
    let flippable = Flippable::new(program, corrupt);
    assert_eq!(
        scan_of_fault(&flippable, 5, 4 * pass),
        Some(predicted(41, 5, n, pass))
    );
    let flippable = Flippable::new(program, corrupt);
    assert_eq!(
        scan_of_fault(&flippable, pass + 11, 4 * pass),
        Some(predicted(41, pass + 11, n, pass))
    );
    // Stream word 41 is read in the eleventh scan of a pass (16 bytes a
    // scan): flipped after it, it is found by the next pass.
    assert_eq!(predicted(41, pass + 11, n, pass), 3 * pass - 1);
}

#[test]
fn the_start_up_check_finds_corruption_at_once() {
    let program = ring(16);
    let corrupt = with_table_bit_flipped(program, Part::Targets, 40, 7);
    let flippable = Flippable::new(program, corrupt);
    flippable.flip();
    let mut c = Controller::new(&flippable, Mem::new()).unwrap();
    assert_eq!(c.fault(), Some(Fault::Corrupt));
    assert!(!c.image_test().verified);
    let r = c.scan(0, &[false, false]);
    assert_eq!((r.fault, r.outputs), (Some(Fault::Corrupt), &[false][..]));
    assert_eq!(c.counters().faults, 1);
}

/// Scans with constant inputs from scan `from` until the pass under way
/// completes; the next scan number.
fn finish_pass<P: Program, M: crate::Memory>(c: &mut Controller<P, M>, from: u32) -> u32 {
    let passes = c.image_test().passes;
    let mut k = from;
    while c.image_test().passes == passes {
        c.scan(10 * k, &[false, false]);
        k += 1;
    }
    k
}

#[test]
fn a_reset_scan_checks_its_share_like_any_other_scan() {
    // A fault the image has no part in: a lost edge, configured as one.
    let program = with_config(Config {
        lost_edge_fault: true,
        ..ring_config(64)
    });
    let (n, pass) = shares(&program);
    let mut c = Controller::new(&program, Mem::new()).unwrap();
    c.scan(0, &[false, false]);
    c.report_lost_edge();
    assert_eq!(c.scan(10, &[false, false]).fault, Some(Fault::LostEdge));
    assert!(pass > 3);
    let before = c.image_test();
    let r = c.scan(20, &[false, true]);
    assert_eq!(r.fault, None, "the reset leaves fault mode at once");
    assert_eq!(r.outputs, [true], "the initial image");
    let after = c.image_test();
    assert_eq!(
        (after.checked_bytes - before.checked_bytes, after.passes),
        (4 * n, before.passes),
        "one share of the image, not all of it; the pass goes on"
    );
}

#[test]
fn a_reset_waits_for_a_pass_that_matches_after_a_corruption() {
    let program = ring(16);
    let (_, pass) = shares(&program);
    let corrupt = with_table_bit_flipped(program, Part::Defined, 3, 0);
    let flippable = Flippable::new(program, corrupt);
    let mut c = Controller::new(&flippable, Mem::new()).unwrap();
    flippable.flip();
    let mut k = finish_pass(&mut c, 0);
    assert_eq!(c.fault(), Some(Fault::Corrupt));
    // The corruption goes away (a transient read error): resets are
    // refused until a whole pass has matched again.
    flippable.restore();
    let r = c.scan(10 * k, &[false, true]);
    assert_eq!(r.fault, Some(Fault::Corrupt), "reset refused");
    k += 1;
    c.scan(10 * k, &[false, false]);
    k = finish_pass(&mut c, k + 1);
    assert!(c.image_test().verified);
    let r = c.scan(10 * k, &[false, true]);
    assert_eq!(r.fault, None);
    assert_eq!(r.outputs, [true]);
    assert!(k as usize <= 4 * pass);
}

#[test]
fn a_lasting_corruption_refuses_every_reset() {
    let program = ring(16);
    let (_, pass) = shares(&program);
    let corrupt = with_table_bit_flipped(program, Part::Targets, 0, 31);
    let flippable = Flippable::new(program, corrupt);
    let mut c = Controller::new(&flippable, Mem::new()).unwrap();
    flippable.flip();
    for k in 0..5 * pass as u32 {
        // The reset input toggles all the while.
        c.scan(10 * k, &[false, k % 2 == 1]);
    }
    assert_eq!(c.fault(), Some(Fault::Corrupt));
    assert!(c.image_test().passes >= 4);
    assert!(!c.image_test().verified);
}

/// A flipped RAM bit, simulated by writing the sealed state array from
/// inside the crate: the ring's state leaves its 300 states between two
/// scans.
#[test]
fn a_state_out_of_range_between_scans_is_corrupt_with_the_safe_image() {
    let program = ring(16);
    let mut c = Controller::new(&program, Mem::new()).unwrap();
    let r = c.scan(0, &[false, false]);
    assert_eq!(r.outputs, [true], "the home lamp: state 0");
    use crate::memory::sealed::Storage;
    // 511 fits the 9-bit state width and is no state.
    c.memory.ram().states[0] = 511;
    // The edge of `step` would move the ring: the range check comes first.
    let r = c.scan(10, &[true, false]);
    assert_eq!(r.fault, Some(Fault::Corrupt));
    assert!(
        r.executed.is_empty(),
        "no transition from a state that is none"
    );
    assert_eq!(r.outputs, [false], "the safe image");
    assert_eq!(c.counters().faults, 1);
    // The image itself is intact: a reset re-initialises the state.
    let r = c.scan(20, &[false, true]);
    assert_eq!(
        (r.fault, r.states, r.outputs),
        (None, &[0][..], &[true][..])
    );
}

/// A table word flipped after start-up so that a target is no state: the
/// event that would move there is refused before the state is stored,
/// long before the background pass (4 bytes a scan) reaches the word.
#[test]
fn a_table_target_out_of_range_is_corrupt_before_the_state_is_stored() {
    let program = ring(4);
    // State 0's target (entry 0, bits 0..9, value 1) becomes 511.
    let mut corrupt = program;
    for b in 1..9 {
        corrupt = with_table_bit_flipped(corrupt, Part::Targets, 0, b);
    }
    assert_eq!(corrupt.tables[0].next_state(0, 0), Some(511));
    let flippable = Flippable::new(program, corrupt);
    let mut c = Controller::new(&flippable, Mem::new()).unwrap();
    c.scan(0, &[false, false]);
    flippable.flip();
    let r = c.scan(10, &[true, false]);
    assert_eq!(r.fault, Some(Fault::Corrupt));
    assert!(r.executed.is_empty());
    assert_eq!((r.states, r.outputs), (&[0][..], &[false][..]));
    assert_eq!(c.counters().faults, 1);
    assert_eq!(c.image_test().passes, 0, "found by the scan, not the pass");
}

/// The keyed ring runs as the dense one, and what a corrupt keyed table
/// can break is refused: its sizes at start-up ([`crate::validate`]), its
/// row starts and targets by the generator's check.
#[test]
fn a_keyed_table_runs_and_its_corruptions_are_refused() {
    use crate::validate::{validate, validate_generated, Flaw, Invalid};
    let program = ring_keyed(16);
    assert_eq!(validate_generated(&program), Ok(()));
    let mut c = Controller::new(&program, Mem::new()).unwrap();
    c.scan(0, &[false, false]);
    for k in 1..5u32 {
        c.scan(20 * k, &[true, false]);
        let r = c.scan(20 * k + 10, &[false, false]);
        assert_eq!((r.fault, r.states), (None, &[k][..]), "step {k}");
    }
    let table = program.tables[0];
    let Rows::Keyed { states, .. } = table.rows else {
        unreachable!()
    };
    let rows = |records: &'static [u32], key_bits, start_bits| Rows::Keyed {
        states: records,
        key_bits,
        start_bits,
    };
    let flipped = |word: usize, mask: u32| {
        let mut copy = states.to_vec();
        copy[word] ^= mask;
        leak(copy)
    };
    let at = |flaw| {
        Err(Invalid {
            part: crate::validate::Part::Table(0),
            flaw,
        })
    };
    let with = |table: SupervisorTable<'static>| TableProgram {
        tables: leak(vec![table]),
        ..program
    };
    // Refused at start-up: sizes.
    #[rustfmt::skip]
    let sizes: Vec<(&str, SupervisorTable<'static>)> = vec![
        ("a dictionary word too many", SupervisorTable { defined: leak(vec![1, 0]), ..table }),
        ("no dictionary", SupervisorTable { defined: &[], ..table }),
        ("keys of no bits", SupervisorTable { rows: rows(states, 0, 9), ..table }),
        ("starts of no bits", SupervisorTable { rows: rows(states, 1, 0), ..table }),
        ("records wider than a word", SupervisorTable { rows: rows(states, 24, 9), ..table }),
        ("records cut short", SupervisorTable { rows: rows(leak(states[1..].to_vec()), 1, 9), ..table }),
        ("targets cut short", SupervisorTable { targets: leak(table.targets[1..].to_vec()), ..table }),
        // State 0 keyed to row 1: the dictionary has one word, one row.
        ("a key past the dictionary", SupervisorTable { rows: rows(flipped(0, 1), 1, 9), ..table }),
    ];
    for (what, table) in sizes {
        assert_eq!(validate(&with(table)), at(Flaw::TableLength), "{what}");
    }
    // Passed at start-up, refused by the generator's check: state 0 keyed
    // to row 1 of a dictionary of two (row 1 empty: no event defined, so
    // state 1's row starts one entry late); a row start off by one (state
    // 0's record, start bits 1..10); a target no state.
    let key = with(SupervisorTable {
        defined: leak(vec![1, 0]),
        rows: rows(flipped(0, 1), 1, 9),
        ..table
    });
    assert_eq!(validate(&key), Ok(()));
    assert_eq!(validate_generated(&key), at(Flaw::RowStart { state: 1 }));
    let start = with(SupervisorTable {
        rows: rows(flipped(0, 1 << 1), 1, 9),
        ..table
    });
    assert_eq!(validate(&start), Ok(()));
    assert_eq!(validate_generated(&start), at(Flaw::RowStart { state: 0 }));
    let mut far = table.targets.to_vec();
    far[0] |= 0x1ff;
    let far = with(SupervisorTable {
        targets: leak(far),
        ..table
    });
    assert_eq!(validate(&far), Ok(()));
    assert_eq!(
        validate_generated(&far),
        at(Flaw::OutOfRange {
            index: 511,
            count: STATES
        })
    );
}

/// A model of an STM32F4's CRC unit: a data register that only a reset
/// loads (with [`image::CRC_START`]) and that every written word advances,
/// one bit at a time. The register is shared with the test, which may use
/// the unit between two scans as other code on a board would.
struct ModelUnit {
    register: std::rc::Rc<Cell<u32>>,
    /// Words written to the register.
    written: std::rc::Rc<Cell<usize>>,
}

impl ModelUnit {
    fn write(&self, word: u32) {
        self.register.set(bitwise(self.register.get(), &[word]));
        self.written.set(self.written.get() + 1);
    }
}

/// The engine as a board would write it for the unit
/// ([`image::CrcEngine`]): the unit when its register holds `crc` (or
/// after a reset when `crc` is the start value), else the software
/// fallback.
impl image::CrcEngine for ModelUnit {
    fn feed(&mut self, crc: u32, words: &[u32]) -> u32 {
        if self.register.get() != crc {
            if crc != image::CRC_START {
                return image::feed_bitwise(crc, words);
            }
            self.register.set(image::CRC_START);
        }
        words.iter().for_each(|&w| self.write(w));
        self.register.get()
    }
}

/// The image CRC's algorithm one bit at a time, as the STM32 reference
/// manual describes its CRC unit: each word XORed into the register,
/// then 32 shifts, the polynomial XORed in when a 1 is shifted out.
fn bitwise(mut crc: u32, words: &[u32]) -> u32 {
    for &word in words {
        crc ^= word;
        for _ in 0..32 {
            let top = crc & 0x8000_0000 != 0;
            crc <<= 1;
            if top {
                crc ^= 0x04C1_1DB7;
            }
        }
    }
    crc
}

#[test]
fn the_unit_the_table_and_the_bitwise_fallback_agree_on_every_image_word() {
    use image::CrcEngine;
    for program in [ring(16), every_pool()] {
        let mut words = Vec::new();
        image::for_each_word(&program, |w| words.push(w));
        let whole = image::crc(&program);
        assert_eq!(bitwise(image::CRC_START, &words), whole);
        // And from every register value the stream passes through.
        let mut crc = image::CRC_START;
        for chunk in words.chunks(7) {
            let next = bitwise(crc, chunk);
            assert_eq!(image::TableCrc.feed(crc, chunk), next);
            assert_eq!(image::feed_bitwise(crc, chunk), next);
            crc = next;
        }
        assert_eq!(crc, whole);
    }
    assert_eq!(
        image::crc(&ring(16)),
        ring(16).crc,
        "the ring records its CRC"
    );
}

/// A controller whose image CRC a CRC unit computes scans as one with the
/// software CRC: the same checks, passes, verdicts and records, a flipped
/// bit found in the same scan, also when other code used the unit between
/// two scans (the engine then falls back to software for the rest of the
/// pass, and the unit takes the next pass over).
#[test]
fn a_crc_unit_checks_the_image_as_the_software_does() {
    let program = ring(16);
    let (_, pass) = shares(&program);
    let corrupt = with_table_bit_flipped(program, Part::Targets, 3, 5);
    for disturb in [None, Some(pass / 2)] {
        let software = Flippable::new(program, corrupt);
        let hardware = Flippable::new(program, corrupt);
        let register = std::rc::Rc::new(Cell::new(0x1234_5678));
        let written = std::rc::Rc::new(Cell::new(0));
        let unit = ModelUnit {
            register: register.clone(),
            written: written.clone(),
        };
        let mut a = Controller::new_proven(&software, Mem::new()).unwrap();
        let mut b = Controller::new_proven_with_crc(&hardware, Mem::new(), unit).unwrap();
        assert!(written.get() > 0, "the start-up check ran on the unit");
        let flip_at = 3 * pass + 2;
        let mut found = None;
        for k in 0..5 * pass {
            if k == flip_at {
                software.flip();
                hardware.flip();
            }
            if disturb.is_some_and(|d| k % pass == d) {
                // Another user of the unit between two scans.
                register.set(image::CRC_START);
                register.set(bitwise(image::CRC_START, &[0xdead_beef]));
            }
            let inputs = [k % 3 == 0, false];
            let ra = owned(&a.scan(10 * k as u32, &inputs));
            let fault = ra.3;
            assert_eq!(
                ra,
                owned(&b.scan(10 * k as u32, &inputs)),
                "scan {k}, disturbed {disturb:?}"
            );
            assert_eq!(a.image_test(), b.image_test(), "scan {k}");
            if found.is_none() && fault.is_some() {
                found = Some(k);
            }
        }
        let found = found.expect("the flipped bit is found");
        assert!(found >= flip_at && found < flip_at + 2 * pass, "{found}");
        // The start-up check and five passes; disturbed, the second half
        // of each pass is computed in software.
        let image_words = image::bytes(&program) / 4;
        let least = match disturb {
            None => 6 * image_words - 4,
            Some(_) => 3 * image_words,
        };
        assert!(
            written.get() >= least,
            "the unit computed the passes: {} words of {image_words}, disturbed {disturb:?}",
            written.get()
        );
        assert!(a.check_image() == b.check_image());
    }
}
