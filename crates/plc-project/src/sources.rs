//! Supervisor sources: the stage between parsing and validation that reads
//! the model file of every `[[supervisor]]`, or synthesises it, so that
//! validation ([`super::validate`]) checks automata that are already
//! there.
//!
//! `file` names any supported automaton file, relative to the project
//! file's directory. Without `component`, the file must hold exactly one
//! component of kind supervisor, spec or unspecified; `component` selects
//! one by automaton name (any kind). `synthesize` expands its glob
//! patterns relative to the project directory (matches in alphabetical
//! order, duplicates dropped; a pattern without `*`, `?` or `[` is a plain
//! path); every pattern must match at least one file. From a file under
//! `plants` every plant and unspecified component is taken, from a file
//! under `specs` every spec, supervisor and unspecified component. The
//! supervisor is `supcon(sync(plants), sync(specs))` (no specs: the plant's
//! nonblocking controllable part), then `minstate` if `minimize = true`
//! ([`ops::synthesize`], the pipeline of `codegen synth`).
//!
//! A missing or unreadable model file, or one of unknown format, is
//! reported at the line of the project that names it; errors inside a
//! model file propagate unchanged (they point into that file). Every file
//! read is recorded, once, for `rerun-if-changed` ([`Project::files`](super::Project::files)).
//! A model path that a build script could not print for cargo (a line
//! break or other control character, not UTF-8, trailing whitespace:
//! [`printable_path`]) is refused at the line that names it, with the
//! pattern that matched it: such a name is never what the user meant, and
//! printed it could inject a `cargo:` directive into their build.

mod guarded;

pub(crate) use guarded::LoadedGuarded;

use super::locate::ProjectFile;
use super::model::{NetSource, SupervisorSource};
use super::parse::{names, Name, RawNet, RawSupervisor};
use crate::paths::printable_path;
use des::automaton::{Alphabet, Automaton};
use des::error::{Error, Result};
use des::formats::{self, Component, Kind};
use des::ops;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// An automaton a supervisor was read or synthesised from.
#[derive(Clone)]
pub(crate) struct ModelOrigin {
    /// The model file.
    pub file: PathBuf,
    /// The automaton's name in it.
    pub name: String,
    /// Its alphabet, with the controllability the file states (if any).
    pub alphabet: Alphabet,
}

/// A supervisor's automaton as read or synthesised, not yet checked
/// against the project.
pub(crate) struct LoadedSupervisor {
    /// The automaton to run.
    pub automaton: Automaton,
    /// Where it came from.
    pub source: SupervisorSource,
    /// The automata it was read or synthesised from.
    pub origins: Vec<ModelOrigin>,
}

/// What one `[[supervisor]]` loads: an automaton, or a symbolic
/// supervisor's components and guards.
pub(crate) enum LoadedEntry {
    /// One automaton.
    Automaton(LoadedSupervisor),
    /// A symbolic supervisor.
    Guarded(LoadedGuarded),
    /// A reduced supervisor (`reduce = true`) or the local controllers
    /// of a localized one (`localize = true`, each with its event), and
    /// the plant components they run beside, each with its model.
    Reduced(
        Vec<(Option<String>, LoadedSupervisor)>,
        Vec<(Automaton, ModelOrigin)>,
    ),
}

/// A `[[net]]` as read (and synthesised), analysed, not yet checked
/// against the project.
pub(crate) struct LoadedNet {
    /// The net to run.
    pub net: des::petri::PetriNet,
    /// Where it came from.
    pub source: NetSource,
    /// Its reachability graph's figures.
    pub reach: des::petri::reach::Reachability,
    /// The control places added by synthesis.
    pub control_places: usize,
}

/// The models a `synthesize` names (explicit or symbolic).
struct SynthesisModels {
    /// Plant files.
    plants: Vec<PathBuf>,
    /// Their automata.
    plant_automata: Vec<Automaton>,
    /// Specification files.
    specs: Vec<PathBuf>,
    /// Their automata.
    spec_automata: Vec<Automaton>,
    /// Where each automaton came from, plants first.
    origins: Vec<ModelOrigin>,
}

/// What the files of a project hold.
pub(crate) struct Sources {
    /// One per `[[supervisor]]`, in declaration order.
    pub supervisors: Vec<LoadedEntry>,
    /// One per `[[net]]`, in declaration order.
    pub nets: Vec<LoadedNet>,
    /// Every file the project is built from: the project file, then each
    /// model file in the order it was first read.
    pub files: Vec<PathBuf>,
}

/// Reads (or synthesises) the automaton of every supervisor of the project
/// `project`.
pub(crate) fn load(
    supervisors: &[Spanned<RawSupervisor>],
    nets: &[Spanned<RawNet>],
    project: &ProjectFile,
) -> Result<Sources> {
    let mut loader = Loader {
        project,
        dir: project
            .path()
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default(),
        files: vec![project.path().to_path_buf()],
    };
    let supervisors = supervisors
        .iter()
        .map(|sup| loader.supervisor(sup))
        .collect::<Result<_>>()?;
    let nets = nets
        .iter()
        .map(|net| loader.net(net))
        .collect::<Result<_>>()?;
    Ok(Sources {
        supervisors,
        nets,
        files: loader.files,
    })
}

struct Loader<'a> {
    project: &'a ProjectFile<'a>,
    /// The project file's directory, which model paths are relative to.
    dir: PathBuf,
    files: Vec<PathBuf>,
}

fn kind_list(kinds: &[Kind]) -> String {
    kinds
        .iter()
        .map(Kind::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

impl Loader<'_> {
    fn error(&self, span: &Range<usize>, message: impl Into<String>) -> Error {
        self.project.error(span, message)
    }

    /// Records a model file for `rerun-if-changed` (once).
    fn depend_on(&mut self, file: &Path) {
        if !self.files.iter().any(|f| f == file) {
            self.files.push(file.to_path_buf());
        }
    }

    /// The automaton `sup` names, where it came from, and the automata of
    /// its source files.
    fn supervisor(&mut self, sup: &Spanned<RawSupervisor>) -> Result<LoadedEntry> {
        let header = sup.span();
        let raw = sup.get_ref();
        let symbolic = raw
            .synthesize
            .as_ref()
            .and_then(|s| s.get_ref().symbolic.as_ref())
            .is_some_and(|b| *b.get_ref());
        if let Some(guards) = &raw.guards {
            if let Some(other) = raw.file.as_ref().or(raw.component.as_ref()) {
                return Err(self.error(
                    &other.span(),
                    "a supervisor with `guards` takes its components from the guard file: no `file` or `component`",
                ));
            }
            if let Some(s) = &raw.synthesize {
                return Err(self.error(
                    &s.span(),
                    "a supervisor has either `guards` or `synthesize`, not both",
                ));
            }
            return self.guard_file(guards).map(LoadedEntry::Guarded);
        }
        if symbolic && raw.file.is_none() {
            if let Some(c) = &raw.component {
                return Err(self.error(
                    &c.span(),
                    "`component` selects from a `file`; a synthesised supervisor has none",
                ));
            }
            let synth = raw
                .synthesize
                .as_ref()
                .expect("symbolic implies synthesize");
            return self.synthesize_symbolic(synth).map(LoadedEntry::Guarded);
        }
        let automaton = match (&raw.file, &raw.synthesize) {
            (Some(_), Some(s)) => Err(self.error(
                &s.span(),
                "a supervisor has either `file` or `synthesize`, not both",
            )),
            (None, None) => Err(self.error(
                &header,
                "a supervisor needs `file = \"…\"`, `synthesize = { plants = […], specs = […] }` or `guards = \"….guards.toml\"`",
            )),
            (Some(file), None) => {
                let path = self.dir.join(file.get_ref());
                let components = self.read_model(&path, &file.span())?;
                let automaton =
                    self.select(components, raw.component.as_ref(), &path, &file.span())?;
                let origins = vec![ModelOrigin {
                    file: path.clone(),
                    name: automaton.name().to_owned(),
                    alphabet: automaton.alphabet().clone(),
                }];
                Ok(LoadedSupervisor {
                    automaton,
                    source: SupervisorSource::File(path),
                    origins,
                })
            }
            (None, Some(synth)) => {
                if let Some(c) = &raw.component {
                    return Err(self.error(
                        &c.span(),
                        "`component` selects from a `file`; a synthesised supervisor has none",
                    ));
                }
                return self.synthesize(synth);
            }
        };
        automaton.map(LoadedEntry::Automaton)
    }

    /// The net of a `[[net]]`: read, its control places synthesised when
    /// it has `constraints`, and its reachability graph explored (the
    /// counters' widths come from the bounds, so an unbounded net, or one
    /// beyond `max_markings`, is refused here).
    fn net(&mut self, raw: &Spanned<RawNet>) -> Result<LoadedNet> {
        use des::petri::{self, reach};
        let r = raw.get_ref();
        let file = &r.file;
        let path = self.dir.join(file.get_ref());
        let control = self.net_control(raw)?;
        let plant = self.read_net(&path, &file.span(), &control)?;
        let (net, source, control_places) = match &r.constraints {
            None => {
                if let Some(t) = &r.transform {
                    return Err(self.error(
                        &t.span(),
                        "`transform` applies to `constraints`; this net has none",
                    ));
                }
                (plant, NetSource::File(path), 0)
            }
            Some(c) => {
                let constraints_path = self.dir.join(c.get_ref());
                self.check_printable(&constraints_path, &c.span(), None)?;
                self.depend_on(&constraints_path);
                let constraints = petri::constraints::read_file(&constraints_path, &plant)
                    .map_err(|e| self.located_io(e, &c.span(), "constraints", ".toml"))?;
                let transform = r.transform.as_ref().is_some_and(|t| *t.get_ref());
                let enforced = petri::admissible::enforced(&plant, &constraints, transform)?;
                let supervised = petri::synth::synthesize(&plant, &enforced)?;
                let source = NetSource::Synthesized {
                    plant: path,
                    constraints: constraints_path,
                    transform,
                };
                (supervised.net, source, supervised.control.len())
            }
        };
        let max = match &r.max_markings {
            None => reach::DEFAULT_MAX_STATES,
            Some(n) => match usize::try_from(*n.get_ref()) {
                Ok(n) if n > 0 => n,
                _ => {
                    return Err(self.error(
                        &n.span(),
                        "max_markings must be a positive number of markings",
                    ))
                }
            },
        };
        // The exploration's refusals name no file: they are located here,
        // at the `[[net]]` entry, once.
        let reach = reach::reachability(&net, max).map_err(|e| {
            let hint = match &e {
                Error::StateLimit { .. } => " (raise it with `max_markings`)",
                Error::Incompatible(_) => "",
                _ => return e,
            };
            self.error(
                &raw.span(),
                format!(
                    "net `{}`: {e}{hint}; a net runs with a counter per place, so it must be bounded",
                    r.name.get_ref()
                ),
            )
        })?;
        Ok(LoadedNet {
            net,
            source,
            reach,
            control_places,
        })
    }

    /// Reads a net file named at `span` (`.toml` or `.pnml`), with what
    /// its `[[net]]` entry states about its transitions.
    fn read_net(
        &mut self,
        file: &Path,
        span: &Range<usize>,
        control: &des::petri::control::Control,
    ) -> Result<des::petri::PetriNet> {
        self.check_printable(file, span, None)?;
        self.depend_on(file);
        des::petri::read_file_with(file, control)
            .map_err(|e| self.located_io(e, span, "net", ".toml or .pnml"))
    }

    /// What a `[[net]]` entry states about its net's transitions:
    /// `uncontrollable` and `unobservable` lists, or a `control` file.
    fn net_control(&mut self, raw: &Spanned<RawNet>) -> Result<des::petri::control::Control> {
        use des::petri::control::{self, Control, Listed};
        let r = raw.get_ref();
        let hint = format!(
            "add `uncontrollable = [\"T1\", …]` (the others are controllable; [] for none) \
             or `control = \"FILE\"` to the [[net]] at {}",
            self.project.location(&raw.span())
        );
        if let Some(c) = &r.control {
            if let Some(list) = r.uncontrollable.as_ref().or(r.unobservable.as_ref()) {
                return Err(self.error(
                    &list.span(),
                    "`control` names a file that states this: give `uncontrollable` and `unobservable` there, not both ways",
                ));
            }
            let path = self.dir.join(c.get_ref());
            self.check_printable(&path, &c.span(), None)?;
            self.depend_on(&path);
            return control::read_file(&path, hint)
                .map_err(|e| self.located_io(e, &c.span(), "control", ".toml"));
        }
        let list = |key: &str, field: &Option<Spanned<super::parse::Names>>| {
            field.as_ref().map(|f| Listed {
                source: format!("`{key}` in {}", self.project.path().display()),
                ids: names(Some(f))
                    .into_iter()
                    .map(|n| {
                        let at = self.project.location(&n.span());
                        (n.into_inner(), Some(at))
                    })
                    .collect(),
            })
        };
        Ok(Control {
            uncontrollable: list("uncontrollable", &r.uncontrollable),
            unobservable: list("unobservable", &r.unobservable),
            hint,
        })
    }

    /// An I/O or format error of a file named at `span`, located there;
    /// errors inside the file unchanged.
    /// `what` is the kind of file (`model`), `expected` its extensions.
    fn located_io(&self, e: Error, span: &Range<usize>, what: &str, expected: &str) -> Error {
        match e {
            Error::Io { path, source } => self.error(
                span,
                format!("cannot read {what} file `{}`: {source}", path.display()),
            ),
            Error::UnknownFormat { path } => self.error(
                span,
                format!(
                    "`{}`: unknown {what} format (expected {expected})",
                    path.display()
                ),
            ),
            other => other,
        }
    }

    /// Synthesises the supervisor of `synthesize = { … }`; with `reduce`
    /// or `localize`, the reduced supervisor or the local controllers and
    /// the plant components they run beside.
    fn synthesize(&mut self, synth: &Spanned<super::parse::RawSynthesize>) -> Result<LoadedEntry> {
        let s = synth.get_ref();
        let SynthesisModels {
            plants,
            plant_automata,
            specs,
            spec_automata,
            origins,
        } = self.synthesis_models(s)?;
        let max_states = match &s.max_states {
            None => ops::sync::DEFAULT_MAX_STATES,
            Some(n) => match usize::try_from(*n.get_ref()) {
                Ok(n) if n > 0 => n,
                _ => {
                    return Err(
                        self.error(&n.span(), "max_states must be a positive number of states")
                    )
                }
            },
        };
        let reduce = s.reduce.as_ref().is_some_and(|r| *r.get_ref());
        let localize = s.localize.as_ref().filter(|l| *l.get_ref());
        if let (true, Some(l)) = (reduce, localize) {
            return Err(self.error(
                &l.span(),
                "`localize` and `reduce` are two ways to shrink one supervisor: choose one",
            ));
        }
        if let (true, Some(l)) = (s.minimize, localize) {
            return Err(self.error(
                &l.span(),
                "`localize` minimises each local controller itself: no `minimize` with it",
            ));
        }
        let options = ops::SynthesisOptions {
            minstate: s.minimize,
            reduce,
            compose: ops::ComposeOptions {
                max_states,
                ..ops::ComposeOptions::default()
            },
        };
        // Synthesis's refusals name no file: they are located here, at
        // `synthesize`, once.
        let synthesis = ops::synthesize(&plant_automata, &spec_automata, options).map_err(|e| {
            let hint = match &e {
                Error::StateLimit { .. } => " (raise it with `max_states` in `synthesize`)",
                Error::Incompatible(_) => "",
                _ => return e,
            };
            self.error(
                &synth.span(),
                format!("cannot synthesise the supervisor: {e}{hint}"),
            )
        })?;
        if synthesis.supervisor.is_empty() {
            return Err(self.error(
                &synth.span(),
                "synthesis gave the empty supervisor: the specification cannot be enforced",
            ));
        }
        let source = |local: Option<String>| SupervisorSource::Synthesized {
            plants: plants.clone(),
            specs: specs.clone(),
            minimized: s.minimize,
            reduced: reduce,
            local,
        };
        if !reduce && localize.is_none() {
            return Ok(LoadedEntry::Automaton(LoadedSupervisor {
                automaton: synthesis.supervisor,
                source: source(None),
                origins,
            }));
        }
        if let (Some(l), false) = (localize, synthesis.unobservable.is_empty()) {
            return Err(self.error(
                &l.span(),
                format!(
                    "localization assumes a supervisor that sees every event, and the plant's \
                     events {} are unobservable: synthesise without `localize`",
                    quoted_list(&synthesis.unobservable)
                ),
            ));
        }
        let controllers = if localize.is_some() {
            let located = |e: Error| {
                self.error(
                    &synth.span(),
                    format!("cannot localize the supervisor: {e}"),
                )
            };
            let localization = ops::localize(&synthesis.plant, &synthesis.supervisor, max_states)
                .map_err(located)?;
            ops::check_localized(
                &synthesis.plant,
                &synthesis.supervisor,
                &localization,
                options.compose,
            )
            .map_err(located)?;
            localization
                .controllers
                .into_iter()
                .map(|(event, automaton)| {
                    let loaded = LoadedSupervisor {
                        automaton,
                        source: source(Some(event.clone())),
                        origins: origins.clone(),
                    };
                    (Some(event), loaded)
                })
                .collect()
        } else {
            vec![(
                None,
                LoadedSupervisor {
                    automaton: synthesis.supervisor,
                    source: source(None),
                    origins: origins.clone(),
                },
            )]
        };
        let plant = plant_automata.into_iter().zip(origins).collect();
        Ok(LoadedEntry::Reduced(controllers, plant))
    }

    /// Refuses a model path that a build script could not print for cargo
    /// ([`printable_path`]), at `span`, naming the glob `pattern` that
    /// matched it if any.
    fn check_printable(
        &self,
        file: &Path,
        span: &Range<usize>,
        pattern: Option<&str>,
    ) -> Result<()> {
        printable_path(file).map(drop).map_err(|reason| {
            let matched = pattern.map_or(String::new(), |p| format!(" (matched by `{p}`)"));
            self.error(
                span,
                format!(
                    "model file {file:?}{matched}: {reason}; rename the file \
                     (a build script could not name it to cargo)"
                ),
            )
        })
    }

    /// Reads a model file named at `span`; I/O and format errors are
    /// reported at that line, errors inside the file propagate unchanged.
    fn read_model(&mut self, file: &Path, span: &Range<usize>) -> Result<Vec<Component>> {
        self.check_printable(file, span, None)?;
        self.depend_on(file);
        formats::read_file(file)
            .map_err(|e| self.located_io(e, span, "model", ".toml, .gen, .ads or .wmod"))
    }

    /// Picks the supervisor among a file's components.
    fn select(
        &self,
        mut components: Vec<Component>,
        wanted: Option<&Name>,
        path: &Path,
        file_span: &Range<usize>,
    ) -> Result<Automaton> {
        let listing = |components: &[Component]| {
            components
                .iter()
                .map(|c| format!("`{}` ({})", c.automaton.name(), c.kind))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if let Some(name) = wanted {
            return match components
                .iter()
                .position(|c| c.automaton.name() == name.get_ref())
            {
                Some(i) => Ok(components.swap_remove(i).automaton),
                None => Err(self.error(
                    &name.span(),
                    format!(
                        "`{}` has no component `{}` (components: {})",
                        path.display(),
                        name.get_ref(),
                        listing(&components)
                    ),
                )),
            };
        }
        let candidates: Vec<usize> = components
            .iter()
            .enumerate()
            .filter(|(_, c)| matches!(c.kind, Kind::Supervisor | Kind::Spec | Kind::Unspecified))
            .map(|(i, _)| i)
            .collect();
        match candidates.as_slice() {
            [i] => Ok(components.swap_remove(*i).automaton),
            [] => Err(self.error(
                file_span,
                format!(
                    "`{}` holds no supervisor, spec or unspecified component (components: {}); name the one to run with `component = \"…\"`",
                    path.display(),
                    listing(&components)
                ),
            )),
            _ => Err(self.error(
                file_span,
                format!(
                    "`{}` holds several components that could be the supervisor ({}); name one with `component = \"…\"`",
                    path.display(),
                    listing(&components)
                ),
            )),
        }
    }

    /// The files `patterns` (relative to the project directory) match,
    /// each with the span of the pattern that matched it first.
    fn expand(&self, patterns: &[Name]) -> Result<Vec<(PathBuf, Range<usize>)>> {
        let mut files: Vec<(PathBuf, Range<usize>)> = Vec::new();
        for pattern in patterns {
            let p = pattern.get_ref();
            let span = pattern.span();
            if !p.contains(['*', '?', '[']) {
                let file = self.dir.join(p);
                if !files.iter().any(|(f, _)| *f == file) {
                    files.push((file, span));
                }
                continue;
            }
            let full = if Path::new(p).is_absolute() || self.dir.as_os_str().is_empty() {
                p.clone()
            } else {
                let dir = self.dir.to_str().ok_or_else(|| {
                    self.error(
                        &span,
                        format!(
                            "cannot expand `{p}`: the project directory `{}` is not valid UTF-8",
                            self.dir.display()
                        ),
                    )
                })?;
                format!("{}/{p}", glob::Pattern::escape(dir))
            };
            let matches = glob::glob(&full)
                .map_err(|e| self.error(&span, format!("invalid file pattern `{p}`: {}", e.msg)))?;
            let mut matched = Vec::new();
            for m in matches {
                let file = m.map_err(|e| {
                    self.error(
                        &span,
                        format!("cannot expand `{p}`: {}: {}", e.path().display(), e.error()),
                    )
                })?;
                if !file.is_file() {
                    continue;
                }
                self.check_printable(&file, &span, Some(p))?;
                if !files.iter().any(|(f, _)| *f == file) {
                    files.push((file.clone(), span.clone()));
                }
                matched.push(file);
            }
            self.check_listable(&full, &matched, &span, p)?;
            if matched.is_empty() {
                return Err(self.error(
                    &span,
                    format!(
                        "`{p}` matches no file (patterns are relative to `{}`)",
                        if self.dir.as_os_str().is_empty() {
                            ".".to_owned()
                        } else {
                            self.dir.display().to_string()
                        }
                    ),
                ));
            }
        }
        Ok(files)
    }

    /// Refuses the pattern `p` (expanded to `full`) when a directory it
    /// searched holds a name that is not UTF-8: the glob crate skips such
    /// names without a word, so a plant could silently drop out of a
    /// synthesis. The directories checked are the one before the first
    /// wildcard and the directory of every file `matched` by the pattern.
    fn check_listable(
        &self,
        full: &str,
        matched: &[PathBuf],
        span: &Range<usize>,
        p: &str,
    ) -> Result<()> {
        let literal: PathBuf = Path::new(full)
            .components()
            .take_while(|c| !c.as_os_str().to_string_lossy().contains(['*', '?', '[']))
            .collect();
        let literal = if literal.as_os_str().is_empty() {
            PathBuf::from(".")
        } else {
            literal
        };
        let mut dirs = vec![literal];
        for file in matched {
            if let Some(parent) = file.parent() {
                if !dirs.iter().any(|d| d == parent) {
                    dirs.push(parent.to_owned());
                }
            }
        }
        for dir in dirs {
            let Ok(entries) = std::fs::read_dir(&dir) else {
                continue;
            };
            for entry in entries.flatten() {
                if entry.file_name().to_str().is_none() {
                    return Err(self.error(
                        span,
                        format!(
                            "`{p}` cannot tell whether it matches {:?}: the name is not valid UTF-8; \
                             rename the file",
                            entry.path()
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The plant and specification files of `synthesize` and their
    /// automata: every plant and unspecified one of the `plants` files,
    /// every specification, supervisor and unspecified one of the `specs`
    /// files.
    fn synthesis_models(&mut self, s: &super::parse::RawSynthesize) -> Result<SynthesisModels> {
        let plant_patterns = names(Some(&s.plants));
        if plant_patterns.is_empty() {
            return Err(self.error(&s.plants.span(), "synthesis needs at least one plant"));
        }
        let mut origins = Vec::new();
        let (plants, plant_automata) = self.synthesis_inputs(
            &plant_patterns,
            &[Kind::Plant, Kind::Unspecified],
            "plant",
            &mut origins,
        )?;
        let (specs, spec_automata) = self.synthesis_inputs(
            &names(s.specs.as_ref()),
            &[Kind::Spec, Kind::Supervisor, Kind::Unspecified],
            "specification",
            &mut origins,
        )?;
        Ok(SynthesisModels {
            plants,
            plant_automata,
            specs,
            spec_automata,
            origins,
        })
    }

    /// The components of `patterns`' files whose kind is in `kinds`, and
    /// the files, for a synthesis `role` (plant or specification).
    fn synthesis_inputs(
        &mut self,
        patterns: &[Name],
        kinds: &[Kind],
        role: &str,
        origins: &mut Vec<ModelOrigin>,
    ) -> Result<(Vec<PathBuf>, Vec<Automaton>)> {
        let mut paths = Vec::new();
        let mut automata = Vec::new();
        for (file, span) in self.expand(patterns)? {
            let before = automata.len();
            for c in self.read_model(&file, &span)? {
                if kinds.contains(&c.kind) {
                    origins.push(ModelOrigin {
                        file: file.clone(),
                        name: c.automaton.name().to_owned(),
                        alphabet: c.automaton.alphabet().clone(),
                    });
                    automata.push(c.automaton);
                }
            }
            if automata.len() == before {
                return Err(self.error(
                    &span,
                    format!(
                        "`{}` holds no component usable as a {role} (kinds: {})",
                        file.display(),
                        kind_list(kinds)
                    ),
                ));
            }
            paths.push(file);
        }
        Ok((paths, automata))
    }
}

/// `names` as `` `a`, `b` `` for messages.
fn quoted_list(names: &[String]) -> String {
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::super::from_str;
    use std::path::Path;

    #[test]
    fn a_missing_model_file_is_reported_at_its_line_before_any_declaration_error() {
        let err = from_str(
            "[plc]\nname = \"p\"\nreset = \"nowhere\"\n[[supervisor]]\nfile = \"absent.toml\"\n",
            Path::new("dir/p.plc.toml"),
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.starts_with("dir/p.plc.toml:5:8: cannot read model file `dir/absent.toml`"),
            "{err}"
        );
    }

    /// A project in a fresh directory whose only supervisor is synthesised
    /// from `plants = [pattern]`, with the model file `plant/<name>`.
    fn globbed_project(name: &std::ffi::OsStr) -> (tempfile::TempDir, String) {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("plant")).unwrap();
        std::fs::write(dir.path().join("plant").join(name), "").unwrap();
        let project = dir.path().join("p.plc.toml");
        let text =
            "[plc]\nname = \"p\"\n[[supervisor]]\nsynthesize = { plants = [\"plant/*.toml\"] }\n";
        let err = from_str(text, &project).unwrap_err().to_string();
        (dir, err)
    }

    #[cfg(unix)]
    #[test]
    fn a_file_name_that_is_not_utf8_where_a_pattern_looks_is_refused_not_skipped() {
        use std::os::unix::ffi::OsStrExt;
        let (dir, err) = globbed_project(std::ffi::OsStr::from_bytes(b"\xffplant.toml"));
        let dir = dir.path().display();
        assert_eq!(
            err,
            format!(
                "{dir}/p.plc.toml:4:26: `plant/*.toml` cannot tell whether it matches \
                 \"{dir}/plant/\\xFFplant.toml\": the name is not valid UTF-8; rename the file"
            )
        );
    }

    #[test]
    fn a_globbed_model_file_with_a_line_break_in_its_name_is_refused_at_its_pattern() {
        let (dir, err) = globbed_project("plant\ncargo:rustc-env=PWNED=1.toml".as_ref());
        let dir = dir.path().display();
        assert_eq!(
            err,
            format!(
                "{dir}/p.plc.toml:4:26: model file \"{dir}/plant/plant\\ncargo:rustc-env=PWNED=1.toml\" \
                 (matched by `plant/*.toml`): it holds the control character U+000A; rename the file \
                 (a build script could not name it to cargo)"
            )
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_model_path_that_is_not_utf8_is_refused_at_its_line() {
        use std::os::unix::ffi::OsStrExt;
        let project = Path::new(std::ffi::OsStr::from_bytes(b"\xff/p.plc.toml"));
        let err = from_str(
            "[plc]\nname = \"p\"\n[[supervisor]]\nfile = \"m.toml\"\n",
            project,
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            err,
            "\u{fffd}/p.plc.toml:4:8: model file \"\\xFF/m.toml\": it is not valid UTF-8; \
             rename the file (a build script could not name it to cargo)"
        );
    }

    #[test]
    fn a_named_model_file_with_a_carriage_return_is_refused_at_its_line() {
        let err = from_str(
            "[plc]\nname = \"p\"\n[[supervisor]]\nfile = \"m\\r.toml\"\n",
            Path::new("dir/p.plc.toml"),
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            err,
            "dir/p.plc.toml:4:8: model file \"dir/m\\r.toml\": it holds the control character \
             U+000D; rename the file (a build script could not name it to cargo)"
        );
    }

    #[test]
    fn a_synthesised_supervisor_takes_no_component() {
        let err = from_str(
            "[plc]\nname = \"p\"\n[[supervisor]]\nsynthesize = { plants = \"m.toml\" }\ncomponent = \"x\"\n",
            Path::new("p.plc.toml"),
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            err,
            "p.plc.toml:5:13: `component` selects from a `file`; a synthesised supervisor has none"
        );
    }
}
