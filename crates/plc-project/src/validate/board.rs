//! Board: which MCU pin carries each signal.
//!
//! The optional `[board]` section maps signals to pins of the MCU the
//! board firmware runs on:
//!
//! ```toml
//! [board]
//! chip = "STM32F411RETx"            # optional, this is the default
//! inputs = { auto_pb = { pin = "PC13", pull = "up", active_low = true }, part = "PA1" }
//! outputs = { down_sol = { pin = "PB0" }, auto_lamp = "PA5" }
//! ```
//!
//! (`[board.inputs]` / `[board.outputs]` tables work as well). A bare
//! string is the pin with every option at its default: `pull = "none"`,
//! `active_low = false`. Outputs are push-pull and take no `pull`.
//!
//! - `chip` must be an STM32F411 (the firmware's HAL); its package letter
//!   (`R`: 64 pins, `C`: 48 pins) limits the pins that exist.
//! - Every key names a declared input (under `inputs`) or output (under
//!   `outputs`); a pin is `P<port><n>`, ports A–E and H, pins 0–15 (port H:
//!   PH0 and PH1), case-insensitive. PA13/PA14 (SWD, which flashes the board
//!   and carries the log) and PH0 (the HSE clock input) are refused.
//! - No pin carries two signals; `pull` is `up`, `down` or `none`.
//! - `scan_period_ms` is at most [`MAX_BOARD_SCAN_PERIOD_MS`] (the
//!   watchdog waits 4 periods and at most 32.7 s).
//! - Warnings: an input without a pin (the firmware reads 0), an output
//!   without a pin (computed, not driven), Nucleo-F411RE pins that are
//!   wired to something else by default (PA2/PA3, PC14/PC15, PC13 as an
//!   output), and an input whose EXTI line is taken.
//!
//! **Edge latching** ([`EdgeLatch`]): the firmware counts the changes of an
//! input between two samples with an interrupt on both edges of EXTI line
//! *n* (the pin number); more than one change is a lost edge (docs/semantics.md,
//! `LostEdge`). A line listens to one port, so the first input in
//! declaration order with pin number *n* owns it and a later one on
//! another port is not latched (a warning). Debounced inputs
//! (`debounce_scans > 1`) are not latched either: their filter drops short
//! pulses on purpose, so a pulse between samples is not an error there.

use super::super::model::*;
use super::super::parse::{Name, RawBoard, RawInputPin, RawOutputPin, RawPin};
use super::Validator;
use des::error::Result;
use std::collections::HashMap;
use std::ops::Range;
use toml::Spanned;

/// The chip when `[board]` names none: the Nucleo-F411RE's.
pub const DEFAULT_CHIP: &str = "STM32F411RETx";

/// Longest scan period a board project may have: the firmware's
/// independent watchdog waits 4 periods for a scan to complete and
/// cannot wait longer than 32.7 s.
pub const MAX_BOARD_SCAN_PERIOD_MS: u32 = 8000;

/// A pin the board firmware cannot give to a signal, and why.
fn reserved(pin: PinId) -> Option<&'static str> {
    match (pin.port, pin.number) {
        ('A', 13) => Some(
            "PA13 is SWDIO of the debug port: the probe (the Nucleo's ST-LINK) flashes the board and reads the defmt log through it",
        ),
        ('A', 14) => Some(
            "PA14 is SWCLK of the debug port: the probe (the Nucleo's ST-LINK) flashes the board and reads the defmt log through it",
        ),
        ('H', 0) => Some(
            "PH0 is OSC_IN: the firmware clocks the chip from the ST-LINK's 8 MHz clock on PH0 (HSE bypass)",
        ),
        _ => None,
    }
}

/// The package of an STM32F411 from its part name (the letter after
/// `STM32F411`), as far as it limits the pins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Package {
    /// `R`: LQFP64 (the Nucleo-F411RE): ports A–C, PD2, PH0–1.
    Pins64,
    /// `C`: UFQFPN48 / WLCSP49 ("Black Pill"): ports A and B without
    /// PB11, PC13–15, PH0–1.
    Pins48,
    /// `V` or unknown: every pin of ports A–E and H exists.
    Full,
}

impl Package {
    fn of(chip: &str) -> Package {
        match chip.as_bytes().get(9).map(u8::to_ascii_uppercase) {
            Some(b'R') => Package::Pins64,
            Some(b'C') => Package::Pins48,
            _ => Package::Full,
        }
    }

    /// `None` when the package has `pin`, otherwise what it has instead.
    fn lacks(self, pin: PinId) -> Option<&'static str> {
        let has = match self {
            Package::Full => true,
            Package::Pins64 => match pin.port {
                'A' | 'B' | 'C' | 'H' => true,
                'D' => pin.number == 2,
                _ => false,
            },
            Package::Pins48 => match pin.port {
                'A' | 'H' => true,
                'B' => pin.number != 11,
                'C' => pin.number >= 13,
                _ => false,
            },
        };
        match (has, self) {
            (true, _) | (false, Package::Full) => None,
            (false, Package::Pins64) => Some("the 64-pin package has ports A–C, PD2, PH0 and PH1"),
            (false, Package::Pins48) => {
                Some("the 48-pin package has port A, port B without PB11, PC13–PC15, PH0 and PH1")
            }
        }
    }
}

/// What the Nucleo-F411RE has on `pin` that a project should know about,
/// if anything (warnings only, for the 64-pin chip: other boards with it
/// differ).
fn nucleo_note(pin: PinId, output: bool) -> Option<&'static str> {
    match (pin.port, pin.number) {
        ('A', 2) | ('A', 3) => Some(
            "carries USART2 to the ST-LINK virtual COM port on a Nucleo-F411RE and reaches the headers only after changing solder bridges (UM1724)",
        ),
        ('C', 14) | ('C', 15) => Some(
            "is wired to the 32.768 kHz crystal X2 on a Nucleo-F411RE and is not on the headers by default (UM1724)",
        ),
        ('C', 13) if output => Some(
            "is the user button B1 on a Nucleo-F411RE: pressing it shorts the output to ground",
        ),
        _ => None,
    }
}

/// Who already uses a pin.
struct PinUse {
    kind: &'static str,
    name: String,
    line: u32,
}

impl Validator<'_> {
    /// Validates `[board]` against the declared signals.
    pub(super) fn board(
        &mut self,
        raw: Option<&Spanned<RawBoard>>,
        scan_period: Option<&Spanned<i64>>,
        inputs: &[Input],
        outputs: &[Output],
    ) -> Result<Option<Board>> {
        let Some(raw) = raw else {
            return Ok(None);
        };
        let header = raw.span();
        let decl = raw.get_ref();

        let chip = match &decl.chip {
            None => DEFAULT_CHIP.to_owned(),
            Some(chip) => {
                if !chip.get_ref().to_ascii_uppercase().starts_with("STM32F411") {
                    return Err(self.error(
                        &chip.span(),
                        format!(
                            "chip `{}` is not supported: the board firmware is written for the STM32F411 (probe-rs names such as `STM32F411RETx`, the Nucleo-F411RE's, or `STM32F411CEUx`)",
                            chip.get_ref()
                        ),
                    ));
                }
                chip.get_ref().clone()
            }
        };
        let package = Package::of(&chip);
        // The Nucleo-F411RE carries the 64-pin package.
        let nucleo = package == Package::Pins64;

        if let Some(period) = scan_period {
            if *period.get_ref() > i64::from(MAX_BOARD_SCAN_PERIOD_MS) {
                return Err(self.error(
                    &period.span(),
                    format!(
                        "a project with a [board] needs scan_period_ms ≤ {MAX_BOARD_SCAN_PERIOD_MS}, found {}: the board's watchdog restarts it when no scan completes within 4 periods, and it cannot wait longer than 32.7 s",
                        period.get_ref()
                    ),
                ));
            }
        }

        let input_index: HashMap<&str, usize> = inputs
            .iter()
            .enumerate()
            .map(|(i, x)| (x.name.as_str(), i))
            .collect();
        let output_index: HashMap<&str, usize> = outputs
            .iter()
            .enumerate()
            .map(|(o, x)| (x.name.as_str(), o))
            .collect();
        let mut used: HashMap<PinId, PinUse> = HashMap::new();

        // Inputs.
        let mut input_pins: Vec<Option<InputPin>> = vec![None; inputs.len()];
        for (name, value) in &decl.inputs.0 {
            let i = self.signal(name, &input_index, &output_index, "input")?;
            let (pin_name, pin_span, pull, active_low) = match value.get_ref() {
                RawPin::Bare(pin) => (pin.as_str(), value.span(), Pull::None, false),
                RawPin::Table(RawInputPin {
                    pin,
                    pull,
                    active_low,
                }) => (
                    pin.get_ref().as_str(),
                    pin.span(),
                    self.pull(pull.as_ref())?,
                    *active_low,
                ),
            };
            let pin = self.pin(pin_name, &pin_span, package, &chip)?;
            self.claim_pin(&mut used, pin, &pin_span, "input", name.get_ref())?;
            if let Some(note) = nucleo_note(pin, false).filter(|_| nucleo) {
                self.warn(
                    &pin_span,
                    format!("input `{}`: {pin} {note}", name.get_ref()),
                );
            }
            input_pins[i] = Some(InputPin {
                pin,
                pull,
                active_low,
                edge_latch: EdgeLatch::Latched,
                line: self.line(&pin_span),
            });
        }

        // Outputs.
        let mut output_pins: Vec<Option<OutputPin>> = vec![None; outputs.len()];
        for (name, value) in &decl.outputs.0 {
            let o = self.signal(name, &output_index, &input_index, "output")?;
            let (pin_name, pin_span, active_low) = match value.get_ref() {
                RawPin::Bare(pin) => (pin.as_str(), value.span(), false),
                RawPin::Table(RawOutputPin { pin, active_low }) => {
                    (pin.get_ref().as_str(), pin.span(), *active_low)
                }
            };
            let pin = self.pin(pin_name, &pin_span, package, &chip)?;
            self.claim_pin(&mut used, pin, &pin_span, "output", name.get_ref())?;
            if let Some(note) = nucleo_note(pin, true).filter(|_| nucleo) {
                self.warn(
                    &pin_span,
                    format!("output `{}`: {pin} {note}", name.get_ref()),
                );
            }
            output_pins[o] = Some(OutputPin {
                pin,
                active_low,
                line: self.line(&pin_span),
            });
        }

        // Edge latching: one port per EXTI line, the first input in
        // declaration order wins.
        let mut line_owner: [Option<(usize, PinId)>; 16] = [None; 16];
        for (i, slot) in input_pins.iter_mut().enumerate() {
            let Some(p) = slot else { continue };
            if inputs[i].debounce_scans > 1 {
                p.edge_latch = EdgeLatch::Debounced;
                continue;
            }
            let line = usize::from(p.pin.number);
            match line_owner[line] {
                None => line_owner[line] = Some((i, p.pin)),
                Some((owner, owner_pin)) => {
                    p.edge_latch = EdgeLatch::LineTaken(owner);
                    let (name, pin, at) = (&inputs[i].name, p.pin, p.line);
                    self.warnings.push(Warning {
                        line: at,
                        message: format!(
                            "input `{name}` ({pin}) shares EXTI line {line} with input `{}` ({owner_pin}): one port per line can interrupt, so lost edges of `{name}` go undetected; give it a pin number no earlier input uses",
                            inputs[owner].name
                        ),
                    });
                }
            }
        }

        // Signals without a pin.
        for (i, input) in inputs.iter().enumerate() {
            if input_pins[i].is_none() {
                self.warn(
                    &header,
                    format!(
                        "input `{}` has no pin in [board.inputs]: the board firmware reads it as 0",
                        input.name
                    ),
                );
            }
        }
        for (o, output) in outputs.iter().enumerate() {
            if output_pins[o].is_none() {
                self.warn(
                    &header,
                    format!(
                        "output `{}` has no pin in [board.outputs]: the board firmware computes it but drives no pin",
                        output.name
                    ),
                );
            }
        }

        Ok(Some(Board {
            chip,
            inputs: input_pins,
            outputs: output_pins,
            line: self.line(&header),
        }))
    }

    /// The index of the signal `name` of `kind`; naming a signal of the
    /// other kind says so.
    fn signal(
        &self,
        name: &Name,
        index: &HashMap<&str, usize>,
        other: &HashMap<&str, usize>,
        kind: &str,
    ) -> Result<usize> {
        if let Some(&i) = index.get(name.get_ref().as_str()) {
            return Ok(i);
        }
        let hint = if other.contains_key(name.get_ref().as_str()) {
            let other_kind = if kind == "input" { "output" } else { "input" };
            format!(
                ": `{}` is an {other_kind}, map it under [board.{other_kind}s]",
                name.get_ref()
            )
        } else {
            String::new()
        };
        Err(self.error(
            &name.span(),
            format!(
                "unknown {kind} `{}` in [board.{kind}s]: not declared in [{kind}s]{hint}",
                name.get_ref()
            ),
        ))
    }

    fn pull(&self, pull: Option<&Name>) -> Result<Pull> {
        match pull {
            None => Ok(Pull::None),
            Some(p) => match p.get_ref().as_str() {
                "none" => Ok(Pull::None),
                "up" => Ok(Pull::Up),
                "down" => Ok(Pull::Down),
                other => Err(self.error(
                    &p.span(),
                    format!("pull must be \"up\", \"down\" or \"none\", found {other:?}"),
                )),
            },
        }
    }

    /// Parses a pin name and checks that the chip has it and that the
    /// firmware may use it.
    fn pin(&self, name: &str, span: &Range<usize>, package: Package, chip: &str) -> Result<PinId> {
        let pin: PinId = name.parse().map_err(|e: String| self.error(span, e))?;
        if let Some(why) = reserved(pin) {
            return Err(self.error(span, format!("{pin} cannot carry a signal: {why}")));
        }
        if let Some(has) = package.lacks(pin) {
            return Err(self.error(
                span,
                format!("{pin} is not bonded out on the {chip}: {has}"),
            ));
        }
        Ok(pin)
    }

    fn claim_pin(
        &self,
        used: &mut HashMap<PinId, PinUse>,
        pin: PinId,
        span: &Range<usize>,
        kind: &'static str,
        name: &str,
    ) -> Result<()> {
        if let Some(u) = used.get(&pin) {
            return Err(self.error(
                span,
                format!(
                    "pin {pin} of {kind} `{name}` is already used by {} `{}` (line {}); a pin carries one signal",
                    u.kind, u.name, u.line
                ),
            ));
        }
        used.insert(
            pin,
            PinUse {
                kind,
                name: name.to_owned(),
                line: self.line(span),
            },
        );
        Ok(())
    }
}
