//! Where the two field-update slots live in each board's flash (feature
//! `field-update`), one module per chip: the addresses, the erase unit,
//! and the linker layout `build.rs` writes from them (the firmware's
//! `FLASH` ends where slot A begins). The board's slot store erases,
//! programs and reads these regions.

pub mod rp2040;
pub mod stm32f411re;

/// Where a board's two slots are (slot A's and B's address: the
/// firmware's `field::address`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SlotMap {
    /// Slot A's address.
    pub a: u32,
    /// Slot B's address.
    pub b: u32,
    /// Bytes of each slot.
    pub bytes: u32,
}

impl SlotMap {
    /// Words of each slot.
    pub const fn words(&self) -> usize {
        (self.bytes / 4) as usize
    }
}

#[cfg(test)]
mod tests {
    /// The origin and length of memory region `name` (`FLASH`, `RAM`,
    /// `BOOT2`) in a linker script.
    pub fn region(script: &str, name: &str) -> (u32, u32) {
        let line = script
            .lines()
            .find(|l| {
                l.trim_start()
                    .strip_prefix(name)
                    .is_some_and(|rest| rest.trim_start().starts_with(':'))
            })
            .expect("region");
        let origin = number_after(line, "ORIGIN =");
        (origin, number_after(line, "LENGTH ="))
    }

    /// The linker script `write` writes.
    pub fn written(write: fn(&mut String) -> core::fmt::Result) -> String {
        let mut script = String::new();
        write(&mut script).expect("writes");
        script
    }

    /// The number after `key` in `text`: hex with `0x`, or decimal
    /// followed by `K` (KiB).
    pub fn number_after(text: &str, key: &str) -> u32 {
        let rest = &text[text.find(key).expect(key) + key.len()..];
        let token: String = rest
            .trim_start()
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        match token.strip_prefix("0x") {
            Some(hex) => u32::from_str_radix(hex, 16).expect("hex"),
            None => {
                token
                    .strip_suffix('K')
                    .expect("K")
                    .parse::<u32>()
                    .expect("kib")
                    * 1024
            }
        }
    }
}
