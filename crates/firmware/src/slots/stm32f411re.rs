//! Where the two field-update slots live in the STM32F411RE's flash
//! (the Nucleo-F411RE's, feature `field-update`): the one place that
//! states it. `build.rs` writes the linker's `FLASH` region from these
//! figures (it ends where slot A begins), and the board's slot store
//! (`nucleo_f411re::flash`) erases and reads these sectors.
//!
//! The STM32F411RE has 512 KiB of flash in sectors 0–3 of 16 KiB, 4 of
//! 64 KiB and 5–7 of 128 KiB (RM0383 §3.3). Slot A is sector 6, slot B
//! sector 7; the firmware keeps sectors 0–5 (384 KiB).

/// Where the chip's flash begins.
pub const FLASH_ORIGIN: u32 = 0x0800_0000;
/// The chip's flash (bytes).
pub const FLASH_BYTES: u32 = 512 * 1024;
/// Slot A's address: sector 6.
pub const SLOT_A: u32 = 0x0804_0000;
/// Slot B's address: sector 7.
pub const SLOT_B: u32 = 0x0806_0000;
/// Bytes of a slot: one 128 KiB sector.
pub const SLOT_BYTES: u32 = 128 * 1024;
/// Slot A's erase sector.
pub const SECTOR_A: u8 = 6;
/// Slot B's erase sector.
pub const SECTOR_B: u8 = 7;
/// The firmware's flash when it keeps the slots: everything before slot A.
pub const FIRMWARE_BYTES: u32 = SLOT_A - FLASH_ORIGIN;

/// The start of sector `n` of the STM32F411RE (0–7).
pub const fn sector_start(n: u8) -> u32 {
    let kib = match n {
        0..=4 => n as u32 * 16,
        _ => 128 * (n as u32 - 4),
    };
    FLASH_ORIGIN + kib * 1024
}

const _: () = assert!(sector_start(SECTOR_A) == SLOT_A && sector_start(SECTOR_B) == SLOT_B);
const _: () = assert!(sector_start(SECTOR_B) + SLOT_BYTES == FLASH_ORIGIN + FLASH_BYTES);
const _: () = assert!(SLOT_A + SLOT_BYTES == SLOT_B);

/// The two slots.
pub const SLOTS: super::SlotMap = super::SlotMap {
    a: SLOT_A,
    b: SLOT_B,
    bytes: SLOT_BYTES,
};

/// Writes the linker's memory regions of the board firmware with the
/// slots kept out of `FLASH` (what `build.rs` writes as `plc-layout.x`).
pub fn write_linker_layout(out: &mut impl core::fmt::Write) -> core::fmt::Result {
    write!(
        out,
        "/* STM32F411RE with field-update slots (crates/firmware/src/slots/stm32f411re.rs):\n \
         * the firmware's flash ends at slot A ({SLOT_A:#010x}); slot B is at {SLOT_B:#010x},\n \
         * {} KiB each. Written by crates/firmware/build.rs. */\n\
         MEMORY\n{{\n  FLASH : ORIGIN = {FLASH_ORIGIN:#010x}, LENGTH = {}K\n  \
         RAM   : ORIGIN = 0x20000000, LENGTH = 128K\n}}\n",
        SLOT_BYTES / 1024,
        FIRMWARE_BYTES / 1024,
    )
}

#[cfg(test)]
mod tests {
    use super::super::tests::{region, written};
    use super::*;

    #[test]
    fn the_linker_flash_region_ends_where_slot_a_begins() {
        let script = written(write_linker_layout);
        let (origin, length) = region(&script, "FLASH");
        assert_eq!(origin, FLASH_ORIGIN);
        assert_eq!(origin + length, SLOT_A);
        // The slots are whole sectors, at the end of the chip's flash.
        assert_eq!(sector_start(SECTOR_A), SLOT_A);
        assert_eq!(sector_start(SECTOR_B), SLOT_B);
        assert_eq!(SLOT_B + SLOT_BYTES, FLASH_ORIGIN + FLASH_BYTES);
        // The script without the slots covers the whole chip.
        let plain = include_str!("../../layout/stm32f411re.x");
        assert_eq!(region(plain, "FLASH"), (FLASH_ORIGIN, FLASH_BYTES));
        assert_eq!(region(&script, "RAM"), region(plain, "RAM"));
    }
}
