//! Build-script API: a project file in, `OUT_DIR/<name>.rs` out.
//!
//! In the `build.rs` of a firmware or simulation crate:
//!
//! ```no_run
//! codegen::build::Build::new("models/press.plc.toml")
//!     .backend(codegen::backend::Backend::Table)
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
//!
//! Cargo reads a build script's standard output as lines split at `\n`,
//! each trimmed, a line that is not UTF-8 skipped, and every line starting
//! with `cargo:` taken as a directive. A path with a line break would start
//! a directive of its own choosing (`cargo:rustc-env=…`, linker arguments),
//! so a path is printed only if cargo reads it back unchanged
//! ([`printable_path`]); anything else fails the build, naming the file,
//! before a single line is printed. Warning text has its control
//! characters replaced ([`warning_line`]).

use crate::backend::Backend;
use crate::emit::{generate, Generated};
use crate::error::{Error, Result};
use plc_project as project;
pub use plc_project::paths::{printable_path, UnprintablePath};
use std::path::{Path, PathBuf};

/// The `cargo:rerun-if-changed` line of every file of a project (the
/// project file `project` first), or an error naming the first file that
/// cannot be printed ([`Error::UnprintableProject`],
/// [`Error::UnprintableModel`]).
pub fn rerun_lines(project: &Path, files: &[PathBuf]) -> Result<Vec<String>> {
    files
        .iter()
        .map(|file| match printable_path(file) {
            Ok(text) => Ok(format!("cargo:rerun-if-changed={text}")),
            Err(reason) if file == project => Err(Error::UnprintableProject {
                file: file.clone(),
                reason,
            }),
            Err(reason) => Err(Error::UnprintableModel {
                project: project.to_path_buf(),
                file: file.clone(),
                reason,
            }),
        })
        .collect()
}

/// The `cargo:warning` line of `text`: line breaks become spaces and every
/// other control character its escape (`\u{1b}`), so that the warning
/// stays one line and prints as it reads.
pub fn warning_line(text: &str) -> String {
    let mut line = String::from("cargo:warning=");
    for c in text.chars() {
        match c {
            '\n' | '\r' => line.push(' '),
            c if c.is_control() => line.extend(c.escape_default()),
            c => line.push(c),
        }
    }
    line
}

/// A generation request.
#[derive(Debug, Clone)]
pub struct Build {
    project: PathBuf,
    backend: Backend,
    out_dir: Option<PathBuf>,
    file_name: Option<String>,
    require_board: bool,
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
            require_board: false,
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

    /// Refuses a project without a `[board]` section ([`Error::NoBoard`]):
    /// a board firmware needs the pin of each signal.
    pub fn require_board(mut self) -> Build {
        self.require_board = true;
        self
    }

    /// Loads, validates and generates; writes the file only when its
    /// content changed (keeps incremental builds incremental). Returns the
    /// path written and the generation figures.
    pub fn generate(self) -> Result<(PathBuf, Generated)> {
        let out_dir = match self.out_dir {
            Some(d) => d,
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(Error::NoOutDir)?,
        };
        let project = project::load(&self.project)?;
        if self.require_board && project.board.is_none() {
            return Err(Error::NoBoard {
                project: self.project,
            });
        }
        // Every line is checked before any is printed: a refused path
        // fails the build without half its directives.
        let rerun = rerun_lines(&self.project, &project.files)?;
        for line in rerun {
            println!("{line}");
        }
        for w in &project.warnings {
            let text = format!("{}:{}: {}", self.project.display(), w.line, w.message);
            println!("{}", warning_line(&text));
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
            std::fs::write(&path, &generated.code).map_err(|e| des::Error::io(&path, e))?;
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
    use super::{output_stem, rerun_lines, warning_line, UnprintablePath};
    use crate::Error;
    use std::path::{Path, PathBuf};

    #[test]
    fn ordinary_paths_become_one_rerun_line_each() {
        let files = [
            PathBuf::from("models/press.plc.toml"),
            PathBuf::from("models/plant/motor 1.toml"),
            PathBuf::from("/abs/é/spec.gen"),
        ];
        assert_eq!(
            rerun_lines(&files[0], &files).unwrap(),
            [
                "cargo:rerun-if-changed=models/press.plc.toml",
                "cargo:rerun-if-changed=models/plant/motor 1.toml",
                "cargo:rerun-if-changed=/abs/é/spec.gen",
            ]
        );
    }

    #[test]
    fn a_refused_file_fails_the_whole_list_naming_the_file_and_the_project() {
        let project = PathBuf::from("p.plc.toml");
        let files = [
            project.clone(),
            PathBuf::from("plant/a\ncargo:rustc-cfg=x.toml"),
        ];
        let err = rerun_lines(&project, &files).unwrap_err();
        assert!(
            matches!(
                &err,
                Error::UnprintableModel { project: p, file, reason: UnprintablePath::Control('\n') }
                    if *p == project && *file == files[1]
            ),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "\"p.plc.toml\": the model file \"plant/a\\ncargo:rustc-cfg=x.toml\" cannot be named \
             to cargo (`cargo:rerun-if-changed`): it holds the control character U+000A; rename it"
        );
        let project = PathBuf::from("p\r.plc.toml");
        let err = rerun_lines(&project, std::slice::from_ref(&project)).unwrap_err();
        assert!(
            matches!(
                &err,
                Error::UnprintableProject { file, reason: UnprintablePath::Control('\r') }
                    if *file == project
            ),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "the project file \"p\\r.plc.toml\" cannot be named to cargo \
             (`cargo:rerun-if-changed`): it holds the control character U+000D; rename it"
        );
    }

    #[test]
    fn a_warning_stays_one_line_with_its_control_characters_visible() {
        assert_eq!(
            warning_line("p.plc.toml:3: event `a\ncargo:rustc-cfg=x`\r\u{1b}[31m"),
            "cargo:warning=p.plc.toml:3: event `a cargo:rustc-cfg=x` \\u{1b}[31m"
        );
    }

    #[test]
    fn output_names_come_from_the_file_name() {
        assert_eq!(output_stem(Path::new("models/press.plc.toml")), "press");
        assert_eq!(output_stem(Path::new("Boiler-2.plc.toml")), "boiler_2");
        assert_eq!(output_stem(Path::new(".plc.toml")), "program");
    }
}
