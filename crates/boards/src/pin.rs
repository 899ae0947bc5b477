//! Pins by name (`PC13`) and the bias resistor of an input pin.

use core::fmt;
use core::str::FromStr;

/// A GPIO pin named by its port letter and its number in the port, such
/// as `PA0` or `PC13`.
///
/// This is the name only: which ports and pins exist is the chip's
/// ([`Chip::pin`](crate::Chip::pin) parses a name and checks it), which
/// of them a package bonds out is the package's
/// ([`Package::has`](crate::Package::has)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PinId {
    /// Port letter, upper case (`'A'`..=`'E'` or `'H'` on the STM32F411).
    pub port: char,
    /// Pin number in the port (0–15 on the STM32F411); also its EXTI
    /// line ([`Chip::exti_line`](crate::Chip::exti_line)).
    pub number: u8,
}

impl PinId {
    /// The port of a chip whose pins are one numbered bank
    /// ([`PinNaming::Bank`](crate::PinNaming::Bank), the RP2040's `GP25`):
    /// not a letter, so no STM32 port can be taken for it.
    pub const BANK: char = '#';

    /// Port `port`, pin `number`.
    pub const fn new(port: char, number: u8) -> PinId {
        PinId { port, number }
    }

    /// Pin `number` of a numbered bank ([`PinId::BANK`]): `GP<number>`.
    pub const fn gp(number: u8) -> PinId {
        PinId {
            port: PinId::BANK,
            number,
        }
    }

    /// Parses `GP<number>` (one or two decimal digits, case-insensitive,
    /// surrounding white space ignored) as a pin of a numbered bank.
    pub fn parse_bank(s: &str) -> Option<PinId> {
        let s = s.trim();
        let digits = s
            .get(..2)
            .filter(|p| p.eq_ignore_ascii_case("GP"))
            .and(s.get(2..))?;
        if digits.is_empty() || digits.len() > 2 || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        Some(PinId::gp(digits.parse().ok()?))
    }
}

impl fmt::Display for PinId {
    /// `P<port><number>`, such as `PC13`; `GP<number>` for a pin of a
    /// numbered bank ([`PinId::BANK`]), such as `GP25`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.port == PinId::BANK {
            write!(f, "GP{}", self.number)
        } else {
            write!(f, "P{}{}", self.port, self.number)
        }
    }
}

/// A text that is not shaped like a pin name, `P<port><number>` (see
/// [`PinId`]'s `FromStr`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NotAPinName;

impl fmt::Display for NotAPinName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("not a pin name: expected `P<port><number>` such as `PA0` or `PC13`")
    }
}

impl core::error::Error for NotAPinName {}

impl FromStr for PinId {
    type Err = NotAPinName;

    /// Parses the shape of a pin name: `P`, one port character and one or
    /// two decimal digits, case-insensitive, surrounding white space
    /// ignored (`pc13` is `PC13`). Any character is taken as the port
    /// here; [`Chip::pin`](crate::Chip::pin) checks that the chip has the
    /// port and the pin.
    fn from_str(s: &str) -> Result<PinId, NotAPinName> {
        let mut chars = s.trim().chars();
        if chars.next().map(|c| c.to_ascii_uppercase()) != Some('P') {
            return Err(NotAPinName);
        }
        let port = chars.next().ok_or(NotAPinName)?.to_ascii_uppercase();
        let digits = chars.as_str();
        if digits.is_empty() || digits.len() > 2 || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(NotAPinName);
        }
        let number = digits.parse().map_err(|_| NotAPinName)?;
        Ok(PinId { port, number })
    }
}

/// Internal bias resistor of an input pin.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Pull {
    /// Floating: the wiring defines the level (default).
    #[default]
    None,
    /// Pulled up to VDD.
    Up,
    /// Pulled down to ground.
    Down,
}

impl Pull {
    /// Every pull, in the order of [`Pull::name`]'s documentation.
    pub const ALL: [Pull; 3] = [Pull::None, Pull::Up, Pull::Down];

    /// The name used in project files: `none`, `up` or `down`.
    pub const fn name(self) -> &'static str {
        match self {
            Pull::None => "none",
            Pull::Up => "up",
            Pull::Down => "down",
        }
    }

    /// The pull named `name` in a project file ([`Pull::name`], exactly).
    pub fn from_name(name: &str) -> Option<Pull> {
        Pull::ALL.into_iter().find(|p| p.name() == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;

    #[test]
    fn pin_names_read_back_in_upper_case() {
        for (text, port, number) in [
            ("PA0", 'A', 0),
            ("pc13", 'C', 13),
            (" PB07 ", 'B', 7),
            ("PZ9", 'Z', 9),
            ("P11", '1', 1),
        ] {
            let pin: PinId = text.parse().unwrap();
            assert_eq!(pin, PinId::new(port, number), "{text}");
        }
        assert_eq!(PinId::new('C', 13).to_string(), "PC13");
        for text in ["", "P", "PA", "A0", "PA001", "PAx", "PA-1", "PA 1", "QA0"] {
            assert_eq!(text.parse::<PinId>(), Err(NotAPinName), "{text:?}");
        }
        assert_eq!(PinId::parse_bank(" gp25"), Some(PinId::gp(25)));
        assert_eq!(PinId::gp(7).to_string(), "GP7");
        for text in ["", "GP", "G25", "GP123", "GPx", "PA0", "GP 1", "GPIO2"] {
            assert_eq!(PinId::parse_bank(text), None, "{text:?}");
        }
    }

    #[test]
    fn pulls_are_named_as_in_project_files() {
        for pull in Pull::ALL {
            assert_eq!(Pull::from_name(pull.name()), Some(pull));
        }
        assert_eq!(Pull::from_name("Up"), None);
        assert_eq!(Pull::default(), Pull::None);
    }
}

/// A signal's pin in a generated pin map: the pin, its bias resistor and
/// how the signal maps onto its level. Generated files hold these as
/// data; the firmware configures its pins from them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SignalPin {
    /// The pin.
    pub pin: PinId,
    /// Internal bias resistor ([`Pull::None`] for outputs, which are
    /// push-pull).
    pub pull: Pull,
    /// The signal is 1 while the pin is low.
    pub active_low: bool,
}
