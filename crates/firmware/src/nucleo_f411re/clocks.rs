//! Clocks: a 100 MHz system clock from the PLL, fed by the ST-LINK's
//! 8 MHz clock on PH0 (HSE bypass, the Nucleo-F411RE's default) when it is
//! there, else by the internal 16 MHz RC oscillator (HSI, ±1 %: plenty for
//! millisecond scans).

use stm32f4xx_hal::pac::{DBGMCU, RCC};
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::rcc::{Config, Rcc};

/// The system clock.
pub const SYSCLK_HZ: u32 = 100_000_000;

/// The ST-LINK's clock output (MCO) on PH0.
const HSE_HZ: u32 = 8_000_000;

/// Where the PLL's input comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The 8 MHz ST-LINK clock on PH0 (HSE bypass).
    Hse,
    /// The internal 16 MHz RC oscillator.
    Hsi,
}

impl Source {
    /// Its name in the start-up line.
    pub fn name(self) -> &'static str {
        match self {
            Source::Hse => "Hse",
            Source::Hsi => "Hsi",
        }
    }
}

/// Whether an external clock drives PH0: HSE in bypass mode becomes ready
/// within a few of its cycles when it does. Leaves HSE off when it does
/// not (`freeze` would wait for it forever).
fn hse_present(rcc: &RCC) -> bool {
    // HSEBYP may only change while HSE is off, as it is after reset.
    rcc.cr().modify(|_, w| w.hsebyp().set_bit());
    rcc.cr().modify(|_, w| w.hseon().set_bit());
    // A few milliseconds at the 16 MHz HSI clock the core runs on now.
    let ready = (0..20_000).any(|_| rcc.cr().read().hserdy().bit_is_set());
    if !ready {
        rcc.cr().modify(|_, w| w.hseon().clear_bit());
        rcc.cr().modify(|_, w| w.hsebyp().clear_bit());
    }
    ready
}

/// Sets the clock tree up: [`SYSCLK_HZ`] from HSE bypass when present,
/// else from HSI.
pub fn init(rcc: RCC) -> (Rcc, Source) {
    let source = if hse_present(&rcc) {
        Source::Hse
    } else {
        Source::Hsi
    };
    let config = match source {
        Source::Hse => Config::hse(HSE_HZ.Hz()).bypass_hse_oscillator(),
        Source::Hsi => Config::hsi(),
    };
    let rcc = rcc.freeze(config.sysclk(SYSCLK_HZ.Hz()));
    (rcc, source)
}

/// Keeps the debug port usable while the core sleeps in `wfi` between
/// scans, so the probe can still read the defmt log over RTT: debug in
/// sleep mode on, and the DMA1 clock on (without a bus master clocked, the
/// STM32F4's AHB matrix stops in sleep and the probe reads garbage).
pub fn keep_debug_in_sleep(dbgmcu: &DBGMCU, rcc: &mut Rcc) {
    dbgmcu.cr().modify(|_, w| w.dbg_sleep().set_bit());
    rcc.ahb1enr().modify(|_, w| w.dma1en().set_bit());
}
