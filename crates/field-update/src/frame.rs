//! Frames on the serial link: a postcard-encoded message, its CRC
//! ([`crate::CRC_ALGORITHM`], four bytes little-endian), all COBS-encoded
//! and ended by a zero byte. A receiver resynchronises on the next zero
//! after a damaged frame.

use crc::Crc;
use postcard::ser_flavors::{crc::CrcModifier, Cobs, Slice};
use serde::{Deserialize, Serialize};

/// Largest frame, zero byte included: a [`crate::protocol::Request::Data`]
/// of [`crate::protocol::MAX_DATA`] bytes with room to spare.
pub const MAX_FRAME: usize = 320;

/// Why a frame could not be written or read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrameError {
    /// More bytes before the zero byte than a frame may have.
    TooLong,
    /// Not valid COBS.
    Cobs,
    /// The CRC does not match: bytes were lost or changed.
    Crc,
    /// The bytes are not a message of the protocol (or the buffer for
    /// writing one is too small).
    Message,
}

/// Writes `message` as one frame into `buf`; returns the frame, zero byte
/// included.
pub fn encode<'b, T: Serialize + ?Sized>(
    message: &T,
    crc: &Crc<u32>,
    buf: &'b mut [u8],
) -> Result<&'b [u8], FrameError> {
    let cobs = Cobs::try_new(Slice::new(buf)).map_err(|_| FrameError::Message)?;
    let frame = postcard::serialize_with_flavor(message, CrcModifier::new(cobs, crc.digest()))
        .map_err(|_| FrameError::Message)?;
    Ok(frame)
}

/// Reads the message of a frame whose COBS bytes (without the zero byte)
/// are `frame`; decodes in place.
pub fn decode<'a, T: Deserialize<'a>>(
    frame: &'a mut [u8],
    crc: &Crc<u32>,
) -> Result<T, FrameError> {
    message(unframe(frame, crc)?)
}

/// The message bytes of a frame (COBS decoded in place, CRC checked and
/// cut off).
pub fn unframe<'a>(frame: &'a mut [u8], crc: &Crc<u32>) -> Result<&'a [u8], FrameError> {
    let len = cobs::decode_in_place(frame).map_err(|_| FrameError::Cobs)?;
    let bytes = &frame[..len];
    if bytes.len() < 4 {
        return Err(FrameError::Crc);
    }
    let (body, sum) = bytes.split_at(bytes.len() - 4);
    let mut digest = crc.digest();
    digest.update(body);
    if digest.finalize().to_le_bytes() != sum {
        return Err(FrameError::Crc);
    }
    Ok(body)
}

/// The message in `body` (a frame's bytes after [`unframe`]), every byte
/// used.
pub fn message<'a, T: Deserialize<'a>>(body: &'a [u8]) -> Result<T, FrameError> {
    match postcard::take_from_bytes::<T>(body) {
        Ok((message, [])) => Ok(message),
        _ => Err(FrameError::Message),
    }
}

/// Collects bytes from the link until a zero byte ends a frame.
#[derive(Debug)]
pub struct FrameReader<const N: usize = MAX_FRAME> {
    buf: [u8; N],
    len: usize,
    overflow: bool,
}

impl<const N: usize> Default for FrameReader<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> FrameReader<N> {
    /// An empty reader.
    pub const fn new() -> Self {
        FrameReader {
            buf: [0; N],
            len: 0,
            overflow: false,
        }
    }

    /// Takes one byte; at a zero byte, returns the frame it ends (its COBS
    /// bytes, for [`decode`]), or [`FrameError::TooLong`] if it did not
    /// fit. Empty frames (two zeros in a row) are skipped.
    pub fn push(&mut self, byte: u8) -> Option<Result<&mut [u8], FrameError>> {
        if byte != 0 {
            match self.buf.get_mut(self.len) {
                Some(slot) => {
                    *slot = byte;
                    self.len += 1;
                }
                None => self.overflow = true,
            }
            return None;
        }
        let (len, overflow) = (self.len, self.overflow);
        self.len = 0;
        self.overflow = false;
        if overflow {
            Some(Err(FrameError::TooLong))
        } else if len == 0 {
            None
        } else {
            Some(Ok(&mut self.buf[..len]))
        }
    }
}
