//! `host-sim replay` as a user runs it: an inputs file in, `trace.csv` and
//! a VCD out, the same trace on both backends, and input errors located
//! at file and line.

mod common;

use common::waveform::{SaveFile, Waveform};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use vcd::VarType;

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

fn replay(inputs: &Path, out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .arg("replay")
        .arg(repo("models/press.plc.toml"))
        .arg("--inputs")
        .arg(inputs)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .expect("host-sim runs")
}

#[test]
fn press_cycle_replays_to_the_reviewed_trace_on_both_backends() {
    let dir = tempfile::tempdir().unwrap();
    let inputs = repo("models/press/cycle.inputs.csv");
    // The reviewed trace: the work cycle 1→2→3→4→6→2 with the lesson's
    // Moore outputs, the part sensor's 3-scan filter, then at_bottom in
    // state 2 (fault, safe outputs) and recovery by the reset button.
    let expected = std::fs::read_to_string(repo("models/press/cycle.trace.csv")).unwrap();
    for backend in ["table", "logic"] {
        let out = dir.path().join(format!("{backend}.csv"));
        let vcd = dir.path().join(format!("{backend}.vcd"));
        let result = replay(
            &inputs,
            &out,
            &["--backend", backend, "--vcd", vcd.to_str().unwrap()],
        );
        assert!(result.status.success(), "{result:?}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(
            stderr.contains("replayed 25 scans: 5 events executed, 4 scans in fault mode"),
            "{stderr}"
        );
        assert_eq!(
            std::fs::read_to_string(&out).unwrap(),
            expected,
            "{backend}"
        );
        let text = std::fs::read_to_string(&vcd).unwrap();
        assert!(text.contains("$timescale 1 ms $end"));
        let save_file = std::fs::read_to_string(vcd.with_extension("gtkw")).unwrap();
        assert!(save_file.contains(&format!("[dumpfile] \"{backend}.vcd\"")));
        assert_save_file_shows(
            &SaveFile::parse(&save_file),
            &Waveform::parse(text.as_bytes()),
        );
        // The reviewed trace's fault at 160 ms, the state it faulted in.
        let w = Waveform::parse(text.as_bytes());
        assert!(!w.at("stamping-press.fault", 150).bit());
        assert!(w.at("stamping-press.fault", 160).bit());
        assert_eq!(w.at("stamping-press.states.press", 160).text(), "2");
        assert!(w.at("stamping-press.inputs.auto_pb", 10).bit());
        assert!(w.at("stamping-press.outputs.down_sol", 50).bit());
        assert!(w.at("stamping-press.events.part_in", 50).bit());
    }
}

/// The `d` of every `<path>` whose `data-signal` is `signal`.
fn signal_paths<'a>(svg: &'a str, signal: &str) -> Vec<&'a str> {
    let key = format!("<path data-signal=\"{signal}\" d=\"");
    svg.match_indices(&key)
        .map(|(at, _)| {
            let rest = &svg[at + key.len()..];
            &rest[..rest.find('"').unwrap()]
        })
        .collect()
}

/// No line of `text` passes 120 characters.
fn assert_fits_a_terminal(text: &str) {
    for line in text.lines() {
        assert!(
            line.chars().count() <= 120,
            "{} chars: {line}",
            line.chars().count()
        );
    }
}

#[test]
fn timelines_fit_120_columns_unless_asked_wide_and_lose_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let result = Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args(args)
            .arg("--project")
            .arg(repo(if args[0] == "boiler" {
                "models/boiler/boiler.plc.toml"
            } else {
                "models/testbed/testbed.plc.toml"
            }))
            .output()
            .expect("host-sim runs");
        assert!(result.status.success(), "{result:?}");
        String::from_utf8(result.stdout).unwrap()
    };
    let vcd = dir.path().join("b.vcd");
    let vcd = vcd.to_str().unwrap();
    let narrow = run(&["boiler", "--scenario", "controller-stall", "--vcd", vcd]);
    let wide = run(&[
        "boiler",
        "--scenario",
        "controller-stall",
        "--vcd",
        vcd,
        "--wide",
    ]);
    assert_fits_a_terminal(&narrow);
    assert!(
        wide.lines().any(|l| l.chars().count() > 120),
        "the old layout"
    );
    // The same words, only laid out differently.
    let words = |text: &str| {
        let mut w: Vec<String> = text.split_whitespace().map(str::to_owned).collect();
        w.sort();
        w
    };
    assert_eq!(words(&narrow), words(&wide));
    let testbed = run(&["testbed", "laps"]);
    assert_fits_a_terminal(&testbed);
    assert!(testbed.contains("fault: none"), "{testbed}");
    let testbed_wide = run(&["testbed", "laps", "--wide"]);
    assert!(testbed_wide.lines().any(|l| l.chars().count() > 120));
}

/// The save file names only signals of the VCD, in the groups meant, and
/// every input, output, event, supervisor state and the fault among them.
fn assert_save_file_shows(save_file: &SaveFile, w: &Waveform) {
    let named: Vec<&str> = save_file.signals().collect();
    let declared: Vec<&str> = w.paths().collect();
    for signal in &named {
        assert!(declared.contains(signal), "{signal} is not in the VCD");
    }
    for path in declared {
        let shown = !path.contains(".state_numbers.");
        assert_eq!(named.contains(&path), shown, "{path}");
    }
    for group in ["inputs", "outputs", "events", "supervisor states", "fault"] {
        assert!(save_file.groups.iter().any(|g| g == group), "{group}");
    }
    for (group, _, signal) in &save_file.traces {
        let scope = match group.as_str() {
            "supervisor states" => ".states.",
            "fault" => ".fault",
            "analog" => ".plant.",
            other => &format!(".{other}"),
        };
        assert!(
            signal.contains(scope) || signal.ends_with(".last_events"),
            "{signal} in {group}"
        );
    }
}

/// `inputs/<name>` and `outputs/<name>` for every input and output of the
/// project at `path` (in the repository).
fn io_signals(path: &str) -> Vec<String> {
    let project = plc_project::load(&repo(path)).unwrap();
    let inputs = project.inputs.iter().map(|i| format!("inputs/{}", i.name));
    let outputs = project
        .outputs
        .iter()
        .map(|o| format!("outputs/{}", o.name));
    inputs.chain(outputs).collect()
}

#[test]
fn a_replay_draws_every_signal_as_one_path_with_events_states_and_the_fault() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("press.svg");
    let result = replay(
        &repo("models/press/cycle.inputs.csv"),
        &dir.path().join("t.csv"),
        &["--svg", svg.to_str().unwrap()],
    );
    assert!(result.status.success(), "{result:?}");
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.starts_with("<svg") && picture.ends_with("</svg>\n"));
    let signals = io_signals("models/press.plc.toml").into_iter().chain([
        "states/press".to_owned(),
        "events".into(),
        "fault".into(),
    ]);
    for signal in signals {
        assert_eq!(
            signal_paths(&picture, &signal).len(),
            1,
            "one path for {signal}"
        );
    }
    // A lane is its transitions: `top_ls` falls at 60 ms and rises at
    // 90 ms, two edges in 25 scans.
    let top_ls = signal_paths(&picture, "inputs/top_ls")[0];
    assert_eq!(top_ls.matches('V').count(), 2, "{top_ls}");
    // Five scans executed events: five marks, each named on hover.
    assert_eq!(signal_paths(&picture, "events")[0].matches('M').count(), 5);
    for event in ["auto", "part_in", "at_bottom", "at_top", "part_out"] {
        assert!(
            picture.contains(&format!(" ms: {event}</title>")),
            "{event}"
        );
    }
    // The states the press went through, named, and the fault's cause.
    for state in ["1", "2", "3", "4", "6"] {
        assert!(
            picture.contains(&format!("press = {state} from")),
            "{state}"
        );
    }
    assert!(picture.contains("fault from 160 ms: Unexpected:at_bottom"));
    assert_eq!(
        signal_paths(&picture, "fault-shading")[0]
            .matches('Z')
            .count(),
        1
    );
    // The time axis: 0 to 240 ms in steps of 50 ms.
    for tick in ["0 ms", "50 ms", "200 ms"] {
        assert!(picture.contains(&format!(">{tick}</text>")), "{tick}");
    }
    assert!(!picture.contains(">250 ms<"));

    // `record --svg` draws the same run the same way.
    let recorded = dir.path().join("recorded.svg");
    let result = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .arg("record")
        .arg(repo("models/press.plc.toml"))
        .arg("--inputs")
        .arg(repo("models/press/cycle.inputs.csv"))
        .arg("--out")
        .arg(dir.path().join("s.bin"))
        .arg("--svg")
        .arg(&recorded)
        .output()
        .unwrap();
    assert!(result.status.success(), "{result:?}");
    let paths = |svg: &str| -> Vec<String> {
        svg.lines()
            .filter(|l| l.starts_with("<path data-signal="))
            .map(str::to_owned)
            .collect()
    };
    let recorded = std::fs::read_to_string(&recorded).unwrap();
    assert_eq!(paths(&recorded), paths(&picture));
    assert!(!paths(&picture).is_empty());
}

#[test]
fn a_bom_and_quoted_fields_read_as_the_plain_file() {
    let dir = tempfile::tempdir().unwrap();
    let plain = std::fs::read_to_string(repo("models/press/cycle.inputs.csv")).unwrap();
    // A spreadsheet's export: byte-order mark, quoted header cells, CRLF.
    let exported = format!(
        "\u{feff}{}",
        plain
            .replacen(
                "scan,time_ms,auto_pb",
                "\"scan\",\"time_ms\",\"auto_pb\"",
                1
            )
            .replace('\n', "\r\n")
    );
    let inputs = dir.path().join("exported.csv");
    std::fs::write(&inputs, exported).unwrap();
    let out = dir.path().join("t.csv");
    let result = replay(&inputs, &out, &[]);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let expected = std::fs::read_to_string(repo("models/press/cycle.trace.csv")).unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), expected);
}

#[test]
fn a_time_gap_the_clock_cannot_compare_is_an_error_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let inputs = dir.path().join("gap.csv");
    let text = std::fs::read_to_string(repo("models/press/cycle.inputs.csv"))
        .unwrap()
        .replace("\n4,40,", "\n4,2147483688,");
    std::fs::write(&inputs, text.replace("\n5,50,", "\n5,2147483698,")).unwrap();
    let result = replay(&inputs, &dir.path().join("t.csv"), &[]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("gap.csv:6"), "{stderr}");
    assert!(stderr.contains("below 2^31 ms"), "{stderr}");
}

#[test]
fn a_bad_inputs_file_is_an_error_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let inputs = dir.path().join("bad.csv");
    let text = std::fs::read_to_string(repo("models/press/cycle.inputs.csv"))
        .unwrap()
        .replace("\n4,40,0,0,0,1,1,0\n", "\n4,40,0,0,0,2,1,0\n");
    std::fs::write(&inputs, text).unwrap();
    let result = replay(&inputs, &dir.path().join("t.csv"), &[]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("bad.csv:6"), "{stderr}");
    assert!(
        stderr.contains("`2` for input `part`: expected 0 or 1"),
        "{stderr}"
    );
    assert!(
        !dir.path().join("t.csv").exists(),
        "no trace from bad input"
    );
}

#[test]
fn boiler_main_job_prints_a_timeline_and_writes_waveforms() {
    let dir = tempfile::tempdir().unwrap();
    let vcd = dir.path().join("boiler.vcd");
    let svg = dir.path().join("boiler.svg");
    let result = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["boiler", "--scenario", "main-flame-failure", "--project"])
        .arg(repo("models/boiler/boiler.plc.toml"))
        .arg("--vcd")
        .arg(&vcd)
        .arg("--svg")
        .arg(&svg)
        .output()
        .expect("host-sim runs");
    assert!(result.status.success(), "{result:?}");
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(
        stdout.contains("purge_done pv_open trial_start ign_on"),
        "{stdout}"
    );
    assert!(stdout.contains("mf_off sd2 mv_off pv_close"), "{stdout}");
    assert!(
        stdout.contains("safety invariants: held on all 7500 scans"),
        "{stdout}"
    );
    assert_fits_a_terminal(&stdout);
    let w = Waveform::parse(&std::fs::read(&vcd).unwrap());
    let save_file =
        SaveFile::parse(&std::fs::read_to_string(dir.path().join("boiler.gtkw")).unwrap());
    assert_save_file_shows(&save_file, &w);
    assert_eq!(save_file.groups.last().map(String::as_str), Some("analog"));
    for (group, flags, signal) in &save_file.traces {
        let analog = group == "analog";
        assert_eq!(
            analog,
            signal.starts_with("boiler.plant.") && w.var_type(signal) == VarType::Real,
            "{signal}"
        );
        // Analog, interpolated (TR_ANALOG_INTERPOLATED), as a real (TR_REAL).
        assert_eq!(
            analog,
            flags & 0x5_0000 == 0x5_0000,
            "{signal} drawn with @{flags:x}"
        );
    }
    // The event label changes where an event wire pulses, and holds
    // until the next scan that executes events.
    let pulses: Vec<u64> = w
        .changes("boiler.events.mf_off")
        .iter()
        .filter(|(_, v)| *v == common::waveform::Sample::Bit(vcd::Value::V1))
        .map(|(t, _)| *t)
        .collect();
    assert_eq!(pulses.len(), 1);
    let label = w.at("boiler.last_events", pulses[0]).text().to_owned();
    assert!(label.contains("mf_off"), "{label}");
    let labels = w.changes("boiler.last_events");
    let next = labels
        .iter()
        .find(|(t, _)| *t > pulses[0])
        .map(|(t, _)| *t)
        .unwrap();
    assert_eq!(w.at("boiler.last_events", next - 1).text(), label);
    assert!(w.at("boiler.inputs.main_flame", 30_000).bit());
    assert!(!w.at("boiler.inputs.main_flame", 50_000).bit());
    assert_eq!(w.at("boiler.states.sup_bms", 0).text(), "normal");
    assert!(w.at("boiler.plant.bath_c", 60_000).real() > 20.0);
    assert!(w.at("boiler.plant.flue_c", 44_000).real() > 100.0);
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.starts_with("<svg") && picture.contains("main flame"));
    let sup_bms = signal_paths(&picture, "states/sup_bms");
    let signals = io_signals("models/boiler/boiler.plc.toml")
        .into_iter()
        .chain(["plant/pilot flame", "plant/main flame", "events", "fault"].map(String::from))
        .chain(
            [
                "bath/bath",
                "flue gas/flue gas",
                "power/firing",
                "power/load",
            ]
            .map(|a| format!("analog/{a}")),
        );
    for signal in signals {
        assert_eq!(
            signal_paths(&picture, &signal).len(),
            1,
            "one path for {signal}"
        );
    }
    assert_eq!(sup_bms.len(), 1);
    assert_eq!(picture.matches(r#"<path data-signal="states/"#).count(), 7);
    // The main flame's failure, named on hover at its mark.
    assert!(picture.contains(" ms: mf_off sd2 mv_off pv_close"));
    // Fixed scales with labelled ticks: the bath 0-100 °C, the flue gas
    // 0-300 °C, whatever the run.
    for tick in [">0 °C<", ">100 °C<", ">300 °C<", ">200 kW<", ">60 s<"] {
        assert!(picture.contains(tick), "{tick}");
    }
    // A size regression check, not a timing: the old picture, a point per
    // scan, was 822 KB for cold-start-high; this one keeps transitions.
    assert!(picture.len() < 64 * 1024, "{} bytes", picture.len());

    let unknown = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["boiler", "--scenario", "nope"])
        .output()
        .unwrap();
    assert_eq!(unknown.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("unknown scenario `nope`"));
}

#[cfg(unix)]
#[test]
fn inputs_and_projects_must_be_regular_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.csv");
    for path in des::testing::not_regular_files(dir.path(), "t.csv") {
        let shown = path.display().to_string();
        let record = |project: &Path, inputs: &Path| {
            Command::new(env!("CARGO_BIN_EXE_host-sim"))
                .arg("record")
                .arg(project)
                .arg("--inputs")
                .arg(inputs)
                .arg("--out")
                .arg(dir.path().join("s.bin"))
                .output()
                .unwrap()
        };
        let press = repo("models/press.plc.toml");
        let cycle = repo("models/press/cycle.inputs.csv");
        for (result, kind) in [
            (replay(&path, &out, &[]), "inputs file"),
            (record(&press, &path), "inputs file"),
            (record(&path, &cycle), "project file"),
        ] {
            assert_eq!(result.status.code(), Some(2));
            let stderr = String::from_utf8_lossy(&result.stderr);
            let expected = format!("{shown}: not a regular file (the {kind} must be a file");
            assert!(
                stderr.contains(&expected),
                "expected {expected}\ngot {stderr}"
            );
        }
    }
}

#[test]
fn a_field_beyond_the_record_limit_is_an_error_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let inputs = dir.path().join("long.csv");
    let mut text = std::fs::read_to_string(repo("models/press/cycle.inputs.csv")).unwrap();
    // 17 MiB of one field, one more than the limit allows.
    text.push_str(&format!("999,999999,{}\n", "1".repeat(17 << 20)));
    std::fs::write(&inputs, text).unwrap();
    let result = replay(&inputs, &dir.path().join("t.csv"), &[]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&result.stderr);
    let lines = std::fs::read_to_string(repo("models/press/cycle.inputs.csv"))
        .unwrap()
        .lines()
        .count();
    let expected = format!("long.csv:{}: a record longer than 16 MiB", lines + 1);
    assert!(
        stderr.contains(&expected),
        "expected {expected}\ngot {stderr}"
    );
}
