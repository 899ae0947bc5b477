//! `cargo xtask layers`: the one-way rules, checked from the manifests and
//! the source text alone (no compilation; it takes well under a second).
//!
//! The workspace is built in stages and every arrow points down them:
//!
//! | stage | crates | may use (normal and build dependencies) |
//! |---|---|---|
//! | core | `des`, `executor`, `iec-st` | no workspace crate |
//! | core on des | `des-symbolic` (symbolic synthesis) | `des` only |
//! | front end | `plc-project` | core |
//! | backends | `codegen` (lowering, backends, emission, build-script API), `iec-export` | core and the front end; never each other |
//! | on top | `codegen-cli` (the `codegen` binary), `host-sim`, `firmware` | anything below |
//! | tooling | `e2e` (`tests/`), `xtask` | anything below |
//!
//! A front end knows nothing downstream of it, a backend never reaches
//! into another backend, and the CLI sits on top of them all. Two checks
//! hold the rules:
//!
//! 1. **Crate layering.** From `cargo metadata --no-deps`, every
//!    dependency of a workspace crate on another workspace crate must be
//!    in [`LAYERS`], the table below, for its kind (`[dependencies]`,
//!    `[build-dependencies]`; `[dev-dependencies]` have their own,
//!    broader allowance, since tests may drive a crate from above). The
//!    table itself must respect the stages (normal and build arrows go to
//!    a strictly lower stage, dev arrows to a stage no higher), so a new
//!    upward arrow (`plc-project` → `codegen`, `codegen` → `iec-export`)
//!    cannot be allowed by just adding it to the table.
//! 2. **No import circle inside a crate.** For each library crate
//!    (`src/lib.rs`), the graph of its top-level modules (the first path
//!    segment under `src/`; `lib.rs` itself is the root and left out),
//!    with an edge wherever a module names another one through
//!    `crate::a::…`, `use crate::{a, b::c}` or a `super::` chain that
//!    climbs to the root. Comments and string literals are not code; test
//!    code is skipped (from a `#[cfg(test)]` line to the end of its file,
//!    modules declared test-only, and `tests/`). A strongly connected
//!    component of more than one module is a circle: it is printed with
//!    one `file:line` for each of its edges.
//!
//! [`KNOWN_CYCLES`] lets named edges through while a crate is being
//! reworked elsewhere; it is meant to be empty.

use crate::{cargo, root, Result};
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------
// Crate layering
// ---------------------------------------------------------------------------

/// Where a crate stands; arrows point to lower stages only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Stage {
    /// Automata and the scan cycle, and the ST interpreter (a test tool).
    Core,
    /// Libraries of the core stage built on the automaton model (`des`):
    /// core crates use no workspace crate, so these stand one step above
    /// them and below everything that reads projects.
    CoreOnDes,
    /// Reading and validating PLC projects.
    FrontEnd,
    /// Turning a validated project into something else (Rust, IEC).
    Backend,
    /// What users run: the CLI, the simulator, the firmware.
    Top,
    /// End-to-end tests and project automation.
    Tooling,
}

impl Stage {
    fn name(self) -> &'static str {
        match self {
            Stage::Core => "core",
            Stage::CoreOnDes => "core on des",
            Stage::FrontEnd => "front end",
            Stage::Backend => "backend",
            Stage::Top => "top",
            Stage::Tooling => "tooling",
        }
    }
}

/// One workspace crate: its stage and the workspace crates it may use.
struct Layer {
    name: &'static str,
    stage: Stage,
    /// `[dependencies]` (target-specific tables included).
    normal: &'static [&'static str],
    /// `[build-dependencies]`.
    build: &'static [&'static str],
    /// `[dev-dependencies]`, besides `normal` and `build` (and the crate
    /// itself, which a crate names to turn features on in its tests).
    dev: &'static [&'static str],
}

/// The allowed arrows between workspace crates, in stage order.
const LAYERS: &[Layer] = &[
    Layer {
        name: "des",
        stage: Stage::Core,
        normal: &[],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "executor",
        stage: Stage::Core,
        normal: &[],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "boards",
        stage: Stage::Core,
        normal: &[],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "iec-st",
        stage: Stage::Core,
        normal: &[],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "des-symbolic",
        stage: Stage::CoreOnDes,
        normal: &["des"],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "plc-project",
        stage: Stage::FrontEnd,
        normal: &["boards", "des", "executor"],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "codegen",
        stage: Stage::Backend,
        normal: &["boards", "des", "executor", "plc-project"],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "iec-export",
        stage: Stage::Backend,
        normal: &["des", "plc-project"],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "codegen-cli",
        stage: Stage::Top,
        normal: &["codegen", "des", "iec-export", "plc-project"],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "host-sim",
        stage: Stage::Top,
        normal: &["codegen", "des", "executor", "plc-project"],
        build: &[],
        dev: &[],
    },
    Layer {
        name: "firmware",
        stage: Stage::Top,
        normal: &["boards", "executor"],
        build: &["codegen", "plc-project"],
        dev: &[],
    },
    Layer {
        name: "e2e",
        stage: Stage::Tooling,
        normal: &["codegen", "des", "iec-export", "plc-project"],
        build: &["codegen", "des", "plc-project"],
        dev: &["boards", "executor", "host-sim", "iec-st"],
    },
    Layer {
        name: "xtask",
        stage: Stage::Tooling,
        normal: &[],
        build: &[],
        dev: &[],
    },
];

/// The kind of a dependency, as Cargo's manifest tables say.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    Normal,
    Build,
    Dev,
}

impl Kind {
    fn table(self) -> &'static str {
        match self {
            Kind::Normal => "[dependencies]",
            Kind::Build => "[build-dependencies]",
            Kind::Dev => "[dev-dependencies]",
        }
    }
}

/// A dependency of one workspace crate on another.
#[derive(Debug, Clone)]
struct Dep {
    name: String,
    kind: Kind,
    /// Its line in the manifest, when the manifest was read.
    line: Option<usize>,
}

/// A workspace package as the checks see it.
#[derive(Debug, Clone)]
struct Package {
    name: String,
    /// Its manifest, relative to the workspace root.
    manifest: PathBuf,
    /// Its library's root file, relative to the workspace root.
    lib: Option<PathBuf>,
    /// Its dependencies on other workspace packages.
    deps: Vec<Dep>,
}

/// The part of `cargo metadata --format-version 1 --no-deps` we read.
#[derive(Deserialize)]
struct Metadata {
    packages: Vec<MetaPackage>,
    workspace_root: PathBuf,
}

#[derive(Deserialize)]
struct MetaPackage {
    name: String,
    manifest_path: PathBuf,
    dependencies: Vec<MetaDep>,
    targets: Vec<MetaTarget>,
}

#[derive(Deserialize)]
struct MetaDep {
    name: String,
    kind: Option<String>,
    #[serde(default)]
    path: Option<PathBuf>,
}

#[derive(Deserialize)]
struct MetaTarget {
    kind: Vec<String>,
    src_path: PathBuf,
}

/// The workspace packages in `cargo metadata` output, with their
/// dependencies on each other (paths relative to the workspace root).
fn parse_metadata(json: &str) -> Result<Vec<Package>> {
    let meta: Metadata =
        serde_json::from_str(json).map_err(|e| format!("cargo metadata output: {e}"))?;
    let members: BTreeSet<&str> = meta.packages.iter().map(|p| p.name.as_str()).collect();
    let relative = |path: &Path| {
        path.strip_prefix(&meta.workspace_root)
            .unwrap_or(path)
            .to_path_buf()
    };
    let mut packages = Vec::new();
    for p in &meta.packages {
        let mut deps = Vec::new();
        for d in &p.dependencies {
            if d.path.is_none() || !members.contains(d.name.as_str()) {
                continue;
            }
            let kind = match d.kind.as_deref() {
                None | Some("normal") => Kind::Normal,
                Some("build") => Kind::Build,
                Some("dev") => Kind::Dev,
                Some(other) => {
                    return Err(format!(
                        "{}: dependency `{}` of unknown kind `{other}`",
                        p.name, d.name
                    ))
                }
            };
            deps.push(Dep {
                name: d.name.clone(),
                kind,
                line: None,
            });
        }
        let lib = p
            .targets
            .iter()
            .find(|t| t.kind.iter().any(|k| k == "lib"))
            .map(|t| relative(&t.src_path));
        packages.push(Package {
            name: p.name.clone(),
            manifest: relative(&p.manifest_path),
            lib,
            deps,
        });
    }
    Ok(packages)
}

/// The kind of dependencies a manifest table header (without its
/// brackets) lists, target-specific tables included.
fn table_kind(header: &str) -> Option<Kind> {
    let is = |table: &str| header == table || header.ends_with(&format!(".{table}"));
    if is("dev-dependencies") {
        Some(Kind::Dev)
    } else if is("build-dependencies") {
        Some(Kind::Build)
    } else if is("dependencies") {
        Some(Kind::Normal)
    } else {
        None
    }
}

/// The line of `dep` in `manifest` (the text of a `Cargo.toml`), in a
/// table of its kind.
fn manifest_line(manifest: &str, dep: &str, kind: Kind) -> Option<usize> {
    let mut section = None;
    for (i, line) in manifest.lines().enumerate() {
        let t = line.trim();
        if t.starts_with('[') {
            let header = t.trim_start_matches('[').trim_end_matches(']');
            section = table_kind(header);
            // `[dependencies.name]`
            if section.is_none() {
                if let Some((table, name)) = header.rsplit_once('.') {
                    if name == dep && table_kind(table) == Some(kind) {
                        return Some(i + 1);
                    }
                }
            }
        } else if section == Some(kind) && t.split(['=', '.', ' ']).next() == Some(dep) {
            return Some(i + 1);
        }
    }
    None
}

/// Arrows of [`LAYERS`] that go against the stages, and crates it names
/// that it does not list.
fn table_failures(layers: &[Layer]) -> Vec<String> {
    let stage = |name: &str| layers.iter().find(|l| l.name == name).map(|l| l.stage);
    let mut failures = Vec::new();
    for layer in layers {
        let arrows = layer
            .normal
            .iter()
            .chain(layer.build)
            .map(|d| (d, false))
            .chain(layer.dev.iter().map(|d| (d, true)));
        for (dep, dev) in arrows {
            match stage(dep) {
                None => failures.push(format!(
                    "xtask/src/layers.rs: LAYERS lets `{}` use `{dep}`, which has no row of its own",
                    layer.name
                )),
                Some(s) if s > layer.stage || (!dev && s == layer.stage) => {
                    failures.push(format!(
                        "xtask/src/layers.rs: LAYERS lets `{}` ({}) use `{dep}` ({}) outside its \
                         tests: arrows point to lower stages only (a front end never uses a \
                         backend, backends never use each other)",
                        layer.name,
                        layer.stage.name(),
                        s.name()
                    ))
                }
                Some(_) => {}
            }
        }
    }
    failures
}

/// Dependencies of `packages` that [`LAYERS`] does not allow, and
/// packages it has no row for.
fn crate_failures(packages: &[Package], layers: &[Layer]) -> Vec<String> {
    let mut failures = Vec::new();
    for p in packages {
        let Some(layer) = layers.iter().find(|l| l.name == p.name) else {
            failures.push(format!(
                "{}: workspace crate `{}` has no row in LAYERS (xtask/src/layers.rs): add it \
                 with its stage and the crates it may use",
                p.manifest.display(),
                p.name
            ));
            continue;
        };
        for d in &p.deps {
            if d.name == p.name {
                continue;
            }
            let allowed: Vec<&str> = match d.kind {
                Kind::Normal => layer.normal.to_vec(),
                Kind::Build => layer.build.to_vec(),
                Kind::Dev => [layer.normal, layer.build, layer.dev].concat(),
            };
            if allowed.contains(&d.name.as_str()) {
                continue;
            }
            let stage = layers
                .iter()
                .find(|l| l.name == d.name)
                .map_or("not in LAYERS", |l| l.stage.name());
            let mut allowed = allowed;
            allowed.sort_unstable();
            allowed.dedup();
            let location = match d.line {
                Some(line) => format!("{}:{line}", p.manifest.display()),
                None => p.manifest.display().to_string(),
            };
            failures.push(format!(
                "{location}: `{}` ({}) depends on `{}` ({stage}) in {}; there it may use {}. \
                 Arrows point down the stages (core <- core on des <- front end <- backends <- top <- \
                 tooling) and backends never use each other: move what it needs down a \
                 stage instead",
                p.name,
                layer.stage.name(),
                d.name,
                d.kind.table(),
                if allowed.is_empty() {
                    "no workspace crate".to_string()
                } else {
                    allowed.join(", ")
                }
            ));
        }
    }
    failures
}

/// Rows of [`LAYERS`] for crates the workspace does not have.
fn stale_rows(packages: &[Package], layers: &[Layer]) -> Vec<String> {
    layers
        .iter()
        .filter(|l| !packages.iter().any(|p| p.name == l.name))
        .map(|l| {
            format!(
                "xtask/src/layers.rs: LAYERS has a row for `{}`, which is not a workspace crate",
                l.name
            )
        })
        .collect()
}

/// The workspace's packages, from `cargo metadata`, with manifest lines.
fn workspace_packages() -> Result<Vec<Package>> {
    let out = cargo()
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .output()
        .map_err(|e| format!("cannot run cargo metadata: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "`cargo metadata` failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let mut packages = parse_metadata(&String::from_utf8_lossy(&out.stdout))?;
    for p in &mut packages {
        let path = root().join(&p.manifest);
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        for d in &mut p.deps {
            d.line = manifest_line(&text, &d.name, d.kind);
        }
    }
    Ok(packages)
}

// ---------------------------------------------------------------------------
// Import circles inside a crate
// ---------------------------------------------------------------------------

/// Edges that close import circles the check lets through for now, as
/// `(crate, from module, to module)`: one edge a circle, the one to cut.
///
/// Temporary, and empty at the lead's merge. Meant for a crate being
/// reworked on another branch (`codegen`, `host-sim`): its circle's
/// cutting edge is listed here so that CI runs meanwhile, while a new
/// circle anywhere (or a new edge in a listed component that closes
/// another circle) still fails. An entry whose edge no longer closes a
/// circle fails the check, so it cannot outlive its reason.
const KNOWN_CYCLES: &[(&str, &str, &str)] = &[];

/// Where an edge comes from: the first place (in file and line order)
/// that names the other module.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Site {
    file: PathBuf,
    line: usize,
}

/// A library's top-level modules and the edges between them.
#[derive(Debug, Default)]
struct ModuleGraph {
    modules: BTreeSet<String>,
    edges: BTreeMap<(String, String), Site>,
}

/// `text` with comments, string and character literals blanked out
/// (line breaks kept, so lines still count).
fn code_only(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |out: &mut String, c: char| out.push(if c == '\n' { '\n' } else { ' ' });
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
            }
        } else if let Some((quote, hashes)) = raw_string(&chars, i) {
            // A raw string: r"…", r#"…"#, br"…".
            let mut j = quote + 1;
            while j < chars.len() {
                if chars[j] == '"'
                    && chars.len() > j + hashes
                    && chars[j + 1..=j + hashes].iter().all(|&h| h == '#')
                {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            for &ch in &chars[i..j.min(chars.len())] {
                blank(&mut out, ch);
            }
            i = j;
        } else if c == '"' {
            blank(&mut out, c);
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
                if i < chars.len() {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
            }
            if i < chars.len() {
                blank(&mut out, chars[i]);
                i += 1;
            }
        } else if c == '\'' && (next == Some('\\') || chars.get(i + 2) == Some(&'\'')) {
            // A character literal ('a', '\n', '\''), not a lifetime.
            let mut j = i + 1;
            if chars[j] == '\\' {
                j += 2;
            }
            while j < chars.len() && chars[j] != '\'' {
                j += 1;
            }
            for &ch in &chars[i..(j + 1).min(chars.len())] {
                blank(&mut out, ch);
            }
            i = j + 1;
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// Where the raw string literal starting at `chars[i]` (`r"`, `r#"`,
/// `br"`) has its opening quote, and how many `#` it has; `None` if no raw
/// string starts there.
fn raw_string(chars: &[char], i: usize) -> Option<(usize, usize)> {
    let ident = |c: &char| c.is_alphanumeric() || *c == '_';
    if i > 0 && ident(&chars[i - 1]) {
        return None;
    }
    let start = match (chars.get(i), chars.get(i + 1)) {
        (Some('r'), _) => i + 1,
        (Some('b'), Some('r')) => i + 2,
        _ => return None,
    };
    let hashes = chars[start.min(chars.len())..]
        .iter()
        .take_while(|&&h| h == '#')
        .count();
    (chars.get(start + hashes) == Some(&'"')).then_some((start + hashes, hashes))
}

/// Whether a line (comments blanked) is an attribute that makes the next
/// item test-only: `#[cfg(test)]` or `#[cfg(all(test, …))]`.
fn test_only_attribute(line: &str) -> bool {
    let t: String = line.chars().filter(|c| !c.is_whitespace()).collect();
    t.starts_with("#[cfg(test)]") || t.starts_with("#[cfg(all(test,") || t == "#[cfg(all(test))]"
}

/// The `mod name;` declarations of a file (comments blanked), with their
/// lines, leaving out test-only modules (by an attribute on the lines
/// above or before it on its line). Inline modules are not listed.
fn module_declarations(code: &str) -> Vec<(String, usize)> {
    let lines: Vec<&str> = code.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let mut t = line.trim();
        let mut test_only = false;
        // Attributes on the declaration's own line.
        while t.starts_with("#[") {
            let mut depth = 0;
            let end = t.char_indices().find_map(|(k, c)| {
                match c {
                    '[' => depth += 1,
                    ']' => depth -= 1,
                    _ => return None,
                }
                (depth == 0).then_some(k)
            });
            let Some(end) = end else { break };
            test_only |= test_only_attribute(&t[..=end]);
            t = t[end + 1..].trim_start();
        }
        if let Some(rest) = t.strip_prefix("pub") {
            let rest = rest.trim_start();
            t = match rest.strip_prefix('(') {
                Some(vis) => vis.split_once(')').map_or(rest, |(_, r)| r.trim_start()),
                None => rest,
            };
        }
        let Some(rest) = t.strip_prefix("mod ") else {
            continue;
        };
        let rest = rest.trim_start();
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if name.is_empty() || !rest[name.len()..].trim_start().starts_with(';') {
            continue;
        }
        test_only |= lines[..i]
            .iter()
            .rev()
            .map(|l| l.trim())
            .take_while(|l| l.is_empty() || l.starts_with("#["))
            .any(test_only_attribute);
        if !test_only {
            found.push((name, i + 1));
        }
    }
    found
}

/// A token of code: an identifier, `::`, or another punctuation
/// character; with its line.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Tok {
    Ident(String),
    PathSep,
    Punct(char),
}

fn tokens(code: &str) -> Vec<(Tok, usize)> {
    let mut toks = Vec::new();
    for (n, line) in code.lines().enumerate() {
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if c.is_alphabetic() || c == '_' {
                let start = i;
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
                let word: String = chars[start..i].iter().collect();
                // Raw identifiers: r#name.
                if word == "r" && chars.get(i) == Some(&'#') {
                    i += 1;
                    continue;
                }
                toks.push((Tok::Ident(word), n + 1));
            } else if c.is_ascii_digit() {
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
            } else if c == ':' && chars.get(i + 1) == Some(&':') {
                toks.push((Tok::PathSep, n + 1));
                i += 2;
            } else {
                if !c.is_whitespace() {
                    toks.push((Tok::Punct(c), n + 1));
                }
                i += 1;
            }
        }
    }
    toks
}

/// The top-level modules one file names, as `(module, line, the module
/// path where it is named)`, the file being module `path` (empty for the
/// crate root; inline modules extend it). Only paths that start at
/// `crate::` or climb there with `super::` count.
fn referenced_modules(code: &str, path: &[String]) -> Vec<(String, usize, Vec<String>)> {
    let toks = tokens(code);
    let ident = |i: usize| match toks.get(i) {
        Some((Tok::Ident(s), _)) => Some(s.as_str()),
        _ => None,
    };
    let is = |i: usize, t: &Tok| toks.get(i).map(|(x, _)| x) == Some(t);
    let mut found = Vec::new();
    // Inline modules this point of the file is in, with the brace depth
    // they opened at.
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let mut i = 0;
    while i < toks.len() {
        match &toks[i].0 {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                depth = depth.saturating_sub(1);
                while inline.last().is_some_and(|&(_, d)| d == depth) {
                    inline.pop();
                }
            }
            Tok::Ident(kw) if kw == "mod" => {
                if let (Some(name), true) = (ident(i + 1), is(i + 2, &Tok::Punct('{'))) {
                    inline.push((name.to_string(), depth));
                    i += 2;
                    continue;
                }
            }
            Tok::Ident(kw)
                if (kw == "crate" || kw == "super")
                    && is(i + 1, &Tok::PathSep)
                    && !(i > 0 && is(i - 1, &Tok::PathSep)) =>
            {
                let current: Vec<String> = path
                    .iter()
                    .cloned()
                    .chain(inline.iter().map(|(m, _)| m.clone()))
                    .collect();
                let mut j = i;
                let base: Vec<String> = if kw == "crate" {
                    j += 2;
                    Vec::new()
                } else {
                    let mut up = 0;
                    while ident(j) == Some("super") && is(j + 1, &Tok::PathSep) {
                        up += 1;
                        j += 2;
                    }
                    if up > current.len() {
                        i = j;
                        continue;
                    }
                    current[..current.len() - up].to_vec()
                };
                // Below the root the path stays inside the top-level
                // module it climbed from: only the root's children count.
                if base.is_empty() {
                    if let Some(name) = ident(j) {
                        found.push((name.to_string(), toks[j].1, current.clone()));
                    } else if is(j, &Tok::Punct('{')) {
                        // use crate::{a, b::c, d::{e, f}}: the first
                        // segment of every item.
                        let mut level = 0;
                        let mut item_start = true;
                        let mut k = j + 1;
                        while k < toks.len() {
                            match &toks[k].0 {
                                Tok::Punct('{') => level += 1,
                                Tok::Punct('}') if level == 0 => break,
                                Tok::Punct('}') => level -= 1,
                                Tok::Punct(',') if level == 0 => {
                                    item_start = true;
                                    k += 1;
                                    continue;
                                }
                                Tok::Ident(name) if item_start && level == 0 => {
                                    found.push((name.clone(), toks[k].1, current.clone()));
                                }
                                _ => {}
                            }
                            item_start = false;
                            k += 1;
                        }
                    }
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    found
}

/// The file of module `name`, declared by `mod name;` in file `parent`.
fn child_file(files: &BTreeMap<PathBuf, String>, parent: &Path, name: &str) -> Option<PathBuf> {
    let stem = parent.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let dir = parent.parent().unwrap_or(Path::new(""));
    let dir = if matches!(stem, "lib" | "mod" | "main") {
        dir.to_path_buf()
    } else {
        dir.join(stem)
    };
    [
        dir.join(format!("{name}.rs")),
        dir.join(name).join("mod.rs"),
    ]
    .into_iter()
    .find(|p| files.contains_key(p))
}

/// The graph of top-level modules of the library whose root is `lib`,
/// from the crate's files (path → text; paths as they are to be printed).
/// Modules are found by following `mod name;` from `lib`, so binaries,
/// test-only modules and `tests/` are not read.
fn module_graph(files: &BTreeMap<PathBuf, String>, lib: &Path) -> Result<ModuleGraph> {
    // Files still to read, with their module paths.
    let mut queue = vec![(lib.to_path_buf(), Vec::<String>::new())];
    let mut reached = Vec::new();
    while let Some((file, path)) = queue.pop() {
        let text = files
            .get(&file)
            .ok_or_else(|| format!("{}: cannot read", file.display()))?;
        let code = code_only(text);
        for (name, line) in module_declarations(&code) {
            let child = child_file(files, &file, &name).ok_or_else(|| {
                format!(
                    "{}:{line}: `mod {name};` has neither {name}.rs nor {name}/mod.rs beside it",
                    file.display()
                )
            })?;
            let mut child_path = path.clone();
            child_path.push(name);
            queue.push((child, child_path));
        }
        // Test code: from the first test-only attribute to the end.
        let end = code
            .lines()
            .position(test_only_attribute)
            .unwrap_or(usize::MAX);
        let code: String = code.lines().take(end).map(|l| format!("{l}\n")).collect();
        reached.push((file, path, code));
    }
    reached.sort();
    let mut graph = ModuleGraph::default();
    for (_, path, code) in &reached {
        if let Some(top) = path.first() {
            graph.modules.insert(top.clone());
        } else {
            // Inline modules of the root are top-level modules too.
            for w in tokens(code).windows(3) {
                if let [(Tok::Ident(m), _), (Tok::Ident(name), _), (Tok::Punct('{'), _)] = w {
                    if m == "mod" {
                        graph.modules.insert(name.clone());
                    }
                }
            }
        }
    }
    for (file, path, code) in &reached {
        for (to, line, current) in referenced_modules(code, path) {
            let Some(from) = current.first() else {
                continue;
            };
            if *from == to || !graph.modules.contains(&to) {
                continue;
            }
            graph
                .edges
                .entry((from.clone(), to))
                .or_insert_with(|| Site {
                    file: file.clone(),
                    line,
                });
        }
    }
    Ok(graph)
}

/// Strongly connected components of more than one module (Tarjan), each
/// sorted, in sorted order.
fn circles(modules: &BTreeSet<String>, edges: &BTreeSet<(String, String)>) -> Vec<Vec<String>> {
    struct Tarjan<'a> {
        edges: &'a BTreeSet<(String, String)>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        found: Vec<Vec<String>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a str) {
            let n = self.index.len();
            self.index.insert(v, n);
            self.low.insert(v, n);
            self.stack.push(v);
            self.on_stack.insert(v);
            let edges = self.edges;
            for (_, w) in edges.iter().filter(|(a, _)| a == v) {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    component.push(w.to_string());
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort();
                    self.found.push(component);
                }
            }
        }
    }
    let mut t = Tarjan {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for m in modules {
        if !t.index.contains_key(m.as_str()) {
            t.visit(m);
        }
    }
    t.found.sort();
    t.found
}

/// One shortest circle through the first module of `component`, as the
/// modules in order (the first repeated at the end).
fn one_circle(component: &[String], edges: &BTreeSet<(String, String)>) -> Vec<String> {
    let start = &component[0];
    let inside = |m: &String| component.contains(m);
    // Breadth-first from `start` back to it, inside the component.
    let mut previous: BTreeMap<&String, &String> = BTreeMap::new();
    let mut frontier = vec![start];
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for v in frontier {
            for (_, w) in edges.iter().filter(|(a, b)| a == v && inside(b)) {
                if w == start {
                    let mut circle = vec![start.clone()];
                    let mut at = v;
                    while at != start {
                        circle.push(at.clone());
                        at = previous[at];
                    }
                    circle.push(start.clone());
                    circle.reverse();
                    return circle;
                }
                if !previous.contains_key(w) {
                    previous.insert(w, v);
                    next.push(w);
                }
            }
        }
        frontier = next;
    }
    component.to_vec()
}

/// The import circles of one crate's graph, `known` edges left out, as
/// messages; and the `known` edges that close no circle.
fn circle_failures(
    krate: &str,
    graph: &ModuleGraph,
    known: &[(&str, &str, &str)],
) -> (Vec<String>, Vec<String>) {
    let all: BTreeSet<(String, String)> = graph.edges.keys().cloned().collect();
    let known: Vec<(String, String)> = known
        .iter()
        .filter(|(k, _, _)| *k == krate)
        .map(|(_, a, b)| (a.to_string(), b.to_string()))
        .collect();
    let mut stale = Vec::new();
    let full = circles(&graph.modules, &all);
    for (a, b) in &known {
        let closes = all.contains(&(a.clone(), b.clone()))
            && full.iter().any(|c| c.contains(a) && c.contains(b));
        if !closes {
            stale.push(format!(
                "xtask/src/layers.rs: KNOWN_CYCLES lets `{krate}`: {a} -> {b} through, but that \
                 edge closes no circle any more: delete the entry"
            ));
        }
    }
    let kept: BTreeSet<(String, String)> =
        all.iter().filter(|e| !known.contains(e)).cloned().collect();
    let mut failures = Vec::new();
    for component in circles(&graph.modules, &kept) {
        let mut msg = format!(
            "`{krate}`: import circle {} (modules {})",
            one_circle(&component, &kept).join(" -> "),
            component.join(", ")
        );
        for ((a, b), site) in &graph.edges {
            if kept.contains(&(a.clone(), b.clone()))
                && component.contains(a)
                && component.contains(b)
            {
                msg.push_str(&format!(
                    "\n    {a} -> {b}: {}:{}",
                    site.file.display(),
                    site.line
                ));
            }
        }
        failures.push(msg);
    }
    (failures, stale)
}

/// Every `.rs` file under `dir`, by path relative to the workspace root.
fn read_sources(dir: &Path, files: &mut BTreeMap<PathBuf, String>) -> Result {
    let entries =
        std::fs::read_dir(root().join(dir)).map_err(|e| format!("{}: {e}", dir.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", dir.display()))?;
        let path = dir.join(entry.file_name());
        let kind = entry
            .file_type()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        if kind.is_dir() {
            read_sources(&path, files)?;
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(root().join(&path))
                .map_err(|e| format!("{}: {e}", path.display()))?;
            files.insert(path, text);
        }
    }
    Ok(())
}

/// Runs both checks on the workspace; `--edges` also prints every
/// library's module edges, each with the place that makes it.
pub fn run_task(args: &[String]) -> Result {
    let mut show_edges = false;
    for arg in args {
        match arg.as_str() {
            "--edges" => show_edges = true,
            _ => return Err(format!("layers: unknown argument `{arg}` (try --edges)")),
        }
    }
    let packages = workspace_packages()?;
    let mut failures = table_failures(LAYERS);
    failures.extend(crate_failures(&packages, LAYERS));
    failures.extend(stale_rows(&packages, LAYERS));
    let arrows: usize = packages.iter().map(|p| p.deps.len()).sum();

    let mut libraries = Vec::new();
    for p in &packages {
        // Libraries with their own `src/` (the e2e package's lib is the
        // test helpers at the root of `tests/`).
        let Some(lib) = p.lib.as_ref().filter(|l| l.ends_with("src/lib.rs")) else {
            continue;
        };
        let src = lib.parent().expect("src/lib.rs has a parent");
        let mut files = BTreeMap::new();
        read_sources(src, &mut files)?;
        let graph = module_graph(&files, lib)?;
        if show_edges {
            eprintln!(
                "{}: modules {}",
                p.name,
                graph.modules.iter().cloned().collect::<Vec<_>>().join(", ")
            );
            for ((a, b), site) in &graph.edges {
                eprintln!("  {a} -> {b}: {}:{}", site.file.display(), site.line);
            }
        }
        let (circles, stale) = circle_failures(&p.name, &graph, KNOWN_CYCLES);
        failures.extend(circles);
        failures.extend(stale);
        libraries.push(p.name.as_str());
    }
    for (krate, _, _) in KNOWN_CYCLES {
        if !libraries.contains(krate) {
            failures.push(format!(
                "xtask/src/layers.rs: KNOWN_CYCLES names `{krate}`, which is not a library crate \
                 of the workspace: delete the entry"
            ));
        }
    }
    if !failures.is_empty() {
        return Err(format!(
            "the one-way rules are broken (docs/architecture.md, \"The one-way rules\"):\n{}",
            failures
                .iter()
                .map(|f| format!("  {f}"))
                .collect::<Vec<_>>()
                .join("\n")
        ));
    }
    eprintln!(
        "xtask: layers: {} crates, {arrows} arrows between them, all in the layer table; \
         no import circle in {} ({} libraries)",
        packages.len(),
        libraries.join(", "),
        libraries.len()
    );
    if !KNOWN_CYCLES.is_empty() {
        eprintln!(
            "xtask: layers: {} circle edges let through for now (KNOWN_CYCLES, to be emptied):",
            KNOWN_CYCLES.len()
        );
        for (krate, a, b) in KNOWN_CYCLES {
            eprintln!("  {krate}: {a} -> {b}");
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
                 (backend) in [dependencies]; there it may use boards, des, executor."
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
            failure.contains("there it may use boards, executor."),
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
}
