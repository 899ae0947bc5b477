//! Pin levels and signal values: an active-low pin shows signal 1 as a
//! low level (a button that closes to ground, a relay driver that sinks).

/// The signal an input pin at level `pin_high` carries.
#[inline]
pub const fn signal(pin_high: bool, active_low: bool) -> bool {
    pin_high != active_low
}

/// The level an output pin drives to show `signal`.
#[inline]
pub const fn pin_high(signal: bool, active_low: bool) -> bool {
    signal != active_low
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn active_low_inverts_both_ways() {
        for level in [false, true] {
            assert_eq!(signal(level, false), level);
            assert_eq!(signal(level, true), !level);
            assert_eq!(pin_high(level, false), level);
            assert_eq!(pin_high(level, true), !level);
            // Reading back what was driven gives the signal again.
            assert_eq!(signal(pin_high(level, true), true), level);
        }
    }
}
