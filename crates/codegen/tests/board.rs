//! The `[board]` section of project files: both spellings of a pin load
//! with every option in place, every rule rejects its violation at the
//! offending line, warnings name what the firmware will do, and the pin
//! map comes out as generated Rust and as a wiring table.

use codegen::backend::Backend;
use codegen::board::{board_module, wiring_rows, wiring_table, Direction};
use codegen::emit::generate;
use plc_project::{self as project, EdgeLatch, PinId, Pull};
use std::path::Path;

mod common;
use common::{assert_errors_at_marked_lines, load_err, load_ok, marked_line};

/// Signals of a small station: three inputs (one debounced), two outputs.
const SIGNALS: &str = "[plc]\nname = \"station\"\n\
[inputs]\nstart_pb = {}\npart = { debounce_scans = 3 }\nlimit = {}\n\
[outputs]\nlamp = {}\nvalve = { safe = true }\n\
[events]\ngo = { rising = \"start_pb\", set = \"lamp\" }\nstop = { falling = \"limit\", clear = \"lamp\", set = \"valve\" }\n";

fn pin(s: &str) -> PinId {
    s.parse().unwrap()
}

#[test]
fn both_spellings_of_a_pin_load_with_every_option_in_place() {
    let p = load_ok(&format!(
        "{SIGNALS}[board]\nchip = \"STM32F411RETx\"\n\
outputs = {{ lamp = {{ pin = \"PA5\" }}, valve = {{ pin = \"PB0\", active_low = true }} }}\n\
[board.inputs]\nstart_pb = {{ pin = \"PC13\", pull = \"up\", active_low = true }}\npart = \"pa1\"\n\
[board.inputs.limit]\npin = \"PB4\"\npull = \"down\"\n"
    ));
    let b = p.board.as_ref().expect("a board");
    assert_eq!(b.chip, "STM32F411RETx");
    assert_eq!(b.line, 13);
    let start = b.inputs[0].as_ref().unwrap();
    assert_eq!(
        (start.pin, start.pull, start.active_low, start.line),
        (pin("PC13"), Pull::Up, true, 17)
    );
    assert_eq!(start.edge_latch, EdgeLatch::Latched);
    // A bare string: the pin, defaults for the rest (and any case).
    let part = b.inputs[1].as_ref().unwrap();
    assert_eq!(
        (part.pin, part.pull, part.active_low),
        (pin("PA1"), Pull::None, false)
    );
    assert_eq!(part.edge_latch, EdgeLatch::Debounced);
    let limit = b.inputs[2].as_ref().unwrap();
    assert_eq!(
        (limit.pin, limit.pull, limit.line),
        (pin("PB4"), Pull::Down, 20)
    );
    let lamp = b.outputs[0].as_ref().unwrap();
    assert_eq!((lamp.pin, lamp.active_low), (pin("PA5"), false));
    let valve = b.outputs[1].as_ref().unwrap();
    assert_eq!((valve.pin, valve.active_low), (pin("PB0"), true));
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

#[test]
fn the_chip_defaults_to_the_nucleo_and_a_project_without_board_has_none() {
    let p = load_ok(&format!(
        "{SIGNALS}[board]\ninputs = {{ start_pb = \"PA0\", part = \"PA1\", limit = \"PA4\" }}\noutputs = {{ lamp = \"PA5\", valve = \"PA6\" }}\n"
    ));
    assert_eq!(p.board.unwrap().chip, "STM32F411RETx");
    assert!(load_ok(SIGNALS).board.is_none());
    assert_eq!(board_module(&load_ok(SIGNALS)), "");
    assert_eq!(wiring_table(&load_ok(SIGNALS)), "");
}

/// Each case: a `[board]` section (after [`SIGNALS`]) with the offending
/// line marked `# <-`, and what the error must say.
const ERRORS: &[(&str, &str)] = &[
    // Shape.
    (
        "[board]\nchipset = \"x\" # <-\n",
        "unknown field `chipset`",
    ),
    (
        "[board.inputs]\nstart_pb = { pin = \"PA0\", pul = \"up\" } # <-\n",
        "unknown field `pul`",
    ),
    (
        "[board.outputs]\nlamp = { pin = \"PA5\", pull = \"up\" } # <-\n",
        "unknown field `pull`",
    ),
    (
        "[board.inputs]\nstart_pb = 7 # <-\n",
        "expected a pin name such as \"PA0\" or a table",
    ),
    (
        "[board.inputs]\nstart_pb = { pull = \"up\" } # <-\n",
        "missing field `pin`",
    ),
    // Names.
    (
        "[board.inputs]\nstrat_pb = \"PA0\" # <-\n",
        "unknown input `strat_pb` in [board.inputs]: not declared in [inputs]",
    ),
    (
        "[board.inputs]\nlamp = \"PA0\" # <-\n",
        "`lamp` is an output, map it under [board.outputs]",
    ),
    (
        "[board.outputs]\nhorn = \"PA0\" # <-\n",
        "unknown output `horn` in [board.outputs]",
    ),
    // Pins.
    (
        "[board.inputs]\nstart_pb = \"PF0\" # <-\n",
        "the STM32F411 has no GPIO port F",
    ),
    (
        "[board.inputs]\nstart_pb = \"PA16\" # <-\n",
        "a port has pins 0–15",
    ),
    (
        "[board.inputs]\nstart_pb = \"A0\" # <-\n",
        "`A0` is not a pin name",
    ),
    (
        "[board.inputs]\nstart_pb = \"PA\" # <-\n",
        "`PA` is not a pin name",
    ),
    (
        "[board.inputs]\nstart_pb = \"PH2\" # <-\n",
        "port H of the STM32F411 has only PH0 and PH1",
    ),
    (
        "[board.inputs]\nstart_pb = { pin = \"PA13\", pull = \"up\" } # <-\n",
        "PA13 cannot carry a signal: PA13 is SWDIO of the debug port",
    ),
    (
        "[board.outputs]\nlamp = \"PA14\" # <-\n",
        "PA14 cannot carry a signal: PA14 is SWCLK of the debug port",
    ),
    (
        "[board.outputs]\nlamp = \"PH0\" # <-\n",
        "PH0 is OSC_IN",
    ),
    (
        "[board.outputs]\nlamp = \"PE3\" # <-\n",
        "PE3 is not bonded out on the STM32F411RETx: the 64-pin package has ports A–C, PD2, PH0 and PH1",
    ),
    (
        "[board]\nchip = \"STM32F411CEUx\"\n[board.outputs]\nlamp = \"PB11\" # <-\n",
        "PB11 is not bonded out on the STM32F411CEUx",
    ),
    (
        "[board.inputs]\nstart_pb = \"PA0\"\nlimit = \"pa0\" # <-\n",
        "pin PA0 of input `limit` is already used by input `start_pb` (line 14); a pin carries one signal",
    ),
    (
        "[board.inputs]\nstart_pb = \"PB0\"\n[board.outputs]\nlamp = { pin = \"PB0\" } # <-\n",
        "pin PB0 of output `lamp` is already used by input `start_pb`",
    ),
    (
        "[board.inputs]\nstart_pb = { pin = \"PA0\", pull = \"sideways\" } # <-\n",
        "pull must be \"up\", \"down\" or \"none\", found \"sideways\"",
    ),
    (
        "[board]\nchip = \"STM32F103C8\" # <-\n",
        "chip `STM32F103C8` is not supported: the board firmware is written for the STM32F411 and the RP2040 (probe-rs part names that start so, such as `STM32F411RETx`, the Nucleo-F411RE's; `RP2040`, the Raspberry Pi Pico's)",
    ),
];

#[test]
fn every_board_rule_rejects_its_violation_at_the_offending_line() {
    assert_errors_at_marked_lines(
        ERRORS
            .iter()
            .map(|&(section, expected)| (format!("{SIGNALS}{section}"), expected)),
    );
}

#[test]
fn a_long_scan_period_does_not_fit_the_watchdog() {
    let text = SIGNALS.replace(
        "name = \"station\"\n",
        "name = \"station\"\nscan_period_ms = 9000 # <-\n",
    ) + "[board]\n";
    let msg = load_err(&text);
    assert!(
        msg.contains(&format!("t.plc.toml:{}:", marked_line(&text))),
        "{msg}"
    );
    assert!(msg.contains("scan_period_ms ≤ 8000, found 9000"), "{msg}");
    let ok = SIGNALS.replace(
        "name = \"station\"\n",
        "name = \"station\"\nscan_period_ms = 8000\n",
    );
    assert!(load_ok(&(ok + "[board]\n")).board.is_some());
}

#[test]
fn unwired_signals_are_warnings_at_the_board_header() {
    let p = load_ok(&format!(
        "{SIGNALS}\n[board]\ninputs = {{ start_pb = \"PA0\" }}\noutputs = {{ valve = \"PB0\" }}\n"
    ));
    let warnings: Vec<(u32, &str)> = p
        .warnings
        .iter()
        .map(|w| (w.line, w.message.as_str()))
        .collect();
    assert_eq!(
        warnings,
        [
            (
                14,
                "input `part` has no pin in [board.inputs]: the board firmware reads it as 0"
            ),
            (
                14,
                "input `limit` has no pin in [board.inputs]: the board firmware reads it as 0"
            ),
            (
                14,
                "output `lamp` has no pin in [board.outputs]: the board firmware computes it but drives no pin"
            ),
        ]
    );
    let b = p.board.unwrap();
    assert_eq!(b.inputs[1], None);
    assert_eq!(b.outputs[0], None);
}

#[test]
fn one_port_per_exti_line_the_first_input_wins() {
    let p = load_ok(&format!(
        "{SIGNALS}[board.inputs]\nstart_pb = \"PA4\"\npart = \"PB4\"\nlimit = \"PC4\"\n[board.outputs]\nlamp = \"PA5\"\nvalve = \"PA6\"\n"
    ));
    let b = p.board.as_ref().unwrap();
    let latch: Vec<EdgeLatch> = b
        .inputs
        .iter()
        .map(|i| i.as_ref().unwrap().edge_latch)
        .collect();
    // `part` is debounced, so it does not claim line 4; `limit` on PC4
    // finds it taken by `start_pb` on PA4.
    assert_eq!(
        latch,
        [
            EdgeLatch::Latched,
            EdgeLatch::Debounced,
            EdgeLatch::LineTaken(0)
        ]
    );
    assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    assert_eq!(p.warnings[0].line, 16);
    assert!(
        p.warnings[0]
            .message
            .starts_with("input `limit` (PC4) shares EXTI line 4 with input `start_pb` (PA4)"),
        "{}",
        p.warnings[0].message
    );
}

#[test]
fn nucleo_pins_wired_to_something_else_are_warnings() {
    let p = load_ok(&format!(
        "{SIGNALS}[board.inputs]\nstart_pb = \"PA2\"\npart = \"PC14\"\nlimit = \"PA0\"\n[board.outputs]\nlamp = \"PC13\"\nvalve = \"PA5\"\n"
    ));
    let messages: Vec<&str> = p.warnings.iter().map(|w| w.message.as_str()).collect();
    assert_eq!(messages.len(), 3, "{messages:?}");
    assert!(messages[0].starts_with("input `start_pb`: PA2 carries USART2 to the ST-LINK"));
    assert!(messages[1].starts_with("input `part`: PC14 is wired to the 32.768 kHz crystal"));
    assert!(messages[2].starts_with("output `lamp`: PC13 is the user button B1"));
}

#[test]
fn the_generated_pin_map_compiles_into_the_program_and_reads_back() {
    let text = format!(
        "{SIGNALS}[board]\nchip = \"STM32F411CEUx\"\n[board.inputs]\nstart_pb = {{ pin = \"PA0\", pull = \"up\", active_low = true }}\nlimit = \"PH1\"\n[board.outputs]\nvalve = {{ pin = \"PB12\", active_low = true }}\n"
    );
    let p = load_ok(&text);
    let module = board_module(&p);
    assert!(
        module.starts_with("/// Board wiring of `station`"),
        "{module}"
    );
    for expected in [
        "pub const CHIP: &str = \"STM32F411CEUx\";",
        "pub use boards::{PinId, Pull, SignalPin};",
        "pub const INPUT_PINS: [Option<SignalPin>; super::input::COUNT] = [Some(SignalPin { pin: PinId::new('A', 0), pull: Pull::Up, active_low: true }), None, Some(SignalPin { pin: PinId::new('H', 1), pull: Pull::None, active_low: false })];",
        "pub const OUTPUT_PINS: [Option<SignalPin>; super::output::COUNT] = [None, Some(SignalPin { pin: PinId::new('B', 12), pull: Pull::None, active_low: true })];",
        "pub const EDGE_LATCHED: [bool; super::input::COUNT] = [true, false, true];",
        "/// - 1 `part`: not wired, reads 0",
        "/// - 0 `lamp`: not driven",
    ] {
        assert!(module.contains(expected), "missing `{expected}` in\n{module}");
    }
    // In the whole program, after the name modules it refers to.
    let code = generate(&p, Backend::Table, "test").unwrap().code;
    let board = code.find("pub mod board {").expect("board module");
    assert!(code.find("pub mod input {").unwrap() < board);
    assert!(
        code.contains("pub const EDGE_LATCHED: [bool; super::input::COUNT] = [true, false, true];")
    );
    // No board, no module.
    let plain = generate(&load_ok(SIGNALS), Backend::Table, "test")
        .unwrap()
        .code;
    assert!(!plain.contains("mod board"));
}

#[test]
fn hostile_names_stay_inside_comments_and_literals() {
    let text = "[plc]\nname = \"x\\n}\\nfn evil() {\"\n[inputs]\n\"a`b\\r\\nc\" = {}\n[outputs]\n\"o|p\" = {}\n[events]\ne = { rising = \"a`b\\r\\nc\", set = \"o|p\" }\n[board]\ninputs = { \"a`b\\r\\nc\" = \"PA0\" }\noutputs = { \"o|p\" = \"PA1\" }\n";
    let p = load_ok(text);
    let code = generate(&p, Backend::Table, "test").unwrap().code;
    assert!(
        !code.lines().any(|l| l.trim_start().starts_with("fn evil")),
        "{code}"
    );
    let table = wiring_table(&p);
    assert_eq!(table.lines().count(), 4, "{table}");
    assert!(table.contains("| `a'b  c` | input | PA0 |"), "{table}");
    assert!(table.contains("| `o\\|p` | output | PA1 |"), "{table}");
}

#[test]
fn the_wiring_table_lists_inputs_then_outputs() {
    let p = load_ok(&format!(
        "{SIGNALS}[board.inputs]\nstart_pb = {{ pin = \"PC13\", pull = \"up\", active_low = true }}\npart = \"PA0\"\n[board.outputs]\nvalve = {{ pin = \"PA5\", active_low = true }}\n"
    ));
    assert_eq!(
        wiring_table(&p),
        "| signal | direction | pin | pull | active level | notes |\n\
|---|---|---|---|---|---|\n\
| `start_pb` | input | PC13 | up | low | Nucleo: user button B1 (low while pressed); edge-latched on EXTI13 |\n\
| `part` | input | PA0 | none | high | Nucleo: Arduino A0; not edge-latched: debounced |\n\
| `limit` | input | - | none | - | not wired: reads 0 |\n\
| `lamp` | output | - | - | - | not driven |\n\
| `valve` | output | PA5 | - | low | Nucleo: Arduino D13, user LED LD2; fault mode: 1 (pin low) |\n"
    );
    let rows = wiring_rows(&p).unwrap();
    assert_eq!(rows.len(), 5);
    assert_eq!(rows[0].direction, Direction::Input);
    assert!(rows[0].edge_latched && !rows[1].edge_latched);
    assert_eq!(rows[4].pin.as_deref(), Some("PA5"));
}

#[test]
fn every_seed_project_is_wired() {
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models");
    for seed in ["press", "press7", "motivating", "conveyor", "crane"] {
        let path = models.join(format!("{seed}.plc.toml"));
        let p = project::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let b = p
            .board
            .as_ref()
            .unwrap_or_else(|| panic!("{seed}: no [board]"));
        assert!(
            b.inputs.iter().all(Option::is_some) && b.outputs.iter().all(Option::is_some),
            "{seed}: every signal has a pin"
        );
        assert!(board_module(&p).contains("pub const EDGE_LATCHED"));
        assert!(p.warnings.is_empty(), "{seed}: {:?}", p.warnings);
    }
}

/// The station wired as in the first test, with `edit` applied to the
/// project text.
fn station(edit: impl Fn(String) -> String) -> project::Project {
    load_ok(&edit(format!(
        "{SIGNALS}[board]\nchip = \"STM32F411RETx\"\n\
outputs = {{ lamp = {{ pin = \"PA5\" }}, valve = {{ pin = \"PB0\", active_low = true }} }}\n\
[board.inputs]\nstart_pb = {{ pin = \"PC13\", pull = \"up\", active_low = true }}\npart = \"pa1\"\n\
[board.inputs.limit]\npin = \"PB4\"\npull = \"down\"\n"
    )))
}

#[test]
fn the_wiring_signature_changes_with_every_fact_a_firmware_fixes_and_nothing_else() {
    use codegen::board::{wiring_signature, wiring_text};
    let base = station(|t| t);
    assert_eq!(
        wiring_text(&base),
        "chip STM32F411RETx\nin start_pb PC13 pull-up active low\nin part PA1 no pull active high\n\
in limit PB4 pull-down active high\nout lamp PA5 active high\nout valve PB0 active low\n"
    );
    let signature = wiring_signature(&base);
    // What the image carries itself (events, debouncing, safe levels)
    // is not wiring: an update may change it.
    let behaviour = station(|t| {
        t.replace("debounce_scans = 3", "debounce_scans = 5")
            .replace("set = \"lamp\" }", "set = \"lamp\", clear = \"valve\" }")
    });
    assert_eq!(wiring_signature(&behaviour), signature);
    // Each wiring fact, changed alone, gives another signature.
    let edits: [(&str, &str); 6] = [
        // Every occurrence: declared, used and wired.
        ("start_pb", "begin_pb"),
        ("pin = \"PB4\"", "pin = \"PB5\""),
        ("pull = \"down\"", "pull = \"up\""),
        (
            "valve = { pin = \"PB0\", active_low = true }",
            "valve = { pin = \"PB0\" }",
        ),
        ("lamp = { pin = \"PA5\" }, ", ""),
        ("chip = \"STM32F411RETx\"", "chip = \"STM32F411CEUx\""),
    ];
    for (from, to) in edits {
        let changed = station(|t| t.replace(from, to));
        assert_ne!(
            wiring_signature(&changed),
            signature,
            "`{from}` -> `{to}`:\n{}",
            wiring_text(&changed)
        );
    }
}

#[test]
fn the_press_and_its_update_share_a_wiring_and_the_generated_program_states_it() {
    use codegen::board::wiring_signature;
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let load = |p: &str| project::load(&root.join(p)).expect("the model loads");
    let (press, press7) = (
        load("models/press.plc.toml"),
        load("models/press7.plc.toml"),
    );
    assert_eq!(wiring_signature(&press), wiring_signature(&press7));
    let module = board_module(&press);
    assert!(
        module.contains(&format!(
            "pub const WIRING: u32 = {:#010x};",
            wiring_signature(&press)
        )),
        "{module}"
    );
}
