//! What describes an MCU the board firmware runs on: [`Chip`] and its
//! parts ([`Port`], [`Package`], [`Reserved`], [`Watchdog`]).

use crate::pin::PinId;
use core::fmt;

/// An MCU line the board firmware is written for, as const data: its GPIO
/// ports, the packages its part names select, the pins the firmware keeps
/// for itself, its edge-interrupt rule and its watchdog.
///
/// [`STM32F411`](crate::STM32F411) and [`RP2040`](crate::RP2040) are
/// the ones there are; another MCU is another `const Chip` added to
/// [`CHIPS`](crate::CHIPS) (and a board module in the firmware,
/// docs/board.md).
#[derive(Debug, PartialEq, Eq)]
pub struct Chip {
    /// The line's name, which every part name of it starts with
    /// (case-insensitive), such as `STM32F411`.
    pub name: &'static str,
    /// How its pins are named: `PC13` (ports) or `GP25` (one bank).
    pub naming: PinNaming,
    /// The GPIO ports, in letter order.
    pub ports: &'static [Port],
    /// How many pins a full port has (numbers `0..port_width`).
    pub port_width: u8,
    /// The packages that bond out fewer pins than the ports have, by the
    /// letter after [`Chip::name`] in a part name. A part whose letter is
    /// not listed has every pin of [`Chip::ports`].
    pub packages: &'static [Package],
    /// Pins the firmware cannot give to a signal.
    pub reserved: &'static [Reserved],
    /// How many EXTI lines (edge interrupts) there are; see
    /// [`Chip::exti_line`].
    pub exti_lines: u8,
    /// What an edge interrupt line is called, before its number
    /// ([`Chip::exti_line`]): `EXTI` (`EXTI13`) on an STM32,
    /// `GPIO` (`GPIO25`, one edge interrupt per pin) on the RP2040.
    pub edge_line: &'static str,
    /// The independent watchdog.
    pub watchdog: Watchdog,
}

/// How a chip's pins are named.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PinNaming {
    /// `P<port><number>`, such as `PA0` or `PC13` (STM32).
    Ports,
    /// `GP<number>`, such as `GP0` or `GP25`: one bank of numbered pins,
    /// held as port [`PinId::BANK`] (RP2040).
    Bank,
}

/// A GPIO port.
#[derive(Debug, PartialEq, Eq)]
pub struct Port {
    /// Its letter, upper case.
    pub letter: char,
    /// How many pins it has (numbers `0..pins`).
    pub pins: u8,
}

/// A package that bonds out only some pins of the ports.
#[derive(Debug, PartialEq, Eq)]
pub struct Package {
    /// The letter after the chip's name in a part name (`R` in
    /// `STM32F411RETx`).
    pub letter: char,
    /// Its pin count.
    pub pins: u16,
    /// The pins it has: per port letter, bit `n` for pin `n`; a port not
    /// listed has none.
    pub bonded: &'static [(char, u16)],
    /// The same in words, for an error naming a pin it lacks.
    pub summary: &'static str,
}

/// A pin the firmware keeps for itself.
#[derive(Debug, PartialEq, Eq)]
pub struct Reserved {
    /// The pin.
    pub pin: PinId,
    /// Why no signal may use it, a sentence starting with the pin's name.
    pub why: &'static str,
}

/// The independent watchdog and how the firmware sets it: it resets the
/// chip when no scan completes within [`Watchdog::periods`] scan periods.
#[derive(Debug, PartialEq, Eq)]
pub struct Watchdog {
    /// Scan periods the firmware's watchdog waits for a scan to complete.
    pub periods: u32,
    /// The shortest timeout the firmware sets (ms), so that a 1 ms scan
    /// tolerates a slow log line.
    pub min_timeout_ms: u32,
    /// The longest timeout the watchdog can count (ms).
    pub max_timeout_ms: u32,
}

impl Watchdog {
    /// The firmware's watchdog timeout for a scan period: [`periods`]
    /// periods, at least [`min_timeout_ms`] (saturating).
    ///
    /// [`periods`]: Watchdog::periods
    /// [`min_timeout_ms`]: Watchdog::min_timeout_ms
    pub const fn timeout_ms(&self, scan_period_ms: u32) -> u32 {
        let timeout = scan_period_ms.saturating_mul(self.periods);
        if timeout < self.min_timeout_ms {
            self.min_timeout_ms
        } else {
            timeout
        }
    }

    /// The longest scan period a board project may have: the longest
    /// period whose [`timeout_ms`](Watchdog::timeout_ms) the watchdog can
    /// count, in whole seconds (rounded down, so the limit is a figure a
    /// user can remember and a little below the bound).
    pub const fn max_scan_period_ms(&self) -> u32 {
        self.max_timeout_ms / self.periods / 1000 * 1000
    }
}

impl Chip {
    /// The port with letter `letter` (upper case), if the chip has it.
    pub fn port(&self, letter: char) -> Option<&'static Port> {
        self.ports.iter().find(|p| p.letter == letter)
    }

    /// Whether the part name `part` (case-insensitive) is one of this
    /// chip's.
    pub fn matches_part(&self, part: &str) -> bool {
        part.get(..self.name.len())
            .is_some_and(|prefix| prefix.eq_ignore_ascii_case(self.name))
    }

    /// The package of the part `part` (one of this chip's), `None` when
    /// its package letter is not in [`Chip::packages`]: then every pin of
    /// the ports is there.
    pub fn package(&self, part: &str) -> Option<&'static Package> {
        let letter = char::from(part.as_bytes().get(self.name.len())?.to_ascii_uppercase());
        self.packages.iter().find(|p| p.letter == letter)
    }

    /// Parses the pin name `name` and checks that the chip has the pin
    /// (not whether a package bonds it out or the firmware may use it).
    pub fn pin<'a>(&'static self, name: &'a str) -> Result<PinId, PinError<'a>> {
        let error = |kind| PinError {
            name,
            chip: self,
            kind,
        };
        let pin = match self.naming {
            PinNaming::Ports => name.parse().map_err(|_| error(PinErrorKind::Shape))?,
            PinNaming::Bank => PinId::parse_bank(name).ok_or(error(PinErrorKind::Shape))?,
        };
        let Some(port) = self.port(pin.port) else {
            return Err(error(PinErrorKind::NoPort(pin.port)));
        };
        if pin.number >= self.port_width {
            return Err(error(PinErrorKind::PastPortWidth));
        }
        if pin.number >= port.pins {
            return Err(error(PinErrorKind::ShortPort(pin.port, port.pins)));
        }
        Ok(pin)
    }

    /// Why the firmware cannot give `pin` to a signal, if it cannot.
    pub fn reserved(&self, pin: PinId) -> Option<&'static str> {
        self.reserved.iter().find(|r| r.pin == pin).map(|r| r.why)
    }

    /// The EXTI line of `pin`: its number. Line *n* listens to pin *n* of
    /// one port at a time, so two inputs with the same number on different
    /// ports cannot both interrupt.
    pub const fn exti_line(&self, pin: PinId) -> u8 {
        pin.number
    }
}

impl Package {
    /// Whether the package bonds out `pin`.
    pub fn has(&self, pin: PinId) -> bool {
        self.bonded.iter().any(|&(port, mask)| {
            port == pin.port && pin.number < 16 && mask & (1 << pin.number) != 0
        })
    }
}

/// A pin name that [`Chip::pin`] refused: the name, the chip, and what is
/// wrong, which `Display` says in a sentence.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PinError<'a> {
    /// The name as given.
    pub name: &'a str,
    /// The chip it was checked against.
    pub chip: &'static Chip,
    /// What is wrong.
    pub kind: PinErrorKind,
}

/// What is wrong with a pin name ([`PinError`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PinErrorKind {
    /// Not shaped `P<port><number>`.
    Shape,
    /// The chip has no such port.
    NoPort(char),
    /// A number past [`Chip::port_width`].
    PastPortWidth,
    /// A port with fewer pins than a full one: its letter and pin count.
    ShortPort(char, u8),
}

/// The chip's ports as a list of letter ranges: `ports A–E and H`.
struct PortList(&'static Chip);

impl fmt::Display for PortList {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ports = self.0.ports;
        f.write_str(if ports.len() == 1 { "port " } else { "ports " })?;
        // Runs of consecutive letters.
        let mut runs = ports
            .chunk_by(|a, b| u32::from(a.letter) + 1 == u32::from(b.letter))
            .peekable();
        let mut first = true;
        while let Some(run) = runs.next() {
            if !first {
                f.write_str(if runs.peek().is_some() { ", " } else { " and " })?;
            }
            first = false;
            let (start, end) = (run[0].letter, run[run.len() - 1].letter);
            match run.len() {
                1 => write!(f, "{start}")?,
                2 => write!(f, "{start}, {end}")?,
                _ => write!(f, "{start}–{end}")?,
            }
        }
        Ok(())
    }
}

impl fmt::Display for PinError<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (name, chip) = (self.name, self.chip);
        let last = chip.port_width.saturating_sub(1);
        if chip.naming == PinNaming::Bank {
            let pins = chip.ports.first().map_or(0, |p| p.pins);
            let last = pins.saturating_sub(1);
            return match self.kind {
                PinErrorKind::Shape | PinErrorKind::NoPort(_) => write!(
                    f,
                    "`{name}` is not a pin name of the {}: expected `GP<number>` such as `GP0` or `GP15` (GP0–GP{last})",
                    chip.name
                ),
                PinErrorKind::PastPortWidth | PinErrorKind::ShortPort(..) => {
                    write!(f, "`{name}`: the {} has GP0–GP{last}", chip.name)
                }
            };
        }
        match self.kind {
            PinErrorKind::Shape => write!(
                f,
                "`{name}` is not a pin name: expected `P<port><number>` such as `PA0` or `PC13` ({}, pins 0–{last})",
                PortList(chip)
            ),
            PinErrorKind::NoPort(port) => write!(
                f,
                "`{name}`: the {} has no GPIO port {port} ({})",
                chip.name,
                PortList(chip)
            ),
            PinErrorKind::PastPortWidth => write!(f, "`{name}`: a port has pins 0–{last}"),
            PinErrorKind::ShortPort(port, pins) => {
                write!(f, "`{name}`: port {port} of the {} has only ", chip.name)?;
                match pins {
                    0 => f.write_str("no pins"),
                    1 => write!(f, "P{port}0"),
                    2 => write!(f, "P{port}0 and P{port}1"),
                    _ => write!(f, "P{port}0–P{port}{}", pins - 1),
                }
            }
        }
    }
}

impl core::error::Error for PinError<'_> {}
