//! The `[board]` section for the RP2040 (Raspberry Pi Pico): `GP<n>` pins
//! load, every pin the chip lacks or the firmware keeps is refused at its
//! line with the reason, the watchdog bounds the scan period at 2 s, and
//! the seed model `press_pico` is wired without warnings.

use plc_project::{self as project, EdgeLatch, PinId, Pull};
use std::path::Path;

/// Signals of a small station: two inputs (one debounced), two outputs.
const SIGNALS: &str = "[plc]\nname = \"station\"\n\
[inputs]\nstart_pb = {}\npart = { debounce_scans = 3 }\n\
[outputs]\nlamp = {}\nvalve = {}\n\
[events]\ngo = { rising = \"start_pb\", set = \"lamp\" }\nstop = { falling = \"part\", clear = \"lamp\", set = \"valve\" }\n";

fn load(text: &str) -> Result<project::Project, String> {
    project::from_str(text, Path::new("t.plc.toml")).map_err(|e| e.to_string())
}

/// The 1-based line of `text` marked `# <-`.
fn marked_line(text: &str) -> usize {
    text.lines().position(|l| l.contains("# <-")).unwrap() + 1
}

#[test]
fn gp_pins_load_with_their_options() {
    let p = load(&format!(
        "{SIGNALS}[board]\nchip = \"rp2040\"\n\
inputs = {{ start_pb = {{ pin = \"GP14\", pull = \"up\", active_low = true }}, part = \"gp16\" }}\n\
outputs = {{ lamp = \"GP25\", valve = {{ pin = \"GP2\", active_low = true }} }}\n"
    ))
    .unwrap();
    let b = p.board.as_ref().unwrap();
    assert_eq!(b.mcu, &boards::RP2040);
    let start = b.inputs[0].as_ref().unwrap();
    assert_eq!(
        (start.pin, start.pull, start.active_low, start.edge_latch),
        (PinId::gp(14), Pull::Up, true, EdgeLatch::Latched)
    );
    assert_eq!(start.pin.to_string(), "GP14");
    assert_eq!(b.inputs[1].as_ref().unwrap().pin, PinId::gp(16));
    assert_eq!(b.outputs[0].as_ref().unwrap().pin, PinId::gp(25));
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

#[test]
fn every_rp2040_pin_rule_names_its_line() {
    for (board, expected) in [
        (
            "inputs = { start_pb = \"PA0\" } # <-",
            "`PA0` is not a pin name of the RP2040: expected `GP<number>` such as `GP0` or `GP15` (GP0–GP29)",
        ),
        (
            "outputs = { lamp = \"GP30\" } # <-",
            "`GP30`: the RP2040 has GP0–GP29",
        ),
        (
            "outputs = { lamp = \"GP23\" } # <-",
            "GP23 cannot carry a signal: GP23 drives the power-save input of the Pico's SMPS regulator",
        ),
        (
            "inputs = { start_pb = \"GP24\" } # <-",
            "GP24 cannot carry a signal: GP24 senses VBUS",
        ),
        (
            "inputs = { start_pb = \"GP29\" } # <-",
            "GP29 cannot carry a signal: GP29 measures VSYS/3",
        ),
        (
            "inputs = { start_pb = \"GP5\" }\noutputs = { lamp = \"gp5\" } # <-",
            "pin GP5 of output `lamp` is already used by input `start_pb`",
        ),
    ] {
        let text = format!("{SIGNALS}[board]\nchip = \"RP2040\"\n{board}\n");
        let msg = load(&text).unwrap_err();
        let at = format!("t.plc.toml:{}:", marked_line(&text));
        assert!(
            msg.contains(&at) && msg.contains(expected),
            "expected `{at}` and `{expected}`, got `{msg}`"
        );
    }
}

#[test]
fn an_input_on_the_pico_led_is_a_warning() {
    let p = load(&format!(
        "{SIGNALS}[board]\nchip = \"RP2040\"\ninputs = {{ start_pb = \"GP25\" }}\n"
    ))
    .unwrap();
    assert!(
        p.warnings
            .iter()
            .any(|w| w.message.contains("GP25 drives the Pico's LED")),
        "{:?}",
        p.warnings
    );
}

#[test]
fn the_rp2040_watchdog_bounds_the_scan_period_at_two_seconds() {
    let text = SIGNALS.replace(
        "name = \"station\"\n",
        "name = \"station\"\nscan_period_ms = 2500 # <-\n",
    ) + "[board]\nchip = \"RP2040\"\n";
    let msg = load(&text).unwrap_err();
    assert!(
        msg.contains(&format!("t.plc.toml:{}:", marked_line(&text))),
        "{msg}"
    );
    assert!(
        msg.contains("scan_period_ms ≤ 2000, found 2500") && msg.contains("8.3 s"),
        "{msg}"
    );
    let ok = SIGNALS.replace(
        "name = \"station\"\n",
        "name = \"station\"\nscan_period_ms = 2000\n",
    );
    assert!(load(&(ok + "[board]\nchip = \"RP2040\"\n")).is_ok());
}

#[test]
fn the_pico_press_is_wired() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/press_pico.plc.toml");
    let p = project::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let b = p.board.as_ref().expect("a [board]");
    assert_eq!(b.mcu, &boards::RP2040);
    assert!(b.inputs.iter().all(Option::is_some) && b.outputs.iter().all(Option::is_some));
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}
