//! The body of the `fuzz_image` target, a plain function so that the
//! stable test suite runs it too (`crates/codegen/tests/corrupt_image.rs`
//! includes this file).
//!
//! A real generated program image (a seed project as the table backend
//! lays it out) is corrupted as the input says (fields, indices and spans
//! rewritten, table words flipped, pools cut short or grown, the CRC left
//! alone or recomputed to match), then run through a sequence of scans at
//! times and with raw input images the input chooses, on two controllers
//! side by side. What must hold, whatever the input:
//!
//! - nothing panics;
//! - an image that fails the structure check or its CRC starts in fault
//!   mode `Corrupt` and stays there on every scan, every output at its safe
//!   level, nothing executed, one fault counted;
//! - an image that passes both starts without a fault, and every scan
//!   writes one level per output (the safe image whenever it ends in fault
//!   mode) and leaves every supervisor in a state of its own, having
//!   executed only events that exist;
//! - the two controllers, fed the same, record the same scans.

use arbitrary::{Result, Unstructured};
use codegen::lower::TableImage;
use executor::memory::HeapMemory;
use executor::pacing::Pacer;
use executor::program::{Index, Program, Span};
use executor::validate::validate;
use executor::{Config, Controller, Fault, ScanRecord};
use std::path::Path;

/// The seed projects (under `models/`): sensors and Moore outputs (press),
/// commands with request inputs and two supervisors (crane), a timer and
/// actions (conveyor), eight supervisors, switches and timers (boiler), a
/// Petri net in the net layout with place maps (mixers).
pub const SEED_PROJECTS: [&str; 5] = [
    "press.plc.toml",
    "crane.plc.toml",
    "conveyor.plc.toml",
    "boiler/boiler.plc.toml",
    "petri/mixers.plc.toml",
];

/// The table images of [`SEED_PROJECTS`], `models` being the repository's
/// `models/` directory.
pub fn seed_images(models: &Path) -> Vec<TableImage> {
    SEED_PROJECTS
        .iter()
        .map(|name| {
            let project = plc_project::load(&models.join(name))
                .unwrap_or_else(|e| panic!("seed project {name}: {e}"));
            TableImage::new(&project).unwrap_or_else(|e| panic!("seed project {name}: {e}"))
        })
        .collect()
}

/// How many kinds of [`Mutation`] there are (its `field`).
pub const FIELDS: u8 = 31;

/// One field of an image rewritten to `value` (`item` picks the item of a
/// list or pool, modulo its length; an empty one is left alone).
#[derive(Debug, Clone, Copy)]
pub struct Mutation {
    /// Which field, `0..FIELDS` (see [`apply`]).
    pub field: u8,
    /// Which item of the list or pool.
    pub item: usize,
    /// The new value, or what decides it.
    pub value: u32,
}

/// A span of the low and high halves of `v`.
fn span(v: u32) -> Span {
    Span::new(v as u16, (v >> 16) as u16)
}

/// The `k`-th item of `items` (modulo its length), if it has any.
fn at<T>(items: &mut [T], k: usize) -> Option<&mut T> {
    let n = items.len();
    (n != 0).then(|| &mut items[k % n])
}

/// Cuts `items` short (even `v`) or appends a copy of one of its items
/// (odd `v`).
fn resize<T: Clone>(items: &mut Vec<T>, v: u32) {
    let n = items.len();
    let k = (v >> 1) as usize;
    if v % 2 == 0 {
        items.truncate(k % (n + 1));
    } else if n != 0 {
        items.push(items[k % n].clone());
    }
}

/// Applies `m` to `image` (not its CRC).
pub fn apply(image: &mut TableImage, m: Mutation) {
    use executor::program::{Action, Membership, Trigger, UnexpectedPolicy};
    let (v, k, p) = (m.value, m.item, &mut image.pools);
    let small = v as Index;
    match m.field % FIELDS {
        0 => at(&mut p.inputs, k).map(|x| x.raises = span(v)),
        1 => at(&mut p.debounced, k).map(|x| *x = small),
        2 => at(&mut p.outputs, k).map(|x| x.state_map = span(v)),
        3 => at(&mut p.timers, k).map(|x| x.raises = span(v)),
        4 => at(&mut p.timers, k).map(|x| x.preset_ms = v),
        5 => at(&mut p.events, k).map(|x| {
            x.trigger = match v % 4 {
                0 => Trigger::Command,
                1 => Trigger::Rising(span(v >> 2)),
                2 => Trigger::Falling(span(v >> 2)),
                _ => Trigger::Expired((v >> 2) as Index),
            }
        }),
        6 => at(&mut p.events, k).map(|x| x.when = span(v)),
        7 => at(&mut p.events, k).map(|x| x.unless = span(v)),
        8 => at(&mut p.events, k).map(|x| x.request = Some(small)),
        9 => at(&mut p.events, k).map(|x| x.actions = span(v)),
        10 => at(&mut p.events, k).map(|x| x.members = span(v)),
        11 => at(&mut p.supervisors, k).map(|x| x.states = v),
        12 => at(&mut p.supervisors, k).map(|x| x.initial = v),
        13 => at(&mut p.supervisors, k).map(|x| x.alphabet = span(v)),
        14 => at(&mut p.supervisors, k).map(|x| x.outside = span(v)),
        15 => at(&mut p.input_masks, k).map(|x| *x = v),
        16 => at(&mut p.event_lists, k).map(|x| *x = small),
        17 => at(&mut p.event_masks, k).map(|x| *x = v),
        18 => {
            p.commands = span(v);
            Some(())
        }
        19 => {
            p.requested = span(v);
            Some(())
        }
        20 => at(&mut p.actions, k).map(|x| {
            let i = (v >> 2) as Index;
            *x = [
                Action::Set(i),
                Action::Clear(i),
                Action::Start(i),
                Action::Reset(i),
            ][v as usize % 4]
        }),
        21 => at(&mut p.memberships, k).map(|x| {
            *x = Membership {
                supervisor: (v >> 16) as Index,
                local: small,
            }
        }),
        22 => at(&mut p.state_map, k).map(|x| x.state = v),
        23 => {
            p.reset = Some(small);
            Some(())
        }
        24 => at(&mut image.tables, k).and_then(|t| {
            let words = if v % 2 == 0 {
                &mut t.defined
            } else {
                &mut t.targets
            };
            at(words, (v >> 1) as usize).map(|w| *w ^= 1 << (v % 32))
        }),
        25 => at(&mut image.tables, k).map(|t| {
            t.events = small;
            t.state_bits = (v >> 16) as u8;
        }),
        // The scalars of the configuration.
        26 => {
            match k % 7 {
                0 => p.scan_period_ms = v,
                1 => p.overrun_limit = small,
                2 => p.max_commands_per_scan = small,
                3 => p.rom_test_bytes_per_scan = small,
                4 => p.debounce_mask = span(v),
                5 => {
                    p.overrun_fault = v & 1 != 0;
                    p.lost_edge_fault = v & 2 != 0;
                }
                _ => {
                    p.unexpected = if v % 2 == 0 {
                        UnexpectedPolicy::Fault
                    } else {
                        UnexpectedPolicy::Ignore
                    }
                }
            }
            Some(())
        }
        // A supervisor's stored allowed sets: their index span, the width
        // of an entry, a word of the index.
        27 => at(&mut p.supervisors, k).map(|x| x.allowed.index = span(v)),
        28 => at(&mut p.supervisors, k).map(|x| x.allowed.bits = v as u8),
        29 => at(&mut p.allowed_index, k).map(|x| *x ^= 1 << (v % 32)),
        // A list or pool cut short or grown by a copy of one of its items.
        _ => {
            match k % 14 {
                0 => resize(&mut p.inputs, v),
                1 => resize(&mut p.debounced, v),
                2 => resize(&mut p.outputs, v),
                3 => resize(&mut p.timers, v),
                4 => resize(&mut p.events, v),
                5 => resize(&mut p.supervisors, v),
                6 => resize(&mut p.input_masks, v),
                7 => resize(&mut p.event_lists, v),
                8 => resize(&mut p.event_masks, v),
                9 => resize(&mut p.actions, v),
                10 => resize(&mut p.memberships, v),
                11 => resize(&mut p.state_map, v),
                12 => resize(&mut p.allowed_index, v),
                _ => resize(&mut image.tables, v),
            }
            Some(())
        }
    };
    // The image holds the pools' records: written anew from the changed
    // typed pools.
    image.pools.refresh();
}

/// A value near the sizes of a small project half the time, any value the
/// other half.
fn value(u: &mut Unstructured<'_>) -> Result<u32> {
    if u.arbitrary()? {
        u.int_in_range(0..=15)
    } else {
        u.arbitrary()
    }
}

fn mutation(u: &mut Unstructured<'_>) -> Result<Mutation> {
    Ok(Mutation {
        field: u.int_in_range(0..=FIELDS - 1)?,
        item: u.int_in_range(0..=255)?,
        value: value(u)?,
    })
}

/// Scans per input at most: enough for debouncing, timers and a reset.
const MAX_STEPS: usize = 96;

/// Runs `data` against one of `images` (see the module docs); panics when
/// anything that must hold does not.
pub fn run_image(images: &[TableImage], data: &[u8]) {
    // An input too short to say what to do is simply done.
    let _ = run(images, &mut Unstructured::new(data));
}

fn run(images: &[TableImage], u: &mut Unstructured<'_>) -> Result<()> {
    let mut image = images[u.choose_index(images.len())?].clone();
    for _ in 0..u.int_in_range(0..=4)? {
        apply(&mut image, mutation(u)?);
    }
    if u.arbitrary()? {
        image.crc = image.computed_crc();
    }
    let corrupt = validate(&image).is_err() || image.computed_crc() != image.crc;
    let config = image.config();
    let safe: Vec<bool> = config.output_specs().map(|o| o.safe).collect();
    let controller = || {
        Controller::new(&image, HeapMemory::for_config(&config))
            .expect("memory sized for its configuration fits it")
    };
    let (mut a, mut b) = (controller(), controller());
    let expected = corrupt.then_some(Fault::Corrupt);
    assert_eq!(a.fault(), expected, "the start-up check");
    // One scan schedule per controller, built from the image whatever it
    // holds, as the board builds it.
    let [mut pa, mut pb] = [Pacer::for_config(&config, 0); 2];
    let mut now = 0u32;
    for _ in 0..MAX_STEPS {
        if u.is_empty() {
            break;
        }
        now = now.wrapping_add(if u.arbitrary()? {
            u.int_in_range(0..=2 * config.scan_period_ms.min(1 << 20))?
        } else {
            u.arbitrary()?
        });
        let step = u.int_in_range(0..=7)?;
        let record = match step {
            0..=3 => {
                let n = u.int_in_range(0..=config.inputs.len() + 2)?;
                let raw: Vec<bool> = (0..n).map(|_| u.arbitrary()).collect::<Result<_>>()?;
                b.scan(now, &raw);
                a.scan(now, &raw)
            }
            4 => {
                let n = u.int_in_range(0..=config.inputs.len().div_ceil(32) + 1)?;
                let raw: Vec<u32> = (0..n).map(|_| u.arbitrary()).collect::<Result<_>>()?;
                b.scan_packed(now, &raw);
                a.scan_packed(now, &raw)
            }
            5 => {
                let start = a.scan_due(&mut pa, now);
                assert_eq!(b.scan_due(&mut pb, now), start, "the same schedule");
                match start {
                    Some(start) => {
                        b.scan(start.time_ms, &[]);
                        a.scan(start.time_ms, &[])
                    }
                    None => continue,
                }
            }
            6 => {
                a.report_overrun();
                b.report_overrun();
                a.report_lost_edge();
                b.report_lost_edge();
                continue;
            }
            _ => {
                let intact = a.check_image();
                assert_eq!(b.check_image(), intact);
                assert_eq!(intact, image.computed_crc() == image.crc);
                continue;
            }
        };
        check_scan(&config, &record, &safe, expected);
        assert_eq!(record, b.record(), "the same scan on the twin controller");
    }
    if corrupt {
        assert_eq!(a.fault(), Some(Fault::Corrupt));
        assert_eq!(a.counters().faults, 1, "one fault, however long it lasts");
    }
    Ok(())
}

/// What every scan record must show; `corrupt` is `Some(Fault::Corrupt)`
/// for an image that failed its checks.
fn check_scan(config: &Config<'_>, r: &ScanRecord<'_>, safe: &[bool], corrupt: Option<Fault>) {
    assert_eq!(
        r.outputs.len(),
        config.outputs.len(),
        "one level per output"
    );
    assert_eq!(r.states.len(), config.supervisors.len());
    if corrupt.is_some() {
        assert_eq!(r.fault, corrupt, "a corrupt image stays in fault mode");
        assert!(r.executed.is_empty() && r.unexpected.is_empty());
    }
    match r.fault {
        Some(_) => assert_eq!(r.outputs, safe, "fault mode writes the safe image"),
        None => {
            for (x, spec) in r.states.iter().zip(config.supervisor_specs()) {
                assert!(*x < spec.states, "state {x} of {}", spec.states);
            }
        }
    }
    for &e in r.executed.iter().chain(r.unexpected) {
        assert!(usize::from(e) < config.events.len(), "event {e}");
    }
}
