//! Symbolic supervisors: a guard file read with its components' model
//! files (`guards = "….guards.toml"`), or plants and specifications
//! synthesised on BDDs at build time (`synthesize = { …, symbolic = true
//! }`, the pipeline of `codegen synth --symbolic`).
//!
//! A guard file names each component's model file relative to its own
//! directory; the component is the automaton of that name in the file,
//! and its states must be those the file lists, in the same order (the
//! guards read state numbers). Errors inside the guard file point into
//! it; a file that is missing or disagrees with the guard file is reported
//! at the line of `guards`.

use super::{Loader, ModelOrigin};
use crate::model::GuardedSource;
use crate::parse::{Name, RawSynthesize};
use des::automaton::Automaton;
use des::error::{Error, Location, Result};
use des_symbolic::guard_file::GuardFile;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A symbolic supervisor as read or synthesised, not yet checked against
/// the project.
pub(crate) struct LoadedGuarded {
    /// The components and guards.
    pub file: GuardFile,
    /// Each component's automaton and model file, in the guard file's
    /// component order.
    pub components: Vec<(Automaton, PathBuf)>,
    /// The automata each component was read from (one per component).
    pub origins: Vec<ModelOrigin>,
    /// Where it came from.
    pub source: GuardedSource,
    /// The span of `guards` or `synthesize`, where problems with its
    /// content are reported.
    pub span: Range<usize>,
}

impl Loader<'_> {
    /// Reads the guard file `guards` names and its components.
    pub(super) fn guard_file(&mut self, guards: &Name) -> Result<LoadedGuarded> {
        let span = guards.span();
        let path = self.dir.join(guards.get_ref());
        self.check_printable(&path, &span, None)?;
        self.depend_on(&path);
        let text = std::fs::read_to_string(&path).map_err(|e| {
            self.error(
                &span,
                format!("cannot read guard file `{}`: {e}", path.display()),
            )
        })?;
        let file = GuardFile::parse(&text, &path).map_err(|e| {
            Error::model(
                Location::new(PathBuf::from(&e.file), e.line as u32, 1),
                e.message,
            )
        })?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let mut components = Vec::with_capacity(file.components.len());
        let mut origins = Vec::with_capacity(file.components.len());
        for c in &file.components {
            let Some(model) = &c.file else {
                return Err(self.error(
                    &span,
                    format!(
                        "component `{}` of `{}` names no `file`: the project cannot run it",
                        c.name,
                        path.display()
                    ),
                ));
            };
            let model = dir.join(model);
            let automata = self.read_model(&model, &span)?;
            let Some(automaton) = automata
                .into_iter()
                .map(|m| m.automaton)
                .find(|a| a.name() == c.name)
            else {
                return Err(self.error(
                    &span,
                    format!(
                        "component `{}` of `{}`: `{}` has no automaton of that name",
                        c.name,
                        path.display(),
                        model.display()
                    ),
                ));
            };
            let states: Vec<String> = automaton
                .states()
                .map(|s| automaton.state_name(s).into_owned())
                .collect();
            if states != c.states {
                return Err(self.error(
                    &span,
                    format!(
                        "component `{}` of `{}`: `{}` has the states [{}], the guard file was written for [{}]; synthesise the guards again",
                        c.name,
                        path.display(),
                        model.display(),
                        states.join(", "),
                        c.states.join(", ")
                    ),
                ));
            }
            origins.push(ModelOrigin {
                file: model.clone(),
                name: automaton.name().to_owned(),
                alphabet: automaton.alphabet().clone(),
            });
            components.push((automaton, model));
        }
        Ok(LoadedGuarded {
            file,
            components,
            origins,
            source: GuardedSource::File(path),
            span,
        })
    }

    /// Synthesises `synthesize = { …, symbolic = true }` on BDDs.
    pub(super) fn synthesize_symbolic(
        &mut self,
        synth: &Spanned<RawSynthesize>,
    ) -> Result<LoadedGuarded> {
        let s = synth.get_ref();
        if s.minimize {
            return Err(self.error(
                &synth.span(),
                "`minimize` minimises one automaton; a symbolic supervisor has components and guards instead",
            ));
        }
        if let Some(m) = &s.max_states {
            return Err(self.error(
                &m.span(),
                "`max_states` limits explicit compositions; symbolic synthesis builds none",
            ));
        }
        if let Some(r) = s.reduce.as_ref().filter(|r| *r.get_ref()) {
            return Err(self.error(
                &r.span(),
                "`reduce` reduces one supervisor automaton; a symbolic supervisor has components and guards instead",
            ));
        }
        if let Some(l) = s.localize.as_ref().filter(|l| *l.get_ref()) {
            return Err(self.error(
                &l.span(),
                "`localize` localizes one supervisor automaton; a symbolic supervisor has components and guards instead",
            ));
        }
        let super::SynthesisModels {
            plants,
            plant_automata,
            specs,
            spec_automata,
            origins,
        } = self.synthesis_models(s)?;
        let mut unobservable: Vec<String> = Vec::new();
        for a in plant_automata.iter().chain(&spec_automata) {
            for (_, e) in a.alphabet().unobservable() {
                if !unobservable.contains(&e.name) {
                    unobservable.push(e.name.clone());
                }
            }
        }
        if !unobservable.is_empty() {
            return Err(self.error(
                &synth.span(),
                format!(
                    "symbolic synthesis assumes a supervisor that sees every event, and the \
                     events {} are unobservable: synthesise without `symbolic` (the explicit \
                     supervisor runs projected onto the observable events)",
                    super::quoted_list(&unobservable)
                ),
            ));
        }
        let synthesis = des_symbolic::synthesize(&plant_automata, &spec_automata).map_err(|e| {
            self.error(
                &synth.span(),
                format!("cannot synthesise the supervisor: {e}"),
            )
        })?;
        if synthesis.is_empty() {
            return Err(self.error(
                &synth.span(),
                "synthesis gave the empty supervisor: the specification cannot be enforced",
            ));
        }
        // Named by validation (a symbolic `synthesize` needs `name`).
        let file = GuardFile::new("", &synthesis, &plant_automata, &spec_automata);
        let components = plant_automata
            .into_iter()
            .chain(spec_automata)
            .zip(&origins)
            .map(|(a, o)| (a, o.file.clone()))
            .collect();
        Ok(LoadedGuarded {
            file,
            components,
            origins,
            source: GuardedSource::Synthesized { plants, specs },
            span: synth.span(),
        })
    }
}
