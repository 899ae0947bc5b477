//! A project loaded with its synthesised supervisors shrunk: every
//! `synthesize = { … }` that makes one automaton, without `reduce` or
//! `localize`, read as if it said `reduce = true` (or `localize = true`).
//!
//! This is how a tool tries the smaller forms of a project without a
//! second project file: the ladder export falls back on it when the full
//! supervisor's rungs are over their limit. The override is applied to
//! the parsed declarations, before the supervisors are synthesised, so
//! the reduced supervisor or the local controllers come out of the same
//! code path as a file that asks for them, with the same closed-loop
//! check ([`des::ops::check_closed_loop`], [`des::ops::check_localized`])
//! and the same errors, located at the `synthesize` that was overridden.

use super::parse::RawProject;
use toml::Spanned;

/// The smaller form a project's synthesised supervisors are loaded in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shrink {
    /// Supervisor reduction (`reduce = true`): one reduced supervisor
    /// beside the plant components.
    Reduce,
    /// Localization (`localize = true`): one local controller per
    /// controllable event beside the plant components. `minimize` is
    /// dropped: localization minimises each local controller itself, and
    /// minimising the supervisor first does not change its closed loop.
    Localize,
}

impl Shrink {
    /// The `synthesize` key that asks for this form.
    pub fn key(self) -> &'static str {
        match self {
            Shrink::Reduce => "reduce",
            Shrink::Localize => "localize",
        }
    }

    /// The form's name in prose: `reduced` or `localized`.
    pub fn adjective(self) -> &'static str {
        match self {
            Shrink::Reduce => "reduced",
            Shrink::Localize => "localized",
        }
    }
}

/// Makes every supervisor of `raw` that synthesises one automaton
/// without `reduce` or `localize` (and is not `symbolic`) shrink it the
/// `shrink` way; the key's span is the whole `synthesize` value, where
/// its errors are reported. The number of supervisors changed.
pub(crate) fn apply(raw: &mut RawProject, shrink: Shrink) -> usize {
    let mut changed = 0;
    for sup in &mut raw.supervisor {
        let Some(synth) = sup.get_mut().synthesize.as_mut() else {
            continue;
        };
        let span = synth.span();
        let s = synth.get_mut();
        let set = |flag: &Option<Spanned<bool>>| flag.as_ref().is_some_and(|f| *f.get_ref());
        if set(&s.symbolic) || set(&s.reduce) || set(&s.localize) {
            continue;
        }
        match shrink {
            Shrink::Reduce => s.reduce = Some(Spanned::new(span, true)),
            Shrink::Localize => {
                s.localize = Some(Spanned::new(span, true));
                s.minimize = false;
            }
        }
        changed += 1;
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::Shrink;
    use crate::{load, load_shrunk, SupervisorSource};
    use std::path::{Path, PathBuf};

    fn model(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../models")
            .join(name)
    }

    /// The conveyor says `minimize = true`: localized, it drops it (the
    /// file alone would be refused) and runs one local controller per
    /// command beside its three plant components; reduced, one reduced
    /// supervisor beside them.
    #[test]
    fn a_synthesised_supervisor_loads_reduced_or_localized() {
        let path = model("conveyor.plc.toml");
        let full = load(&path).unwrap();
        assert_eq!(full.supervisors.len(), 1);
        let local = load_shrunk(&path, Shrink::Localize).unwrap().unwrap();
        let sources: Vec<_> = local.supervisors.iter().map(|s| &s.source).collect();
        let plants = sources
            .iter()
            .filter(
                |s| matches!(s, SupervisorSource::Plant { reduced, .. } if reduced == "conveyor"),
            )
            .count();
        let controllers: Vec<&str> = sources
            .iter()
            .filter_map(|s| match s {
                SupervisorSource::Synthesized {
                    local: Some(event),
                    minimized: false,
                    ..
                } => Some(event.as_str()),
                _ => None,
            })
            .collect();
        assert_eq!((plants, controllers), (3, vec!["start", "stop"]));
        let reduced = load_shrunk(&path, Shrink::Reduce).unwrap().unwrap();
        assert_eq!(reduced.supervisors.len(), 4);
        assert!(matches!(
            reduced.supervisors[3].source,
            SupervisorSource::Synthesized {
                reduced: true,
                local: None,
                ..
            }
        ));
    }

    /// A file asking for a symbolic supervisor in either form is refused
    /// at the key (`localize` was once ignored there).
    #[test]
    fn a_symbolic_supervisor_is_neither_reduced_nor_localized() {
        for key in ["reduce", "localize"] {
            let text = format!(
                "[plc]\nname = \"p\"\n[[supervisor]]\nsynthesize = {{ plants = [\"m.toml\"], symbolic = true, {key} = true }}\n"
            );
            let err = crate::from_str(&text, Path::new("p.plc.toml"))
                .unwrap_err()
                .to_string();
            let column = 54 + key.len() + 3;
            assert_eq!(
                err,
                format!(
                    "p.plc.toml:4:{column}: `{key}` {} one supervisor automaton; a symbolic supervisor has components and guards instead",
                    if key == "reduce" { "reduces" } else { "localizes" }
                )
            );
        }
    }

    /// Nothing to shrink: supervisors read from files, or synthesised
    /// symbolically.
    #[test]
    fn a_project_without_a_synthesised_automaton_has_no_shrunk_form() {
        for name in ["press.plc.toml", "module.plc.toml"] {
            for shrink in [Shrink::Reduce, Shrink::Localize] {
                assert!(
                    load_shrunk(&model(name), shrink).unwrap().is_none(),
                    "{name}"
                );
            }
        }
    }
}
