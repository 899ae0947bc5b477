//! What generation refuses is a variant of [`codegen::Error`] each, with
//! the location it is about attached once; the messages read as they
//! always have. (Nets on the other backends: `project_nets.rs`; the logic
//! backend's effort limit: `project.rs`; paths cargo would misread and
//! the emitters' own failures: the unit tests of `build.rs` and `emit`.)

use codegen::backend::Backend;
use codegen::build::Build;
use codegen::emit::generate;
use codegen::Error;
use des::automaton::AutomatonBuilder;
use plc_project::Project;
use std::path::{Path, PathBuf};

fn model(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(relative)
}

fn press() -> Project {
    plc_project::load(&model("press.plc.toml")).unwrap()
}

#[test]
fn a_count_past_the_executors_indices_names_the_project_file() {
    let mut project = press();
    // Outputs latched by actions: no pool grows with them, only the count.
    let more = usize::from(u16::MAX) + 1 - project.outputs.len();
    project
        .outputs
        .extend((0..more).map(|k| plc_project::Output {
            name: format!("extra_{k}"),
            safe: false,
            drive: plc_project::Drive::Actions { initial: false },
            line: 0,
        }));
    for backend in [Backend::Table, Backend::Match] {
        let err = generate(&project, backend, "").unwrap_err();
        assert!(
            matches!(
                &err,
                Error::TooMany { project: file, what: "outputs", limit: 65535 }
                    if *file == project.path
            ),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            format!(
                "{}: too many outputs for the executor (at most 65535)",
                project.path.display()
            )
        );
    }
}

#[test]
fn a_supervisor_without_an_initial_state_names_the_project_file() {
    let mut project = press();
    project.supervisors[0].automaton = AutomatonBuilder::new("none").build().unwrap();
    let name = project.supervisors[0].name.clone();
    let err = codegen::lower::TableImage::new(&project).unwrap_err();
    assert!(
        matches!(&err, Error::NoInitialState { supervisor, .. } if *supervisor == name),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        format!(
            "{}: supervisor `{name}` has no initial state",
            project.path.display()
        )
    );
}

#[test]
fn the_build_api_outside_a_build_script_needs_a_directory() {
    // Cargo sets `OUT_DIR` for build scripts and for crates with one;
    // codegen has none.
    assert_eq!(std::env::var_os("OUT_DIR"), None);
    let err = Build::new(model("press.plc.toml")).generate().unwrap_err();
    assert!(matches!(err, Error::NoOutDir), "{err:?}");
    assert_eq!(
        err.to_string(),
        "OUT_DIR is not set: call Build::generate from a build script or set out_dir"
    );
}

#[test]
fn an_invalid_project_is_the_front_ends_error_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.plc.toml");
    std::fs::write(&path, "[plc]\nname = \"broken\"\nscan_period_ms = 0\n").unwrap();
    let err = Build::new(&path)
        .out_dir(dir.path())
        .generate()
        .unwrap_err();
    let Error::Model(inner) = &err else {
        panic!("{err:?}");
    };
    let (location, _) = inner.located().expect("a located model error");
    assert_eq!(
        (location.file.as_path(), location.line),
        (path.as_path(), 3)
    );
    assert_eq!(
        err.to_string(),
        plc_project::load(&path).unwrap_err().to_string()
    );
    assert!(!dir.path().join("broken.rs").exists());
}

#[test]
fn a_board_build_refuses_a_project_without_a_pin_map_and_writes_nothing() {
    let out = tempfile::tempdir().unwrap();
    let fixture =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/project/press.plc.toml");
    let err = Build::new(&fixture)
        .out_dir(out.path())
        .require_board()
        .generate()
        .unwrap_err();
    assert!(
        matches!(&err, Error::NoBoard { project } if *project == fixture),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        format!(
            "{}: no [board] section: the board firmware needs the pin of each signal (see docs/board.md)",
            fixture.display()
        )
    );
    assert!(!out.path().join("press.rs").exists());
    // The seed press has its pin map.
    let (written, _) = Build::new(model("press.plc.toml"))
        .out_dir(out.path())
        .require_board()
        .generate()
        .unwrap();
    assert!(written.exists());
}
