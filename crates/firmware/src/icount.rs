//! Instruction counts in QEMU (the replay harness, the guard benchmark):
//! under `-icount shift=9` one instruction takes 512 ns and SysTick, on
//! the 25 MHz core clock of mps2-an386, advances 12.8 ticks per
//! instruction.

/// Instructions for `ticks` SysTick ticks (× 5 / 64), rounded to nearest,
/// without overflow for any `ticks`.
pub fn instructions(ticks: u32) -> u32 {
    ticks / 64 * 5 + (ticks % 64 * 5 + 32) / 64
}

/// Ticks elapsed between two readings of the 24-bit down-counter.
pub fn elapsed(before: u32, after: u32) -> u32 {
    before.wrapping_sub(after) & 0x00ff_ffff
}

/// The `k`-th smallest of `samples` (from 0; the largest when `k` is past
/// the end; 0 when there are none), found by bisection on the value: 32
/// counting passes, no sort. The harnesses' percentiles: `core`'s sort
/// would add about 5.6 KB to every harness's flash figure.
pub fn kth_smallest(samples: &[u32], k: usize) -> u32 {
    if samples.is_empty() {
        return 0;
    }
    let k = k.min(samples.len() - 1);
    let (mut low, mut high) = (0u32, u32::MAX);
    while low < high {
        let mid = low + (high - low) / 2;
        if samples.iter().filter(|&&s| s <= mid).count() > k {
            high = mid;
        } else {
            low = mid + 1;
        }
    }
    low
}

/// Starts SysTick as the instruction counter (core clock, the whole
/// 24-bit range) and returns the ticks that reading it twice costs, which
/// every sample subtracts.
#[cfg(any(feature = "qemu", feature = "guard-bench"))]
pub fn start(syst: &mut cortex_m::peripheral::SYST) -> u32 {
    use cortex_m::peripheral::{syst::SystClkSource, SYST};
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(0x00ff_ffff);
    syst.clear_current();
    syst.enable_counter();
    let a = SYST::get_current();
    let b = SYST::get_current();
    elapsed(a, b)
}

/// Ends a QEMU run with `code` (semihosting exit); on a debugger without
/// semihosting exit, parks.
#[cfg(any(feature = "qemu", feature = "guard-bench"))]
pub fn exit(code: cortex_m_semihosting::debug::ExitStatus) -> ! {
    cortex_m_semihosting::debug::exit(code);
    loop {
        cortex_m::asm::wfi();
    }
}

/// Ends a QEMU run: exit code 0 when `success`, 1 otherwise.
#[cfg(any(feature = "qemu", feature = "guard-bench"))]
pub fn finish(success: bool) -> ! {
    use cortex_m_semihosting::debug;
    exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_become_instructions_and_wrap() {
        assert_eq!(instructions(64), 5);
        assert_eq!(instructions(13), 1);
        assert_eq!(instructions(u32::MAX), 335_544_320);
        assert_eq!(elapsed(10, 4), 6);
        assert_eq!(elapsed(4, 0x00ff_fffe), 6);
    }

    #[test]
    fn the_kth_smallest_is_the_sorted_samples_kth() {
        let mut state = 0x2545_f491u32;
        for len in [1usize, 2, 3, 10, 101, 1000] {
            let samples: Vec<u32> = (0..len)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 17;
                    state ^= state << 5;
                    // Repeats and the ends of the range too.
                    match state % 7 {
                        0 => 0,
                        1 => u32::MAX,
                        2 => 42,
                        _ => state % 5000,
                    }
                })
                .collect();
            let mut sorted = samples.clone();
            sorted.sort_unstable();
            for (k, &expected) in sorted.iter().enumerate() {
                assert_eq!(kth_smallest(&samples, k), expected, "len {len}, k {k}");
            }
            assert_eq!(kth_smallest(&samples, len), sorted[len - 1]);
        }
        assert_eq!(kth_smallest(&[], 0), 0);
    }
}
