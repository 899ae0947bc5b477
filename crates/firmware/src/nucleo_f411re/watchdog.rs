//! The independent watchdog (IWDG, on its own 32 kHz LSI clock): the scan
//! loop feeds it once per completed scan; a loop that stops scanning
//! resets the chip, and the next start-up logs why it reset.

use crate::scan::ResetCause;
use stm32f4xx_hal::pac::{DBGMCU, IWDG, RCC};
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::watchdog::IndependentWatchdog;

/// Starts the watchdog with `timeout_ms` (at most
/// `MCU.watchdog.max_timeout_ms`, 32 767 ms: the board data's
/// `boards::Watchdog`, which also gives the timeout for a scan period);
/// it is frozen while a debugger halts the core, so a breakpoint does not
/// reset the board.
pub fn start(iwdg: IWDG, dbgmcu: &DBGMCU, timeout_ms: u32) -> IndependentWatchdog {
    let mut watchdog = IndependentWatchdog::new(iwdg);
    watchdog.stop_on_debug(dbgmcu, true);
    watchdog.start(timeout_ms.millis());
    watchdog
}

/// Reads why the chip reset and clears the flags for the next time.
pub fn last_reset(rcc: &RCC) -> ResetCause {
    let csr = rcc.csr().read();
    let cause = if csr.wdgrstf().bit_is_set() {
        ResetCause::Watchdog
    } else if csr.wwdgrstf().bit_is_set() {
        ResetCause::WindowWatchdog
    } else if csr.sftrstf().bit_is_set() {
        ResetCause::Software
    } else if csr.lpwrrstf().bit_is_set() {
        ResetCause::LowPower
    } else if csr.porrstf().bit_is_set() || csr.borrstf().bit_is_set() {
        ResetCause::PowerOn
    } else {
        ResetCause::Pin
    };
    rcc.csr().modify(|_, w| w.rmvf().set_bit());
    cause
}
