//! The partial-observation verbs as a user runs them: `normal`,
//! `observable`, `supnorm`, `supconnorm`, with the observable events
//! listed or taken from the plant files' own attributes.

mod common;

use common::{run, supervisor, BRSPEC, BUFSPEC, MACH1, MACH2};

/// Every event of the small factory but the two machines' ends of work
/// (`e10`, `e20`).
const WITHOUT_ENDS: &str = "e11,e12,e13,e21,e22,e23";

fn json(args: &[&str]) -> (i32, serde_json::Value) {
    let mut all = vec!["--json"];
    all.extend(args);
    let (code, stdout, stderr) = run(&all);
    let value = serde_json::from_str(&stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}):\n{stdout}\n{stderr}"));
    (code, value)
}

/// `codegen --json VERB --plant MACH1 MACH2 --sup SUP [--observable LIST]`.
fn on_factory(verb: &str, sup: &str, observable: Option<&str>) -> (i32, serde_json::Value) {
    let mut args = vec![verb, "--plant", MACH1, MACH2, "--sup", sup];
    args.extend(
        observable
            .map(|o| ["--observable", o])
            .into_iter()
            .flatten(),
    );
    json(&args)
}

#[test]
fn normality_and_observability_fail_with_strings_that_look_alike() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    let all = "e10,e11,e12,e13,e20,e21,e22,e23";
    let (code, report) = on_factory("normal", &sup, Some(all));
    assert_eq!(
        (code, &report["normal"]),
        (0, &serde_json::json!(true)),
        "{report}"
    );
    let (code, report) = on_factory("normal", &sup, Some(WITHOUT_ENDS));
    assert_eq!(code, 1, "{report}");
    let looks = &report["violation"]["looks_like"];
    let erase = |v: &serde_json::Value| -> Vec<String> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|e| e.as_str().unwrap().to_owned())
            .filter(|e| e != "e10" && e != "e20")
            .collect()
    };
    // The two strings look the same to the observer.
    assert_eq!(
        erase(&looks["string"]),
        erase(&looks["look_alike"]),
        "{report}"
    );
    assert_ne!(looks["string"], looks["look_alike"]);
    let (code, report) = on_factory("observable", &sup, Some(WITHOUT_ENDS));
    assert_eq!(code, 1, "{report}");
    assert!(report["violation"]["event"].is_string(), "{report}");
}

#[test]
fn unobservable_events_come_from_the_plant_files_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    // MACH1 and MACH2 as TOML, their ends of work unobservable.
    let mut plants = Vec::new();
    for (file, end) in [(MACH1, "e10"), (MACH2, "e20")] {
        let toml = dir.path().join(format!("{end}.toml"));
        let toml = toml.to_str().unwrap().to_owned();
        assert_eq!(run(&["convert", file, &toml]).0, 0);
        let text = std::fs::read_to_string(&toml).unwrap();
        let text = text.replacen(
            "states = [",
            &format!("unobservable = [\"{end}\"]\nstates = ["),
            1,
        );
        std::fs::write(&toml, text).unwrap();
        plants.push(toml);
    }
    let (code, report) = json(&["normal", "--plant", &plants[0], &plants[1], "--sup", &sup]);
    assert_eq!(code, 1, "{report}");
    let observable: Vec<&str> = report["observable"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e.as_str().unwrap())
        .collect();
    assert!(
        !observable.contains(&"e10") && !observable.contains(&"e20"),
        "{observable:?}"
    );
    assert_eq!(observable.len(), 6);
    let (_, listed) = on_factory("normal", &sup, Some(WITHOUT_ENDS));
    assert_eq!(report["violation"], listed["violation"]);
}

#[test]
fn supconnorm_is_controllable_and_normal() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("scn.toml").display().to_string();
    let hidden = "e11,e12,e13,e21,e22,e23,e10";
    let (code, report) = json(&[
        "supconnorm",
        "--plant",
        MACH1,
        MACH2,
        "--spec",
        BUFSPEC,
        BRSPEC,
        "--observable",
        hidden,
        "-o",
        &out,
    ]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(report["empty"], false, "{report}");
    let (code, _, stderr) = run(&["check", "--plant", MACH1, MACH2, "--sup", &out]);
    assert_eq!(code, 0, "controllable and nonblocking: {stderr}");
    let (code, report) = on_factory("normal", &out, Some(hidden));
    assert_eq!(code, 0, "{report}");
    // Hiding a machine's start as well leaves nothing.
    let (code, report) = json(&[
        "supnorm",
        "--plant",
        MACH1,
        MACH2,
        "--spec",
        BUFSPEC,
        BRSPEC,
        "--observable",
        "e11",
        "-o",
        &out,
    ]);
    assert_eq!(
        (code, &report["empty"]),
        (0, &serde_json::json!(true)),
        "{report}"
    );
    let (code, _, stderr) = run(&[
        "normal",
        "--plant",
        MACH1,
        "--sup",
        &out,
        "--observable",
        "nope",
    ]);
    assert_eq!(code, 2, "{stderr}");
}

#[test]
fn synth_under_partial_observation_writes_the_projected_supervisor() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cell.toml").display().to_string();
    let files = [
        "models/breakdown/m1.toml",
        "models/breakdown/m2.toml",
        "models/breakdown/buffer.toml",
        "models/breakdown/zone.toml",
    ];
    let synth = |extra: &[&str]| {
        let mut args = vec!["synth", "--plant", files[0], files[1], "--spec"];
        args.extend(&files[2..]);
        args.extend(["-o", &out]);
        args.extend(extra);
        run(&args)
    };
    let (code, stdout, stderr) = synth(&[]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("supconnorm: 14 states"), "{stdout}");
    assert!(
        stdout.contains("observed:   10 states") && stdout.contains("`b1` unobservable"),
        "{stdout}"
    );
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(!written.contains("b1"), "{written}");
    assert!(
        written.contains("\"{working.idle.one.clear,down.idle.one.m1_down}\""),
        "{written}"
    );
    // With the plant, the written supervisor is controllable and
    // nonblocking; it is normal for the events the plant lets it see.
    let (code, _, stderr) = run(&["check", "--plant", files[0], files[1], "--sup", &out]);
    assert_eq!(code, 0, "{stderr}");
    // The same in JSON, and refused with reduction.
    let (code, stdout, _) = run(&[
        "--json", "synth", "--plant", files[0], files[1], "--spec", files[2], files[3], "-o", &out,
    ]);
    assert_eq!(code, 0);
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(report["unobservable"], serde_json::json!(["b1"]));
    assert_eq!(report["observed"]["states"], 10);
    let (code, _, stderr) = synth(&["--reduce"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("`b1` are unobservable"), "{stderr}");
}
