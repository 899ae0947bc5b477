//! The STM32F411's CRC unit as the controller's image CRC engine.
//!
//! The unit computes CRC-32/MPEG-2 over 32-bit words written to its data
//! register (polynomial `0x04C1_1DB7`, register reset to `0xFFFF_FFFF`,
//! no reflection, no final XOR; RM0383, "CRC calculation unit"): the
//! image CRC's algorithm with each word fed most significant byte first
//! (`executor::image`), 4 AHB cycles a word. The software engine takes a
//! 1 KiB table and about 16 instructions a word.
//!
//! Its register can be reset but not loaded. The controller owns the
//! engine, so between two shares of a background pass the register still
//! holds the CRC the pass has reached; should anything else have used the
//! unit, the share is computed in software ([`feed_bitwise`], no table) and the
//! unit takes the next pass over from its reset.

use executor::image::{feed_bitwise, CrcEngine, CRC_START};
use stm32f4xx_hal::crc32::Crc32;

/// The CRC unit, owned by the controller.
pub struct CrcUnit(Crc32);

impl CrcUnit {
    /// The engine of the unit `crc` (clocked and reset by the HAL).
    pub fn new(crc: Crc32) -> CrcUnit {
        CrcUnit(crc)
    }
}

impl CrcEngine for CrcUnit {
    fn feed(&mut self, crc: u32, words: &[u32]) -> u32 {
        // `update` of no words reads the data register.
        if self.0.update(&[]) != crc {
            if crc != CRC_START {
                return feed_bitwise(crc, words);
            }
            self.0.init();
        }
        self.0.update(words)
    }
}
