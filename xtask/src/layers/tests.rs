//! The layering and circle checks on made-up workspaces and sources.

use super::crates::*;
use super::modules::*;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A made-up package's workspace dependencies: `(name, kind)`, the
/// kind as `cargo metadata` writes it (`None`: normal).
type Deps = Vec<(&'static str, Option<&'static str>)>;

/// `cargo metadata` output for a made-up workspace, every dependency
/// by path.
fn metadata(packages: &[(&str, Deps)]) -> String {
    let packages: Vec<serde_json::Value> = packages
        .iter()
        .map(|(name, deps)| {
            let deps: Vec<serde_json::Value> = deps
                .iter()
                .map(|(dep, kind)| {
                    serde_json::json!({
                        "name": dep,
                        "kind": kind,
                        "path": format!("/ws/crates/{dep}"),
                    })
                })
                .collect();
            serde_json::json!({
                "name": name,
                "manifest_path": format!("/ws/crates/{name}/Cargo.toml"),
                "dependencies": deps,
                "targets": [{"kind": ["lib"], "src_path": format!("/ws/crates/{name}/src/lib.rs")}],
            })
        })
        .collect();
    serde_json::json!({ "packages": packages, "workspace_root": "/ws" }).to_string()
}

/// The workspace as `LAYERS` allows it: every crate using all it may.
fn as_allowed() -> Vec<(&'static str, Deps)> {
    LAYERS
        .iter()
        .map(|l| {
            let deps = l
                .normal
                .iter()
                .map(|d| (*d, None))
                .chain(l.build.iter().map(|d| (*d, Some("build"))))
                .chain(l.dev.iter().map(|d| (*d, Some("dev"))))
                // A crate's own name in its dev-dependencies (features
                // for its tests).
                .chain([(l.name, Some("dev"))])
                .collect();
            (l.name, deps)
        })
        .collect()
}

fn failures_of(workspace: &[(&str, Deps)]) -> Vec<String> {
    let packages = parse_metadata(&metadata(workspace)).unwrap();
    let mut failures = crate_failures(&packages, LAYERS);
    failures.extend(stale_rows(&packages, LAYERS));
    failures
}

#[test]
fn the_table_respects_the_stages() {
    assert_eq!(table_failures(LAYERS), Vec::<String>::new());
}

#[test]
fn the_allowed_workspace_passes() {
    assert_eq!(failures_of(&as_allowed()), Vec::<String>::new());
}

/// The one failure of the allowed workspace plus `krate` → `dep`.
fn one_failure(krate: &str, dep: &'static str, kind: Option<&'static str>) -> String {
    let mut ws = as_allowed();
    let row = ws.iter_mut().find(|(n, _)| *n == krate).unwrap();
    row.1.push((dep, kind));
    let mut failures = failures_of(&ws);
    assert_eq!(
        failures.len(),
        1,
        "{krate} -> {dep} ({kind:?}): {failures:?}"
    );
    failures.remove(0)
}

#[test]
fn a_front_end_using_a_backend_fails() {
    let failure = one_failure("plc-project", "codegen", None);
    assert!(
        failure.starts_with(
            "crates/plc-project/Cargo.toml: `plc-project` (front end) depends on `codegen` \
             (backend) in [dependencies]; there it may use boards, des, des-symbolic, executor."
        ),
        "{failure}"
    );
}

#[test]
fn a_backend_using_another_backend_fails_in_every_kind() {
    for kind in [None, Some("build"), Some("dev")] {
        let failure = one_failure("codegen", "iec-export", kind);
        assert!(
            failure.contains("`codegen` (backend) depends on `iec-export` (backend)"),
            "{failure}"
        );
    }
}

#[test]
fn a_build_dependency_is_not_a_normal_one() {
    // The firmware's build script may use codegen; its code may not.
    let failure = one_failure("firmware", "codegen", None);
    assert!(
        failure.contains("there it may use boards, executor, field-update."),
        "{failure}"
    );
}

#[test]
fn unknown_and_missing_crates_fail() {
    let mut ws = as_allowed();
    ws.retain(|(n, _)| *n != "iec-st");
    ws.push(("board-data", vec![]));
    let failures = failures_of(&ws);
    assert_eq!(failures.len(), 2, "{failures:?}");
    assert!(failures[0].contains("`board-data` has no row in LAYERS"));
    assert!(failures[1].contains("a row for `iec-st`"));
}

#[test]
fn an_upward_arrow_in_the_table_fails() {
    const BAD: &[Layer] = &[
        Layer {
            name: "plc-project",
            stage: Stage::FrontEnd,
            normal: &["codegen"],
            build: &[],
            dev: &[],
        },
        Layer {
            name: "codegen",
            stage: Stage::Backend,
            normal: &["plc-project"],
            build: &[],
            dev: &["iec-export"],
        },
        Layer {
            name: "iec-export",
            stage: Stage::Backend,
            normal: &[],
            build: &[],
            dev: &[],
        },
    ];
    let failures = table_failures(BAD);
    assert_eq!(failures.len(), 1, "{failures:?}");
    assert!(failures[0].contains("lets `plc-project` (front end) use `codegen` (backend)"));
}

#[test]
fn manifest_lines_are_found_by_table() {
    let manifest = "[package]\nname = \"codegen\"\n\n[dependencies]\ndes = { path = \"../des\" }\nserde.workspace = true\n\n[target.'cfg(unix)'.dependencies]\nexecutor = { path = \"../executor\" }\n\n[dev-dependencies]\ndes = { path = \"../des\", features = [\"testing\"] }\n\n[build-dependencies.plc-project]\npath = \"../plc-project\"\n";
    assert_eq!(manifest_line(manifest, "des", Kind::Normal), Some(5));
    assert_eq!(manifest_line(manifest, "serde", Kind::Normal), Some(6));
    assert_eq!(manifest_line(manifest, "executor", Kind::Normal), Some(9));
    assert_eq!(manifest_line(manifest, "des", Kind::Dev), Some(12));
    assert_eq!(
        manifest_line(manifest, "plc-project", Kind::Build),
        Some(14)
    );
    assert_eq!(manifest_line(manifest, "codegen", Kind::Normal), None);
}

/// The workspace itself, through `cargo metadata` (no compilation).
#[test]
fn the_workspace_passes() {
    let packages = workspace_packages().unwrap();
    assert_eq!(crate_failures(&packages, LAYERS), Vec::<String>::new());
    assert_eq!(stale_rows(&packages, LAYERS), Vec::<String>::new());
    assert!(packages
        .iter()
        .all(|p| p.deps.iter().all(|d| d.line.is_some())));
}

/// A crate's files, from `(path under src/, text)` pairs.
fn tree(files: &[(&str, &str)]) -> BTreeMap<PathBuf, String> {
    files
        .iter()
        .map(|(p, t)| (Path::new("c/src").join(p), t.to_string()))
        .collect()
}

fn graph(files: &[(&str, &str)]) -> ModuleGraph {
    module_graph(&tree(files), Path::new("c/src/lib.rs")).unwrap()
}

fn edges(g: &ModuleGraph) -> Vec<String> {
    g.edges
        .iter()
        .map(|((a, b), s)| format!("{a}->{b} {}:{}", s.file.display(), s.line))
        .collect()
}

/// `a` and `b` name each other: through `super::super` in a
/// submodule and a `use crate::{…}` group across lines.
const CIRCLE: &[(&str, &str)] = &[
    (
        "lib.rs",
        "//! Root.\npub mod a;\nmod b;\nmod c;\npub use a::A;\n",
    ),
    ("a/mod.rs", "mod deep;\npub struct A;\n"),
    (
        "a/deep.rs",
        "// super::super::c is a comment\nfn f() -> super::super::b::B {\n    todo!()\n}\n",
    ),
    (
        "b.rs",
        "use crate::{\n    c::C,\n    a::{self, A},\n};\npub struct B;\n",
    ),
    ("c.rs", "pub struct C;\n"),
];

#[test]
fn a_circle_is_found_with_its_places() {
    let g = graph(CIRCLE);
    assert_eq!(
        edges(&g),
        [
            "a->b c/src/a/deep.rs:2",
            "b->a c/src/b.rs:3",
            "b->c c/src/b.rs:2"
        ]
    );
    let (failures, stale) = circle_failures("c", &g, &[]);
    assert!(stale.is_empty());
    assert_eq!(
        failures,
        ["`c`: import circle a -> b -> a (modules a, b)\n    \
          a -> b: c/src/a/deep.rs:2\n    b -> a: c/src/b.rs:3"]
    );
}

#[test]
fn no_circle_passes() {
    let mut files = CIRCLE.to_vec();
    files[2].1 = "fn f() -> super::super::c::C {\n    todo!()\n}\n";
    let g = graph(&files);
    assert_eq!(
        edges(&g),
        [
            "a->c c/src/a/deep.rs:1",
            "b->a c/src/b.rs:3",
            "b->c c/src/b.rs:2"
        ]
    );
    assert_eq!(circle_failures("c", &g, &[]), (vec![], vec![]));
}

#[test]
fn tests_comments_strings_and_binaries_are_not_code() {
    let g = graph(&[
        (
            "lib.rs",
            "mod a;\n#[cfg(feature = \"b\")] pub(crate) mod b;\n#[cfg(test)]\nmod tests;\n#[cfg(all(test, feature = \"x\"))]\n\nmod more;\n#[cfg(test)] mod also;\n",
        ),
        (
            "a.rs",
            "/* crate::b */\nconst S: &str = \"crate::b::X\";\nconst R: &str = r#\"super::b\"#;\nconst C: char = '\"';\n/// [`crate::b`]\nfn f<'a>(x: &'a str) {}\n#[cfg(test)]\nmod tests {\n    use crate::b::B;\n}\n",
        ),
        ("b.rs", "use crate::a;\n"),
        ("tests.rs", "use crate::{a, b};\n"),
        ("more.rs", "use crate::b;\n"),
        ("also.rs", "use crate::b;\n"),
        ("main.rs", "use crate::b;\n"),
    ]);
    assert_eq!(edges(&g), ["b->a c/src/b.rs:1"]);
    assert_eq!(g.modules, BTreeSet::from(["a".into(), "b".into()]));
}

#[test]
fn inline_modules_move_super() {
    // In `a::inner`, `super::b` is `a::b`, inside `a`; `super::super::b`
    // is the crate's `b`. An inline module of the root is a module.
    let g = graph(&[
        ("lib.rs", "mod a;\nmod b;\npub mod c {\n    use super::b;\n}\n"),
        (
            "a.rs",
            "mod inner {\n    use super::b;\n}\nmod other {\n    fn f() { super::super::c::g() }\n}\n",
        ),
        ("b.rs", ""),
    ]);
    assert_eq!(edges(&g), ["a->c c/src/a.rs:5", "c->b c/src/lib.rs:4"]);
}

#[test]
fn a_missing_module_file_is_an_error() {
    let err = module_graph(
        &tree(&[("lib.rs", "pub mod gone;\n")]),
        Path::new("c/src/lib.rs"),
    )
    .unwrap_err();
    assert_eq!(
        err,
        "c/src/lib.rs:1: `mod gone;` has neither gone.rs nor gone/mod.rs beside it"
    );
}

#[test]
fn known_cycles_let_one_edge_through_and_go_stale() {
    let g = graph(CIRCLE);
    assert_eq!(
        circle_failures("c", &g, &[("c", "a", "b")]),
        (vec![], vec![])
    );
    // Another crate's entry does not apply here.
    assert_eq!(circle_failures("c", &g, &[("d", "a", "b")]).0.len(), 1);
    // An edge that closes no circle is stale.
    let (failures, stale) = circle_failures("c", &g, &[("c", "a", "b"), ("c", "b", "c")]);
    assert!(failures.is_empty());
    assert_eq!(stale.len(), 1);
    assert!(stale[0].contains("`c`: b -> c through"), "{}", stale[0]);
}

#[test]
fn a_longer_circle_is_printed_in_order() {
    let g = graph(&[
        ("lib.rs", "mod a;\nmod b;\nmod c;\n"),
        ("a.rs", "use crate::b;\n"),
        ("b.rs", "use crate::c;\n"),
        ("c.rs", "use crate::a;\n"),
    ]);
    let (failures, _) = circle_failures("k", &g, &[]);
    assert_eq!(failures.len(), 1);
    assert!(
        failures[0].starts_with("`k`: import circle a -> b -> c -> a (modules a, b, c)"),
        "{}",
        failures[0]
    );
}
