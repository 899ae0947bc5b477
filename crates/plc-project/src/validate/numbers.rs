//! Numbers: the range of every integer field.
//!
//! `scan_period_ms` and `preset_ms` lie in `1..2^31` (time differences
//! must stay wrap-safe on a 32-bit millisecond clock; the scan period's
//! ranges are the executor's, [`executor::pacing::SCAN_PERIOD_MS`] and
//! [`executor::timers::PRESET_MS`]);
//! `max_commands_per_scan` and `overrun_limit` in `0..=65535`;
//! `rom_test_bytes_per_scan` in `4..=65532`; `stored_sets_bytes` in
//! `0..2^31`; `debounce_scans` in `0..=255`.

use super::Validator;
use des::error::Result;
use executor::{pacing, timers};
use std::ops::RangeInclusive;
use toml::Spanned;

/// An integer field: its name and its range.
pub(super) struct Field {
    name: &'static str,
    range: RangeInclusive<i64>,
}

/// `[plc] scan_period_ms`: the executor's range, so that a project that
/// passes validation is never refused by the image check or the pacer.
pub(super) const SCAN_PERIOD_MS: Field = Field {
    name: "scan_period_ms",
    range: *pacing::SCAN_PERIOD_MS.start() as i64..=*pacing::SCAN_PERIOD_MS.end() as i64,
};

/// `[plc] max_commands_per_scan` (0: no limit).
pub(super) const MAX_COMMANDS_PER_SCAN: Field = Field {
    name: "max_commands_per_scan",
    range: 0..=u16::MAX as i64,
};

/// `[plc] overrun_limit`.
pub(super) const OVERRUN_LIMIT: Field = Field {
    name: "overrun_limit",
    range: 0..=u16::MAX as i64,
};

/// `[plc] rom_test_bytes_per_scan` (also a multiple of 4).
pub(super) const ROM_TEST_BYTES_PER_SCAN: Field = Field {
    name: "rom_test_bytes_per_scan",
    range: 4..=u16::MAX as i64 - 3,
};

/// `[plc] stored_sets_bytes`.
pub(super) const STORED_SETS_BYTES: Field = Field {
    name: "stored_sets_bytes",
    range: 0..=i32::MAX as i64,
};

/// `debounce_scans` of an input.
pub(super) const DEBOUNCE_SCANS: Field = Field {
    name: "debounce_scans",
    range: 0..=u8::MAX as i64,
};

/// `preset_ms` of a timer.
pub(super) const PRESET_MS: Field = Field {
    name: "preset_ms",
    range: *timers::PRESET_MS.start() as i64..=*timers::PRESET_MS.end() as i64,
};

impl Validator<'_> {
    /// The value of `field`, or `default` when it is absent.
    pub(super) fn number_or(
        &self,
        value: Option<&Spanned<i64>>,
        field: &Field,
        default: i64,
    ) -> Result<i64> {
        value.map_or(Ok(default), |v| self.number(v, field))
    }

    /// The value of `field`, checked against its range.
    pub(super) fn number(&self, v: &Spanned<i64>, field: &Field) -> Result<i64> {
        if field.range.contains(v.get_ref()) {
            Ok(*v.get_ref())
        } else {
            Err(self.error(
                &v.span(),
                format!(
                    "{} must be between {} and {}, found {}",
                    field.name,
                    field.range.start(),
                    field.range.end(),
                    v.get_ref()
                ),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::{Drive, Unexpected};
    use super::super::testing::{load, HEAD};

    #[test]
    fn defaults_fill_what_the_file_leaves_out() {
        let p = load(&format!("{HEAD}[inputs]\ni = {{}}\n[outputs]\no = {{}}\n")).unwrap();
        assert_eq!(p.scan_period_ms, 10);
        assert_eq!(p.max_commands_per_scan, 1);
        assert_eq!(p.unexpected, Unexpected::Fault);
        assert_eq!(p.reset, None);
        assert_eq!(p.overrun_limit, 1);
        assert!(!p.overrun_fault && !p.lost_edge_fault);
        assert_eq!(p.rom_test_bytes_per_scan, 64);
        assert_eq!(p.stored_sets_bytes, 1024);
        assert_eq!(p.inputs[0].debounce_scans, 0);
        assert!(!p.outputs[0].safe);
        assert_eq!(p.outputs[0].drive, Drive::Actions { initial: false });
    }

    #[test]
    fn every_bound_is_inclusive_and_named_in_the_error() {
        let period = |v: &str| load(&format!("[plc]\nname = \"n\"\nscan_period_ms = {v}\n"));
        assert_eq!(period("1").unwrap().scan_period_ms, 1);
        assert_eq!(
            period("2147483647").unwrap().scan_period_ms,
            i32::MAX as u32
        );
        let err = period("2147483648").unwrap_err().to_string();
        assert_eq!(
            err,
            "dir/p.plc.toml:3:18: scan_period_ms must be between 1 and 2147483647, found 2147483648"
        );
        let err = load(&format!("{HEAD}[inputs]\ni = {{ debounce_scans = 256 }}\n"))
            .unwrap_err()
            .to_string();
        assert!(
            err.ends_with("debounce_scans must be between 0 and 255, found 256"),
            "{err}"
        );
        let p = load(&format!(
            "{HEAD}max_commands_per_scan = 0\noverrun_limit = 65535\nrom_test_bytes_per_scan = 65532\n"
        ))
        .unwrap();
        assert_eq!((p.max_commands_per_scan, p.overrun_limit), (0, 65535));
        assert_eq!(p.rom_test_bytes_per_scan, 65532);
        let p = load(&format!("{HEAD}rom_test_bytes_per_scan = 4\n")).unwrap();
        assert_eq!(p.rom_test_bytes_per_scan, 4);
        let sets = |v: &str| load(&format!("{HEAD}stored_sets_bytes = {v}\n"));
        assert_eq!(sets("0").unwrap().stored_sets_bytes, 0);
        assert_eq!(
            sets("2147483647").unwrap().stored_sets_bytes,
            i32::MAX as u32
        );
        let err = sets("-1").unwrap_err().to_string();
        assert!(
            err.ends_with("stored_sets_bytes must be between 0 and 2147483647, found -1"),
            "{err}"
        );
    }
}
