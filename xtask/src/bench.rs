//! `cargo xtask bench-faudes`: compose + supcon, ours against libFAUDES,
//! on the same models in the same run, reported as ratios.
//!
//! Models are the shared benchmarks under `models/bench/` or instances of
//! the scalable families, `tline:N`, `ringb:N` and `phil:N`, written by the
//! `families` example of `des` (`target/bench-families/`). Beside the
//! explicit synthesis, `sym ms` is `codegen synth --symbolic` on the same
//! files (one run: its BDD fixpoint and guards, the same supervisor size).
//!
//! Both sides exclude file reading from the timed phases and report the
//! median of `--runs` runs; memory is each process's peak resident set
//! (ours: the whole `codegen synth` process; libFAUDES: the Python process,
//! interpreter included, about 10 MiB of it).

use crate::{cargo, python_with_faudes, root, Result};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

struct Model {
    name: String,
    plants: Vec<PathBuf>,
    specs: Vec<PathBuf>,
}

fn files(dir: &Path, keep: impl Fn(&str) -> bool) -> Result<Vec<PathBuf>> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|e| e == "gen")
                && p.file_stem().and_then(|s| s.to_str()).is_some_and(&keep)
        })
        .collect();
    out.sort();
    Ok(out)
}

fn model(name: &str) -> Result<Model> {
    let dir = root().join("models/bench").join(name);
    let is_spec = |s: &str| s.ends_with("SPEC") || s.ends_with("SP");
    Ok(Model {
        name: name.to_owned(),
        plants: files(&dir, |s| !is_spec(s))?,
        specs: files(&dir, is_spec)?,
    })
}

/// The family instance `FAMILY:N` (`tline`, `ringb`, `phil`), written by
/// `cargo run --release -p des --example families` (its specifications are
/// the `B*` files).
fn family(arg: &str) -> Result<Model> {
    let (family, n) = arg.split_once(':').ok_or("not FAMILY:N")?;
    if !["tline", "ringb", "phil"].contains(&family) {
        return Err(format!("unknown family `{family}` (tline, ringb, phil)"));
    }
    let n: usize = n
        .parse()
        .map_err(|_| format!("`{arg}`: the size is not a number"))?;
    let name = format!("{family}{n}");
    let dir = crate::target_dir().join("bench-families").join(&name);
    crate::run(
        cargo()
            .args([
                "run",
                "--release",
                "-q",
                "-p",
                "des",
                "--example",
                "families",
                "--",
            ])
            .args([family, &n.to_string()])
            .arg(&dir),
    )?;
    Ok(Model {
        name,
        plants: files(&dir, |s| !s.starts_with('B'))?,
        specs: files(&dir, |s| s.starts_with('B'))?,
    })
}

/// Ours on BDDs (`synth --symbolic`, one run): milliseconds (fixpoint and
/// guards), peak KiB, supervisor states.
fn symbolic(m: &Model) -> Result<(f64, f64, f64)> {
    let exe = crate::target_dir().join("release/codegen");
    let out = std::env::temp_dir().join(format!("xtask-bench-{}.guards.toml", m.name));
    let mut cmd = Command::new(&exe);
    cmd.args(["--json", "synth", "--symbolic", "-o"])
        .arg(&out)
        .arg("--plant")
        .args(&m.plants);
    if !m.specs.is_empty() {
        cmd.arg("--spec").args(&m.specs);
    }
    let v = json_of(
        cmd.output().map_err(|e| e.to_string())?,
        "codegen synth --symbolic",
    )?;
    let _ = std::fs::remove_file(out);
    let states: f64 = v["supervisor_states"]
        .as_str()
        .and_then(|s| s.parse().ok())
        .ok_or("missing supervisor_states")?;
    Ok((
        number(&v, &["milliseconds", "fixpoint"])? + number(&v, &["milliseconds", "guards"])?,
        number(&v, &["peak_rss_kib"])?,
        states,
    ))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

fn json_of(output: std::process::Output, what: &str) -> Result<Value> {
    if !output.status.success() {
        return Err(format!(
            "{what} failed: {}",
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    serde_json::from_slice(&output.stdout).map_err(|e| format!("{what}: unreadable output ({e})"))
}

fn number(v: &Value, path: &[&str]) -> Result<f64> {
    let mut cur = v;
    for p in path {
        cur = &cur[p];
    }
    cur.as_f64()
        .ok_or_else(|| format!("missing `{}` in {v}", path.join(".")))
}

/// Ours: milliseconds (median compose + supcon), peak KiB, sup size.
fn ours(m: &Model, runs: usize, names: bool) -> Result<(f64, f64, (f64, f64))> {
    let exe = crate::target_dir().join("release/codegen");
    let out = std::env::temp_dir().join(format!("xtask-bench-{}.gen", m.name));
    let mut totals = Vec::new();
    let mut peak: f64 = 0.0;
    let mut size = (0.0, 0.0);
    for _ in 0..runs {
        let mut cmd = Command::new(&exe);
        cmd.args(["--json", "synth", "-o"])
            .arg(&out)
            .arg("--plant")
            .args(&m.plants);
        if !m.specs.is_empty() {
            cmd.arg("--spec").args(&m.specs);
        }
        if !names {
            cmd.arg("--no-state-names");
        }
        let v = json_of(cmd.output().map_err(|e| e.to_string())?, "codegen synth")?;
        let ms = &["milliseconds"];
        totals.push(
            number(&v, &[ms[0], "compose_plant"])?
                + number(&v, &[ms[0], "compose_spec"])?
                + number(&v, &[ms[0], "supcon"])?,
        );
        peak = peak.max(number(&v, &["peak_rss_kib"])?);
        size = (
            number(&v, &["supervisor", "states"])?,
            number(&v, &["supervisor", "transitions"])?,
        );
    }
    let _ = std::fs::remove_file(out);
    Ok((median(totals), peak, size))
}

/// libFAUDES: milliseconds (median compose + supcon), peak KiB, sup size.
fn theirs(m: &Model, runs: usize, python: &str) -> Result<(f64, f64, (f64, f64))> {
    let mut cmd = Command::new(python);
    cmd.arg(root().join("scripts/faudes_bench.py"))
        .args(["--runs", &runs.to_string(), "--plant"])
        .args(&m.plants);
    if !m.specs.is_empty() {
        cmd.arg("--spec").args(&m.specs);
    }
    let v = json_of(cmd.output().map_err(|e| e.to_string())?, "faudes_bench.py")?;
    let sup = v["supervisor"]
        .as_array()
        .ok_or("missing supervisor size")?;
    Ok((
        number(&v, &["total_ms_median"])?,
        number(&v, &["peak_rss_kib"])?,
        (
            sup[0].as_f64().unwrap_or(-1.0),
            sup[1].as_f64().unwrap_or(-1.0),
        ),
    ))
}

/// Runs the comparison.
pub fn run(args: &[String]) -> Result {
    let mut runs = 3usize;
    let mut models: Vec<Model> = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--runs" => {
                runs = it
                    .next()
                    .and_then(|n| n.parse().ok())
                    .filter(|&n| n > 0)
                    .ok_or("--runs needs a positive number")?
            }
            "smallfactory" | "transferline" | "agv" | "phil5" | "phil8" | "phil10" => {
                models.push(model(a)?);
            }
            family_instance if family_instance.contains(':') => {
                models.push(family(family_instance)?);
            }
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    if models.is_empty() {
        models = ["agv", "phil8", "phil10"]
            .into_iter()
            .map(model)
            .collect::<Result<_>>()?;
    }
    let python = python_with_faudes()?;
    self::run_build()?;
    println!(
        "{:<8} {:>14} {:>10} {:>10} {:>10} {:>10} {:>8} {:>10} {:>10} {:>7}",
        "model",
        "supervisor",
        "ours ms",
        "names ms",
        "sym ms",
        "faudes ms",
        "speedup",
        "ours MiB",
        "faudes MiB",
        "mem"
    );
    for m in &models {
        let name = &m.name;
        let (ms, kib, size) = ours(m, runs, false)?;
        let (named_ms, _, _) = ours(m, runs, true)?;
        let (sms, _, sstates) = symbolic(m)?;
        if sstates != size.0 {
            return Err(format!(
                "{name}: supervisor sizes differ: explicit {} states, symbolic {sstates}",
                size.0
            ));
        }
        let (fms, fkib, fsize) = theirs(m, runs, &python)?;
        if size != fsize {
            return Err(format!(
                "{name}: supervisor sizes differ: ours {size:?}, libFAUDES {fsize:?}"
            ));
        }
        println!(
            "{:<8} {:>14} {:>10.1} {:>10.1} {:>10.1} {:>10.1} {:>7.1}x {:>10.1} {:>10.1} {:>6.2}x",
            name,
            format!("{}/{}", size.0, size.1),
            ms,
            named_ms,
            sms,
            fms,
            fms / ms,
            kib / 1024.0,
            fkib / 1024.0,
            kib / fkib
        );
    }
    println!(
        "(median of {runs} runs; `ours ms` numbers states, `names ms` names them a.b.c, \
         `sym ms` on BDDs (one run); \
         speedup = libFAUDES time / ours unnamed; mem = ours / libFAUDES peak RSS)"
    );
    Ok(())
}

fn run_build() -> Result {
    crate::run(cargo().args([
        "build",
        "--release",
        "-p",
        "codegen-cli",
        "--bin",
        "codegen",
    ]))
}
