//! `cargo xtask guard-bench`: the guard forms measured on the target.
//!
//! Writes the benchmark's data with the host generator
//! (`crates/codegen-cli/examples/guard_bench`: guard collections as the
//! executor's node tables and as Espresso-minimised sums of products,
//! with state vectors) to `target/guard-bench/data.rs`, builds the
//! firmware's `guard-bench` binary on it, runs it in QEMU (mps2-an386,
//! Cortex-M4, `-icount shift=9`) and prints per collection the
//! instructions of one guard evaluation in each form, their bytes and
//! their sizes. Fails when the two forms disagree on any evaluation.

use crate::qemu::{firmware_build, run_elf};
use crate::size::llvm_tool;
use crate::{codegen_cli, run, sysdeps, Result};
use std::path::Path;
use std::process::Command;

/// The target the benchmark runs on.
const TARGET: &str = "thumbv7em-none-eabihf";

/// One collection's line, as `key=value` pairs in the binary's order.
struct Row(Vec<(String, String)>);

impl Row {
    /// A `collection=…` line; `None` for any other.
    fn parse(line: &str) -> Option<Row> {
        line.starts_with("collection=").then(|| {
            Row(line
                .split_whitespace()
                .filter_map(|p| p.split_once('='))
                .map(|(k, v)| (k.to_owned(), v.to_owned()))
                .collect())
        })
    }

    fn get(&self, key: &str) -> &str {
        self.0
            .iter()
            .find(|(k, _)| k == key)
            .map_or("?", |(_, v)| v.as_str())
    }
}

/// Runs the benchmark (no arguments); fails on a disagreement.
pub fn run_task(args: &[String]) -> Result {
    if let Some(arg) = args.first() {
        return Err(format!(
            "guard-bench: unknown argument `{arg}` (it takes none)"
        ));
    }
    let qemu = sysdeps::ensure_qemu()?;
    // The generator minimises with Espresso, whose bindings need libclang.
    sysdeps::ensure_libclang()?;
    let dir = crate::target_dir().join("guard-bench");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let data = dir.join("data.rs");
    // The test profile's build (`cargo test` builds the same crates, with
    // Espresso and the BDD library optimised): 11 s here, 8 s in release,
    // and no second build of its dependencies in `cargo xtask ci`.
    run(codegen_cli(&["--example", "guard_bench"]).arg(&data))?;
    run(firmware_build("guard-bench", "guard-bench", TARGET).env("PLC_GUARD_BENCH", &data))?;
    let elf = crate::target_dir().join(format!("{TARGET}/release/guard-bench"));
    let copy = dir.join("guard-bench.elf");
    std::fs::copy(&elf, &copy).map_err(|e| format!("{}: {e}", copy.display()))?;
    let (status, stdout) = run_elf(&qemu, &copy)?;
    let rows: Vec<Row> = stdout.lines().filter_map(Row::parse).collect();
    let (bdd_code, sop_code) = code_sizes(&copy)?;
    let summary = stdout
        .lines()
        .rev()
        .find(|l| l.starts_with("collections="))
        .ok_or_else(|| format!("{}: no summary line (exit {status})", copy.display()))?;
    let call = summary
        .split_whitespace()
        .find_map(|w| w.strip_prefix("call="))
        .unwrap_or("?");
    print_table(&rows, call, (bdd_code, sop_code));
    if !status.success() || !summary.split_whitespace().any(|w| w == "disagreements=0") {
        return Err(format!(
            "guard-bench: the node tables and the sums of products disagree ({summary}, exit {status})"
        ));
    }
    eprintln!("xtask: guard-bench passed ({summary})");
    Ok(())
}

/// Code bytes of the two evaluators in `elf`: the node-table walk (the
/// benchmark's wrapper and the executor's functions it calls) and the
/// sum of products.
fn code_sizes(elf: &Path) -> Result<(u64, u64)> {
    let out = Command::new(llvm_tool("llvm-nm")?)
        .args(["--print-size", "--demangle"])
        .arg(elf)
        .output()
        .map_err(|e| format!("llvm-nm: {e}"))?;
    if !out.status.success() {
        return Err(format!("llvm-nm {} failed ({})", elf.display(), out.status));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let size_of = |patterns: &[&str]| -> u64 {
        text.lines()
            .filter(|l| patterns.iter().any(|p| l.contains(p)))
            .filter_map(|l| l.split_whitespace().nth(1))
            .filter_map(|s| u64::from_str_radix(s, 16).ok())
            .sum()
    };
    Ok((
        size_of(&[
            "guard_bench::bdd_holds",
            "GuardTable::eval",
            "Guards>::holds",
            "Guards>::table",
        ]),
        size_of(&["guard_bench::sop_holds"]),
    ))
}

/// The figures of `rows`; `call`: the instructions of a timed call that
/// reads no guard; `code`: the evaluators' bytes (node walk, sum of
/// products).
fn print_table(rows: &[Row], call: &str, (bdd_code, sop_code): (u64, u64)) {
    println!(
        "\n{:<18} {:>6} {:>7} {:>7} {:>6} {:>6} {:>7} {:>7} {:>6} {:>7} {:>7} {:>7} {:>7} {:>7}",
        "collection",
        "guards",
        "as_node",
        "vectors",
        "nodes",
        "cubes",
        "bdd_md",
        "bdd_max",
        "sop_md",
        "sop_max",
        "bdd_B",
        "sop_B",
        "evals",
        "disagr"
    );
    for r in rows {
        println!(
            "{:<18} {:>6} {:>7} {:>7} {:>6} {:>6} {:>7} {:>7} {:>6} {:>7} {:>7} {:>7} {:>7} {:>7}",
            r.get("collection"),
            r.get("guards"),
            r.get("as_nodes"),
            format!("{}/{}", r.get("reachable"), r.get("vectors")),
            r.get("nodes"),
            r.get("cubes"),
            r.get("bdd_median"),
            r.get("bdd_max"),
            r.get("sop_median"),
            r.get("sop_max"),
            r.get("bdd_bytes"),
            r.get("sop_bytes"),
            r.get("evals"),
            r.get("disagreements"),
        );
    }
    println!(
        "(instructions per guard evaluation, call included (a call that reads no guard: {call}); bytes: the data of each form; \
         as_node: guards with no sum of products, kept as node tables in the second form; \
         vectors: reachable/all; code: node walk {bdd_code} B, sum of products {sop_code} B)"
    );
}
