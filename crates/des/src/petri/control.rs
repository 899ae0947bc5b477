//! Which transitions are uncontrollable or unobservable, stated beside the
//! net file.
//!
//! PNML has no word for controllability: our own files carry it in a
//! tool-specific element ([`super::pnml`]), but nets from other editors
//! (PIPE, TINA, WoPeD, …) carry none. A [`Control`] states it from outside
//! the file: the command line (`codegen petri … --uncontrollable t1,t2
//! --unobservable t3`), a control file (`--control FILE`, [`read_file`]) or
//! a PLC project's `[[net]]` entry. Each of the two lists, when given, is
//! the whole truth about its property: the transitions listed are
//! uncontrollable (unobservable), every other is controllable (observable).
//!
//! The rules, applied by the readers of both net formats:
//!
//! - a list names transitions of the net; any other name is an error naming
//!   it (a typo would otherwise leave a transition controllable);
//! - where the file states a property too, it must agree with the list (an
//!   error at the transition otherwise): nothing is changed silently;
//! - a transition whose controllability neither the file nor a list states
//!   is refused; when no transition of the file states it, the error says
//!   so once, for the whole file, with the way to state it ([`Control`]'s
//!   hint). Taking it as controllable would let a supervisor count on
//!   disabling what it cannot;
//! - observability unstated everywhere is "observable", as in both formats.
//!
//! The control file is TOML, both keys optional, unknown keys refused:
//!
//! ```toml
//! uncontrollable = ["t2", "t4"]   # every other transition controllable
//! unobservable = ["t3"]           # every other transition observable
//! ```

use super::PetriNet;
use crate::error::{Error, Location, Result};
use crate::files::FileKind;
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// Control files as [`crate::files`] reads them: a regular file of at most
/// 4 MiB (lists of ids; 200,000 transitions fit).
pub const CONTROL_FILE: FileKind = FileKind::new("control file", 4 << 20);

/// One list of transition ids and where it was given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Listed {
    /// Where the list comes from, as errors name it: `--uncontrollable`,
    /// or the key (`uncontrollable`) when every id has its location.
    pub source: String,
    /// The ids, each with its location in a file when it has one.
    pub ids: Vec<(String, Option<Location>)>,
}

impl Listed {
    /// A list given on the command line as `option`.
    pub fn from_option(option: &str, ids: impl IntoIterator<Item = String>) -> Listed {
        Listed {
            source: option.to_owned(),
            ids: ids.into_iter().map(|id| (id, None)).collect(),
        }
    }

    fn has(&self, id: &str) -> bool {
        self.ids.iter().any(|(i, _)| i == id)
    }
}

/// What is stated beside a net file about its transitions (see the module
/// documentation); the default states nothing.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Control {
    /// The uncontrollable transitions, when stated: every other one is
    /// controllable.
    pub uncontrollable: Option<Listed>,
    /// The unobservable transitions, when stated: every other one is
    /// observable.
    pub unobservable: Option<Listed>,
    /// How a user states controllability where this net is read (for
    /// instance `give --uncontrollable T1,T2 …`), ending the error about a
    /// net that does not say.
    pub hint: String,
}

/// What a net file says of one transition.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Stated {
    pub controllable: Option<bool>,
    pub observable: Option<bool>,
}

impl Control {
    /// Nothing stated; `hint` says how one would state it.
    pub fn none(hint: impl Into<String>) -> Control {
        Control {
            hint: hint.into(),
            ..Control::default()
        }
    }

    /// Whether controllability is stated here.
    pub fn states_controllability(&self) -> bool {
        self.uncontrollable.is_some()
    }

    fn hint(&self) -> String {
        if self.hint.is_empty() {
            "state which transitions are uncontrollable beside the file".to_owned()
        } else {
            self.hint.clone()
        }
    }

    /// The refusal of a net none of whose `count` transitions says whether
    /// it is controllable, at `at`.
    pub(crate) fn unstated(&self, at: Location, count: usize) -> Error {
        Error::model(
            at,
            format!(
                "none of the net's {count} transitions says whether it is controllable \
                 (PNML from other tools carries no controllability): {}",
                self.hint()
            ),
        )
    }

    /// Transition `id`'s `(controllable, observable)` from what its file
    /// states (`stated`, at `at`) and what is stated here.
    pub(crate) fn resolve(&self, id: &str, stated: Stated, at: &Location) -> Result<(bool, bool)> {
        let property = |list: &Option<Listed>,
                        file: Option<bool>,
                        yes: &str,
                        no: &str|
         -> Result<Option<bool>> {
            let Some(list) = list else { return Ok(file) };
            let value = !list.has(id);
            match file {
                Some(w) if w != value => Err(Error::model(
                    at.clone(),
                    format!(
                        "transition `{id}` is {} in this file, but {} {}",
                        if w { yes } else { no },
                        list.source,
                        if value {
                            "does not list it"
                        } else {
                            "lists it"
                        }
                    ),
                )),
                _ => Ok(Some(value)),
            }
        };
        let controllable = property(
            &self.uncontrollable,
            stated.controllable,
            "controllable",
            "uncontrollable",
        )?
        .ok_or_else(|| {
            Error::model(
                at.clone(),
                format!(
                    "transition `{id}` does not say whether it is controllable: {}",
                    self.hint()
                ),
            )
        })?;
        let observable = property(
            &self.unobservable,
            stated.observable,
            "observable",
            "unobservable",
        )?
        .unwrap_or(true);
        Ok((controllable, observable))
    }

    /// Checks that every listed id is a transition of `net`, read from
    /// `origin`.
    pub(crate) fn check_names(&self, net: &PetriNet, origin: &Path) -> Result<()> {
        for list in [&self.uncontrollable, &self.unobservable]
            .into_iter()
            .flatten()
        {
            for (id, at) in &list.ids {
                if net.transition(id).is_some() {
                    continue;
                }
                let what = if net.place(id).is_some() {
                    "a place, not a transition,"
                } else {
                    "no transition"
                };
                let message = format!(
                    "{} names `{id}`, which is {what} of `{}`",
                    list.source,
                    origin.display()
                );
                return Err(match at {
                    Some(at) => Error::model(at.clone(), message),
                    None => Error::Incompatible(message),
                });
            }
        }
        Ok(())
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    #[serde(default)]
    uncontrollable: Option<Vec<Spanned<String>>>,
    #[serde(default)]
    unobservable: Option<Vec<Spanned<String>>>,
}

/// Parses a control file; `origin` names it in errors, and `hint` goes
/// into the [`Control`].
pub fn read(text: &str, origin: &Path, hint: impl Into<String>) -> Result<Control> {
    let file: File = crate::formats::toml::parse(text, origin)?;
    let list = |key: &str, ids: Option<Vec<Spanned<String>>>| {
        ids.map(|ids| Listed {
            source: format!("`{key}` in {}", origin.display()),
            ids: ids
                .into_iter()
                .map(|s| {
                    let at = Location::at_offset(origin, text, s.span().start);
                    (s.into_inner(), Some(at))
                })
                .collect(),
        })
    };
    Ok(Control {
        uncontrollable: list("uncontrollable", file.uncontrollable),
        unobservable: list("unobservable", file.unobservable),
        hint: hint.into(),
    })
}

/// Reads the control file at `path` ([`CONTROL_FILE`]'s rules).
pub fn read_file(path: &Path, hint: impl Into<String>) -> Result<Control> {
    let text = crate::files::read_text(path, CONTROL_FILE)?;
    read(&text, path, hint)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at() -> Location {
        Location::new("n.pnml", 3, 7)
    }

    fn stated(controllable: Option<bool>, observable: Option<bool>) -> Stated {
        Stated {
            controllable,
            observable,
        }
    }

    fn option(name: &str, ids: &[&str]) -> Option<Listed> {
        Some(Listed::from_option(name, ids.iter().map(|s| s.to_string())))
    }

    #[test]
    fn a_list_decides_for_every_transition_and_must_agree_with_the_file() {
        let c = Control {
            uncontrollable: option("--uncontrollable", &["t2"]),
            unobservable: option("--unobservable", &["t3"]),
            hint: String::new(),
        };
        let none = stated(None, None);
        assert_eq!(c.resolve("t1", none, &at()).unwrap(), (true, true));
        assert_eq!(c.resolve("t2", none, &at()).unwrap(), (false, true));
        assert_eq!(c.resolve("t3", none, &at()).unwrap(), (true, false));
        assert_eq!(
            c.resolve("t2", stated(Some(false), Some(true)), &at())
                .unwrap(),
            (false, true)
        );
        assert_eq!(
            c.resolve("t1", stated(Some(false), None), &at()).unwrap_err().to_string(),
            "n.pnml:3:7: transition `t1` is uncontrollable in this file, but --uncontrollable does not list it"
        );
        assert_eq!(
            c.resolve("t3", stated(None, Some(true)), &at())
                .unwrap_err()
                .to_string(),
            "n.pnml:3:7: transition `t3` is observable in this file, but --unobservable lists it"
        );
    }

    #[test]
    fn without_a_list_the_file_decides_and_controllability_is_required() {
        let c = Control::none("give --uncontrollable");
        assert_eq!(
            c.resolve("t", stated(Some(false), None), &at()).unwrap(),
            (false, true),
            "observable unless said otherwise"
        );
        assert_eq!(
            c.resolve("t", stated(None, Some(false)), &at()).unwrap_err().to_string(),
            "n.pnml:3:7: transition `t` does not say whether it is controllable: give --uncontrollable"
        );
    }

    #[test]
    fn a_control_file_locates_its_names() {
        let text = "uncontrollable = [\"t2\",\n  \"t9\"]\n";
        let c = read(text, Path::new("c.toml"), "").unwrap();
        let list = c.uncontrollable.as_ref().unwrap();
        assert_eq!(list.ids[1].0, "t9");
        assert_eq!(list.ids[1].1, Some(Location::new("c.toml", 2, 3)));
        assert!(c.unobservable.is_none());
        let err = read("uncontrolable = []\n", Path::new("c.toml"), "")
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("c.toml:1:1: unknown field `uncontrolable`"),
            "{err}"
        );
    }
}
