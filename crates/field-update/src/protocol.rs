//! The messages of the serial link. The PC sends one [`Request`] and
//! waits for its [`Response`] before it sends the next.
//!
//! A load is `Begin`, `Data` from offset 0 in order (each answered by
//! `Next` with the offset the PLC expects next: a lost or repeated chunk
//! is sent again from there), then `Commit`, answered by `Switched` once
//! the image is checked and its header written, or `Refused`. `Abort`
//! drops a load; `Status` may come at any time.
//!
//! The PLC answers `Begin` after erasing the slot, which stalls it for up
//! to [`ERASE_MS`]: the PC waits that long for the answer before it
//! sends `Begin` again, and a `Begin` sent again before any `Data` is
//! answered without a second erase.

use crate::slot::{Rejected, Slot};
use serde::{Deserialize, Serialize};

/// Most image bytes in one `Data` request: a multiple of 4 and of the
/// 256-byte flash page of the boards.
pub const MAX_DATA: usize = 256;

/// The longest a PLC may take to answer `Begin`, in milliseconds: the
/// erase of a slot. The Nucleo-F411RE's slot is a 128 KiB sector, erased
/// at the HAL's 8-bit parallelism in at most 4 s (STM32F411 datasheet,
/// typically 2 s), during which its core stalls and bytes sent to it are
/// lost.
pub const ERASE_MS: u32 = 4_000;

/// What the PC asks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Request<'a> {
    /// What runs, and how far a load has come.
    Status,
    /// Load an image of `words` words into the slot that does not run
    /// (erasing it): its CRC, version and wiring signature as the slot
    /// header will record them. An image of another wiring is refused
    /// before anything is erased.
    Begin {
        /// Words of the image.
        words: u32,
        /// The image CRC the generator recorded.
        image_crc: u32,
        /// The program's version ([`crate::header::version`]).
        version: u32,
        /// The wiring signature of the image's project
        /// ([`crate::header::SlotHeader::wiring`]).
        wiring: u32,
    },
    /// Image bytes (words little-endian) from byte `offset`, at most
    /// [`MAX_DATA`], a whole number of words.
    Data {
        /// Where the bytes go in the image, in bytes.
        offset: u32,
        /// The bytes.
        #[serde(borrow)]
        bytes: &'a [u8],
    },
    /// Check the image received and run it.
    Commit,
    /// Drop the load; the slot keeps no valid header.
    Abort,
}

/// What the PLC answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Response<'a> {
    /// The answer to `Status`.
    Status(#[serde(borrow)] Status<'a>),
    /// Send the bytes from `offset` (the whole image is in when it is the
    /// image's length in bytes).
    Next {
        /// The byte offset expected next.
        offset: u32,
    },
    /// The image is checked, its header written: it runs from the next
    /// scan on.
    Switched {
        /// The slot it is in.
        slot: Slot,
        /// Its sequence number.
        sequence: u32,
    },
    /// The request is refused; what runs is unchanged.
    Refused(Refusal),
}

/// What runs and what is being loaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Status<'a> {
    /// The running project's name.
    #[serde(borrow)]
    pub name: &'a str,
    /// The running program's slot, `None` for the built-in program.
    pub slot: Option<Slot>,
    /// The running program's version (0 for the built-in program).
    pub version: u32,
    /// The running program's image CRC.
    pub image_crc: u32,
    /// The firmware's wiring signature: what an image loaded into it
    /// must record ([`crate::header::SlotHeader::wiring`]).
    pub wiring: u32,
    /// The byte offset the load in progress expects next.
    pub loading: Option<u32>,
}

/// Why a request was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Refusal {
    /// `Data`, `Commit` or `Abort` without a `Begin`.
    NotLoading,
    /// The image does not fit a slot.
    TooLarge {
        /// Words of the image.
        words: u32,
        /// Words a slot holds for an image.
        capacity: u32,
    },
    /// An empty image.
    Empty,
    /// The image was made for another wiring than this firmware's: its
    /// signals would not mean what the pins carry.
    Wiring {
        /// This firmware's wiring signature.
        expected: u32,
        /// The image's.
        found: u32,
    },
    /// `Data` at another offset than the one expected, or not a whole
    /// number of words, or more than [`MAX_DATA`] bytes, or past the end.
    Offset {
        /// The byte offset expected.
        expected: u32,
    },
    /// `Commit` before every byte arrived.
    Incomplete {
        /// The byte offset expected next.
        expected: u32,
    },
    /// The image was checked and refused.
    Rejected(Rejected),
    /// The flash controller failed to erase or program the slot.
    Flash,
    /// A frame that was not a request (reported, then ignored).
    Frame,
}

/// The `Data` requests that carry `image` (its words as little-endian
/// bytes), [`MAX_DATA`] bytes each but the last: what a PC sends after
/// `Begin`.
pub fn data_requests(image: &[u8]) -> impl Iterator<Item = Request<'_>> {
    image
        .chunks(MAX_DATA)
        .enumerate()
        .map(|(k, bytes)| Request::Data {
            offset: (k * MAX_DATA) as u32,
            bytes,
        })
}

/// What the PC tells its user about a refusal.
impl core::fmt::Display for Refusal {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Refusal::NotLoading => write!(f, "no load in progress"),
            Refusal::TooLarge { words, capacity } => write!(
                f,
                "the image of {words} words does not fit a slot of {capacity}"
            ),
            Refusal::Empty => write!(f, "an empty image"),
            Refusal::Wiring { expected, found } => write!(
                f,
                "the image was made for other wiring (signature {found:#010x}; this firmware's is \
                 {expected:#010x}: its project's board, inputs or outputs differ from the \
                 firmware's)"
            ),
            Refusal::Offset { expected } => {
                write!(f, "data out of order (byte {expected} expected)")
            }
            Refusal::Incomplete { expected } => {
                write!(
                    f,
                    "commit before the whole image (byte {expected} expected)"
                )
            }
            Refusal::Rejected(why) => write!(f, "the image was checked and refused: {why}"),
            Refusal::Flash => write!(f, "the flash controller failed"),
            Refusal::Frame => write!(f, "a damaged frame"),
        }
    }
}
