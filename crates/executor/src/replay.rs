//! Recorded scans: what a replay harness feeds a target and what it
//! expects back, one record per scan.
//!
//! host-sim writes a scenario as a [`ScenarioHeader`] followed by one
//! [`RecordedScan`] per scan (postcard on the wire); the QEMU harness reads
//! them back, runs each scan through the same executor and generated
//! program, and compares with [`RecordedScan::mismatch`]. Capacities are
//! fixed so a target needs no allocator: up to [`MAX_INPUTS`] inputs and
//! outputs, [`MAX_SUPERVISORS`] supervisors and [`MAX_EVENTS`] events per
//! scan.

use crate::program::Index;
use crate::record::{Fault, ScanRecord};
use heapless::Vec;
use serde::{Deserialize, Serialize};

/// Largest number of inputs (and of outputs) a recorded scan holds.
pub const MAX_INPUTS: usize = 128;
/// Largest number of supervisors a recorded scan holds (64: the
/// manufacturing testbed runs 45, its 29 supervisors and 16 plant
/// components; a record holds its states on the harness's stack, 4 bytes
/// each).
pub const MAX_SUPERVISORS: usize = 64;
/// Largest number of executed (or unexpected) events in one recorded scan.
pub const MAX_EVENTS: usize = 64;

const BIT_BYTES: usize = MAX_INPUTS / 8;

/// Booleans packed eight to a byte, least significant bit first.
pub type Bits = Vec<u8, BIT_BYTES>;

/// What a scenario was recorded for; the first record of a scenario.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ScenarioHeader {
    /// The program image CRC of the project the trace was recorded with
    /// (the configuration CRC for a logic program): a harness refuses a
    /// scenario of another program.
    pub config_crc: u32,
    /// Number of inputs.
    pub inputs: u16,
    /// Number of outputs.
    pub outputs: u16,
    /// Number of scans that follow.
    pub scans: u32,
}

/// One scan: the raw inputs given and the record expected.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct RecordedScan {
    /// The scan's time in ms (wrapping).
    pub time_ms: u32,
    /// Raw input image.
    pub inputs: Bits,
    /// Expected executed events.
    pub executed: Vec<Index, MAX_EVENTS>,
    /// Expected unexpected events.
    pub unexpected: Vec<Index, MAX_EVENTS>,
    /// Expected state vector.
    pub states: Vec<u32, MAX_SUPERVISORS>,
    /// Expected output image.
    pub outputs: Bits,
    /// Expected fault cause.
    pub fault: Option<RecordedFault>,
}

/// [`Fault`] in serialisable form.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RecordedFault {
    /// [`Fault::Unexpected`] with the event.
    Unexpected(Index),
    /// [`Fault::Corrupt`].
    Corrupt,
    /// [`Fault::Overrun`].
    Overrun,
    /// [`Fault::LostEdge`].
    LostEdge,
}

impl From<Fault> for RecordedFault {
    fn from(f: Fault) -> RecordedFault {
        match f {
            Fault::Unexpected { event } => RecordedFault::Unexpected(event),
            Fault::Corrupt => RecordedFault::Corrupt,
            Fault::Overrun => RecordedFault::Overrun,
            Fault::LostEdge => RecordedFault::LostEdge,
        }
    }
}

/// Which field of a scan differs first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Field {
    /// Executed events.
    Executed,
    /// Unexpected events.
    Unexpected,
    /// State vector.
    States,
    /// Output image.
    Outputs,
    /// Fault cause.
    Fault,
}

impl Field {
    /// The field's name, as `{:?}` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Field::Executed => "Executed",
            Field::Unexpected => "Unexpected",
            Field::States => "States",
            Field::Outputs => "Outputs",
            Field::Fault => "Fault",
        }
    }
}

/// Too many items for a recorded scan's fixed capacity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CapacityExceeded;

/// Packs `values` into [`Bits`].
pub fn pack(values: &[bool]) -> Result<Bits, CapacityExceeded> {
    let mut bits = Bits::new();
    for chunk in values.chunks(8) {
        let byte = chunk
            .iter()
            .enumerate()
            .fold(0u8, |acc, (i, &v)| acc | (u8::from(v) << i));
        bits.push(byte).map_err(|_| CapacityExceeded)?;
    }
    Ok(bits)
}

/// Unpacks the first `out.len()` values of `bits` into `out` (missing bits
/// read as 0).
pub fn unpack(bits: &[u8], out: &mut [bool]) {
    for (i, v) in out.iter_mut().enumerate() {
        *v = bits.get(i / 8).is_some_and(|b| b >> (i % 8) & 1 == 1);
    }
}

/// Unpacks `bits` into input words as [`crate::Controller::scan_packed`]
/// takes them: value `i` at bit `i % 32` of word `i / 32` (missing bytes
/// read as 0).
pub fn unpack_words(bits: &[u8], out: &mut [u32]) {
    for (k, word) in out.iter_mut().enumerate() {
        let byte = |b: usize| u32::from(bits.get(4 * k + b).copied().unwrap_or(0)) << (8 * b);
        *word = byte(0) | byte(1) | byte(2) | byte(3);
    }
}

impl RecordedScan {
    /// The recorded form of `record` for raw inputs `raw`.
    pub fn new(raw: &[bool], record: &ScanRecord<'_>) -> Result<RecordedScan, CapacityExceeded> {
        let copy = |s: &[Index]| Vec::from_slice(s).map_err(|_| CapacityExceeded);
        Ok(RecordedScan {
            time_ms: record.time_ms,
            inputs: pack(raw)?,
            executed: copy(record.executed)?,
            unexpected: copy(record.unexpected)?,
            states: Vec::from_slice(record.states).map_err(|_| CapacityExceeded)?,
            outputs: pack(record.outputs)?,
            fault: record.fault.map(RecordedFault::from),
        })
    }

    /// The first field in which `record` differs from this expectation,
    /// `None` when they agree.
    pub fn mismatch(&self, record: &ScanRecord<'_>) -> Option<Field> {
        if self.executed.as_slice() != record.executed {
            return Some(Field::Executed);
        }
        if self.unexpected.as_slice() != record.unexpected {
            return Some(Field::Unexpected);
        }
        if self.states.as_slice() != record.states {
            return Some(Field::States);
        }
        let outputs_agree = record.outputs.len() <= MAX_INPUTS
            && pack(record.outputs).is_ok_and(|bits| bits == self.outputs);
        if !outputs_agree {
            return Some(Field::Outputs);
        }
        if self.fault != record.fault.map(RecordedFault::from) {
            return Some(Field::Fault);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits_round_trip() {
        let values: [bool; 11] = [
            true, false, false, true, true, false, true, false, false, false, true,
        ];
        let bits = pack(&values).unwrap();
        assert_eq!(bits.as_slice(), [0b0101_1001, 0b100]);
        let mut back = [false; 11];
        unpack(&bits, &mut back);
        assert_eq!(back, values);
        assert_eq!(pack(&[false; MAX_INPUTS + 1]), Err(CapacityExceeded));
    }

    #[test]
    fn field_names_are_their_debug_names() {
        extern crate std;
        use std::format;
        for f in [
            Field::Executed,
            Field::Unexpected,
            Field::States,
            Field::Outputs,
            Field::Fault,
        ] {
            assert_eq!(f.name(), format!("{f:?}"));
        }
    }

    #[test]
    fn mismatch_names_the_first_differing_field() {
        let record = ScanRecord {
            scan: 3,
            time_ms: 30,
            executed: &[1, 4],
            unexpected: &[],
            states: &[2, 0],
            outputs: &[true, false, true],
            fault: None,
        };
        let good = RecordedScan::new(&[false, true], &record).unwrap();
        assert_eq!(good.mismatch(&record), None);
        let mut states = record;
        states.states = &[2, 1];
        assert_eq!(good.mismatch(&states), Some(Field::States));
        let mut outputs = record;
        outputs.outputs = &[true, false, false];
        assert_eq!(good.mismatch(&outputs), Some(Field::Outputs));
        let mut fault = record;
        fault.fault = Some(Fault::Unexpected { event: 4 });
        assert_eq!(good.mismatch(&fault), Some(Field::Fault));
        let mut order = record;
        order.executed = &[4, 1];
        assert_eq!(good.mismatch(&order), Some(Field::Executed));
    }
}
