//! The language verbs as a user runs them: `include`, `equal`, `compose`,
//! `project [--observer]` and `check --spec`, each in text and `--json`,
//! with exit code 0 when the property holds, 1 with a shortest
//! counterexample when it fails, and 2 for bad input.

mod common;

use common::{root, run, supervisor, BRSPEC, BUFSPEC, MACH1, MACH2};
use std::path::Path;
use std::process::Command;

const MODULE: &str = "crates/des/tests/fixtures/formats/smallfactory.wmod";

/// Exit code and JSON report of `codegen --json args…`.
fn run_json(args: &[&str]) -> (i32, serde_json::Value) {
    let mut all = vec!["--json"];
    all.extend(args);
    let (code, stdout, stderr) = run(&all);
    let value = serde_json::from_str(&stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}):\n{stdout}\nstderr:\n{stderr}"));
    (code, value)
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

#[test]
fn include_and_equal_give_a_shortest_string_and_the_side_that_has_it() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    let plant = dir.path().join("plant.gen").display().to_string();
    let (code, report) = run_json(&["compose", MACH1, MACH2, "-o", &plant]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["result"]["states"], 9);
    assert_eq!(report["state_names"], serde_json::json!(["MACH1", "MACH2"]));

    // The supervised behaviour is within the plant's, not the converse.
    let (code, report) = run_json(&["include", &sup, &plant]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["included"], true);
    assert_eq!(report["first"]["states"], 12);
    let (code, report) = run_json(&["include", &plant, &sup]);
    assert_eq!(code, 1, "{report}");
    assert_eq!(report["holds"], false);
    // M2 may not start before the buffer holds a part.
    let c = &report["counterexample"];
    assert_eq!(c["string"], serde_json::json!(["e21"]));
    assert_eq!(c["language"], "closed");
    let (code, text, _) = run(&["include", &plant, &sup]);
    assert_eq!(code, 1);
    assert_eq!(
        text,
        "plant ⊆ sup: NO: e21 is in L(plant) but not in L(sup)\n"
    );

    let (code, report) = run_json(&["equal", &sup, &plant]);
    assert_eq!(code, 1, "{report}");
    let d = &report["difference"];
    assert_eq!(d["string"], serde_json::json!(["e21"]));
    assert_eq!(
        (&d["language"], &d["in"]),
        (&"closed".into(), &"second".into())
    );
    let (code, text, _) = run(&["equal", &sup, &sup]);
    assert_eq!(code, 0);
    assert_eq!(
        text,
        format!("sup ({sup}) = sup ({sup}): yes (closed and marked languages)\n")
    );
}

#[test]
fn a_marked_difference_is_named_as_one() {
    let dir = tempfile::tempdir().unwrap();
    let a = write(
        dir.path(),
        "a.toml",
        "name = \"a\"\ninitial = \"0\"\nmarked = [\"0\", \"1\"]\ncontrollable = [\"go\"]\n\
         uncontrollable = []\ntransitions = [[\"0\", \"go\", \"1\"]]\n",
    );
    let b = write(
        dir.path(),
        "b.toml",
        "name = \"b\"\ninitial = \"0\"\nmarked = [\"0\"]\ncontrollable = [\"go\"]\n\
         uncontrollable = []\ntransitions = [[\"0\", \"go\", \"1\"]]\n",
    );
    let (code, text, _) = run(&["equal", &b, &a]);
    assert_eq!(code, 1);
    assert_eq!(text, "b = a: NO: go is in Lm(a) but not in Lm(b)\n");
    let (code, report) = run_json(&["include", &b, &a]);
    assert_eq!(code, 0, "{report}");
    let (code, report) = run_json(&["include", &a, &b]);
    assert_eq!(code, 1);
    assert_eq!(report["counterexample"]["language"], "marked");
}

#[test]
fn components_of_a_module_are_chosen_by_name() {
    // One name for both files, two for A and B in turn.
    let (code, report) = run_json(&["equal", MODULE, MODULE, "--component", "MACH1"]);
    assert_eq!(code, 0, "{report}");
    let args = [
        "include",
        MODULE,
        MODULE,
        "--component",
        "BUFSPEC",
        "--component",
        "MACH1",
    ];
    let (code, report) = run_json(&args);
    assert_eq!(code, 1, "{report}");
    assert_eq!(report["first"]["name"], "BUFSPEC");
    // Without a name, a module is refused with its components listed.
    let (code, _, stderr) = run(&["equal", MODULE, MACH1]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("MACH1, BUFSPEC, NEVER_E20_FIRST"),
        "{stderr}"
    );
    assert!(stderr.contains("--component NAME"), "{stderr}");
    let (code, _, stderr) = run(&["equal", MODULE, MODULE, "--component", "NOPE"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("no component `NOPE`"), "{stderr}");
}

#[test]
fn compose_keeps_the_named_components_and_refuses_beyond_max_states() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.toml").display().to_string();
    let args = [
        "compose",
        MODULE,
        MACH2,
        "--component",
        "MACH1",
        "-o",
        &out,
        "--name",
        "loop",
    ];
    let (code, text, stderr) = run(&args);
    assert_eq!(code, 0, "{stderr}");
    assert!(text.starts_with("composed:   MACH1, MACH2\n"), "{text}");
    let written = des::formats::read_automaton(Path::new(&out)).unwrap();
    assert_eq!((written.name(), written.num_states()), ("loop", 9));
    let (code, report) = run_json(&["compose", MACH1, MACH2, "-o", &out, "--max-states", "4"]);
    assert_eq!(code, 2);
    let error = report["error"].as_str().unwrap();
    assert!(
        error.contains("limit of 4 states (raise it with --max-states)"),
        "{error}"
    );
}

#[test]
fn project_checks_both_observer_properties_and_names_the_broken_promise() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    let out = dir.path().join("p.toml").display().to_string();
    // Only the machines' ends seen: after M1 and M2 have both been
    // busy once, the abstraction still offers M2's end at once.
    let args = [
        "project",
        &sup,
        "--keep",
        "e10,e20",
        "-o",
        &out,
        "--observer",
    ];
    let (code, report) = run_json(&args);
    assert_eq!(code, 1, "{report}");
    assert_eq!(report["projection"]["states"], 3);
    assert_eq!(report["keep"], serde_json::json!(["e10", "e20"]));
    let w = &report["observer"]["marked"]["witness"];
    assert_eq!(w["string"], serde_json::json!(["e11", "e10", "e21", "e22"]));
    assert_eq!(w["projected"], serde_json::json!(["e10"]));
    assert_eq!(w["continuation"], serde_json::json!(["e20"]));
    assert_eq!(report["observer"]["closed"]["holds"], false);
    let projection = des::formats::read_automaton(Path::new(&out)).unwrap();
    assert_eq!(projection.name(), "p");
    assert_eq!(
        projection.state_name(projection.initial().unwrap()),
        "{0.0.0.0,1.0.0.0,2.0.0.0}"
    );
    let (code, text, _) = run(&args);
    assert_eq!(code, 1);
    assert!(
        text.contains(
            "Lm-observer: NO: after e11 e10 e21 e22 (seen as e10), the projection promises e20 \
             to a marked state, but sup (in state 0.2.0.1) cannot reach a marked state along it"
        ),
        "{text}"
    );

    // Seeing all of M1: an observer.
    let args = [
        "project",
        &sup,
        "--keep",
        "e10,e11,e12,e13",
        "-o",
        &out,
        "--observer",
    ];
    let (code, text, _) = run(&args);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("Lm-observer: yes\nL-observer:  yes\n"),
        "{text}"
    );
    // Without --observer nothing is checked; `''` keeps no event.
    let (code, report) = run_json(&["project", &sup, "--keep", "", "-o", &out]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["projection"]["states"], 1);
    assert!(report.get("observer").is_none(), "{report}");
    // Seeing M2 only: after M1's e11 e10, the buffer is full, which the
    // projection (marked there) does not show.
    let args = [
        "project",
        &sup,
        "--keep",
        "e20,e21",
        "-o",
        &out,
        "--observer",
    ];
    let (code, text, _) = run(&args);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains(
            "Lm-observer: NO: after e11 e10 (seen as (the empty string)), the projection is \
             marked, but sup (in state 0.0.1.0) cannot reach a marked state by erased events alone"
        ),
        "{text}"
    );
}

#[test]
fn bad_input_is_exit_2_with_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let bad = write(
        dir.path(),
        "bad.toml",
        "name = \"m\"\ninitial = \"a\"\ncontrollable = [\"go\"]\nuncontrollable = []\n\
         transitions = [\n  [\"a\", \"go\", \"b\"],\n  [\"a\", \"stop\", \"b\"],\n]\n",
    );
    let out = dir.path().join("o.gen").display().to_string();
    for args in [
        vec!["include", &bad, MACH1],
        vec!["equal", MACH1, &bad],
        vec!["compose", MACH1, &bad, "-o", &out],
        vec!["project", &bad, "--keep", "go", "-o", &out],
        vec!["check", "--plant", MACH1, "--sup", MACH1, "--spec", &bad],
    ] {
        let (code, _, stderr) = run(&args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stderr.contains("bad.toml:7"), "{args:?}: {stderr}");
    }
    let (code, report) = run_json(&["project", MACH1, "--keep", "e11,nope", "-o", &out]);
    assert_eq!(code, 2);
    assert_eq!(
        report["error"],
        "projection: event `nope` is not in the alphabet of `MACH1`"
    );
}

#[test]
fn check_with_a_spec_decides_within_and_supremal() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    let check = |sups: &[&str]| {
        let mut args = vec!["check", "--plant", MACH1, MACH2, "--sup"];
        args.extend(sups);
        args.extend(["--spec", BUFSPEC, BRSPEC]);
        run_json(&args)
    };
    let (code, report) = check(&[&sup]);
    assert_eq!(code, 0, "{report}");
    let s = &report["specification"];
    assert_eq!((&s["within"], &s["supremal"]), (&true.into(), &true.into()));
    assert_eq!(s["supcon_states"], 12);
    assert_eq!(s["specs"], serde_json::json!(["BUFSPEC", "BRSPEC"]));

    // Within the specification and controllable, but stricter than supcon:
    // M1 starts at most once.
    let once = write(
        dir.path(),
        "once.toml",
        "name = \"once\"\ninitial = \"0\"\nmarked = [\"0\", \"1\"]\ncontrollable = [\"e11\"]\n\
         uncontrollable = []\ntransitions = [[\"0\", \"e11\", \"1\"]]\n",
    );
    let (code, report) = check(&[&sup, &once]);
    assert_eq!(code, 1, "{report}");
    let s = &report["specification"];
    assert_eq!(s["within"], true);
    assert_eq!(s["supremal"], false);
    let d = &s["difference"];
    assert_eq!(d["in"], "supcon");
    assert_eq!(d["string"].as_array().unwrap().last().unwrap(), "e11");

    // The buffer specification alone lets the breakdown order be broken.
    let (code, report) = check(&[BUFSPEC]);
    assert_eq!(code, 1, "{report}");
    let s = &report["specification"];
    assert_eq!(s["within"], false);
    assert_eq!(s["outside"]["language"], "closed");
    assert_eq!(s["difference"]["in"], "closed_loop");

    // Without --spec, the report has no such section.
    let (code, report) = run_json(&["check", "--plant", MACH1, MACH2, "--sup", &sup]);
    assert_eq!(code, 0, "{report}");
    assert!(report.get("specification").is_none(), "{report}");
}

#[test]
fn a_reader_that_stops_early_ends_every_language_verb_quietly_with_its_exit_code() {
    // `codegen … | head -0`: no panic, nothing on stderr, the same code.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.gen").display().to_string();
    let cases: [(Vec<&str>, i32); 5] = [
        (vec!["include", MACH1, MACH2], 1),
        (vec!["equal", MACH1, MACH1], 0),
        (vec!["compose", MACH1, MACH2, "-o", &out], 0),
        (
            vec!["project", MACH1, "--keep", "e10", "-o", &out, "--observer"],
            0,
        ),
        (
            vec![
                "check", "--plant", MACH1, MACH2, "--sup", BUFSPEC, "--spec", BUFSPEC,
            ],
            1,
        ),
    ];
    for (args, code) in cases {
        for json in [false, true] {
            let mut cmd = Command::new(env!("CARGO_BIN_EXE_codegen"));
            cmd.current_dir(root());
            if json {
                cmd.arg("--json");
            }
            let mut child = cmd
                .args(&args)
                .stdin(std::process::Stdio::null())
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .expect("the codegen binary runs");
            drop(child.stdout.take());
            let done = child.wait_with_output().unwrap();
            let stderr = String::from_utf8_lossy(&done.stderr);
            assert_eq!(stderr, "", "{args:?}");
            assert_eq!(done.status.code(), Some(code), "{args:?}");
        }
    }
}
