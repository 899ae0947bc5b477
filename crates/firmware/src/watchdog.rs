//! The independent watchdog's timeout for a scan period (the board code
//! that starts and feeds it is `board::watchdog` in the firmware binary).
//! When scans start is the executor's rule (`executor::pacing`).

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
