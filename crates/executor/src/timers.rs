//! Timers: deadlines on a wrapping millisecond clock.

/// `true` when `deadline` has been reached at `now`, comparing on the
/// wrapping 32-bit clock (valid while presets stay below 2^31 ms).
#[inline]
pub(crate) fn due(deadline: u32, now: u32) -> bool {
    (now.wrapping_sub(deadline) as i32) >= 0
}

#[cfg(test)]
mod tests {
    use super::due;

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
}
