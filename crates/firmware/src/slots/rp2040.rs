//! Where the two field-update slots live in the Raspberry Pi Pico's flash
//! (feature `pico` with `field-update`): the one place that states it.
//! `build.rs` writes the linker's `FLASH` region from these figures (it
//! ends where slot A begins), and the board's slot store (`pico::flash`)
//! erases, programs and reads these regions.
//!
//! The Pico's W25Q16JV holds 2 MiB, mapped at `0x1000_0000` (XIP). It
//! erases 4 KiB sectors (command 20h: typically 45 ms, at most 400 ms)
//! or 64 KiB blocks (D8h: 150 ms, at most 2 s), and programs 256-byte
//! pages (at most 3 ms; W25Q16JV datasheet, AC characteristics). The
//! slots are the last 256 KiB, two 128 KiB slots of two blocks each; the
//! firmware keeps the 1,792 KiB before them, the second-stage
//! bootloader's 256 bytes first.

/// Where the chip's flash is mapped.
pub const FLASH_ORIGIN: u32 = 0x1000_0000;
/// The Pico's flash (bytes).
pub const FLASH_BYTES: u32 = 2048 * 1024;
/// The second-stage bootloader at the start of flash (bytes).
pub const BOOT2_BYTES: u32 = 0x100;
/// Bytes of a slot: two erase blocks.
pub const SLOT_BYTES: u32 = 128 * 1024;
/// Slot A's address.
pub const SLOT_A: u32 = FLASH_ORIGIN + FLASH_BYTES - 2 * SLOT_BYTES;
/// Slot B's address: the last 128 KiB.
pub const SLOT_B: u32 = SLOT_A + SLOT_BYTES;
/// The erase block the slots are made of (bytes; command D8h).
pub const BLOCK_BYTES: u32 = 64 * 1024;
/// The erase command of a 64 KiB block.
pub const BLOCK_ERASE: u8 = 0xD8;
/// The smallest erase unit (bytes; command 20h).
pub const SECTOR_BYTES: u32 = 4 * 1024;
/// The most sectors erased one by one after the whole blocks of a range:
/// more take longer than their block's erase (typically 45 ms each
/// against 150 ms for the block).
pub const MAX_TAIL_SECTORS: u32 = 3;
/// The programming unit (bytes): a page, 256-byte aligned.
pub const PAGE_BYTES: u32 = 256;
/// The firmware's code and data in flash when it keeps the slots:
/// everything between the bootloader and slot A.
pub const FIRMWARE_BYTES: u32 = SLOT_A - FLASH_ORIGIN - BOOT2_BYTES;

const _: () = assert!(SLOT_A % BLOCK_BYTES == 0 && SLOT_BYTES % BLOCK_BYTES == 0);
const _: () = assert!(SLOT_B + SLOT_BYTES == FLASH_ORIGIN + FLASH_BYTES);

/// The bytes from a slot's start that erasing its first `bytes` covers:
/// whole 64 KiB blocks, then the last block's sectors when at most
/// [`MAX_TAIL_SECTORS`] of them are needed, else that whole block; never
/// more than the slot. The boot ROM's `flash_range_erase` erases a range
/// so given in blocks where it can and in sectors elsewhere.
pub const fn erase_bytes(bytes: u32) -> u32 {
    let blocks = bytes / BLOCK_BYTES;
    let sectors = (bytes % BLOCK_BYTES).div_ceil(SECTOR_BYTES);
    let covered = if sectors > MAX_TAIL_SECTORS {
        (blocks + 1) * BLOCK_BYTES
    } else {
        blocks * BLOCK_BYTES + sectors * SECTOR_BYTES
    };
    if covered < SLOT_BYTES {
        covered
    } else {
        SLOT_BYTES
    }
}

/// The byte offsets (in a slot) of the pages that programming `words` at
/// byte `first` of the slot touches, in order.
pub fn pages(first: usize, words: usize) -> impl Iterator<Item = usize> {
    let page = PAGE_BYTES as usize;
    let last = first + words * 4;
    (first - first % page..last).step_by(page)
}

/// The page at byte `page_start` of a slot as programming `words` at byte
/// `first` writes it: their bytes (little-endian, as the core reads them)
/// where they fall in the page, 0xFF elsewhere, which leaves a byte of
/// the flash as it is (programming only clears bits).
pub fn page_bytes(page_start: usize, first: usize, words: &[u32]) -> [u8; PAGE_BYTES as usize] {
    let mut page = [0xFF_u8; PAGE_BYTES as usize];
    let last = first + words.len() * 4;
    for (at, byte) in page.iter_mut().enumerate() {
        let i = page_start + at;
        if (first..last).contains(&i) {
            *byte = words[(i - first) / 4].to_le_bytes()[(i - first) % 4];
        }
    }
    page
}

/// The two slots.
pub const SLOTS: super::SlotMap = super::SlotMap {
    a: SLOT_A,
    b: SLOT_B,
    bytes: SLOT_BYTES,
};

/// Writes the linker's memory regions of the board firmware with the
/// slots kept out of `FLASH` (what `build.rs` writes as `plc-layout.x`):
/// `layout/rp2040.x` with a shorter `FLASH`.
pub fn write_linker_layout(out: &mut impl core::fmt::Write) -> core::fmt::Result {
    write!(
        out,
        "/* RP2040 (Raspberry Pi Pico) with field-update slots\n \
         * (crates/firmware/src/slots/rp2040.rs): the second-stage bootloader's\n \
         * 256 bytes, then the firmware up to slot A ({SLOT_A:#010x}); slot B is at\n \
         * {SLOT_B:#010x}, {} KiB each. Written by crates/firmware/build.rs. */\n\
         MEMORY\n{{\n  BOOT2 : ORIGIN = {FLASH_ORIGIN:#010x}, LENGTH = {BOOT2_BYTES:#x}\n  \
         FLASH : ORIGIN = {:#010x}, LENGTH = {FIRMWARE_BYTES:#x}\n  \
         RAM   : ORIGIN = 0x20000000, LENGTH = 256K\n}}\n\n\
         SECTIONS\n{{\n  .boot2 ORIGIN(BOOT2) :\n  {{\n    KEEP(*(.boot2));\n  }} > BOOT2\n\
         }} INSERT BEFORE .text;\n",
        SLOT_BYTES / 1024,
        FLASH_ORIGIN + BOOT2_BYTES,
    )
}

#[cfg(test)]
mod tests {
    use super::super::tests::{region, written};
    use super::*;

    /// Programs `words` at word `offset` of a slot modelled as NOR flash
    /// (programming ANDs a page into it), page by page as the Pico does.
    fn program(flash: &mut [u8], offset: usize, words: &[u32]) {
        let first = offset * 4;
        for start in pages(first, words.len()) {
            let page = page_bytes(start, first, words);
            for (cell, byte) in flash[start..start + page.len()].iter_mut().zip(page) {
                *cell &= byte;
            }
        }
    }

    #[test]
    fn an_erase_covers_what_it_must_in_the_fewest_slow_units() {
        // The press's image (716 bytes and the 32-byte header): one sector.
        assert_eq!(erase_bytes(716 + 32), SECTOR_BYTES);
        assert_eq!(erase_bytes(SECTOR_BYTES), SECTOR_BYTES);
        assert_eq!(erase_bytes(SECTOR_BYTES + 1), 2 * SECTOR_BYTES);
        // Three sectors, then a whole block.
        assert_eq!(erase_bytes(3 * SECTOR_BYTES), 3 * SECTOR_BYTES);
        assert_eq!(erase_bytes(3 * SECTOR_BYTES + 4), BLOCK_BYTES);
        // The AGV's image (35,340 bytes): the first block.
        assert_eq!(erase_bytes(35_340 + 32), BLOCK_BYTES);
        // A block and a sector; two blocks; never past the slot.
        assert_eq!(erase_bytes(BLOCK_BYTES + 8), BLOCK_BYTES + SECTOR_BYTES);
        assert_eq!(erase_bytes(BLOCK_BYTES + 3 * SECTOR_BYTES + 1), SLOT_BYTES);
        assert_eq!(erase_bytes(SLOT_BYTES), SLOT_BYTES);
        assert_eq!(erase_bytes(SLOT_BYTES + 4), SLOT_BYTES);
        // Every range covers its bytes, in whole sectors.
        for bytes in (4..=SLOT_BYTES).step_by(4 * 97) {
            let covered = erase_bytes(bytes);
            assert!(covered >= bytes && covered % SECTOR_BYTES == 0, "{bytes}");
        }
    }

    #[test]
    fn chunks_programmed_page_by_page_leave_every_other_byte_as_it_was() {
        // A slot of 8 pages, erased; the loader's order: the image in
        // chunks that straddle pages (here 23 words, then 64, ...) from
        // word 4, then the 4-word header at word 0.
        let mut flash = vec![0xFF_u8; 8 * PAGE_BYTES as usize];
        let image: Vec<u32> = (0..400_u32)
            .map(|i| i.wrapping_mul(0x9E37_79B9) ^ 0x0101_0101)
            .collect();
        let mut at = 0;
        for len in [23, 64, 1, 100, 64, 148] {
            program(&mut flash, 4 + at, &image[at..at + len]);
            // Nothing after the chunk is touched.
            let end = (4 + at + len) * 4;
            assert!(
                flash[end..].iter().all(|&b| b == 0xFF),
                "after chunk at {at}"
            );
            at += len;
        }
        assert_eq!(at, image.len());
        let header = [0xDEAD_BEEF, 7, 400, 0x1234_5678];
        program(&mut flash, 0, &header);
        let words: Vec<u32> = flash
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        assert_eq!(words[..4], header);
        assert_eq!(words[4..404], image[..]);
        assert!(words[404..].iter().all(|&w| w == u32::MAX));
        // A chunk inside one page touches that page only; one across a
        // page boundary touches both.
        assert_eq!(pages(8, 3).collect::<Vec<_>>(), [0]);
        assert_eq!(pages(252, 2).collect::<Vec<_>>(), [0, 256]);
        assert_eq!(pages(256, 64).collect::<Vec<_>>(), [256]);
    }

    #[test]
    fn the_linker_flash_region_ends_where_slot_a_begins() {
        let script = written(write_linker_layout);
        let (origin, length) = region(&script, "FLASH");
        assert_eq!(origin, FLASH_ORIGIN + BOOT2_BYTES);
        assert_eq!(origin + length, SLOT_A);
        assert_eq!(SLOT_A, 0x101C_0000);
        assert_eq!(SLOT_B, 0x101E_0000);
        // The rest is the plain layout's: the bootloader's region and
        // section, the RAM.
        let plain = include_str!("../../layout/rp2040.x");
        for name in ["BOOT2", "RAM"] {
            assert_eq!(region(&script, name), region(plain, name), "{name}");
        }
        let sections = |text: &str| text[text.find("SECTIONS").expect("SECTIONS")..].to_owned();
        assert_eq!(sections(&script), sections(plain));
        // The plain layout covers the whole chip: FLASH is its 2 MiB less
        // the bootloader's 256 bytes.
        assert_eq!(
            region(plain, "FLASH"),
            (FLASH_ORIGIN + BOOT2_BYTES, FLASH_BYTES)
        );
        assert!(plain.contains("FLASH : ORIGIN = 0x10000100, LENGTH = 2048K - 0x100\n"));
    }
}
