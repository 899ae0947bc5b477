//! What the firmware tells over defmt-rtt (`probe-rs run` prints it with
//! the time stamp of the millisecond clock): start-up (reset cause,
//! clocks, the program image check), every executed and unexpected event
//! by name, fault changes, overruns, lost edges, and every 10 s a status
//! line (scans, counters, states, outputs, scan times).
//!
//! Only what changes is logged per scan, so a quiet plant costs nothing
//! and the log stays readable.

use crate::scan::{ResetCause, Startup};
use executor::image::CrcEngine;
use executor::memory::Memory;
use executor::pacing::ScanStart;
use executor::program::Index;
use executor::{Controller, Fault, Program, ScanRecord};
use firmware::program::{event, input, supervisor, CONFIG};

/// The names the log gives a program's events and inputs: the built-in
/// program's ([`BuiltIn`]); a program loaded into a field-update slot
/// has none in its image, and its log gives numbers ([`Numbered`]).
pub trait Names {
    /// Whether events and inputs are logged by number.
    const NUMBERED: bool;
    /// The name of event `e`.
    fn event(&self, e: Index) -> &'static str;
    /// The name of input `i`.
    fn input(&self, i: usize) -> &'static str;
    /// The reset input, if the program has one.
    fn reset(&self) -> Option<Index>;
}

/// The built-in program's names.
pub struct BuiltIn;

impl Names for BuiltIn {
    const NUMBERED: bool = false;

    fn event(&self, e: Index) -> &'static str {
        event::NAMES.get(usize::from(e)).copied().unwrap_or("?")
    }

    fn input(&self, i: usize) -> &'static str {
        input::NAMES.get(i).copied().unwrap_or("?")
    }

    fn reset(&self) -> Option<Index> {
        CONFIG.reset
    }
}

/// A loaded program's: numbers only.
#[cfg_attr(not(feature = "field-update"), allow(dead_code))]
pub struct Numbered {
    /// The program's reset input.
    pub reset: Option<Index>,
}

impl Names for Numbered {
    const NUMBERED: bool = true;

    fn event(&self, _: Index) -> &'static str {
        "event"
    }

    fn input(&self, _: usize) -> &'static str {
        "input"
    }

    fn reset(&self) -> Option<Index> {
        self.reset
    }
}

/// The start-up line.
pub fn startup(startup: &Startup, watchdog_ms: u32) {
    defmt::info!(
        "PLC `{=str}` on {=str}: reset cause {}, {=u32} Hz from {=str}, scan every {=u32} ms, watchdog {=u32} ms",
        CONFIG.name,
        firmware::program::board::CHIP,
        startup.reset,
        startup.sysclk_hz,
        startup.clock_source,
        CONFIG.scan_period_ms,
        watchdog_ms
    );
    if startup.reset == ResetCause::Watchdog {
        defmt::warn!("the watchdog reset the board: a scan did not complete in time");
    }
    defmt::info!(
        "{=usize} inputs {=[?]}, {=usize} outputs, supervisors {=[?]}",
        input::COUNT,
        input::NAMES[..],
        firmware::program::output::COUNT,
        supervisor::NAMES[..]
    );
}

/// The program image check of `Controller::new_proven`, and which program runs:
/// the built-in one (version 0), its image CRC (what a field update's
/// `Status` reports, `codegen image` prints).
pub fn image_check(fault: Option<Fault>, image_crc: u32) {
    match fault {
        None => defmt::info!(
            "program `{=str}` built-in, image CRC {=u32:#010x}: intact",
            CONFIG.name,
            image_crc
        ),
        Some(f) => defmt::error!(
            "program image check failed ({}): fault mode, outputs at their safe levels",
            f
        ),
    }
}

/// A scan that started too late.
pub fn overrun(scan: u32, start: &ScanStart, period_ms: u32) {
    defmt::warn!(
        "scan {=u32}: overrun, started {=u32} ms late ({=u32} periods of {=u32} ms skipped)",
        scan,
        start.late_ms,
        start.skipped,
        period_ms
    );
}

/// An input that changed `count` times between two samples.
pub fn lost_edge<N: Names>(names: &N, scan: u32, input: usize, count: u8) {
    if N::NUMBERED {
        return defmt::warn!(
            "scan {=u32}: lost edge on input #{=usize} ({=u8} changes since the last sample)",
            scan,
            input,
            count
        );
    }
    defmt::warn!(
        "scan {=u32}: lost edge on `{=str}` ({=u8} changes since the last sample)",
        scan,
        names.input(input),
        count
    );
}

/// What scan `record` did, given the fault before it.
pub fn scan<N: Names>(names: &N, record: &ScanRecord<'_>, before: Option<Fault>) {
    for &e in record.executed {
        if N::NUMBERED {
            defmt::info!("scan {=u32}: event #{=u16}", record.scan, e);
        } else {
            defmt::info!("scan {=u32}: {=str}", record.scan, names.event(e));
        }
    }
    for &e in record.unexpected {
        if N::NUMBERED {
            defmt::warn!("scan {=u32}: unexpected event #{=u16}", record.scan, e);
        } else {
            defmt::warn!(
                "scan {=u32}: unexpected {=str}",
                record.scan,
                names.event(e)
            );
        }
    }
    match (before, record.fault) {
        (None, Some(fault)) => entered(names, record, fault),
        (Some(_), None) => defmt::info!(
            "scan {=u32}: reset: controller re-initialised, states {=[?]}",
            record.scan,
            record.states
        ),
        _ => {}
    }
}

fn entered<N: Names>(names: &N, record: &ScanRecord<'_>, fault: Fault) {
    let until = match names.reset() {
        Some(r) => names.input(usize::from(r)),
        None => "power-on (no reset input)",
    };
    match fault {
        Fault::Unexpected { event } => defmt::error!(
            "scan {=u32}: fault: unexpected {=str} in states {=[?]}; safe outputs until {=str}",
            record.scan,
            names.event(event),
            record.states,
            until
        ),
        other => defmt::error!(
            "scan {=u32}: fault: {}; safe outputs until {=str}",
            record.scan,
            other,
            until
        ),
    }
}

/// Scan durations since the last status line, in board timer ticks
/// (`Board::timer`), in 32-bit arithmetic: a 64-bit division would link
/// about 900 bytes of `u64_div_rem` on the Cortex-M. A 10 s window holds
/// at most 10^9 ticks of scans at 100 MHz (the sum saturates at 4.3·10^9).
#[derive(Debug, Default)]
pub struct ScanTimes {
    scans: u32,
    total: u32,
    max: u32,
}

impl ScanTimes {
    /// One scan of `ticks`.
    pub fn add(&mut self, ticks: u32) {
        self.scans = self.scans.saturating_add(1);
        self.total = self.total.saturating_add(ticks);
        self.max = self.max.max(ticks);
    }
}

/// The status line (`ticks_per_us`: the board timer's rate); starts a new
/// scan-time window.
pub fn status<P: Program, M: Memory, C: CrcEngine>(
    controller: &Controller<P, M, C>,
    times: &mut ScanTimes,
    ticks_per_us: u32,
) {
    let mean = times.total / times.scans.max(1);
    defmt::info!(
        "status: {=u32} scans, fault {}, {}, states {=[?]}, outputs {=[?]}, scan time mean {=u32} us max {=u32} us",
        controller.next_scan(),
        controller.fault(),
        controller.counters(),
        controller.states(),
        controller.outputs(),
        mean / ticks_per_us,
        times.max / ticks_per_us
    );
    *times = ScanTimes::default();
}

/// The start-up choice of a field-update slot: which slot runs (or the
/// built-in program) and why each slot was passed over.
#[cfg(feature = "field-update")]
pub fn choice(choice: &field_update::slot::Choice) {
    match choice.running {
        Some(v) => defmt::info!(
            "field update: slot {} chosen (sequence {=u32}); passed over: A {}, B {}",
            v.slot,
            v.header.sequence,
            choice.rejected[0],
            choice.rejected[1]
        ),
        None => defmt::info!(
            "field update: no valid slot, the built-in program runs; passed over: A {}, B {}",
            choice.rejected[0],
            choice.rejected[1]
        ),
    }
}

/// The program of slot `valid` runs (`name`, its version and image CRC),
/// with its start-up image check.
#[cfg(feature = "field-update")]
pub fn slot_runs(valid: &field_update::slot::Valid, name: &str, fault: Option<Fault>) {
    let (major, minor, patch) = field_update::header::version_parts(valid.header.version);
    defmt::info!(
        "program `{=str}` from slot {}, version {=u16}.{=u8}.{=u8}, sequence {=u32}, image CRC {=u32:#010x}: {}",
        name,
        valid.slot,
        major,
        minor,
        patch,
        valid.header.sequence,
        valid.header.image_crc,
        if fault.is_none() { "intact" } else { "fault mode" }
    );
    if let Some(f) = fault {
        defmt::error!(
            "program image check failed ({}): fault mode, outputs at their safe levels",
            f
        );
    }
}

/// A slot that passed its check at start-up or at a commit but does not
/// load now (refusal `code`, `firmware::update`): the built-in program
/// runs.
#[cfg(feature = "field-update")]
pub fn slot_refused(slot: field_update::slot::Slot, code: u16) {
    defmt::error!(
        "slot {} does not load (code {=u16:#x}): the built-in program runs",
        slot,
        code
    );
}

/// A committed load's outcome.
#[cfg(feature = "field-update")]
pub fn load(outcome: &field_update::loader::Outcome) {
    match outcome {
        field_update::loader::Outcome::Switched(v) => defmt::info!(
            "field update: slot {} written (sequence {=u32}, image CRC {=u32:#010x}); the next scan runs it",
            v.slot,
            v.header.sequence,
            v.header.image_crc
        ),
        field_update::loader::Outcome::Refused(r) => {
            defmt::warn!("field update: load refused: {}", r)
        }
    }
}
