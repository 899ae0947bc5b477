//! Crate layering: the stage table ([`LAYERS`]) and the check of every
//! workspace dependency against it, from `cargo metadata --no-deps` and
//! the manifests.

use crate::{cargo, root, Result};
use serde::Deserialize;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Where a crate stands; arrows point to lower stages only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Stage {
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
    pub(super) fn name(self) -> &'static str {
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
pub(super) struct Layer {
    pub(super) name: &'static str,
    pub(super) stage: Stage,
    /// `[dependencies]` (target-specific tables included).
    pub(super) normal: &'static [&'static str],
    /// `[build-dependencies]`.
    pub(super) build: &'static [&'static str],
    /// `[dev-dependencies]`, besides `normal` and `build` (and the crate
    /// itself, which a crate names to turn features on in its tests).
    pub(super) dev: &'static [&'static str],
}

/// The allowed arrows between workspace crates, in stage order.
pub(super) const LAYERS: &[Layer] = &[
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
        name: "field-update",
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
        dev: &["executor"],
    },
    Layer {
        name: "plc-project",
        stage: Stage::FrontEnd,
        normal: &["boards", "des", "des-symbolic", "executor"],
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
        normal: &[
            "codegen",
            "des",
            "des-symbolic",
            "executor",
            "field-update",
            "iec-export",
            "plc-project",
        ],
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
        normal: &["boards", "executor", "field-update"],
        build: &["codegen"],
        dev: &[],
    },
    Layer {
        name: "e2e",
        stage: Stage::Tooling,
        normal: &[
            "codegen",
            "des",
            "des-symbolic",
            "iec-export",
            "plc-project",
        ],
        build: &["codegen", "des", "plc-project"],
        dev: &["boards", "des-symbolic", "executor", "host-sim", "iec-st"],
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
pub(super) enum Kind {
    Normal,
    Build,
    Dev,
}

impl Kind {
    pub(super) fn table(self) -> &'static str {
        match self {
            Kind::Normal => "[dependencies]",
            Kind::Build => "[build-dependencies]",
            Kind::Dev => "[dev-dependencies]",
        }
    }
}

/// A dependency of one workspace crate on another.
#[derive(Debug, Clone)]
pub(super) struct Dep {
    pub(super) name: String,
    pub(super) kind: Kind,
    /// Its line in the manifest, when the manifest was read.
    pub(super) line: Option<usize>,
}

/// A workspace package as the checks see it.
#[derive(Debug, Clone)]
pub(super) struct Package {
    pub(super) name: String,
    /// Its manifest, relative to the workspace root.
    pub(super) manifest: PathBuf,
    /// Its library's root file, relative to the workspace root.
    pub(super) lib: Option<PathBuf>,
    /// Its dependencies on other workspace packages.
    pub(super) deps: Vec<Dep>,
}

/// The part of `cargo metadata --format-version 1 --no-deps` we read.
#[derive(Deserialize)]
pub(super) struct Metadata {
    pub(super) packages: Vec<MetaPackage>,
    pub(super) workspace_root: PathBuf,
}

#[derive(Deserialize)]
pub(super) struct MetaPackage {
    pub(super) name: String,
    pub(super) manifest_path: PathBuf,
    pub(super) dependencies: Vec<MetaDep>,
    pub(super) targets: Vec<MetaTarget>,
}

#[derive(Deserialize)]
pub(super) struct MetaDep {
    pub(super) name: String,
    pub(super) kind: Option<String>,
    #[serde(default)]
    pub(super) path: Option<PathBuf>,
}

#[derive(Deserialize)]
pub(super) struct MetaTarget {
    pub(super) kind: Vec<String>,
    pub(super) src_path: PathBuf,
}

/// The workspace packages in `cargo metadata` output, with their
/// dependencies on each other (paths relative to the workspace root).
pub(super) fn parse_metadata(json: &str) -> Result<Vec<Package>> {
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
pub(super) fn table_kind(header: &str) -> Option<Kind> {
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
pub(super) fn manifest_line(manifest: &str, dep: &str, kind: Kind) -> Option<usize> {
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
pub(super) fn table_failures(layers: &[Layer]) -> Vec<String> {
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
                    "xtask/src/layers/crates.rs: LAYERS lets `{}` use `{dep}`, which has no row of its own",
                    layer.name
                )),
                Some(s) if s > layer.stage || (!dev && s == layer.stage) => {
                    failures.push(format!(
                        "xtask/src/layers/crates.rs: LAYERS lets `{}` ({}) use `{dep}` ({}) outside its \
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
pub(super) fn crate_failures(packages: &[Package], layers: &[Layer]) -> Vec<String> {
    let mut failures = Vec::new();
    for p in packages {
        let Some(layer) = layers.iter().find(|l| l.name == p.name) else {
            failures.push(format!(
                "{}: workspace crate `{}` has no row in LAYERS (xtask/src/layers/crates.rs): add it \
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
pub(super) fn stale_rows(packages: &[Package], layers: &[Layer]) -> Vec<String> {
    layers
        .iter()
        .filter(|l| !packages.iter().any(|p| p.name == l.name))
        .map(|l| {
            format!(
                "xtask/src/layers/crates.rs: LAYERS has a row for `{}`, which is not a workspace crate",
                l.name
            )
        })
        .collect()
}

/// The workspace's packages, from `cargo metadata`, with manifest lines.
pub(super) fn workspace_packages() -> Result<Vec<Package>> {
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
