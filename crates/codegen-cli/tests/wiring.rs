//! `codegen wiring` as a user runs it.

use codegen::board::wiring_table;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// What `codegen wiring PROJECT` prints (it must succeed).
fn wiring_of(project: &Path) -> String {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_codegen"))
        .arg("wiring")
        .arg(project)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    String::from_utf8(out.stdout).unwrap()
}

/// `codegen wiring`: the table on stdout, JSON rows with `--json`, and a
/// usage error (exit code 2) for a project without `[board]`.
#[test]
fn the_wiring_verb_prints_the_table_or_json() {
    let codegen = env!("CARGO_BIN_EXE_codegen");
    let press = root().join("models/press.plc.toml");
    let text = wiring_of(&press);
    assert!(text.starts_with("| signal | direction | pin | pull | active level | notes |\n"));
    assert!(
        text.contains("| `auto_pb` | input | PC13 | up | low |"),
        "{text}"
    );
    assert_eq!(text, wiring_table(&plc_project::load(&press).unwrap()));

    let out = std::process::Command::new(codegen)
        .args(["--json", "wiring"])
        .arg(&press)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["chip"], "STM32F411RETx");
    assert_eq!(json["project"], "stamping-press");
    let signature = codegen::board::wiring_signature(&plc_project::load(&press).unwrap());
    assert_eq!(json["signature"], format!("{signature:#010x}"));
    let first = &json["signals"][0];
    assert_eq!(first["signal"], "auto_pb");
    assert_eq!(first["direction"], "input");
    assert_eq!(first["pin"], "PC13");
    assert_eq!(first["active_level"], "low");
    assert_eq!(first["edge_latched"], true);

    let out = std::process::Command::new(codegen)
        .arg("wiring")
        .arg(root().join("crates/codegen/tests/fixtures/project/press.plc.toml"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("has no [board] section"));
}

/// The press wired to a Raspberry Pi Pico: `GP<n>` pins, the Pico's
/// header pin of each, one edge interrupt per GPIO.
#[test]
fn the_pico_press_is_wired_by_header_pin() {
    let press = root().join("models/press_pico.plc.toml");
    let text = wiring_of(&press);
    assert_eq!(text, wiring_table(&plc_project::load(&press).unwrap()));
    for row in [
        "| `auto_pb` | input | GP14 | up | low | Pico: pin 19; edge-latched on GPIO14 |",
        "| `part` | input | GP16 | none | high | Pico: pin 21; not edge-latched: debounced |",
        "| `auto_lamp` | output | GP25 | - | high | Pico: user LED; fault mode: 0 (pin low) |",
    ] {
        assert!(text.contains(row), "{row}\n{text}");
    }
}
