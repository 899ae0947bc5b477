//! Symbolic supervisors in projects: a guard file and a symbolic
//! `synthesize` load into components and guards; what cannot run is
//! refused at its line (docs/formats.md, "Symbolic supervisors").

/// A machine `M` (`idle -start-> busy -done-> idle`), a consumer `T`
/// that may `take` at any time, and a buffer spec `B` of one slot: `done`
/// fills it (never when full), `take` empties it, `start` it lets pass.
/// Since `done` is uncontrollable, the supervisor must hold `start` back
/// while the buffer is full: a guard no component states by itself.
const MACHINE: &str = r#"name = "M"
kind = "plant"
initial = "idle"
marked = ["idle"]
controllable = ["start"]
uncontrollable = ["done"]
states = ["idle", "busy"]
transitions = [["idle", "start", "busy"], ["busy", "done", "idle"]]
"#;

const TAKER: &str = r#"name = "T"
kind = "plant"
initial = "wait"
marked = ["wait"]
uncontrollable = ["take"]
states = ["wait"]
transitions = [["wait", "take", "wait"]]
"#;

const BUFFER: &str = r#"name = "B"
kind = "spec"
initial = "empty"
marked = ["empty"]
controllable = ["start"]
uncontrollable = ["done", "take"]
states = ["empty", "full"]
transitions = [["empty", "start", "empty"], ["full", "start", "full"], ["empty", "take", "empty"], ["empty", "done", "full"], ["full", "take", "empty"]]
"#;

/// The project's head: the events bound to inputs.
const HEAD: &str = r#"[plc]
name = "p"
[inputs]
done_in = {}
take_in = {}
[events]
done = { rising = "done_in" }
take = { rising = "take_in" }
start = { controllable = true }
"#;

/// A directory with the two models under `plant/` and `spec/`, and the
/// project `p.plc.toml` of `HEAD` and `supervisor`.
fn project(supervisor: &str) -> (tempfile::TempDir, Result<plc_project::Project, String>) {
    let dir = tempfile::tempdir().unwrap();
    for (sub, name, text) in [
        ("plant", "M", MACHINE),
        ("plant", "T", TAKER),
        ("spec", "B", BUFFER),
    ] {
        std::fs::create_dir_all(dir.path().join(sub)).unwrap();
        std::fs::write(dir.path().join(sub).join(format!("{name}.toml")), text).unwrap();
    }
    let path = dir.path().join("p.plc.toml");
    std::fs::write(&path, format!("{HEAD}{supervisor}")).unwrap();
    let loaded = plc_project::load(&path).map_err(|e| e.to_string());
    (dir, loaded)
}

/// The guard file `codegen synth --symbolic` writes for the models in
/// `dir`, each component naming its file.
fn guard_file(dir: &std::path::Path) -> des_symbolic::guard_file::GuardFile {
    let read = |files: &[&str]| -> Vec<des::Automaton> {
        files
            .iter()
            .flat_map(|f| des::formats::read_file(&dir.join(f)).unwrap())
            .map(|c| c.automaton)
            .collect()
    };
    let plants = read(&["plant/M.toml", "plant/T.toml"]);
    let specs = read(&["spec/B.toml"]);
    let synthesis = des_symbolic::synthesize(&plants, &specs).unwrap();
    let mut file = des_symbolic::guard_file::GuardFile::new("cell", &synthesis, &plants, &specs);
    for (c, path) in file
        .components
        .iter_mut()
        .zip(["plant/M.toml", "plant/T.toml", "spec/B.toml"])
    {
        c.file = Some(path.into());
    }
    file
}

const SYMBOLIC: &str = "[[supervisor]]\nname = \"cell\"\nsynthesize = { plants = [\"plant/*.toml\"], specs = [\"spec/*.toml\"], symbolic = true }\n";

#[test]
fn a_symbolic_synthesis_runs_its_components_and_guards_start() {
    let (_dir, p) = project(SYMBOLIC);
    let p = p.unwrap();
    let names: Vec<&str> = p.supervisors.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["cell.M", "cell.T", "cell.B"]);
    let g = &p.guarded[0];
    assert_eq!((g.name.as_str(), g.components.clone()), ("cell", 0..3));
    let start = p.event("start").unwrap();
    // `start` only while the buffer is empty: B = empty is state 0.
    assert!(g.allows(start, &[0, 0, 0]));
    assert!(!g.allows(start, &[0, 0, 1]));
    // Uncontrollable events have no guard.
    assert!(g.guards.iter().all(|x| p.events[x.event].controllable));
}

#[test]
fn a_guard_file_runs_as_written_and_its_problems_are_located() {
    let (dir, p) = project(SYMBOLIC);
    let p = p.unwrap();
    // The guard file `codegen synth --symbolic` would write, from the
    // same synthesis.
    let file = guard_file(dir.path());
    let write = |f: &des_symbolic::guard_file::GuardFile| {
        std::fs::write(dir.path().join("cell.guards.toml"), f.to_toml()).unwrap();
        std::fs::write(
            dir.path().join("p.plc.toml"),
            format!("{HEAD}[[supervisor]]\nguards = \"cell.guards.toml\"\n"),
        )
        .unwrap();
        plc_project::load(&dir.path().join("p.plc.toml")).map_err(|e| e.to_string())
    };
    let from_file = write(&file).unwrap();
    assert_eq!(from_file.guarded[0].guards, p.guarded[0].guards);
    assert_eq!(from_file.guarded[0].bits, p.guarded[0].bits);

    // States in another order than the file's: the guards would read the
    // wrong numbers.
    let mut swapped = file.clone();
    swapped.components[2].states.reverse();
    let e = write(&swapped).unwrap_err();
    assert!(
        e.contains("p.plc.toml:11:") && e.contains("synthesise the guards again"),
        "{e}"
    );

    // A component without its model file.
    let mut unnamed = file.clone();
    unnamed.components[0].file = None;
    let e = write(&unnamed).unwrap_err();
    assert!(
        e.contains("p.plc.toml:11:") && e.contains("names no `file`"),
        "{e}"
    );

    // A guard of an event the project does not declare.
    let mut stranger = file.clone();
    stranger.guards[0].event = "unknown".into();
    let e = write(&stranger).unwrap_err();
    assert!(e.contains("not declared in [events]"), "{e}");
}

#[test]
fn a_guard_on_an_uncontrollable_event_is_refused_at_the_event() {
    let (dir, p) = project(SYMBOLIC);
    drop(p);
    // `take` declared controllable in the models would disagree with the
    // project; so guard `done`, which the project reads as an edge.
    let mut file = guard_file(dir.path());
    file.guards[0].event = "done".into();
    std::fs::write(dir.path().join("cell.guards.toml"), file.to_toml()).unwrap();
    let path = dir.path().join("p.plc.toml");
    std::fs::write(
        &path,
        format!("{HEAD}[[supervisor]]\nguards = \"cell.guards.toml\"\n"),
    )
    .unwrap();
    let e = plc_project::load(&path).unwrap_err().to_string();
    // `done` is declared on line 7.
    assert!(
        e.contains("p.plc.toml:7:") && e.contains("uncontrollable"),
        "{e}"
    );
}

#[test]
fn what_a_symbolic_synthesis_cannot_take_is_refused_at_its_line() {
    let cases = [
        (
            "[[supervisor]]\nsynthesize = { plants = [\"plant/*.toml\"], symbolic = true }\n",
            ":10:",
            "needs `name",
        ),
        (
            "[[supervisor]]\nname = \"c\"\nsynthesize = { plants = [\"plant/*.toml\"], minimize = true, symbolic = true }\n",
            ":12:",
            "`minimize`",
        ),
        (
            "[[supervisor]]\nname = \"c\"\nsynthesize = { plants = [\"plant/*.toml\"], max_states = 9, symbolic = true }\n",
            ":12:",
            "`max_states`",
        ),
        (
            "[[supervisor]]\nname = \"c\"\nguards = \"x.guards.toml\"\nfile = \"plant/M.toml\"\n",
            ":13:",
            "no `file` or `component`",
        ),
        (
            "[[supervisor]]\nname = \"c\"\nguards = \"missing.guards.toml\"\n",
            ":12:",
            "cannot read guard file",
        ),
    ];
    for (supervisor, line, message) in cases {
        let (_dir, p) = project(supervisor);
        let e = p.unwrap_err();
        assert!(
            e.contains(&format!("p.plc.toml{line}")) && e.contains(message),
            "{supervisor}: {e}"
        );
    }
}
