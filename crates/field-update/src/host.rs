//! The PC side: slot files, and a load over any byte stream (a serial
//! port, or a simulated PLC in tests).
//!
//! A *slot file* (`codegen image`) is what a slot holds: the header and
//! the image, every word little-endian, the order in which a Cortex-M
//! reads them from flash. `probe-rs download --binary-format bin
//! --base-address <slot>` writes it straight into a slot; [`load`]
//! sends its image over the protocol, and the PLC writes its own header
//! (with the next sequence number).

use crate::crc_of_words;
use crate::frame::{self, FrameError, FrameReader, MAX_FRAME};
use crate::header::{HeaderFault, SlotHeader, HEADER_WORDS};
use crate::protocol::{data_requests, Refusal, Request, Response, ERASE_MS, MAX_DATA};
use crate::slot::Slot;
use crc::Crc;
use std::io::{self, Read, Write};
use std::vec::Vec;

/// A slot file read back: its header and image.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlotFile {
    /// The header, checked.
    pub header: SlotHeader,
    /// The image's words.
    pub image: Vec<u32>,
}

/// Why bytes are not a slot file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum SlotFileError {
    /// Not a whole number of words.
    #[error("{0} bytes are not a whole number of 32-bit words")]
    Unaligned(usize),
    /// The header does not check.
    #[error("no valid slot header: {0:?}")]
    Header(HeaderFault),
    /// Words after the image.
    #[error("{found} words after the header, the header says {expected}")]
    Length {
        /// Words the header announces.
        expected: u32,
        /// Words the file holds after the header.
        found: usize,
    },
    /// The image's CRC is not the header's.
    #[error("the image's CRC is {found:#010x}, its header records {recorded:#010x}")]
    ImageCrc {
        /// Computed.
        found: u32,
        /// Recorded.
        recorded: u32,
    },
}

impl SlotFile {
    /// A slot file for `image` with `header`'s fields (its length and CRC
    /// taken from the image), made for a firmware of wiring signature
    /// `wiring`.
    pub fn new(
        image: Vec<u32>,
        sequence: u32,
        version: u32,
        wiring: u32,
        crc: &Crc<u32>,
    ) -> SlotFile {
        let header = SlotHeader {
            sequence,
            version,
            words: image.len() as u32,
            image_crc: crc_of_words(crc, &image),
            wiring,
        };
        SlotFile { header, image }
    }

    /// The file's bytes.
    pub fn to_bytes(&self, crc: &Crc<u32>) -> Vec<u8> {
        self.header
            .to_words(crc)
            .iter()
            .chain(&self.image)
            .flat_map(|w| w.to_le_bytes())
            .collect()
    }

    /// Reads and checks a slot file: header, length, image CRC.
    pub fn parse(bytes: &[u8], crc: &Crc<u32>) -> Result<SlotFile, SlotFileError> {
        if bytes.len() % 4 != 0 {
            return Err(SlotFileError::Unaligned(bytes.len()));
        }
        let words: Vec<u32> = bytes
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        let header = SlotHeader::read(&words, crc).map_err(SlotFileError::Header)?;
        let image = words[HEADER_WORDS..].to_vec();
        if image.len() != header.words as usize {
            return Err(SlotFileError::Length {
                expected: header.words,
                found: image.len(),
            });
        }
        let found = crc_of_words(crc, &image);
        if found != header.image_crc {
            return Err(SlotFileError::ImageCrc {
                found,
                recorded: header.image_crc,
            });
        }
        Ok(SlotFile { header, image })
    }
}

/// What went wrong on the link.
#[derive(Debug, thiserror::Error)]
pub enum LinkError {
    /// Reading or writing the port.
    #[error("the link: {0}")]
    Io(#[from] io::Error),
    /// No intact answer after every retry.
    #[error("no intact answer to {request} after {tries} tries (last: {last:?})")]
    NoAnswer {
        /// The request, by name.
        request: &'static str,
        /// Tries made.
        tries: u32,
        /// The last frame error, if a frame came.
        last: Option<FrameError>,
    },
    /// The PLC refused a request.
    #[error("the PLC refused {request}: {why}")]
    Refused {
        /// The request, by name.
        request: &'static str,
        /// Its reason.
        why: Refusal,
    },
    /// An answer that does not fit the request.
    #[error("unexpected answer to {request}: {answer}")]
    Unexpected {
        /// The request, by name.
        request: &'static str,
        /// The answer, debug-printed.
        answer: String,
    },
}

/// The read timeout a link's port is assumed to have until
/// [`Link::timeout_ms`] says otherwise (ms): `codegen load`'s default.
pub const DEFAULT_TIMEOUT_MS: u64 = 2_000;

/// Read timeouts of `timeout_ms` each that a link waits out for the
/// answer to `Begin` beyond the first: together they last at least
/// [`ERASE_MS`], the erase the PLC does before it answers.
pub fn erase_timeouts(timeout_ms: u64) -> u32 {
    let timeouts = u64::from(ERASE_MS).div_ceil(timeout_ms.max(1));
    u32::try_from(timeouts).unwrap_or(u32::MAX)
}

/// One end of a link to a PLC: requests out, answers in.
pub struct Link<'c, T> {
    io: T,
    crc: &'c Crc<u32>,
    reader: FrameReader<MAX_FRAME>,
    body: Vec<u8>,
    /// Tries per request before [`LinkError::NoAnswer`].
    pub tries: u32,
    /// Read timeouts waited out for `Begin`'s answer beyond the first
    /// ([`erase_timeouts`]).
    erase_timeouts: u32,
}

fn name_of(request: &Request<'_>) -> &'static str {
    match request {
        Request::Status => "Status",
        Request::Begin { .. } => "Begin",
        Request::Data { .. } => "Data",
        Request::Commit => "Commit",
        Request::Abort => "Abort",
    }
}

impl<'c, T: Read + Write> Link<'c, T> {
    /// A link over `io`, a port with a read timeout of
    /// [`DEFAULT_TIMEOUT_MS`]: a timeout counts as a lost answer and the
    /// request is sent again, except while `Begin`'s answer may still be
    /// on its way ([`erase_timeouts`]).
    pub fn new(io: T, crc: &'c Crc<u32>) -> Link<'c, T> {
        Link {
            io,
            crc,
            reader: FrameReader::new(),
            body: Vec::new(),
            tries: 3,
            erase_timeouts: erase_timeouts(DEFAULT_TIMEOUT_MS),
        }
    }

    /// States the port's read timeout, in ms, from which the wait for
    /// `Begin`'s answer follows.
    pub fn timeout_ms(mut self, timeout_ms: u64) -> Link<'c, T> {
        self.erase_timeouts = erase_timeouts(timeout_ms);
        self
    }

    /// Sends `request` and returns the PLC's answer, sending it again
    /// after a timeout (for `Begin`, after the erase's timeouts), a
    /// damaged answer, or `Refused(Frame)` (the request arrived damaged
    /// and did nothing). Answers of a kind `request` does not get are
    /// late answers to earlier requests, and skipped.
    pub fn request(&mut self, request: &Request<'_>) -> Result<Response<'_>, LinkError> {
        let mut out = [0u8; MAX_FRAME];
        let no_answer = |tries, last| LinkError::NoAnswer {
            request: name_of(request),
            tries,
            last,
        };
        let bytes =
            frame::encode(request, self.crc, &mut out).map_err(|e| no_answer(0, Some(e)))?;
        let patience = match request {
            Request::Begin { .. } => self.erase_timeouts.saturating_add(1),
            _ => 1,
        };
        let mut last = None;
        let mut damaged = false;
        for _ in 0..self.tries {
            self.io.write_all(bytes)?;
            self.io.flush()?;
            let mut timeouts = 0;
            let answer = loop {
                match self.read_frame() {
                    Err(e) if is_timeout(&e) => {
                        timeouts += 1;
                        if timeouts >= patience {
                            break None;
                        }
                    }
                    // A late answer to an earlier request: read on.
                    Ok(Ok(()))
                        if frame::message::<Response<'_>>(&self.body)
                            .is_ok_and(|answer| !answers(request, &answer)) => {}
                    other => break Some(other),
                }
            };
            damaged = false;
            match answer {
                Some(Ok(Ok(()))) => match frame::message::<Response<'_>>(&self.body) {
                    Ok(Response::Refused(Refusal::Frame)) => damaged = true,
                    Ok(_) => return frame::message(&self.body).map_err(|e| no_answer(0, Some(e))),
                    Err(_) => last = Some(FrameError::Message),
                },
                Some(Ok(Err(e))) => last = Some(e),
                Some(Err(e)) => return Err(e.into()),
                None => {}
            }
        }
        if damaged {
            return Err(LinkError::Refused {
                request: name_of(request),
                why: Refusal::Frame,
            });
        }
        Err(no_answer(self.tries, last))
    }

    /// Reads bytes until a frame ends; its message bytes go to
    /// `self.body`.
    fn read_frame(&mut self) -> io::Result<Result<(), FrameError>> {
        let mut byte = [0u8; 1];
        loop {
            if self.io.read(&mut byte)? == 0 {
                return Err(io::ErrorKind::UnexpectedEof.into());
            }
            if let Some(frame) = self.reader.push(byte[0]) {
                let crc = self.crc;
                return Ok(frame.and_then(|f| frame::unframe(f, crc)).map(|body| {
                    self.body.clear();
                    self.body.extend_from_slice(body);
                }));
            }
        }
    }
}

/// Whether `response` is of a kind that answers `request`.
fn answers(request: &Request<'_>, response: &Response<'_>) -> bool {
    match response {
        Response::Refused(_) => true,
        Response::Status(_) => matches!(request, Request::Status | Request::Abort),
        Response::Next { .. } => matches!(request, Request::Begin { .. } | Request::Data { .. }),
        Response::Switched { .. } => matches!(request, Request::Commit),
    }
}

fn is_timeout(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock
    )
}

/// A finished load: where the image went.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Loaded {
    /// The slot written.
    pub slot: Slot,
    /// Its sequence number.
    pub sequence: u32,
}

/// Loads `file`'s image into the PLC at the other end of `link`:
/// `Begin`, every `Data`, `Commit`. `progress(sent, total)` is called
/// after each chunk, in bytes.
pub fn load<T: Read + Write>(
    link: &mut Link<'_, T>,
    file: &SlotFile,
    mut progress: impl FnMut(u32, u32),
) -> Result<Loaded, LinkError> {
    let bytes: Vec<u8> = file.image.iter().flat_map(|w| w.to_le_bytes()).collect();
    let total = bytes.len() as u32;
    let begin = Request::Begin {
        words: file.header.words,
        image_crc: file.header.image_crc,
        version: file.header.version,
        wiring: file.header.wiring,
    };
    expect_next(link, &begin, 0)?;
    let chunks: Vec<Request<'_>> = data_requests(&bytes).collect();
    let mut k = 0;
    while let Some(request) = chunks.get(k) {
        let Request::Data {
            offset,
            bytes: chunk,
        } = *request
        else {
            unreachable!("data_requests gives Data")
        };
        let next = offset + chunk.len() as u32;
        match link.request(request)? {
            Response::Next { offset: expected } if expected == next => k += 1,
            // The PLC expects an earlier chunk again (one of ours was lost).
            Response::Next { offset: expected }
                if expected < next && expected as usize % MAX_DATA == 0 =>
            {
                k = expected as usize / MAX_DATA;
            }
            Response::Refused(why) => {
                return Err(LinkError::Refused {
                    request: "Data",
                    why,
                })
            }
            other => {
                return Err(LinkError::Unexpected {
                    request: "Data",
                    answer: format!("{other:?}"),
                })
            }
        }
        progress(next.min(total), total);
    }
    match link.request(&Request::Commit)? {
        Response::Switched { slot, sequence } => Ok(Loaded { slot, sequence }),
        Response::Refused(why) => Err(LinkError::Refused {
            request: "Commit",
            why,
        }),
        other => Err(LinkError::Unexpected {
            request: "Commit",
            answer: format!("{other:?}"),
        }),
    }
}

fn expect_next<T: Read + Write>(
    link: &mut Link<'_, T>,
    request: &Request<'_>,
    offset: u32,
) -> Result<(), LinkError> {
    match link.request(request)? {
        Response::Next { offset: o } if o == offset => Ok(()),
        Response::Refused(why) => Err(LinkError::Refused {
            request: name_of(request),
            why,
        }),
        other => Err(LinkError::Unexpected {
            request: name_of(request),
            answer: format!("{other:?}"),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loader::{Endpoint, Loader, Running};
    use crate::slot::{choose, Check, RamSlots, SlotStore};
    use crate::tests::Counting;
    use std::collections::VecDeque;

    static CRC: Crc<u32> = Crc::<u32>::new(&crate::CRC_ALGORITHM);

    struct AnyImage;
    impl Check for AnyImage {
        fn wiring(&self) -> u32 {
            0
        }
        fn check(&mut self, image: &[u32]) -> Result<(), u16> {
            if image.first() == Some(&0) {
                Err(9)
            } else {
                Ok(())
            }
        }
    }

    /// A PLC at the other end of a byte stream: an endpoint over RAM
    /// slots, losing every `lose`-th answer. An erase stalls it for
    /// `erase_reads` of the PC's read timeouts: bytes sent meanwhile are
    /// lost, and the answer comes after them.
    struct SimulatedPlc {
        a: Vec<u32>,
        b: Vec<u32>,
        endpoint: Endpoint<'static>,
        out: VecDeque<u8>,
        answers: usize,
        lose: Option<usize>,
        erase_reads: usize,
        /// Read timeouts until the erase in progress ends.
        busy: usize,
        /// The answer sent once the erase ends.
        pending: Vec<u8>,
        erases: usize,
        /// The requests the PC sent, by name.
        sent: Vec<&'static str>,
        sent_reader: FrameReader<MAX_FRAME>,
    }

    impl SimulatedPlc {
        fn new(lose: Option<usize>) -> SimulatedPlc {
            SimulatedPlc {
                a: vec![u32::MAX; 512],
                b: vec![u32::MAX; 512],
                endpoint: Endpoint::new(Loader::new(&CRC, None, &AnyImage)),
                out: VecDeque::new(),
                answers: 0,
                lose,
                erase_reads: 0,
                busy: 0,
                pending: Vec::new(),
                erases: 0,
                sent: Vec::new(),
                sent_reader: FrameReader::new(),
            }
        }

        /// A PLC whose erase lasts `reads` read timeouts.
        fn slow_erase(reads: usize) -> SimulatedPlc {
            SimulatedPlc {
                erase_reads: reads,
                ..SimulatedPlc::new(None)
            }
        }
    }

    impl Write for SimulatedPlc {
        fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
            let running = Running {
                name: "sim",
                image_crc: 0,
            };
            for &byte in bytes {
                if let Some(Ok(request)) = self
                    .sent_reader
                    .push(byte)
                    .map(|f| f.and_then(|f| frame::decode::<Request<'_>>(f, &CRC)))
                {
                    self.sent.push(name_of(&request));
                }
                if self.busy > 0 {
                    continue;
                }
                let erases = self.erases;
                let mut store = Counting {
                    slots: RamSlots::new(&mut self.a, &mut self.b),
                    erases: &mut self.erases,
                };
                let mut answer = self
                    .endpoint
                    .receive(byte, &mut store, running)
                    .map(<[u8]>::to_vec);
                while self.endpoint.loader().is_checking() && answer.is_none() {
                    answer = self
                        .endpoint
                        .poll(&mut store, &mut AnyImage, 7)
                        .map(|(_, frame)| frame.to_vec());
                }
                let erased = self.erases > erases && self.erase_reads > 0;
                if let Some(frame) = answer {
                    self.answers += 1;
                    if erased {
                        self.busy = self.erase_reads;
                        self.pending = frame;
                    } else if self.lose.is_none_or(|n| self.answers % n != 0) {
                        self.out.extend(frame);
                    }
                }
            }
            Ok(bytes.len())
        }

        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    impl Read for SimulatedPlc {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            if self.busy > 0 {
                self.busy -= 1;
                if self.busy == 0 {
                    self.out.extend(self.pending.drain(..));
                }
                return Err(io::ErrorKind::TimedOut.into());
            }
            match self.out.pop_front() {
                Some(byte) if !buf.is_empty() => {
                    buf[0] = byte;
                    Ok(1)
                }
                _ => Err(io::ErrorKind::TimedOut.into()),
            }
        }
    }

    fn file(len: u32, first: u32) -> SlotFile {
        let image = (0..len).map(|k| first.wrapping_add(k * 77)).collect();
        SlotFile::new(image, 1, crate::header::version(1, 2, 3), 0, &CRC)
    }

    #[test]
    fn a_slot_file_round_trips_and_refuses_damage() {
        let f = file(300, 5);
        let bytes = f.to_bytes(&CRC);
        assert_eq!(bytes.len(), (HEADER_WORDS + 300) * 4);
        assert_eq!(SlotFile::parse(&bytes, &CRC), Ok(f));
        assert_eq!(
            SlotFile::parse(&bytes[..9], &CRC),
            Err(SlotFileError::Unaligned(9))
        );
        let mut damaged = bytes.clone();
        damaged[HEADER_WORDS * 4 + 17] ^= 4;
        assert!(matches!(
            SlotFile::parse(&damaged, &CRC),
            Err(SlotFileError::ImageCrc { .. })
        ));
        assert_eq!(
            SlotFile::parse(&bytes[..bytes.len() - 4], &CRC),
            Err(SlotFileError::Header(HeaderFault::Length(300)))
        );
        let mut longer = bytes.clone();
        longer.extend([0; 4]);
        assert_eq!(
            SlotFile::parse(&longer, &CRC),
            Err(SlotFileError::Length {
                expected: 300,
                found: 301
            })
        );
    }

    #[test]
    fn a_load_over_a_lossy_link_lands_in_the_slot() {
        for lose in [None, Some(3), Some(5)] {
            let mut plc = SimulatedPlc::new(lose);
            let f = file(300, 5);
            let mut seen = Vec::new();
            let loaded = {
                let mut link = Link::new(&mut plc, &CRC);
                load(&mut link, &f, |sent, total| seen.push((sent, total))).expect("loads")
            };
            assert_eq!(
                loaded,
                Loaded {
                    slot: Slot::A,
                    sequence: 1
                },
                "lose {lose:?}"
            );
            assert_eq!(seen.last(), Some(&(1200, 1200)));
            let slots = RamSlots::new(&mut plc.a, &mut plc.b);
            let running = choose(&slots, &CRC, &mut AnyImage)
                .running
                .expect("A is valid");
            assert_eq!(running.header.version, f.header.version);
            assert_eq!(
                &slots.contents(Slot::A)[HEADER_WORDS..HEADER_WORDS + 300],
                &f.image[..]
            );
        }
    }

    #[test]
    fn a_refused_image_is_reported_with_its_reason() {
        let mut plc = SimulatedPlc::new(None);
        let f = file(10, 0);
        let mut link = Link::new(&mut plc, &CRC);
        let err = load(&mut link, &f, |_, _| {}).expect_err("refused");
        assert!(
            matches!(
                err,
                LinkError::Refused {
                    request: "Commit",
                    why: Refusal::Rejected(crate::slot::Rejected::Structure(9))
                }
            ),
            "{err}"
        );
        let too_big = file(600, 1);
        let err = load(&mut link, &too_big, |_, _| {}).expect_err("refused");
        assert!(
            matches!(
                err,
                LinkError::Refused {
                    request: "Begin",
                    why: Refusal::TooLarge { .. }
                }
            ),
            "{err}"
        );
    }

    /// Loads `f` into the fresh `plc` over a link with the default
    /// timeout: it lands in slot A, sequence 1.
    fn load_into_a(plc: &mut SimulatedPlc, f: &SlotFile) {
        let loaded = {
            let mut link = Link::new(&mut *plc, &CRC);
            load(&mut link, f, |_, _| {}).map_err(|e| e.to_string())
        };
        assert_eq!(
            loaded,
            Ok(Loaded {
                slot: Slot::A,
                sequence: 1
            })
        );
        let slots = RamSlots::new(&mut plc.a, &mut plc.b);
        assert_eq!(
            &slots.contents(Slot::A)[HEADER_WORDS..HEADER_WORDS + f.image.len()],
            &f.image[..]
        );
    }

    #[test]
    fn an_erase_longer_than_the_timeout_is_waited_for_begin_is_sent_once() {
        // The longest erase (ERASE_MS) at the default timeout: two read
        // timeouts of 2 s before the answer.
        let reads = erase_timeouts(DEFAULT_TIMEOUT_MS) as usize;
        assert_eq!(reads, 2);
        let mut plc = SimulatedPlc::slow_erase(reads);
        load_into_a(&mut plc, &file(300, 5));
        assert_eq!(plc.erases, 1);
        assert_eq!(plc.sent.iter().filter(|&&r| r == "Begin").count(), 1);
        assert_eq!(plc.sent.len(), 1 + 5 + 1, "Begin, five Data, Commit");
    }

    #[test]
    fn a_begin_sent_again_after_a_slower_erase_does_not_erase_again() {
        // An erase longer than the PC waits for: it sends Begin again,
        // which arrives after the erase; the load still lands, with one
        // erase, and the late answers are skipped.
        let mut plc = SimulatedPlc::slow_erase(erase_timeouts(DEFAULT_TIMEOUT_MS) as usize + 1);
        load_into_a(&mut plc, &file(300, 5));
        assert_eq!(plc.sent.iter().filter(|&&r| r == "Begin").count(), 2);
        assert_eq!(plc.erases, 1);
        let mut link = Link::new(&mut plc, &CRC);
        assert!(
            matches!(link.request(&Request::Status), Ok(Response::Status(s)) if s.slot == Some(Slot::A)),
            "the late answers are all read"
        );
    }

    #[test]
    fn the_wait_for_begin_covers_the_erase_at_any_timeout() {
        for timeout_ms in [1, 100, 1_000, 1_999, 2_000, 3_000, 4_000, 10_000] {
            let timeouts = u64::from(erase_timeouts(timeout_ms));
            assert!(timeouts * timeout_ms >= u64::from(ERASE_MS), "{timeout_ms}");
            assert!(
                (timeouts - 1) * timeout_ms < u64::from(ERASE_MS),
                "{timeout_ms}"
            );
        }
        assert_eq!(erase_timeouts(0), ERASE_MS);
    }

    /// A PLC that answers the `k`-th write with `answers[k]`'s frames.
    struct Scripted {
        answers: VecDeque<Vec<Response<'static>>>,
        out: VecDeque<u8>,
        writes: usize,
    }

    impl Write for Scripted {
        fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
            self.writes += 1;
            let mut buf = [0u8; MAX_FRAME];
            for answer in self.answers.pop_front().unwrap_or_default() {
                let frame = frame::encode(&answer, &CRC, &mut buf).expect("fits");
                self.out.extend(frame.iter().copied());
            }
            Ok(bytes.len())
        }

        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    impl Read for Scripted {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            match self.out.pop_front() {
                Some(byte) if !buf.is_empty() => {
                    buf[0] = byte;
                    Ok(1)
                }
                _ => Err(io::ErrorKind::TimedOut.into()),
            }
        }
    }

    #[test]
    fn a_request_refused_as_damaged_is_sent_again_and_late_answers_are_skipped() {
        let status = Response::Status(crate::protocol::Status {
            name: "sim",
            slot: None,
            version: 0,
            image_crc: 0,
            wiring: 0,
            loading: None,
        });
        let late = Response::Switched {
            slot: Slot::A,
            sequence: 1,
        };
        let mut plc = Scripted {
            answers: VecDeque::from([vec![Response::Refused(Refusal::Frame)], vec![late, status]]),
            out: VecDeque::new(),
            writes: 0,
        };
        let mut link = Link::new(&mut plc, &CRC);
        assert_eq!(link.request(&Request::Status).ok(), Some(status));
        assert_eq!(plc.writes, 2);
    }
}
