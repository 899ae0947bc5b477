//! Measures one `Instance::call` of a generated function block with about
//! 2,000 statements (IFs over a constant transition array, assignments,
//! comparisons), the shape of an exported supervisor.
//!
//! `cargo run --release -p iec-st --example call_cost [STATEMENTS]`

use std::fmt::Write;
use std::time::Instant;

use iec_st::{parse, Value};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let statements: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(2_000);
    let (inputs, states, events) = (32, 50, 40);
    let mut src = String::from("FUNCTION_BLOCK big\nVAR_INPUT\n");
    for i in 0..inputs {
        writeln!(src, "    in{i} : BOOL;")?;
    }
    src.push_str("END_VAR\nVAR_OUTPUT\n");
    for i in 0..inputs {
        writeln!(src, "    out{i} : BOOL;")?;
    }
    src.push_str("    fired : UDINT;\nEND_VAR\nVAR CONSTANT\n");
    let table: Vec<String> = (0..states * events)
        .map(|k| {
            let next = (k * 7 + 3) % (states + 10);
            if next >= states {
                "-1".into()
            } else {
                next.to_string()
            }
        })
        .collect();
    writeln!(
        src,
        "    TR : ARRAY [0..{}, 0..{}] OF INT := [{}];",
        states - 1,
        events - 1,
        table.join(", ")
    )?;
    src.push_str("END_VAR\nVAR\n");
    for s in 0..states {
        writeln!(src, "    s{s} : INT;")?;
    }
    src.push_str("END_VAR\n");
    // Each round is one IF (with two assignments inside) and one assignment.
    let mut count = 0;
    let mut k = 0;
    while count < statements {
        let (i, s, e) = (k % inputs, k % states, k % events);
        writeln!(
            src,
            "IF in{i} AND TR[s{s}, {e}] >= 0 THEN s{s} := TR[s{s}, {e}]; fired := fired + 1; END_IF;\nout{i} := s{s} = {} OR in{};",
            k % 7,
            (k + 1) % inputs
        )?;
        count += 4;
        k += 1;
    }
    src.push_str("END_FUNCTION_BLOCK\n");

    let started = Instant::now();
    let file = parse(&src)?;
    let compile = started.elapsed();
    let mut fb = file.instantiate("big")?;
    let slots: Vec<_> = (0..inputs)
        .map(|i| fb.slot(&format!("in{i}")))
        .collect::<Result<_, _>>()?;
    let calls = 20_000u32;
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let started = Instant::now();
    for _ in 0..calls {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        for (bit, slot) in slots.iter().enumerate() {
            fb.set_slot(*slot, Value::Bool(seed >> bit & 1 != 0))?;
        }
        fb.call()?;
    }
    let per_call = started.elapsed() / calls;
    println!(
        "{count} statements ({} lines): parse+compile {compile:?}, one call (incl. 32 input writes) {per_call:?}, fired {}",
        src.lines().count(),
        fb.get("fired")?
    );
    Ok(())
}
