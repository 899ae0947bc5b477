//! Clocks: a fixed 100 MHz system clock from the PLL, fed by the
//! ST-LINK's 8 MHz clock on PH0 (HSE bypass, the Nucleo-F411RE's default)
//! when it is there, else by the internal 16 MHz RC oscillator (HSI,
//! ±1 %: plenty for millisecond scans).
//!
//! The configuration is fixed and set register by register (RM0383 §6,
//! §3.4, §5.4) rather than searched for by the HAL's `Rcc::freeze`, whose
//! PLL and I2S PLL search and 64-bit divisions cost about 3 KB of flash
//! (`cargo xtask size`):
//!
//! | | HSE 8 MHz | HSI 16 MHz |
//! |---|---|---|
//! | PLLM (VCO input 2 MHz) | 4 | 8 |
//! | PLLN (VCO 200 MHz) | 100 | 100 |
//! | PLLP (SYSCLK 100 MHz) | 2 | 2 |
//! | PLLQ (PLL48CK 40 MHz, unused: no USB) | 5 | 5 |
//!
//! AHB 100 MHz (/1), APB1 50 MHz (/2, its maximum), APB2 100 MHz (/1);
//! the regulator at scale 1 (up to 100 MHz); 3 flash wait states (90–100
//! MHz at 2.7–3.6 V) with prefetch and both caches on.

use stm32f4xx_hal::pac::{DBGMCU, FLASH, PWR, RCC};
use stm32f4xx_hal::rcc::{Rcc, RccExt};

/// The system clock.
pub const SYSCLK_HZ: u32 = 100_000_000;

/// PLLM for each source: a 2 MHz VCO input.
const PLLM_HSE: u8 = 4;
const PLLM_HSI: u8 = 8;
/// PLLN: a 200 MHz VCO.
const PLLN: u16 = 100;
/// PLLQ: 40 MHz on the (unused) 48 MHz domain, within its 75 MHz limit.
const PLLQ: u8 = 5;

const _: () = assert!(8_000_000 / PLLM_HSE as u32 * PLLN as u32 / 2 == SYSCLK_HZ);
const _: () = assert!(16_000_000 / PLLM_HSI as u32 * PLLN as u32 / 2 == SYSCLK_HZ);

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
/// not.
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
/// else from HSI. The HAL's `Rcc` (for the GPIO and SYSCFG clock enables)
/// is taken with `constrain`, which configures nothing.
pub fn init(rcc: RCC, pwr: &PWR, flash: &FLASH) -> (Rcc, Source) {
    let source = if hse_present(&rcc) {
        Source::Hse
    } else {
        Source::Hsi
    };
    // Regulator scale 1 (the reset value, scale 2, allows 84 MHz).
    rcc.apb1enr().modify(|_, w| w.pwren().set_bit());
    pwr.cr().modify(|_, w| w.vos().scale1());
    // Wait states before the clock rises.
    flash.acr().modify(|_, w| {
        w.latency().ws3();
        w.prften().set_bit();
        w.icen().set_bit();
        w.dcen().set_bit()
    });
    let pllm = match source {
        Source::Hse => PLLM_HSE,
        Source::Hsi => PLLM_HSI,
    };
    // SAFETY: PLLM 4 or 8, PLLN 100 and PLLQ 5 are within the fields'
    // ranges (2–63, 50–432, 2–15) and give the clocks above.
    #[allow(unsafe_code)]
    rcc.pllcfgr().write(|w| unsafe {
        match source {
            Source::Hse => w.pllsrc().hse(),
            Source::Hsi => w.pllsrc().hsi(),
        };
        w.pllm().bits(pllm);
        w.plln().bits(PLLN);
        w.pllp().div2();
        w.pllq().bits(PLLQ)
    });
    rcc.cfgr().modify(|_, w| {
        w.hpre().div1();
        w.ppre1().div2();
        w.ppre2().div1()
    });
    rcc.cr().modify(|_, w| w.pllon().set_bit());
    while rcc.cr().read().pllrdy().bit_is_clear() {}
    rcc.cfgr().modify(|_, w| w.sw().pll());
    while !rcc.cfgr().read().sws().is_pll() {}
    (rcc.constrain(), source)
}

/// Keeps the debug port usable while the core sleeps in `wfi` between
/// scans, so the probe can still read the defmt log over RTT: debug in
/// sleep mode on, and the DMA1 clock on (without a bus master clocked, the
/// STM32F4's AHB matrix stops in sleep and the probe reads garbage).
pub fn keep_debug_in_sleep(dbgmcu: &DBGMCU, rcc: &mut Rcc) {
    dbgmcu.cr().modify(|_, w| w.dbg_sleep().set_bit());
    rcc.ahb1enr().modify(|_, w| w.dma1en().set_bit());
}
