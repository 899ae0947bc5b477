//! `codegen verify` on the testbed of docs/seeds.md B (`models/testbed/`):
//! its 29 supervisors are controllable, each decided on its reduced
//! plant, and the paper's Fig. 5 read literally (`models/crane/
//! sup_crane1.toml`, without the other train's arrival self-looped) is
//! not, with a counterexample that is a string of the whole plant.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `.toml` files of `models/testbed/<sub>`, sorted, relative to the
/// repository root.
fn files(sub: &str) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root().join("models/testbed").join(sub))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .map(|n| format!("models/testbed/{sub}/{n}"))
        .collect();
    names.sort();
    names
}

fn verify(sups: &[String], json: bool) -> Output {
    verify_with(sups, json, &[])
}

fn verify_with(sups: &[String], json: bool, flags: &[&str]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_codegen"));
    cmd.current_dir(root());
    if json {
        cmd.arg("--json");
    }
    cmd.arg("verify")
        .args(flags)
        .arg("--plant")
        .args(files("plant"));
    cmd.arg("--sup").args(sups);
    cmd.output().expect("the codegen binary runs")
}

fn json(output: &Output) -> serde_json::Value {
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

#[test]
fn the_29_testbed_supervisors_are_controllable_on_their_reduced_plants() {
    let run = verify_with(&files("sup"), true, &["--nonblocking"]);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let report = json(&run);
    assert_eq!(report["plant_components"], 22);
    assert_eq!(report["holds"], true);
    let sups = report["supervisors"].as_array().unwrap();
    assert_eq!(sups.len(), 29);
    for s in sups {
        assert_eq!(s["controllable"], true, "{s}");
        assert_eq!(s["rounds"], 1, "{s}");
        let reduced = s["reduced_names"].as_array().unwrap().len();
        assert!((4..=7).contains(&reduced), "{s}");
    }
    let crane1 = sups
        .iter()
        .find(|s| s["supervisor"] == "sup_crane1")
        .unwrap();
    assert_eq!(
        crane1["reduced_names"],
        serde_json::json!([
            "crane1",
            "order_t1",
            "order_t2",
            "sensors_sw1",
            "train1",
            "train2"
        ])
    );
    assert_eq!(crane1["reduced_states"], 10816);
    // The closed loop with all 29 is small, and nonblocking.
    assert_eq!(report["closed_loop"]["states"], 12318);
    assert_eq!(report["closed_loop"]["nonblocking"], true);
}

#[test]
fn the_papers_section_figure_read_literally_blocks_the_testbed() {
    // models/crane/sup_section.toml counts any `run_t1` as entering the
    // section 13 -> 14, so train 1 leaving sensor 1 is held at sensor 2
    // for ever, and train 2 with it. Controllable, but blocking.
    let mut sups = files("sup");
    sups.push("models/crane/sup_section.toml".to_owned());
    let run = verify_with(&sups, true, &["--nonblocking"]);
    assert_eq!(run.status.code(), Some(1));
    let report = json(&run);
    let all = report["supervisors"].as_array().unwrap();
    assert_eq!(all.len(), 30);
    assert!(all.iter().all(|s| s["controllable"] == true));
    let closed = &report["closed_loop"];
    assert_eq!(closed["nonblocking"], false);
    assert_eq!(closed["blocking_path"], serde_json::json!(["run_t1"]));
    assert_eq!(closed["blocking_state"]["sup_section"], "t1_in");
    assert_eq!(closed["blocking_state"]["train1"], "moving");
}

#[test]
fn the_papers_crane_figure_read_literally_is_not_controllable() {
    let sup = vec!["models/crane/sup_crane1.toml".to_owned()];
    let run = verify(&sup, true);
    assert_eq!(run.status.code(), Some(1));
    let report = json(&run);
    let s = &report["supervisors"][0];
    assert_eq!(s["controllable"], false);
    let c = &s["counterexample"];
    // Train 1 is held at crane 1's sensor 13 when train 2 arrives there:
    // Fig. 5 has no transition for it.
    assert_eq!(c["witness"]["event"], "t2_at13");
    assert_eq!(c["witness"]["supervisor_state"], "train1");
    assert_eq!(s["plant_components"]["order_t1"], "at13");
    assert_eq!(s["plant_components"]["train2"], "moving");
    let path = c["witness"]["path"].as_array().unwrap();
    assert_eq!(path.len(), 54);
    assert_eq!(path.last().unwrap(), "run_t2");
    // The whole plant needs a request before switch 1 moves.
    let plant_path = c["plant_path"].as_array().unwrap();
    assert_eq!(plant_path.len(), path.len() + 1);
    assert_eq!(plant_path[0], "t1_req_sw1_d");

    let text = verify(&sup, false);
    let stdout = String::from_utf8(text.stdout).unwrap();
    assert!(stdout.contains("sup_crane1: NOT controllable"), "{stdout}");
    assert!(
        stdout.contains(
            "can do uncontrollable `t2_at13` but the supervisor (in state train1) disables it"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("as a string of the whole plant: t1_req_sw1_d sw1_d run_t1"),
        "{stdout}"
    );
    assert!(
        stdout.contains("1 supervisors on 22 plant components: 0 controllable, 1 not"),
        "{stdout}"
    );
}

#[test]
fn a_supervisor_event_in_no_plant_component_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(
        &bad,
        "name = \"bad\"\ninitial = \"0\"\ncontrollable = [\"fly_t1\"]\n",
    )
    .unwrap();
    let run = verify(&[bad.display().to_string()], false);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("`fly_t1`") && stderr.contains("no plant component"),
        "{stderr}"
    );

    std::fs::write(
        &bad,
        "name = \"bad\"\ninitial = \"0\"\ntransitions = [\n  [\"0\", \"x\"],\n]\n",
    )
    .unwrap();
    let run = verify(&[bad.display().to_string()], false);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("bad.toml:4"), "{stderr}");
}

#[test]
fn the_closed_loop_decided_on_bdds_agrees_with_the_explicit_one() {
    // Nonblocking: the same exact count, never building the closed loop.
    let run = verify_with(&files("sup"), true, &["--nonblocking", "--symbolic"]);
    assert_eq!(run.status.code(), Some(0));
    let closed = &json(&run)["closed_loop"];
    assert_eq!(closed["method"], "symbolic");
    assert_eq!(closed["states"], 12318);
    assert_eq!(closed["nonblocking"], true);
    assert!(closed.get("transitions").is_none());
    // Blocking with Fig. 6 read literally: a shortest string as long as
    // the explicit one (either train's first move blocks), into the state
    // where the section holds that train.
    let mut sups = files("sup");
    sups.push("models/crane/sup_section.toml".to_owned());
    let run = verify_with(&sups, true, &["--nonblocking", "--symbolic"]);
    assert_eq!(run.status.code(), Some(1));
    let closed = &json(&run)["closed_loop"];
    assert_eq!(closed["nonblocking"], false);
    let path = closed["blocking_path"].as_array().unwrap();
    assert_eq!(path.len(), 1, "{path:?}");
    let train = match path[0].as_str().unwrap() {
        "run_t1" => "t1",
        "run_t2" => "t2",
        other => panic!("{other}"),
    };
    assert_eq!(
        closed["blocking_state"]["sup_section"],
        format!("{train}_in")
    );
}
