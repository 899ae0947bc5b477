//! The loader against RAM slots: loads, refusals, damaged slots and
//! frames, and hostile request streams.

use crate::frame::{self, FrameError, FrameReader, MAX_FRAME};
use crate::header::{SlotHeader, HEADER_WORDS};
use crate::loader::{Loader, Outcome, Reply};
use crate::protocol::{data_requests, Refusal, Request, Response};
use crate::slot::{choose, Check, RamSlots, Rejected, Slot, SlotStore, Valid};
use crate::{crc_of_words, CRC_ALGORITHM};
use crc::Crc;
use proptest::prelude::*;

static CRC: Crc<u32> = Crc::<u32>::new(&CRC_ALGORITHM);

const SLOT_WORDS: usize = 256;

/// The tests' firmware's wiring signature.
const WIRING: u32 = 0x5EED_0001;

/// A structure check for the tests: an image is valid when its first word
/// is its length and no word is `0xDEAD`.
struct LengthCheck;

impl Check for LengthCheck {
    fn wiring(&self) -> u32 {
        WIRING
    }

    fn check(&mut self, image: &[u32]) -> Result<(), u16> {
        if image.first() != Some(&(image.len() as u32)) {
            return Err(1);
        }
        if image.contains(&0xDEAD) {
            return Err(2);
        }
        Ok(())
    }
}

fn image(len: usize, seed: u32) -> Vec<u32> {
    let mut words: Vec<u32> = (0..len as u32)
        .map(|k| k.wrapping_mul(0x9E37_79B9) ^ seed)
        .collect();
    words[0] = len as u32;
    words.retain(|&w| w != 0xDEAD);
    words.resize(len, 7);
    words
}

fn bytes(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}

/// Sends every request of a load through frames, as the link carries
/// them; returns the answer to `Commit` (after polling `budget` words at
/// a time) or the first refusal.
fn load(
    loader: &mut Loader<'_>,
    slots: &mut RamSlots<'_>,
    words: &[u32],
    image_crc: u32,
    budget: usize,
) -> Outcome {
    let image_bytes = bytes(words);
    let begin = Request::Begin {
        words: words.len() as u32,
        image_crc,
        version: 0x0001_0200,
        wiring: WIRING,
    };
    let requests = [begin]
        .into_iter()
        .chain(data_requests(&image_bytes))
        .chain([Request::Commit]);
    for request in requests {
        match through_link(loader, slots, &request) {
            Reply::Send(Response::Refused(why)) => return Outcome::Refused(why),
            Reply::Send(Response::Next { .. }) => {}
            Reply::Later => {
                let mut polls = 0;
                loop {
                    polls += 1;
                    if let Some(outcome) = loader.poll(slots, &mut LengthCheck, budget) {
                        assert_eq!(polls, words.len().div_ceil(budget.max(1)).max(1));
                        return outcome;
                    }
                }
            }
            other => panic!("unexpected reply {other:?}"),
        }
    }
    unreachable!("Commit is answered later")
}

/// [`load`] of `words` under their own CRC, which must switch to them:
/// the slot and header now running.
fn load_switched(
    loader: &mut Loader<'_>,
    slots: &mut RamSlots<'_>,
    words: &[u32],
    budget: usize,
) -> Valid {
    match load(loader, slots, words, crc_of_words(&CRC, words), budget) {
        Outcome::Switched(valid) => valid,
        outcome => panic!("{outcome:?}"),
    }
}

/// Encodes `request` as a frame, reads it back byte by byte as the PLC
/// does, and hands it to the loader.
fn through_link(loader: &mut Loader<'_>, slots: &mut RamSlots<'_>, request: &Request<'_>) -> Reply {
    let mut out = [0u8; MAX_FRAME];
    let frame = frame::encode(request, &CRC, &mut out).expect("a request fits a frame");
    let mut reader = FrameReader::<MAX_FRAME>::new();
    let (last, body) = frame.split_last().expect("a frame");
    assert_eq!(*last, 0);
    for &b in body {
        assert!(reader.push(b).is_none());
    }
    let received = reader
        .push(0)
        .expect("the zero ends the frame")
        .expect("intact");
    let decoded: Request<'_> = frame::decode(received, &CRC).expect("intact");
    assert_eq!(&decoded, request);
    loader.handle(decoded, slots)
}

fn fresh() -> (Vec<u32>, Vec<u32>) {
    (vec![u32::MAX; SLOT_WORDS], vec![u32::MAX; SLOT_WORDS])
}

#[test]
fn loads_alternate_between_slots_and_the_newest_valid_slot_runs() {
    let (mut a, mut b) = fresh();
    let mut slots = RamSlots::new(&mut a, &mut b);
    let mut loader = Loader::new(&CRC, None, &LengthCheck);

    let one = load_switched(&mut loader, &mut slots, &image(100, 1), 16);
    assert_eq!((one.slot, one.header.sequence), (Slot::A, 1));

    let two = load_switched(&mut loader, &mut slots, &image(200, 2), 1000);
    assert_eq!(
        (two.slot, two.header.sequence, two.header.version),
        (Slot::B, 2, 0x0001_0200)
    );

    let choice = choose(&slots, &CRC, &mut LengthCheck);
    assert_eq!(choice.running, Some(two));
    assert_eq!(choice.rejected, [None, None]);

    // One flipped bit in B's image: B is passed over, A runs again.
    slots.words_mut(Slot::B)[HEADER_WORDS + 150] ^= 1 << 7;
    let choice = choose(&slots, &CRC, &mut LengthCheck);
    assert_eq!(choice.running, Some(one));
    assert!(matches!(
        choice.rejected[1],
        Some(Rejected::ImageCrc { .. })
    ));

    // A damaged header too: the built-in program runs.
    slots.words_mut(Slot::A)[3] ^= 1;
    let choice = choose(&slots, &CRC, &mut LengthCheck);
    assert_eq!(choice.running, None);
    assert_eq!(choice.rejected[0], Some(Rejected::Header));
}

#[test]
fn a_load_erases_its_header_and_image_only_and_the_old_tail_does_not_matter() {
    let (mut a, mut b) = fresh();
    let mut slots = RamSlots::new(&mut a, &mut b);
    let mut loader = Loader::new(&CRC, None, &LengthCheck);
    // A long image in A, another in B: B runs.
    for (len, seed) in [(200, 3), (220, 4)] {
        load_switched(&mut loader, &mut slots, &image(len, seed), 64);
    }
    let old_tail: Vec<u32> = slots.contents(Slot::A)[HEADER_WORDS + 50..].to_vec();
    assert!(old_tail[..150].iter().all(|&w| w != u32::MAX));
    // A short image goes into A, over the first one's head only.
    let short = image(50, 5);
    let three = load_switched(&mut loader, &mut slots, &short, 64);
    assert_eq!((three.slot, three.header.sequence), (Slot::A, 3));
    let slot = slots.contents(Slot::A);
    assert_eq!(slot[HEADER_WORDS..HEADER_WORDS + 50], short[..]);
    assert_eq!(
        slot[HEADER_WORDS + 50..],
        old_tail[..],
        "not erased, not read"
    );
    // The short image runs, at start-up too.
    let choice = choose(&slots, &CRC, &mut LengthCheck);
    assert_eq!(choice.running, Some(three));
    assert_eq!(choice.rejected, [None, None]);
}

#[test]
fn a_refused_image_leaves_the_running_program_and_no_valid_slot() {
    let (mut a, mut b) = fresh();
    let mut slots = RamSlots::new(&mut a, &mut b);
    let mut loader = Loader::new(&CRC, None, &LengthCheck);
    let good = image(40, 3);
    let running = load_switched(&mut loader, &mut slots, &good, 8);

    // Structurally wrong, with a matching CRC (a hostile image).
    let mut bad = image(40, 4);
    bad[9] = 0xDEAD;
    let outcome = load(&mut loader, &mut slots, &bad, crc_of_words(&CRC, &bad), 8);
    assert_eq!(
        outcome,
        Outcome::Refused(Refusal::Rejected(Rejected::Structure(2)))
    );
    // The CRC of another image.
    let outcome = load(&mut loader, &mut slots, &good, 0x1234_5678, 8);
    assert!(matches!(
        outcome,
        Outcome::Refused(Refusal::Rejected(Rejected::ImageCrc {
            recorded: 0x1234_5678,
            ..
        }))
    ));

    assert_eq!(loader.running(), Some(running));
    let choice = choose(&slots, &CRC, &mut LengthCheck);
    assert_eq!(choice.running, Some(running));
    assert_eq!(
        choice.rejected[1],
        Some(Rejected::Empty),
        "no header was written to B"
    );
}

#[test]
fn a_load_cut_short_never_runs() {
    let (mut a, mut b) = fresh();
    let mut slots = RamSlots::new(&mut a, &mut b);
    let mut loader = Loader::new(&CRC, None, &LengthCheck);
    let words = image(100, 5);
    let image_bytes = bytes(&words);
    let begin = Request::Begin {
        words: 100,
        image_crc: crc_of_words(&CRC, &words),
        version: 1,
        wiring: WIRING,
    };
    assert_eq!(
        loader.handle(begin, &mut slots),
        Reply::Send(Response::Next { offset: 0 })
    );
    let first = data_requests(&image_bytes).next().expect("a chunk");
    assert_eq!(
        loader.handle(first, &mut slots),
        Reply::Send(Response::Next { offset: 256 })
    );
    // The same chunk again (its answer was lost): acknowledged, not written twice.
    assert_eq!(
        loader.handle(first, &mut slots),
        Reply::Send(Response::Next { offset: 256 })
    );
    // A chunk from further on.
    let skipped = Request::Data {
        offset: 512,
        bytes: &image_bytes[..4],
    };
    assert_eq!(
        loader.handle(skipped, &mut slots),
        Reply::Send(Response::Refused(Refusal::Offset { expected: 256 }))
    );
    assert_eq!(
        loader.handle(Request::Commit, &mut slots),
        Reply::Send(Response::Refused(Refusal::Incomplete { expected: 256 }))
    );
    // Power cut here: the words are in A, its header is not.
    assert_eq!(choose(&slots, &CRC, &mut LengthCheck).running, None);
    assert_eq!(loader.handle(Request::Abort, &mut slots), Reply::Status);
    assert!(!loader.is_loading());
    assert_eq!(
        loader.handle(Request::Commit, &mut slots),
        Reply::Send(Response::Refused(Refusal::NotLoading))
    );
}

#[test]
fn images_too_large_or_empty_are_refused_before_the_erase() {
    let (mut a, mut b) = fresh();
    a[0] = 0x1234;
    let mut slots = RamSlots::new(&mut a, &mut b);
    let mut loader = Loader::new(&CRC, None, &LengthCheck);
    let too_large = Request::Begin {
        words: (SLOT_WORDS - HEADER_WORDS + 1) as u32,
        image_crc: 0,
        version: 0,
        wiring: WIRING,
    };
    assert_eq!(
        loader.handle(too_large, &mut slots),
        Reply::Send(Response::Refused(Refusal::TooLarge {
            words: (SLOT_WORDS - HEADER_WORDS + 1) as u32,
            capacity: (SLOT_WORDS - HEADER_WORDS) as u32
        }))
    );
    let empty = Request::Begin {
        words: 0,
        image_crc: 0,
        version: 0,
        wiring: WIRING,
    };
    assert_eq!(
        loader.handle(empty, &mut slots),
        Reply::Send(Response::Refused(Refusal::Empty))
    );
    assert_eq!(slots.contents(Slot::A)[0], 0x1234, "nothing was erased");
}

#[test]
fn an_image_of_other_wiring_is_refused_before_the_erase_and_never_chosen() {
    let (mut a, mut b) = fresh();
    a[0] = 0x1234;
    let mut slots = RamSlots::new(&mut a, &mut b);
    let mut loader = Loader::new(&CRC, None, &LengthCheck);
    let words = image(20, 3);
    let other = Request::Begin {
        words: 20,
        image_crc: crc_of_words(&CRC, &words),
        version: 1,
        wiring: WIRING ^ 0x100,
    };
    assert_eq!(
        loader.handle(other, &mut slots),
        Reply::Send(Response::Refused(Refusal::Wiring {
            expected: WIRING,
            found: WIRING ^ 0x100
        }))
    );
    assert!(!loader.is_loading());
    assert_eq!(slots.contents(Slot::A)[0], 0x1234, "nothing was erased");

    // Written into a slot by other means (a debug probe): its header and
    // image check, its wiring does not, and it is passed over.
    let header = SlotHeader {
        sequence: 1,
        version: 1,
        words: 20,
        image_crc: crc_of_words(&CRC, &words),
        wiring: WIRING ^ 0x100,
    };
    slots.erase(Slot::A, SLOT_WORDS).unwrap();
    slots.program(Slot::A, 0, &header.to_words(&CRC)).unwrap();
    slots.program(Slot::A, HEADER_WORDS, &words).unwrap();
    let choice = choose(&slots, &CRC, &mut LengthCheck);
    assert_eq!(choice.running, None);
    assert_eq!(
        choice.rejected[0],
        Some(Rejected::Wiring {
            expected: WIRING,
            found: WIRING ^ 0x100
        })
    );
    // The same image with the firmware's wiring runs.
    let header = SlotHeader {
        wiring: WIRING,
        ..header
    };
    slots.erase(Slot::A, SLOT_WORDS).unwrap();
    slots.program(Slot::A, 0, &header.to_words(&CRC)).unwrap();
    slots.program(Slot::A, HEADER_WORDS, &words).unwrap();
    let running = choose(&slots, &CRC, &mut LengthCheck).running;
    assert_eq!(running.map(|v| (v.slot, v.header)), Some((Slot::A, header)));
}

/// A slot store that counts its erases.
pub(crate) struct Counting<'a> {
    /// The slots.
    pub slots: RamSlots<'a>,
    /// Erases so far.
    pub erases: &'a mut usize,
}

impl SlotStore for Counting<'_> {
    type Error = <RamSlots<'static> as SlotStore>::Error;

    fn slot_words(&self) -> usize {
        self.slots.slot_words()
    }

    fn contents(&self, slot: Slot) -> &[u32] {
        self.slots.contents(slot)
    }

    fn erase(&mut self, slot: Slot, words: usize) -> Result<(), Self::Error> {
        *self.erases += 1;
        self.slots.erase(slot, words)
    }

    fn program(&mut self, slot: Slot, offset: usize, words: &[u32]) -> Result<(), Self::Error> {
        self.slots.program(slot, offset, words)
    }
}

#[test]
fn a_begin_sent_again_before_any_data_does_not_erase_again() {
    let (mut a, mut b) = fresh();
    let mut erases = 0;
    let mut store = Counting {
        slots: RamSlots::new(&mut a, &mut b),
        erases: &mut erases,
    };
    let mut loader = Loader::new(&CRC, None, &LengthCheck);
    let words = image(20, 3);
    let begin = Request::Begin {
        words: 20,
        image_crc: crc_of_words(&CRC, &words),
        version: 7,
        wiring: WIRING,
    };
    let next = |offset| Reply::Send(Response::Next { offset });
    for _ in 0..3 {
        assert_eq!(loader.handle(begin, &mut store), next(0));
    }
    assert_eq!(*store.erases, 1, "one erase for the Begin and its repeats");
    // Another image's Begin is another load: its own erase.
    let other = Request::Begin {
        words: 20,
        image_crc: 1,
        version: 7,
        wiring: WIRING,
    };
    assert_eq!(loader.handle(other, &mut store), next(0));
    assert_eq!(*store.erases, 2);
    // Once a word is written, the same Begin starts the load over: the
    // slot is erased again before it is written again.
    assert_eq!(loader.handle(begin, &mut store), next(0));
    let image_bytes = bytes(&words);
    let first = data_requests(&image_bytes).next().expect("a chunk");
    assert_eq!(loader.handle(first, &mut store), next(80));
    assert_eq!(loader.handle(begin, &mut store), next(0));
    assert_eq!(*store.erases, 4);
    for request in data_requests(&image_bytes) {
        assert_eq!(loader.handle(request, &mut store), next(80));
    }
    assert_eq!(loader.handle(Request::Commit, &mut store), Reply::Later);
    let outcome = loop {
        if let Some(outcome) = loader.poll(&mut store, &mut LengthCheck, 8) {
            break outcome;
        }
    };
    assert!(
        matches!(outcome, Outcome::Switched(v) if v.slot == Slot::A),
        "{outcome:?}"
    );
    assert_eq!(*store.erases, 4);
}

#[test]
fn a_damaged_frame_is_refused_and_the_next_one_is_read() {
    let mut out = [0u8; MAX_FRAME];
    let frame = frame::encode(&Request::Commit, &CRC, &mut out)
        .expect("fits")
        .to_vec();
    let mut damaged = frame.clone();
    damaged[1] ^= 0x10;
    let mut reader = FrameReader::<MAX_FRAME>::new();
    let mut results = Vec::new();
    for &b in damaged.iter().chain(&frame) {
        if let Some(frame) = reader.push(b) {
            results.push(
                frame.and_then(|f| frame::decode::<Request<'_>>(f, &CRC).map(|r| format!("{r:?}"))),
            );
        }
    }
    assert_eq!(results.len(), 2);
    assert!(
        matches!(results[0], Err(FrameError::Crc | FrameError::Cobs)),
        "{:?}",
        results[0]
    );
    assert_eq!(results[1], Ok("Commit".to_owned()));

    let mut reader = FrameReader::<8>::new();
    for b in 1..=20u8 {
        assert!(reader.push(b).is_none());
    }
    assert_eq!(
        reader.push(0).map(|r| r.map(|_| ())),
        Some(Err(FrameError::TooLong))
    );
}

#[test]
fn slot_headers_round_trip_and_refuse_damage() {
    let header = SlotHeader {
        sequence: 7,
        version: 0x0002_0001,
        words: 10,
        image_crc: 0xCAFE_F00D,
        wiring: WIRING,
    };
    let mut slot = vec![u32::MAX; 32];
    slot[..HEADER_WORDS].copy_from_slice(&header.to_words(&CRC));
    assert_eq!(SlotHeader::read(&slot, &CRC), Ok(header));
    for k in 0..HEADER_WORDS {
        let mut damaged = slot.clone();
        damaged[k] ^= 1 << (k * 3 % 32);
        assert!(SlotHeader::read(&damaged, &CRC).is_err(), "word {k}");
    }
    let long = SlotHeader {
        words: 25,
        ..header
    };
    slot[..HEADER_WORDS].copy_from_slice(&long.to_words(&CRC));
    assert!(
        SlotHeader::read(&slot, &CRC).is_err(),
        "25 words do not fit 24"
    );
}

proptest! {
    /// Any bytes on the link: no panic, and a slot becomes valid only
    /// with an image the check accepts and whose CRC its header records.
    #[test]
    fn hostile_bytes_never_make_a_slot_valid_unless_it_passes(stream in proptest::collection::vec(any::<u8>(), 0..2000)) {
        let (mut a, mut b) = fresh();
        let mut slots = RamSlots::new(&mut a, &mut b);
        let mut loader = Loader::new(&CRC, None, &LengthCheck);
        let mut reader = FrameReader::<MAX_FRAME>::new();
        for &byte in &stream {
            if let Some(Ok(frame)) = reader.push(byte) {
                if let Ok(request) = frame::decode::<Request<'_>>(frame, &CRC) {
                    let _ = loader.handle(request, &mut slots);
                }
            }
            let _ = loader.poll(&mut slots, &mut LengthCheck, 4);
        }
        let choice = choose(&slots, &CRC, &mut LengthCheck);
        if let Some(valid) = choice.running {
            let words = slots.contents(valid.slot);
            let image = &words[HEADER_WORDS..HEADER_WORDS + valid.header.words as usize];
            prop_assert_eq!(crc_of_words(&CRC, image), valid.header.image_crc);
            prop_assert_eq!(valid.header.wiring, WIRING);
            prop_assert!(LengthCheck.check(image).is_ok());
        }
    }

    /// Random well-formed requests in any order: the same guarantee.
    #[test]
    fn requests_in_any_order_keep_the_guarantee(ops in proptest::collection::vec((0u8..5, 0u32..80, any::<u32>()), 0..60)) {
        let (mut a, mut b) = fresh();
        let mut slots = RamSlots::new(&mut a, &mut b);
        let mut loader = Loader::new(&CRC, None, &LengthCheck);
        let data = bytes(&image(80, 9));
        for (kind, n, x) in ops {
            let request = match kind {
                0 => Request::Begin { words: n, image_crc: x, version: 0, wiring: if n % 7 == 0 { x } else { WIRING } },
                1 => { let at = (n as usize * 4).min(data.len()); Request::Data { offset: at as u32, bytes: &data[at..(at + 64).min(data.len())] } }
                2 => Request::Commit,
                3 => Request::Abort,
                _ => Request::Status,
            };
            let _ = loader.handle(request, &mut slots);
            let _ = loader.poll(&mut slots, &mut LengthCheck, (x % 100) as usize);
        }
        if let Some(valid) = choose(&slots, &CRC, &mut LengthCheck).running {
            let image = &slots.contents(valid.slot)[HEADER_WORDS..HEADER_WORDS + valid.header.words as usize];
            prop_assert_eq!(crc_of_words(&CRC, image), valid.header.image_crc);
            prop_assert_eq!(valid.header.wiring, WIRING);
            prop_assert!(LengthCheck.check(image).is_ok());
        }
    }
}
