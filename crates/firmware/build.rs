//! Generates the PLC program and picks the memory layout.
//!
//! - `PLC_PROJECT`: the project file, relative to the workspace root
//!   (default `models/boiler/boiler.plc.toml`, the boiler).
//! - `PLC_BACKEND`: `table` (default), `logic` (needs the `logic` feature),
//!   or `match` (the baseline).
//! - `PLC_SCENARIO` (feature `qemu`): the recorded scenario to replay
//!   (`host-sim record`); `cargo xtask qemu` sets it.
//! - `PLC_UPDATE_SCENARIO`, `PLC_UPDATE_IMAGE` (feature `qemu-update`):
//!   the loaded project's scenario and slot file (`codegen image`);
//!   `cargo xtask qemu-update` sets them.
//! - `PLC_GUARD_BENCH` (feature `guard-bench`): the data of the guard-form
//!   benchmark (Rust source); `cargo xtask guard-bench` writes and sets it.
//!
//! The program goes to `OUT_DIR/program.rs`. The memory layout (the
//! board's, `stm32f411re.x` or with feature `pico` `rp2040.x`, or QEMU's,
//! from `layout/`) is copied to `OUT_DIR/plc-layout.x`,
//! which the workspace root's `memory.x` includes. With feature
//! `field-update` the board's layout is written from `src/slots/`
//! instead: `FLASH` ends where the first field-update slot begins.
//!
//! Feature `board` (the default): the board binary links defmt's linker
//! script (`-Tdefmt.x`, for that binary only), and for a bare-metal target
//! the project must have a `[board]` section (its pin map).

use std::path::{Path, PathBuf};

/// The field-update slots' addresses, shared with the firmware.
#[allow(dead_code)]
#[path = "src/slots/mod.rs"]
mod slots;

fn env(name: &str) -> Option<String> {
    println!("cargo:rerun-if-env-changed={name}");
    std::env::var(name).ok().filter(|v| !v.is_empty())
}

/// `path` as cargo reads it back from a `cargo:` line; exits with an error
/// for a path that would break or inject a line (`PLC_SCENARIO` and the
/// checkout's directory come from the user).
fn printable(path: &Path) -> &str {
    codegen::build::printable_path(path).unwrap_or_else(|reason| {
        eprintln!("error: {path:?} cannot be named to cargo: {reason}");
        std::process::exit(1);
    })
}

fn copy(from: &Path, to: &Path) {
    println!("cargo:rerun-if-changed={}", printable(from));
    if let Err(e) = std::fs::copy(from, to) {
        eprintln!("error: copying {} to {}: {e}", from.display(), to.display());
        std::process::exit(1);
    }
}

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = manifest.join("../..");
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("set by cargo"));
    let qemu = std::env::var_os("CARGO_FEATURE_QEMU").is_some();
    let guard_bench = std::env::var_os("CARGO_FEATURE_GUARD_BENCH").is_some();
    let board = std::env::var_os("CARGO_FEATURE_BOARD").is_some();
    // Linker scripts only mean something on the bare-metal target; on a
    // host the binaries are stubs (`cargo clippy --workspace`).
    let bare_metal = std::env::var("CARGO_CFG_TARGET_OS").is_ok_and(|os| os == "none");

    let project = env("PLC_PROJECT").unwrap_or_else(|| "models/boiler/boiler.plc.toml".to_owned());
    let backend = match env("PLC_BACKEND").as_deref().unwrap_or("table").parse() {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: PLC_BACKEND: {e}");
            std::process::exit(1);
        }
    };
    if backend == codegen::backend::Backend::Logic
        && std::env::var_os("CARGO_FEATURE_LOGIC").is_none()
    {
        eprintln!(
            "error: PLC_BACKEND=logic needs the firmware's `logic` feature (`--features logic`): \
             the logic backend minimises its equations with Espresso at build time, whose \
             bindings need libclang (Debian/Ubuntu: `apt-get install libclang-dev`)"
        );
        std::process::exit(1);
    }
    let build = codegen::build::Build::new(root.join(&project))
        .backend(backend)
        .file_name("program");
    let build = if board && bare_metal {
        build.require_board()
    } else {
        build
    };
    if let Err(e) = build.generate() {
        eprintln!("error: {e}");
        if matches!(e, codegen::Error::NoBoard { .. }) {
            eprintln!("note: the QEMU harness builds with --no-default-features --features qemu");
        }
        std::process::exit(1);
    }

    // The root memory.x (found first by the linker) includes plc-layout.x.
    let pico = std::env::var_os("CARGO_FEATURE_PICO").is_some();
    // Feature `field-update`: FLASH ends where the board's slot A
    // begins, written from src/slots/.
    let field_update = std::env::var_os("CARGO_FEATURE_FIELD_UPDATE").is_some();
    if field_update && !(qemu || guard_bench) {
        let mut script = String::new();
        if pico {
            slots::rp2040::write_linker_layout(&mut script)
        } else {
            slots::stm32f411re::write_linker_layout(&mut script)
        }
        .expect("formats");
        if let Err(e) = std::fs::write(out.join("plc-layout.x"), script) {
            eprintln!("error: writing plc-layout.x: {e}");
            std::process::exit(1);
        }
        println!("cargo:rerun-if-changed=src/slots");
    } else {
        let layout = manifest.join(if qemu || guard_bench {
            "layout/mps2-an386.x"
        } else if pico {
            "layout/rp2040.x"
        } else {
            "layout/stm32f411re.x"
        });
        copy(&layout, &out.join("plc-layout.x"));
    }
    println!(
        "cargo:rerun-if-changed={}",
        printable(&root.join("memory.x"))
    );
    println!("cargo:rustc-link-search={}", printable(&out));
    if bare_metal {
        println!("cargo:rustc-link-arg-bins=-Tlink.x");
        if board {
            println!("cargo:rustc-link-arg-bin=firmware=-Tdefmt.x");
        }
    }

    if qemu {
        let Some(scenario) = env("PLC_SCENARIO") else {
            eprintln!("error: the qemu harness needs PLC_SCENARIO (a file from `host-sim record`); `cargo xtask qemu` sets it");
            std::process::exit(1);
        };
        copy(&root.join(scenario), &out.join("scenario.bin"));
    }
    if std::env::var_os("CARGO_FEATURE_QEMU_UPDATE").is_some() {
        for (var, file) in [
            ("PLC_UPDATE_SCENARIO", "update-scenario.bin"),
            ("PLC_UPDATE_IMAGE", "update.slot"),
        ] {
            let Some(path) = env(var) else {
                eprintln!(
                    "error: the qemu-update harness needs {var}; `cargo xtask qemu-update` sets it"
                );
                std::process::exit(1);
            };
            copy(&root.join(path), &out.join(file));
        }
    }
    if guard_bench {
        let Some(data) = env("PLC_GUARD_BENCH") else {
            eprintln!("error: the guard-bench binary needs PLC_GUARD_BENCH (its data); `cargo xtask guard-bench` sets it");
            std::process::exit(1);
        };
        copy(&root.join(data), &out.join("guard_bench.rs"));
    }
}
