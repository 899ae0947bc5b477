//! `cargo xtask reduction [MODEL…]`: the supervisors of models of
//! `budgets.toml` on the target in full, reduced and localized form.
//!
//! For each model whose project synthesises its supervisor
//! (`synthesize = { … }`), two variants are written to
//! `target/reduction/`: the project with `reduce = true` and with
//! `localize = true` in every such `synthesize` (model paths made
//! absolute; `minimize` dropped for `localize`, which minimises each
//! local controller itself), as a user would write them. Each form
//! (the project as it is, then the two variants) is measured as
//! `cargo xtask qemu` measures a model: `codegen gen --stats` (the
//! automata, their tables, the image under the CRC), a scenario recorded
//! by host-sim (3,000 guided random scans, seed 1; the forms have the
//! same closed loop, so the same inputs), the table backend's QEMU
//! harness (flash without the scenario, instructions per scan, zero
//! mismatches against host-sim). A form the project loader refuses is
//! reported with its reason; a model whose supervisors are files with no
//! plant is reported as such (reduction needs the plant). No budgets are
//! checked: this is a report, not a CI gate (41 s with current release
//! builds, 3 to 4 minutes after a change; `qemu` already holds the AGV's
//! reduced and localized projects to budgets).

use crate::budgets::{Budgets, ModelBudget};
use crate::qemu::{self, Figures};
use crate::{codegen_cli, root, sysdeps, target_dir, Result};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use toml::{Table, Value};

/// The models measured when none is named: the AGV, the boiler's
/// monolithic supervisor, the seed projects (synthesised or not), the
/// breakdown cell (partial observation) and the modular boiler.
const DEFAULT_MODELS: [&str; 9] = [
    "agv",
    "boiler_mono",
    "conveyor",
    "module",
    "breakdown",
    "press",
    "crane",
    "motivating",
    "boiler",
];

/// The three forms of a model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Form {
    Full,
    Reduced,
    Localized,
}

impl Form {
    fn label(self) -> &'static str {
        match self {
            Form::Full => "full",
            Form::Reduced => "reduced",
            Form::Localized => "localized",
        }
    }
}

/// What `codegen gen --stats` says of a project.
#[derive(Debug, Default)]
struct Stats {
    /// Each automaton run: name, states.
    automata: Vec<(String, u64)>,
    /// Bytes of the transition tables.
    tables: u64,
    /// Bytes of the image under the CRC.
    image: u64,
}

/// One row of the report.
enum Row {
    /// A form measured.
    Measured(Stats, Figures),
    /// A form not measured, and why.
    Not(String),
}

pub fn run_task(args: &[String]) -> Result {
    let budgets = Budgets::load()?;
    let names: Vec<String> = if args.is_empty() {
        DEFAULT_MODELS.iter().map(|m| m.to_string()).collect()
    } else {
        args.to_vec()
    };
    let models = names
        .iter()
        .map(|n| {
            budgets
                .models
                .get(n)
                .map(|m| (n.clone(), m.clone()))
                .ok_or_else(|| format!("reduction: no model `{n}` in budgets.toml"))
        })
        .collect::<Result<Vec<_>>>()?;
    let qemu = sysdeps::ensure_qemu()?;
    let dir = target_dir().join("reduction");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut report = Vec::new();
    for (name, model) in &models {
        let path = root().join(&model.project);
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let project: Table = text
            .parse()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        if !synthesises(&project) {
            report.push((
                name.clone(),
                Form::Full,
                Row::Not(
                    "supervisor files with no plant: reduction needs the plant, not measured"
                        .into(),
                ),
            ));
            continue;
        }
        for form in [Form::Full, Form::Reduced, Form::Localized] {
            let file = match form {
                Form::Full => model.project.clone(),
                _ => {
                    let file = dir.join(format!("{name}_{}.plc.toml", form.label()));
                    let variant = variant(&project, &path, form)?;
                    std::fs::write(&file, variant)
                        .map_err(|e| format!("{}: {e}", file.display()))?;
                    file.display().to_string()
                }
            };
            let row = match gen_stats(&file)? {
                Err(refusal) => Row::Not(refusal),
                Ok(stats) => Row::Measured(stats, replay(&qemu, name, form, &file, &dir)?),
            };
            report.push((name.clone(), form, row));
        }
    }
    print_report(&report);
    let failed: Vec<String> = report
        .iter()
        .filter_map(|(name, form, row)| match row {
            Row::Measured(_, f) if f.mismatches > 0 => Some(format!(
                "{name} ({}): {} mismatches",
                form.label(),
                f.mismatches
            )),
            _ => None,
        })
        .collect();
    if failed.is_empty() {
        Ok(())
    } else {
        Err(format!("reduction: {}", failed.join("; ")))
    }
}

/// Whether a `[[supervisor]]` of `project` is synthesised.
fn synthesises(project: &Table) -> bool {
    supervisors(project).any(|s| s.contains_key("synthesize"))
}

fn supervisors(project: &Table) -> impl Iterator<Item = &Table> {
    project
        .get("supervisor")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(Value::as_table)
}

/// `project` (read from `path`) with every synthesised supervisor in
/// `form` and every model path absolute, as TOML text.
fn variant(project: &Table, path: &Path, form: Form) -> Result<String> {
    let base = path.parent().unwrap_or(Path::new("."));
    let mut project = project.clone();
    let absolute = |v: &mut Value| {
        let fix = |s: &mut Value| {
            if let Value::String(p) = s {
                *p = base.join(&*p).display().to_string();
            }
        };
        match v {
            Value::Array(items) => items.iter_mut().for_each(fix),
            other => fix(other),
        }
    };
    for section in ["supervisor", "net"] {
        let Some(Value::Array(entries)) = project.get_mut(section) else {
            continue;
        };
        for entry in entries.iter_mut().filter_map(Value::as_table_mut) {
            for key in ["file", "guards", "constraints", "control"] {
                if let Some(v) = entry.get_mut(key) {
                    absolute(v);
                }
            }
            let Some(Value::Table(synth)) = entry.get_mut("synthesize") else {
                continue;
            };
            for key in ["plants", "specs"] {
                if let Some(v) = synth.get_mut(key) {
                    absolute(v);
                }
            }
            match form {
                Form::Full => {}
                Form::Reduced => {
                    synth.insert("reduce".into(), Value::Boolean(true));
                }
                Form::Localized => {
                    synth.remove("minimize");
                    synth.insert("localize".into(), Value::Boolean(true));
                }
            }
        }
    }
    let text = toml::to_string(&project).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(format!(
        "# {} of {} (`cargo xtask reduction`)\n{text}",
        form.label(),
        path.display()
    ))
}

/// `codegen gen --stats` of `file`: its figures, or the loader's refusal.
fn gen_stats(file: &str) -> Result<std::result::Result<Stats, String>> {
    let mut cmd = codegen_cli(&["--release"]);
    cmd.args(["gen", "--stats", file]).stdin(Stdio::null());
    eprintln!("$ codegen gen --stats {file}");
    let out = cmd
        .output()
        .map_err(|e| format!("cannot run codegen: {e}"))?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        let reason = stderr
            .lines()
            .find(|l| l.starts_with("error"))
            .unwrap_or(stderr.trim())
            .replace(&format!("{}/", root().display()), "");
        eprintln!("  refused: {reason}");
        return Ok(Err(reason));
    }
    Ok(Ok(parse_stats(&stdout)))
}

/// The supervisor rows (name, states, events, layout, bytes, …), the
/// total and the image line of `codegen gen --stats`.
fn parse_stats(text: &str) -> Stats {
    let mut stats = Stats::default();
    let mut total = None;
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["total", bytes, ..] => total = bytes.parse().ok(),
            ["image:", bytes, ..] => stats.image = bytes.parse().unwrap_or(0),
            [name, states, _events, _layout, bytes, ..] => {
                if let (Ok(states), Ok(bytes)) = (states.parse(), bytes.parse::<u64>()) {
                    stats.automata.push((name.to_string(), states));
                    stats.tables += bytes;
                }
            }
            _ => {}
        }
    }
    if let Some(total) = total {
        stats.tables = total;
    }
    stats
}

/// The table backend's harness of `file` in QEMU, on its own recorded
/// scenario.
fn replay(qemu_bin: &str, name: &str, form: Form, file: &str, dir: &Path) -> Result<Figures> {
    let tag = format!("{name}_{}", form.label());
    let scenario: PathBuf = qemu::record(&tag, file, None, dir)?;
    let budget = ModelBudget::unbounded(file);
    let elf = qemu::build(file, "table", &scenario, &budget, "thumbv7em-none-eabihf")?;
    let copy = dir.join(format!("{tag}-table.elf"));
    std::fs::copy(&elf, &copy).map_err(|e| format!("{}: {e}", copy.display()))?;
    qemu::run_qemu(qemu_bin, &copy)
}

/// "6 (521; largest 491)": the automata run and their states.
fn automata(stats: &Stats) -> String {
    let states: u64 = stats.automata.iter().map(|(_, s)| s).sum();
    let largest = stats.automata.iter().map(|(_, s)| *s).max().unwrap_or(0);
    if stats.automata.len() == 1 {
        format!("1 ({states})")
    } else {
        format!("{} ({states}; largest {largest})", stats.automata.len())
    }
}

fn print_report(report: &[(String, Form, Row)]) {
    println!(
        "\n| model | form | automata (states) | tables | image under the CRC | harness flash | instructions median / p99 / max | mismatches |"
    );
    println!("|---|---|---|---:|---:|---:|---|---:|");
    for (name, form, row) in report {
        match row {
            Row::Measured(stats, f) => println!(
                "| {name} | {} | {} | {} B | {} B | {} B | {} / {} / {} | {} of {} |",
                form.label(),
                automata(stats),
                stats.tables,
                stats.image,
                f.flash,
                f.median,
                f.p99,
                f.max,
                f.mismatches,
                f.scans
            ),
            Row::Not(why) => println!(
                "| {name} | {} | {} | | | | | |",
                form.label(),
                why.replace('|', "\\|")
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PROJECT: &str = r#"[plc]
name = "p"

[events]
zeta = { rising = "a" }
alpha = { controllable = true }

[[supervisor]]
name = "s"
synthesize = { plants = ["plant/*.toml"], specs = "spec.toml", minimize = true }

[[supervisor]]
name = "f"
file = "f.toml"
"#;

    /// A variant keeps the events in their (priority) order, makes every
    /// model path absolute, and asks for its form (without `minimize`
    /// when localized).
    #[test]
    fn a_variant_asks_for_its_form_with_absolute_paths_in_the_same_order() {
        let table: Table = PROJECT.parse().unwrap();
        assert!(synthesises(&table));
        let path = Path::new("/w/models/p.plc.toml");
        for form in [Form::Reduced, Form::Localized] {
            let text = variant(&table, path, form).unwrap();
            let back: Table = text.parse().unwrap();
            let events: Vec<&String> = back["events"].as_table().unwrap().keys().collect();
            assert_eq!(events, ["zeta", "alpha"]);
            let sups: Vec<&Table> = supervisors(&back).collect();
            let synth = sups[0]["synthesize"].as_table().unwrap();
            assert_eq!(
                synth["plants"].as_array().unwrap()[0].as_str(),
                Some("/w/models/plant/*.toml")
            );
            assert_eq!(synth["specs"].as_str(), Some("/w/models/spec.toml"));
            assert_eq!(sups[1]["file"].as_str(), Some("/w/models/f.toml"));
            let (key, minimize) = match form {
                Form::Reduced => ("reduce", Some(true)),
                _ => ("localize", None),
            };
            assert_eq!(synth[key].as_bool(), Some(true), "{text}");
            assert_eq!(synth.get("minimize").and_then(Value::as_bool), minimize);
        }
        let files: Table = "[[supervisor]]\nfile = \"s.toml\"\n".parse().unwrap();
        assert!(!synthesises(&files));
    }

    #[test]
    fn the_stats_are_read_from_codegen_gen() {
        let text = "p.plc.toml:
  supervisor                states  events  layout      bytes      naive   ratio
  agv.AGV1                       4       4   dense          8         32   4.00x
  agv                          491      26  sparse       6316      25532   4.04x
  total                                                  6372      25828   4.05x
  (naive: one u16 per state × event pair)
  image: 8520 bytes under the CRC; background check 64 bytes per scan
";
        let stats = parse_stats(text);
        assert_eq!(
            stats.automata,
            [("agv.AGV1".to_owned(), 4), ("agv".to_owned(), 491)]
        );
        assert_eq!((stats.tables, stats.image), (6372, 8520));
        assert_eq!(automata(&stats), "2 (495; largest 491)");
    }
}
