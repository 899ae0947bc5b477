//! What describes a development board: [`DevBoard`], the pins it wires
//! to something by default ([`PinNote`]) and where pins are on it.

use crate::chip::Chip;
use crate::pin::PinId;

/// A development board: the chip it carries and what it wires to its
/// pins, for warnings and the wiring table.
#[derive(Debug, PartialEq, Eq)]
pub struct DevBoard {
    /// Its name, such as `Nucleo-F411RE`.
    pub name: &'static str,
    /// Its short name in the wiring table's notes (`Nucleo: Arduino D2`).
    pub short_name: &'static str,
    /// The chip it carries.
    pub chip: &'static Chip,
    /// The part on it, as probe-rs names it.
    pub part: &'static str,
    /// Pins wired to something else by default: what a project mapping a
    /// signal there should know (validation warnings).
    pub notes: &'static [PinNote],
    /// Where pins are on its headers, buttons and LEDs (the wiring table).
    pub places: &'static [(PinId, &'static str)],
}

/// Something a board wires to some pins by default.
#[derive(Debug, PartialEq, Eq)]
pub struct PinNote {
    /// The pins.
    pub pins: &'static [PinId],
    /// Whether it matters only for an output on the pin.
    pub outputs_only: bool,
    /// Whether it matters only for an input on the pin.
    pub inputs_only: bool,
    /// What, as the end of a sentence that starts with the pin's name.
    pub text: &'static str,
}

impl DevBoard {
    /// Whether the part `part` (case-insensitive) is the board's chip in
    /// the board's package (the package letter after the chip's name):
    /// the board may be what a project with that part runs on. Other
    /// boards with the same part may wire it differently.
    pub fn carries(&self, part: &str) -> bool {
        let letter = |p: &str| {
            p.as_bytes()
                .get(self.chip.name.len())
                .map(u8::to_ascii_uppercase)
        };
        self.chip.matches_part(part) && letter(part) == letter(self.part)
    }

    /// What the board wires to `pin` that a signal there should know
    /// about (`output`: the signal is an output), if anything.
    pub fn note(&self, pin: PinId, output: bool) -> Option<&'static str> {
        self.notes
            .iter()
            .find(|n| {
                n.pins.contains(&pin)
                    && if output {
                        !n.inputs_only
                    } else {
                        !n.outputs_only
                    }
            })
            .map(|n| n.text)
    }

    /// Where `pin` is on the board (a header pin, a button, an LED);
    /// `None` for pins only on the extension headers.
    pub fn place(&self, pin: PinId) -> Option<&'static str> {
        self.places
            .iter()
            .find(|(p, _)| *p == pin)
            .map(|&(_, place)| place)
    }
}
