//! The field-update slots in the Pico's flash (feature `field-update`):
//! its last 256 KiB (`firmware::slots::rp2040`), erased and programmed
//! through the RP2040 boot ROM's flash functions, read where XIP maps
//! them.
//!
//! The flash cannot be read while it is erased or programmed, and the
//! firmware runs from it (XIP). So each operation runs the sequence of
//! the RP2040 datasheet (§2.8.3.1.3: `connect_internal_flash`,
//! `flash_exit_xip`, the erase or program, `flash_flush_cache`, then XIP
//! set up again) in a function linked into RAM (`.data.ram_func`, which
//! cortex-m-rt copies to RAM at start-up), with interrupts masked,
//! calling the boot ROM through pointers looked up beforehand. XIP is set
//! up again by the second-stage bootloader ([`BOOT2`]) copied to the
//! stack: the ROM's `flash_enter_cmd_xip` would leave the flash in its
//! slow 03h read mode. (The `rp2040-flash` crate does the same, but its
//! 0.6 release is built on rp2040-hal 0.11: a second HAL in the image.)
//!
//! The SysTick handler cannot run meanwhile either: the millisecond clock
//! is set right after each operation from the 1 MHz timer
//! (`systick::across`), so the executor sees the pause as it was.
//!
//! An erase covers the header and the image a load announced, not the
//! whole slot (`firmware::slots::rp2040::erase_bytes`): the press's
//! image one 4 KiB sector (at most 400 ms), the AGV's one 64 KiB block
//! (at most 2 s), a full slot two blocks (at most 4 s; W25Q16JV
//! datasheet). No scan runs meanwhile, the outputs keep their levels,
//! and the watchdog is started again with [`ERASE_WATCHDOG_MS`] just
//! before and with its scan timeout just after. A page (256 bytes)
//! programs in at most 3 ms, so a 256-byte `Data` chunk, at most two
//! pages, takes at most 6 ms of the scan's link share. Each
//! operation is read back through XIP: a word that did not take is
//! reported, and the loader refuses the load.

use super::BOOT2;
use crate::field;
use crate::scan::Board;
use crate::systick;
use core::sync::atomic::{compiler_fence, Ordering};
use field_update::protocol::ERASE_MS;
use field_update::slot::{Slot, SlotStore};
use firmware::slots::rp2040::{
    erase_bytes, page_bytes, pages, BLOCK_BYTES, BLOCK_ERASE, FLASH_ORIGIN, PAGE_BYTES, SLOTS,
};
use fugit::MicrosDurationU32;
use rp2040_hal::rom_data;
use rp2040_hal::{Timer, Watchdog};

/// The watchdog timeout over a slot erase (ms): twice the longest
/// 128 KiB erase ([`ERASE_MS`], 4 s, which the PC also waits out for
/// `Begin`'s answer), below the RP2040's 8.388 s.
pub const ERASE_WATCHDOG_MS: u32 = 2 * ERASE_MS;
const _: () = assert!(ERASE_WATCHDOG_MS <= firmware::MCU.watchdog.max_timeout_ms);

/// Timer ticks a millisecond (the board's scan timer, 1 MHz).
const TICKS_PER_MS: u32 = <super::Pico as Board>::TIMER_TICKS_PER_US * 1_000;

/// Words of a slot.
const SLOT_WORDS: usize = SLOTS.words();
/// Bytes of a page.
const PAGE: usize = PAGE_BYTES as usize;

/// What went wrong writing a slot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlashError {
    /// The words do not fit the slot.
    OutOfRange,
    /// A word read back is not what was erased or programmed.
    Verify,
}

/// The two slots, the watchdog while a slot is erased, and the timer
/// that keeps the millisecond clock true across an erase or a write.
pub struct FlashSlots<'w> {
    /// The running watchdog (`None` before it starts).
    watchdog: Option<&'w mut Watchdog>,
    watchdog_ms: u32,
    timer: Timer,
}

impl<'w> FlashSlots<'w> {
    /// The slots; `watchdog` (running with `watchdog_ms`) is given the
    /// erase's timeout while a slot is erased.
    pub fn new(
        watchdog: Option<&'w mut Watchdog>,
        watchdog_ms: u32,
        timer: Timer,
    ) -> FlashSlots<'w> {
        FlashSlots {
            watchdog,
            watchdog_ms,
            timer,
        }
    }

    /// Runs `operation` with interrupts masked (`rom`), the millisecond
    /// clock set right after it from the 1 MHz timer.
    fn paused(&self, operation: impl FnOnce()) {
        let timer = self.timer;
        systick::across(|| timer.get_counter_low(), TICKS_PER_MS, operation);
    }

    fn restart_watchdog(&mut self, ms: u32) {
        if let Some(w) = self.watchdog.as_deref_mut() {
            w.start(MicrosDurationU32::millis(ms));
        }
    }
}

/// The words of `slot` where XIP maps the flash.
pub fn words(slot: Slot) -> &'static [u32] {
    // SAFETY: `firmware::slots::rp2040` places both slots, word-aligned,
    // inside the 2 MiB that XIP maps and after the linker's FLASH region,
    // so no code or data of the firmware shares their bytes. XIP reads
    // them whenever code runs; the only time it cannot (between
    // `flash_exit_xip` and the bootloader's return) runs from RAM with
    // interrupts masked and reads no slot. Their bytes change only in
    // `FlashSlots::erase`/`program`, through `&mut` of the store, and
    // never in the slot whose program runs and borrows these words.
    #[allow(unsafe_code)]
    unsafe {
        core::slice::from_raw_parts(field::address(&SLOTS, slot) as *const u32, SLOT_WORDS)
    }
}

impl SlotStore for FlashSlots<'_> {
    type Error = FlashError;

    fn slot_words(&self) -> usize {
        SLOT_WORDS
    }

    fn contents(&self, slot: Slot) -> &[u32] {
        words(slot)
    }

    fn erase(&mut self, slot: Slot, words: usize) -> Result<(), FlashError> {
        let needed = u32::try_from(words.saturating_mul(4)).unwrap_or(u32::MAX);
        let bytes = erase_bytes(needed);
        self.restart_watchdog(ERASE_WATCHDOG_MS);
        self.paused(|| rom::erase(field::address(&SLOTS, slot) - FLASH_ORIGIN, bytes));
        self.restart_watchdog(self.watchdog_ms);
        let erased = &self::words(slot)[..bytes as usize / 4];
        if erased.iter().all(|&w| w == u32::MAX) {
            Ok(())
        } else {
            Err(FlashError::Verify)
        }
    }

    fn program(&mut self, slot: Slot, offset: usize, words: &[u32]) -> Result<(), FlashError> {
        let end = offset.saturating_add(words.len());
        if end > SLOT_WORDS {
            return Err(FlashError::OutOfRange);
        }
        // Each page is programmed whole: the bytes outside `words` are
        // 0xFF, which leaves them as they are.
        let first = offset * 4;
        for page_start in pages(first, words.len()) {
            let page = page_bytes(page_start, first, words);
            let in_flash = field::address(&SLOTS, slot) - FLASH_ORIGIN + page_start as u32;
            self.paused(|| rom::program(in_flash, &page));
        }
        if self::words(slot)[offset..end] == *words {
            Ok(())
        } else {
            Err(FlashError::Verify)
        }
    }
}

/// The boot ROM's flash functions, called from RAM.
mod rom {
    #![allow(unsafe_code)]

    use super::*;

    /// The functions of one operation, looked up while XIP still runs
    /// (the lookup's code is in flash), and the bootloader's copy.
    #[repr(C)]
    struct Rom {
        connect_internal_flash: unsafe extern "C" fn(),
        flash_exit_xip: unsafe extern "C" fn(),
        flash_range_erase: unsafe extern "C" fn(u32, usize, u32, u8),
        flash_range_program: unsafe extern "C" fn(u32, *const u8, usize),
        flash_flush_cache: unsafe extern "C" fn(),
        /// The second-stage bootloader copied to RAM: sets up fast XIP
        /// again and returns.
        enter_xip: unsafe extern "C" fn(),
    }

    /// Runs `operation` on the ROM's functions with interrupts masked
    /// (their handlers are in flash) and the bootloader in a stack copy.
    fn with_rom(operation: impl FnOnce(&Rom)) {
        // The bootloader's 256 bytes as words (its code reads no data
        // outside itself, so it runs from any address).
        let mut boot2 = [0_u32; 64];
        for (word, bytes) in boot2.iter_mut().zip(BOOT2.chunks_exact(4)) {
            *word = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
        }
        // SAFETY: `boot2` holds the bootloader's code (Thumb: the address
        // with bit 0 set), which returns to its caller when called with
        // a non-zero return address (the Pico SDK's `flash_range_erase`
        // calls its copy the same way). It lives until after the call.
        let entry = boot2.as_ptr().cast::<u8>().wrapping_add(1);
        let enter_xip = unsafe { core::mem::transmute::<*const u8, unsafe extern "C" fn()>(entry) };
        let rom = Rom {
            connect_internal_flash: rom_data::connect_internal_flash::ptr(),
            flash_exit_xip: rom_data::flash_exit_xip::ptr(),
            flash_range_erase: rom_data::flash_range_erase::ptr(),
            flash_range_program: rom_data::flash_range_program::ptr(),
            flash_flush_cache: rom_data::flash_flush_cache::ptr(),
            enter_xip,
        };
        cortex_m::interrupt::free(|_| {
            compiler_fence(Ordering::SeqCst);
            operation(&rom);
            compiler_fence(Ordering::SeqCst);
        });
    }

    /// Erases `bytes` at `offset` in the flash: 64 KiB blocks where the
    /// range covers them, 4 KiB sectors elsewhere (`erase_bytes`).
    pub fn erase(offset: u32, bytes: u32) {
        // SAFETY: interrupts are masked and the one core runs; `erase_in_ram`
        // is in RAM and touches only the stack and the ROM until XIP is
        // back; the region is a slot, which holds no code or data of the
        // firmware.
        with_rom(|rom| unsafe { erase_in_ram(rom, offset, bytes) });
    }

    /// Programs one 256-byte page at `offset` (page-aligned) in the flash.
    pub fn program(offset: u32, page: &[u8; PAGE]) {
        // SAFETY: as for `erase`; the page is on the stack.
        with_rom(|rom| unsafe { program_in_ram(rom, offset, page.as_ptr()) });
    }

    /// The erase sequence. In RAM, and calls nothing but `rom`'s pointers:
    /// XIP is off from `flash_exit_xip` to `enter_xip`.
    #[inline(never)]
    #[link_section = ".data.ram_func"]
    unsafe fn erase_in_ram(rom: &Rom, offset: u32, bytes: u32) {
        (rom.connect_internal_flash)();
        (rom.flash_exit_xip)();
        (rom.flash_range_erase)(offset, bytes as usize, BLOCK_BYTES, BLOCK_ERASE);
        (rom.flash_flush_cache)();
        (rom.enter_xip)();
    }

    /// The program sequence of one page: as [`erase_in_ram`].
    #[inline(never)]
    #[link_section = ".data.ram_func"]
    unsafe fn program_in_ram(rom: &Rom, offset: u32, page: *const u8) {
        (rom.connect_internal_flash)();
        (rom.flash_exit_xip)();
        (rom.flash_range_program)(offset, page, PAGE);
        (rom.flash_flush_cache)();
        (rom.enter_xip)();
    }
}
