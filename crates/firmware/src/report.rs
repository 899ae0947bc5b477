//! What the firmware tells over defmt-rtt (`probe-rs run` prints it with
//! the time stamp of the millisecond clock): start-up (reset cause,
//! clocks, the program image check), every executed and unexpected event
//! by name, fault changes, overruns, lost edges, and every 10 s a status
//! line (scans, counters, states, outputs, scan times).
//!
//! Only what changes is logged per scan, so a quiet plant costs nothing
//! and the log stays readable.

use crate::scan::{ResetCause, Startup};
use executor::memory::Memory;
use executor::pacing::ScanStart;
use executor::program::Index;
use executor::{Controller, Fault, Program, ScanRecord};
use firmware::program::{event, input, supervisor, CONFIG};

/// The name of event `e`.
fn event_name(e: Index) -> &'static str {
    event::NAMES.get(usize::from(e)).copied().unwrap_or("?")
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
pub fn lost_edge(scan: u32, input: usize, count: u8) {
    defmt::warn!(
        "scan {=u32}: lost edge on `{=str}` ({=u8} changes since the last sample)",
        scan,
        input::NAMES.get(input).copied().unwrap_or("?"),
        count
    );
}

/// What scan `record` did, given the fault before it.
pub fn scan(record: &ScanRecord<'_>, before: Option<Fault>) {
    for &e in record.executed {
        defmt::info!("scan {=u32}: {=str}", record.scan, event_name(e));
    }
    for &e in record.unexpected {
        defmt::warn!("scan {=u32}: unexpected {=str}", record.scan, event_name(e));
    }
    match (before, record.fault) {
        (None, Some(fault)) => entered(record, fault),
        (Some(_), None) => defmt::info!(
            "scan {=u32}: reset: controller re-initialised, states {=[?]}",
            record.scan,
            record.states
        ),
        _ => {}
    }
}

fn entered(record: &ScanRecord<'_>, fault: Fault) {
    let until = match CONFIG.reset {
        Some(r) => input::NAMES.get(usize::from(r)).copied().unwrap_or("?"),
        None => "power-on (no reset input)",
    };
    match fault {
        Fault::Unexpected { event } => defmt::error!(
            "scan {=u32}: fault: unexpected {=str} in states {=[?]}; safe outputs until {=str}",
            record.scan,
            event_name(event),
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
pub fn status<P: Program, M: Memory>(
    controller: &Controller<P, M>,
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
