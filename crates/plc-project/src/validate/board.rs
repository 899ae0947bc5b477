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
//! What the chip has and the firmware may use is the board data's (crate
//! `boards`, one `boards::Chip` per supported chip); this module applies
//! it to the section:
//!
//! - `chip` must name a supported chip (`boards::chip_of`: an STM32F411
//!   or the RP2040, the chips the firmware has a board module for); an
//!   STM32F411's package letter (`R`: 64 pins, `C`: 48 pins) limits the
//!   pins that exist (`boards::Package`).
//! - Every key names a declared input (under `inputs`) or output (under
//!   `outputs`); a pin is `P<port><n>`, ports A–E and H, pins 0–15 (port H:
//!   PH0 and PH1), case-insensitive (`boards::Chip::pin`); on the RP2040
//!   `GP<n>`, GP0–GP29. PA13/PA14 (SWD, which flashes the board and
//!   carries the log) and PH0 (the HSE clock input) are refused, and on
//!   the RP2040 the Pico's GP23, GP24 and GP29 (`boards::Chip::reserved`).
//! - No pin carries two signals; `pull` is `up`, `down` or `none`.
//! - `scan_period_ms` is at most the chip's limit (the watchdog waits 4
//!   periods: [`MAX_BOARD_SCAN_PERIOD_MS`] on the STM32F411, whose
//!   watchdog waits at most 32.7 s; 2000 ms on the RP2040, 8.3 s:
//!   `boards::Watchdog::max_scan_period_ms`).
//! - Warnings: an input without a pin (the firmware reads 0), an output
//!   without a pin (computed, not driven), Nucleo-F411RE pins that are
//!   wired to something else by default (PA2/PA3, PC14/PC15, PC13 as an
//!   output: `boards::DevBoard::note`, for a chip the board carries), and
//!   an input whose EXTI line is taken.
//!
//! **Edge latching** ([`EdgeLatch`]): the firmware counts the changes of an
//! input between two samples with an interrupt on both edges of EXTI line
//! *n* (the pin number, `boards::Chip::exti_line`); more than one change is
//! a lost edge (docs/semantics.md, `LostEdge`). A line listens to one port,
//! so the first input in declaration order with pin number *n* owns it and
//! a later one on another port is not latched (a warning). Debounced inputs
//! (`debounce_scans > 1`) are not latched either: their filter drops short
//! pulses on purpose, so a pulse between samples is not an error there.

use super::super::model::*;
use super::super::parse::{Name, RawBoard, RawInputPin, RawOutputPin, RawPin};
use super::Validator;
use boards::{Chip, Package};
use des::error::Result;
use std::collections::HashMap;
use std::ops::Range;
use toml::Spanned;

pub use boards::{DEFAULT_CHIP, MAX_BOARD_SCAN_PERIOD_MS};

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

        let chip = decl
            .chip
            .as_ref()
            .map_or(DEFAULT_CHIP, |c| c.get_ref().as_str());
        let Some(mcu) = boards::chip_of(chip) else {
            // Only a chip the project names can be unsupported.
            let span = decl.chip.as_ref().map_or(header.clone(), |c| c.span());
            return Err(self.error(&span, unsupported_chip(chip)));
        };
        let chip = chip.to_owned();
        let package = mcu.package(&chip);
        // Warnings about default wiring for a board that carries the chip.
        let dev_board = boards::dev_board_of(&chip);

        if let Some(period) = scan_period {
            let watchdog = &mcu.watchdog;
            let max = watchdog.max_scan_period_ms();
            if *period.get_ref() > i64::from(max) {
                return Err(self.error(
                    &period.span(),
                    format!(
                        "a project with a [board] needs scan_period_ms ≤ {max}, found {}: the board's watchdog restarts it when no scan completes within {} periods, and it cannot wait longer than {}.{} s",
                        period.get_ref(),
                        watchdog.periods,
                        watchdog.max_timeout_ms / 1000,
                        watchdog.max_timeout_ms % 1000 / 100
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
            let pin = self.pin(pin_name, &pin_span, mcu, package, &chip)?;
            self.claim_pin(&mut used, pin, &pin_span, "input", name.get_ref())?;
            if let Some(note) = dev_board.and_then(|b| b.note(pin, false)) {
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
            let pin = self.pin(pin_name, &pin_span, mcu, package, &chip)?;
            self.claim_pin(&mut used, pin, &pin_span, "output", name.get_ref())?;
            if let Some(note) = dev_board.and_then(|b| b.note(pin, true)) {
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
        let mut line_owner: Vec<Option<(usize, PinId)>> = vec![None; usize::from(mcu.exti_lines)];
        for (i, slot) in input_pins.iter_mut().enumerate() {
            let Some(p) = slot else { continue };
            if inputs[i].debounce_scans > 1 {
                p.edge_latch = EdgeLatch::Debounced;
                continue;
            }
            let line = usize::from(mcu.exti_line(p.pin));
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
            mcu,
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
        let Some(p) = pull else {
            return Ok(Pull::None);
        };
        Pull::from_name(p.get_ref()).ok_or_else(|| {
            self.error(
                &p.span(),
                format!(
                    "pull must be \"up\", \"down\" or \"none\", found {:?}",
                    p.get_ref()
                ),
            )
        })
    }

    /// Parses a pin name and checks that the chip has it, that the
    /// package of the part `chip` bonds it out and that the firmware may
    /// use it.
    fn pin(
        &self,
        name: &str,
        span: &Range<usize>,
        mcu: &'static Chip,
        package: Option<&Package>,
        chip: &str,
    ) -> Result<PinId> {
        let pin = mcu.pin(name).map_err(|e| self.error(span, e.to_string()))?;
        if let Some(why) = mcu.reserved(pin) {
            return Err(self.error(span, format!("{pin} cannot carry a signal: {why}")));
        }
        if let Some(package) = package.filter(|p| !p.has(pin)) {
            return Err(self.error(
                span,
                format!("{pin} is not bonded out on the {chip}: {}", package.summary),
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

/// Why `chip` is refused: the chip lines the board data has
/// ([`boards::CHIPS`]) and, as examples, the part of each development board
/// ([`boards::DEV_BOARDS`]).
fn unsupported_chip(chip: &str) -> String {
    let names: Vec<&str> = boards::CHIPS.iter().map(|c| c.name).collect();
    let lines = match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and the {last}", rest.join(", the ")),
        _ => names.join(""),
    };
    let examples: Vec<String> = boards::DEV_BOARDS
        .iter()
        .map(|b| format!("`{}`, the {}'s", b.part, b.name))
        .collect();
    format!(
        "chip `{chip}` is not supported: the board firmware is written for the {lines} (probe-rs part names that start so, such as {})",
        examples.join("; ")
    )
}
