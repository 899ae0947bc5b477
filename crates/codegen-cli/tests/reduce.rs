//! `codegen reduce` and `codegen localize` as a user runs them: the
//! small factory's supervisor reduced and localized, and `check --spec`
//! confirming that beside the plant they give supcon's closed loop.

mod common;

use common::{run, supervisor, BRSPEC, BUFSPEC, MACH1, MACH2};

/// `check --spec` of `sups` beside the plant: their closed loop has
/// supcon's languages. (A local controller alone may block an
/// uncontrollable event where the others never let the plant go, so
/// `check` may still find one uncontrollable taken alone.)
fn is_supcons_closed_loop(sups: &[&str]) -> bool {
    let mut args = vec!["--json", "check", "--plant", MACH1, MACH2, "--sup"];
    args.extend(sups);
    args.extend(["--spec", BUFSPEC, BRSPEC]);
    let (code, stdout, stderr) = run(&args);
    let report: serde_json::Value = serde_json::from_str(&stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}):\n{stdout}\n{stderr}"));
    assert!(code == 0 || code == 1, "{stderr}");
    report["specification"]["supremal"] == true
}

#[test]
fn a_reduced_supervisor_gives_the_plant_supcons_closed_loop() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    let reduced = dir.path().join("small.toml").display().to_string();
    let (code, stdout, stderr) = run(&[
        "reduce", "--plant", MACH1, MACH2, "--sup", &sup, "-o", &reduced,
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("reduced:    3 states"), "{stdout}");
    assert!(stdout.contains("checked equal"), "{stdout}");
    let text = std::fs::read_to_string(&reduced).unwrap();
    assert!(text.contains("name = \"small\""), "{text}");
    assert!(is_supcons_closed_loop(&[&sup]));
    assert!(is_supcons_closed_loop(&[&reduced]));
    // Controllable and nonblocking on its own too.
    let (code, _, stderr) = run(&["check", "--plant", MACH1, MACH2, "--sup", &reduced]);
    assert_eq!(code, 0, "{stderr}");
    // The reduced supervisor alone is not the plant: beside a plant it
    // was not reduced against, it is no longer supcon's.
    assert!(!is_supcons_closed_loop(&[MACH1]));
}

#[test]
fn local_controllers_together_give_the_plant_supcons_closed_loop() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    let module = dir.path().join("local.wmod").display().to_string();
    let (code, stdout, stderr) = run(&[
        "--json", "localize", "--plant", MACH1, MACH2, "--sup", &sup, "-o", &module,
    ]);
    assert_eq!(code, 0, "{stderr}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let events: Vec<&str> = report["controllers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["event"].as_str().unwrap())
        .collect();
    assert_eq!(
        events,
        ["e11", "e13", "e21", "e23"],
        "one per controllable event"
    );
    assert!(report["total_states"].as_u64().unwrap() <= 8, "{report}");
    assert!(is_supcons_closed_loop(&[&module]));
    // One local controller alone is not enough.
    let out_dir = dir.path().join("each");
    let (code, _, stderr) = run(&[
        "localize",
        "--plant",
        MACH1,
        MACH2,
        "--sup",
        &sup,
        "--output-dir",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let mut files: Vec<String> = std::fs::read_dir(&out_dir)
        .unwrap()
        .map(|e| e.unwrap().path().display().to_string())
        .collect();
    files.sort();
    assert_eq!(files.len(), 4);
    assert!(!is_supcons_closed_loop(&[&files[0]]));
    let both: Vec<&str> = files.iter().map(String::as_str).collect();
    assert!(is_supcons_closed_loop(&both));
}

#[test]
fn bad_input_is_refused_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let sup = supervisor(dir.path());
    let one_file = dir.path().join("local.gen").display().to_string();
    let (code, _, stderr) = run(&[
        "localize", "--plant", MACH1, MACH2, "--sup", &sup, "-o", &one_file,
    ]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("needs a format holding several"),
        "{stderr}"
    );
    let (code, _, stderr) = run(&[
        "reduce", "--plant", "nope.gen", "--sup", &sup, "-o", &one_file,
    ]);
    assert_eq!(code, 2);
    assert!(stderr.contains("nope.gen"), "{stderr}");
}

/// `codegen plcopen --ladder` on the AGV: its full ladder (11,349 rungs)
/// is over a limit of 800, the reduced one (3,100) too, the localized one
/// (750) fits: standard error says so, and the file holds the local
/// controllers in the program and in the ladder, whose documentation
/// names what was localized. Under 700 nothing fits, and the refusal
/// lists both forms tried.
#[test]
fn the_ladder_export_falls_back_on_the_localized_agv() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("agv.xml").display().to_string();
    let (code, stdout, stderr) = run(&[
        "plcopen",
        "models/agv.plc.toml",
        "--ladder",
        "--max-rungs",
        "800",
        "-o",
        &out,
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert!(
        stderr.contains(
            "models/agv.plc.toml: the ladder and the program export the localized form (`localize = true`): \
             supervisor 'agv' (synthesised, 4406 states) runs localized as 10 local controllers"
        ) && stderr.contains("750 rungs, where the full ladder would have 11349, over the limit of 800"),
        "{stderr}"
    );
    let xml = std::fs::read_to_string(&out).unwrap();
    assert!(
        xml.contains("X_agv_e11_"),
        "the ladder's state bits are the local controllers'"
    );
    assert!(xml.contains("runs localized as 10 local controllers"));
    let (code, _, stderr) = run(&[
        "plcopen",
        "models/agv.plc.toml",
        "--ladder",
        "--max-rungs",
        "700",
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("models/agv.plc.toml:96:1: the ladder (LD) rendering would have 11349 rungs, over the limit of 700")
            && stderr.contains("tried reduced (`reduce = true`): 3100 rungs; tried localized (`localize = true`): 750 rungs"),
        "{stderr}"
    );
}
