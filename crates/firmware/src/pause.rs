//! The millisecond clock across a pause that blocks its tick (a flash
//! erase or write: the SysTick handler cannot run, and SysTick keeps one
//! pending tick only): how many milliseconds the tick missed, from a
//! free-running timer read before and after. The board firmware's
//! `systick::across` adds them, so that the executor sees the pause as
//! the time it was.

/// A pause as the millisecond clock and the timer saw it: their readings
/// before and after (both wrapping), and the timer's ticks a millisecond.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pause {
    /// The millisecond clock before the pause.
    pub start_ms: u32,
    /// The millisecond clock after it.
    pub end_ms: u32,
    /// The timer before the pause.
    pub start_ticks: u32,
    /// The timer after it: the pause must be shorter than the timer's
    /// period (2^32 ticks: 42.9 s of the STM32's cycle counter at
    /// 100 MHz, 71.6 min of the Pico's 1 MHz timer).
    pub end_ticks: u32,
    /// Timer ticks a millisecond (non-zero).
    pub ticks_per_ms: u32,
}

impl Pause {
    /// The whole milliseconds the timer measured that the clock did not
    /// count (0 when it counted them all).
    pub const fn missed_ms(&self) -> u32 {
        let elapsed = self.end_ticks.wrapping_sub(self.start_ticks) / self.ticks_per_ms;
        let counted = self.end_ms.wrapping_sub(self.start_ms);
        elapsed.saturating_sub(counted)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clock_gets_what_the_timer_measured_beyond_its_own_ticks() {
        // A 4 s erase on the Pico's 1 MHz timer; the tick ran once after it.
        let erase = Pause {
            start_ms: 1_000,
            end_ms: 1_001,
            start_ticks: 5_000_000,
            end_ticks: 9_000_500,
            ticks_per_ms: 1_000,
        };
        assert_eq!(erase.missed_ms(), 3_999);
        // The STM32's cycle counter (100 MHz) wrapping during the pause,
        // and the clock wrapping too.
        let wrapped = Pause {
            start_ms: u32::MAX - 1,
            end_ms: 0,
            start_ticks: u32::MAX - 50_000_000,
            end_ticks: 150_000_000,
            ticks_per_ms: 100_000,
        };
        assert_eq!(wrapped.missed_ms(), 2_000 - 2);
        // A pause the tick counted in full (or more, the clock's fraction
        // of a millisecond): nothing to add.
        let short = Pause {
            start_ms: 7,
            end_ms: 10,
            start_ticks: 0,
            end_ticks: 2_999,
            ticks_per_ms: 1_000,
        };
        assert_eq!(short.missed_ms(), 0);
    }
}
