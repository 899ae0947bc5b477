//! The slot header: eight words in front of a program image that say
//! what the slot holds and whether it was written to the end.
//!
//! | word | content |
//! |---|---|
//! | 0 | [`MAGIC`] |
//! | 1 | [`FORMAT`], the header layout |
//! | 2 | sequence number: the slot with the higher one is the newer |
//! | 3 | the program's version (`major << 16 \| minor << 8 \| patch`) |
//! | 4 | the image's length in words |
//! | 5 | the image CRC (the executor's, over the image's words) |
//! | 6 | the wiring signature of the project the image was made for ([`SlotHeader::wiring`]) |
//! | 7 | CRC of words 0–6 ([`crate::CRC_ALGORITHM`]) |
//!
//! The loader writes the header last: an erased header (all ones) or a
//! half-written one fails its CRC, so a slot whose image is incomplete
//! is never chosen.

use crate::crc_of_words;
use crc::Crc;

/// Word 0 of a written header: `"PLCI"` in ASCII, `P` the most
/// significant byte.
pub const MAGIC: u32 = u32::from_be_bytes(*b"PLCI");

/// The header layout this crate writes and reads (2: word 6 is the
/// wiring signature; layout 1 left it 0).
pub const FORMAT: u32 = 2;

/// Words of a header.
pub const HEADER_WORDS: usize = 8;

/// What a slot header says about its image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SlotHeader {
    /// Higher is newer.
    pub sequence: u32,
    /// The program's version, `major << 16 | minor << 8 | patch`.
    pub version: u32,
    /// Words of the image that follows the header.
    pub words: u32,
    /// The image CRC recorded by the generator.
    pub image_crc: u32,
    /// The wiring signature of the project the image was made for: a CRC
    /// of its board chip and of each input's and output's name, pin and
    /// electrical settings (`codegen::board::wiring_signature`). A
    /// firmware runs only images of its own wiring, whose signals mean
    /// what its pins carry.
    pub wiring: u32,
}

/// Why a header is not a valid one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum HeaderFault {
    /// Fewer than [`HEADER_WORDS`] words.
    Short,
    /// Word 0 is not [`MAGIC`] (an erased or never written slot).
    Magic,
    /// A layout this crate does not know.
    Format(u32),
    /// Word 7 does not match the CRC of words 0–6.
    Crc,
    /// The image would not fit the slot.
    Length(u32),
}

impl SlotHeader {
    /// The header's words, CRC included.
    pub fn to_words(&self, crc: &Crc<u32>) -> [u32; HEADER_WORDS] {
        let mut words = [
            MAGIC,
            FORMAT,
            self.sequence,
            self.version,
            self.words,
            self.image_crc,
            self.wiring,
            0,
        ];
        words[HEADER_WORDS - 1] = crc_of_words(crc, &words[..HEADER_WORDS - 1]);
        words
    }

    /// The header at the start of `slot` (a slot's words), checked: magic,
    /// layout, CRC, and an image length that fits the slot.
    pub fn read(slot: &[u32], crc: &Crc<u32>) -> Result<SlotHeader, HeaderFault> {
        let Some(words) = slot.get(..HEADER_WORDS) else {
            return Err(HeaderFault::Short);
        };
        if words[0] != MAGIC {
            return Err(HeaderFault::Magic);
        }
        if words[1] != FORMAT {
            return Err(HeaderFault::Format(words[1]));
        }
        if crc_of_words(crc, &words[..HEADER_WORDS - 1]) != words[HEADER_WORDS - 1] {
            return Err(HeaderFault::Crc);
        }
        let header = SlotHeader {
            sequence: words[2],
            version: words[3],
            words: words[4],
            image_crc: words[5],
            wiring: words[6],
        };
        let fits =
            usize::try_from(header.words).is_ok_and(|n| n > 0 && n <= slot.len() - HEADER_WORDS);
        if fits {
            Ok(header)
        } else {
            Err(HeaderFault::Length(header.words))
        }
    }
}

/// A version number from its three parts (each part's low bits kept:
/// major 16, minor and patch 8).
pub const fn version(major: u16, minor: u8, patch: u8) -> u32 {
    (major as u32) << 16 | (minor as u32) << 8 | patch as u32
}

/// The three parts of a version number.
pub const fn version_parts(version: u32) -> (u16, u8, u8) {
    ((version >> 16) as u16, (version >> 8) as u8, version as u8)
}
