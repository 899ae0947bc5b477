//! The field-update slots in the STM32F411RE's flash (feature
//! `field-update`): sectors 6 and 7 (`firmware::slots::stm32f411re`), erased and
//! programmed through stm32f4xx-hal's `flash` module (the data cache reset
//! after each through the PAC: the HAL does not), read where they are
//! mapped.
//!
//! Erasing a 128 KiB sector stalls the core for 1–4 s (RM0383 and the
//! datasheet: typically 2 s, at most 4 s at the HAL's 8-bit parallelism;
//! every fetch from flash waits, the SysTick handler's too: the
//! millisecond clock is set right after it from the cycle counter,
//! `systick::across`). No scan runs meanwhile: outputs keep
//! the levels the last scan wrote, and the watchdog, whose scan-period
//! timeout would reset the chip, is started again with
//! [`ERASE_WATCHDOG_MS`] just before the erase and with its scan timeout
//! just after. Programming is byte by byte (16 µs a byte at most: 4 ms
//! for a 256-byte `Data` chunk), inside the scan's link share.

use crate::field;
use crate::scan::Board;
use crate::systick;
use cortex_m::peripheral::DWT;
use field_update::protocol::ERASE_MS;
use field_update::slot::{Slot, SlotStore};
use firmware::slots::stm32f411re::{FLASH_ORIGIN, SECTOR_A, SECTOR_B, SLOTS};
use stm32f4xx_hal::flash::{self, FlashExt};
use stm32f4xx_hal::pac::FLASH;
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::watchdog::IndependentWatchdog;

/// The watchdog timeout over a sector erase (ms): twice the longest
/// 128 KiB erase ([`ERASE_MS`], 4 s, which the PC also waits out for
/// `Begin`'s answer), well below the IWDG's 32 s.
pub const ERASE_WATCHDOG_MS: u32 = 2 * ERASE_MS;

/// Cycle-counter ticks a millisecond (the board's scan timer), which
/// keep the millisecond clock true across an erase ([`systick::across`]).
const TICKS_PER_MS: u32 = <super::Nucleo as Board>::TIMER_TICKS_PER_US * 1_000;

/// Words of a slot.
const SLOT_WORDS: usize = SLOTS.words();

/// The two slots: the flash controller, and the watchdog while a sector
/// is erased.
pub struct FlashSlots<'w> {
    flash: &'w mut FLASH,
    watchdog: Option<&'w mut IndependentWatchdog>,
    watchdog_ms: u32,
}

impl<'w> FlashSlots<'w> {
    /// The slots of `flash`; `watchdog` (running with `watchdog_ms`) is
    /// given the erase's timeout while a sector is erased.
    pub fn new(
        flash: &'w mut FLASH,
        watchdog: Option<&'w mut IndependentWatchdog>,
        watchdog_ms: u32,
    ) -> FlashSlots<'w> {
        FlashSlots {
            flash,
            watchdog,
            watchdog_ms,
        }
    }
}

/// The words of `slot` where the flash is mapped.
pub fn words(slot: Slot) -> &'static [u32] {
    // SAFETY: the slot is SLOT_BYTES of the chip's memory-mapped flash
    // (firmware::slots::stm32f411re, checked against the sector map at compile time),
    // word-aligned, always readable, and outside the linker's FLASH region
    // (build.rs), so nothing of the firmware lives there. Its contents
    // change only through `FlashSlots::erase`/`program`, which take the
    // store mutably: the loader never changes the running slot, whose
    // words the running program borrows.
    #[allow(unsafe_code)]
    unsafe {
        core::slice::from_raw_parts(field::address(&SLOTS, slot) as *const u32, SLOT_WORDS)
    }
}

impl FlashSlots<'_> {
    /// Empties the flash's data cache (RM0383 §3.4: it may hold words of
    /// a slot as they were before an erase or a write; the stm32f4xx-hal
    /// does not reset it), so that the loader reads back what the flash
    /// holds. The ART's data cache may be reset only while it is off.
    fn reset_data_cache(&mut self) {
        self.flash.acr().modify(|_, w| w.dcen().clear_bit());
        self.flash.acr().modify(|_, w| w.dcrst().set_bit());
        self.flash.acr().modify(|_, w| w.dcrst().clear_bit());
        self.flash.acr().modify(|_, w| w.dcen().set_bit());
    }
}

impl SlotStore for FlashSlots<'_> {
    type Error = flash::Error;

    fn slot_words(&self) -> usize {
        SLOT_WORDS
    }

    fn contents(&self, slot: Slot) -> &[u32] {
        words(slot)
    }

    /// Erases the slot's sector, whatever `_words`: the sector is the
    /// STM32F411's erase unit here.
    fn erase(&mut self, slot: Slot, _words: usize) -> Result<(), flash::Error> {
        let sector = match slot {
            Slot::A => SECTOR_A,
            Slot::B => SECTOR_B,
        };
        if let Some(w) = self.watchdog.as_deref_mut() {
            w.start(ERASE_WATCHDOG_MS.millis());
        }
        let flash = &mut *self.flash;
        let result = systick::across(DWT::cycle_count, TICKS_PER_MS, || {
            flash.unlocked().erase(sector)
        });
        if let Some(w) = self.watchdog.as_deref_mut() {
            w.start(self.watchdog_ms.millis());
        }
        self.reset_data_cache();
        result
    }

    fn program(&mut self, slot: Slot, offset: usize, words: &[u32]) -> Result<(), flash::Error> {
        if offset.saturating_add(words.len()) > SLOT_WORDS {
            return Err(flash::Error::ProgrammingSequence);
        }
        let start = (field::address(&SLOTS, slot) - FLASH_ORIGIN) as usize + offset * 4;
        let flash = &mut *self.flash;
        let result = systick::across(DWT::cycle_count, TICKS_PER_MS, || {
            let mut unlocked = flash.unlocked();
            words.iter().enumerate().try_for_each(|(i, word)| {
                unlocked.program(start + i * 4, word.to_le_bytes().iter())
            })
        });
        self.reset_data_cache();
        result
    }
}

const _: () = assert!(FLASH_ORIGIN == 0x0800_0000);
