//! The PLC side of a load: requests in, responses out, the slot written
//! and checked, and the moment the new program may run.
//!
//! The firmware feeds each request it reads to [`Loader::handle`], and
//! calls [`Loader::poll`] once per scan with a budget of words, so that
//! checking a large image is spread over scans like the background image
//! check. When `poll` returns [`Outcome::Switched`], the firmware starts
//! the new program before the next scan: the switch takes at most one
//! scan period after the check completes.

use crate::frame::{decode, encode, FrameReader, MAX_FRAME};
use crate::header::{SlotHeader, HEADER_WORDS};
use crate::protocol::{Refusal, Request, Response, Status, MAX_DATA};
use crate::slot::{accept, image_of, Check, Slot, SlotStore, Valid};
use crc::Crc;

/// Where a load stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Idle,
    /// Bytes arrive; `next` is the byte offset expected.
    Receiving {
        slot: Slot,
        header: SlotHeader,
        next: u32,
    },
    /// `Commit` came: the image CRC is computed `budget` words per poll.
    Checking {
        slot: Slot,
        header: SlotHeader,
        checked: usize,
        crc: u32,
    },
}

/// What the firmware does with a request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reply {
    /// Send this response.
    Send(Response<'static>),
    /// Send the firmware's status ([`Response::Status`], with
    /// [`Loader::expected`] as the load in progress).
    Status,
    /// Send nothing yet: [`Loader::poll`] gives the answer to `Commit`.
    Later,
}

/// The end of a check that `Commit` started.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Outcome {
    /// The image passed and its header is written: run it from the next
    /// scan on. Answer [`Response::Switched`].
    Switched(Valid),
    /// The image was refused; what runs is unchanged. Answer
    /// [`Response::Refused`].
    Refused(Refusal),
}

impl Outcome {
    /// The response that reports the outcome.
    pub fn response(&self) -> Response<'static> {
        match *self {
            Outcome::Switched(valid) => Response::Switched {
                slot: valid.slot,
                sequence: valid.header.sequence,
            },
            Outcome::Refused(why) => Response::Refused(why),
        }
    }
}

/// The PLC side of the protocol.
pub struct Loader<'c> {
    crc: &'c Crc<u32>,
    /// The firmware's wiring signature: a `Begin` of another is refused.
    wiring: u32,
    running: Option<Valid>,
    state: State,
    /// The outcome of the last commit, until the next `Begin` or `Abort`:
    /// a `Commit` sent again after its answer was lost gets it again.
    finished: Option<Outcome>,
}

impl core::fmt::Debug for Loader<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Loader")
            .field("running", &self.running)
            .field("state", &self.state)
            .finish_non_exhaustive()
    }
}

impl<'c> Loader<'c> {
    /// A loader for a controller running `running` (from
    /// [`crate::slot::choose`]; `None`: the built-in program) whose
    /// images `check` checks: a `Begin` must name its [`Check::wiring`],
    /// so the loader and the check cannot disagree on it.
    pub fn new(crc: &'c Crc<u32>, running: Option<Valid>, check: &impl Check) -> Loader<'c> {
        Loader {
            crc,
            wiring: check.wiring(),
            running,
            state: State::Idle,
            finished: None,
        }
    }

    /// The slot that runs, `None` for the built-in program.
    pub fn running(&self) -> Option<Valid> {
        self.running
    }

    /// The byte offset a load in progress expects next; `None` when no
    /// load is in progress.
    pub fn expected(&self) -> Option<u32> {
        match self.state {
            State::Idle => None,
            State::Receiving { next, .. } => Some(next),
            State::Checking { header, .. } => Some(header.words.saturating_mul(4)),
        }
    }

    /// `true` from `Commit` until its check ends: [`Loader::poll`] has
    /// work to do.
    pub fn is_checking(&self) -> bool {
        matches!(self.state, State::Checking { .. })
    }

    /// `true` from `Begin` until the load is committed, refused or
    /// aborted.
    pub fn is_loading(&self) -> bool {
        self.state != State::Idle
    }

    /// Handles one request.
    pub fn handle<S: SlotStore>(&mut self, request: Request<'_>, store: &mut S) -> Reply {
        let refuse = |why| Reply::Send(Response::Refused(why));
        match (request, self.state) {
            (Request::Status, _) => Reply::Status,
            (Request::Commit, State::Idle) => match self.finished {
                Some(outcome) => Reply::Send(outcome.response()),
                None => refuse(Refusal::NotLoading),
            },
            (Request::Abort, State::Idle) => refuse(Refusal::NotLoading),
            (Request::Abort, _) => {
                self.state = State::Idle;
                self.finished = None;
                Reply::Status
            }
            (
                Request::Begin {
                    words,
                    image_crc,
                    version,
                    wiring,
                },
                State::Receiving {
                    header, next: 0, ..
                },
            ) if (
                header.words,
                header.image_crc,
                header.version,
                header.wiring,
            ) == (words, image_crc, version, wiring) =>
            {
                // The same `Begin` sent again after its answer was lost (or
                // came late: the erase stalls the PLC for seconds): its slot
                // is erased and nothing is written yet, so it is answered
                // again without a second erase.
                Reply::Send(Response::Next { offset: 0 })
            }
            (
                Request::Begin {
                    words,
                    image_crc,
                    version,
                    wiring,
                },
                _,
            ) => {
                self.state = State::Idle;
                self.finished = None;
                if wiring != self.wiring {
                    return refuse(Refusal::Wiring {
                        expected: self.wiring,
                        found: wiring,
                    });
                }
                let capacity = store.slot_words().saturating_sub(HEADER_WORDS);
                if words == 0 {
                    return refuse(Refusal::Empty);
                }
                if usize::try_from(words).map_or(true, |w| w > capacity) {
                    return refuse(Refusal::TooLarge {
                        words,
                        capacity: u32::try_from(capacity).unwrap_or(u32::MAX),
                    });
                }
                let slot = self.running.map_or(Slot::A, |r| r.slot.other());
                // The header and the image, not the whole slot: a small
                // program's erase (the pause of the control) is short
                // where the flash erases small units (the Pico's).
                if store.erase(slot, HEADER_WORDS + words as usize).is_err() {
                    return refuse(Refusal::Flash);
                }
                let sequence = self
                    .running
                    .map_or(1, |r| r.header.sequence.saturating_add(1));
                self.state = State::Receiving {
                    slot,
                    header: SlotHeader {
                        sequence,
                        version,
                        words,
                        image_crc,
                        wiring,
                    },
                    next: 0,
                };
                Reply::Send(Response::Next { offset: 0 })
            }
            (Request::Data { offset, bytes }, State::Receiving { slot, header, next }) => {
                let end = u64::from(offset) + bytes.len() as u64;
                if offset < next && end <= u64::from(next) {
                    // A chunk sent again after its answer was lost.
                    return Reply::Send(Response::Next { offset: next });
                }
                let fits = end <= u64::from(header.words) * 4;
                if offset != next || bytes.len() % 4 != 0 || bytes.len() > MAX_DATA || !fits {
                    return refuse(Refusal::Offset { expected: next });
                }
                let mut words = [0u32; MAX_DATA / 4];
                let words = &mut words[..bytes.len() / 4];
                for (word, chunk) in words.iter_mut().zip(bytes.chunks_exact(4)) {
                    *word = u32::from_le_bytes([chunk[0], chunk[1], chunk[2], chunk[3]]);
                }
                let at = HEADER_WORDS + offset as usize / 4;
                if store.program(slot, at, words).is_err() {
                    self.state = State::Idle;
                    return refuse(Refusal::Flash);
                }
                let next = next + bytes.len() as u32;
                self.state = State::Receiving { slot, header, next };
                Reply::Send(Response::Next { offset: next })
            }
            (Request::Commit, State::Receiving { slot, header, next }) => {
                if u64::from(next) != u64::from(header.words) * 4 {
                    return refuse(Refusal::Incomplete { expected: next });
                }
                self.state = State::Checking {
                    slot,
                    header,
                    checked: 0,
                    crc: crate::CRC_ALGORITHM.init,
                };
                Reply::Later
            }
            (Request::Commit, State::Checking { .. }) => Reply::Later,
            (Request::Data { .. }, _) => refuse(Refusal::NotLoading),
        }
    }

    /// Advances a committed load's check by at most `budget` image words
    /// (at least one); at its end, checks the structure, writes the
    /// header and returns the outcome. `None` while the check goes on or
    /// no commit is pending.
    pub fn poll<S: SlotStore, C: Check>(
        &mut self,
        store: &mut S,
        check: &mut C,
        budget: usize,
    ) -> Option<Outcome> {
        let State::Checking {
            slot,
            header,
            checked,
            crc,
        } = self.state
        else {
            return None;
        };
        let image = image_of(store.contents(slot), &header);
        let end = checked.saturating_add(budget.max(1)).min(image.len());
        let mut digest = self.crc.digest_with_initial(crc);
        for word in &image[checked..end] {
            digest.update(&word.to_be_bytes());
        }
        let crc = digest.finalize();
        if end < image.len() {
            self.state = State::Checking {
                slot,
                header,
                checked: end,
                crc,
            };
            return None;
        }
        self.state = State::Idle;
        let outcome = self.finish(store, check, slot, header, crc);
        if let Outcome::Switched(valid) = outcome {
            self.running = Some(valid);
        }
        self.finished = Some(outcome);
        Some(outcome)
    }

    /// The structure check and the header, once the image CRC is known.
    fn finish<S: SlotStore, C: Check>(
        &self,
        store: &mut S,
        check: &mut C,
        slot: Slot,
        header: SlotHeader,
        found: u32,
    ) -> Outcome {
        let image = image_of(store.contents(slot), &header);
        if let Err(why) = accept(image, &header, found, check) {
            return Outcome::Refused(Refusal::Rejected(why));
        }
        if store.program(slot, 0, &header.to_words(self.crc)).is_err() {
            return Outcome::Refused(Refusal::Flash);
        }
        // Read back what the flash holds, not what was meant to be written.
        match SlotHeader::read(store.contents(slot), self.crc) {
            Ok(written) if written == header => Outcome::Switched(Valid { slot, header }),
            _ => Outcome::Refused(Refusal::Flash),
        }
    }
}

/// The running program as a `Status` answer reports it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Running<'a> {
    /// The project's name.
    pub name: &'a str,
    /// The image CRC of the program that runs.
    pub image_crc: u32,
}

/// A loader at the end of a byte link: bytes in, answer frames out. What
/// the firmware runs on its serial port.
pub struct Endpoint<'c> {
    loader: Loader<'c>,
    reader: FrameReader<MAX_FRAME>,
    out: [u8; MAX_FRAME],
}

impl core::fmt::Debug for Endpoint<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Endpoint")
            .field("loader", &self.loader)
            .finish_non_exhaustive()
    }
}

impl<'c> Endpoint<'c> {
    /// An endpoint over `loader`.
    pub fn new(loader: Loader<'c>) -> Endpoint<'c> {
        Endpoint {
            loader,
            reader: FrameReader::new(),
            out: [0; MAX_FRAME],
        }
    }

    /// The loader.
    pub fn loader(&self) -> &Loader<'c> {
        &self.loader
    }

    /// Takes one byte from the link; when it ends a request, handles it
    /// and returns the answer's frame to send (none for a `Commit`, whose
    /// answer [`Endpoint::poll`] gives). A damaged frame is answered with
    /// [`Refusal::Frame`].
    pub fn receive<S: SlotStore>(
        &mut self,
        byte: u8,
        store: &mut S,
        running: Running<'_>,
    ) -> Option<&[u8]> {
        let frame = self.reader.push(byte)?;
        let crc = self.loader.crc;
        let reply = match frame.and_then(|f| decode::<Request<'_>>(f, crc)) {
            Ok(request) => self.loader.handle(request, store),
            Err(_) => Reply::Send(Response::Refused(Refusal::Frame)),
        };
        let response = match reply {
            Reply::Send(response) => response,
            Reply::Status => Response::Status(Status {
                name: running.name,
                slot: self.loader.running.map(|v| v.slot),
                version: self.loader.running.map_or(0, |v| v.header.version),
                image_crc: running.image_crc,
                wiring: self.loader.wiring,
                loading: self.loader.expected(),
            }),
            Reply::Later => return None,
        };
        encode(&response, crc, &mut self.out).ok()
    }

    /// [`Loader::poll`], with the answer's frame when the check ends.
    pub fn poll<S: SlotStore, C: Check>(
        &mut self,
        store: &mut S,
        check: &mut C,
        budget: usize,
    ) -> Option<(Outcome, &[u8])> {
        let outcome = self.loader.poll(store, check, budget)?;
        let crc = self.loader.crc;
        let frame = encode(&outcome.response(), crc, &mut self.out).unwrap_or(&[]);
        Some((outcome, frame))
    }
}
