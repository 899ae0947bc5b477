//! Scan pacing (docs/semantics.md, "Scan pacing": `Overrun`): scans are due every
//! `scan_period_ms` on a fixed grid, and a scan that starts more than
//! `overrun_limit` periods after its deadline is an overrun.
//!
//! Times are the board's millisecond clock (`u32`, wrapping); every
//! comparison is wrap-safe (a difference read as `i32`), so the schedule
//! runs through the 49.7-day wrap like any other millisecond.
//!
//! A late scan does not make the schedule catch up with a burst of scans
//! at the same instant (they would all sample the same inputs): the
//! periods it missed are skipped and the grid keeps its phase.

/// When a due scan starts and how late it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScanStart {
    /// The scan's time `t` (ms): when it was found due.
    pub time_ms: u32,
    /// How long after its deadline it starts (ms).
    pub late_ms: u32,
    /// Whole periods skipped because the scan was that late.
    pub skipped: u32,
    /// Late by more than `overrun_limit` periods.
    pub overrun: bool,
}

/// A fixed-rate schedule: a deadline every `period_ms`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pacer {
    period_ms: u32,
    limit_ms: u64,
    deadline: u32,
}

impl Pacer {
    /// A schedule whose first deadline is `first_ms`, then every
    /// `period_ms`; a start more than `overrun_limit × period_ms` late is an
    /// overrun (`overrun_limit = 0`: any lateness).
    ///
    /// # Panics
    ///
    /// When `period_ms` is 0 or not below 2^31 (validation guarantees
    /// `1..2^31` for `scan_period_ms`).
    pub const fn new(first_ms: u32, period_ms: u32, overrun_limit: u16) -> Pacer {
        assert!(
            period_ms > 0 && period_ms < 1 << 31,
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

    /// `Some` when a scan is due at `now_ms` (the deadline has passed); the
    /// schedule then moves to the next deadline after `now_ms`. `None`
    /// before the deadline. A start more than 2^31 ms late looks early (the
    /// watchdog has long reset the board by then).
    pub fn poll(&mut self, now_ms: u32) -> Option<ScanStart> {
        let late = now_ms.wrapping_sub(self.deadline);
        if late >= 1 << 31 {
            return None;
        }
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

/// The independent watchdog's timeout for a scan period: four periods, at
/// least 50 ms (so a 1 ms scan tolerates a slow log line).
pub const fn watchdog_timeout_ms(scan_period_ms: u32) -> u32 {
    let four = scan_period_ms.saturating_mul(4);
    if four < 50 {
        50
    } else {
        four
    }
}

/// The longest timeout the STM32's independent watchdog can count (LSI
/// 32 kHz, prescaler 256, 12-bit reload; the HAL refuses 32 768 ms and
/// more). `[board]` validation keeps scan periods at or below 8 s, so
/// [`watchdog_timeout_ms`] stays at or below 32 000 ms.
pub const WATCHDOG_MAX_MS: u32 = 32_767;

#[cfg(test)]
mod tests {
    use super::*;

    fn start(p: &mut Pacer, now: u32) -> Option<(u32, u32, bool)> {
        p.poll(now).map(|s| (s.late_ms, s.skipped, s.overrun))
    }

    #[test]
    fn scans_are_due_on_a_fixed_grid() {
        let mut p = Pacer::new(100, 10, 1);
        assert_eq!(start(&mut p, 99), None);
        assert_eq!(start(&mut p, 100), Some((0, 0, false)));
        assert_eq!(p.deadline(), 110);
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

    #[test]
    fn the_schedule_runs_through_the_clock_wrap() {
        let mut p = Pacer::new(u32::MAX - 14, 10, 1);
        assert_eq!(start(&mut p, u32::MAX - 14), Some((0, 0, false)));
        assert_eq!(p.deadline(), u32::MAX - 4);
        assert_eq!(start(&mut p, u32::MAX - 5), None);
        assert_eq!(start(&mut p, u32::MAX - 4), Some((0, 0, false)));
        assert_eq!(p.deadline(), 5);
        // Wrapped past zero, still before the deadline.
        assert_eq!(start(&mut p, 2), None);
        assert_eq!(start(&mut p, 7), Some((2, 0, false)));
        assert_eq!(p.deadline(), 15);
    }

    #[test]
    fn huge_limits_and_periods_do_not_overflow() {
        let period = (1 << 31) - 1;
        let mut p = Pacer::new(0, period, u16::MAX);
        assert_eq!(start(&mut p, 0), Some((0, 0, false)));
        assert_eq!(p.deadline(), period);
        assert_eq!(start(&mut p, period + 5), Some((5, 0, false)));
    }

    #[test]
    #[should_panic(expected = "the period must be in 1..2^31 ms")]
    fn a_zero_period_is_refused() {
        let _ = Pacer::new(0, 0, 1);
    }

    #[test]
    fn the_watchdog_waits_four_periods_and_at_least_50_ms() {
        assert_eq!(watchdog_timeout_ms(1), 50);
        assert_eq!(watchdog_timeout_ms(10), 50);
        assert_eq!(watchdog_timeout_ms(13), 52);
        assert_eq!(watchdog_timeout_ms(100), 400);
        assert_eq!(watchdog_timeout_ms(8000), 32_000);
        assert!(watchdog_timeout_ms(8000) <= WATCHDOG_MAX_MS);
        assert_eq!(watchdog_timeout_ms(u32::MAX), u32::MAX);
    }
}
