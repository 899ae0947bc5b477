//! Lines of text to the host over semihosting without `core::fmt`: the
//! replay harness's reports. The board never links `core::fmt` (its
//! panics have constant messages, its log is defmt), so the harness that
//! measures its flash does not either: `hprintln!` and a formatting panic
//! handler were about 3.5 KB of every harness's flash figure.

/// A line being built in a fixed buffer (text past its capacity is cut).
pub struct Line {
    bytes: [u8; Line::CAPACITY],
    len: usize,
}

impl Line {
    /// Bytes a line holds.
    pub const CAPACITY: usize = 320;

    /// An empty line.
    pub const fn new() -> Line {
        Line {
            bytes: [0; Line::CAPACITY],
            len: 0,
        }
    }

    /// Appends `text`.
    #[inline(never)]
    pub fn text(&mut self, text: &str) -> &mut Line {
        for &b in text.as_bytes() {
            self.push(b);
        }
        self
    }

    /// Appends `value` in decimal.
    #[inline(never)]
    pub fn num(&mut self, value: u32) -> &mut Line {
        let mut divisor = 1_000_000_000u32;
        while divisor > 1 && value / divisor == 0 {
            divisor /= 10;
        }
        while divisor > 0 {
            self.push(b'0' + (value / divisor % 10) as u8);
            divisor /= 10;
        }
        self
    }

    /// Appends `value` as `0x` and eight hexadecimal digits.
    #[inline(never)]
    pub fn hex(&mut self, value: u32) -> &mut Line {
        self.text("0x");
        for shift in (0..8).rev() {
            let nibble = (value >> (shift * 4) & 0xf) as u8;
            self.push(if nibble < 10 {
                b'0' + nibble
            } else {
                b'a' + nibble - 10
            });
        }
        self
    }

    /// The line so far.
    pub fn as_bytes(&self) -> &[u8] {
        self.bytes.get(..self.len).unwrap_or_default()
    }

    /// Writes the line and a newline to the host's standard output (lost
    /// when the host has none).
    #[cfg(any(feature = "qemu", feature = "guard-bench"))]
    #[inline(never)]
    pub fn print(&mut self) {
        self.text("\n");
        if let Ok(mut out) = cortex_m_semihosting::hio::hstdout() {
            let _ = out.write_all(self.as_bytes());
        }
    }

    fn push(&mut self, b: u8) {
        if let Some(slot) = self.bytes.get_mut(self.len) {
            *slot = b;
            self.len += 1;
        }
    }
}

impl Default for Line {
    fn default() -> Line {
        Line::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_text_as_fmt_writes_them() {
        let mut line = Line::new();
        line.text("scans=")
            .num(3000)
            .text(" zero=")
            .num(0)
            .text(" max=")
            .num(u32::MAX)
            .text(" crc=")
            .hex(0x6a97_9c27)
            .text(" ")
            .hex(0);
        assert_eq!(
            line.as_bytes(),
            format!(
                "scans={} zero={} max={} crc={:#010x} {:#010x}",
                3000,
                0,
                u32::MAX,
                0x6a97_9c27u32,
                0
            )
            .as_bytes()
        );
    }

    #[test]
    fn text_past_the_capacity_is_cut() {
        let mut line = Line::new();
        for _ in 0..100 {
            line.text("abcd");
        }
        assert_eq!(line.as_bytes().len(), Line::CAPACITY);
        assert!(line.as_bytes().starts_with(b"abcdabcd"));
    }
}
