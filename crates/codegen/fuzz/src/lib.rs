//! The body of the `fuzz_project` target, a plain function so that the
//! stable test suite runs it too (`crates/codegen/tests/fuzz_project.rs`
//! includes this file).
//!
//! The input is the text of a project file, read as if it lay in a
//! directory holding the model directories of the seed projects
//! ([`model_root`]), so that the seeds and their mutations find real
//! models. What must hold, whatever the text:
//!
//! - nothing panics;
//! - a project that fails gets an error that names a file (located at a
//!   line of it where the format has lines);
//! - a project that validates can be named to cargo (every file on a
//!   `rerun-if-changed` line), has a table image that passes the executor's
//!   structure check with its CRC and starts a controller without a fault,
//!   and generates on the table and `match` backends: code with no two
//!   items of one module under one name, and in every name module
//!   (`input`, `output`, `timer`, `event`, `supervisor`) one index constant
//!   per name, numbered in declaration order, with `NAMES` holding the
//!   names exactly and `COUNT` their number.
//!
//! Model paths that leave the directory (absolute, or through `..`) are
//! not followed: that would fuzz the machine's file system, not the
//! project reader.

use codegen::backend::Backend;
use codegen::emit::generate;
use codegen::lower::TableImage;
use executor::memory::HeapMemory;
use executor::program::Program;
use executor::validate::{validate, validate_allowed_sets};
use executor::Controller;
use plc_project::{self as project, Project};
use std::collections::HashSet;
use std::path::{Component, Path};

/// The model directories of the seed projects: where a project file in
/// the fuzzing directory finds each (the name its projects use), and where
/// it lies in the repository.
pub const MODEL_DIRS: [(&str, &str); 12] = [
    ("press", "models/press"),
    ("conveyor", "models/conveyor"),
    ("crane", "models/crane"),
    ("motivating", "models/motivating"),
    ("bench", "models/bench"),
    ("plant", "models/boiler/plant"),
    ("spec", "models/boiler/spec"),
    ("sup", "models/boiler/sup"),
    ("cell", "crates/codegen/tests/fixtures/project/cell"),
    ("mini", "crates/codegen/tests/fixtures/project/mini"),
    ("factory", "crates/codegen/tests/fixtures/project/factory"),
    (
        "formats_example",
        "crates/codegen/tests/fixtures/project/formats_example",
    ),
];

/// The seed projects, relative to the repository: every project file of
/// `models/` and of the codegen test fixtures.
pub const SEED_PROJECTS: [&str; 11] = [
    "models/agv.plc.toml",
    "models/conveyor.plc.toml",
    "models/crane.plc.toml",
    "models/motivating.plc.toml",
    "models/press.plc.toml",
    "models/press7.plc.toml",
    "models/boiler/boiler.plc.toml",
    "models/boiler/boiler_mono.plc.toml",
    "crates/codegen/tests/fixtures/project/cell.plc.toml",
    "crates/codegen/tests/fixtures/project/factory.plc.toml",
    "crates/codegen/tests/fixtures/project/press.plc.toml",
];

/// Fills `root` with copies of the [`MODEL_DIRS`] of the repository at
/// `repo` (overwriting older copies).
pub fn model_root(repo: &Path, root: &Path) -> std::io::Result<()> {
    fn copy(from: &Path, to: &Path) -> std::io::Result<()> {
        std::fs::create_dir_all(to)?;
        for entry in std::fs::read_dir(from)? {
            let entry = entry?;
            let target = to.join(entry.file_name());
            if entry.file_type()?.is_dir() {
                copy(&entry.path(), &target)?;
            } else {
                std::fs::copy(entry.path(), target)?;
            }
        }
        Ok(())
    }
    for (name, dir) in MODEL_DIRS {
        copy(&repo.join(dir), &root.join(name))?;
    }
    Ok(())
}

/// Some string of `value` is a path out of the directory.
fn leaves_directory(value: &toml::Value) -> bool {
    match value {
        toml::Value::String(s) => {
            let path = Path::new(s);
            path.has_root()
                || path
                    .components()
                    .any(|c| matches!(c, Component::ParentDir | Component::Prefix(_)))
        }
        toml::Value::Array(items) => items.iter().any(leaves_directory),
        toml::Value::Table(table) => table.values().any(leaves_directory),
        _ => false,
    }
}

/// Checks `text` as the project file `fuzz.plc.toml` of `root` (see the
/// module docs); panics when anything that must hold does not.
pub fn check_project(text: &str, root: &Path) {
    if let Ok(table) = text.parse::<toml::Table>() {
        if table.values().any(leaves_directory) {
            return;
        }
    }
    let path = root.join("fuzz.plc.toml");
    match project::from_str(text, &path) {
        Ok(project) => check_valid(&project, &path),
        Err(e) => check_error(&e, text, &path),
    }
}

/// A refused project: the error names a file, and a line of the project
/// file that exists.
fn check_error(e: &des::Error, text: &str, path: &Path) {
    use des::Error;
    let message = e.to_string();
    match e {
        Error::Syntax { location, .. } | Error::Model { location, .. } => {
            assert!(!location.file.as_os_str().is_empty(), "{message}");
            if location.file == path {
                let lines = text.lines().count().max(1) as u32;
                assert!(location.line <= lines + 1, "{message}: past line {lines}");
            }
        }
        Error::Io { path, .. } | Error::UnknownFormat { path } => {
            assert!(!path.as_os_str().is_empty(), "{message}");
        }
        Error::Incompatible(_) | Error::StateLimit { .. } => {
            panic!("an error that names no file: {message}")
        }
    }
}

/// A validated project: its files, its image and its generated code.
fn check_valid(project: &Project, path: &Path) {
    codegen::build::rerun_lines(path, &project.files)
        .unwrap_or_else(|e| panic!("a validated project cannot be named to cargo: {e}"));
    let image = TableImage::new(project).expect("a validated project has a table image");
    assert_eq!(validate(&image), Ok(()), "the structure check");
    assert_eq!(
        validate_allowed_sets(&image),
        Ok(()),
        "the stored allowed sets"
    );
    assert_eq!(image.computed_crc(), image.crc, "the recorded CRC");
    let config = image.config();
    let controller = Controller::new(&image, HeapMemory::for_config(&config)).unwrap();
    assert_eq!(
        controller.fault(),
        None,
        "a controller of a validated project"
    );
    for backend in [Backend::Table, Backend::Match] {
        let generated = generate(project, backend, "fuzz")
            .unwrap_or_else(|e| panic!("{backend:?}: a validated project fails to generate: {e}"));
        if backend == Backend::Table {
            assert_eq!(generated.crc, image.crc, "the CRC recorded in the code");
        }
        check_code(&generated.code, project, backend);
    }
}

/// The generated `code` of `project`: items unique, the name modules
/// exact.
fn check_code(code: &str, project: &Project, backend: Backend) {
    let file = syn::parse_file(code).expect("generated code parses");
    unique_items(&file.items, "the file", backend);
    let modules: [(&str, Vec<String>); 5] = [
        (
            "input",
            project.inputs.iter().map(|x| x.name.clone()).collect(),
        ),
        (
            "output",
            project.outputs.iter().map(|x| x.name.clone()).collect(),
        ),
        (
            "timer",
            project.timers.iter().map(|x| x.name.clone()).collect(),
        ),
        (
            "event",
            project.events.iter().map(|x| x.name.clone()).collect(),
        ),
        (
            "supervisor",
            project.supervisors.iter().map(|x| x.name.clone()).collect(),
        ),
    ];
    for (module, declared) in modules {
        let items = file
            .items
            .iter()
            .find_map(|item| match item {
                syn::Item::Mod(m) if m.ident == module => m.content.as_ref().map(|c| &c.1),
                _ => None,
            })
            .unwrap_or_else(|| panic!("{backend:?}: no module `{module}`"));
        let mut indices = Vec::new();
        let (mut listed, mut count) = (None, None);
        for item in items {
            match item {
                syn::Item::Const(c) if c.ident == "COUNT" => count = Some(int(&c.expr)),
                syn::Item::Const(c) => indices.push(int(&c.expr)),
                syn::Item::Static(s) if s.ident == "NAMES" => listed = Some(strings(&s.expr)),
                _ => {}
            }
        }
        let what = format!("{backend:?}: module `{module}`");
        assert_eq!(listed.as_ref(), Some(&declared), "{what}: NAMES");
        assert_eq!(count, Some(declared.len()), "{what}: COUNT");
        assert_eq!(indices, (0..declared.len()).collect::<Vec<_>>(), "{what}");
    }
}

/// The value of an integer literal.
fn int(expr: &syn::Expr) -> usize {
    match expr {
        syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Int(i),
            ..
        }) => i.base10_parse().expect("an index that fits"),
        _ => panic!("an index constant that is not an integer literal"),
    }
}

/// The values of an array of string literals.
fn strings(expr: &syn::Expr) -> Vec<String> {
    match expr {
        syn::Expr::Array(array) => array
            .elems
            .iter()
            .map(|e| match e {
                syn::Expr::Lit(syn::ExprLit {
                    lit: syn::Lit::Str(s),
                    ..
                }) => s.value(),
                _ => panic!("a name that is not a string literal"),
            })
            .collect(),
        _ => panic!("`NAMES` that is not an array"),
    }
}

/// No two items of `items` (a module, `scope`) share a name in one
/// namespace (rustc's E0428), nor does an item share one with a `use`;
/// the same for every inline module within.
fn unique_items(items: &[syn::Item], scope: &str, backend: Backend) {
    let mut types = HashSet::new();
    let mut values = HashSet::new();
    let mut seen = |name: String, ty: bool, value: bool| {
        let clash = (ty && !types.insert(name.clone())) | (value && !values.insert(name.clone()));
        assert!(!clash, "{backend:?}: two items `{name}` in {scope}");
    };
    for item in items {
        match item {
            syn::Item::Const(x) => seen(x.ident.to_string(), false, true),
            syn::Item::Static(x) => seen(x.ident.to_string(), false, true),
            syn::Item::Fn(x) => seen(x.sig.ident.to_string(), false, true),
            syn::Item::Enum(x) => seen(x.ident.to_string(), true, false),
            syn::Item::Type(x) => seen(x.ident.to_string(), true, false),
            syn::Item::Trait(x) => seen(x.ident.to_string(), true, false),
            syn::Item::Struct(x) => seen(
                x.ident.to_string(),
                true,
                !matches!(x.fields, syn::Fields::Named(_)),
            ),
            syn::Item::Use(x) => {
                let mut leaves = Vec::new();
                use_leaves(&x.tree, &mut leaves);
                for leaf in leaves {
                    seen(leaf, true, true);
                }
            }
            syn::Item::Mod(m) => {
                seen(m.ident.to_string(), true, false);
                if let Some((_, inner)) = &m.content {
                    unique_items(inner, &format!("module `{}`", m.ident), backend);
                }
            }
            _ => {}
        }
    }
}

/// The names a `use` tree brings into scope.
fn use_leaves(tree: &syn::UseTree, out: &mut Vec<String>) {
    match tree {
        syn::UseTree::Path(p) => use_leaves(&p.tree, out),
        syn::UseTree::Name(n) => out.push(n.ident.to_string()),
        syn::UseTree::Rename(r) => out.push(r.rename.to_string()),
        syn::UseTree::Glob(_) => {}
        syn::UseTree::Group(g) => g.items.iter().for_each(|t| use_leaves(t, out)),
    }
}
