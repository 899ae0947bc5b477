//! Build-script API: a project file in, `OUT_DIR/<name>.rs` out.
//!
//! In the `build.rs` of a firmware or simulation crate:
//!
//! ```no_run
//! codegen::build::Build::new("models/press.plc.toml")
//!     .backend(codegen::emit::Backend::Table)
//!     .generate_or_exit();
//! ```
//!
//! and in the crate:
//!
//! ```ignore
//! mod press {
//!     include!(concat!(env!("OUT_DIR"), "/press.rs"));
//! }
//! ```
//!
//! Every file the project was built from (the project, its automata, the
//! plant and specification files of synthesised supervisors) is announced
//! with `cargo:rerun-if-changed`, and validation warnings become
//! `cargo:warning` lines.

use crate::emit::{generate, Backend, Generated};
use crate::error::{Error, Result};
use crate::project;
use std::path::{Path, PathBuf};

/// A generation request.
#[derive(Debug, Clone)]
pub struct Build {
    project: PathBuf,
    backend: Backend,
    out_dir: Option<PathBuf>,
    file_name: Option<String>,
}

/// The default output name of a project file: its file name up to the
/// first dot (`press.plc.toml` → `press`).
pub fn output_stem(project: &Path) -> String {
    let name = project
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stem = name.split('.').next().unwrap_or_default();
    if stem.is_empty() {
        "program".to_owned()
    } else {
        project::ident::snake_ident(stem)
    }
}

impl Build {
    /// Generation of the project at `project` (relative to the crate's
    /// manifest directory when run from a build script).
    pub fn new(project: impl Into<PathBuf>) -> Build {
        Build {
            project: project.into(),
            backend: Backend::Table,
            out_dir: None,
            file_name: None,
        }
    }

    /// The backend (default: tables).
    pub fn backend(mut self, backend: Backend) -> Build {
        self.backend = backend;
        self
    }

    /// Where to write (default: `$OUT_DIR`).
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Build {
        self.out_dir = Some(dir.into());
        self
    }

    /// The output file's name without `.rs` (default: [`output_stem`]).
    pub fn file_name(mut self, name: impl Into<String>) -> Build {
        self.file_name = Some(name.into());
        self
    }

    /// Loads, validates and generates; writes the file only when its
    /// content changed (keeps incremental builds incremental). Returns the
    /// path written and the generation figures.
    pub fn generate(self) -> Result<(PathBuf, Generated)> {
        let out_dir = match self.out_dir {
            Some(d) => d,
            None => std::env::var_os("OUT_DIR").map(PathBuf::from).ok_or_else(|| {
                Error::Incompatible("OUT_DIR is not set: call Build::generate from a build script or set out_dir".into())
            })?,
        };
        let project = project::load(&self.project)?;
        for file in &project.files {
            println!("cargo:rerun-if-changed={}", file.display());
        }
        for w in &project.warnings {
            println!(
                "cargo:warning={}:{}: {}",
                self.project.display(),
                w.line,
                w.message.replace('\n', " ")
            );
        }
        let backend = self.backend.name();
        let regenerate = format!(
            "cargo build (build script), or: codegen gen {} --backend {backend}",
            self.project.display()
        );
        let generated = generate(&project, self.backend, &regenerate)?;
        let name = self.file_name.unwrap_or_else(|| output_stem(&self.project));
        let path = out_dir.join(format!("{name}.rs"));
        let unchanged = std::fs::read_to_string(&path).is_ok_and(|old| old == generated.code);
        if !unchanged {
            std::fs::write(&path, &generated.code).map_err(|e| Error::io(&path, e))?;
        }
        Ok((path, generated))
    }

    /// [`Build::generate`], printing any error for cargo and exiting with
    /// status 1 (a build script's way to fail with a readable message).
    pub fn generate_or_exit(self) -> PathBuf {
        match self.generate() {
            Ok((path, _)) => path,
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::output_stem;
    use std::path::Path;

    #[test]
    fn output_names_come_from_the_file_name() {
        assert_eq!(output_stem(Path::new("models/press.plc.toml")), "press");
        assert_eq!(output_stem(Path::new("Boiler-2.plc.toml")), "boiler_2");
        assert_eq!(output_stem(Path::new(".plc.toml")), "program");
    }
}
