//! System packages the build needs beyond the Rust toolchain.
//!
//! The logic backend (`codegen`'s `espresso` feature, which the tests turn
//! on) minimises CMSSM logic with the `espresso-logic` crate, whose build
//! script generates bindings with bindgen and therefore loads libclang and
//! clang's builtin headers. Nothing else needs them (`cargo xtask deps`). On Debian and Ubuntu the task installs them
//! with apt (`libclang1` and the matching `libclang-common-N-dev`) when they
//! are missing; elsewhere it says what to install.

use std::path::Path;
use std::process::Command;

use crate::{run, Result};

/// Makes sure libclang and its builtin headers are present, installing them
/// with apt-get when they are not and apt-get is available.
pub fn ensure_libclang() -> Result {
    if std::env::var_os("LIBCLANG_PATH").is_some() || libclang_present() {
        return Ok(());
    }
    eprintln!("xtask: libclang (needed by espresso-logic's bindgen) is missing; installing it");
    if Command::new("apt-get").arg("--version").output().is_err() {
        return Err(MISSING.into());
    }
    apt_install(&["libclang1"])?;
    // The builtin headers come in a package named after the LLVM major version.
    let major = llvm_major().ok_or(MISSING)?;
    apt_install(&[&format!("libclang-common-{major}-dev")])?;
    if libclang_present() {
        Ok(())
    } else {
        Err(MISSING.into())
    }
}

/// `apt-get update` (once per process) and `apt-get install
/// --no-install-recommends` of `packages`, through sudo when not root.
pub fn apt_install(packages: &[&str]) -> Result {
    use std::sync::atomic::{AtomicBool, Ordering};
    static UPDATED: AtomicBool = AtomicBool::new(false);
    if Command::new("apt-get").arg("--version").output().is_err() {
        return Err(format!(
            "apt-get is not available: install {} by hand",
            packages.join(", ")
        ));
    }
    let apt = |args: &[&str]| {
        let mut cmd = if is_root() {
            Command::new("apt-get")
        } else {
            let mut c = Command::new("sudo");
            c.arg("apt-get");
            c
        };
        cmd.args(args).env("DEBIAN_FRONTEND", "noninteractive");
        run(&mut cmd)
    };
    if !UPDATED.swap(true, Ordering::SeqCst) {
        apt(&["update", "-qq"])?;
    }
    let mut args = vec!["install", "-y", "-qq", "--no-install-recommends"];
    args.extend_from_slice(packages);
    apt(&args)
}

/// Makes sure `qemu-system-arm` is on the PATH, installing Debian's
/// package when it is not.
pub fn ensure_qemu() -> Result<String> {
    let present = || {
        Command::new("qemu-system-arm")
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    };
    if !present() {
        eprintln!("xtask: qemu-system-arm is missing; installing it");
        apt_install(&["qemu-system-arm"]).map_err(|e| {
            format!("{e}\nqemu-system-arm is needed to run the firmware in QEMU (Debian/Ubuntu: `apt-get install --no-install-recommends qemu-system-arm`)")
        })?;
        if !present() {
            return Err("qemu-system-arm still missing after installing it".into());
        }
    }
    Ok("qemu-system-arm".into())
}

/// Makes sure headless Chromium and chromedriver are installed (Debian's
/// `chromium` and `chromium-driver`), installing them with apt when they
/// are not; returns their paths. `CHROMIUM` and `CHROMEDRIVER` override.
pub fn ensure_chromium() -> Result<(String, String)> {
    let find = |var: &str, names: &[&str]| {
        std::env::var(var).ok().or_else(|| {
            names
                .iter()
                .map(|n| format!("/usr/bin/{n}"))
                .find(|p| Path::new(p).exists())
        })
    };
    let chromium = || {
        find(
            "CHROMIUM",
            &["chromium", "chromium-browser", "google-chrome"],
        )
    };
    let driver = || find("CHROMEDRIVER", &["chromedriver"]);
    if chromium().is_none() || driver().is_none() {
        eprintln!("xtask: chromium or chromedriver is missing; installing them");
        // Fonts are only recommended by the package; without them every
        // label of the screenshots would be a row of boxes.
        apt_install(&["chromium", "chromium-driver", "fonts-dejavu-core"]).map_err(|e| {
            format!("{e}\nthe browser test needs Chromium and chromedriver (Debian: `apt-get install chromium chromium-driver`)")
        })?;
    }
    match (chromium(), driver()) {
        (Some(c), Some(d)) => Ok((c, d)),
        _ => Err("chromium or chromedriver still missing after installing them".into()),
    }
}

const MISSING: &str = "libclang is required to build the logic backend (`codegen --features espresso`, which the tests use; espresso-logic runs bindgen): \
     install libclang and clang's builtin headers (Debian/Ubuntu: `apt-get install libclang-dev`) \
     or set LIBCLANG_PATH";

fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.stdout.trim_ascii() == b"0")
}

/// The LLVM major version of the installed `libclang1-N` package.
fn llvm_major() -> Option<String> {
    let out = Command::new("dpkg-query")
        .args(["-W", "-f", "${Package}\\n", "libclang1-*"])
        .output()
        .ok()?;
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|p| p.strip_prefix("libclang1-"))
        .find(|v| v.chars().all(|c| c.is_ascii_digit()) && !v.is_empty())
        .map(str::to_owned)
}

/// True when some LLVM installation has both a libclang shared library and
/// clang's builtin `stddef.h`.
fn libclang_present() -> bool {
    let Ok(entries) = std::fs::read_dir("/usr/lib") else {
        return false;
    };
    entries.flatten().any(|e| {
        let name = e.file_name();
        let name = name.to_string_lossy();
        name.starts_with("llvm-") && has_lib_and_headers(&e.path())
    })
}

fn has_lib_and_headers(llvm: &Path) -> bool {
    let lib = llvm.join("lib");
    let has_lib = std::fs::read_dir(&lib).is_ok_and(|d| {
        d.flatten().any(|e| {
            e.file_name().to_string_lossy().starts_with("libclang")
                && e.file_name().to_string_lossy().contains(".so")
        })
    });
    let has_headers = std::fs::read_dir(lib.join("clang")).is_ok_and(|d| {
        d.flatten()
            .any(|e| e.path().join("include/stddef.h").exists())
    });
    has_lib && has_headers
}
