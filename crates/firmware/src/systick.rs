//! The millisecond clock of every board: SysTick (in every Cortex-M core)
//! interrupts at 1 kHz and counts into a `u32` (wrapping after 49.7 days,
//! which the executor handles) shared through a critical section. It also
//! stamps every defmt log line.

use core::cell::Cell;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;
use cortex_m_rt::exception;
use critical_section::Mutex;

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

#[exception]
fn SysTick() {
    critical_section::with(|cs| {
        let millis = MILLIS.borrow(cs);
        millis.set(millis.get().wrapping_add(1));
    });
}
