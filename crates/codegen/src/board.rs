//! A project's `[board]` section as generated Rust for the board firmware
//! ([`board_module`]) and as a wiring table for whoever wires the cabinet
//! ([`wiring_table`], `codegen wiring`).
//!
//! The generated module is plain data (no HAL types), so the firmware
//! decides how to configure pins and the data stays testable on a PC:
//!
//! - `CHIP`: the chip the pins belong to, as probe-rs names it;
//! - `WIRING`: the wiring signature ([`wiring_signature`]), which a field
//!   update's image must carry to run on this firmware;
//! - `Pin` and `Pull`: a GPIO pin and how a signal maps onto its level;
//! - `INPUT_PINS` / `OUTPUT_PINS`: the pin of each signal by index
//!   (`None`: an input reads 0, an output drives nothing);
//! - `EDGE_LATCHED`: the inputs whose changes between two samples an
//!   interrupt on both edges counts (lost-edge detection), see
//!   [`EdgeLatch`].
//!
//! What the words say about the chip and the board (EXTI lines, where a
//! pin is on a Nucleo-F411RE) is the board data's (crate `boards`).

use boards::Chip;
use plc_project::{EdgeLatch, InputPin, OutputPin, PinId, Project, Pull};
use std::fmt::Write;

/// One line of text safe inside a doc comment or a Markdown cell.
fn doc_text(text: &str) -> String {
    text.replace(['\n', '\r'], " ").replace('`', "'")
}

fn pull_variant(pull: Pull) -> &'static str {
    match pull {
        Pull::None => "Pull::None",
        Pull::Up => "Pull::Up",
        Pull::Down => "Pull::Down",
    }
}

/// `Some(SignalPin { … })` for the generated tables.
fn pin_literal(pin: PinId, pull: Pull, active_low: bool) -> String {
    format!(
        "Some(SignalPin {{ pin: PinId::new('{}', {}), pull: {}, active_low: {active_low} }})",
        pin.port,
        pin.number,
        pull_variant(pull)
    )
}

fn pull_words(pull: Pull) -> &'static str {
    match pull {
        Pull::None => "no pull",
        Pull::Up => "pull-up",
        Pull::Down => "pull-down",
    }
}

fn level_words(active_low: bool) -> &'static str {
    if active_low {
        "active low"
    } else {
        "active high"
    }
}

/// Why an input is (not) edge-latched, in words; `mcu` is the chip of
/// the project's board.
fn latch_words(project: &Project, mcu: &Chip, pin: &InputPin) -> String {
    let line = mcu.exti_line(pin.pin);
    match pin.edge_latch {
        EdgeLatch::Latched => format!("edge-latched on {}{line}", mcu.edge_line),
        EdgeLatch::Debounced => "not edge-latched: debounced".to_owned(),
        EdgeLatch::LineTaken(owner) => format!(
            "not edge-latched: {}{line} belongs to `{}`",
            mcu.edge_line,
            doc_text(&project.inputs[owner].name)
        ),
    }
}

/// What a firmware fixes when it is built and a loaded image must agree
/// with, one line each: the board's chip, then every input's name, pin,
/// pull and level, then every output's name, pin and level, in index
/// order (`-` for a signal without a pin, `none` for a project without a
/// `[board]`). Names are identifiers, so a space separates fields.
pub fn wiring_text(project: &Project) -> String {
    let board = project.board.as_ref();
    let mut text = format!("chip {}\n", board.map_or("none", |b| b.chip.as_str()));
    for (i, input) in project.inputs.iter().enumerate() {
        let pin = board.and_then(|b| b.inputs.get(i)).and_then(Option::as_ref);
        let _ = match pin {
            Some(p) => writeln!(
                text,
                "in {} {} {} {}",
                input.name,
                p.pin,
                pull_words(p.pull),
                level_words(p.active_low)
            ),
            None => writeln!(text, "in {} -", input.name),
        };
    }
    for (o, output) in project.outputs.iter().enumerate() {
        let pin = board
            .and_then(|b| b.outputs.get(o))
            .and_then(Option::as_ref);
        let _ = match pin {
            Some(p) => writeln!(
                text,
                "out {} {} {}",
                output.name,
                p.pin,
                level_words(p.active_low)
            ),
            None => writeln!(text, "out {} -", output.name),
        };
    }
    text
}

/// The wiring signature of `project`: the image CRC's algorithm over
/// [`wiring_text`]. A field-update slot header records it
/// (`field_update::header::SlotHeader::wiring`), and a firmware built
/// for one wiring refuses an image made for another: with the same
/// number of signals, its inputs and outputs would mean something else
/// than what the pins carry.
pub fn wiring_signature(project: &Project) -> u32 {
    executor::image::IMAGE_CRC.checksum(wiring_text(project).as_bytes())
}

/// The Rust source of `pub mod board { … }` for `project`, or an empty
/// string when it has no `[board]` section. Names and the chip appear only
/// in doc comments (sanitised) and escaped string literals. The text is
/// laid out by [`crate::emit::generate`] with the rest of the program; it
/// refers to the program's `input::COUNT` and `output::COUNT` as
/// `super::…`.
pub fn board_module(project: &Project) -> String {
    let Some(board) = &project.board else {
        return String::new();
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "/// Board wiring of `{}` (the project's `[board]` section): which pin of\n/// the {} carries each signal. Plain data; the board firmware\n/// configures the pins from it.\n#[allow(dead_code)]\npub mod board {{",
        doc_text(&project.name),
        doc_text(&board.chip)
    );
    let _ = writeln!(
        out,
        "/// The chip the pins belong to, as probe-rs names it.\npub const CHIP: &str = {:?};",
        board.chip
    );
    let _ = writeln!(
        out,
        "/// The wiring signature (`codegen::board::wiring_signature`): a\n/// field-update image runs on this firmware only when its slot header\n/// records the same.\npub const WIRING: u32 = {:#010x};",
        wiring_signature(project)
    );
    // The types are the board data crate's: a generated file is data.
    out.push_str("pub use boards::{PinId, Pull, SignalPin};\n");

    // Inputs.
    let mut doc = String::new();
    let mut items = Vec::new();
    for (i, (input, pin)) in project.inputs.iter().zip(&board.inputs).enumerate() {
        let name = doc_text(&input.name);
        match pin {
            Some(p) => {
                let _ = writeln!(
                    doc,
                    "/// - {i} `{name}`: {}, {}, {}",
                    p.pin,
                    pull_words(p.pull),
                    level_words(p.active_low)
                );
                items.push(pin_literal(p.pin, p.pull, p.active_low));
            }
            None => {
                let _ = writeln!(doc, "/// - {i} `{name}`: not wired, reads 0");
                items.push("None".to_owned());
            }
        }
    }
    let _ = writeln!(
        out,
        "/// Pin of each input, by input index (`None`: not wired, the firmware\n/// reads 0):\n{doc}pub const INPUT_PINS: [Option<SignalPin>; super::input::COUNT] = [{}];",
        items.join(", ")
    );

    // Outputs.
    let mut doc = String::new();
    let mut items = Vec::new();
    for (o, (output, pin)) in project.outputs.iter().zip(&board.outputs).enumerate() {
        let name = doc_text(&output.name);
        match pin {
            Some(OutputPin {
                pin, active_low, ..
            }) => {
                let _ = writeln!(
                    doc,
                    "/// - {o} `{name}`: {pin}, push-pull, {}",
                    level_words(*active_low)
                );
                items.push(pin_literal(*pin, Pull::None, *active_low));
            }
            None => {
                let _ = writeln!(doc, "/// - {o} `{name}`: not driven");
                items.push("None".to_owned());
            }
        }
    }
    let _ = writeln!(
        out,
        "/// Pin of each output, by output index (`None`: computed, not driven):\n{doc}pub const OUTPUT_PINS: [Option<SignalPin>; super::output::COUNT] = [{}];",
        items.join(", ")
    );

    // Edge latching.
    let mut doc = String::new();
    let mut items = Vec::new();
    for (i, (input, pin)) in project.inputs.iter().zip(&board.inputs).enumerate() {
        let latched = pin
            .as_ref()
            .is_some_and(|p| p.edge_latch == EdgeLatch::Latched);
        if let Some(p) = pin {
            let _ = writeln!(
                doc,
                "/// - {i} `{}`: {}",
                doc_text(&input.name),
                latch_words(project, board.mcu, p)
            );
        }
        items.push(latched.to_string());
    }
    let _ = writeln!(
        out,
        "/// Inputs whose changes an interrupt on both edges of EXTI line `pin`\n/// counts between two samples, by input index; more than one change is a\n/// lost edge. One input per line; debounced inputs are not latched:\n{doc}pub const EDGE_LATCHED: [bool; super::input::COUNT] = [{}];",
        items.join(", ")
    );
    out.push_str("}\n");
    out
}

/// Signal direction in the wiring table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Read by the PLC.
    Input,
    /// Driven by the PLC.
    Output,
}

/// One row of the wiring table.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct WiringRow {
    /// Signal name.
    pub signal: String,
    /// Input or output.
    pub direction: Direction,
    /// Pin (`PA0`), `None` when not wired.
    pub pin: Option<String>,
    /// Internal pull (`up`, `down`, `none`; outputs: `none`).
    pub pull: &'static str,
    /// Pin level while the signal is 1: `high` or `low`.
    pub active_level: &'static str,
    /// Whether lost edges of the input are detected.
    pub edge_latched: bool,
    /// What else to know (Nucleo header, edge latching, not wired).
    pub note: String,
}

/// The rows of the wiring table, inputs then outputs in declaration
/// order; `None` when the project has no `[board]` section.
pub fn wiring_rows(project: &Project) -> Option<Vec<WiringRow>> {
    let board = project.board.as_ref()?;
    // Where a pin is on a development board that carries the chip.
    let dev_board = boards::dev_board_of(&board.chip);
    let place = |pin: PinId| {
        let b = dev_board?;
        Some(format!("{}: {}", b.short_name, b.place(pin)?))
    };
    let mut rows = Vec::new();
    for (input, pin) in project.inputs.iter().zip(&board.inputs) {
        rows.push(match pin {
            Some(p) => WiringRow {
                signal: input.name.clone(),
                direction: Direction::Input,
                pin: Some(p.pin.to_string()),
                pull: p.pull.name(),
                active_level: if p.active_low { "low" } else { "high" },
                edge_latched: p.edge_latch == EdgeLatch::Latched,
                note: place(p.pin)
                    .into_iter()
                    .chain([latch_words(project, board.mcu, p)])
                    .collect::<Vec<_>>()
                    .join("; "),
            },
            None => WiringRow {
                signal: input.name.clone(),
                direction: Direction::Input,
                pin: None,
                pull: Pull::None.name(),
                active_level: "high",
                edge_latched: false,
                note: "not wired: reads 0".to_owned(),
            },
        });
    }
    for (output, pin) in project.outputs.iter().zip(&board.outputs) {
        rows.push(WiringRow {
            signal: output.name.clone(),
            direction: Direction::Output,
            pin: pin.as_ref().map(|p| p.pin.to_string()),
            pull: Pull::None.name(),
            active_level: if pin.as_ref().is_some_and(|p| p.active_low) {
                "low"
            } else {
                "high"
            },
            edge_latched: false,
            note: match pin {
                Some(p) => {
                    let pin_level = if output.safe != p.active_low {
                        "high"
                    } else {
                        "low"
                    };
                    place(p.pin)
                        .into_iter()
                        .chain([format!(
                            "fault mode: {} (pin {pin_level})",
                            u8::from(output.safe)
                        )])
                        .collect::<Vec<_>>()
                        .join("; ")
                }
                None => "not driven".to_owned(),
            },
        });
    }
    Some(rows)
}

/// The wiring as a Markdown table (signal, direction, pin, pull, active
/// level, notes), inputs then outputs in declaration order; an empty
/// string when the project has no `[board]` section. "Active level" is
/// the pin level while the signal is 1.
pub fn wiring_table(project: &Project) -> String {
    let Some(rows) = wiring_rows(project) else {
        return String::new();
    };
    let mut out = String::from(
        "| signal | direction | pin | pull | active level | notes |\n|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let direction = match r.direction {
            Direction::Input => "input",
            Direction::Output => "output",
        };
        let pull = if r.direction == Direction::Output {
            "-"
        } else {
            r.pull
        };
        let _ = writeln!(
            out,
            "| `{}` | {direction} | {} | {pull} | {} | {} |",
            doc_text(&r.signal).replace('|', "\\|"),
            r.pin.as_deref().unwrap_or("-"),
            if r.pin.is_some() { r.active_level } else { "-" },
            doc_text(&r.note).replace('|', "\\|"),
        );
    }
    out
}
