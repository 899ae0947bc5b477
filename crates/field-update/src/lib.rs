//! Field update: a new program image loaded into a running PLC without a
//! toolchain, the way a PLC IDE downloads a program into its runtime.
//!
//! - [`slot`]: two flash slots, each a [`header::SlotHeader`] followed by
//!   a program image (the executor's configuration and tables as 32-bit
//!   words); the slot with the highest sequence number whose header,
//!   CRC and structure check pass is the one that runs
//!   ([`slot::choose`]), the program built into the firmware when none
//!   does.
//! - [`protocol`]: the requests a loader on a PC sends and the responses
//!   of the PLC, each a frame of postcard bytes, a CRC-32 and COBS
//!   ([`frame`]).
//! - [`loader`]: the PLC side: it writes a new image into the slot that
//!   is not running, checks it, and only then writes its header, so a
//!   power cut or a refused image leaves the running program in place.
//!
//! - `host` (feature `std`): the PC side, slot files and a load over
//!   any byte stream (the `codegen load` command).
//!
//! The crate knows nothing of the executor: what a valid program is comes
//! from a [`slot::Check`] the firmware provides (the executor's
//! structure check and image CRC). `docs/field-update.md` describes the
//! flash layout, the protocol and the commands.

#![cfg_attr(not(any(test, feature = "std")), no_std)]
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod frame;
pub mod header;
#[cfg(feature = "std")]
pub mod host;
pub mod loader;
pub mod protocol;
pub mod slot;

#[cfg(test)]
mod tests;

/// The CRC of slot headers and frames: CRC-32/MPEG-2 (polynomial
/// `0x04C11DB7`, no reflection, no final XOR), the executor's image CRC
/// and the STM32 CRC unit's, words fed most significant byte first.
pub const CRC_ALGORITHM: crc::Algorithm<u32> = crc::CRC_32_MPEG_2;

/// The CRC of `words`, each fed as its four bytes most significant first.
pub fn crc_of_words(crc: &crc::Crc<u32>, words: &[u32]) -> u32 {
    let mut digest = crc.digest();
    for word in words {
        digest.update(&word.to_be_bytes());
    }
    digest.finalize()
}
