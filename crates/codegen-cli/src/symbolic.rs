//! `codegen synth --symbolic`: the supervisor of plants ∥ specifications
//! computed on BDDs without building their product (crate
//! `des-symbolic`), written as a guard file (`*.guards.toml`).

use super::error::CliError;
use super::output::{outln, Out};
use super::progress::Spinner;
use super::synth::{ms, peak_rss_kib, SynthArgs};
use super::Outcome;
use des::formats;
use des::Automaton;
use des_symbolic::guard_file::GuardFile;
use des_symbolic::synthesize;
use std::path::{Component as PathPart, Path, PathBuf};
use std::time::Instant;

/// The extension a guard file must have.
const EXTENSION: &str = ".guards.toml";

#[derive(Debug, Default, serde::Serialize)]
struct Timings {
    load: f64,
    model: f64,
    fixpoint: f64,
    guards: f64,
    write: f64,
    total: f64,
}

#[derive(Debug, serde::Serialize)]
struct GuardReport {
    event: String,
    form: String,
    nodes: usize,
    text: String,
}

#[derive(Debug, serde::Serialize)]
struct Report {
    components: usize,
    /// State bits of the encoding (each component's `⌈log2 n⌉`).
    state_bits: usize,
    /// States of plants ∥ specifications reachable without control, as
    /// an exact decimal integer.
    reachable_states: String,
    /// States of the closed loop, exact.
    supervisor_states: String,
    empty: bool,
    /// BDD nodes of the reachable set, the closed loop and all guards.
    bdd_nodes: BddNodes,
    /// Rounds of the controllability/nonblocking loop.
    rounds: usize,
    guards: Vec<GuardReport>,
    output: String,
    milliseconds: Timings,
    /// Peak resident memory of this process (Linux only).
    peak_rss_kib: Option<u64>,
}

#[derive(Debug, serde::Serialize)]
struct BddNodes {
    reachable: usize,
    supervisor: usize,
    guards: usize,
}

/// Every automaton of the files `paths`, each with its file.
fn load(paths: &[PathBuf]) -> Result<Vec<(Automaton, PathBuf)>, CliError> {
    let mut out = Vec::new();
    for path in paths {
        for c in formats::read_file(path)? {
            out.push((c.automaton, path.clone()));
        }
    }
    Ok(out)
}

/// `file` as a path from `dir` (both taken from the working directory
/// when relative), `..` where needed.
fn relative(file: &Path, dir: &Path) -> String {
    let absolute = |p: &Path| {
        let p = if p.as_os_str().is_empty() {
            Path::new(".")
        } else {
            p
        };
        std::path::absolute(p)
            .unwrap_or_else(|_| p.to_path_buf())
            .components()
            .filter(|c| *c != PathPart::CurDir)
            .collect::<PathBuf>()
    };
    let (file, dir) = (absolute(file), absolute(dir));
    let a: Vec<PathPart> = file.components().collect();
    let b: Vec<PathPart> = dir.components().collect();
    let common = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let mut rel = PathBuf::new();
    for _ in common..b.len() {
        rel.push("..");
    }
    for part in &a[common..] {
        rel.push(part);
    }
    rel.to_string_lossy().replace('\\', "/")
}

/// Runs `codegen synth --symbolic`.
pub fn run(args: &SynthArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let start = Instant::now();
    let file_name = args
        .output
        .file_name()
        .map(|n| n.to_string_lossy().into_owned());
    let Some(stem) = file_name.as_deref().and_then(|n| n.strip_suffix(EXTENSION)) else {
        return Err(CliError::Usage(format!(
            "--symbolic writes a guard file: name the output `*{EXTENSION}`, not `{}`",
            args.output.display()
        )));
    };
    let name = args.name.clone().unwrap_or_else(|| stem.to_owned());
    let mut t = Timings::default();
    let spinner = Spinner::new("loading");
    let mark = Instant::now();
    let plants = load(&args.plants)?;
    let specs = load(&args.specs)?;
    t.load = ms(mark);
    let automata = |list: &[(Automaton, PathBuf)]| -> Vec<Automaton> {
        list.iter().map(|(a, _)| a.clone()).collect()
    };
    let (plant_automata, spec_automata) = (automata(&plants), automata(&specs));

    spinner.phase("synthesising on BDDs");
    let synthesis = synthesize(&plant_automata, &spec_automata)?;
    let ms_of = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    t.model = ms_of(synthesis.timings.model);
    t.fixpoint = ms_of(synthesis.timings.fixpoint);
    t.guards = ms_of(synthesis.timings.guards);

    spinner.phase("writing");
    let mark = Instant::now();
    let mut file = GuardFile::new(&name, &synthesis, &plant_automata, &spec_automata);
    let dir = args.output.parent().unwrap_or(Path::new(""));
    for (component, (_, path)) in file.components.iter_mut().zip(plants.iter().chain(&specs)) {
        component.file = Some(relative(path, dir));
    }
    std::fs::write(&args.output, file.to_toml()).map_err(|e| des::Error::io(&args.output, e))?;
    t.write = ms(mark);
    t.total = ms(start);
    drop(spinner);

    let layout = synthesis.model.layout();
    let report = Report {
        components: layout.components.len(),
        state_bits: layout.components.iter().map(|c| c.bits).sum(),
        reachable_states: synthesis.reachable_states().to_string(),
        supervisor_states: synthesis.supervisor_states().to_string(),
        empty: synthesis.is_empty(),
        bdd_nodes: BddNodes {
            reachable: synthesis.fixpoint.reachable.size(),
            supervisor: synthesis.fixpoint.supervisor.size(),
            guards: file.nodes(),
        },
        rounds: synthesis.fixpoint.rounds,
        guards: file
            .guards
            .iter()
            .map(|g| GuardReport {
                event: g.event.clone(),
                form: g.form.clone(),
                nodes: g.nodes.len(),
                text: g.text.clone(),
            })
            .collect(),
        output: args.output.display().to_string(),
        milliseconds: t,
        peak_rss_kib: peak_rss_kib(),
    };
    if json {
        out.json(&report);
        return Ok(Outcome::Holds);
    }
    let m = &report.milliseconds;
    outln!(
        out,
        "model:      {} components, {} state bits ({:.1} ms)",
        report.components,
        report.state_bits,
        m.model
    );
    outln!(
        out,
        "reachable:  {} states, {} BDD nodes",
        report.reachable_states,
        report.bdd_nodes.reachable
    );
    let plural = |n: usize, one: &str, many: &str| {
        if n == 1 {
            format!("1 {one}")
        } else {
            format!("{n} {many}")
        }
    };
    outln!(
        out,
        "supervisor: {} states, {} BDD nodes ({:.1} ms, {})",
        report.supervisor_states,
        report.bdd_nodes.supervisor,
        m.fixpoint,
        plural(report.rounds, "round", "rounds")
    );
    outln!(
        out,
        "guards:     {}, {} in all ({:.1} ms)",
        plural(
            report.guards.len(),
            "controllable event",
            "controllable events"
        ),
        plural(report.bdd_nodes.guards, "node", "nodes"),
        m.guards
    );
    for g in &report.guards {
        outln!(out, "  {}: {}", g.event, g.text);
    }
    if report.empty {
        outln!(
            out,
            "the supervisor is EMPTY: no controllable, nonblocking behaviour of the plant \
             meets the specifications (every guard is false)"
        );
    }
    if let Some(kib) = report.peak_rss_kib {
        outln!(out, "peak memory: {:.1} MB", kib as f64 / 1024.0);
    }
    outln!(out, "wrote {} ({:.1} ms total)", report.output, m.total);
    Ok(Outcome::Holds)
}

#[cfg(test)]
mod tests {
    use super::relative;
    use std::path::Path;

    #[test]
    fn component_files_are_named_from_the_guard_files_directory() {
        assert_eq!(relative(Path::new("m/a.gen"), Path::new("m")), "a.gen");
        assert_eq!(
            relative(Path::new("m/a.gen"), Path::new("out")),
            "../m/a.gen"
        );
        assert_eq!(relative(Path::new("a.gen"), Path::new("")), "a.gen");
        assert_eq!(
            relative(Path::new("/x/y/a.gen"), Path::new("/x/z/w")),
            "../../y/a.gen"
        );
    }
}
