//! State declarations as either flavour reads them, and the automaton
//! built from them: the naming rule of the module docs, builder errors
//! located in the file, the default name.

use crate::automaton::{Automaton, AutomatonBuilder, BuildError, StateId};
use crate::error::{line_column, Error, Location, Result};
use rustc_hash::{FxHashMap, FxHashSet};
use std::borrow::Cow;
use std::fmt::Write as _;
use std::path::Path;

/// One state as declared in a file.
pub(super) struct StateDecl<'a> {
    /// Its name, if it has one.
    pub(super) name: Option<Cow<'a, str>>,
    /// Its libFAUDES index, if the file gives one.
    pub(super) index: Option<u64>,
    /// Byte offset of the declaration, for errors.
    pub(super) pos: usize,
    /// Declared initial (the XML flavour's `<Initial/>`).
    pub(super) initial: bool,
    /// Declared marked (the XML flavour's `<Marked/>`).
    pub(super) marked: bool,
}

/// The declared states, turned into builder states.
#[derive(Default)]
pub(super) struct States {
    /// The builder state of each libFAUDES index the file declared.
    pub(super) by_index: FxHashMap<u64, StateId>,
}

impl States {
    /// Adds `decls` to `b` (see the module docs for the naming rule).
    pub(super) fn commit(
        b: &mut AutomatonBuilder,
        decls: &[StateDecl<'_>],
        err: &dyn Fn(usize, String) -> Error,
    ) -> Result<States> {
        let mut states = States::default();
        let any_named = decls.iter().any(|d| d.name.is_some());
        let named: FxHashSet<&str> = decls.iter().filter_map(|d| d.name.as_deref()).collect();
        let mut index_owner: FxHashMap<u64, &StateDecl<'_>> = FxHashMap::default();
        let mut name_index: FxHashMap<&str, Option<u64>> = FxHashMap::default();
        for d in decls {
            if let Some(name) = d.name.as_deref() {
                match name_index.get(name) {
                    Some(&prev) if prev.is_some() && d.index.is_some() && prev != d.index => {
                        return Err(err(
                            d.pos,
                            format!(
                                "state `{name}` is declared with two indices, {} and {}",
                                prev.unwrap_or_default(),
                                d.index.unwrap_or_default()
                            ),
                        ))
                    }
                    Some(_) if d.index.is_none() => {}
                    _ => {
                        name_index.insert(name, d.index);
                    }
                }
            }
            if let Some(i) = d.index {
                if let Some(other) = index_owner.get(&i) {
                    if other.name != d.name {
                        let who = |n: &Option<Cow<'_, str>>| match n {
                            Some(n) => format!("`{n}`"),
                            None => "an unnamed state".to_owned(),
                        };
                        return Err(err(
                            d.pos,
                            format!(
                                "state index {i} is declared twice (for {} and for {})",
                                who(&other.name),
                                who(&d.name)
                            ),
                        ));
                    }
                    continue;
                }
                index_owner.insert(i, d);
            }
            let s = match (&d.name, any_named) {
                (Some(name), _) => b.add_state(name),
                (None, false) => b.add_anonymous_state(),
                (None, true) => {
                    let mut name = d.index.unwrap_or_default().to_string();
                    while named.contains(name.as_str()) {
                        name.insert(0, '_');
                    }
                    b.add_state(&name)
                }
            };
            if let Some(i) = d.index {
                states.by_index.insert(i, s);
            }
            if d.marked {
                b.mark(s);
            }
            if d.initial {
                b.set_initial(s).map_err(|e| err(d.pos, e.to_string()))?;
            }
        }
        Ok(states)
    }
}

/// Turns a builder error into a model error located at its tag.
pub(super) fn build_error(e: BuildError, text: &str, origin: &Path) -> Error {
    let pos = e.line() as usize;
    let message = match &e {
        BuildError::Nondeterministic { first_line, .. } => {
            let (l, c) = line_column(text, *first_line as usize);
            format!("{e} (the other transition is at line {l}, column {c})")
        }
        _ => e.to_string(),
    };
    if e.line() == 0 && !matches!(e, BuildError::Nondeterministic { .. }) {
        return Error::model(Location::file(origin), message);
    }
    Error::model(Location::at_offset(origin, text, pos), message)
}

/// A state named after its own index is indistinguishable from an unnamed
/// one; automata whose names are exactly `0, 1, …` are left unnamed.
pub(crate) fn drop_index_names(a: &mut Automaton) {
    if !a.has_state_names() {
        return;
    }
    let mut buf = String::new();
    let all_indices = a.states().all(|s| {
        buf.clear();
        let _ = write!(buf, "{}", s.0);
        a.state_name(s) == buf.as_str()
    });
    if all_indices {
        a.clear_state_names();
    }
}

/// The name of a generator whose file gives none: the file's stem.
pub(super) fn default_name(origin: &Path) -> String {
    origin
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("generator")
        .to_owned()
}

/// Clamps a byte offset into the `u32` "line" tag the builder carries.
pub(super) fn tag(pos: usize) -> u32 {
    u32::try_from(pos).unwrap_or(u32::MAX)
}
