//! The conveyor's PLC program run on a PC: the generated program, the
//! executor's scan cycle, and a scripted light sensor in place of real
//! pins. `cargo run` prints every scan in which something happened.
//!
//! On a board, the loop is the same: sample the input pins into `raw`,
//! call `scan` every `CONFIG.scan_period_ms`, write `outputs` to the
//! output pins (the project's `[board]` section says which pin is which:
//! `conveyor::board`).

#![deny(warnings)]
#![forbid(unsafe_code)]

/// The program `build.rs` generated from `conveyor.plc.toml`: `PROGRAM`,
/// its `Memory` type, `CONFIG`, and the names of the inputs, outputs,
/// events, supervisors and their states (`input::LS`, `event::NAMES`, …).
mod conveyor {
    include!(concat!(env!("OUT_DIR"), "/conveyor.rs"));
}

use conveyor::{event, input, output, Memory, CONFIG, PROGRAM};
use executor::Controller;

/// The light sensor `ls`: (scan, level from that scan on). A part
/// arrives, leaves, and a second one arrives during the 1 s run-on.
const SCRIPT: [(u32, bool); 4] = [(5, true), (30, false), (80, true), (95, false)];

/// Scans to run: long enough for the belt to stop after the last part.
const SCANS: u32 = 220;

fn main() {
    let mut plc = Controller::new(&PROGRAM, Memory::new())
        .expect("the generated Memory is sized for the generated PROGRAM");
    // Names index the images as `usize` (they are `executor::program::Index`).
    let ls = usize::from(input::LS);
    let belt_output = usize::from(output::BELT);
    let mut raw = [false; input::COUNT];
    let mut belt_ran = false;
    println!("scan  time_ms  ls  events          belt");
    for scan in 0..SCANS {
        if let Some(&(_, level)) = SCRIPT.iter().find(|(at, _)| *at == scan) {
            raw[ls] = level;
        }
        let record = plc.scan(scan * CONFIG.scan_period_ms, &raw);
        let belt = record.outputs[belt_output];
        belt_ran |= belt;
        if let Some(fault) = record.fault {
            panic!("scan {scan}: fault {fault:?}");
        }
        if record.executed.is_empty() {
            continue;
        }
        let events: Vec<&str> = record
            .executed
            .iter()
            .map(|&e| event::NAMES[usize::from(e)])
            .collect();
        println!(
            "{scan:>4}  {:>7}  {:>2}  {:<14}  {}",
            record.time_ms,
            u8::from(raw[ls]),
            events.join(" "),
            if belt { "on" } else { "off" }
        );
    }
    // What the project promises: the belt ran while there were parts and
    // has stopped once the last one had gone.
    assert!(belt_ran, "the belt never started");
    assert!(!plc.outputs()[belt_output], "the belt still runs");
}
