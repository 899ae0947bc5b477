//! Scan pacing (docs/semantics.md, "Scan pacing"): when scans start, the
//! one rule for the board, QEMU and host-sim.
//!
//! Scans are due on a fixed grid: a deadline at the first time, then every
//! `scan_period_ms`. The caller polls the schedule with its clock
//! ([`Controller::scan_due`](crate::Controller::scan_due), or
//! [`Pacer::poll`]) and a scan starts when it is found due, at its
//! deadline or later. A late scan does not make the schedule catch up with
//! a burst of scans at one instant (they would all sample the same
//! inputs): the deadlines that passed while it waited are skipped and the
//! next deadline is the first grid point after its start, so the grid
//! keeps its phase. A scan that starts more than `overrun_limit × period`
//! after its deadline is an overrun.
//!
//! Times are the controller's millisecond clock (`u32`, wrapping); every
//! comparison is wrap-safe (a difference read as `i32`), so the schedule
//! runs through the 49.7-day wrap like any other millisecond.

use core::ops::RangeInclusive;

use crate::program::Config;

/// The scan periods a program may have (ms): 1 to 2^31 − 1, so that the
/// next deadline is always less than half the millisecond clock away and
/// every comparison with it stays wrap-safe. The one statement of the
/// rule: project validation refuses a period outside it, the image check
/// ([`crate::validate`]) faults on one, and [`Pacer::new`] panics.
///
/// ```
/// use executor::pacing::SCAN_PERIOD_MS;
///
/// assert!(SCAN_PERIOD_MS.contains(&1) && SCAN_PERIOD_MS.contains(&(u32::MAX >> 1)));
/// assert!(!SCAN_PERIOD_MS.contains(&0) && !SCAN_PERIOD_MS.contains(&(1 << 31)));
/// ```
pub const SCAN_PERIOD_MS: RangeInclusive<u32> = 1..=(1 << 31) - 1;

/// When a due scan starts and how late it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScanStart {
    /// The scan's time `t` (ms): when it was found due.
    pub time_ms: u32,
    /// How long after its deadline it starts (ms).
    pub late_ms: u32,
    /// Later deadlines that passed before it started (`late_ms / period`):
    /// the periods skipped.
    pub skipped: u32,
    /// Late by more than `overrun_limit` periods.
    pub overrun: bool,
}

/// A fixed-rate schedule: a deadline every `period_ms`, and the overrun
/// limit the lateness of a scan is judged by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pacer {
    period_ms: u32,
    limit_ms: u64,
    deadline: u32,
}

impl Pacer {
    /// The schedule of a program: every `scan_period_ms` from `first_ms`,
    /// overruns beyond `overrun_limit` periods. Project validation keeps
    /// the period in [`SCAN_PERIOD_MS`]; a corrupt image's period outside
    /// it (which the controller's start-up check refuses: fault mode) is
    /// brought to the nearest end of that range, so that scans go on
    /// writing the safe image instead of the board halting here.
    pub const fn for_config(config: &Config<'_>, first_ms: u32) -> Pacer {
        let (shortest, longest) = (*SCAN_PERIOD_MS.start(), *SCAN_PERIOD_MS.end());
        let period_ms = match config.scan_period_ms {
            p if p < shortest => shortest,
            p if p > longest => longest,
            p => p,
        };
        Pacer::new(first_ms, period_ms, config.overrun_limit)
    }

    /// A schedule whose first deadline is `first_ms`, then every
    /// `period_ms`; a start more than `overrun_limit × period_ms` late is an
    /// overrun (`overrun_limit = 0`: any lateness).
    ///
    /// # Panics
    ///
    /// When `period_ms` is outside [`SCAN_PERIOD_MS`] (0, or not below
    /// 2^31).
    pub const fn new(first_ms: u32, period_ms: u32, overrun_limit: u16) -> Pacer {
        assert!(
            period_ms >= *SCAN_PERIOD_MS.start() && period_ms <= *SCAN_PERIOD_MS.end(),
            "the period must be in 1..2^31 ms"
        );
        Pacer {
            period_ms,
            limit_ms: overrun_limit as u64 * period_ms as u64,
            deadline: first_ms,
        }
    }

    /// The next deadline (ms).
    pub const fn deadline(&self) -> u32 {
        self.deadline
    }

    /// The period (ms).
    pub const fn period_ms(&self) -> u32 {
        self.period_ms
    }

    /// How long a scan may start after its deadline without being an
    /// overrun (ms).
    pub const fn overrun_limit_ms(&self) -> u64 {
        self.limit_ms
    }

    /// Milliseconds from `now_ms` until the next scan is due; 0 when it is
    /// due now (the deadline has passed).
    pub const fn due_in(&self, now_ms: u32) -> u32 {
        let late = now_ms.wrapping_sub(self.deadline);
        if late >= 1 << 31 {
            late.wrapping_neg()
        } else {
            0
        }
    }

    /// `Some` when a scan is due at `now_ms` (the deadline has passed); the
    /// schedule then moves to the first deadline of the grid after
    /// `now_ms`. `None` before the deadline. A start more than 2^31 ms late
    /// looks early (on the board the watchdog has long reset the chip).
    pub fn poll(&mut self, now_ms: u32) -> Option<ScanStart> {
        if self.due_in(now_ms) > 0 {
            return None;
        }
        let late = now_ms.wrapping_sub(self.deadline);
        let skipped = late / self.period_ms;
        // (skipped + 1) × period ≤ late + period < 2^32: no overflow.
        self.deadline = self.deadline.wrapping_add((skipped + 1) * self.period_ms);
        Some(ScanStart {
            time_ms: now_ms,
            late_ms: late,
            skipped,
            overrun: u64::from(late) > self.limit_ms,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn start(p: &mut Pacer, now: u32) -> Option<(u32, u32, bool)> {
        p.poll(now).map(|s| (s.late_ms, s.skipped, s.overrun))
    }

    #[test]
    fn scans_are_due_on_a_fixed_grid() {
        let mut p = Pacer::new(100, 10, 1);
        assert_eq!(p.due_in(99), 1);
        assert_eq!(start(&mut p, 99), None);
        assert_eq!(p.due_in(100), 0);
        assert_eq!(start(&mut p, 100), Some((0, 0, false)));
        assert_eq!(p.deadline(), 110);
        assert_eq!(p.due_in(105), 5);
        assert_eq!(start(&mut p, 105), None);
        // 3 ms late: the next deadline stays on the grid.
        assert_eq!(start(&mut p, 113), Some((3, 0, false)));
        assert_eq!(p.deadline(), 120);
        assert_eq!(p.poll(120).unwrap().time_ms, 120);
    }

    #[test]
    fn more_than_the_limit_late_is_an_overrun_and_missed_periods_are_skipped() {
        let mut p = Pacer::new(0, 10, 1);
        assert!(p.poll(0).is_some());
        // Exactly one period late: not more than the limit.
        assert_eq!(start(&mut p, 20), Some((10, 1, false)));
        assert_eq!(p.deadline(), 30);
        // 11 ms late: overrun; one period skipped.
        assert_eq!(start(&mut p, 41), Some((11, 1, true)));
        assert_eq!(p.deadline(), 50);
        // 3.5 periods late: three skipped, phase kept.
        assert_eq!(start(&mut p, 85), Some((35, 3, true)));
        assert_eq!(p.deadline(), 90);
    }

    #[test]
    fn a_zero_limit_counts_any_lateness() {
        let mut p = Pacer::new(0, 10, 0);
        assert_eq!(start(&mut p, 0), Some((0, 0, false)));
        assert_eq!(start(&mut p, 11), Some((1, 0, true)));
    }

    /// A program without signals, scanned every `scan_period_ms` with an
    /// overrun limit of 3 periods.
    fn paced(scan_period_ms: u32) -> Config<'static> {
        Config {
            name: "paced",
            scan_period_ms,
            max_commands_per_scan: 0,
            unexpected: crate::program::UnexpectedPolicy::Fault,
            reset: None,
            overrun_limit: 3,
            overrun_fault: true,
            lost_edge_fault: false,
            rom_test_bytes_per_scan: 64,
            inputs: &[],
            debounced: &[],
            debounce_mask: crate::program::Span::EMPTY,
            outputs: &[],
            timers: &[],
            events: &[],
            supervisors: &[],
            input_masks: &[],
            event_lists: &[],
            event_masks: &[],
            commands: crate::program::Span::EMPTY,
            requested: crate::program::Span::EMPTY,
            actions: &[],
            memberships: &[],
            state_map: &[],
            guards: crate::program::Guards::NONE,
            allowed_index: &[],
        }
    }

    #[test]
    fn the_limit_and_period_come_from_the_program() {
        let config = paced(20);
        let mut p = Pacer::for_config(&config, 7);
        assert_eq!((p.period_ms(), p.overrun_limit_ms()), (20, 60));
        assert_eq!(start(&mut p, 7), Some((0, 0, false)));
        // 60 ms late is within 3 periods; 61 ms is not.
        assert_eq!(start(&mut p, 87), Some((60, 3, false)));
        assert_eq!(p.deadline(), 107);
        assert_eq!(start(&mut p, 168), Some((61, 3, true)));
    }

    /// Found by the `fuzz_image` target: a corrupt image's period of 0 (or
    /// 2^31 or more) made the board panic here before its first scan.
    #[test]
    fn a_period_out_of_range_is_brought_into_range_not_a_panic() {
        assert_eq!(Pacer::for_config(&paced(0), 0).period_ms(), 1);
        let longest = (1 << 31) - 1;
        assert_eq!(Pacer::for_config(&paced(1 << 31), 0).period_ms(), longest);
        assert_eq!(Pacer::for_config(&paced(u32::MAX), 0).period_ms(), longest);
        assert_eq!(Pacer::for_config(&paced(longest), 0).period_ms(), longest);
    }

    #[test]
    fn the_schedule_runs_through_the_clock_wrap() {
        let mut p = Pacer::new(u32::MAX - 14, 10, 1);
        assert_eq!(start(&mut p, u32::MAX - 14), Some((0, 0, false)));
        assert_eq!(p.deadline(), u32::MAX - 4);
        assert_eq!(start(&mut p, u32::MAX - 5), None);
        assert_eq!(start(&mut p, u32::MAX - 4), Some((0, 0, false)));
        assert_eq!(p.deadline(), 5);
        // Wrapped past zero, still before the deadline.
        assert_eq!(p.due_in(u32::MAX), 6);
        assert_eq!(start(&mut p, 2), None);
        assert_eq!(start(&mut p, 7), Some((2, 0, false)));
        assert_eq!(p.deadline(), 15);
        // Late across the wrap: skipped periods counted, phase kept.
        let mut p = Pacer::new(u32::MAX - 4, 10, 1);
        assert_eq!(start(&mut p, 20), Some((25, 2, true)));
        assert_eq!(p.deadline(), 25);
    }

    #[test]
    fn huge_limits_and_periods_do_not_overflow() {
        let period = (1 << 31) - 1;
        let mut p = Pacer::new(0, period, u16::MAX);
        assert_eq!(start(&mut p, 0), Some((0, 0, false)));
        assert_eq!(p.deadline(), period);
        assert_eq!(p.due_in(0), period);
        assert_eq!(start(&mut p, period + 5), Some((5, 0, false)));
        assert_eq!(
            p.overrun_limit_ms(),
            u64::from(u16::MAX) * u64::from(period)
        );
    }

    #[test]
    fn a_start_more_than_half_the_clock_late_looks_early() {
        let mut p = Pacer::new(0, 10, 1);
        assert_eq!(p.due_in(1 << 31), 1 << 31);
        assert_eq!(start(&mut p, 1 << 31), None);
        assert_eq!(
            start(&mut p, (1 << 31) - 1),
            Some(((1 << 31) - 1, 214_748_364, true))
        );
    }

    #[test]
    #[should_panic(expected = "the period must be in 1..2^31 ms")]
    fn a_zero_period_is_refused() {
        let _ = Pacer::new(0, 0, 1);
    }

    #[test]
    #[should_panic(expected = "the period must be in 1..2^31 ms")]
    fn a_period_of_half_the_clock_is_refused() {
        let _ = Pacer::new(0, 1 << 31, 1);
    }
}
