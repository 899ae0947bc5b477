//! Code bytes of a firmware image by the source they come from: every
//! instruction of `.text` attributed, through the DWARF line table, to the
//! file of its innermost (inlined) source line, and files grouped by
//! crate. So the executor's share counts its code wherever the compiler
//! inlined it (the scan inlined into the board's loop too); core's helpers
//! inlined into executor code count as `core`.

use crate::size::llvm_tool;
use crate::Result;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// The key under which [`by_source`] counts the executor's functions with
/// everything inlined into them.
pub const EXECUTOR_WITH_INLINED: &str = "executor, with what it inlines";

/// Code bytes per source (a workspace crate, a registry crate, `core`,
/// `generated program`, `no line info`), from `llvm-objdump -d -l`; and,
/// under [`EXECUTOR_WITH_INLINED`], the bytes of the executor's functions
/// and of everything inlined into them (core's helpers included), wherever
/// they were inlined.
pub fn by_source(elf: &Path) -> Result<BTreeMap<String, u64>> {
    let out = Command::new(llvm_tool("llvm-objdump")?)
        .args(["-d", "-l", "--no-show-raw-insn", "-j", ".text"])
        .arg("--debug-inlined-funcs=limits-only")
        .arg(elf)
        .output()
        .map_err(|e| format!("llvm-objdump: {e}"))?;
    if !out.status.success() {
        return Err(format!("llvm-objdump failed on {}", elf.display()));
    }
    let listing = String::from_utf8_lossy(&out.stdout);
    let mut bytes = tally(&listing);
    bytes.insert(EXECUTOR_WITH_INLINED.into(), executor_calls(&listing));
    Ok(bytes)
}

/// Whether a mangled symbol is a function of the executor crate (its
/// path, or the type of a trait impl, starts with `executor`).
fn is_executor(symbol: &str) -> bool {
    let Some(path) = symbol.strip_prefix("_ZN") else {
        return symbol.contains("8executor");
    };
    let path = path.trim_start_matches(|c: char| c.is_ascii_digit());
    path.starts_with("executor") || path.starts_with("_$LT$executor..")
}

/// Bytes of instructions inside an executor function or inside code an
/// executor function inlined (the inline markers of
/// `--debug-inlined-funcs=limits-only`).
fn executor_calls(listing: &str) -> u64 {
    let mut total = 0;
    let mut function = false;
    let mut inlined: Vec<&str> = Vec::new();
    let mut last: Option<(u64, bool)> = None;
    for line in listing.lines() {
        if let Some(comment) = line.strip_prefix("; ") {
            if let Some((_, rest)) = comment.split_once(": end of ") {
                if let Some((name, _)) = rest.split_once(" inlined into ") {
                    if let Some(k) = inlined.iter().rposition(|n| *n == name) {
                        inlined.remove(k);
                    }
                }
            } else if let Some((head, _)) = comment.split_once(" inlined into ") {
                if let Some((_, name)) = head.rsplit_once(": ") {
                    inlined.push(name);
                }
            }
            continue;
        }
        if let Some(head) = line.strip_suffix(">:") {
            function = head.split_once(" <").is_some_and(|(_, s)| is_executor(s));
            inlined.clear();
            continue;
        }
        let Some((addr, _)) = line.trim_start().split_once(':') else {
            continue;
        };
        let Ok(addr) = u64::from_str_radix(addr, 16) else {
            continue;
        };
        if let Some((prev, counted)) = last.take() {
            if counted {
                total += addr.saturating_sub(prev).min(8);
            }
        }
        last = Some((addr, function || inlined.iter().any(|n| is_executor(n))));
    }
    total + last.map_or(0, |(_, counted)| if counted { 2 } else { 0 })
}

/// The tally of a disassembly with line numbers: each instruction's
/// bytes (to the next instruction's address) go to the source of the
/// last `; file:line` comment above it within its function.
fn tally(listing: &str) -> BTreeMap<String, u64> {
    let mut bytes: BTreeMap<String, u64> = BTreeMap::new();
    let mut source = String::from("no line info");
    let mut last: Option<(u64, String)> = None;
    for line in listing.lines() {
        if let Some(comment) = line.strip_prefix("; ") {
            if comment.contains(" inlined into ") {
                continue;
            }
            if let Some((file, _)) = comment.rsplit_once(':') {
                if file.starts_with('/') {
                    source = origin(file);
                }
            }
            continue;
        }
        if line.ends_with(">:") {
            // A new function: its first lines may have no line info.
            source = String::from("no line info");
            continue;
        }
        let Some((addr, _)) = line.trim_start().split_once(':') else {
            continue;
        };
        let Ok(addr) = u64::from_str_radix(addr, 16) else {
            continue;
        };
        if let Some((prev, from)) = last.take() {
            *bytes.entry(from).or_default() += addr.saturating_sub(prev).min(8);
        }
        last = Some((addr, source.clone()));
    }
    if let Some((_, from)) = last {
        *bytes.entry(from).or_default() += 2;
    }
    bytes
}

/// The crate a source file belongs to.
fn origin(file: &str) -> String {
    if file.ends_with("/program.rs") && file.contains("/out/") {
        return "generated program".into();
    }
    if let Some((_, rest)) = file.split_once("/crates/") {
        if let Some((name, _)) = rest.split_once('/') {
            return name.into();
        }
    }
    if let Some((_, rest)) = file.split_once("/library/") {
        if let Some((name, _)) = rest.split_once('/') {
            return name.into();
        }
    }
    if let Some((_, rest)) = file.split_once("/registry/src/") {
        // index.crates.io-…/name-1.2.3/src/…
        if let Some(dir) = rest.split('/').nth(1) {
            let name = dir.rsplit_once('-').map_or(dir, |(n, _)| n);
            return name.into();
        }
    }
    "other".into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_executor_share_counts_what_its_functions_inline_and_where_they_are_inlined() {
        let listing = "\
08000d40 <_ZN8firmware4scan3run17h3562ec4290a5d2f6E>:
 8000d40: push\t{r7, lr}
; /work/main/crates/firmware/src/scan.rs:250:9: _ZN8executor10controller23Controller$LT$P$C$M$GT$11step_packed17h0bd5E inlined into _ZN8firmware4scan3run17h3562ec4290a5d2f6E
 8000d42: mov\tr7, sp
; /x/executor/src/controller.rs:250:9: _RNvMs6_NtCs7ldSeZOOJos_4core3numm11to_le_bytes inlined into _ZN8executor10controller23Controller$LT$P$C$M$GT$11step_packed17h0bd5E
 8000d44: str\tr0, [sp]
; /x/executor/src/controller.rs:250:9: end of _RNvMs6_NtCs7ldSeZOOJos_4core3numm11to_le_bytes inlined into _ZN8executor10controller23Controller$LT$P$C$M$GT$11step_packed17h0bd5E
 8000d46: str\tr0, [sp]
; /work/main/crates/firmware/src/scan.rs:250:9: end of _ZN8executor10controller23Controller$LT$P$C$M$GT$11step_packed17h0bd5E inlined into _ZN8firmware4scan3run17h3562ec4290a5d2f6E
 8000d48: bl\t0x8000d50

08000d50 <_ZN60_$LT$executor..table..TableProgram$u20$as$u20$executor..program..Program$GT$5table17h1E>:
 8000d50: bx\tlr

08000d52 <_ZN64_$LT$firmware..program..Tables$u20$as$u20$executor..program..Program$GT$5table17h1E>:
 8000d52: bx\tlr
";
        // The three instructions inside step_packed, then the trait impl of
        // an executor type; not the firmware's own lines, nor the
        // generated program's impl of an executor trait.
        assert_eq!(executor_calls(listing), 2 + 2 + 2 + 2);
    }

    #[test]
    fn instructions_go_to_the_crate_of_their_innermost_line() {
        let listing = "\
080001f0 <EXTI0>:
; EXTI0():
; /work/main/crates/firmware/src/nucleo_f411re/edges.rs:105
 80001f0: push\t{r7, lr}
 80001f2: mov\tr7, sp
; /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/cortex-m-0.7.10/src/register/primask.rs:48
 80001f8: mrs\tr0, primask
; /rustc/59807616e1fa2540724bfbac14d7976d7e4a3860/library/core/src/ptr/mod.rs:2091
 80001fc: ldr\tr2, [r1]
; /work/main/crates/executor/src/controller.rs:72
 80001fe: lsls\tr2, r2, #0x1f
 8000202: bx\tlr

08000204 <other>:
 8000204: bx\tlr
";
        let t = tally(listing);
        assert_eq!(t["firmware"], 8);
        assert_eq!(t["cortex-m"], 4);
        assert_eq!(t["core"], 2);
        assert_eq!(t["executor"], 6);
        assert_eq!(t["no line info"], 2);
    }
}
