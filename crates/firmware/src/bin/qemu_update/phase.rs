//! A program run through its recorded scenario while the PC's requests
//! reach the loader between scans.

use crate::pc::{Answer, Job, Pc, MAX_JOBS};
use crate::{fail, SLOT_WORDS};
use cortex_m::peripheral::SYST;
use cortex_m_semihosting::hprintln;
use executor::replay::{unpack_words, RecordedScan, ScenarioHeader};
use executor::{Controller, Memory, Program};
use field_update::frame::MAX_FRAME;
use field_update::loader::{Endpoint, Outcome, Running};
use field_update::slot::{image_of, RamSlots, SlotStore, Valid};
use firmware::icount::{elapsed, instructions};
use firmware::update::{ImageCheck, Loaded};

/// Held-input scans a phase may run after its scenario while the PC
/// finishes its requests.
const MAX_EXTRA_SCANS: u32 = 20_000;

/// The recorded scans of a scenario, one after the other.
struct Replay<'s> {
    rest: &'s [u8],
    scans: u32,
}

impl<'s> Replay<'s> {
    fn new(scenario: &'s [u8], inputs: usize, config_crc: Option<u32>) -> Replay<'s> {
        let Ok((header, rest)) = postcard::take_from_bytes::<ScenarioHeader>(scenario) else {
            fail("a scenario has no valid header");
        };
        let crc_ok = config_crc.is_none_or(|crc| crc == header.config_crc);
        if !crc_ok || usize::from(header.inputs) != inputs {
            fail("a scenario was recorded for another project");
        }
        Replay {
            rest,
            scans: header.scans,
        }
    }

    fn next(&mut self) -> Option<RecordedScan> {
        if self.rest.is_empty() {
            return None;
        }
        let Ok((scan, tail)) = postcard::take_from_bytes::<RecordedScan>(self.rest) else {
            fail("a scan record does not decode");
        };
        self.rest = tail;
        Some(scan)
    }
}

/// What a phase ended with.
pub struct PhaseEnd {
    pub scans: u32,
    pub mismatches: u32,
    /// Scans of the recorded scenario replayed and compared.
    pub replayed: u32,
    /// The update that ended the phase, at which scan.
    pub switched: Option<(Valid, u32)>,
    /// Most instructions one scan's `Endpoint::poll` took.
    pub poll_max: u32,
    /// Most scans from a `Commit` to its outcome.
    pub check_scans: u32,
    pub answers: [Option<Answer>; MAX_JOBS],
}

/// The PLC's side of the link: the loader, the slots, the check.
pub struct Plc<'s, 'c> {
    pub endpoint: Endpoint<'c>,
    pub store: RamSlots<'s>,
    pub check: ImageCheck,
    /// Image words the loader's CRC check takes per scan.
    pub budget: usize,
}

/// Runs `controller` through `scenario`, then with its last inputs held
/// until the PC is done; the PC's requests go to `plc` meanwhile. Ends
/// early at a switch: the next scan is the new program's.
pub fn phase<P: Program, M: Memory>(
    controller: &mut Controller<P, M>,
    config: &executor::Config<'_>,
    running: Running<'_>,
    scenario: &[u8],
    jobs: &[Job<'_>],
    plc: &mut Plc<'_, '_>,
    syst_overhead: u32,
) -> PhaseEnd {
    let period = config.scan_period_ms;
    let mut replay = Replay::new(scenario, config.inputs.len(), None);
    let mut pc = Pc::new(jobs);
    let mut raw = [0u32; 4];
    let mut end = PhaseEnd {
        scans: 0,
        mismatches: 0,
        replayed: 0,
        switched: None,
        poll_max: 0,
        check_scans: 0,
        answers: [None; MAX_JOBS],
    };
    let (mut time, mut extra, mut checking) = (0u32, 0u32, 0u32);
    loop {
        let expected = replay.next();
        let scenario_over = expected.is_none();
        if scenario_over && pc.done() {
            break;
        }
        match &expected {
            Some(scan) => {
                unpack_words(&scan.inputs, &mut raw);
                time = scan.time_ms;
            }
            None => {
                extra += 1;
                if extra > MAX_EXTRA_SCANS {
                    fail("the PC's requests did not end");
                }
                time = time.wrapping_add(period);
            }
        }
        controller.check_image_share();
        controller.step_packed(time, &raw);
        if let Some(scan) = &expected {
            end.replayed += 1;
            if let Some(field) = scan.mismatch(&controller.record()) {
                if end.mismatches < 5 {
                    hprintln!("  mismatch at scan {}: {:?}", end.scans, field);
                }
                end.mismatches += 1;
            }
        }
        end.scans += 1;

        // Between scans: the link, then a share of a committed check.
        pc.exchange(&mut plc.endpoint, &mut plc.store, running, scenario_over);
        if plc.endpoint.loader().is_checking() {
            checking += 1;
            end.check_scans = end.check_scans.max(checking);
        } else {
            checking = 0;
        }
        let before = SYST::get_current();
        let polled = plc
            .endpoint
            .poll(&mut plc.store, &mut plc.check, plc.budget)
            .map(|(outcome, frame)| {
                let mut copy = [0u8; MAX_FRAME];
                copy[..frame.len()].copy_from_slice(frame);
                (outcome, copy, frame.len())
            });
        let after = SYST::get_current();
        end.poll_max = end.poll_max.max(instructions(
            elapsed(before, after).saturating_sub(syst_overhead),
        ));
        if let Some((outcome, frame, len)) = polled {
            pc.answer_bytes(&frame[..len]);
            if let Outcome::Switched(valid) = outcome {
                end.switched = Some((valid, end.scans));
                break;
            }
        }
    }
    if replay.scans != end.replayed && end.switched.is_none() {
        fail("a scenario's scan count does not match its header");
    }
    end.answers = pc.answers;
    end
}

/// Copies the image of `valid` out of its slot into `copy`.
fn copy_image<'c>(store: &RamSlots<'_>, valid: &Valid, copy: &'c mut [u32]) -> &'c [u32] {
    let image = image_of(store.contents(valid.slot), &valid.header);
    let copy = &mut copy[..image.len()];
    copy.copy_from_slice(image);
    copy
}

/// Runs the program of slot `valid` (copied out of the store) through
/// `scenario` with `jobs` on the link.
pub fn run_slot(
    valid: &Valid,
    scenario: &[u8],
    jobs: &[Job<'_>],
    plc: &mut Plc<'_, '_>,
    overhead: u32,
    switch_instr: &mut u32,
) -> PhaseEnd {
    let mut copy = [0u32; SLOT_WORDS];
    let mut loaded = Loaded::new();
    // The switch: the image out of its slot, parsed, checked, and a
    // controller in its initial state.
    let before = SYST::get_current();
    let image = copy_image(&plc.store, valid, &mut copy);
    let Ok((program, room)) = loaded.program(image, valid.header.image_crc, &plc.check) else {
        fail("a slot that passed its check does not load");
    };
    let Ok(mut controller) = Controller::new_proven(&program, room) else {
        fail("a loaded program does not fit its memory");
    };
    let after = SYST::get_current();
    *switch_instr = instructions(elapsed(before, after).saturating_sub(overhead));
    if controller.fault().is_some() {
        fail("a loaded program starts in fault mode");
    }
    let config = program.config();
    let running = Running {
        name: config.name,
        image_crc: valid.header.image_crc,
    };
    phase(
        &mut controller,
        &config,
        running,
        scenario,
        jobs,
        plc,
        overhead,
    )
}
