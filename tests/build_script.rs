//! The build-script path driven through a real `cargo build` of a throwaway
//! crate whose `build.rs` calls `codegen::build::Build`, as a user's
//! firmware crate does.

use e2e::{repo, Run};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The directive a hostile model file name tries to smuggle into the build.
const INJECTED: &str = "cargo:rustc-env=PWNED=1";

/// A crate `name` in a fresh directory (each test its own name: crates
/// of one name would share their build-script run in the shared target
/// directory): the conveyor project with its supervisor
/// synthesised from `plants = ["plant/*.toml"]`, the conveyor's three plant
/// models in `plant/` (plus `extra_plant`, a copy of the sensor, if given),
/// and a build script that generates the program.
fn conveyor_crate(name: &str, extra_plant: Option<&str>) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    let root = dir.path();
    let models = repo().join("models/conveyor");
    let write = |path: &Path, text: &str| std::fs::write(root.join(path), text).expect("write");
    for sub in ["plant", "spec", "src"] {
        std::fs::create_dir(root.join(sub)).expect("create dir");
    }
    for plant in ["sensor", "belt", "runon"] {
        std::fs::copy(
            models.join(format!("{plant}.toml")),
            root.join(format!("plant/{plant}.toml")),
        )
        .expect("copy plant");
    }
    if let Some(name) = extra_plant {
        std::fs::copy(models.join("sensor.toml"), root.join("plant").join(name))
            .expect("copy plant");
    }
    std::fs::copy(models.join("spec.toml"), root.join("spec/spec.toml")).expect("copy spec");
    let project =
        std::fs::read_to_string(repo().join("models/conveyor.plc.toml")).expect("project");
    let start = project
        .find("synthesize =")
        .expect("a synthesised supervisor");
    let end = start + project[start..].find('\n').expect("one line");
    let project = format!(
        "{}synthesize = {{ plants = [\"plant/*.toml\"], specs = [\"spec/spec.toml\"] }}{}",
        &project[..start],
        &project[end..]
    );
    write(Path::new("conveyor.plc.toml"), &project);
    write(
        Path::new("Cargo.toml"),
        &format!(
            "[package]\nname = {name:?}\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
             [dependencies]\nboards = {{ path = {:?} }}\nexecutor = {{ path = {:?} }}\n\n\
             [build-dependencies]\ncodegen = {{ path = {:?} }}\n\n[workspace]\n",
            repo().join("crates/boards"),
            repo().join("crates/executor"),
            repo().join("crates/codegen")
        ),
    );
    write(
        Path::new("build.rs"),
        "fn main() {\n    codegen::build::Build::new(\"conveyor.plc.toml\").generate_or_exit();\n}\n",
    );
    write(
        Path::new("src/lib.rs"),
        "//! The conveyor's program.\ninclude!(concat!(env!(\"OUT_DIR\"), \"/conveyor.rs\"));\n\
         /// What the build set `PWNED` to (a hostile file name's aim).\n\
         pub const PWNED: Option<&str> = option_env!(\"PWNED\");\n",
    );
    // The workspace's lock file pins the versions already built and cached,
    // so that the build runs offline.
    std::fs::copy(repo().join("Cargo.lock"), root.join("Cargo.lock")).expect("copy lock file");
    dir
}

/// `cargo build` of the crate at `dir`, into a target directory kept
/// between test runs (codegen is built once).
fn cargo_build(dir: &Path) -> Run {
    let target = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("build-script-crate");
    Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .args(["build", "--offline", "-vv", "--target-dir"])
        .arg(&target)
        .current_dir(dir)
        .env_remove("CARGO_TARGET_DIR")
        .output()
        .expect("cargo runs")
        .into()
}

#[test]
fn a_globbed_model_file_named_with_a_directive_is_refused_and_injects_nothing() {
    let hostile = format!("plant\n{INJECTED}.toml");
    let dir = conveyor_crate("conveyor-hostile", Some(&hostile));
    let run = cargo_build(dir.path());
    assert_ne!(run.code, 0, "the build must fail\n{}", run.stderr);
    let expected = format!(
        "error: {}:36:26: model file {:?} (matched by `plant/*.toml`): it holds the control \
         character U+000A; rename the file (a build script could not name it to cargo)",
        Path::new("conveyor.plc.toml").display(),
        Path::new("plant").join(&hostile),
    );
    assert!(
        run.stderr.contains(&expected),
        "expected `{expected}` in\n{}",
        run.stderr
    );
    // `-vv` shows every line the build script printed, prefixed
    // `[conveyor-hostile …]`: none may be the injected directive.
    assert!(
        !run.stdout.lines().chain(run.stderr.lines()).any(|line| {
            line.trim_start().starts_with(INJECTED) || line.contains(&format!("] {INJECTED}"))
        }),
        "an injected line reached cargo\n{}\n{}",
        run.stdout,
        run.stderr
    );
}

#[test]
fn the_same_crate_with_ordinary_file_names_builds() {
    let dir = conveyor_crate("conveyor-ordinary", None);
    let run = cargo_build(dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    for file in [
        "conveyor.plc.toml",
        "plant/belt.toml",
        "plant/runon.toml",
        "plant/sensor.toml",
        "spec/spec.toml",
    ] {
        // `-vv` shows each line the build script printed, on stdout.
        let line = format!("] cargo:rerun-if-changed={file}\n");
        assert!(run.stdout.contains(&line), "no `{line}` in\n{}", run.stdout);
    }
}
