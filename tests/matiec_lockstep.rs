//! The exported programs compiled by matiec, the IEC 61131-3 compiler of
//! OpenPLC's runtime and of the Beremiz IDE, then by gcc, and run in
//! lockstep with host-sim's executor on the same inputs.
//!
//! Three texts per project, each compiled by `iec2c` and gcc into a
//! harness that reads one scan's inputs per line and prints what the
//! scan left:
//! - `codegen st`: the controller block called directly, `NOW_MS` from
//!   the rows (clock jumps, the 2^32 wrap);
//! - `codegen st --configuration`: the configuration run as OpenPLC's
//!   runtime runs it (`config_init__`, then `config_run__` once per task
//!   tick), inputs and outputs at their located addresses, the program on
//!   its own clock;
//! - `codegen plcopen`: the XML turned back into ST as an IDE importing
//!   it does (`common/plcopen_st.rs`), then run as the configuration.
//!
//! Every scan compares every output (the block's and, run as a task, the
//! located ones), every supervisor state (a net's marking packed as the
//! executor packs it), the executed and unexpected events in order, the
//! fault and its cause, and the fault and ignore counters.
//!
//! Needs a matiec build: `MATIEC_DIR` names it (`cargo xtask matiec`
//! builds one from `../shared/tools/matiec` and runs these tests), and
//! gcc. Ignored in a plain `cargo test`.

#[path = "common/lockstep.rs"]
mod lockstep;
#[path = "common/plcopen_st.rs"]
mod plcopen_st;

use host_sim::inputs::InputRow;
use host_sim::random_inputs::guided_inputs;
use iec_export::{self as iec, IoMap, Names};
use lockstep::{blind_inputs, compare, load, on_grid, pack_states, shifted, Coverage, Observed};
use plc_project::Project;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// The matiec build to compile with.
fn matiec_dir() -> PathBuf {
    let dir = std::env::var_os("MATIEC_DIR").map(PathBuf::from).expect(
        "MATIEC_DIR must name a matiec build (`cargo xtask matiec` builds one and runs these tests)",
    );
    assert!(
        dir.join("iec2c").is_file(),
        "{}: no iec2c here",
        dir.display()
    );
    dir
}

/// How the compiled program is driven.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Drive {
    /// The controller block called directly, `NOW_MS` from the rows.
    Block,
    /// The configuration's resource run tick by tick, as OpenPLC's
    /// runtime does; the program keeps its own clock.
    Task,
}

/// A program compiled by matiec and gcc, ready to run.
struct Compiled {
    harness: PathBuf,
    _dir: tempfile::TempDir,
}

/// Compiles `text` with `iec2c` and its C with gcc into a harness for
/// `drive`; `Err` holds what the compiler said.
fn compile(project: &Project, names: &Names, text: &str, drive: Drive) -> Result<Compiled, String> {
    let matiec = matiec_dir();
    let dir = tempfile::tempdir().expect("a temporary directory");
    let st = dir.path().join("program.st");
    std::fs::write(&st, text).expect("write the ST");
    let out = dir.path().join("out");
    std::fs::create_dir(&out).expect("out");
    let iec2c = Command::new(matiec.join("iec2c"))
        .arg("-I")
        .arg(matiec.join("lib"))
        .arg("-T")
        .arg(&out)
        .arg(&st)
        .output()
        .expect("iec2c runs");
    if !iec2c.status.success() {
        return Err(format!(
            "iec2c refused it:\n{}{}",
            String::from_utf8_lossy(&iec2c.stdout),
            String::from_utf8_lossy(&iec2c.stderr)
        ));
    }
    let harness_c = dir.path().join("harness.c");
    std::fs::write(&harness_c, harness(project, names, drive)).expect("write the harness");
    let harness = dir.path().join("harness");
    let mut gcc = Command::new("gcc");
    gcc.args(["-O1", "-w", "-I"])
        .arg(matiec.join("lib/C"))
        .arg("-I")
        .arg(&out)
        .arg(&harness_c);
    if drive == Drive::Task {
        // The configuration and resource files (the resource includes
        // POUS.c), as OpenPLC's runtime links them.
        let mut sources: Vec<PathBuf> = std::fs::read_dir(&out)
            .expect("out")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "c") && !p.ends_with("POUS.c"))
            .collect();
        sources.sort();
        assert_eq!(
            sources.len(),
            2,
            "a configuration and a resource: {sources:?}"
        );
        gcc.args(&sources);
    }
    let gcc = gcc.arg("-o").arg(&harness).output().expect("gcc runs");
    if !gcc.status.success() {
        return Err(format!(
            "gcc refused matiec's C:\n{}",
            String::from_utf8_lossy(&gcc.stderr)
        ));
    }
    Ok(Compiled { harness, _dir: dir })
}

/// The C name of a located variable (`%IX0.3` is `__IX0_3`).
fn located(address: &str) -> String {
    format!("__{}", address.trim_start_matches('%').replace('.', "_"))
}

/// Sizes of the block's event lists (as the export declares them).
fn list_sizes(project: &Project) -> (usize, usize) {
    let uncontrollable = project.events.iter().filter(|e| !e.controllable).count();
    (project.events.len().max(1), uncontrollable.max(1))
}

/// The C driver: per input line (`NOW_MS` then a 0/1 per input for the
/// block; the 0/1s only for a task) one scan, then one line of what it
/// left (see `parse`).
fn harness(project: &Project, names: &Names, drive: Drive) -> String {
    let up = |s: &str| s.to_ascii_uppercase();
    let (inputs, outputs) = IoMap::sequential().addresses(project).expect("addresses");
    let mut c = String::from(
        "#include <stdio.h>\n#include <stdlib.h>\n#include \"iec_std_lib.h\"\n\
         #include \"accessor.h\"\n#include \"POUS.h\"\n\
         IEC_TIME __CURRENT_TIME;\nIEC_BOOL __DEBUG;\n\
         #define __LOCATED_VAR(type, name, ...) type __##name; type *name = &__##name;\n\
         #include \"LOCATED_VARIABLES.h\"\n#undef __LOCATED_VAR\n",
    );
    let ctrl = up(&names.controller);
    match drive {
        Drive::Block => {
            let _ = writeln!(c, "#include \"POUS.c\"\nstatic {ctrl} fb;\n#define FB fb");
        }
        Drive::Task => {
            let [_, resource, _, instance] = &names.configuration;
            let _ = writeln!(
                c,
                "void config_init__(void);\nvoid config_run__(unsigned long tick);\n\
                 extern {program} {resource}__{instance};\n#define FB {resource}__{instance}.CTRL",
                program = up(&names.program),
                resource = up(resource),
                instance = up(instance),
            );
        }
    }
    let (ne, nu) = list_sizes(project);
    c.push_str("static void report(void) {\n");
    c.push_str(
        "    printf(\"%d %d %d %lu %lu %d\", (int)__GET_VAR(FB.FAULT,), (int)__GET_VAR(FB.FAULT_CAUSE,),\n\
         \x20          (int)__GET_VAR(FB.FAULT_EVENT,), (unsigned long)__GET_VAR(FB.FAULTS,),\n\
         \x20          (unsigned long)__GET_VAR(FB.IGNORED,), (int)__GET_VAR(FB.N_EVENTS,));\n",
    );
    let _ = writeln!(
        c,
        "    for (int k = 0; k < {ne}; k++) printf(\" %d\", (int)__GET_VAR(FB.EVENTS,).table[k]);\n\
         \x20   printf(\" %d\", (int)__GET_VAR(FB.N_UNEXPECTED,));\n\
         \x20   for (int k = 0; k < {nu}; k++) printf(\" %d\", (int)__GET_VAR(FB.UNEXPECTED,).table[k]);"
    );
    for s in &names.states {
        let _ = writeln!(c, "    printf(\" %ld\", (long)__GET_VAR(FB.{},));", up(s));
    }
    for (n, net) in project.nets.iter().enumerate() {
        let _ = writeln!(
            c,
            "    for (int p = 0; p < {}; p++) printf(\" %ld\", (long)__GET_VAR(FB.{},).table[p]);",
            net.net.places().len(),
            up(&names.nets[n])
        );
    }
    for o in &names.outputs {
        let _ = writeln!(c, "    printf(\" %d\", (int)__GET_VAR(FB.{},));", up(o));
    }
    if drive == Drive::Task {
        for a in &outputs {
            let _ = writeln!(c, "    printf(\" %d\", (int)*{});", located(a));
        }
    }
    c.push_str("    printf(\"\\n\");\n}\n");
    c.push_str("static char line[1 << 20];\nint main(void) {\n");
    match drive {
        Drive::Block => {
            let _ = writeln!(c, "    {ctrl}_init__(&fb, 0);");
        }
        Drive::Task => c.push_str("    config_init__();\n    unsigned long tick = 0;\n"),
    }
    c.push_str("    while (fgets(line, sizeof line, stdin)) {\n        char *p = line;\n");
    if drive == Drive::Block {
        c.push_str(
            "        unsigned long now = strtoul(p, &p, 10);\n        while (*p == ' ') p++;\n\
             \x20       __SET_VAR(fb., NOW_MS, , (UDINT)now);\n",
        );
    }
    for (i, name) in names.inputs.iter().enumerate() {
        match drive {
            Drive::Block => {
                let _ = writeln!(c, "        __SET_VAR(fb., {}, , p[{i}] == '1');", up(name));
            }
            Drive::Task => {
                let _ = writeln!(c, "        *{} = p[{i}] == '1';", located(&inputs[i]));
            }
        }
    }
    match drive {
        Drive::Block => {
            let _ = writeln!(c, "        {ctrl}_body__(&fb);");
        }
        Drive::Task => c.push_str("        config_run__(tick++);\n"),
    }
    c.push_str("        report();\n    }\n    return 0;\n}\n");
    c
}

/// Runs `rows` through the compiled program: one observation per row.
fn run(compiled: &Compiled, project: &Project, rows: &[InputRow], drive: Drive) -> Vec<Observed> {
    let mut input = String::new();
    for row in rows {
        if drive == Drive::Block {
            let _ = write!(input, "{} ", row.time_ms as u32);
        }
        input.extend(row.values.iter().map(|&v| if v { '1' } else { '0' }));
        input.push('\n');
    }
    let mut child = Command::new(&compiled.harness)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("the harness runs");
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let output = child.wait_with_output().expect("the harness ends");
    writer.join().expect("writer").expect("inputs written");
    assert!(
        output.status.success(),
        "the harness failed: {}",
        output.status
    );
    let text = String::from_utf8(output.stdout).expect("ASCII");
    let seen: Vec<Observed> = text.lines().map(|l| parse(project, l, drive)).collect();
    assert_eq!(seen.len(), rows.len(), "one line per scan");
    seen
}

/// One line of the harness: fault, cause, event, faults, ignored, then
/// the executed events (count, list), the unexpected ones, the automaton
/// states, each net's marking, the outputs and, for a task, the located
/// outputs (which must equal the block's).
fn parse(project: &Project, line: &str, drive: Drive) -> Observed {
    let v: Vec<i64> = line
        .split_whitespace()
        .map(|t| t.parse().expect("a number"))
        .collect();
    let (ne, nu) = list_sizes(project);
    let mut at = 5;
    let mut take = |n: usize| {
        let s = v[at..at + n].to_vec();
        at += n;
        s
    };
    let n_events = take(1)[0] as usize;
    let executed = take(ne)[..n_events].iter().map(|&e| e as u16).collect();
    let n_unexpected = take(1)[0] as usize;
    let unexpected = take(nu)[..n_unexpected].iter().map(|&e| e as u16).collect();
    let automata: Vec<u32> = take(project.supervisors.len())
        .iter()
        .map(|&s| s as u32)
        .collect();
    let markings: Vec<Vec<u32>> = project
        .nets
        .iter()
        .map(|n| {
            take(n.net.places().len())
                .iter()
                .map(|&m| m as u32)
                .collect()
        })
        .collect();
    let outputs: Vec<bool> = take(project.outputs.len())
        .iter()
        .map(|&o| o != 0)
        .collect();
    if drive == Drive::Task {
        let at_addresses: Vec<bool> = take(project.outputs.len())
            .iter()
            .map(|&o| o != 0)
            .collect();
        assert_eq!(at_addresses, outputs, "the program's located outputs");
    }
    assert_eq!(at, v.len(), "the whole line read");
    let fault = (v[0] != 0).then(|| {
        let cause = v[1];
        let event = if cause == iec::scan::CAUSE_UNEXPECTED {
            v[2]
        } else {
            -1
        };
        (cause, event)
    });
    Observed {
        executed,
        unexpected,
        states: pack_states(project, &automata, &markings),
        outputs,
        fault,
        faults: v[3] as u32,
        ignored: v[4] as u32,
    }
}

/// Random inputs for a run driven as `drive`: guided sequences (mostly
/// expected events, then a noisier one) and inputs toggled blindly (every
/// input, the reset too), whose stray edges provoke unexpected events,
/// faults and resets. The block's rows jump the clock and cross 2^32; a
/// task's are on its period grid.
fn random_runs(project: &Project, seed: u64, drive: Drive) -> Vec<Vec<InputRow>> {
    let near_wrap = (1u64 << 32) - 60_000;
    let guided = |scans, noise| guided_inputs(project, scans, seed, noise).expect("inputs");
    match drive {
        Drive::Block => vec![
            shifted(guided(10_000, 40), near_wrap),
            guided(5_000, 3),
            blind_inputs(project, 5_000, seed, near_wrap),
        ],
        Drive::Task => vec![
            on_grid(project, guided(6_000, 40)),
            on_grid(project, blind_inputs(project, 4_000, seed, 0)),
        ],
    }
}

/// Compiles `text` and runs it in lockstep on random inputs; the
/// coverage of the runs.
fn random_lockstep(
    project: &Project,
    names: &Names,
    text: &str,
    drive: Drive,
    what: &str,
    seed: u64,
) -> Coverage {
    let compiled = compile(project, names, text, drive)
        .unwrap_or_else(|e| panic!("{} ({what}): {e}", project.name));
    let mut total = Coverage::default();
    for rows in random_runs(project, seed, drive) {
        let seen = run(&compiled, project, &rows, drive);
        total.add(compare(project, &rows, what, |k, _| seen[k].clone()));
    }
    total
}

/// A project's three texts compiled and run.
fn project_lockstep(rel: &str, seed: u64) {
    texts_lockstep(&load(rel), rel, seed);
}

/// The three texts of `project` (called `rel` in messages) compiled and
/// run.
fn texts_lockstep(project: &Project, rel: &str, seed: u64) {
    let export = iec::export(project, &IoMap::sequential(), "codegen st (test)")
        .unwrap_or_else(|e| panic!("{rel}: {e}"));
    let names = &export.names;
    let st = iec::st::print(&export);
    let configured = st.clone() + &iec::st::configuration(&export);
    let xml = plcopen_st::to_st(&iec::plcopen::print(&export))
        .unwrap_or_else(|e| panic!("{rel}: the PLCopen XML: {e}"));
    let mut report = Vec::new();
    for (text, drive, what) in [
        (&st, Drive::Block, "codegen st"),
        (&configured, Drive::Task, "codegen st --configuration"),
        (&xml, Drive::Task, "codegen plcopen"),
    ] {
        let cov = random_lockstep(project, names, text, drive, what, seed);
        assert!(cov.scans >= 10_000, "{rel} ({what}): {} scans", cov.scans);
        cov.assert_exercised(project, &format!("{rel} ({what})"));
        report.push(format!("{what}: {}", cov.summary(project)));
    }
    println!(
        "{rel}: compiled by iec2c and gcc, 0 differences; {}",
        report.join("; ")
    );
}

macro_rules! matiec_tests {
    ($($name:ident: $index:expr, $seed:expr;)*) => {$(
        #[test]
        #[ignore = "needs matiec (MATIEC_DIR) and gcc: cargo xtask matiec"]
        fn $name() {
            project_lockstep(lockstep::PROJECTS[$index], $seed);
        }
    )*};
}

matiec_tests! {
    motivating_compiles_and_runs_in_lockstep: 0, 21;
    press_compiles_and_runs_in_lockstep: 1, 22;
    press7_compiles_and_runs_in_lockstep: 2, 23;
    conveyor_compiles_and_runs_in_lockstep: 3, 24;
    crane_compiles_and_runs_in_lockstep: 4, 25;
    agv_compiles_and_runs_in_lockstep: 5, 26;
    boiler_compiles_and_runs_in_lockstep: 6, 27;
    boiler_mono_compiles_and_runs_in_lockstep: 7, 28;
    mixers_compiles_and_runs_in_lockstep: 8, 29;
    cell_compiles_and_runs_in_lockstep: 9, 30;
    iec_names_compile_and_run_in_lockstep: 10, 31;
    module_compiles_and_runs_in_lockstep: 11, 32;
    testbed_compiles_and_runs_in_lockstep: 12, 34;
    testbed_whole_compiles_and_runs_in_lockstep: 13, 35;
    breakdown_compiles_and_runs_in_lockstep: 14, 36;
}

/// Guards written as chains of BOOL temporaries (`GN[k]`, the `CHOSEN`
/// flag): the module with random guards, compiled and run in lockstep.
#[test]
#[ignore = "needs matiec (MATIEC_DIR) and gcc: cargo xtask matiec"]
fn guards_written_as_chains_compile_and_run_in_lockstep() {
    let project = lockstep::module_with_random_guards(0x00C0_FFEE);
    let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
    let chains = iec::st::print(&export).matches("GN[0] := ").count();
    assert!(chains >= 5, "{chains} guards written as chains");
    texts_lockstep(&project, "module with random guards", 33);
}

/// The boiler's closed-loop scenarios, replayed into the compiled block of
/// both boilers (the modular one's seven supervisors, the monolithic one's
/// sparse table): the deep sequences random inputs do not reach.
#[test]
#[ignore = "needs matiec (MATIEC_DIR) and gcc: cargo xtask matiec"]
fn the_boilers_closed_loop_scenarios_compile_and_run_in_lockstep() {
    for rel in [
        "models/boiler/boiler.plc.toml",
        "models/boiler/boiler_mono.plc.toml",
    ] {
        let project = load(rel);
        let scenarios = lockstep::boiler_scenarios(&project);
        let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
        let text = iec::st::print(&export);
        let compiled = compile(&project, &export.names, &text, Drive::Block)
            .unwrap_or_else(|e| panic!("{rel}: {e}"));
        let mut total = Coverage::default();
        for (name, rows) in &scenarios {
            let seen = run(&compiled, &project, rows, Drive::Block);
            let cov = compare(&project, rows, name, |k, _| seen[k].clone());
            assert!(!cov.executed.is_empty(), "{rel} {name}: nothing happened");
            total.add(cov);
        }
        assert!(total.scans >= 10_000, "{rel}: {} scans", total.scans);
        println!(
            "{rel}: {} boiler scenarios, {} scans, {} of {} events, 0 differences",
            scenarios.len(),
            total.scans,
            total.executed.len(),
            project.events.len()
        );
    }
}

/// The comparison can fail: the press compiled with one transition of
/// its supervisor redirected differs from host-sim, and matiec refuses
/// what the export no longer writes (an `INT` state from a `SINT` array,
/// an empty statement).
#[test]
#[ignore = "needs matiec (MATIEC_DIR) and gcc: cargo xtask matiec"]
fn a_wrong_transition_or_a_wrong_type_is_found() {
    let project = load("models/press.plc.toml");
    let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
    let text = iec::st::print(&export);
    let mutant = lockstep::mutant(&text, &export.names.tables[0]);
    let outcome = std::panic::catch_unwind(|| {
        random_lockstep(&project, &export.names, &mutant, Drive::Block, "mutant", 2)
    });
    let message = lockstep::panic_text(outcome.expect_err("the mutant must differ"));
    assert!(message.contains("differs"), "{message}");

    let state = &export.names.states[0];
    let widened = text.replacen(&format!("{state} : SINT"), &format!("{state} : INT"), 1);
    let err = compile(&project, &export.names, &widened, Drive::Block)
        .err()
        .expect("matiec refuses an implicit SINT to INT");
    assert!(err.contains("Incompatible data types"), "{err}");
    let empty = text.replacen("IF FAULT THEN", "IF FAULT THEN\n        ;", 1);
    let err = compile(&project, &export.names, &empty, Drive::Block)
        .err()
        .expect("matiec refuses an empty statement");
    assert!(err.contains("iec2c refused"), "{err}");
}

/// The XML converter reads what the export wrote: the same POU names,
/// variables and bodies as the ST.
#[test]
fn the_xml_turned_back_into_st_has_the_exported_pous() {
    for rel in lockstep::PROJECTS {
        let project = load(rel);
        let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
        let st = plcopen_st::to_st(&iec::plcopen::print(&export)).expect("converts");
        for pou in &export.pous {
            assert!(
                st.contains(&pou.body.join("\n")),
                "{rel}: {}'s body",
                pou.name
            );
            assert!(st.contains(&pou.name), "{rel}: {}", pou.name);
            for var in pou.blocks.iter().flat_map(|b| &b.vars) {
                assert!(
                    st.contains(&format!("    {}", var.name)),
                    "{rel}: {} {}",
                    pou.name,
                    var.name
                );
            }
        }
        assert!(st.contains(&format!("CONFIGURATION {}", export.names.configuration[0])));
    }
}
