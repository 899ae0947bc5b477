//! host-sim in a pipeline whose reader has gone (`host-sim boiler | head`,
//! `2>&-`): like any Unix tool it stops writing there, without a panic,
//! does the rest of its work and exits with the status of that work.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

/// The write end of a pipe nobody reads any more: its only reader (`true`)
/// has exited before host-sim starts, so every write host-sim makes to it
/// fails with a broken pipe, whatever the timing.
fn closed_pipe() -> Stdio {
    let mut reader = Command::new("true")
        .stdin(Stdio::piped())
        .spawn()
        .expect("`true` runs");
    let writer = reader.stdin.take().unwrap();
    assert!(reader.wait().unwrap().success());
    Stdio::from(writer)
}

fn host_sim(args: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_host-sim"));
    command.args(args);
    command
}

/// Runs `command` with its standard output going nowhere.
fn stdout_closed(mut command: Command) -> Output {
    command
        .stdout(closed_pipe())
        .output()
        .expect("host-sim runs")
}

/// Runs `command` with its standard error going nowhere.
fn stderr_closed(mut command: Command) -> Output {
    command
        .stderr(closed_pipe())
        .output()
        .expect("host-sim runs")
}

fn assert_quiet_success(result: &Output) {
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(result.status.success(), "{result:?}");
}

#[test]
fn the_boiler_timeline_into_a_closed_pipe_still_writes_the_waveforms() {
    let dir = tempfile::tempdir().unwrap();
    let vcd = dir.path().join("boiler.vcd");
    let svg = dir.path().join("boiler.svg");
    let mut command = host_sim(&["boiler", "--project"]);
    command
        .arg(repo("models/boiler/boiler.plc.toml"))
        .arg("--vcd")
        .arg(&vcd)
        .arg("--svg")
        .arg(&svg);
    let result = stdout_closed(command);
    assert_quiet_success(&result);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("wrote") && stderr.contains("boiler.svg"),
        "{stderr}"
    );
    assert!(std::fs::read_to_string(&vcd)
        .unwrap()
        .contains("$enddefinitions"));
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
}

#[test]
fn the_scenario_list_into_a_closed_pipe_ends_quietly() {
    let result = stdout_closed(host_sim(&["boiler", "--list"]));
    assert_quiet_success(&result);
    assert!(result.stderr.is_empty(), "{result:?}");
}

#[test]
fn help_and_version_into_a_closed_pipe_end_quietly() {
    for args in [&["--help"][..], &["--version"], &["boiler", "--help"]] {
        let result = stdout_closed(host_sim(args));
        assert_quiet_success(&result);
    }
}

#[test]
fn replay_and_record_report_into_a_closed_pipe_and_still_write_their_files() {
    let dir = tempfile::tempdir().unwrap();
    let trace = dir.path().join("trace.csv");
    let mut replay = host_sim(&["replay"]);
    replay
        .arg(repo("models/press.plc.toml"))
        .arg("--inputs")
        .arg(repo("models/press/cycle.inputs.csv"))
        .arg("--out")
        .arg(&trace);
    let result = stderr_closed(replay);
    assert!(result.status.success(), "{result:?}");
    assert_eq!(
        std::fs::read_to_string(&trace).unwrap(),
        std::fs::read_to_string(repo("models/press/cycle.trace.csv")).unwrap()
    );

    let scenario = dir.path().join("crane.scenario");
    let mut record = host_sim(&["record", "--random", "100"]);
    record
        .arg(repo("models/crane.plc.toml"))
        .arg("--out")
        .arg(&scenario);
    let result = stderr_closed(record);
    assert!(result.status.success(), "{result:?}");
    assert!(!std::fs::read(&scenario).unwrap().is_empty());
}

#[test]
fn a_failure_into_a_closed_pipe_keeps_its_exit_status() {
    let result = stderr_closed(host_sim(&["boiler", "--scenario", "nope"]));
    assert_eq!(result.status.code(), Some(2), "{result:?}");
}
