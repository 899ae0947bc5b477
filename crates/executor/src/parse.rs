//! A program image read back from one run of words: the stream of
//! [`crate::image`] stored as it is fed to the CRC, which is what a field
//! update loads into a flash slot. [`Blob::parse`] splits it into the
//! configuration's pools and the tables by the lengths its headers give,
//! refuses anything inconsistent and never panics; what it does not check
//! (indices, spans, sets, tables that decode to states in range) is the
//! structure check's ([`crate::validate`]), which a controller runs on
//! every program at start-up.

use crate::image::{HEADER_WORDS, TABLE_HEADER_WORDS};
use crate::program::{Config, Guards, Index, Span, UnexpectedPolicy};
use crate::table::{Rows, SupervisorTable, TableProgram};
use crate::validate::{validate_generated, Flaw, Invalid, Part};
use core::fmt;

/// Why words are not a program image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ParseError {
    /// Fewer words than the headers' lengths add up to.
    Short,
    /// Words left after the last table.
    Trailing,
    /// A header word out of its field's range (a 16-bit field above
    /// `0xFFFF`, a flag or policy above 1, a table layout above 3, a
    /// keyed table's widths zero or above 32 together).
    Header {
        /// The word's index in its header.
        word: usize,
    },
    /// A name longer than the buffer, not UTF-8, or with padding bytes
    /// that are not zero.
    Name,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ParseError::Short => f.write_str("fewer words than its headers say"),
            ParseError::Trailing => f.write_str("words after the last table"),
            ParseError::Header { word } => write!(f, "header word {word} out of range"),
            ParseError::Name => f.write_str("a name too long, not UTF-8 or badly padded"),
        }
    }
}

/// A program image parsed from its words: the configuration, and the
/// tables' words, read one table after the other by [`Blob::tables`].
#[derive(Debug, Clone, Copy)]
pub struct Blob<'a> {
    /// The configuration, its pools borrowed from the words.
    pub config: Config<'a>,
    /// The words of the tables, checked to hold exactly `count` tables.
    tables: &'a [u32],
    /// The number of tables.
    count: usize,
}

impl<'a> Blob<'a> {
    /// Splits `words` into a configuration and tables. The name's bytes
    /// are copied into `name` (a name longer than it is refused), which
    /// the configuration borrows.
    pub fn parse(words: &'a [u32], name: &'a mut [u8]) -> Result<Blob<'a>, ParseError> {
        let mut rest = words;
        let config = parse_config(&mut rest, name)?;
        let count = header(&config_header(words)?, 28)?;
        let tables = rest;
        for _ in 0..count {
            parse_table(&mut rest)?;
        }
        if !rest.is_empty() {
            return Err(ParseError::Trailing);
        }
        Ok(Blob {
            config,
            tables,
            count: count as usize,
        })
    }

    /// The number of tables.
    pub fn table_count(&self) -> usize {
        self.count
    }

    /// The tables, in supervisor order.
    pub fn tables(&self) -> impl Iterator<Item = SupervisorTable<'a>> + 'a {
        let mut rest = self.tables;
        (0..self.count).map_while(move |_| parse_table(&mut rest).ok())
    }
}

/// Why a loaded image may not run ([`load`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Refusal {
    /// Its words are not a program image.
    Parse(ParseError),
    /// More tables than the room given for them.
    Tables {
        /// Tables in the image.
        count: usize,
        /// Room for tables.
        room: usize,
    },
    /// The structure check, what a generator proves included, refused it.
    Structure(Invalid),
}

impl Refusal {
    /// A number for the refusal: `0x100 +` the parse error's kind (0
    /// short, 1 trailing, 2 header, 3 name), `0x200` too many tables,
    /// `0x300 +` [`Flaw::code`].
    pub const fn code(&self) -> u16 {
        match self {
            Refusal::Parse(e) => {
                0x100
                    + match e {
                        ParseError::Short => 0,
                        ParseError::Trailing => 1,
                        ParseError::Header { .. } => 2,
                        ParseError::Name => 3,
                    }
            }
            Refusal::Tables { .. } => 0x200,
            Refusal::Structure(invalid) => 0x300 + invalid.flaw.code(),
        }
    }
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Refusal::Parse(e) => write!(f, "not a program image: {e}"),
            Refusal::Tables { count, room } => {
                write!(f, "{count} tables, room for {room}")
            }
            Refusal::Structure(invalid) => write!(f, "{invalid}"),
        }
    }
}

/// A program image loaded from outside the build (a field update), made
/// into a program once it passes every check a generator makes
/// ([`validate_generated`]): one table per supervisor, whose entries are
/// its states, memberships, alphabets and sets that agree. `name` holds
/// the name's bytes, `tables` the tables (its length is the most a
/// program may have); `crc` is the image CRC the program reports.
pub fn load<'a>(
    words: &'a [u32],
    name: &'a mut [u8],
    tables: &'a mut [SupervisorTable<'a>],
    crc: u32,
) -> Result<TableProgram<'a>, Refusal> {
    let program = reload(words, name, tables, crc)?;
    validate_generated(&program).map_err(Refusal::Structure)?;
    Ok(program)
}

/// [`load`] without [`validate_generated`], for words `load` accepted
/// before with this `crc` (a field update's slot, judged when it was
/// written, switched in later): the image is parsed again, not judged
/// again. Run it only through a controller
/// ([`crate::Controller::new_proven`], as the firmware does, or
/// [`crate::Controller::new`]): it runs nothing of the words and starts in
/// fault mode unless their CRC is `crc` (other words than those judged).
pub fn reload<'a>(
    words: &'a [u32],
    name: &'a mut [u8],
    tables: &'a mut [SupervisorTable<'a>],
    crc: u32,
) -> Result<TableProgram<'a>, Refusal> {
    let blob = Blob::parse(words, name).map_err(Refusal::Parse)?;
    let count = blob.table_count();
    if count > tables.len() {
        return Err(Refusal::Tables {
            count,
            room: tables.len(),
        });
    }
    if count != blob.config.supervisors.len() {
        return Err(Refusal::Structure(Invalid {
            part: Part::Tables,
            flaw: Flaw::TableCount,
        }));
    }
    for (slot, table) in tables.iter_mut().zip(blob.tables()) {
        *slot = table;
    }
    let tables: &'a [SupervisorTable<'a>] = tables;
    Ok(TableProgram {
        config: blob.config,
        tables: &tables[..count],
        crc,
    })
}

/// The header run of `words`.
fn config_header(words: &[u32]) -> Result<[u32; HEADER_WORDS], ParseError> {
    words
        .first_chunk::<HEADER_WORDS>()
        .copied()
        .ok_or(ParseError::Short)
}

/// Word `k` of `header`, checked to be at most `0xFFFF`.
fn header(header: &[u32], k: usize) -> Result<u16, ParseError> {
    u16::try_from(header[k]).map_err(|_| ParseError::Header { word: k })
}

/// Word `k` of `header`, checked to be 0 or 1.
fn flag(header: &[u32], k: usize) -> Result<bool, ParseError> {
    match header[k] {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(ParseError::Header { word: k }),
    }
}

/// The next `n` words of `words`.
fn take<'a>(words: &mut &'a [u32], n: usize) -> Result<&'a [u32], ParseError> {
    if words.len() < n {
        return Err(ParseError::Short);
    }
    let (taken, rest) = words.split_at(n);
    *words = rest;
    Ok(taken)
}

/// The next `n` records of `N` words.
fn records<'a, const N: usize>(
    words: &mut &'a [u32],
    n: u32,
) -> Result<&'a [[u32; N]], ParseError> {
    let len = (n as usize).checked_mul(N).ok_or(ParseError::Short)?;
    Ok(take(words, len)?.as_chunks::<N>().0)
}

/// The configuration's runs at the start of `words`, which are left at
/// the first table.
fn parse_config<'a>(words: &mut &'a [u32], name: &'a mut [u8]) -> Result<Config<'a>, ParseError> {
    let h = config_header(words)?;
    *words = &words[HEADER_WORDS..];
    let name = parse_name(words, h[0], name)?;
    let n = |k: usize| h[12 + k];
    Ok(Config {
        name,
        scan_period_ms: h[1],
        max_commands_per_scan: header(&h, 2)?,
        unexpected: if flag(&h, 3)? {
            UnexpectedPolicy::Ignore
        } else {
            UnexpectedPolicy::Fault
        },
        reset: match h[4] {
            u32::MAX => None,
            _ => Some(header(&h, 4)? as Index),
        },
        overrun_limit: header(&h, 5)?,
        overrun_fault: flag(&h, 6)?,
        lost_edge_fault: flag(&h, 7)?,
        rom_test_bytes_per_scan: header(&h, 8)?,
        debounce_mask: Span::from_word(h[9]),
        commands: Span::from_word(h[10]),
        requested: Span::from_word(h[11]),
        inputs: records(words, n(0))?,
        debounced: take(words, n(1) as usize)?,
        outputs: records(words, n(2))?,
        timers: records(words, n(3))?,
        events: records(words, n(4))?,
        supervisors: records(words, n(5))?,
        input_masks: take(words, n(6) as usize)?,
        event_lists: take(words, n(7) as usize)?,
        event_masks: take(words, n(8) as usize)?,
        actions: take(words, n(9) as usize)?,
        memberships: take(words, n(10) as usize)?,
        state_map: records(words, n(11))?,
        guards: Guards {
            events: records(words, n(12))?,
            bits: records(words, n(13))?,
            nodes: records(words, n(14))?,
        },
        allowed_index: take(words, n(15) as usize)?,
    })
}

/// The name run: `len` bytes, four a word, first byte least significant,
/// the last word padded with zeros; copied into `buffer`.
fn parse_name<'a>(
    words: &mut &[u32],
    len: u32,
    buffer: &'a mut [u8],
) -> Result<&'a str, ParseError> {
    let len = len as usize;
    if len > buffer.len() {
        return Err(ParseError::Name);
    }
    let run = take(words, len.div_ceil(4))?;
    for (k, word) in run.iter().enumerate() {
        for (i, byte) in word.to_le_bytes().into_iter().enumerate() {
            match buffer.get_mut(4 * k + i) {
                Some(b) if 4 * k + i < len => *b = byte,
                _ if byte == 0 => {}
                _ => return Err(ParseError::Name),
            }
        }
    }
    let buffer: &'a [u8] = buffer;
    core::str::from_utf8(&buffer[..len]).map_err(|_| ParseError::Name)
}

/// The next table: its header, then `defined`, `targets` and
/// `row_starts` (`fields`, `states`).
fn parse_table<'a>(words: &mut &'a [u32]) -> Result<SupervisorTable<'a>, ParseError> {
    let h = take(words, TABLE_HEADER_WORDS)?;
    let bits = |k: usize| u8::try_from(h[k]).map_err(|_| ParseError::Header { word: k });
    let events = header(h, 0)?;
    let state_bits = bits(1)?;
    let defined = take(words, h[4] as usize)?;
    let targets = take(words, h[5] as usize)?;
    let third = take(words, h[6] as usize)?;
    if h[2] == 3 {
        return keyed_table(h[3], third).map(|rows| SupervisorTable {
            events,
            state_bits,
            defined,
            targets,
            rows,
        });
    }
    let start_bits = bits(3)?;
    let rows = match (h[2], start_bits, third.len()) {
        (0, 0, 0) => Rows::Dense,
        (0, 0, _) => return Err(ParseError::Header { word: 6 }),
        (1, _, _) => Rows::Sparse {
            row_starts: third,
            start_bits,
        },
        (2, 0, _) => Rows::Net { fields: third },
        (0 | 2, _, _) => return Err(ParseError::Header { word: 3 }),
        _ => return Err(ParseError::Header { word: 2 }),
    };
    Ok(SupervisorTable {
        events,
        state_bits,
        defined,
        targets,
        rows,
    })
}

/// The rows of a keyed table from its header's widths word (`start_bits
/// | key_bits << 8`, both at least 1, at most 32 together) and its
/// records: refused as header word 3 otherwise. Whether the records'
/// keys and starts fit the dictionary and targets is the structure
/// check's, which knows the supervisor's states.
fn keyed_table(widths: u32, states: &[u32]) -> Result<Rows<'_>, ParseError> {
    let (start_bits, key_bits) = (widths & 0xFF, widths >> 8);
    if start_bits == 0 || key_bits == 0 || start_bits + key_bits > 32 {
        return Err(ParseError::Header { word: 3 });
    }
    Ok(Rows::Keyed {
        states,
        key_bits: key_bits as u8,
        start_bits: start_bits as u8,
    })
}

#[cfg(test)]
mod tests;
