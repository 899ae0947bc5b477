//! Timers: deadlines on a wrapping millisecond clock.

/// The timer presets the executor runs (ms): below 2^31, so that a
/// deadline compared by wrapping difference on the 32-bit clock is never
/// mistaken for one in the past. The image check, the project validation
/// and the IEC export use this range.
pub const PRESET_MS: core::ops::RangeInclusive<u32> = 1..=(1 << 31) - 1;

/// `true` when `deadline` has been reached at `now`, comparing on the
/// wrapping 32-bit clock (valid while presets stay below 2^31 ms).
#[inline]
pub(crate) fn due(deadline: u32, now: u32) -> bool {
    (now.wrapping_sub(deadline) as i32) >= 0
}

/// The earliest deadline of the running timers, `None` when none runs.
/// Every running deadline must lie after `now` (less than 2^31 ms ahead):
/// they are compared by their distance from `now`.
pub(crate) fn earliest(running: &[bool], deadlines: &[u32], now: u32) -> Option<u32> {
    running
        .iter()
        .zip(deadlines)
        .filter(|(&on, _)| on)
        .map(|(_, &deadline)| deadline)
        .min_by_key(|deadline| deadline.wrapping_sub(now))
}

#[cfg(test)]
mod tests {
    use super::{due, earliest};

    #[test]
    fn deadlines_compare_across_the_wrap() {
        assert!(due(100, 100));
        assert!(due(100, 101));
        assert!(!due(100, 99));
        let deadline = 5u32; // started at u32::MAX - 4 with preset 10
        assert!(!due(deadline, u32::MAX));
        assert!(!due(deadline, 4));
        assert!(due(deadline, 5));
    }
    #[test]
    fn the_earliest_deadline_is_the_nearest_after_now_across_the_wrap() {
        let now = u32::MAX - 10;
        // 15 ms ahead (past the wrap), 9 ms ahead, and a stopped timer.
        let deadlines = [4, u32::MAX - 1, now.wrapping_add(1)];
        assert_eq!(
            earliest(&[true, true, false], &deadlines, now),
            Some(u32::MAX - 1)
        );
        assert_eq!(earliest(&[true, false, false], &deadlines, now), Some(4));
        assert_eq!(earliest(&[false; 3], &deadlines, now), None);
    }
}
