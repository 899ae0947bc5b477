//! The PC's end of the serial link: it sends each request as `codegen
//! load` does (the same frame encoder), [`BYTES_PER_SCAN`] bytes per
//! scan, and waits for the answer before it sends the next.

use crate::{fail, CRC};
use field_update::frame::{self, FrameReader, MAX_FRAME};
use field_update::loader::{Endpoint, Running};
use field_update::protocol::{Refusal, Request, Response, MAX_DATA};
use field_update::slot::{Slot, SlotStore};

/// Bytes the PC sends per scan: 115,200 baud over a 10 ms scan carries
/// about 115; half of that.
pub const BYTES_PER_SCAN: usize = 64;

/// Most requests of one phase.
pub const MAX_JOBS: usize = 6;

/// What the PC asks for, one after the other.
#[derive(Clone, Copy)]
pub enum Job<'i> {
    /// `Status`.
    Status,
    /// Nothing until the phase's scenario has ended.
    AfterScenario,
    /// `Begin`, every `Data`, `Commit` of `image`, announcing `image_crc`
    /// and the wiring signature `wiring`.
    Load {
        image: &'i [u32],
        image_crc: u32,
        version: u32,
        wiring: u32,
    },
}

/// A response as the PC keeps it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answer {
    Status {
        name: [u8; 32],
        len: usize,
        slot: Option<Slot>,
        version: u32,
        image_crc: u32,
    },
    Switched {
        slot: Slot,
        sequence: u32,
    },
    Refused(Refusal),
    /// A frame that is not a response, or one that does not fit.
    Garbled,
}

impl Answer {
    fn of(response: &Response<'_>) -> Answer {
        match *response {
            Response::Status(s) => {
                let mut name = [0u8; 32];
                let len = s.name.len().min(32);
                name[..len].copy_from_slice(&s.name.as_bytes()[..len]);
                Answer::Status {
                    name,
                    len,
                    slot: s.slot,
                    version: s.version,
                    image_crc: s.image_crc,
                }
            }
            Response::Switched { slot, sequence } => Answer::Switched { slot, sequence },
            Response::Refused(why) => Answer::Refused(why),
            Response::Next { .. } => Answer::Garbled,
        }
    }
}

/// The PC's end of the link.
pub struct Pc<'i> {
    jobs: &'i [Job<'i>],
    job: usize,
    /// Within a load: `None` before `Begin` is answered, then the byte
    /// offset the PLC expects.
    offset: Option<u32>,
    out: [u8; MAX_FRAME],
    len: usize,
    sent: usize,
    waiting: bool,
    reader: FrameReader<MAX_FRAME>,
    pub answers: [Option<Answer>; MAX_JOBS],
    /// Bytes of the image sent so far in the current load.
    chunk: [u8; MAX_DATA],
}

impl<'i> Pc<'i> {
    pub fn new(jobs: &'i [Job<'i>]) -> Pc<'i> {
        Pc {
            jobs,
            job: 0,
            offset: None,
            out: [0; MAX_FRAME],
            len: 0,
            sent: 0,
            waiting: false,
            reader: FrameReader::new(),
            answers: [None; MAX_JOBS],
            chunk: [0; MAX_DATA],
        }
    }

    pub fn done(&self) -> bool {
        self.job >= self.jobs.len()
    }

    /// The next request's frame into `self.out`; `false` when the PC
    /// has nothing to send now.
    fn prepare(&mut self, scenario_over: bool) -> bool {
        let Some(job) = self.jobs.get(self.job).copied() else {
            return false;
        };
        let request = match job {
            Job::Status => Request::Status,
            Job::AfterScenario => {
                if scenario_over {
                    self.job += 1;
                    return self.prepare(scenario_over);
                }
                return false;
            }
            Job::Load {
                image,
                image_crc,
                version,
                wiring,
            } => match self.offset {
                None => Request::Begin {
                    words: image.len() as u32,
                    image_crc,
                    version,
                    wiring,
                },
                Some(offset) if (offset as usize) < image.len() * 4 => {
                    let first = offset as usize / 4;
                    let words = &image[first..(first + MAX_DATA / 4).min(image.len())];
                    for (bytes, word) in self.chunk.chunks_exact_mut(4).zip(words) {
                        bytes.copy_from_slice(&word.to_le_bytes());
                    }
                    Request::Data {
                        offset,
                        bytes: &self.chunk[..words.len() * 4],
                    }
                }
                Some(_) => Request::Commit,
            },
        };
        let Ok(frame) = frame::encode(&request, &CRC, &mut self.out) else {
            fail("a request does not fit a frame");
        };
        self.len = frame.len();
        self.sent = 0;
        true
    }

    /// Up to [`BYTES_PER_SCAN`] bytes to the PLC, and its answers.
    pub fn exchange<S: SlotStore>(
        &mut self,
        endpoint: &mut Endpoint<'_>,
        store: &mut S,
        running: Running<'_>,
        scenario_over: bool,
    ) {
        for _ in 0..BYTES_PER_SCAN {
            if self.waiting {
                return;
            }
            if self.sent == self.len && !self.prepare(scenario_over) {
                return;
            }
            let byte = self.out[self.sent];
            self.sent += 1;
            let frame_end = self.sent == self.len;
            if let Some(answer) = endpoint.receive(byte, store, running) {
                let mut copy = [0u8; MAX_FRAME];
                copy[..answer.len()].copy_from_slice(answer);
                self.answer_bytes(&copy[..answer.len()]);
            } else if frame_end {
                // A `Commit`: its answer comes when the check ends.
                self.waiting = true;
            }
        }
    }

    /// The bytes of an answer frame from the PLC.
    pub fn answer_bytes(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            let Some(frame) = self.reader.push(byte) else {
                continue;
            };
            let response = frame.and_then(|f| frame::decode::<Response<'_>>(f, &CRC));
            let (answer, next) = match response {
                Ok(Response::Next { offset }) => (None, Some(offset)),
                Ok(r) => (Some(Answer::of(&r)), None),
                Err(_) => (Some(Answer::Garbled), None),
            };
            self.waiting = false;
            // The frame just answered is spent.
            self.sent = 0;
            self.len = 0;
            match (answer, next) {
                (_, Some(offset)) => self.offset = Some(offset),
                (Some(answer), None) => {
                    if let Some(slot) = self.answers.get_mut(self.job) {
                        *slot = Some(answer);
                    }
                    self.job += 1;
                    self.offset = None;
                }
                (None, None) => {}
            }
        }
    }
}
