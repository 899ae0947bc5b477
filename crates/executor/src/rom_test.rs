//! The background image test (a ROM test): the image CRC recomputed a
//! fixed number of words per scan, pass after pass (docs/semantics.md,
//! "Image check").
//!
//! A pass feeds the whole image stream ([`crate::image`]),
//! `rom_test_bytes_per_scan / 4` words per scan, and compares the CRC with
//! the one recorded at generation in the scan that feeds its last word;
//! the next pass starts in the next scan. A pass therefore takes exactly
//! P = ⌈image words / words per scan⌉ scans, and a bit that flips is found
//! at the latest by the (2P − 1)-th scan after it flips: the pass under
//! way may have read its word already, the next one reads it.
//!
//! The position and the running CRC are part of the controller's state,
//! advanced only by scans, so every target finds a corruption in the same
//! scan.

use crate::image::{self, CrcEngine, Cursor};
use crate::program::Program;

/// The background test's state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RomTest {
    /// Where the pass under way stands.
    cursor: Cursor,
    /// The last completed pass (or the full check at start-up) matched.
    verified: bool,
    /// Passes completed since start-up (the full check not counted).
    passes: u32,
}

/// What the background image test has done (see
/// [`crate::Controller::image_test`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImageTest {
    /// The last completed check of the whole image (the start-up check,
    /// a background pass or [`crate::Controller::check_image`]) matched
    /// the recorded CRC: a reset may leave fault mode.
    pub verified: bool,
    /// Background passes completed since start-up.
    pub passes: u32,
    /// Bytes of the image the pass under way has checked.
    pub checked_bytes: usize,
}

impl RomTest {
    /// The full check of `program`'s image, done now; the first background
    /// pass starts at the next scan.
    pub(crate) fn new<P: Program + ?Sized, E: CrcEngine + ?Sized>(
        program: &P,
        engine: &mut E,
    ) -> RomTest {
        RomTest {
            cursor: Cursor::START,
            verified: image::crc_with(program, engine) == program.recorded_crc(),
            passes: 0,
        }
    }

    /// One scan's share: feeds `rom_test_bytes_per_scan / 4` words of
    /// `program`'s image (at least one). `Some(matched)` when this scan
    /// completed a pass.
    pub(crate) fn step<P: Program + ?Sized, E: CrcEngine + ?Sized>(
        &mut self,
        program: &P,
        engine: &mut E,
    ) -> Option<bool> {
        let words = usize::from(program.config().rom_test_bytes_per_scan / 4).max(1);
        if !image::advance(program, &mut self.cursor, words, engine) {
            return None;
        }
        let matched = self.cursor.crc() == program.recorded_crc();
        self.record(matched);
        self.cursor = Cursor::START;
        self.passes = self.passes.wrapping_add(1);
        Some(matched)
    }

    /// The outcome of a complete check of the image.
    pub(crate) fn record(&mut self, matched: bool) {
        self.verified = matched;
    }

    /// What the test has done.
    pub(crate) fn status(&self) -> ImageTest {
        ImageTest {
            verified: self.verified,
            passes: self.passes,
            checked_bytes: 4 * self.cursor.fed(),
        }
    }
}

#[cfg(test)]
pub(crate) mod tests;
