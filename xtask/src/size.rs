//! `cargo xtask size`: flash and static RAM of the board firmware for
//! every model of `budgets.toml`, checked against the board budgets: the
//! Nucleo-F411RE build (STM32F411, `thumbv7em-none-eabihf`) of every model
//! with a board, and the Raspberry Pi Pico build (RP2040, feature `pico`,
//! `thumbv6m-none-eabi`) of every model with a `pico_project`. Per
//! Nucleo image also the executor's code (`code_share`: inlined code
//! counted by its source), checked against `executor_code`; and the
//! first image's code by source in full. The press is also built with
//! feature `field-update` for both boards (`nucleo+update`,
//! `pico+update`), reported without budgets.

use crate::budgets::{self, Budgets};
use crate::{cargo, code_share, root, run, Result};
use std::collections::BTreeMap;
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
    /// The Nucleo-F411RE with field update (feature `field-update`:
    /// the slots in flash sectors 6 and 7, the serial link). Built for
    /// [`FIELD_UPDATE_MODEL`] and reported, not checked against a budget.
    pub const NUCLEO_FIELD_UPDATE: Firmware = Firmware {
        board: "nucleo+update",
        features: "nucleo-f411re,field-update",
        target: "thumbv7em-none-eabihf",
    };
    /// The Raspberry Pi Pico (RP2040).
    pub const PICO: Firmware = Firmware {
        board: "pico",
        features: "pico",
        target: "thumbv6m-none-eabi",
    };
    /// The Raspberry Pi Pico with field update (the slots in the flash's
    /// last 256 KiB, the link on UART0). Built for [`FIELD_UPDATE_MODEL`]
    /// and reported, not checked against a budget.
    pub const PICO_FIELD_UPDATE: Firmware = Firmware {
        board: "pico+update",
        features: "pico,field-update",
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

    /// Builds the board binary of `project` (table backend): what
    /// `cargo xtask size` reports of it.
    fn build(&self, project: &str) -> Result<Built> {
        run(self
            .cargo("build")
            .args(["--bin", "firmware"])
            .env("PLC_PROJECT", project)
            .env("PLC_BACKEND", "table"))?;
        let elf = crate::target_dir().join(format!("{}/release/firmware", self.target));
        let (flash, ram) = llvm_size(&elf)?;
        Ok(Built {
            board: self.board,
            pico: self.target == Firmware::PICO.target,
            flash,
            ram,
            code: code_share::by_source(&elf)?,
        })
    }
}

/// The model whose board images are also built with feature
/// `field-update` (their rows have no budgets).
pub const FIELD_UPDATE_MODEL: &str = "press";

/// A board firmware built.
struct Built {
    board: &'static str,
    pico: bool,
    flash: u64,
    ram: u64,
    /// Code bytes by source (`code_share`).
    code: BTreeMap<String, u64>,
}

impl Built {
    /// Code bytes of the executor's functions and of what they inline,
    /// wherever the compiler put them.
    fn executor(&self) -> u64 {
        let key = code_share::EXECUTOR_WITH_INLINED;
        self.code.get(key).copied().unwrap_or(0)
    }

    /// Code bytes whose source lines are the executor's.
    fn executor_lines(&self) -> u64 {
        self.code.get("executor").copied().unwrap_or(0)
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
        let mut field_update = Vec::new();
        if name == FIELD_UPDATE_MODEL {
            if model.board {
                field_update.push(Firmware::NUCLEO_FIELD_UPDATE.build(&model.project)?);
            }
            if let Some(project) = &model.pico_project {
                field_update.push(Firmware::PICO_FIELD_UPDATE.build(project)?);
            }
        }
        for built in builds {
            failures.extend(model.check_board(name, built.pico, built.flash, built.ram));
            let (bf, br, bx) = if built.pico {
                (model.pico_flash, model.pico_ram, None)
            } else {
                let over =
                    budgets::over(name, "executor code", built.executor(), model.executor_code);
                failures.extend(over);
                (model.board_flash, model.board_ram, model.executor_code)
            };
            rows.push((name.clone(), built, bf, br, bx));
        }
        for built in field_update {
            rows.push((name.clone(), built, None, None, None));
        }
    }
    println!(
        "\n{:<14} {:<14} {:>10} {:>10} {:>12} {:>12} {:>9} {:>8} {:>6}",
        "model",
        "board",
        "flash",
        "ram",
        "flash budget",
        "ram budget",
        "executor",
        "budget",
        "lines"
    );
    let show = |v: Option<u64>| v.map_or("-".to_owned(), |v| v.to_string());
    for (name, built, bf, br, bx) in &rows {
        println!(
            "{name:<14} {:<14} {:>10} {:>10} {:>12} {:>12} {:>9} {:>8} {:>6}",
            built.board,
            built.flash,
            built.ram,
            show(*bf),
            show(*br),
            built.executor(),
            show(*bx),
            built.executor_lines()
        );
    }
    println!(
        "(executor: code bytes of the executor's functions and of what they inline, wherever inlined; lines: of those, the bytes of its own source lines)"
    );
    // The first board image in full: where its code comes from.
    if let Some((name, built, ..)) = rows.first() {
        let mut code: Vec<_> = built
            .code
            .iter()
            .filter(|(s, _)| *s != code_share::EXECUTOR_WITH_INLINED)
            .collect();
        code.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        let total: u64 = code.iter().map(|(_, b)| **b).sum();
        let list: Vec<String> = code.iter().map(|(s, b)| format!("{s} {b}")).collect();
        println!(
            "\ncode of {name} on {} by source ({total} bytes of .text; inlined code counted where its source is): {}",
            built.board,
            list.join(", ")
        );
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(format!("size: {}", failures.join("; ")))
    }
}
