//! QEMU field-update harness (mps2-an386, Cortex-M4): program images
//! loaded over a simulated serial link into two slots while the PLC
//! scans, switched in, refused, and rolled back at start-up.
//!
//! The built-in program is `PLC_PROJECT` (the press), the image loaded
//! is `PLC_UPDATE_IMAGE` (a slot file of `codegen image`, the press with
//! the lesson's state 7), and each program replays its recorded scenario
//! (`PLC_SCENARIO`, `PLC_UPDATE_SCENARIO`) while it runs: every record
//! must equal host-sim's. The PC's end of the link runs here too: it
//! sends each request as the `codegen load` command does (the same frame
//! encoder), [`BYTES_PER_SCAN`] bytes per scan, and waits for the answer
//! before the next one. The slots are RAM with NOR flash's rules
//! ([`RamSlots`]); a switched-in program runs from a RAM copy of its
//! slot (a board runs it from its flash slot in place).
//!
//! The transcript, in order:
//!
//! 1. start-up with both slots erased: the built-in program runs;
//! 2. while it replays its scenario: `Status`, an image whose words were
//!    damaged after its CRC was recorded (refused: image CRC), an image
//!    damaged with its CRC recomputed over the damage (refused by the
//!    structure check); every scan still matches;
//! 3. the update: loaded into slot A, checked in shares per scan, then
//!    switched in: the next scan runs it, and it replays its own scenario;
//! 4. the built-in image loaded again as version 1.2.0: slot B, switched;
//! 5. restarts: slot B chosen; B damaged, A chosen (rollback); A damaged
//!    too, the built-in program (rollback); each runs its scenario.
//!
//! Exit code 0 only when every step gives what it should. The last line
//! is `update: loads=L switched=S refused=R rollbacks=B mismatches=M
//! switch_instr=X poll_max=P check_scans=C failures=F` (F: the steps that
//! did not give what they should).

#![no_std]
#![no_main]

mod pc;
mod phase;

use pc::{Answer, Job, BYTES_PER_SCAN};
use phase::{phase, run_slot, Plc};

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln};
use crc::Crc;
use executor::{Controller, Program};
use field_update::header::{version, version_parts, SlotHeader, HEADER_WORDS};
use field_update::loader::{Endpoint, Loader, Running};
use field_update::protocol::Refusal;
use field_update::slot::{choose, image_of, Choice, RamSlots, Rejected, Slot};
use field_update::{crc_of_words, CRC_ALGORITHM};
use firmware::icount::{exit, finish, start};
use firmware::program;
use firmware::update::ImageCheck;
use panic_semihosting as _;

/// The built-in program's scenario, recorded by `host-sim record`.
static SCENARIO: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/scenario.bin"));
/// The loaded program's scenario.
static UPDATE_SCENARIO: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/update-scenario.bin"));
/// The slot file the PC loads (`codegen image`).
static UPDATE_FILE: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/update.slot"));

/// Slot headers, images and frames.
static CRC: Crc<u32> = Crc::<u32>::new(&CRC_ALGORITHM);

/// Words per slot, header included (16 KiB).
const SLOT_WORDS: usize = 4096;

fn fail(message: &str) -> ! {
    hprintln!("error: {}", message);
    exit(debug::EXIT_FAILURE)
}

/// The tally of the transcript.
struct Tally {
    failures: u32,
    mismatches: u32,
}

impl Tally {
    fn expect(&mut self, ok: bool, what: &str) {
        hprintln!("  [{}] {}", if ok { "ok" } else { "FAIL" }, what);
        if !ok {
            self.failures += 1;
        }
    }
}

fn name_is(answer: &Option<Answer>, want: &str, slot: Option<Slot>, ver: u32, crc: u32) -> bool {
    match answer {
        Some(Answer::Status {
            name,
            len,
            slot: s,
            version: v,
            image_crc,
        }) => &name[..*len] == want.as_bytes() && *s == slot && *v == ver && *image_crc == crc,
        _ => false,
    }
}

fn describe(choice: &Choice) {
    match choice.running {
        Some(v) => {
            let (major, minor, patch) = version_parts(v.header.version);
            hprintln!(
                "  start-up: slot {:?} runs (sequence {}, version {}.{}.{}, image CRC {:#010x}); passed over: A {:?}, B {:?}",
                v.slot,
                v.header.sequence,
                major,
                minor,
                patch,
                v.header.image_crc,
                choice.rejected[0],
                choice.rejected[1]
            );
        }
        None => hprintln!(
            "  start-up: the built-in program runs; passed over: A {:?}, B {:?}",
            choice.rejected[0],
            choice.rejected[1]
        ),
    }
}

/// Prints the PC's answers.
fn show(answers: &[Option<Answer>]) {
    for answer in answers.iter().flatten() {
        match answer {
            Answer::Status {
                name,
                len,
                slot,
                version,
                image_crc,
            } => {
                let (major, minor, patch) = version_parts(*version);
                hprintln!(
                    "  PC <- Status: {} in {:?}, version {}.{}.{}, image CRC {:#010x}",
                    core::str::from_utf8(&name[..*len]).unwrap_or("?"),
                    slot,
                    major,
                    minor,
                    patch,
                    image_crc
                );
            }
            other => hprintln!("  PC <- {:?}", other),
        }
    }
}

/// `image` with word `at` changed by `xor`.
fn damaged(image: &[u32], at: usize, xor: u32, into: &mut [u32]) -> usize {
    let n = image.len();
    into[..n].copy_from_slice(image);
    into[at] ^= xor;
    n
}

#[entry]
fn main() -> ! {
    let Some(mut core) = cortex_m::Peripherals::take() else {
        fail("core peripherals taken twice");
    };
    let overhead = start(&mut core.SYST);

    let built_in = &program::PROGRAM;
    let config = built_in.config();
    let built_in_crc = built_in.recorded_crc();
    let wiring = program::board::WIRING;
    let check = ImageCheck::new(&config, wiring);

    // The PC's files: the update's slot file, and the built-in image.
    let mut file_words = [0u32; SLOT_WORDS];
    if UPDATE_FILE.len() % 4 != 0 || UPDATE_FILE.len() / 4 > SLOT_WORDS {
        fail("the update's slot file is not whole words or too long");
    }
    for (word, bytes) in file_words.iter_mut().zip(UPDATE_FILE.chunks_exact(4)) {
        *word = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
    }
    let Ok(file_header) = SlotHeader::read(&file_words, &CRC) else {
        fail("the update's slot file has no valid header");
    };
    let update = image_of(&file_words, &file_header);
    let update_crc = file_header.image_crc;
    let mut own = [0u32; SLOT_WORDS];
    let mut own_len = 0;
    executor::image::for_each_word(built_in, |w| {
        if let Some(slot) = own.get_mut(own_len) {
            *slot = w;
        }
        own_len += 1;
    });
    if own_len > SLOT_WORDS {
        fail("the built-in image does not fit a slot");
    }
    let own = &own[..own_len];

    // The damaged images: a word flipped after the CRC was recorded, and
    // the first word whose flip the structure check refuses, its CRC
    // recomputed (a hostile image).
    let mut corrupt = [0u32; SLOT_WORDS];
    let n = damaged(update, update.len() / 2, 1 << 4, &mut corrupt);
    let corrupt = &corrupt[..n];
    let mut hostile = [0u32; SLOT_WORDS];
    let mut probe = check;
    // Past the words a parse alone refuses: a flaw only the structure
    // check finds (codes from 0x300).
    let Some((hostile_at, hostile_code)) = (0..update.len()).find_map(|at| {
        damaged(update, at, 1 << 4, &mut hostile);
        field_update::slot::Check::check(&mut probe, &hostile[..update.len()])
            .err()
            .filter(|&code| code >= 0x300)
            .map(|code| (at, code))
    }) else {
        fail("no single flipped word is refused by the structure check");
    };
    damaged(update, hostile_at, 1 << 4, &mut hostile);
    let hostile = &hostile[..update.len()];
    let hostile_crc = crc_of_words(&CRC, hostile);

    let mut a = [u32::MAX; SLOT_WORDS];
    let mut b = [u32::MAX; SLOT_WORDS];
    let mut plc = Plc {
        endpoint: Endpoint::new(Loader::new(&CRC, None, &check)),
        store: RamSlots::new(&mut a, &mut b),
        check,
        budget: usize::from(config.rom_test_bytes_per_scan / 4).max(1),
    };
    let mut tally = Tally {
        failures: 0,
        mismatches: 0,
    };
    let (mut loads, mut switched, mut refused, mut rollbacks) = (0u32, 0u32, 0u32, 0u32);
    let (mut switch_instr, mut poll_max, mut check_scans) = (0u32, 0u32, 0u32);
    let (major, minor, patch) = version_parts(file_header.version);
    hprintln!(
        "update: built-in {} (image CRC {:#010x}, {} words); update {} words, CRC {:#010x}, version {}.{}.{}; slots of {} words in RAM; {} link bytes per scan; check {} words per scan",
        config.name,
        built_in_crc,
        own.len(),
        update.len(),
        update_crc,
        major,
        minor,
        patch,
        SLOT_WORDS,
        BYTES_PER_SCAN,
        plc.budget
    );

    // 1. Start-up, both slots erased.
    hprintln!("1. start-up, slots erased");
    let mut probe = check;
    let choice = choose(&plc.store, &CRC, &mut probe);
    describe(&choice);
    tally.expect(
        choice.running.is_none() && choice.rejected == [Some(Rejected::Empty); 2],
        "the built-in program runs, both slots empty",
    );

    // 2. Refused loads while the built-in program runs its scenario, then
    // the update.
    hprintln!(
        "2. built-in program, its scenario; the PC: Status, a corrupt image, a hostile image (word {} flipped, CRC recomputed), the update announced for other wiring, then the update",
        hostile_at
    );
    let jobs = [
        Job::Status,
        Job::Load {
            image: corrupt,
            image_crc: update_crc,
            version: file_header.version,
            wiring: file_header.wiring,
        },
        Job::Load {
            image: hostile,
            image_crc: hostile_crc,
            version: file_header.version,
            wiring: file_header.wiring,
        },
        Job::Load {
            image: update,
            image_crc: update_crc,
            version: file_header.version,
            wiring: file_header.wiring ^ 0x8000_0000,
        },
        Job::AfterScenario,
        Job::Load {
            image: update,
            image_crc: update_crc,
            version: file_header.version,
            wiring: file_header.wiring,
        },
    ];
    let Ok(mut controller) = Controller::new_proven(built_in, program::Memory::new()) else {
        fail("generated memory does not fit the program");
    };
    let own_running = Running {
        name: config.name,
        image_crc: built_in_crc,
    };
    let end = phase(
        &mut controller,
        &config,
        own_running,
        SCENARIO,
        &jobs,
        &mut plc,
        overhead,
    );
    loads += 4;
    tally.mismatches += end.mismatches;
    poll_max = poll_max.max(end.poll_max);
    check_scans = check_scans.max(end.check_scans);
    hprintln!(
        "  {} scans, {} of the scenario compared, {} mismatches",
        end.scans,
        end.replayed,
        end.mismatches
    );
    show(&end.answers);
    tally.expect(
        name_is(&end.answers[0], config.name, None, 0, built_in_crc),
        "Status: the built-in program, no slot",
    );
    let image_crc_refused = matches!(
        end.answers[1],
        Some(Answer::Refused(Refusal::Rejected(Rejected::ImageCrc { recorded, .. }))) if recorded == update_crc
    );
    tally.expect(
        image_crc_refused,
        "the corrupt image: refused, its CRC is not the announced one",
    );
    let structure_refused = end.answers[2]
        == Some(Answer::Refused(Refusal::Rejected(Rejected::Structure(
            hostile_code,
        ))));
    hprintln!("  hostile image refused with code {:#06x}", hostile_code);
    tally.expect(structure_refused, "the hostile image: refused by the structure check, with the code the firmware's check gives");
    let wiring_refused = end.answers[3]
        == Some(Answer::Refused(Refusal::Wiring {
            expected: wiring,
            found: file_header.wiring ^ 0x8000_0000,
        }));
    tally.expect(
        file_header.wiring == wiring && wiring_refused,
        "the update announced for other wiring: refused at Begin (the update's own wiring is the firmware's)",
    );
    refused +=
        u32::from(image_crc_refused) + u32::from(structure_refused) + u32::from(wiring_refused);
    tally.expect(
        end.mismatches == 0 && end.replayed > 0,
        "the built-in program ran its whole scenario unchanged meanwhile",
    );
    let Some((valid_a, at)) = end.switched else {
        fail("the update was not switched in");
    };
    switched += 1;
    tally.expect(
        valid_a.slot == Slot::A
            && valid_a.header.sequence == 1
            && end.answers[5]
                == Some(Answer::Switched {
                    slot: Slot::A,
                    sequence: 1,
                }),
        "the update: Switched, slot A, sequence 1",
    );
    hprintln!(
        "  switched after scan {} (a check took at most {} scans, at most {} instructions of a scan); the next scan runs the update",
        at,
        end.check_scans,
        end.poll_max
    );

    // 3. The update runs; the built-in image loaded again as 1.2.0.
    hprintln!("3. the update from slot A, its scenario; the PC: Status, then the built-in image as version 1.2.0");
    let v120 = version(1, 2, 0);
    let jobs = [
        Job::Status,
        Job::AfterScenario,
        Job::Load {
            image: own,
            image_crc: built_in_crc,
            version: v120,
            wiring,
        },
    ];
    let mut instr = 0;
    let end = run_slot(
        &valid_a,
        UPDATE_SCENARIO,
        &jobs,
        &mut plc,
        overhead,
        &mut instr,
    );
    switch_instr = switch_instr.max(instr);
    loads += 1;
    tally.mismatches += end.mismatches;
    poll_max = poll_max.max(end.poll_max);
    check_scans = check_scans.max(end.check_scans);
    hprintln!(
        "  switch-in: {} instructions (copy, parse, the board's check, controller and its start-up check); {} scans, {} compared, {} mismatches",
        instr,
        end.scans,
        end.replayed,
        end.mismatches
    );
    show(&end.answers);
    let status_ok = matches!(
        end.answers[0],
        Some(Answer::Status { slot: Some(Slot::A), version, image_crc, .. })
            if version == file_header.version && image_crc == update_crc
    );
    tally.expect(
        status_ok,
        "Status: the update's name, slot A, its version and CRC",
    );
    tally.expect(
        end.mismatches == 0 && end.replayed > 0,
        "the update replays its own scenario",
    );
    let Some((valid_b, _)) = end.switched else {
        fail("the built-in image was not switched in");
    };
    switched += 1;
    tally.expect(
        valid_b.slot == Slot::B && valid_b.header.sequence == 2,
        "the built-in image as 1.2.0: Switched, slot B, sequence 2",
    );

    // 4. Version 1.2.0 runs from slot B.
    hprintln!("4. version 1.2.0 from slot B, its scenario; the PC: Status");
    let jobs = [Job::Status];
    let end = run_slot(&valid_b, SCENARIO, &jobs, &mut plc, overhead, &mut instr);
    switch_instr = switch_instr.max(instr);
    tally.mismatches += end.mismatches;
    hprintln!(
        "  switch-in: {} instructions; {} scans, {} mismatches",
        instr,
        end.scans,
        end.mismatches
    );
    show(&end.answers);
    tally.expect(
        name_is(
            &end.answers[0],
            config.name,
            Some(Slot::B),
            v120,
            built_in_crc,
        ),
        "Status: the built-in project's name, slot B, 1.2.0",
    );
    tally.expect(end.mismatches == 0, "1.2.0 replays the built-in scenario");

    // 5. Restarts: which slot runs, and rollbacks.
    hprintln!("5. restarts");
    let mut probe = check;
    let choice = choose(&plc.store, &CRC, &mut probe);
    describe(&choice);
    tally.expect(
        choice.running == Some(valid_b),
        "restart: slot B, the newest, runs",
    );
    plc.store.words_mut(Slot::B)[HEADER_WORDS + 7] ^= 1 << 9;
    hprintln!("  slot B: image word 7 flipped");
    let choice = choose(&plc.store, &CRC, &mut probe);
    describe(&choice);
    let back_to_a = choice.running == Some(valid_a)
        && matches!(choice.rejected[1], Some(Rejected::ImageCrc { .. }));
    tally.expect(
        back_to_a,
        "restart: B refused (image CRC), A runs: rolled back",
    );
    rollbacks += u32::from(back_to_a);
    let end = run_slot(
        &valid_a,
        UPDATE_SCENARIO,
        &[],
        &mut plc,
        overhead,
        &mut instr,
    );
    tally.mismatches += end.mismatches;
    tally.expect(
        end.mismatches == 0,
        "the update from slot A replays its scenario again",
    );
    plc.store.words_mut(Slot::A)[HEADER_WORDS + 3] ^= 1;
    hprintln!("  slot A: image word 3 flipped");
    let choice = choose(&plc.store, &CRC, &mut probe);
    describe(&choice);
    let to_built_in = choice.running.is_none()
        && matches!(choice.rejected[0], Some(Rejected::ImageCrc { .. }))
        && matches!(choice.rejected[1], Some(Rejected::ImageCrc { .. }));
    tally.expect(
        to_built_in,
        "restart: both slots refused, the built-in program runs: rolled back",
    );
    rollbacks += u32::from(to_built_in);
    let Ok(mut controller) = Controller::new_proven(built_in, program::Memory::new()) else {
        fail("generated memory does not fit the program");
    };
    let end = phase(
        &mut controller,
        &config,
        own_running,
        SCENARIO,
        &[],
        &mut plc,
        overhead,
    );
    tally.mismatches += end.mismatches;
    tally.expect(
        end.mismatches == 0,
        "the built-in program replays its scenario",
    );

    hprintln!(
        "update: loads={} switched={} refused={} rollbacks={} mismatches={} switch_instr={} poll_max={} check_scans={} failures={}",
        loads,
        switched,
        refused,
        rollbacks,
        tally.mismatches,
        switch_instr,
        poll_max,
        check_scans,
        tally.failures
    );
    finish(tally.failures == 0 && tally.mismatches == 0)
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    hprintln!("HardFault at pc={:#010x}", frame.pc());
    exit(debug::EXIT_FAILURE)
}
