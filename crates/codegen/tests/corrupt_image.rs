//! A real generated program image, corrupted: the stamping press
//! (`models/press.plc.toml`) as the table backend lays it out. Whatever is
//! corrupted (a table word under the recorded CRC, or an index, span or
//! size rewritten with the CRC recomputed to match so that only the
//! structure check can tell), the controller runs in fault mode `Corrupt`:
//! the safe output image, one fault counted, no panic whatever the inputs,
//! and no reset out of it.

use codegen::lower::{ImageCheck, LogicImage, TableImage};
use executor::memory::HeapMemory;
use executor::program::{Index, Program, Span};
use executor::table::SupervisorTable;
use executor::validate::{validate, validate_generated, Flaw, Invalid, Part};
use executor::{Config, Controller, Fault};
use plc_project as project;
use proptest::prelude::*;
use std::cell::Cell;
use std::path::Path;

/// Inputs of the press, in declaration order.
const AUTO_PB: usize = 0;
const RESET_PB: usize = 2;
const TOP_LS: usize = 4;
const INPUTS: usize = 6;
/// Its outputs: `auto_lamp` is on in states 2, 3, 4 and 6; every output's
/// safe level is 0.
const AUTO_LAMP: usize = 0;
const SAFE: [bool; 4] = [false; 4];
/// The lesson's state 2 ("armed"): index 1.
const ARMED: u32 = 1;

fn model(name: &str) -> project::Project {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(name);
    project::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn press() -> TableImage {
    let image = TableImage::new(&model("press.plc.toml")).unwrap();
    assert_eq!(
        image.pools.reset,
        Some(RESET_PB as Index),
        "the input edges of `stays_corrupt` press reset too"
    );
    image
}

/// The raw input image with `on` at 1.
fn inputs(on: &[usize]) -> [bool; INPUTS] {
    let mut raw = [false; INPUTS];
    for &i in on {
        raw[i] = true;
    }
    raw
}

/// The press armed: `auto` pressed with the ram at the top.
fn armed<P: Program>(program: P) -> Controller<P, HeapMemory> {
    let memory = HeapMemory::for_config(&program.config());
    let mut c = Controller::new(program, memory).unwrap();
    c.scan(0, &inputs(&[TOP_LS]));
    let r = c.scan(10, &inputs(&[TOP_LS, AUTO_PB]));
    assert_eq!((r.fault, r.states), (None, &[ARMED][..]));
    assert!(r.outputs[AUTO_LAMP], "the auto lamp is on while armed");
    c
}

/// `c` is in fault mode `Corrupt` with the safe image, one fault counted,
/// and stays there through every input edge (each input rising and
/// falling in turn, the reset input among them) without a panic.
fn stays_corrupt<P: Program>(c: &mut Controller<P, HeapMemory>, mut now: u32) {
    assert_eq!(c.fault(), Some(Fault::Corrupt));
    for i in 0..INPUTS {
        for level in [true, false] {
            now += 10;
            let on: Vec<usize> = if level { vec![i, TOP_LS] } else { vec![TOP_LS] };
            let r = c.scan(now, &inputs(&on));
            assert_eq!(r.fault, Some(Fault::Corrupt), "input {i} at {level}");
            assert_eq!(r.outputs, SAFE, "the safe image");
            assert!(r.executed.is_empty());
        }
    }
    assert_eq!(c.counters().faults, 1, "one fault, however long it lasts");
}

#[test]
fn every_generated_image_of_the_seed_projects_is_well_formed() {
    for name in [
        "press.plc.toml",
        "press7.plc.toml",
        "crane.plc.toml",
        "conveyor.plc.toml",
        "motivating.plc.toml",
    ] {
        let project = model(name);
        assert_eq!(
            validate(&TableImage::new(&project).unwrap()),
            Ok(()),
            "{name}"
        );
        assert_eq!(
            validate(&LogicImage::new(&project).unwrap()),
            Ok(()),
            "{name}"
        );
    }
}

#[test]
fn a_flipped_table_word_is_corrupt_from_start_up_and_no_reset_clears_it() {
    let mut image = press();
    image.tables[0].targets[0] ^= 1 << 4;
    let memory = HeapMemory::for_config(&image.config());
    let mut c = Controller::new(&image, memory).unwrap();
    assert_eq!(c.counters().faults, 1);
    c.scan(0, &inputs(&[TOP_LS]));
    stays_corrupt(&mut c, 0);
}

/// A program whose table words can be swapped for corrupted ones between
/// two scans (the flash cell that flips while the controller runs).
struct Flippable {
    intact: TableImage,
    corrupt: TableImage,
    flipped: Cell<bool>,
}

impl Flippable {
    fn now(&self) -> &TableImage {
        if self.flipped.get() {
            &self.corrupt
        } else {
            &self.intact
        }
    }
}

impl Program for Flippable {
    fn config(&self) -> Config<'_> {
        self.now().config()
    }
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        self.now().next_state(supervisor, state, local)
    }
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        self.now().enabled(supervisor, state, from, len)
    }
    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>> {
        self.now().table(supervisor)
    }
    fn recorded_crc(&self) -> u32 {
        self.intact.crc
    }
}

#[test]
fn a_table_word_flipped_while_running_is_found_by_the_background_pass() {
    let intact = press();
    let mut corrupt = intact.clone();
    let last = corrupt.tables[0].defined.len() - 1;
    corrupt.tables[0].defined[last] ^= 1 << 3;
    let bound = ImageCheck::of(&intact).bound_scans();
    let program = Flippable {
        intact,
        corrupt,
        flipped: Cell::new(false),
    };
    let mut c = armed(&program);
    program.flipped.set(true);
    let mut now = 10;
    let mut scans = 0;
    while c.fault().is_none() {
        assert!(scans < bound, "found within the bound of {bound} scans");
        now += 10;
        scans += 1;
        c.scan(now, &inputs(&[TOP_LS]));
    }
    assert_eq!(
        c.record().outputs,
        SAFE,
        "the scan that finds it writes the safe image"
    );
    stays_corrupt(&mut c, now);
}

/// The press with `corrupt` applied and its CRC recomputed: only the
/// structure check can find what is wrong.
fn rewritten(corrupt: impl FnOnce(&mut TableImage)) -> TableImage {
    let mut image = press();
    corrupt(&mut image);
    image.pools.refresh();
    image.crc = image.computed_crc();
    image
}

#[test]
fn an_image_with_a_matching_crc_but_a_broken_structure_is_corrupt_from_start_up() {
    let at = |part, flaw| Err(Invalid { part, flaw });
    let out_of_range = |index, count| Flaw::OutOfRange { index, count };
    let cases: Vec<(&str, TableImage, Result<(), Invalid>)> = vec![
        (
            "a membership's local event past its supervisor's alphabet",
            rewritten(|p| p.pools.memberships[3].local = 99),
            at(Part::Membership(3), out_of_range(99, 7)),
        ),
        (
            "a membership naming a supervisor that does not exist",
            rewritten(|p| p.pools.memberships[0].supervisor = 1),
            at(Part::Membership(0), out_of_range(1, 1)),
        ),
        (
            "an event's actions past the end of the pool",
            rewritten(|p| p.pools.events[0].actions = Span::new(p.pools.actions.len() as u16, 2)),
            at(Part::Event(0), Flaw::SpanPastPool),
        ),
        (
            "an input raising an event that does not exist",
            rewritten(|p| {
                let span = p.pools.inputs[AUTO_PB].raises;
                p.pools.event_lists[usize::from(span.start)] = 7;
            }),
            at(Part::Input(AUTO_PB), out_of_range(7, 7)),
        ),
        (
            "a Moore output mapped to a state out of range",
            rewritten(|p| p.pools.state_map[0].state = 6),
            at(Part::StateMap(0), out_of_range(6, 6)),
        ),
        (
            "an initial state out of range",
            rewritten(|p| p.pools.supervisors[0].initial = 6),
            at(Part::Supervisor(0), out_of_range(6, 6)),
        ),
        (
            "a scan period of 0 (found by the fuzz_image target: the board's pacer panicked)",
            rewritten(|p| p.pools.scan_period_ms = 0),
            at(Part::ScanPeriod, Flaw::Period),
        ),
        (
            "the reset input out of range",
            rewritten(|p| p.pools.reset = Some(INPUTS as Index)),
            at(Part::Reset, out_of_range(INPUTS as u32, INPUTS as u32)),
        ),
        (
            "a table with fewer local events than the alphabet",
            rewritten(|p| p.tables[0].events -= 1),
            at(Part::Table(0), Flaw::TableEvents),
        ),
        (
            "a table cut short",
            rewritten(|p| {
                p.tables[0].targets.pop();
            }),
            at(Part::Table(0), Flaw::TableLength),
        ),
    ];
    for (what, image, flaw) in &cases {
        assert_eq!(image.computed_crc(), image.crc, "{what}: the CRC matches");
        assert_eq!(validate(image), *flaw, "{what}");
        let memory = HeapMemory::for_config(&image.config());
        let mut c = Controller::new(image, memory).unwrap();
        assert_eq!(c.fault(), Some(Fault::Corrupt), "{what}");
        assert!(c.check_image(), "{what}: the CRC alone would pass it");
        c.scan(0, &inputs(&[TOP_LS]));
        stays_corrupt(&mut c, 0);
    }
}

#[test]
fn what_generation_proves_is_refused_by_the_host_check_and_caught_by_the_scan() {
    // Pools that disagree, a table entry that is no state: indices in
    // range, so the controller's own check passes them; generation and
    // host tools refuse them (`validate_generated`).
    let swapped = rewritten(|p| p.pools.memberships.swap(0, 1));
    assert_eq!(validate(&swapped), Ok(()));
    assert_eq!(
        validate_generated(&swapped),
        Err(Invalid {
            part: Part::Supervisor(0),
            flaw: Flaw::Membership
        })
    );
    // An alphabet marked consecutive that is not: the scan would shift
    // the enabled row onto the wrong events.
    let unordered = rewritten(|p| {
        let sup = &mut p.pools.supervisors[0];
        sup.contiguous = true;
        let start = usize::from(sup.alphabet.start);
        p.pools.event_lists.swap(start, start + 1);
    });
    assert_eq!(validate(&unordered), Ok(()));
    assert_eq!(
        validate_generated(&unordered),
        Err(Invalid {
            part: Part::Supervisor(0),
            flaw: Flaw::Contiguous
        })
    );
    // 3 bits hold 7, the press has 6 states: the entry of state 0 on
    // `auto`, the first move of `armed`.
    let far = rewritten(|p| p.tables[0].targets[0] |= 0b111);
    assert_eq!(validate(&far), Ok(()));
    assert_eq!(
        validate_generated(&far),
        Err(Invalid {
            part: Part::Table(0),
            flaw: Flaw::OutOfRange { index: 7, count: 6 }
        })
    );
    // The scan checks the state it moves to: the move is a `Corrupt`
    // fault, never a state out of range (the image passed its checks, so
    // a reset leaves it, and the same move faults again).
    let memory = HeapMemory::for_config(&far.config());
    let mut c = Controller::new(&far, memory).unwrap();
    assert_eq!(c.fault(), None);
    c.scan(0, &inputs(&[TOP_LS]));
    let r = c.scan(10, &inputs(&[TOP_LS, AUTO_PB]));
    assert_eq!((r.fault, r.states), (Some(Fault::Corrupt), &[0][..]));
    assert_eq!(r.outputs, SAFE);
}

/// The mixers of seed D (`models/petri/mixers.plc.toml`, one net group of
/// ten 1-bit counters) with `corrupt` applied and its CRC recomputed.
fn mixers_rewritten(corrupt: impl FnOnce(&mut TableImage)) -> TableImage {
    let mut image = TableImage::new(&model("petri/mixers.plc.toml")).unwrap();
    assert_eq!(validate(&image), Ok(()), "the intact net image");
    corrupt(&mut image);
    image.pools.refresh();
    image.crc = image.computed_crc();
    image
}

#[test]
fn a_net_image_with_a_matching_crc_but_a_broken_structure_is_corrupt_from_start_up() {
    let at = |part, flaw| Err(Invalid { part, flaw });
    let cases: Vec<(&str, TableImage, Result<(), Invalid>)> = vec![
        (
            "two counters sharing a bit",
            mixers_rewritten(|p| p.tables[0].row_starts[1] = 0b11),
            at(Part::Table(0), Flaw::Fields),
        ),
        (
            "a counter whose bits are not contiguous",
            mixers_rewritten(|p| p.tables[0].row_starts[1] = 0b1010),
            at(Part::Table(0), Flaw::Fields),
        ),
        (
            "a counter left out (a bit of the state in no field)",
            mixers_rewritten(|p| {
                p.tables[0].row_starts.pop();
            }),
            at(Part::Table(0), Flaw::Fields),
        ),
        (
            "a state width that does not match the states",
            mixers_rewritten(|p| p.tables[0].state_bits = 11),
            at(Part::Table(0), Flaw::StateBits),
        ),
        (
            "a PRE word with a bit past the fields",
            mixers_rewritten(|p| p.tables[0].defined[2] |= 1 << 12),
            at(Part::Table(0), Flaw::Arcs { local: 2 }),
        ),
        (
            "a POST word missing",
            mixers_rewritten(|p| {
                p.tables[0].targets.pop();
            }),
            at(Part::Table(0), Flaw::TableLength),
        ),
        (
            "a place map entry with bits outside its mask",
            mixers_rewritten(|p| p.pools.state_map[0].state |= 1),
            at(Part::StateMap(0), Flaw::StateMask),
        ),
    ];
    for (what, image, flaw) in &cases {
        assert_eq!(validate(image), *flaw, "{what}");
        let mut c = Controller::new(image, HeapMemory::for_config(&image.config())).unwrap();
        assert_eq!(c.fault(), Some(Fault::Corrupt), "{what}");
        let r = c.scan(0, &[true; 8]);
        assert!(r.outputs.iter().all(|&o| !o), "{what}: the safe image");
        assert!(r.executed.is_empty(), "{what}");
    }
}

/// The body of the `fuzz_image` target (`crates/executor/fuzz`): an image
/// corrupted as its input says (under the old CRC or a recomputed one),
/// then scans at times and with raw inputs the input chooses.
#[path = "../../executor/fuzz/src/lib.rs"]
mod fuzz_image;

/// The intact images the fuzz body corrupts.
fn seeds() -> &'static [TableImage] {
    static SEEDS: std::sync::OnceLock<Vec<TableImage>> = std::sync::OnceLock::new();
    SEEDS.get_or_init(|| {
        fuzz_image::seed_images(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models"))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// Whatever is rewritten: no panic; an image that fails either check
    /// runs in fault mode `Corrupt` with the safe image on every scan; an
    /// image that passes both never holds a state out of range, writes the
    /// safe image whenever it is in fault mode, and runs the same twice.
    #[test]
    fn no_corruption_of_an_image_panics_the_controller(
        input in proptest::collection::vec(any::<u8>(), 0..400),
    ) {
        fuzz_image::run_image(seeds(), &input);
    }
}
