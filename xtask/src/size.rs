//! `cargo xtask size`: flash and static RAM of the board firmware for
//! every model of `budgets.toml`, checked against the board budgets.

use crate::budgets::Budgets;
use crate::{cargo, root, run, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The LLVM tool `name` (`llvm-size`, `llvm-nm`) of the pinned toolchain
/// (component `llvm-tools`).
pub fn llvm_tool(name: &str) -> Result<PathBuf> {
    let out = |args: &[&str]| -> Result<String> {
        let o = Command::new("rustc")
            .args(args)
            .current_dir(root())
            .output()
            .map_err(|e| format!("rustc: {e}"))?;
        Ok(String::from_utf8_lossy(&o.stdout).into_owned())
    };
    let sysroot = out(&["--print", "sysroot"])?;
    let host = out(&["-vV"])?
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_owned))
        .ok_or("rustc -vV names no host")?;
    let tool = Path::new(sysroot.trim()).join(format!("lib/rustlib/{host}/bin/{name}"));
    if tool.exists() {
        Ok(tool)
    } else {
        Err(format!(
            "{} is missing: run `rustup component add llvm-tools`",
            tool.display()
        ))
    }
}

/// Flash (`.text` + `.rodata` + `.data` image, i.e. text + data in
/// Berkeley terms) and static RAM (data + bss) of `elf`.
pub fn llvm_size(elf: &Path) -> Result<(u64, u64)> {
    let out = Command::new(llvm_tool("llvm-size")?)
        .arg(elf)
        .output()
        .map_err(|e| format!("llvm-size: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let numbers: Vec<u64> = text
        .lines()
        .nth(1)
        .ok_or_else(|| format!("llvm-size printed nothing for {}", elf.display()))?
        .split_whitespace()
        .take(3)
        .map(|n| {
            n.parse()
                .map_err(|_| format!("llvm-size: unexpected output `{text}`"))
        })
        .collect::<Result<_>>()?;
    let [text, data, bss] = numbers[..] else {
        return Err(format!("llvm-size: unexpected output `{text}`"));
    };
    Ok((text + data, data + bss))
}

pub fn run_task(args: &[String]) -> Result {
    let budgets = Budgets::load()?;
    let mut failures = Vec::new();
    let mut rows = Vec::new();
    for (name, model) in &budgets.models {
        if !args.is_empty() && !args.iter().any(|a| a == name || *a == model.project) {
            continue;
        }
        if !model.board {
            continue;
        }
        run(cargo()
            .args([
                "build",
                "--release",
                "-p",
                "firmware",
                "--bin",
                "firmware",
                "--target",
                "thumbv7em-none-eabihf",
            ])
            .env("PLC_PROJECT", &model.project)
            .env("PLC_BACKEND", "table"))?;
        let elf = crate::target_dir().join("thumbv7em-none-eabihf/release/firmware");
        let (flash, ram) = llvm_size(&elf)?;
        failures.extend(model.check_board(name, flash, ram));
        rows.push((name.clone(), flash, ram, model.board_flash, model.board_ram));
    }
    println!(
        "\n{:<12} {:>10} {:>10} {:>12} {:>12}",
        "model", "flash", "ram", "flash budget", "ram budget"
    );
    let show = |v: Option<u64>| v.map_or("-".to_owned(), |v| v.to_string());
    for (name, flash, ram, bf, br) in rows {
        println!(
            "{name:<12} {flash:>10} {ram:>10} {:>12} {:>12}",
            show(bf),
            show(br)
        );
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(format!("size: {}", failures.join("; ")))
    }
}
