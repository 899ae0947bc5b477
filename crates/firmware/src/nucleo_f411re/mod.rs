//! Board support for the STM32F411 (Nucleo-F411RE), stm32f4xx-hal: what
//! the scan loop (`crate::scan`) needs and nothing else. No control logic.
//!
//! - [`clocks`]: a fixed 100 MHz from the ST-LINK's 8 MHz clock or the
//!   HSI;
//! - [`pins`]: GPIO from the generated pin map (`program::board`);
//! - [`edges`]: EXTI change counting for lost-edge detection (the edge
//!   latch);
//! - [`watchdog`]: the IWDG and the reset cause;
//! - the millisecond clock is `crate::systick`, scan durations the DWT
//!   cycle counter.

pub mod clocks;
pub mod edges;
pub mod pins;
pub mod watchdog;

use crate::scan::{Board, Changes, Startup};
use crate::systick;
use firmware::program::INPUT_WORDS;
use stm32f4xx_hal::gpio::{ErasedPin, GpioExt, Input, Output, PushPull};
use stm32f4xx_hal::pac;
use stm32f4xx_hal::pac::{DBGMCU, IWDG};
use stm32f4xx_hal::syscfg::SysCfgExt;
use stm32f4xx_hal::watchdog::IndependentWatchdog;

/// The Nucleo-F411RE, set up.
pub struct Nucleo {
    io: pins::Io,
    iwdg: Option<IWDG>,
    dbgmcu: DBGMCU,
    watchdog: Option<IndependentWatchdog>,
}

/// Sets the chip up: clocks, pins, edge latch, millisecond clock, cycle
/// counter. The watchdog starts later, in [`Board::start_watchdog`].
pub fn init() -> (Nucleo, Startup) {
    let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        defmt::panic!("peripherals taken twice");
    };
    let reset = watchdog::last_reset(&dp.RCC);
    let (mut rcc, source) = clocks::init(dp.RCC, &dp.PWR, &dp.FLASH);
    clocks::keep_debug_in_sleep(&dp.DBGMCU, &mut rcc);

    let mut syscfg = dp.SYSCFG.constrain(&mut rcc);
    let mut exti = dp.EXTI;
    let mut io = pins::configure(pins::Ports {
        a: dp.GPIOA.split(&mut rcc),
        b: dp.GPIOB.split(&mut rcc),
        c: dp.GPIOC.split(&mut rcc),
        d: dp.GPIOD.split(&mut rcc),
        e: dp.GPIOE.split(&mut rcc),
        h: dp.GPIOH.split(&mut rcc),
    });
    pins::latch_edges(&mut io, &mut syscfg, &mut exti);
    edges::start(exti);

    // Scan times for the status line, from the cycle counter.
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();
    let sysclk_hz = clocks::SYSCLK_HZ;
    systick::start(cp.SYST, sysclk_hz);

    let board = Nucleo {
        io,
        iwdg: Some(dp.IWDG),
        dbgmcu: dp.DBGMCU,
        watchdog: None,
    };
    let startup = Startup {
        reset,
        sysclk_hz,
        clock_source: source.name(),
    };
    (board, startup)
}

impl Board for Nucleo {
    type Input = ErasedPin<Input>;
    type Output = ErasedPin<Output<PushPull>>;
    const TIMER_TICKS_PER_US: u32 = clocks::SYSCLK_HZ / 1_000_000;

    fn pins(&mut self) -> &mut pins::Io {
        &mut self.io
    }

    fn now_ms(&self) -> u32 {
        systick::now_ms()
    }

    fn timer(&self) -> u32 {
        cortex_m::peripheral::DWT::cycle_count()
    }

    fn start_watchdog(&mut self, timeout_ms: u32) {
        if let Some(iwdg) = self.iwdg.take() {
            self.watchdog = Some(watchdog::start(iwdg, &self.dbgmcu, timeout_ms));
        }
    }

    fn feed_watchdog(&mut self) {
        if let Some(w) = &mut self.watchdog {
            w.feed();
        }
    }

    fn sample(&mut self) -> ([u32; INPUT_WORDS], Changes) {
        edges::sample(&mut self.io)
    }
}
