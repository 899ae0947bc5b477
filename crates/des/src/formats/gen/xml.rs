//! libFAUDES' XML flavour (written by its `XWrite`): a `<Generator>`
//! element with `<Alphabet>`, `<StateSet>` and `<TransitionRelation>`,
//! one function an element.

use super::super::{parse_kind, Component, Kind, KINDS};
use super::lex::shorten;
use super::states::{build_error, default_name, drop_index_names, tag, StateDecl, States};
use super::MAX_RANGE_STATES;
use crate::automaton::AutomatonBuilder;
use crate::error::{Error, Location, Result};
use roxmltree::{Document, Node};
use std::borrow::Cow;
use std::path::Path;

/// `true` when `text` is in the XML flavour: it starts with `<?xml` or a
/// document type, or has a `<StateSet>` element.
pub(super) fn looks_like_xml(text: &str) -> bool {
    let t = text.trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n']);
    t.starts_with("<?xml") || t.starts_with("<!DOCTYPE") || text.contains("<StateSet")
}

/// Reads a generator in the XML flavour; `origin` names the file in
/// errors.
pub(super) fn read(text: &str, origin: &Path) -> Result<Component> {
    let doc = super::super::parse_xml(text, origin)?;
    let x = Elements { doc: &doc, origin };
    let root = doc.root_element();
    if root.tag_name().name() != "Generator" {
        return Err(Error::syntax(
            x.at(root),
            format!(
                "expected a `<Generator>` root element, found `<{}>`",
                root.tag_name().name()
            ),
        ));
    }
    let name = root
        .attribute("name")
        .map_or_else(|| default_name(origin), str::to_owned);
    let mut b = AutomatonBuilder::new(name);
    // As in the token format: without `ftype="System"` and without any
    // event property, controllability is not stated.
    let system = root.attribute("ftype") == Some("System");
    let kind = match root.attribute("kind") {
        None => Kind::Unspecified,
        Some(k) => parse_kind(k).ok_or_else(|| {
            Error::model(
                x.at(root),
                format!("unknown kind `{}` (expected {KINDS})", shorten(k)),
            )
        })?,
    };
    let mut attributed = false;
    let mut decls: Vec<StateDecl<'_>> = Vec::new();
    let mut transitions = Vec::new();
    let mut range_states: u64 = 0;
    for section in root.children().filter(|n| n.is_element()) {
        match section.tag_name().name() {
            "Alphabet" => attributed |= x.alphabet(section, &mut b)?,
            "StateSet" => x.state_set(section, &mut decls, &mut range_states)?,
            "TransitionRelation" | "TransRel" => {
                x.transition_relation(section, &mut transitions)?;
            }
            other => {
                return Err(Error::syntax(
                    x.at(section),
                    format!("unsupported element `<{other}>` (expected <Alphabet>, <StateSet> or <TransitionRelation>)"),
                ))
            }
        }
    }
    let err = |pos: usize, msg: String| Error::model(Location::at_offset(origin, text, pos), msg);
    let states = States::commit(&mut b, &decls, &err)?;
    x.add_transitions(&mut b, &states, transitions)?;
    if !system && !attributed {
        b.set_controllability_stated(false);
    }
    let mut a = b.build().map_err(|e| build_error(e, text, origin))?;
    drop_index_names(&mut a);
    Ok(Component { kind, automaton: a })
}

/// A `<Transition>` as read, its states still libFAUDES indices.
struct Transition<'a, 'input> {
    x1: u64,
    event: String,
    x2: u64,
    node: Node<'a, 'input>,
}

/// The elements of one document, located in its file.
struct Elements<'a, 'input> {
    doc: &'a Document<'input>,
    origin: &'a Path,
}

impl<'a, 'input> Elements<'a, 'input> {
    /// Where `node` starts.
    fn at(&self, node: Node<'_, '_>) -> Location {
        let p = self.doc.text_pos_at(node.range().start);
        Location::new(self.origin, p.row, p.col)
    }

    /// The attribute `key` of `node`, which must have it.
    fn attr(&self, node: Node<'_, '_>, key: &str) -> Result<String> {
        node.attribute(key).map(str::to_owned).ok_or_else(|| {
            Error::syntax(
                self.at(node),
                format!(
                    "element `<{}>` lacks its `{key}` attribute",
                    node.tag_name().name()
                ),
            )
        })
    }

    /// The attribute `key` of `node` as a state index.
    fn index(&self, node: Node<'_, '_>, key: &str) -> Result<u64> {
        let v = self.attr(node, key)?;
        v.trim().parse::<u64>().map_err(|_| {
            Error::syntax(
                self.at(node),
                format!(
                    "attribute `{key}` must be a state index, found `{}`",
                    shorten(&v)
                ),
            )
        })
    }

    /// Adds the `<Event>`s of `<Alphabet>` to `b`; returns whether any
    /// event had a property (which states controllability).
    fn alphabet(&self, section: Node<'a, 'input>, b: &mut AutomatonBuilder) -> Result<bool> {
        let mut attributed = false;
        for ev in section.children().filter(|n| n.is_element()) {
            if ev.tag_name().name() != "Event" {
                return Err(Error::syntax(
                    self.at(ev),
                    format!(
                        "expected `<Event>` in `<Alphabet>`, found `<{}>`",
                        ev.tag_name().name()
                    ),
                ));
            }
            let name = self.attr(ev, "name")?;
            attributed |= ev.children().any(|c| c.is_element());
            let controllable = ev
                .children()
                .any(|c| c.is_element() && c.tag_name().name() == "Controllable");
            b.add_event(&name, controllable)
                .map_err(|e| Error::model(self.at(ev), e.to_string()))?;
        }
        Ok(attributed)
    }

    /// Declares the `<State>`s and `<Consecutive>` ranges of `<StateSet>`;
    /// `range_states` counts the states of the ranges so far.
    fn state_set(
        &self,
        section: Node<'a, 'input>,
        decls: &mut Vec<StateDecl<'a>>,
        range_states: &mut u64,
    ) -> Result<()> {
        for st in section.children().filter(|n| n.is_element()) {
            let pos = st.range().start;
            match st.tag_name().name() {
                "State" => {
                    let flag = |f: &str| {
                        st.children()
                            .any(|c| c.is_element() && c.tag_name().name() == f)
                    };
                    decls.push(StateDecl {
                        name: st.attribute("name").map(Cow::Borrowed),
                        index: Some(self.index(st, "id")?),
                        pos,
                        initial: flag("Initial"),
                        marked: flag("Marked"),
                    });
                }
                "Consecutive" => {
                    let (first, last) = (self.index(st, "from")?, self.index(st, "to")?);
                    if first > last {
                        return Err(Error::syntax(
                            self.at(st),
                            format!("empty index range {first} to {last} in `<Consecutive>`"),
                        ));
                    }
                    *range_states = range_states.saturating_add(last - first + 1);
                    if *range_states > MAX_RANGE_STATES {
                        return Err(Error::model(
                            self.at(st),
                            format!("too many states declared by `<Consecutive>` ranges (at most {MAX_RANGE_STATES} are supported)"),
                        ));
                    }
                    decls.extend((first..=last).map(|i| StateDecl {
                        name: None,
                        index: Some(i),
                        pos,
                        initial: false,
                        marked: false,
                    }));
                }
                other => {
                    let message = format!(
                        "expected `<State>` or `<Consecutive>` in `<StateSet>`, found `<{other}>`"
                    );
                    return Err(Error::syntax(self.at(st), message));
                }
            }
        }
        Ok(())
    }

    /// Reads the `<Transition>`s of `<TransitionRelation>` (or `<TransRel>`).
    fn transition_relation(
        &self,
        section: Node<'a, 'input>,
        transitions: &mut Vec<Transition<'a, 'input>>,
    ) -> Result<()> {
        for tr in section.children().filter(|n| n.is_element()) {
            if tr.tag_name().name() != "Transition" {
                return Err(Error::syntax(
                    self.at(tr),
                    format!(
                        "expected `<Transition>` in `<{}>`, found `<{}>`",
                        section.tag_name().name(),
                        tr.tag_name().name()
                    ),
                ));
            }
            transitions.push(Transition {
                x1: self.index(tr, "x1")?,
                event: self.attr(tr, "event")?,
                x2: self.index(tr, "x2")?,
                node: tr,
            });
        }
        Ok(())
    }

    /// Adds `transitions` to `b`, their indices resolved by `states`.
    fn add_transitions(
        &self,
        b: &mut AutomatonBuilder,
        states: &States,
        transitions: Vec<Transition<'a, 'input>>,
    ) -> Result<()> {
        for Transition {
            x1,
            event,
            x2,
            node,
        } in transitions
        {
            let resolve = |i: u64| {
                states.by_index.get(&i).copied().ok_or_else(|| {
                    Error::model(
                        self.at(node),
                        format!("state index {i} is not declared in <StateSet>"),
                    )
                })
            };
            let (s, t) = (resolve(x1)?, resolve(x2)?);
            let e = b.alphabet().id(&event).ok_or_else(|| {
                Error::model(
                    self.at(node),
                    format!("event `{event}` is not in the <Alphabet>"),
                )
            })?;
            b.add_transition(s, e, t, tag(node.range().start));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::{p, read};
    use crate::automaton::StateId;
    use crate::error::Error;

    #[test]
    fn xml_flavour_reads() {
        let text = r#"<?xml version="1.0" encoding="ISO-8859-1" standalone="no"?>
<!DOCTYPE System SYSTEM "http://www.faudes.org/dtd/1.0/system.dtd">
<Generator name="x gen" ftype="System">
<Alphabet>
<Event name="a"/>
<Event name="c">
<Controllable/>
</Event>
</Alphabet>
<StateSet>
<State id="1" name="x"><Initial/></State>
<Consecutive from="2" to="3"/>
<State id="5"><Marked/></State>
</StateSet>
<TransitionRelation>
<Transition x1="1" event="a" x2="5"/>
<Transition x1="5" event="c" x2="2"/>
</TransitionRelation>
</Generator>"#;
        let a = read(text, p()).unwrap();
        assert_eq!(a.name(), "x gen");
        let names: Vec<_> = a.states().map(|s| a.state_name(s).into_owned()).collect();
        assert_eq!(names, ["x", "2", "3", "5"]);
        assert_eq!(a.initial(), Some(StateId(0)));
        assert!(a.is_marked(StateId(3)));
        assert_eq!(a.num_transitions(), 2);
        assert!(a.alphabet().is_controllable(a.alphabet().id("c").unwrap()));

        let bad = text.replace("<Transition x1=\"5\"", "<Transition x1=\"5\"\n<");
        match read(&bad, p()).unwrap_err() {
            Error::Syntax { location, .. } => assert_eq!(location.line, 18),
            other => panic!("{other:?}"),
        }
        let undeclared = text.replace("x2=\"2\"", "x2=\"4\"");
        match read(&undeclared, p()).unwrap_err() {
            Error::Model { location, message } => {
                assert_eq!(location.line, 17, "{message}");
            }
            other => panic!("{other:?}"),
        }
    }
}
