//! `cargo xtask size`: flash and static RAM of the board firmware for
//! every model of `budgets.toml`, checked against the board budgets: the
//! Nucleo-F411RE build (STM32F411, `thumbv7em-none-eabihf`) of every model
//! with a board, and the Raspberry Pi Pico build (RP2040, feature `pico`,
//! `thumbv6m-none-eabi`) of every model with a `pico_project`.

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

/// One board firmware build: its name in the table, the cargo features
/// and the target.
pub struct Firmware {
    /// The board's name in the size table.
    pub board: &'static str,
    /// `--features` (with `--no-default-features`).
    pub features: &'static str,
    /// The target triple.
    pub target: &'static str,
}

impl Firmware {
    /// The Nucleo-F411RE (STM32F411, the default feature).
    pub const NUCLEO: Firmware = Firmware {
        board: "nucleo-f411re",
        features: "nucleo-f411re",
        target: "thumbv7em-none-eabihf",
    };
    /// The Raspberry Pi Pico (RP2040).
    pub const PICO: Firmware = Firmware {
        board: "pico",
        features: "pico",
        target: "thumbv6m-none-eabi",
    };

    /// `cargo` with the firmware's package, features and target after
    /// `verb` (`build`, `clippy`), in release mode.
    pub fn cargo(&self, verb: &str) -> Command {
        let mut cmd = cargo();
        cmd.args([
            verb,
            "--release",
            "-p",
            "firmware",
            "--no-default-features",
            "--features",
            self.features,
            "--target",
            self.target,
        ]);
        cmd
    }

    /// Builds the board binary of `project` (table backend): the board's
    /// name, whether it is the Pico, and the ELF's flash and static RAM.
    fn build(&self, project: &str) -> Result<(&'static str, bool, u64, u64)> {
        run(self
            .cargo("build")
            .args(["--bin", "firmware"])
            .env("PLC_PROJECT", project)
            .env("PLC_BACKEND", "table"))?;
        let elf = crate::target_dir().join(format!("{}/release/firmware", self.target));
        let (flash, ram) = llvm_size(&elf)?;
        Ok((self.board, self.features == "pico", flash, ram))
    }
}

pub fn run_task(args: &[String]) -> Result {
    let budgets = Budgets::load()?;
    let mut failures = Vec::new();
    let mut rows = Vec::new();
    for (name, model) in &budgets.models {
        if !args.is_empty() && !args.iter().any(|a| a == name || *a == model.project) {
            continue;
        }
        let mut builds = Vec::new();
        if model.board {
            builds.push(Firmware::NUCLEO.build(&model.project)?);
        }
        if let Some(project) = &model.pico_project {
            builds.push(Firmware::PICO.build(project)?);
        }
        for (board, pico, flash, ram) in builds {
            failures.extend(model.check_board(name, pico, flash, ram));
            let (bf, br) = if pico {
                (model.pico_flash, model.pico_ram)
            } else {
                (model.board_flash, model.board_ram)
            };
            rows.push((name.clone(), board, flash, ram, bf, br));
        }
    }
    println!(
        "\n{:<14} {:<14} {:>10} {:>10} {:>12} {:>12}",
        "model", "board", "flash", "ram", "flash budget", "ram budget"
    );
    let show = |v: Option<u64>| v.map_or("-".to_owned(), |v| v.to_string());
    for (name, board, flash, ram, bf, br) in rows {
        println!(
            "{name:<14} {board:<14} {flash:>10} {ram:>10} {:>12} {:>12}",
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
