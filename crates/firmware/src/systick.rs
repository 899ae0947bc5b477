//! The millisecond clock of every board: SysTick (in every Cortex-M core)
//! interrupts at 1 kHz and counts into a `u32` (wrapping after 49.7 days,
//! which the executor handles) shared through a critical section. It also
//! stamps every defmt log line.

use core::cell::Cell;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;
use cortex_m_rt::exception;
use critical_section::Mutex;
#[cfg(feature = "field-update")]
use firmware::pause::Pause;

/// Milliseconds since [`start`].
static MILLIS: Mutex<Cell<u32>> = Mutex::new(Cell::new(0));

defmt::timestamp!("{=u32:ms}", now_ms());

/// Starts the 1 kHz tick from the core clock at `sysclk_hz` (one
/// millisecond of cycles must fit SysTick's 24-bit reload).
pub fn start(mut syst: SYST, sysclk_hz: u32) {
    let reload = sysclk_hz / 1_000 - 1;
    assert!(reload < 1 << 24, "SysTick reload out of range");
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(reload);
    syst.clear_current();
    syst.enable_interrupt();
    syst.enable_counter();
}

/// Milliseconds since [`start`] (wrapping).
pub fn now_ms() -> u32 {
    critical_section::with(|cs| MILLIS.borrow(cs).get())
}

/// Runs `pause`, work that blocks the tick for longer than a millisecond
/// (a flash erase or write: interrupts masked, or the core stalled on a
/// flash fetch, so the SysTick handler cannot run and the ticks missed
/// are lost), then adds the milliseconds it lasted beyond those the tick
/// counted, as `timer` measured them (`ticks_per_ms` a millisecond; the
/// pause shorter than its period; `firmware::pause`). The clock stays
/// true: the executor sees the pause as the time it was (periods
/// skipped, an overrun).
#[cfg(feature = "field-update")]
pub fn across<R>(timer: impl Fn() -> u32, ticks_per_ms: u32, pause: impl FnOnce() -> R) -> R {
    let (start_ms, start_ticks) = (now_ms(), timer());
    let result = pause();
    let end_ticks = timer();
    critical_section::with(|cs| {
        let millis = MILLIS.borrow(cs);
        let missed = Pause {
            start_ms,
            end_ms: millis.get(),
            start_ticks,
            end_ticks,
            ticks_per_ms,
        }
        .missed_ms();
        millis.set(millis.get().wrapping_add(missed));
    });
    result
}

#[exception]
fn SysTick() {
    critical_section::with(|cs| {
        let millis = MILLIS.borrow(cs);
        millis.set(millis.get().wrapping_add(1));
    });
}
