//! Board support for the RP2040 (Raspberry Pi Pico), rp2040-hal: what the
//! scan loop (`crate::scan`) needs and nothing else. No control logic.
//!
//! - clocks: 125 MHz system clock from the Pico's 12 MHz crystal (XOSC)
//!   through PLL_SYS (`rp2040_hal::clocks::init_clocks_and_plls`);
//! - [`pins`]: GPIO from the generated pin map (`program::board`);
//! - [`edges`]: the edge latch, IO_BANK0 edge interrupts on every
//!   edge-latched input (one per GPIO, no shared lines);
//! - the watchdog (`rp2040_hal::Watchdog`, at most 8.3 s) and the reset
//!   cause;
//! - the millisecond clock is `crate::systick`, scan durations the 1 MHz
//!   TIMER (the Cortex-M0+ has no cycle counter);
//! - [`BOOT2`], the second-stage bootloader (W25Q080 family, which the
//!   Pico's W25Q16JV flash belongs to), which the boot ROM runs from the
//!   flash's first 256 bytes (`layout/rp2040.x`);
//! - with feature `field-update`: [`flash`], the program slots in the
//!   flash's last 256 KiB, and [`serial`], the link on UART0.

pub mod edges;
#[cfg(feature = "field-update")]
pub mod flash;
pub mod pins;
#[cfg(feature = "field-update")]
pub mod serial;

use crate::scan::{Board, Changes, ResetCause, Startup};
use crate::systick;
use executor::image::TableCrc;
use firmware::program::INPUT_WORDS;
use fugit::MicrosDurationU32;
use rp2040_hal::clocks::{init_clocks_and_plls, Clock};
use rp2040_hal::pac;
use rp2040_hal::{Sio, Timer, Watchdog};

/// The second-stage bootloader for the W25Q080 family of QSPI flash (the
/// Pico's W25Q16JV is one, and the Pico SDK's board file picks the same
/// bootloader for it): the boot ROM copies these 256 bytes (the `.boot2` section, placed at the start
/// of flash by `layout/rp2040.x`) to SRAM, checks their CRC and runs them
/// to set up execute-in-place.
#[allow(unsafe_code)] // `link_section` places the bytes; nothing unsafe runs.
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XOSC_HZ: u32 = 12_000_000;

/// The Raspberry Pi Pico, set up.
pub struct Pico {
    io: pins::Io,
    timer: Timer,
    watchdog: Watchdog,
    /// Whether [`Board::start_watchdog`] started it (an erase widens a
    /// running watchdog only).
    #[cfg(feature = "field-update")]
    watchdog_started: bool,
    #[cfg(feature = "field-update")]
    port: serial::Port,
}

/// Why the chip started: the watchdog's REASON (its timer, or a forced
/// reset), else the chip-level reset flags (power-on, the RUN pin, the
/// debugger's restart).
fn last_reset(watchdog: &pac::WATCHDOG, chip: &pac::VREG_AND_CHIP_RESET) -> ResetCause {
    let reason = watchdog.reason().read();
    let flags = chip.chip_reset().read();
    if reason.timer().bit_is_set() {
        ResetCause::Watchdog
    } else if reason.force().bit_is_set() || flags.had_psm_restart().bit_is_set() {
        ResetCause::Software
    } else if flags.had_run().bit_is_set() {
        ResetCause::Pin
    } else {
        ResetCause::PowerOn
    }
}

/// Sets the chip up: clocks, pins, edge latch, millisecond clock, timer.
/// The watchdog starts later, in [`Board::start_watchdog`]. The image CRC
/// is computed in software: the RP2040 has no CRC unit of the image's
/// algorithm outside its DMA sniffer.
pub fn init() -> (Pico, Startup, TableCrc) {
    let (Some(mut dp), Some(cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        defmt::panic!("peripherals taken twice");
    };
    let reset = last_reset(&dp.WATCHDOG, &dp.VREG_AND_CHIP_RESET);
    let mut watchdog = Watchdog::new(dp.WATCHDOG);
    let Ok(clocks) = init_clocks_and_plls(
        XOSC_HZ,
        dp.XOSC,
        dp.CLOCKS,
        dp.PLL_SYS,
        dp.PLL_USB,
        &mut dp.RESETS,
        &mut watchdog,
    ) else {
        defmt::panic!("the clocks did not start (12 MHz crystal, PLLs)");
    };
    let sysclk_hz = clocks.system_clock.freq().to_Hz();

    let sio = Sio::new(dp.SIO);
    let bank =
        rp2040_hal::gpio::Pins::new(dp.IO_BANK0, dp.PADS_BANK0, sio.gpio_bank0, &mut dp.RESETS);
    #[cfg_attr(not(feature = "field-update"), allow(clippy::let_unit_value))]
    let (io, link) = pins::configure(bank);
    edges::start(&io);
    #[cfg(feature = "field-update")]
    let port = serial::start(
        dp.UART0,
        link,
        &mut dp.RESETS,
        clocks.peripheral_clock.freq().to_Hz(),
    );
    #[cfg(not(feature = "field-update"))]
    let () = link;

    let timer = Timer::new(dp.TIMER, &mut dp.RESETS, &clocks);
    systick::start(cp.SYST, sysclk_hz);

    let board = Pico {
        io,
        timer,
        watchdog,
        #[cfg(feature = "field-update")]
        watchdog_started: false,
        #[cfg(feature = "field-update")]
        port,
    };
    let startup = Startup {
        reset,
        sysclk_hz,
        clock_source: "Xosc",
    };
    (board, startup, TableCrc)
}

#[cfg(feature = "field-update")]
impl crate::field::UpdateBoard for Pico {
    type Slots<'a> = flash::FlashSlots<'a>;
    type Tx = rp2040_hal::uart::Writer<pac::UART0, serial::LinkPins>;

    fn update_parts(&mut self, watchdog_ms: u32) -> (flash::FlashSlots<'_>, &mut serial::Port) {
        let watchdog = self.watchdog_started.then_some(&mut self.watchdog);
        let slots = flash::FlashSlots::new(watchdog, watchdog_ms, self.timer);
        (slots, &mut self.port)
    }

    fn slot_words(slot: field_update::slot::Slot) -> &'static [u32] {
        flash::words(slot)
    }

    fn set_watchdog_timeout(&mut self, timeout_ms: u32) {
        if self.watchdog_started {
            self.watchdog.start(MicrosDurationU32::millis(timeout_ms));
        }
    }
}

impl Board for Pico {
    type Input = pins::InputPin;
    type Output = pins::OutputPin;
    const TIMER_TICKS_PER_US: u32 = 1;

    fn pins(&mut self) -> &mut pins::Io {
        &mut self.io
    }

    fn now_ms(&self) -> u32 {
        systick::now_ms()
    }

    fn timer(&self) -> u32 {
        self.timer.get_counter_low()
    }

    fn start_watchdog(&mut self, timeout_ms: u32) {
        self.watchdog.pause_on_debug(true);
        self.watchdog.start(MicrosDurationU32::millis(timeout_ms));
        #[cfg(feature = "field-update")]
        {
            self.watchdog_started = true;
        }
    }

    fn feed_watchdog(&mut self) {
        self.watchdog.feed();
    }

    fn sample(&mut self) -> ([u32; INPUT_WORDS], Changes) {
        edges::sample(&mut self.io)
    }
}
