//! The two program slots and which one runs.

use crate::crc_of_words;
use crate::header::{HeaderFault, SlotHeader, HEADER_WORDS};
use crc::Crc;

/// One of the two program slots.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Slot {
    /// The first slot.
    A,
    /// The second slot.
    B,
}

impl Slot {
    /// Both slots, A first.
    pub const BOTH: [Slot; 2] = [Slot::A, Slot::B];

    /// The other slot.
    pub const fn other(self) -> Slot {
        match self {
            Slot::A => Slot::B,
            Slot::B => Slot::A,
        }
    }
}

/// Flash (or, in tests and QEMU, RAM) holding the two slots, each a whole
/// number of erase sectors of the same size.
pub trait SlotStore {
    /// What went wrong in the flash controller.
    type Error: core::fmt::Debug;

    /// Words of one slot, header included.
    fn slot_words(&self) -> usize;

    /// The slot's words as the program reads them (memory-mapped flash).
    fn contents(&self, slot: Slot) -> &[u32];

    /// Erases at least the slot's first `words` words (every one becomes
    /// `0xFFFF_FFFF`): the header and the image a load announced. A store
    /// erases whole units of its flash, so it may erase more (the
    /// STM32F411's unit is the slot, a 128 KiB sector); the words after
    /// the image are never read.
    fn erase(&mut self, slot: Slot, words: usize) -> Result<(), Self::Error>;

    /// Programs `words` at word `offset` of an erased part of the slot.
    fn program(&mut self, slot: Slot, offset: usize, words: &[u32]) -> Result<(), Self::Error>;
}

/// What the firmware asks of an image before it runs it: the wiring
/// signature of its header, then (after the CRC against the header) the
/// executor's structure check.
pub trait Check {
    /// The wiring signature of this firmware's project
    /// ([`SlotHeader::wiring`]): an image whose header records another is
    /// not run.
    fn wiring(&self) -> u32;

    /// `Err(code)` when `image` is not a program this firmware can run;
    /// the code names the first flaw found (reported to the loader).
    fn check(&mut self, image: &[u32]) -> Result<(), u16>;
}

/// Why a slot was not chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Rejected {
    /// Never written, or written only in part (no valid header).
    Empty,
    /// The header is there but damaged (layout, CRC or length).
    Header,
    /// The image was made for another wiring than this firmware's.
    Wiring {
        /// This firmware's wiring signature.
        expected: u32,
        /// The one the header records.
        found: u32,
    },
    /// The image's CRC is not the header's: found, recorded.
    ImageCrc {
        /// The CRC of the words in the slot.
        found: u32,
        /// The CRC the header records.
        recorded: u32,
    },
    /// The structure check refused the image (its code).
    Structure(u16),
}

impl From<HeaderFault> for Rejected {
    fn from(fault: HeaderFault) -> Rejected {
        match fault {
            HeaderFault::Short | HeaderFault::Magic => Rejected::Empty,
            HeaderFault::Format(_) | HeaderFault::Crc | HeaderFault::Length(_) => Rejected::Header,
        }
    }
}

/// A slot whose header, image CRC and structure check pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Valid {
    /// The slot.
    pub slot: Slot,
    /// Its header.
    pub header: SlotHeader,
}

/// What runs after start-up: the newest valid slot, or the built-in
/// program, with the reason each slot was passed over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Choice {
    /// The slot that runs, `None` for the program built into the firmware.
    pub running: Option<Valid>,
    /// Per slot (A, B): why it is not valid, `None` when it is.
    pub rejected: [Option<Rejected>; 2],
}

/// The image of `slot` checked in full: header, image CRC, structure.
pub fn verify(
    store: &impl SlotStore,
    slot: Slot,
    crc: &Crc<u32>,
    check: &mut impl Check,
) -> Result<Valid, Rejected> {
    let words = store.contents(slot);
    let header = SlotHeader::read(words, crc)?;
    let image = image_of(words, &header);
    accept(image, &header, crc_of_words(crc, image), check)?;
    Ok(Valid { slot, header })
}

/// The verdict on an image whose CRC, `found`, is computed: the header's
/// wiring and CRC, then the firmware's check. What start-up ([`verify`])
/// and a load ([`crate::loader::Loader::poll`]) both ask.
pub(crate) fn accept(
    image: &[u32],
    header: &SlotHeader,
    found: u32,
    check: &mut impl Check,
) -> Result<(), Rejected> {
    if header.wiring != check.wiring() {
        return Err(Rejected::Wiring {
            expected: check.wiring(),
            found: header.wiring,
        });
    }
    if found != header.image_crc {
        return Err(Rejected::ImageCrc {
            found,
            recorded: header.image_crc,
        });
    }
    check.check(image).map_err(Rejected::Structure)
}

/// The image words of a slot whose header was read from it.
pub fn image_of<'a>(slot_words: &'a [u32], header: &SlotHeader) -> &'a [u32] {
    let end = HEADER_WORDS.saturating_add(header.words as usize);
    slot_words.get(HEADER_WORDS..end).unwrap_or(&[])
}

/// Which program runs: the valid slot with the higher sequence number
/// (on a tie, A), else the built-in program.
pub fn choose(store: &impl SlotStore, crc: &Crc<u32>, check: &mut impl Check) -> Choice {
    let mut rejected = [None, None];
    let mut running: Option<Valid> = None;
    for (k, slot) in Slot::BOTH.into_iter().enumerate() {
        match verify(store, slot, crc, check) {
            Ok(valid) => {
                if running.is_none_or(|r| valid.header.sequence > r.header.sequence) {
                    running = Some(valid);
                }
            }
            Err(why) => rejected[k] = Some(why),
        }
    }
    Choice { running, rejected }
}

/// Two slots in RAM with NOR flash's rules (programming only clears
/// bits, erasing sets them all): the QEMU harness's slots, and the tests'.
#[derive(Debug)]
pub struct RamSlots<'a> {
    a: &'a mut [u32],
    b: &'a mut [u32],
}

/// Programming a RAM slot outside its erased words or range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RamSlotError {
    /// Past the end of the slot.
    OutOfRange,
    /// A word not erased since it was programmed.
    NotErased,
}

impl<'a> RamSlots<'a> {
    /// Slots over two buffers of the same length, as they are (erase
    /// them first if they hold nothing).
    pub fn new(a: &'a mut [u32], b: &'a mut [u32]) -> RamSlots<'a> {
        let len = a.len().min(b.len());
        let (a, _) = a.split_at_mut(len);
        let (b, _) = b.split_at_mut(len);
        RamSlots { a, b }
    }

    /// The slot's words, writable: how the tests damage a slot.
    pub fn words_mut(&mut self, slot: Slot) -> &mut [u32] {
        match slot {
            Slot::A => self.a,
            Slot::B => self.b,
        }
    }
}

impl SlotStore for RamSlots<'_> {
    type Error = RamSlotError;

    fn slot_words(&self) -> usize {
        self.a.len()
    }

    fn contents(&self, slot: Slot) -> &[u32] {
        match slot {
            Slot::A => self.a,
            Slot::B => self.b,
        }
    }

    /// Erases exactly the first `words` words (all of the slot when it
    /// has fewer), leaving the rest as it was: what comes after an image
    /// must not matter.
    fn erase(&mut self, slot: Slot, words: usize) -> Result<(), RamSlotError> {
        let slot = self.words_mut(slot);
        let end = words.min(slot.len());
        slot[..end].fill(u32::MAX);
        Ok(())
    }

    fn program(&mut self, slot: Slot, offset: usize, words: &[u32]) -> Result<(), RamSlotError> {
        let target = self
            .words_mut(slot)
            .get_mut(offset..offset.saturating_add(words.len()))
            .ok_or(RamSlotError::OutOfRange)?;
        if target.iter().any(|&w| w != u32::MAX) {
            return Err(RamSlotError::NotErased);
        }
        target.copy_from_slice(words);
        Ok(())
    }
}

/// Why a slot was not chosen, in words.
impl core::fmt::Display for Rejected {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Rejected::Empty => write!(f, "no valid slot header"),
            Rejected::Header => write!(f, "a damaged slot header"),
            Rejected::Wiring { expected, found } => write!(
                f,
                "made for other wiring (signature {found:#010x}, the firmware's {expected:#010x})"
            ),
            Rejected::ImageCrc { found, recorded } => write!(
                f,
                "image CRC {found:#010x}, its header records {recorded:#010x}"
            ),
            Rejected::Structure(code) => write!(f, "structure check code {code:#06x}"),
        }
    }
}
