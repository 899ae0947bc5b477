//! Field update on every board (feature `field-update`; see
//! docs/field-update.md): which program runs at start-up, the serial link
//! between scans, and the switch to a program loaded while the PLC scans.
//! A board gives its slots, its link and its watchdog through
//! [`UpdateBoard`]; everything else is here.
//!
//! - Start-up: `field_update::slot::choose` over the two flash slots
//!   with the firmware's [`ImageCheck`]; the newest valid slot's program
//!   runs (parsed where it lies in flash, [`Loaded::program`], in the
//!   memory [`Room`](firmware::update::Room)), else the built-in one. The
//!   log names the program, its slot, version and image CRC, and why each
//!   slot was passed over.
//! - Each scan, after the outputs are written and the watchdog fed: the
//!   bytes the link received go to `Endpoint::receive` (a `Begin` erases
//!   the slot not running: no scan for up to 4 s, outputs held, the
//!   watchdog widened, the board's `flash`), its answers are sent, and
//!   `Endpoint::poll` advances a committed load's check by the
//!   program's `rom_test_bytes_per_scan` (as the QEMU harness does).
//! - When `poll` reports `Switched`, the scan loop ends and the next scan
//!   runs the new program: a fresh controller (initial states), whose
//!   initial outputs are written at once, paced on its own scan period,
//!   the watchdog's timeout set for that period.
//! - Every program's image check runs in the board's CRC engine (the
//!   STM32's CRC unit, the RP2040's software table), lent to each
//!   controller in turn (`executor::image::CrcEngine` for `&mut`).

use crate::link::Port;
use crate::report::{self, Numbered};
use crate::scan::{self, Board, Link, Startup, WATCHDOG_MS};
use crc::Crc;
use embedded_hal_nb::serial::Write;
use executor::image::CrcEngine;
use executor::{Controller, Program};
use field_update::loader::{Endpoint, Loader, Outcome, Running};
use field_update::slot::{choose, image_of, Choice, Slot, SlotStore, Valid};
use field_update::CRC_ALGORITHM;
use firmware::program::{self, CONFIG};
use firmware::slots::SlotMap;
use firmware::update::{ImageCheck, Loaded};
use firmware::MCU;

/// Slot headers, images and frames.
static CRC: Crc<u32> = Crc::<u32>::new(&CRC_ALGORITHM);

/// The address of `slot` on a board whose slots are `map`.
pub const fn address(map: &SlotMap, slot: Slot) -> u32 {
    match slot {
        Slot::A => map.a,
        Slot::B => map.b,
    }
}

/// What field update needs of a board beyond the scan loop's [`Board`].
pub trait UpdateBoard: Board {
    /// Its two slots in flash.
    type Slots<'a>: SlotStore
    where
        Self: 'a;
    /// Its link's transmitter.
    type Tx: Write<u8>;

    /// The slots (with the watchdog, which an erase starts again with a
    /// longer timeout, then with `watchdog_ms`) and the serial link.
    fn update_parts(&mut self, watchdog_ms: u32) -> (Self::Slots<'_>, &mut Port<Self::Tx>);

    /// The words of `slot` where the flash is mapped.
    fn slot_words(slot: Slot) -> &'static [u32];

    /// Starts the running watchdog again with `timeout_ms` (a switched-in
    /// program's scan period may differ from the built-in one's).
    fn set_watchdog_timeout(&mut self, timeout_ms: u32);
}

/// The link between two scans of the program `running`.
struct Serial<'e, 'c, 'n> {
    endpoint: &'e mut Endpoint<'c>,
    check: ImageCheck,
    /// Image words a committed load's check takes per scan.
    budget: usize,
    running: Running<'n>,
    /// The watchdog timeout for the running program's scan period.
    watchdog_ms: u32,
}

impl<B: UpdateBoard> Link<B> for Serial<'_, '_, '_> {
    type Switch = Valid;

    fn after_scan(&mut self, board: &mut B) -> Option<Valid> {
        let (mut store, port) = board.update_parts(self.watchdog_ms);
        while let Some(byte) = port.read() {
            if let Some(frame) = self.endpoint.receive(byte, &mut store, self.running) {
                port.send(frame);
            }
        }
        let switched = match self.endpoint.poll(&mut store, &mut self.check, self.budget) {
            Some((outcome, frame)) => {
                port.send(frame);
                report::load(&outcome);
                match outcome {
                    Outcome::Switched(valid) => Some(valid),
                    Outcome::Refused(_) => None,
                }
            }
            None => None,
        };
        port.flush();
        switched
    }
}

/// Runs the newest valid slot's program, else the built-in one, and
/// whatever the link switches to, forever.
pub fn run<B: UpdateBoard, C: CrcEngine>(mut board: B, startup: Startup, mut crc: C) -> ! {
    report::startup(&startup, WATCHDOG_MS);
    let check = ImageCheck::new(&CONFIG, program::board::WIRING);
    let choice: Choice = {
        let (store, _) = board.update_parts(WATCHDOG_MS);
        let mut probe = check;
        choose(&store, &CRC, &mut probe)
    };
    report::choice(&choice);
    let mut endpoint = Endpoint::new(Loader::new(&CRC, choice.running, &check));
    board.start_watchdog(WATCHDOG_MS);
    let mut next = choice.running;
    loop {
        next = match next {
            Some(valid) => run_slot(&mut board, &mut endpoint, check, valid, &mut crc),
            None => {
                let mut controller = scan::built_in(&mut crc);
                report::image_check(controller.fault(), program::PROGRAM.recorded_crc());
                let mut link = Serial {
                    endpoint: &mut endpoint,
                    check,
                    budget: budget(&CONFIG),
                    running: Running {
                        name: CONFIG.name,
                        image_crc: program::PROGRAM.recorded_crc(),
                    },
                    watchdog_ms: WATCHDOG_MS,
                };
                board.set_watchdog_timeout(WATCHDOG_MS);
                Some(scan::scan_loop(
                    &mut board,
                    &mut controller,
                    &CONFIG,
                    &report::BuiltIn,
                    &mut link,
                ))
            }
        };
    }
}

/// Image words per scan of a committed load's check: the program's ROM
/// test share (`rom_test_bytes_per_scan`), at least one word.
fn budget(config: &executor::Config<'_>) -> usize {
    usize::from(config.rom_test_bytes_per_scan / 4).max(1)
}

/// Runs the program of slot `valid` from flash until the link switches
/// to another; `None` (the built-in program next) when it does not load.
fn run_slot<B: UpdateBoard, C: CrcEngine>(
    board: &mut B,
    endpoint: &mut Endpoint<'_>,
    check: ImageCheck,
    valid: Valid,
    crc: &mut C,
) -> Option<Valid> {
    let image = image_of(B::slot_words(valid.slot), &valid.header);
    let mut loaded = Loaded::new();
    let (program, room) = match loaded.program(image, valid.header.image_crc, &check) {
        Ok(p) => p,
        Err(code) => {
            report::slot_refused(valid.slot, code);
            return None;
        }
    };
    let Ok(mut controller) = Controller::new_proven_with_crc(&program, room, crc) else {
        report::slot_refused(valid.slot, firmware::update::REFUSED_NO_ROOM);
        return None;
    };
    let config = program.config();
    report::slot_runs(&valid, config.name, controller.fault());
    // The new program's outputs before its first scan: its initial
    // levels (or, in fault mode, its safe ones).
    board.pins().write(controller.outputs());
    let names = Numbered {
        reset: config.reset,
    };
    // The watchdog for this program's scan period (the built-in one's
    // may differ), at most what the IWDG counts.
    let watchdog_ms = MCU
        .watchdog
        .timeout_ms(config.scan_period_ms)
        .min(MCU.watchdog.max_timeout_ms);
    board.set_watchdog_timeout(watchdog_ms);
    let mut link = Serial {
        endpoint,
        check,
        budget: budget(&config),
        running: Running {
            name: config.name,
            image_crc: valid.header.image_crc,
        },
        watchdog_ms,
    };
    Some(scan::scan_loop(
        board,
        &mut controller,
        &config,
        &names,
        &mut link,
    ))
}
