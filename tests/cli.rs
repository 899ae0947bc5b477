//! The `codegen` command as a user runs it: synthesis, checks, control
//! data, conversions, Graphviz, and how it reports bad input.

use des::formats::read_automaton;
use des::ops;
use e2e::{model, run_codegen, run_json, run_with_closed_stdout};
use std::path::Path;

const SMALL_FACTORY_PLANTS: [&str; 2] = [
    "models/bench/smallfactory/MACH1.gen",
    "models/bench/smallfactory/MACH2.gen",
];
const SMALL_FACTORY_SPECS: [&str; 2] = [
    "models/bench/smallfactory/BUFSPEC.gen",
    "models/bench/smallfactory/BRSPEC.gen",
];

fn synth_small_factory(out: &Path, extra: &[&str]) -> (i32, serde_json::Value) {
    let mut args: Vec<String> = vec!["synth".into(), "--plant".into()];
    args.extend(SMALL_FACTORY_PLANTS.map(String::from));
    args.push("--spec".into());
    args.extend(SMALL_FACTORY_SPECS.map(String::from));
    args.push("-o".into());
    args.push(out.display().to_string());
    args.extend(extra.iter().map(|s| s.to_string()));
    run_json(args)
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

#[test]
fn synth_writes_the_small_factory_supervisor_and_check_accepts_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sup.gen");
    let (code, report) = synth_small_factory(&out, &[]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["plant"]["states"], 9);
    assert_eq!(report["supervisor"]["states"], 12);
    assert_eq!(report["supervisor"]["transitions"], 24);
    assert_eq!(report["empty"], false);

    let sup = read_automaton(&out).unwrap();
    assert_eq!((sup.num_states(), sup.num_transitions()), (12, 24));
    assert_eq!(sup.name(), "sup");

    let mut args = vec!["check", "--plant"];
    args.extend(SMALL_FACTORY_PLANTS);
    args.push("--sup");
    let out_str = out.display().to_string();
    args.push(&out_str);
    let (code, check) = run_json(&args);
    assert_eq!(code, 0, "{check}");
    assert_eq!(check["holds"], true);
    assert_eq!(check["supervisors"][0]["controllable"], true);
    assert_eq!(check["supervisors"][0]["nonblocking"], true);

    let (code, info) = run_json(["info", &out_str]);
    assert_eq!(code, 0);
    assert_eq!(info[0]["trim"], true);
    assert_eq!(info[0]["nonblocking"], true);
    assert_eq!(info[0]["controllable"], 4);
}

#[test]
fn synth_minstate_keeps_the_language_and_shrinks_the_supervisor() {
    let dir = tempfile::tempdir().unwrap();
    // The spec counts cycles modulo 2 without caring: supcon keeps the
    // count (4 states), minstate merges it away (2 states).
    let plant = write(
        dir.path(),
        "m.toml",
        r#"
name = "m"
initial = "idle"
controllable = ["go"]
uncontrollable = ["done"]
transitions = [["idle", "go", "busy"], ["busy", "done", "idle"]]
"#,
    );
    let spec = write(
        dir.path(),
        "count.toml",
        r#"
name = "count"
initial = "even"
marked = ["even", "odd"]
controllable = ["go"]
uncontrollable = ["done"]
transitions = [
  ["even", "go", "even_busy"], ["even_busy", "done", "odd"],
  ["odd", "go", "odd_busy"], ["odd_busy", "done", "even"],
]
"#,
    );
    let full = dir.path().join("full.toml");
    let small = dir.path().join("small.wmod");
    let synth = |out: &Path, extra: &[&str]| {
        let mut args = vec![
            "synth",
            "--plant",
            &plant,
            "--spec",
            &spec,
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        run_json(args)
    };
    let (code, report) = synth(&full, &[]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["supervisor"]["states"], 4);
    let (code, report) = synth(&small, &["--minstate"]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["minimised"]["states"], 2);
    let a = read_automaton(&full).unwrap();
    let b = read_automaton(&small).unwrap();
    assert!(ops::language_equal(&a, &b));
    assert_eq!(b.num_states(), 2);
}

#[test]
fn synth_without_spec_gives_the_nonblocking_supervisor() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("phil5.gen");
    let mut args = vec![
        "synth".to_string(),
        "-o".into(),
        out.display().to_string(),
        "--plant".into(),
    ];
    for i in 1..=5 {
        args.push(format!("models/bench/phil5/P{i}.gen"));
        args.push(format!("models/bench/phil5/F{i}.gen"));
    }
    let (code, report) = run_json(&args);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["plant"]["states"], 243);
    assert_eq!(report["supervisor"]["states"], 241);
    assert_eq!(report["supervisor"]["transitions"], 935);
    assert!(report["spec"].is_null());
}

#[test]
fn an_empty_supervisor_is_written_and_announced() {
    let dir = tempfile::tempdir().unwrap();
    // The plant can always do `leak` (uncontrollable); the spec forbids it.
    let plant = write(
        dir.path(),
        "tank.toml",
        r#"
name = "tank"
initial = "full"
controllable = ["fill"]
uncontrollable = ["leak"]
transitions = [["full", "leak", "empty"], ["empty", "fill", "full"]]
"#,
    );
    let spec = write(
        dir.path(),
        "noleak.toml",
        r#"
name = "noleak"
initial = "ok"
controllable = ["fill"]
uncontrollable = ["leak"]
transitions = [["ok", "fill", "ok"]]
"#,
    );
    let out = dir.path().join("sup.toml");
    let args = [
        "synth",
        "--plant",
        &plant,
        "--spec",
        &spec,
        "-o",
        out.to_str().unwrap(),
    ];
    let run = run_codegen(args);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("EMPTY"), "{}", run.stdout);
    let sup = read_automaton(&out).unwrap();
    assert!(sup.is_empty());
    let (_, report) = run_json(args);
    assert_eq!(report["empty"], true);
    assert_eq!(report["supervisor"]["states"], 0);
}

#[test]
fn check_reports_an_uncontrollable_supervisor_with_a_witness_and_exit_1() {
    // The buffer spec itself, used as a supervisor, disables the
    // uncontrollable `e10` (M1 finishing) when the buffer is full.
    let mut args = vec!["check", "--plant"];
    args.extend(SMALL_FACTORY_PLANTS);
    args.extend(["--sup", SMALL_FACTORY_SPECS[0]]);
    let (code, report) = run_json(&args);
    assert_eq!(code, 1, "{report}");
    assert_eq!(report["holds"], false);
    let w = &report["supervisors"][0]["uncontrollable"];
    assert_eq!(w["event"], "e10");
    // A shortest string: M1 starts, finishes (buffer full), starts again.
    assert_eq!(w["path"], serde_json::json!(["e11", "e10", "e11"]));
    let run = run_codegen(&args);
    assert_eq!(run.code, 1);
    assert!(run.stdout.contains("controllable: NO"), "{}", run.stdout);
    assert!(run.stdout.contains("e11 e10 e11"), "{}", run.stdout);
}

#[test]
fn check_finds_conflicting_modular_supervisors() {
    let dir = tempfile::tempdir().unwrap();
    let plant = write(
        dir.path(),
        "g.toml",
        r#"
name = "g"
initial = "0"
controllable = ["a", "b"]
uncontrollable = []
transitions = [["0", "a", "1"], ["0", "b", "2"], ["1", "b", "3"], ["2", "a", "3"]]
marked = ["3"]
"#,
    );
    let ab = write(
        dir.path(),
        "ab.toml",
        r#"
name = "ab"
initial = "0"
controllable = ["a", "b"]
uncontrollable = []
transitions = [["0", "a", "1"], ["1", "b", "2"]]
marked = ["2"]
"#,
    );
    let ba = write(
        dir.path(),
        "ba.toml",
        r#"
name = "ba"
initial = "0"
controllable = ["a", "b"]
uncontrollable = []
transitions = [["0", "b", "1"], ["1", "a", "2"]]
marked = ["2"]
"#,
    );
    let (code, report) = run_json(["check", "--plant", &plant, "--sup", &ab, &ba]);
    assert_eq!(code, 1, "{report}");
    assert_eq!(report["supervisors"][0]["controllable"], true);
    assert_eq!(report["supervisors"][1]["nonblocking"], true);
    assert_eq!(report["nonconflicting"], false);
    assert_eq!(report["conflict"]["path"], serde_json::json!([]));
}

#[test]
fn condat_lists_the_disabled_restart_when_the_buffer_is_full() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sup.gen");
    assert_eq!(synth_small_factory(&out, &[]).0, 0);
    let mut args = vec!["condat", "--plant"];
    args.extend(SMALL_FACTORY_PLANTS);
    let out_str = out.display().to_string();
    args.extend(["--sup", &out_str]);
    let (code, rows) = run_json(&args);
    assert_eq!(code, 0);
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 12);
    let disabled: Vec<&str> = rows
        .iter()
        .flat_map(|r| r["disabled"].as_array().unwrap())
        .map(|e| e.as_str().unwrap())
        .collect();
    // Only controllable events are ever disabled: M1's start (e11) when
    // the buffer is full, M2's start (e21) when it is empty, M1's repair
    // (e13) while M2 is down.
    assert!(disabled.contains(&"e11") && disabled.contains(&"e21"));
    assert!(disabled
        .iter()
        .all(|e| ["e11", "e13", "e21", "e23"].contains(e)));
}

#[test]
fn convert_round_trips_through_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let original = model("models/bench/transferline/TU.gen");
    let mut current = original.clone();
    for ext in ["wmod", "toml", "ads", "gen"] {
        let next = dir.path().join(format!("tu.{ext}"));
        let run = run_codegen(["convert", current.to_str().unwrap(), next.to_str().unwrap()]);
        assert_eq!(run.code, 0, "{ext}: {}", run.stderr);
        current = next;
    }
    let a = read_automaton(&original).unwrap();
    let b = read_automaton(&current).unwrap();
    assert!(ops::isomorphic(&a, &b));
    assert_eq!(a.name(), b.name());
}

#[test]
fn dot_draws_controllable_solid_and_uncontrollable_dashed() {
    let run = run_codegen(["dot", SMALL_FACTORY_PLANTS[0]]);
    assert_eq!(run.code, 0);
    assert!(
        run.stdout.starts_with("digraph \"MACH1\""),
        "{}",
        run.stdout
    );
    assert!(run.stdout.contains("[label=\"e11\"]"));
    assert!(run.stdout.contains("[label=\"e10\", style=dashed]"));
    assert!(run.stdout.contains("shape=doublecircle"));
}

#[test]
fn malformed_input_is_reported_with_file_and_line_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let bad = write(
        dir.path(),
        "bad.toml",
        "name = \"m\"\ninitial = \"a\"\ncontrollable = [\"go\"]\nuncontrollable = []\ntransitions = [\n  [\"a\", \"go\", \"b\"],\n  [\"a\", \"stop\", \"b\"],\n]\n",
    );
    let run = run_codegen(["info", &bad]);
    assert_eq!(run.code, 2);
    assert!(run.stderr.contains("bad.toml:7"), "{}", run.stderr);
    assert!(run.stderr.contains("stop"), "{}", run.stderr);

    let nondet = write(
        dir.path(),
        "nd.toml",
        "name = \"m\"\ninitial = \"a\"\ncontrollable = [\"go\"]\nuncontrollable = []\ntransitions = [\n  [\"a\", \"go\", \"b\"],\n  [\"a\", \"go\", \"c\"],\n]\n",
    );
    let run = run_codegen(["info", &nondet]);
    assert_eq!(run.code, 2);
    assert!(run.stderr.contains("nondeterministic"), "{}", run.stderr);
    assert!(run.stderr.contains("nd.toml:7"), "{}", run.stderr);

    let (code, err) = run_json(["info", "no/such/file.gen"]);
    assert_eq!(code, 2);
    assert!(err["error"].as_str().unwrap().contains("no/such/file.gen"));

    let run = run_codegen(["info", "README.md"]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr.contains("unknown model format"),
        "{}",
        run.stderr
    );
}

/// Every file `codegen` reads from a path it is given is refused when it
/// is no regular file, naming the path and the kind of file, instead of
/// being read until memory runs out (`/dev/zero`) or blocking (a FIFO).
#[cfg(unix)]
#[test]
fn every_file_argument_must_be_a_regular_file() {
    let dir = tempfile::tempdir().unwrap();
    let press = model("models/press.plc.toml").display().to_string();
    let mixers = model("models/petri/mixers.toml").display().to_string();
    let out = dir.path().join("out").display().to_string();
    // (file name, kind in the message, arguments around the path)
    type Case = (&'static str, &'static str, Vec<String>, Vec<String>);
    let s = |v: &[&str]| v.iter().map(|a| a.to_string()).collect::<Vec<_>>();
    let cases: Vec<Case> = vec![
        (
            "map.io.toml",
            "I/O map",
            s(&["st", &press, "--io"]),
            s(&["-o", &out]),
        ),
        (
            "map.io.toml",
            "I/O map",
            s(&["plcopen", &press, "--io"]),
            s(&["-o", &out]),
        ),
        ("p.plc.toml", "project file", s(&["gen"]), vec![]),
        ("p.plc.toml", "project file", s(&["st"]), vec![]),
        ("p.plc.toml", "project file", s(&["wiring"]), vec![]),
        ("m.gen", "model file", s(&["info"]), vec![]),
        ("n.pnml", "model file", s(&["petri", "info"]), vec![]),
        (
            "c.toml",
            "model file",
            s(&["petri", "synth", &mixers, "--constraints"]),
            s(&["-o", &out]),
        ),
    ];
    for (k, (name, kind, before, after)) in cases.into_iter().enumerate() {
        for path in des::testing::not_regular_files(&dir.path().join(k.to_string()), name) {
            let path = path.display().to_string();
            let run = run_codegen(before.iter().chain([&path]).chain(&after));
            assert_eq!(run.code, 2, "{before:?} {path}: {}", run.stderr);
            let expected = format!("{path}: not a regular file (the {kind} must be a file");
            assert!(
                run.stderr.contains(&expected),
                "{before:?}: expected {expected}\ngot {}",
                run.stderr
            );
        }
    }
}

#[test]
fn nothing_but_results_reaches_a_pipe() {
    // The progress spinner stays off when stderr is not a terminal.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sup.ads");
    let mut args = vec!["synth", "-o", out.to_str().unwrap(), "--plant"];
    args.extend(SMALL_FACTORY_PLANTS);
    args.push("--spec");
    args.extend(SMALL_FACTORY_SPECS);
    let run = run_codegen(&args);
    assert_eq!(run.code, 0);
    assert_eq!(run.stderr, "");
    assert!(
        run.stdout.contains("supervisor: 12 states, 24 transitions"),
        "{}",
        run.stdout
    );
}

/// The seed projects `codegen gen` must handle with both backends.
const SEED_PROJECTS: [&str; 4] = [
    "models/motivating.plc.toml",
    "models/press.plc.toml",
    "models/press7.plc.toml",
    "models/conveyor.plc.toml",
];

#[test]
fn gen_prints_rust_that_parses_and_defines_the_program() {
    let dir = tempfile::tempdir().unwrap();
    for project in SEED_PROJECTS {
        for backend in ["table", "logic"] {
            let what = format!("{project} --backend {backend}");
            let run = run_codegen(["gen", project, "--backend", backend]);
            assert_eq!(run.code, 0, "{what}: {}", run.stderr);
            assert_eq!(run.stderr, "", "{what}: warnings on a seed project");
            if let Err(e) = syn::parse_file(&run.stdout) {
                panic!("{what}: output is not Rust: {e}\n{}", run.stdout);
            }
            for item in [
                "pub static PROGRAM",
                "pub type Memory",
                "pub const CONFIG",
                "pub const IMAGE_CRC",
            ] {
                assert!(run.stdout.contains(item), "{what}: no `{item}`");
            }
            assert!(
                run.stdout.contains(&format!("({backend} backend)")),
                "{what}: header does not name the backend"
            );

            // `-o FILE` writes the same text and prints nothing.
            let out = dir.path().join("out.rs");
            let out_str = out.to_str().unwrap();
            let written = run_codegen(["gen", project, "--backend", backend, "-o", out_str]);
            assert_eq!(written.code, 0, "{what} -o: {}", written.stderr);
            assert_eq!(written.stdout, "", "{what} -o");
            assert_eq!(
                std::fs::read_to_string(&out).unwrap(),
                run.stdout,
                "{what} -o"
            );
        }
    }
}

#[test]
fn gen_stats_print_every_supervisor_with_bytes_naive_bytes_and_ratio() {
    for project in SEED_PROJECTS {
        let (code, stats) = run_json(["gen", project, "--stats"]);
        assert_eq!(code, 0, "{project}: {stats}");
        let run = run_codegen(["gen", project, "--stats"]);
        assert_eq!(run.code, 0, "{project}: {}", run.stderr);
        let lines: Vec<&str> = run.stdout.lines().collect();
        let header = lines
            .iter()
            .find(|l| l.split_whitespace().next() == Some("supervisor"))
            .unwrap_or_else(|| panic!("{project}: no header\n{}", run.stdout));
        for column in ["bytes", "naive", "ratio"] {
            assert!(header.contains(column), "{project}: {header}");
        }
        let stats = stats.as_array().unwrap();
        assert!(!stats.is_empty(), "{project}");
        for s in stats {
            let name = s["name"].as_str().unwrap();
            let bytes = s["table_bytes"].as_u64().unwrap();
            let naive = s["naive_bytes"].as_u64().unwrap();
            let row: Vec<&str> = lines
                .iter()
                .map(|l| l.split_whitespace().collect::<Vec<_>>())
                .find(|cells| cells.first() == Some(&name))
                .unwrap_or_else(|| panic!("{project}: no row for `{name}`\n{}", run.stdout));
            let ratio = format!("{:.2}x", naive as f64 / bytes as f64);
            for cell in [bytes.to_string(), naive.to_string(), ratio] {
                assert!(
                    row.contains(&cell.as_str()),
                    "{project}: row of `{name}` lacks `{cell}`: {row:?}"
                );
            }
        }
    }
}

#[test]
fn gen_json_stats_show_the_press_table_smaller_than_the_naive_one() {
    let (code, stats) = run_json(["gen", "models/press.plc.toml", "--stats"]);
    assert_eq!(code, 0, "{stats}");
    let stats = stats.as_array().expect("a list of supervisors");
    assert_eq!(stats.len(), 1, "{stats:?}");
    let press = &stats[0];
    assert_eq!(press["name"], "press");
    assert_eq!(press["states"], 6);
    assert_eq!(press["events"], 7);
    let bytes = press["table_bytes"].as_u64().unwrap();
    let naive = press["naive_bytes"].as_u64().unwrap();
    assert!(0 < bytes && bytes < naive, "{press}");
    // Naive: one u16 per state × event pair.
    assert_eq!(naive, 2 * 6 * 7);
}

/// `models/press.plc.toml` as a temporary project (its supervisor file
/// named by absolute path), with `edit` applied to its text.
fn press_variant(dir: &Path, edit: impl Fn(&str) -> String) -> (String, String) {
    let text = std::fs::read_to_string(model("models/press.plc.toml")).unwrap();
    let supervisor = model("models/press/press.toml");
    let text = text.replace(
        "file = \"press/press.toml\"",
        &format!("file = {:?}", supervisor.display().to_string()),
    );
    let edited = edit(&text);
    assert_ne!(edited, text, "the edit changes nothing");
    let path = write(dir, "bad.plc.toml", &edited);
    (path, edited)
}

/// The 1-based line of `text` that contains `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("no `{needle}` in\n{text}"))
        + 1
}

#[test]
fn gen_reports_project_errors_with_file_and_line_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();

    // The unmodified copy generates: the errors below are the edits'.
    let (good, _) = press_variant(dir.path(), |t| t.replace("# The stamping", "# A stamping"));
    let run = run_codegen(["gen", &good]);
    assert_eq!(run.code, 0, "{}", run.stderr);

    // A binding that names an unknown input.
    let (bad, text) = press_variant(dir.path(), |t| {
        t.replace("rising = \"part\"", "rising = \"parts\"")
    });
    let line = line_of(&text, "\"parts\"");
    for backend in ["table", "logic"] {
        let run = run_codegen(["gen", &bad, "--backend", backend]);
        assert_eq!(run.code, 2, "{}", run.stderr);
        assert!(
            run.stderr.contains(&format!("bad.plc.toml:{line}:")),
            "{}",
            run.stderr
        );
        assert!(
            run.stderr.contains("unknown input `parts`"),
            "{}",
            run.stderr
        );
        assert_eq!(run.stdout, "", "no code on error");
    }
    let (code, err) = run_json(["gen", &bad, "--stats"]);
    assert_eq!(code, 2);
    let message = err["error"].as_str().unwrap();
    assert!(
        message.contains(&format!("bad.plc.toml:{line}:")),
        "{message}"
    );

    // An event of the supervisor that the project does not declare: the
    // error points at the `[[supervisor]]` that needs it.
    let (bad, text) = press_variant(dir.path(), |t| {
        t.replace("at_top = { rising = \"top_ls\" }\n", "")
    });
    let line = line_of(&text, "[[supervisor]]");
    let run = run_codegen(["gen", &bad]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr.contains(&format!("bad.plc.toml:{line}:")),
        "{}",
        run.stderr
    );
    assert!(
        run.stderr.contains("event `at_top`") && run.stderr.contains("not declared in [events]"),
        "{}",
        run.stderr
    );
}

#[test]
fn a_reader_that_stops_early_ends_every_verb_quietly_with_its_exit_code() {
    // `codegen … | head`: the pipe closes before the output is written.
    // Every verb that prints must stop without a panic and without a
    // word on stderr, and still exit with its result (check: 1).
    let dir = tempfile::tempdir().unwrap();
    let tmp = |name: &str| dir.path().join(name).display().to_string();
    let mut synth = vec!["synth".to_owned(), "-o".to_owned(), tmp("sup.gen")];
    synth.push("--plant".into());
    synth.extend(SMALL_FACTORY_PLANTS.map(String::from));
    synth.push("--spec".into());
    synth.extend(SMALL_FACTORY_SPECS.map(String::from));
    let mut check = vec!["check".to_owned(), "--plant".to_owned()];
    check.extend(SMALL_FACTORY_PLANTS.map(String::from));
    check.extend(["--sup".to_owned(), SMALL_FACTORY_SPECS[0].to_owned()]);
    let mut condat = vec!["condat".to_owned(), "--plant".to_owned()];
    condat.extend(SMALL_FACTORY_PLANTS.map(String::from));
    condat.extend(["--sup".to_owned(), SMALL_FACTORY_SPECS[0].to_owned()]);
    let mut verify = vec!["verify".to_owned(), "--plant".to_owned()];
    verify.extend(SMALL_FACTORY_PLANTS.map(String::from));
    verify.extend(["--sup".to_owned(), SMALL_FACTORY_SPECS[0].to_owned()]);
    let words = |ws: &[&str]| ws.iter().map(|w| w.to_string()).collect::<Vec<_>>();
    let cases: Vec<(Vec<String>, i32)> = vec![
        (words(&["info", SMALL_FACTORY_PLANTS[0]]), 0),
        (synth, 0),
        (check, 1),
        (verify, 1),
        (condat, 0),
        (
            words(&[
                "convert",
                "models/bench/transferline/TU.gen",
                &tmp("tu.wmod"),
            ]),
            0,
        ),
        (words(&["dot", "models/boiler/sup/sup_pilot.toml"]), 0),
        (words(&["gen", "models/press.plc.toml"]), 0),
        (words(&["gen", "models/press.plc.toml", "--stats"]), 0),
        (words(&["wiring", "models/press.plc.toml"]), 0),
        (words(&["--help"]), 0),
        (words(&["dot", "--help"]), 0),
    ];
    for (args, code) in cases {
        for json in [false, true] {
            let mut args = args.clone();
            if json {
                if args[0].starts_with("--") || args.contains(&"--help".to_owned()) {
                    continue;
                }
                args.insert(0, "--json".into());
            }
            let what = args.join(" ");
            let open = run_codegen(&args);
            assert_eq!(open.code, code, "{what}: {}", open.stderr);
            assert!(!open.stdout.is_empty(), "{what}: prints nothing to cut");
            let closed = run_with_closed_stdout(&args);
            assert!(
                !closed.stderr.contains("panicked"),
                "{what}: {}",
                closed.stderr
            );
            assert_eq!(closed.stderr, "", "{what}");
            assert_eq!(closed.code, code, "{what}");
        }
    }
    // An error still reaches stderr (and exit code 2) when stdout is gone.
    let closed = run_with_closed_stdout(["--json", "info", "no/such/file.gen"]);
    assert_eq!(closed.code, 2);
    assert!(closed.stderr.starts_with("error: "), "{}", closed.stderr);
    assert!(!closed.stderr.contains("panicked"), "{}", closed.stderr);
}

#[test]
fn dot_writes_one_graph_per_file_and_names_the_files_after_the_components() {
    let module = "crates/des/tests/fixtures/formats/smallfactory.wmod";
    // Several graphs in one stream are not a Graphviz file: refused, with
    // the two ways out.
    let run = run_codegen(["dot", module]);
    assert_eq!(run.code, 2, "{}", run.stdout);
    assert_eq!(run.stdout, "");
    for needle in [
        "3 automata",
        "MACH1, BUFSPEC, NEVER_E20_FIRST",
        "--component NAME",
        "--output-dir DIR",
    ] {
        assert!(run.stderr.contains(needle), "{needle}: {}", run.stderr);
    }

    let dir = tempfile::tempdir().unwrap();
    let graphs = dir.path().join("graphs");
    let run = run_codegen(["dot", module, "--output-dir", graphs.to_str().unwrap()]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let mut files: Vec<String> = std::fs::read_dir(&graphs)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    files.sort();
    assert_eq!(files, ["BUFSPEC.dot", "MACH1.dot", "NEVER_E20_FIRST.dot"]);
    for file in &files {
        let text = std::fs::read_to_string(graphs.join(file)).unwrap();
        let name = file.trim_end_matches(".dot");
        assert!(
            text.starts_with(&format!("digraph \"{name}\" {{")),
            "{file}: {text}"
        );
        assert_eq!(text.matches("digraph").count(), 1, "{file}");
        assert!(
            run.stdout.contains(&format!("{file} ({name})")),
            "{}",
            run.stdout
        );
    }

    // One component: to stdout, or to a file with -o.
    let run = run_codegen(["dot", module, "--component", "BUFSPEC"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        run.stdout,
        std::fs::read_to_string(graphs.join("BUFSPEC.dot")).unwrap()
    );
    let out = dir.path().join("mach1.dot");
    let run = run_codegen([
        "dot",
        module,
        "--component",
        "MACH1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        std::fs::read_to_string(graphs.join("MACH1.dot")).unwrap()
    );
}

#[test]
fn dot_summarises_a_large_automaton_unless_asked_for_all_of_it() {
    // 406 states, 5,525 transitions: Graphviz `dot` does not finish in
    // minutes on the whole.
    let big = "models/boiler/sup/sup_pilot_seq.toml";
    let run = run_codegen(["dot", big]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    for needle in [
        "summary (406 states, more than --max-states 100)",
        "1 strongly connected component",
        "--full",
        "--layout sfdp",
    ] {
        assert!(run.stdout.contains(needle), "{needle}: {}", run.stdout);
    }

    let run = run_codegen(["dot", big, "--full", "--layout", "sfdp"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("layout=sfdp;"), "{}", run.stdout);
    assert!(!run.stdout.contains("rankdir"), "sfdp has no ranks");
    assert!(run.stdout.contains("label=<idle<BR/>"));

    let run = run_codegen(["dot", big, "--full", "--quick"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stdout.contains("rankdir=TB;\n  nslimit=1;\n"),
        "{}",
        run.stdout
    );
    assert!(run.stdout.contains("[xlabel=\""), "{}", run.stdout);
    assert!(
        run.stdout
            .lines()
            .filter(|l| l.contains(" -> "))
            .all(|l| !l.contains("[label=")),
        "edge labels float"
    );

    let run = run_codegen(["dot", big, "--full", "--no-labels"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let edges: Vec<&str> = run.stdout.lines().filter(|l| l.contains(" -> s")).collect();
    assert!(edges.len() > 406, "{}", edges.len());
    assert!(edges.iter().all(|e| !e.contains("label")), "{edges:?}");
    assert!(edges.iter().any(|e| e.contains("style=dashed")));
}

#[test]
fn check_gives_the_components_of_every_composite_state() {
    let mut args = vec!["check", "--plant"];
    args.extend(SMALL_FACTORY_PLANTS);
    args.extend(["--sup", SMALL_FACTORY_SPECS[0]]);
    let run = run_codegen(&args);
    assert!(
        run.stdout
            .contains("the plant (in state 1.0 = (MACH1 1, MACH2 0)) can do uncontrollable `e10`"),
        "{}",
        run.stdout
    );
    let (_, report) = run_json(&args);
    let w = &report["supervisors"][0]["uncontrollable"];
    assert_eq!(w["plant_state"], "1.0");
    assert_eq!(
        w["plant_components"],
        serde_json::json!({ "MACH1": "1", "MACH2": "0" })
    );
    // JSON objects keep the composition order.
    let text = serde_json::to_string(&w["plant_components"]).unwrap();
    assert!(text.find("MACH1") < text.find("MACH2"), "{text}");
}

#[test]
fn check_keys_a_blocking_closed_loop_state_by_plant_and_supervisors() {
    let dir = tempfile::tempdir().unwrap();
    let plant = write(
        dir.path(),
        "g.toml",
        "name = \"g\"\ninitial = \"0\"\ncontrollable = [\"a\", \"b\"]\nuncontrollable = []\n\
         transitions = [[\"0\", \"a\", \"1\"], [\"0\", \"b\", \"2\"], [\"1\", \"b\", \"3\"], [\"2\", \"a\", \"3\"]]\n\
         marked = [\"3\"]\n",
    );
    // After `a` the supervisor stops everything: the closed loop blocks.
    let stop = write(
        dir.path(),
        "stop.toml",
        "name = \"stop\"\ninitial = \"go\"\ncontrollable = [\"a\", \"b\"]\nuncontrollable = []\n\
         transitions = [[\"go\", \"a\", \"stopped\"], [\"go\", \"b\", \"done\"], [\"done\", \"a\", \"done\"]]\n\
         marked = [\"done\"]\n",
    );
    let (code, report) = run_json(["check", "--plant", &plant, "--sup", &stop]);
    assert_eq!(code, 1, "{report}");
    let b = &report["supervisors"][0]["blocking"];
    assert_eq!(b["path"], serde_json::json!(["a"]));
    assert_eq!(b["state"], "1.stopped");
    assert_eq!(
        b["components"],
        serde_json::json!({ "g": "1", "stop": "stopped" })
    );
    let run = run_codegen(["check", "--plant", &plant, "--sup", &stop]);
    assert!(
        run.stdout
            .contains("the closed loop is in state 1.stopped = (g 1, stop stopped)"),
        "{}",
        run.stdout
    );
}

#[test]
fn synth_and_condat_give_the_key_to_the_supervisors_state_names() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sup.gen");
    let (code, report) = synth_small_factory(&out, &[]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(
        report["state_names"],
        serde_json::json!(["MACH1", "MACH2", "BUFSPEC", "BRSPEC"])
    );
    let mut args = vec!["synth".to_owned(), "--plant".to_owned()];
    args.extend(SMALL_FACTORY_PLANTS.map(String::from));
    args.push("--spec".into());
    args.extend(SMALL_FACTORY_SPECS.map(String::from));
    args.extend(["-o".into(), out.display().to_string()]);
    let run = run_codegen(&args);
    assert!(
        run.stdout
            .contains("states:     named MACH1.MACH2.BUFSPEC.BRSPEC\n"),
        "{}",
        run.stdout
    );

    let mut args = vec!["condat", "--plant"];
    args.extend(SMALL_FACTORY_PLANTS);
    let out_str = out.display().to_string();
    args.extend(["--sup", &out_str]);
    let (code, rows) = run_json(&args);
    assert_eq!(code, 0);
    // A synthesised supervisor's state is one plant state, and the key
    // matches the first positions of its name.
    for row in rows.as_array().unwrap() {
        let plant = row["plant"].as_array().unwrap();
        assert_eq!(plant.len(), 1, "{row}");
        let key = format!(
            "{}.{}.",
            plant[0]["MACH1"].as_str().unwrap(),
            plant[0]["MACH2"].as_str().unwrap()
        );
        assert!(row["state"].as_str().unwrap().starts_with(&key), "{row}");
    }
    let run = run_codegen(&args);
    assert!(
        run.stdout
            .starts_with("sup: controllable events disabled per state, with the plant state (MACH1, MACH2) it occurs with\n"),
        "{}",
        run.stdout
    );
    assert!(
        run.stdout.contains("\n  0.0.0.0 (0, 0): e21\n"),
        "{}",
        run.stdout
    );
}

#[test]
fn convert_keeps_the_kind_of_every_component() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name).display().to_string();
    let (code, _) = synth_small_factory(dir.path().join("sup.gen").as_path(), &[]);
    assert_eq!(code, 0);
    // A supervisor stays one through every format.
    let mut current = path("sup.gen");
    for next in ["sup.ads", "sup.toml", "sup2.gen", "sup.wmod", "sup3.toml"] {
        let next = path(next);
        let (code, report) = run_json(["convert", &current, &next]);
        assert_eq!(code, 0, "{report}");
        assert_eq!(report["components"][0]["kind"], "supervisor", "{next}");
        let (_, info) = run_json(["info", &next]);
        assert_eq!(info[0]["kind"], "supervisor", "{next}");
        current = next;
    }
    let wmod = std::fs::read_to_string(path("sup.wmod")).unwrap();
    assert!(
        wmod.contains("<SimpleComponent Kind=\"SUPERVISOR\" Name=\"sup\">"),
        "{wmod}"
    );

    // The components of a module keep theirs through single-automaton
    // formats.
    let module = "crates/des/tests/fixtures/formats/smallfactory.wmod";
    for (component, kind) in [
        ("BUFSPEC", "SPEC"),
        ("NEVER_E20_FIRST", "PROPERTY"),
        ("MACH1", "PLANT"),
    ] {
        let gen = path(&format!("{component}.gen"));
        let back = path(&format!("{component}.wmod"));
        assert_eq!(
            run_codegen(["convert", module, &gen, "--component", component]).code,
            0
        );
        assert_eq!(run_codegen(["convert", &gen, &back]).code, 0);
        let text = std::fs::read_to_string(&back).unwrap();
        assert!(
            text.contains(&format!(
                "<SimpleComponent Kind=\"{kind}\" Name=\"{component}\">"
            )),
            "{component}: {text}"
        );
    }

    // A file that states no kind gets one with --kind.
    let spec = path("bufspec.wmod");
    let run = run_codegen(["convert", SMALL_FACTORY_SPECS[0], &spec, "--kind", "spec"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("BUFSPEC (spec)"), "{}", run.stdout);
    let text = std::fs::read_to_string(&spec).unwrap();
    assert!(text.contains("Kind=\"SPEC\""), "{text}");
}

/// Thirty independent two-state machines compose to 2^30 states: refused
/// at the limit with the limit named, instead of exhausting memory
/// minutes later. (The default limit, 500,000 states, is reached in under
/// a second by a release build; a debug build takes half a minute, so the
/// test sets a small one.)
#[test]
fn synth_refuses_a_composition_beyond_its_state_limit() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["synth".to_string(), "--plant".to_string()];
    for k in 0..30 {
        args.push(write(
            dir.path(),
            &format!("m{k}.toml"),
            &format!(
                "name = \"m{k}\"\ninitial = \"idle\"\ncontrollable = [\"start{k}\"]\nuncontrollable = [\"done{k}\"]\ntransitions = [[\"idle\", \"start{k}\", \"busy\"], [\"busy\", \"done{k}\", \"idle\"]]\n"
            ),
        ));
    }
    args.push("-o".into());
    args.push(dir.path().join("sup.toml").display().to_string());
    args.extend(["--max-states".to_string(), "5000".to_string()]);
    let run = run_codegen(&args);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr.contains("exceeds the limit of 5000 states"),
        "{}",
        run.stderr
    );
    // The command line names its own flag, and only that (a project's
    // `max_states` is the front end's to name).
    assert!(
        run.stderr
            .trim_end()
            .ends_with("exceeds the limit of 5000 states (raise it with --max-states)"),
        "{}",
        run.stderr
    );
    assert!(!run.stderr.contains("max_states"), "{}", run.stderr);
    assert!(!dir.path().join("sup.toml").exists());
}

#[test]
fn petri_reach_beyond_its_state_limit_names_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let output = dir.path().join("graph.toml").display().to_string();
    let run = run_codegen([
        "petri",
        "reach",
        "models/petri/mixers.toml",
        "-o",
        &output,
        "--max-states",
        "15",
    ]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert_eq!(
        run.stderr,
        "error: the reachability graph of `mixers` exceeds the limit of 15 states \
         (raise it with --max-states)\n"
    );
    assert!(!dir.path().join("graph.toml").exists());
}

#[test]
fn petri_info_shows_the_mixers_incidence_and_that_both_can_take_the_supply() {
    let (code, info) = run_json(["petri", "info", "models/petri/mixers.toml"]);
    assert_eq!(code, 1, "not safe: exit 1");
    // SEEDS.md D: the row of the shared place m3 of D_p.
    assert_eq!(info["places"][2], "m3");
    assert_eq!(
        info["incidence"][2],
        serde_json::json!([1, -1, 0, 0, 1, -1, 0, 0])
    );
    assert_eq!(info["reachable_markings"], 16);
    assert_eq!(info["bounds"][2], 2);
    assert_eq!(info["safe"], false);
    assert_eq!(info["dead_markings"], serde_json::json!([]));
    let first = &info["place_invariants"][0];
    assert_eq!(first["value"], 1);
    let ids: Vec<&str> = first["weights"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["id"].as_str().unwrap())
        .collect();
    assert_eq!(ids, ["ma1", "ma2", "ma4", "ma5"]);
    assert_eq!(info["transition_invariants"].as_array().unwrap().len(), 2);
    assert_eq!(info["not_live"], serde_json::json!([]));
    let text = run_codegen(["petri", "info", "models/petri/mixers.pnml"]);
    assert_eq!(text.code, 1);
    assert!(
        text.stdout.contains("    m3  [  1 -1  0  0  1 -1  0  0 ]"),
        "{}",
        text.stdout
    );
    assert!(
        text.stdout
            .contains("safe:               no (m3 holds up to 2)"),
        "{}",
        text.stdout
    );
}

#[test]
fn petri_reach_writes_the_graph_and_convert_keeps_the_net() {
    let dir = tempfile::tempdir().unwrap();
    let graph = dir.path().join("mixers.gen");
    let run = run_codegen([
        "petri",
        "reach",
        "models/petri/mixers.pnml",
        "-o",
        graph.to_str().unwrap(),
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let a = read_automaton(&graph).unwrap();
    assert_eq!((a.num_states(), a.num_transitions()), (16, 32));
    assert_eq!(a.state_name(a.initial().unwrap()), "ma1+mb1");

    // The PNML in models/ is the TOML net converted: converting back gives
    // the same text.
    let back = dir.path().join("mixers.toml");
    let run = run_codegen([
        "petri",
        "convert",
        "models/petri/mixers.pnml",
        back.to_str().unwrap(),
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let original = des::petri::read_file(&model("models/petri/mixers.toml")).unwrap();
    let converted = des::petri::read_file(&back).unwrap();
    assert_eq!(converted, original);

    // Malformed: located, exit 2.
    let bad = write(
        dir.path(),
        "bad.toml",
        "name = \"x\"\ntransitions = [{ id = \"t\" }]\n",
    );
    let run = run_codegen(["petri", "info", &bad]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr
            .contains("bad.toml:2:16: transition `t` does not say whether it is controllable"),
        "{}",
        run.stderr
    );
}

#[test]
fn petri_synth_gives_the_mixers_the_papers_control_place() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("controlled.pnml");
    let (code, report) = run_json([
        "petri",
        "synth",
        "models/petri/mixers.pnml",
        "--constraints",
        "models/petri/mixers.constraints.toml",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0);
    // SEEDS.md D: D_c = [−1 1 0 0 −1 1 0 0], m_c0 = 1.
    let c1 = &report["control_places"][0];
    assert_eq!(c1["id"], "c1");
    assert_eq!(
        c1["incidence"],
        serde_json::json!({ "t1": -1, "t2": 1, "t5": -1, "t6": 1 })
    );
    assert_eq!(c1["initial"], 1);
    assert_eq!(report["safe"], true);
    assert_eq!(report["dead_markings"], serde_json::json!([]));
    assert_eq!(report["supcon"]["same_language"], true);
    assert_eq!(report["supcon"]["states"], 15);
    // The controlled net: the plant plus c1, safe.
    let (code, info) = run_json(["petri", "info", out.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert_eq!(info["places"].as_array().unwrap().len(), 10);
    assert_eq!(info["reachable_markings"], 15);
}

#[test]
fn petri_synth_reports_a_dead_closed_loop_with_the_firing_sequence_and_exit_1() {
    let dir = tempfile::tempdir().unwrap();
    // m3 ≤ 0: neither mixer may ever take the supply.
    let constraints = write(
        dir.path(),
        "none.toml",
        "[[constraint]]\nname = \"no supply\"\nweights = { m3 = 1 }\nbound = 0\n",
    );
    let out = dir.path().join("dead.toml");
    let run = run_codegen([
        "petri",
        "synth",
        "models/petri/mixers.toml",
        "--constraints",
        &constraints,
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(
        run.stdout
            .contains("closed loop: 1 reachable markings, safe, can deadlock"),
        "{}",
        run.stdout
    );
    assert!(
        run.stdout.contains("dead in ma1+mb1 after no firing"),
        "{}",
        run.stdout
    );
    // An inadmissible constraint: exit 2 at its line.
    let wild = write(
        dir.path(),
        "wild.toml",
        &std::fs::read_to_string(model("models/petri/mixers.toml"))
            .unwrap()
            .replace(
                "{ id = \"t5\", controllable = true",
                "{ id = \"t5\", controllable = false",
            ),
    );
    let run = run_codegen([
        "petri",
        "synth",
        &wild,
        "--constraints",
        "models/petri/mixers.constraints.toml",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr.contains(
            "mixers.constraints.toml:4:1: constraint `one mixer on the supply` is not admissible"
        ) && run.stderr.contains("`t5`"),
        "{}",
        run.stderr
    );
    // With --transform it is enforced through m3 + mb1 ≤ 1, which is
    // exactly supcon's behaviour here.
    let (code, report) = run_json([
        "petri",
        "synth",
        &wild,
        "--constraints",
        "models/petri/mixers.constraints.toml",
        "-o",
        out.to_str().unwrap(),
        "--transform",
    ]);
    assert_eq!(code, 0);
    assert_eq!(report["control_places"][0]["enforced_as"], "m3 + mb1 ≤ 1");
    assert_eq!(report["supcon"]["same_language"], true);
    assert_eq!(report["dead_markings"], serde_json::json!([]));
}

#[test]
fn gen_logic_stats_show_each_supervisors_effort_against_its_limit() {
    use codegen::backend::logic::{effort, Encoding, Minimisation, DEFAULT_MAX_EFFORT};
    let (code, stats) = run_json([
        "gen",
        "models/crane.plc.toml",
        "--backend",
        "logic",
        "--stats",
    ]);
    assert_eq!(code, 0, "{stats}");
    let project = plc_project::load(&model("models/crane.plc.toml")).unwrap();
    let stats = stats.as_array().unwrap();
    assert_eq!(stats.len(), project.supervisors.len());
    for (s, sup) in stats.iter().zip(&project.supervisors) {
        let local: Vec<_> = sup.local_events.iter().map(|&(_, id)| id).collect();
        let expected = effort(
            &sup.automaton,
            &local,
            &Encoding::binary(sup.automaton.num_states()),
            Minimisation::PerFunction,
        )
        .unwrap();
        assert_eq!(
            s["logic_effort"],
            serde_json::json!([expected, DEFAULT_MAX_EFFORT]),
            "{}",
            sup.name
        );
    }
    let run = run_codegen([
        "gen",
        "models/crane.plc.toml",
        "--backend",
        "logic",
        "--stats",
    ]);
    assert!(
        run.stdout
            .lines()
            .any(|l| l.contains("effort") && l.contains("limit")),
        "{}",
        run.stdout
    );
}

#[test]
fn gen_stats_show_a_net_group_with_its_markings_and_no_naive_table() {
    let (code, stats) = run_json(["gen", "models/petri/mixers.plc.toml", "--stats"]);
    assert_eq!(code, 0, "{stats}");
    let project = plc_project::load(&model("models/petri/mixers.plc.toml")).unwrap();
    let group = &stats.as_array().unwrap()[0];
    assert_eq!(group["name"], "mixers");
    assert_eq!(group["layout"], "net");
    assert_eq!(group["states"], project.nets[0].markings as u64);
    assert_eq!(group["naive_bytes"], 0);
    // 8 transitions: a PRE and a POST word each, one mask per place.
    let places = project.nets[0].net.places().len() as u64;
    assert_eq!(group["table_bytes"], 4 * (2 * 8 + places));
    let run = run_codegen(["gen", "models/petri/mixers.plc.toml", "--stats"]);
    let row = run
        .stdout
        .lines()
        .find(|l| l.trim_start().starts_with("mixers "))
        .unwrap_or_else(|| panic!("{}", run.stdout));
    let columns: Vec<&str> = row.split_whitespace().collect();
    let expected = [
        project.nets[0].markings.to_string(),
        "8".to_owned(),
        "net".to_owned(),
        (4 * (2 * 8 + places)).to_string(),
        "-".to_owned(),
        "-".to_owned(),
    ];
    assert_eq!(columns[1..], expected, "{row}");
}

/// The mixers' PNML as another editor writes it: no tool-specific
/// elements of ours, so no word on controllability.
fn foreign_mixers(dir: &Path) -> String {
    let pnml = std::fs::read_to_string(model("models/petri/mixers.pnml")).unwrap();
    let foreign: String = pnml
        .lines()
        .filter(|l| !l.contains("<toolspecific tool=\"codegen\""))
        .map(|l| format!("{l}\n"))
        .collect();
    write(dir, "foreign.pnml", &foreign)
}

#[test]
fn petri_verbs_take_the_controllability_a_foreign_net_does_not_state() {
    let dir = tempfile::tempdir().unwrap();
    let net = foreign_mixers(dir.path());
    let out = dir.path().join("out.pnml").display().to_string();
    let reach = dir.path().join("r.toml").display().to_string();
    let constraints = model("models/petri/mixers.constraints.toml")
        .display()
        .to_string();
    // Without a statement every verb refuses, saying how to give one.
    for args in [
        vec!["petri", "info", &net],
        vec!["petri", "reach", &net, "-o", &reach],
        vec![
            "petri",
            "synth",
            &net,
            "--constraints",
            &constraints,
            "-o",
            &out,
        ],
        vec!["petri", "convert", &net, &out],
    ] {
        let run = run_codegen(&args);
        assert_eq!(run.code, 2, "{args:?}");
        assert!(
            run.stderr.contains(
                "foreign.pnml:3:3: none of the net's 8 transitions says whether it is controllable"
            ) && run.stderr.contains("give --uncontrollable T1,T2,"),
            "{args:?}: {}",
            run.stderr
        );
    }
    // Stated on the command line.
    let (code, info) = run_json([
        "petri",
        "info",
        &net,
        "--uncontrollable",
        "t2, t6",
        "--unobservable",
        "t4",
    ]);
    // Exit 1: the plant alone is not safe (both mixers on the supply).
    assert_eq!(code, 1, "{info}");
    let flags: Vec<(String, bool, bool)> = info["transitions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            (
                t["id"].as_str().unwrap().to_owned(),
                t["controllable"].as_bool().unwrap(),
                t["observable"].as_bool().unwrap(),
            )
        })
        .collect();
    for (id, controllable, observable) in &flags {
        assert_eq!(*controllable, id != "t2" && id != "t6", "{id}");
        assert_eq!(*observable, id != "t4", "{id}");
    }
    // An id that is no transition is named.
    let run = run_codegen(["petri", "info", &net, "--uncontrollable", "t2,ma1"]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr
            .contains("--uncontrollable names `ma1`, which is a place, not a transition, of"),
        "{}",
        run.stderr
    );
    // A control file, located.
    let control = write(
        dir.path(),
        "c.toml",
        "uncontrollable = []\nunobservable = [\"t99\"]\n",
    );
    let run = run_codegen(["petri", "info", &net, "--control", &control]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr.contains("c.toml:2:17: `unobservable` in"),
        "{}",
        run.stderr
    );
    assert!(
        run.stderr.contains("names `t99`, which is no transition"),
        "{}",
        run.stderr
    );
    // Converted, the net carries the statement; a later one must agree.
    let run = run_codegen(["petri", "convert", &net, &out, "--uncontrollable", ""]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let (code, info) = run_json(["petri", "info", &out]);
    assert_eq!(code, 1, "{info}");
    assert!(info["transitions"]
        .as_array()
        .unwrap()
        .iter()
        .all(|t| t["controllable"] == true));
    let run = run_codegen(["petri", "info", &out, "--uncontrollable", "t3"]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr.contains(
            "transition `t3` is controllable in this file, but --uncontrollable lists it"
        ),
        "{}",
        run.stderr
    );
    // Synthesis with the statement.
    let run = run_codegen([
        "petri",
        "synth",
        &net,
        "--constraints",
        &constraints,
        "-o",
        &out,
        "--uncontrollable",
        "",
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    // Not both ways.
    let run = run_codegen([
        "petri",
        "info",
        &net,
        "--control",
        &control,
        "--uncontrollable",
        "",
    ]);
    assert_eq!(run.code, 2);
    assert!(run.stderr.contains("cannot be used with"), "{}", run.stderr);
}

#[test]
fn petri_synth_bounds_an_unbounded_buffer_and_checks_what_is_finite() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bounded.toml");
    let args = |extra: &[&str]| {
        let mut a: Vec<String> = [
            "petri",
            "synth",
            "models/petri/buffer.toml",
            "--constraints",
            "models/petri/buffer.constraints.toml",
            "-o",
            out.to_str().unwrap(),
        ]
        .map(String::from)
        .to_vec();
        a.extend(extra.iter().map(|s| s.to_string()));
        a
    };
    // The plant is unbounded (it was refused as such); the control place
    // is algebra, and within B ≤ 3 the plant is finite for supcon.
    let (code, report) = run_json(args(&["--transform"]));
    assert_eq!(code, 0, "{report}");
    let c1 = &report["control_places"][0];
    assert_eq!(c1["enforced_as"], "W1 + B ≤ 3");
    assert_eq!(
        c1["incidence"],
        serde_json::json!({ "start1": -1, "start2": 1 })
    );
    assert_eq!(c1["initial"], 3);
    assert_eq!(report["reachable_markings"], 14);
    assert_eq!(report["closed_loop_skipped"], serde_json::Value::Null);
    assert_eq!(report["supcon"]["same_language"], true);
    assert_eq!(report["supcon"]["skipped"], serde_json::Value::Null);

    // A constraint that leaves the buffer unbounded: the control place is
    // still given, the checks are skipped with the reason, exit 0.
    let loose = write(
        dir.path(),
        "loose.toml",
        "[[constraint]]\nname = \"one at a time in 2\"\nweights = { W2 = 1 }\nbound = 1\n",
    );
    let run = run_codegen([
        "petri",
        "synth",
        "models/petri/buffer.toml",
        "--constraints",
        &loose,
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stdout.contains(
            "closed loop: not checked (safeness, dead markings): net `two machines and a buffer` \
             is unbounded: place `B` grows without bound"
        ),
        "{}",
        run.stdout
    );
    assert!(
        run.stdout
            .contains("supcon on the reachability graph: not compared: the closed loop was not explored (it is unbounded)"),
        "{}",
        run.stdout
    );
    assert!(out.exists());

    // `info` gives the invariants of the unbounded plant, and says it is
    // not safe.
    let (code, info) = run_json(["petri", "info", "models/petri/buffer.toml"]);
    assert_eq!(code, 1);
    assert_eq!(info["reachable_markings"], serde_json::Value::Null);
    assert_eq!(info["safe"], false);
    assert!(info["not_explored"]
        .as_str()
        .unwrap()
        .contains("place `B` grows without bound"));
    assert_eq!(info["place_invariants"].as_array().unwrap().len(), 2);

    // 0 is not "no limit".
    let run = run_codegen([
        "petri",
        "info",
        "models/petri/mixers.toml",
        "--max-states",
        "0",
    ]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr.contains("the limit must be at least 1 marking"),
        "{}",
        run.stderr
    );
}

#[test]
fn petri_reach_never_merges_two_markings_whose_plain_names_coincide() {
    let dir = tempfile::tempdir().unwrap();
    // One token in `a+b`, or one each in `a` and `b`: both read `a+b`
    // plainly, and were one state with a self-loop.
    let net = write(
        dir.path(),
        "collide.toml",
        "name = \"collide\"\nplaces = [{ id = \"a\" }, { id = \"b\" }, { id = \"a+b\", tokens = 1 }]\n\
         transitions = [{ id = \"split\", controllable = true, input = { \"a+b\" = 1 }, output = { a = 1, b = 1 } }]\n",
    );
    let graph = dir.path().join("collide.gen");
    let run = run_codegen(["petri", "reach", &net, "-o", graph.to_str().unwrap()]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let a = read_automaton(&graph).unwrap();
    assert_eq!((a.num_states(), a.num_transitions()), (2, 1));
    assert_eq!(a.state_name(a.initial().unwrap()), "\"a+b\"");
}

/// `synth --symbolic` writes the small factory's guards; run on plant ∥
/// specifications, they enable exactly what the explicit supervisor
/// enables, state by state.
#[test]
fn synth_symbolic_writes_guards_that_act_as_the_explicit_supervisor() {
    use des_symbolic::guard_file::GuardFile;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sf.guards.toml");
    let (code, report) = synth_small_factory(&out, &["--symbolic"]);
    assert_eq!(code, 0, "{report}");
    // Exact counts are decimal strings: they outgrow JSON numbers.
    assert_eq!(report["supervisor_states"], "12");
    assert_eq!(report["reachable_states"], "18");
    assert_eq!(report["components"], 4);
    assert_eq!(report["guards"].as_array().unwrap().len(), 4);
    let text = std::fs::read_to_string(&out).unwrap();
    let file = GuardFile::parse(&text, &out).unwrap();
    for c in &file.components {
        let from_guards = dir.path().join(c.file.as_deref().unwrap());
        assert!(from_guards.exists(), "{}: {from_guards:?}", c.name);
    }

    let explicit = dir.path().join("sup.gen");
    let (code, report) = synth_small_factory(&explicit, &[]);
    assert_eq!(code, 0, "{report}");
    let sup = read_automaton(&explicit).unwrap();
    let parts: Vec<des::Automaton> = SMALL_FACTORY_PLANTS
        .iter()
        .chain(&SMALL_FACTORY_SPECS)
        .map(|p| read_automaton(&model(p)).unwrap())
        .collect();
    let mut compared = 0;
    for s in sup.states() {
        // The explicit supervisor names its states after the components'.
        let name = sup.state_name(s);
        let tuple: Vec<u32> = name
            .split('.')
            .zip(&parts)
            .map(|(x, a)| a.state_by_name(x).unwrap().0)
            .collect();
        for (_, ev) in sup.alphabet().iter().filter(|(_, e)| e.controllable) {
            let enabled = parts.iter().zip(&tuple).all(|(a, &x)| {
                a.alphabet()
                    .id(&ev.name)
                    .is_none_or(|e| a.successor(des::StateId(x), e).is_some())
            });
            let guarded = enabled && file.allows(&ev.name, &tuple).unwrap();
            let by_sup = sup
                .alphabet()
                .id(&ev.name)
                .and_then(|e| sup.successor(s, e))
                .is_some();
            assert_eq!(guarded, by_sup, "{} in {name}", ev.name);
            compared += 1;
        }
    }
    assert_eq!(compared, 12 * 4);

    // A guard file is named so; the explicit options do not apply.
    let (code, report) = synth_small_factory(&dir.path().join("sf.gen"), &["--symbolic"]);
    assert_eq!(code, 2);
    assert!(
        report["error"]
            .as_str()
            .unwrap()
            .contains("name the output `*.guards.toml`"),
        "{report}"
    );
    let mut args = vec!["synth", "--symbolic", "--minstate", "--plant"];
    args.extend(SMALL_FACTORY_PLANTS);
    args.extend(["-o", "x.guards.toml"]);
    let run = run_codegen(&args);
    assert_eq!(run.code, 2);
    assert!(run.stderr.contains("--minstate"), "{}", run.stderr);
}
