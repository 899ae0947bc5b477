//! Board support for the STM32F411 (Nucleo-F411RE), stm32f4xx-hal: what
//! the scan loop (`crate::scan`) needs and nothing else. No control logic.
//!
//! - [`clocks`]: a fixed 100 MHz from the ST-LINK's 8 MHz clock or the
//!   HSI;
//! - [`pins`]: GPIO from the generated pin map (`program::board`);
//! - [`edges`]: EXTI change counting for lost-edge detection (the edge
//!   latch);
//! - [`watchdog`]: the IWDG and the reset cause;
//! - with feature `field-update`: [`flash`], the program slots in flash
//!   sectors 6 and 7, and [`serial`], the link on USART2;
//! - the millisecond clock is `crate::systick`, scan durations the DWT
//!   cycle counter.

pub mod clocks;
pub mod crc;
pub mod edges;
#[cfg(feature = "field-update")]
pub mod flash;
pub mod pins;
#[cfg(feature = "field-update")]
pub mod serial;
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
    #[cfg(feature = "field-update")]
    flash: pac::FLASH,
    #[cfg(feature = "field-update")]
    port: serial::Port,
}

/// Sets the chip up: clocks, pins, edge latch, millisecond clock, cycle
/// counter, and the CRC unit for the image check. The watchdog starts
/// later, in [`Board::start_watchdog`].
pub fn init() -> (Nucleo, Startup, crc::CrcUnit) {
    let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        defmt::panic!("peripherals taken twice");
    };
    let reset = watchdog::last_reset(&dp.RCC);
    let (mut rcc, source) = clocks::init(dp.RCC, &dp.PWR, &dp.FLASH);
    clocks::keep_debug_in_sleep(&dp.DBGMCU, &mut rcc);

    let crc = crc::CrcUnit::new(stm32f4xx_hal::crc32::Crc32::new(dp.CRC, &mut rcc));
    let mut syscfg = dp.SYSCFG.constrain(&mut rcc);
    let mut exti = dp.EXTI;
    #[cfg_attr(not(feature = "field-update"), allow(clippy::let_unit_value))]
    let (mut io, link) = pins::configure(pins::Ports {
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
        #[cfg(feature = "field-update")]
        flash: dp.FLASH,
        #[cfg(feature = "field-update")]
        port: serial::start(dp.USART2, link.0, link.1, &mut rcc),
    };
    #[cfg(not(feature = "field-update"))]
    let () = link;
    let startup = Startup {
        reset,
        sysclk_hz,
        clock_source: source.name(),
    };
    (board, startup, crc)
}

#[cfg(feature = "field-update")]
impl crate::field::UpdateBoard for Nucleo {
    type Slots<'a> = flash::FlashSlots<'a>;
    type Tx = stm32f4xx_hal::serial::Tx<pac::USART2>;

    fn update_parts(&mut self, watchdog_ms: u32) -> (flash::FlashSlots<'_>, &mut serial::Port) {
        (
            flash::FlashSlots::new(&mut self.flash, self.watchdog.as_mut(), watchdog_ms),
            &mut self.port,
        )
    }

    fn slot_words(slot: field_update::slot::Slot) -> &'static [u32] {
        flash::words(slot)
    }

    fn set_watchdog_timeout(&mut self, timeout_ms: u32) {
        if let Some(w) = &mut self.watchdog {
            w.start(stm32f4xx_hal::prelude::_fugit_ExtU32::millis(timeout_ms));
        }
    }
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
