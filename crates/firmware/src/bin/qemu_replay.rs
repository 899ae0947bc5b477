//! QEMU replay harness (mps2-an386, Cortex-M4): replays a scenario recorded
//! by host-sim through the same executor and generated program the board
//! runs, compares every trace record, and counts instructions per scan.
//!
//! Run under `qemu-system-arm -M mps2-an386 -icount shift=9
//! -semihosting-config enable=on,target=native -nographic -kernel …`
//! (`cargo xtask qemu` does it). With `-icount shift=9` SysTick (25 MHz)
//! advances exactly 12.8 ticks per executed instruction, so
//! `instructions = ticks × 5 / 64`. The last line printed is
//!
//! `scans=N mismatches=M instr_median=X instr_p99=Y instr_max=Z flash=F ram=R
//! quiet_scans=Q quiet_median=QX quiet_max=QZ share_mean=SM share_max=SX`
//!
//! where `flash` is the image without the embedded scenario, `ram` the
//! static RAM (`.data` + `.bss`), and the `quiet_` figures count the quiet
//! scans alone: same raw inputs as the scan before, no fault in either,
//! nothing executed or unexpected. Each scan runs as on the board: the
//! background image share (`Controller::check_image_share`, timed on its
//! own: `share_` figures), then `Controller::step_packed` (the `instr_`
//! figures), inputs packed in words as the board reads them; the record is
//! read after it. The exit code is 0 only when M = 0 and
//! the budgets given at build time (`PLC_BUDGET_FLASH`, `PLC_BUDGET_RAM`,
//! `PLC_BUDGET_INSTR_MEDIAN`, `PLC_BUDGET_INSTR_MAX`) hold. A HardFault
//! or a panic exits with failure.
//!
//! The replay loop is a function of its own (`replay`), so that the
//! reports around it do not change the code of the scans it times; its
//! lines are written without `core::fmt` ([`firmware::hostline`]), which
//! the board never links either, so that `flash` is the board's share.

#![no_std]
#![no_main]

use core::panic::PanicInfo;
use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m::peripheral::SYST;
use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::debug;
use executor::replay::{unpack_words, RecordedScan, ScenarioHeader};
use executor::{Controller, Program};
use firmware::hostline::Line;
use firmware::icount::{elapsed, exit, finish, instructions, kth_smallest, start};
use firmware::program;

/// The scenario, recorded by `host-sim record`.
static SCENARIO: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/scenario.bin"));

/// Most scans whose instruction counts are kept (the median
/// and p99 are of the first this many; the maximum is of every scan).
const MAX_SCANS: usize = 8192;

/// A budget given at build time, `u32::MAX` when absent.
fn budget(value: Option<&str>) -> u32 {
    value.and_then(|v| v.parse().ok()).unwrap_or(u32::MAX)
}

extern "C" {
    static __sdata: u8;
    static __edata: u8;
    static __ebss: u8;
    static __erodata: u8;
    static __stext: u8;
    static __vector_table: u8;
}

/// Flash used (vector table to the end of `.rodata`, plus `.data`'s load
/// image) and static RAM (`.data` + `.bss`), from the linker's symbols.
fn image_sizes() -> (u32, u32) {
    let addr = |p: *const u8| p as u32;
    let start = addr(&raw const __vector_table);
    let rodata_end = addr(&raw const __erodata);
    let data = addr(&raw const __edata) - addr(&raw const __sdata);
    let ram = addr(&raw const __ebss) - addr(&raw const __sdata);
    let _ = addr(&raw const __stext);
    (rodata_end - start + data, ram)
}

/// SysTick wraps counted by its exception while [`instructions_long`] runs.
static WRAPS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    // The only writer: a load and a store suffice, on ARMv6-M too.
    WRAPS.store(WRAPS.load(Ordering::Relaxed) + 1, Ordering::Relaxed);
}

/// Instructions `f` takes, however long (up to 2^32 ticks, 335 million
/// instructions): the counter restarts from its reload value and its
/// interrupt counts the wraps (2^24 ticks each).
fn instructions_long(syst: &mut SYST, f: impl FnOnce()) -> u32 {
    WRAPS.store(0, Ordering::Relaxed);
    syst.clear_current();
    syst.enable_interrupt();
    let before = SYST::get_current();
    f();
    let after = SYST::get_current();
    syst.disable_interrupt();
    let ticks = (WRAPS.load(Ordering::Relaxed) << 24)
        .wrapping_add(before)
        .wrapping_sub(after);
    instructions(ticks)
}

/// What [`replay`] counted.
struct Tally {
    scans: usize,
    mismatches: u32,
    /// The worst scan of all, past the samples too.
    worst: u32,
    quiet_scans: usize,
    share_max: u32,
    share_sum: u32,
}

/// Replays the scan records `rest` through `controller`, comparing each
/// record and counting instructions into `samples` (every scan's) and
/// `quiet` (the quiet scans': no input changed since the scan before,
/// which was not in fault mode, and nothing was executed or unexpected).
/// Out of line, so that the code around it (reports, budgets) leaves the
/// timed loop's code, and so its counts, unchanged: the scan is inlined
/// into this loop, as into the board's.
#[inline(never)]
fn replay<P: Program, M: executor::Memory>(
    controller: &mut Controller<P, M>,
    mut rest: &[u8],
    overhead: u32,
    samples: &mut [u32; MAX_SCANS],
    quiet: &mut [u32; MAX_SCANS],
) -> Tally {
    // Packed as a board reads its input ports, before the scan is timed.
    let mut raw = [0u32; program::INPUT_WORDS];
    let mut quiet_scans = 0usize;
    let mut previous: Option<[u32; program::INPUT_WORDS]> = None;
    let (mut share_max, mut share_sum) = (0u32, 0u32);
    let (mut scans, mut mismatches) = (0usize, 0u32);
    let mut worst = 0u32;
    while !rest.is_empty() {
        let Ok((expected, tail)) = postcard::take_from_bytes::<RecordedScan>(rest) else {
            fail("a scan record does not decode");
        };
        rest = tail;
        unpack_words(&expected.inputs, &mut raw);

        // A scan as the board runs it: the image share, then the scan.
        let share_start = SYST::get_current();
        controller.check_image_share();
        let before = SYST::get_current();
        controller.step_packed(expected.time_ms, &raw);
        let after = SYST::get_current();
        let record = controller.record();
        let share = instructions(elapsed(share_start, before).saturating_sub(overhead));
        share_max = share_max.max(share);
        share_sum = share_sum.saturating_add(share);

        if let Some(field) = expected.mismatch(&record) {
            if mismatches < 10 {
                Line::new()
                    .text("mismatch at scan ")
                    .num(record.scan)
                    .text(": ")
                    .text(field.name())
                    .print();
            }
            mismatches += 1;
        }
        let cost = instructions(elapsed(before, after).saturating_sub(overhead));
        worst = worst.max(cost);
        if scans < MAX_SCANS {
            samples[scans] = cost;
        }
        let calm = record.executed.is_empty() && record.unexpected.is_empty();
        if calm && record.fault.is_none() && previous == Some(raw) && quiet_scans < MAX_SCANS {
            quiet[quiet_scans] = cost;
            quiet_scans += 1;
        }
        previous = record.fault.is_none().then_some(raw);
        scans += 1;
    }
    Tally {
        scans,
        mismatches,
        worst,
        quiet_scans,
        share_max,
        share_sum,
    }
}

fn fail(message: &str) -> ! {
    Line::new().text("error: ").text(message).print();
    exit(debug::EXIT_FAILURE)
}

#[entry]
fn main() -> ! {
    let Some(mut core) = cortex_m::Peripherals::take() else {
        fail("core peripherals taken twice");
    };
    // The cost of reading the counter twice, subtracted from every sample.
    let overhead = start(&mut core.SYST);

    let Ok((header, rest)) = postcard::take_from_bytes::<ScenarioHeader>(SCENARIO) else {
        fail("the scenario has no valid header");
    };
    let config = program::PROGRAM.config();
    // The configuration CRC the generator recorded (computing it here would
    // link a second copy of the image stream, for another program type).
    if header.config_crc != program::CONFIG_CRC || usize::from(header.inputs) != config.inputs.len()
    {
        Line::new()
            .text("scenario configuration CRC ")
            .hex(header.config_crc)
            .text(", program ")
            .hex(program::CONFIG_CRC)
            .print();
        fail("the scenario was recorded for another project (configuration CRC differs)");
    }
    let Ok(mut controller) = Controller::new_proven(&program::PROGRAM, program::Memory::new())
    else {
        fail("generated memory does not fit the program");
    };
    // The whole-image CRC, as at start-up (scans check the image in the
    // background, `rom_test_bytes_per_scan` bytes each, and pay for that
    // share in their own counts).
    let mut intact = false;
    let check = instructions_long(&mut core.SYST, || intact = controller.check_image());
    if !intact {
        fail("the program image's CRC does not match");
    }
    let bytes = executor::image::bytes(&program::PROGRAM);
    let per_scan = usize::from(config.rom_test_bytes_per_scan / 4).max(1) * 4;
    Line::new()
        .text("image_check instr=")
        .num(check)
        .text(" image_bytes=")
        .num(bytes as u32)
        .text(" rom_test_bytes_per_scan=")
        .num(per_scan as u32)
        .text(" pass_scans=")
        .num(bytes.div_ceil(per_scan) as u32)
        .text(" (CRC-32 of the whole program image, as at start-up)")
        .print();

    let mut samples = [0u32; MAX_SCANS];
    let mut quiet = [0u32; MAX_SCANS];
    let tally = replay(&mut controller, rest, overhead, &mut samples, &mut quiet);
    if tally.scans as u32 != header.scans {
        fail("the scenario's scan count does not match its header");
    }

    // Slices without a panic path (its message would link `core::fmt`).
    let measured = samples
        .get(..tally.scans.min(MAX_SCANS))
        .unwrap_or_default();
    let at = |q: usize| kth_smallest(measured, measured.len().saturating_sub(1) * q / 100);
    let (median, p99, max) = (at(50), at(99), tally.worst);
    let quiet = quiet.get(..tally.quiet_scans).unwrap_or_default();
    let quiet_median = kth_smallest(quiet, quiet.len().saturating_sub(1) / 2);
    let quiet_max = kth_smallest(quiet, quiet.len());
    let (flash, ram) = image_sizes();
    let flash = flash - SCENARIO.len() as u32;
    Line::new()
        .text("scans=")
        .num(tally.scans as u32)
        .text(" mismatches=")
        .num(tally.mismatches)
        .text(" instr_median=")
        .num(median)
        .text(" instr_p99=")
        .num(p99)
        .text(" instr_max=")
        .num(max)
        .text(" flash=")
        .num(flash)
        .text(" ram=")
        .num(ram)
        .text(" quiet_scans=")
        .num(tally.quiet_scans as u32)
        .text(" quiet_median=")
        .num(quiet_median)
        .text(" quiet_max=")
        .num(quiet_max)
        .text(" share_mean=")
        .num(tally.share_sum / (tally.scans.max(1) as u32))
        .text(" share_max=")
        .num(tally.share_max)
        .print();
    let within = flash <= budget(option_env!("PLC_BUDGET_FLASH"))
        && ram <= budget(option_env!("PLC_BUDGET_RAM"))
        && median <= budget(option_env!("PLC_BUDGET_INSTR_MEDIAN"))
        && max <= budget(option_env!("PLC_BUDGET_INSTR_MAX"));
    finish(tally.mismatches == 0 && within)
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    Line::new().text("HardFault at pc=").hex(frame.pc()).print();
    exit(debug::EXIT_FAILURE)
}

/// A panic: its place (not its message, which would link `core::fmt`:
/// [`firmware::hostline`]), then exit with failure.
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    let mut line = Line::new();
    line.text("panicked");
    if let Some(at) = info.location() {
        line.text(" at ").text(at.file()).text(":").num(at.line());
    }
    line.print();
    exit(debug::EXIT_FAILURE)
}
