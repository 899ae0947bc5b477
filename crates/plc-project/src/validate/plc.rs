//! The `[plc]` table: scan period, command limit, policies and the reset
//! input (its numbers' ranges are in [`super::numbers`]).
//!
//! `unexpected` is `"fault"` (the default) or `"ignore"`; `reset` names a
//! declared input; `rom_test_bytes_per_scan` is a whole number of 32-bit
//! words (the image is checked word by word).

use super::super::model::{Input, Unexpected};
use super::super::parse::RawPlc;
use super::numbers::{
    MAX_COMMANDS_PER_SCAN, OVERRUN_LIMIT, ROM_TEST_BYTES_PER_SCAN, SCAN_PERIOD_MS,
    STORED_SETS_BYTES,
};
use super::{Declared, Validator};
use des::error::Result;

/// `stored_sets_bytes` when the file leaves it out: a supervisor's
/// allowed sets are stored while they take at most 1 KiB of flash.
pub const DEFAULT_STORED_SETS_BYTES: i64 = 1024;

/// The validated settings of `[plc]` (its name needs no checks).
pub(super) struct Settings {
    pub scan_period_ms: u32,
    pub max_commands_per_scan: u16,
    pub unexpected: Unexpected,
    pub reset: Option<usize>,
    pub overrun_limit: u16,
    pub overrun_fault: bool,
    pub lost_edge_fault: bool,
    pub rom_test_bytes_per_scan: u16,
    pub stored_sets_bytes: u32,
}

impl Validator<'_> {
    /// Validates `[plc]`; `reset` resolves against `inputs`.
    pub(super) fn plc(&self, plc: &RawPlc, inputs: &Declared<Input>) -> Result<Settings> {
        let scan_period_ms =
            self.number_or(plc.scan_period_ms.as_ref(), &SCAN_PERIOD_MS, 10)? as u32;
        let max_commands_per_scan = self.number_or(
            plc.max_commands_per_scan.as_ref(),
            &MAX_COMMANDS_PER_SCAN,
            1,
        )? as u16;
        let overrun_limit = self.number_or(plc.overrun_limit.as_ref(), &OVERRUN_LIMIT, 1)? as u16;
        let rom_test_bytes_per_scan = self.number_or(
            plc.rom_test_bytes_per_scan.as_ref(),
            &ROM_TEST_BYTES_PER_SCAN,
            64,
        )? as u16;
        if let Some(v) = plc.rom_test_bytes_per_scan.as_ref() {
            if v.get_ref() % 4 != 0 {
                return Err(self.error(
                    &v.span(),
                    format!(
                        "rom_test_bytes_per_scan must be a multiple of 4 (the image is checked in 32-bit words), found {}",
                        v.get_ref()
                    ),
                ));
            }
        }
        let stored_sets_bytes = self.number_or(
            plc.stored_sets_bytes.as_ref(),
            &STORED_SETS_BYTES,
            DEFAULT_STORED_SETS_BYTES,
        )? as u32;
        let unexpected = match &plc.unexpected {
            None => Unexpected::Fault,
            Some(u) => match u.get_ref().as_str() {
                "fault" => Unexpected::Fault,
                "ignore" => Unexpected::Ignore,
                other => {
                    return Err(self.error(
                        &u.span(),
                        format!("unexpected must be \"fault\" or \"ignore\", found {other:?}"),
                    ))
                }
            },
        };
        let reset = match &plc.reset {
            None => None,
            Some(r) => Some(self.resolve(inputs, r)?),
        };
        Ok(Settings {
            scan_period_ms,
            max_commands_per_scan,
            unexpected,
            reset,
            overrun_limit,
            overrun_fault: plc.overrun_fault,
            lost_edge_fault: plc.lost_edge_fault,
            rom_test_bytes_per_scan,
            stored_sets_bytes,
        })
    }
}
