//! The native automaton format: TOML.
//!
//! ```toml
//! name = "MACH1"
//! kind = "plant"                        # optional: plant, spec, supervisor, property
//! initial = "idle"
//! marked = ["idle"]                     # optional, default: [initial]
//! controllable = ["start", "repair"]
//! uncontrollable = ["finish", "break"]
//! unobservable = ["break"]              # optional: events the controller cannot see
//! states = ["idle", "working", "down"]  # optional; if given, lists every state
//! transitions = [
//!   ["idle", "start", "working"],
//!   ["working", "finish", "idle"],
//! ]
//! ```
//!
//! Every event of a transition must be declared in exactly one of
//! `controllable` and `uncontrollable`; declared events need not occur on
//! a transition (they still belong to the alphabet); `unobservable` names
//! declared events the controller does not see (the writer lists it only
//! when there are some). Without a `states`
//! list, states are numbered in order of first mention (initial state,
//! then transitions, then marked states). Unknown keys are errors. An
//! automaton without states has no `initial` key and `states = []`.
//!
//! Every error carries the file, line and column of the offending entry.
//! States named `"0"`, `"1"`, … in order read as an unnamed automaton (see
//! [`super::gen`]); the writer names the states of unnamed automata that
//! way.

use super::{Component, Kind};
use crate::automaton::{AutomatonBuilder, BuildError};
use crate::error::{line_column, Error, Location, Result};
use serde::Deserialize;
use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

/// The role as spelled in the file.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum FileKind {
    Plant,
    Spec,
    Supervisor,
    Property,
}

type Name = Spanned<String>;

/// The file's fields, exactly as in docs/formats.md ("Native TOML").
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    name: Name,
    #[serde(default)]
    kind: Option<FileKind>,
    #[serde(default)]
    initial: Option<Name>,
    #[serde(default)]
    marked: Option<Vec<Name>>,
    #[serde(default)]
    controllable: Vec<Name>,
    #[serde(default)]
    uncontrollable: Vec<Name>,
    #[serde(default)]
    unobservable: Vec<Name>,
    #[serde(default)]
    states: Option<Vec<Name>>,
    #[serde(default)]
    /// `[source, event, target]`; read as a list so that a wrong length is
    /// a located error rather than extra elements silently dropped.
    transitions: Vec<Spanned<Vec<Name>>>,
}

/// Deserialises TOML `text` (the file `origin`), a syntax or shape error
/// located at its line and column.
pub(crate) fn parse<T: serde::de::DeserializeOwned>(text: &str, origin: &Path) -> Result<T> {
    ::toml::from_str(text).map_err(|e| {
        let location = match e.span() {
            Some(span) => Location::at_offset(origin, text, span.start),
            None => Location::file(origin),
        };
        Error::syntax(location, e.message().trim_end().to_owned())
    })
}

/// Parses a native TOML automaton; `origin` names the file in errors.
pub fn read(text: &str, origin: &Path) -> Result<Component> {
    let file: File = parse(text, origin)?;
    let at = |span: Range<usize>| Location::at_offset(origin, text, span.start);

    let mut b = AutomatonBuilder::new(file.name.get_ref().clone());
    // Builder "line" tags index this table of spans.
    let mut spans: Vec<Range<usize>> = Vec::new();
    let mut tag = |span: Range<usize>| {
        spans.push(span);
        u32::try_from(spans.len()).unwrap_or(u32::MAX)
    };

    for e in &file.controllable {
        b.add_event(e.get_ref(), true)
            .map_err(|err| Error::model(at(e.span()), err.to_string()))?;
    }
    for e in &file.uncontrollable {
        b.add_event(e.get_ref(), false)
            .map_err(|err| Error::model(at(e.span()), err.to_string()))?;
    }
    for e in &file.unobservable {
        let id = b.alphabet().id(e.get_ref()).ok_or_else(|| {
            Error::model(
                at(e.span()),
                format!(
                    "unobservable event `{}` is not declared (list it in `controllable` or `uncontrollable` too)",
                    e.get_ref()
                ),
            )
        })?;
        b.set_unobservable(id);
    }

    if let Some(states) = &file.states {
        for s in states {
            if b.find_state(s.get_ref()).is_some() {
                return Err(Error::model(
                    at(s.span()),
                    format!("state `{}` is listed twice in `states`", s.get_ref()),
                ));
            }
            b.add_state(s.get_ref());
        }
        b.close_states();
    }
    let undeclared = |s: &Name| {
        Error::model(
            at(s.span()),
            format!(
                "state `{}` is not declared (it is missing from `states`)",
                s.get_ref()
            ),
        )
    };

    if let Some(init) = &file.initial {
        let s = b.state(init.get_ref(), 0).map_err(|_| undeclared(init))?;
        b.set_initial(s)
            .map_err(|e| Error::model(at(init.span()), e.to_string()))?;
    }

    for t in &file.transitions {
        let [source, event, target] = t.get_ref().as_slice() else {
            return Err(Error::model(
                at(t.span()),
                format!(
                    "a transition is [source, event, target]: this one has {} element{}",
                    t.get_ref().len(),
                    if t.get_ref().len() == 1 { "" } else { "s" }
                ),
            ));
        };
        let e = b.alphabet().id(event.get_ref()).ok_or_else(|| {
            Error::model(
                at(event.span()),
                format!(
                    "event `{}` is not declared (list it in `controllable` or `uncontrollable`)",
                    event.get_ref()
                ),
            )
        })?;
        let s = b
            .state(source.get_ref(), 0)
            .map_err(|_| undeclared(source))?;
        let d = b
            .state(target.get_ref(), 0)
            .map_err(|_| undeclared(target))?;
        let line = tag(t.span());
        b.add_transition(s, e, d, line);
    }

    let default_marked;
    let marked = match &file.marked {
        Some(m) => m.as_slice(),
        None => {
            default_marked = file.initial.iter().cloned().collect::<Vec<_>>();
            default_marked.as_slice()
        }
    };
    for m in marked {
        let s = b.state(m.get_ref(), 0).map_err(|_| undeclared(m))?;
        b.mark(s);
    }

    let mut a = b.build().map_err(|e| match &e {
        BuildError::Nondeterministic {
            line, first_line, ..
        } => {
            let span_of = |tag: u32| {
                spans
                    .get((tag as usize).wrapping_sub(1))
                    .cloned()
                    .unwrap_or(0..0)
            };
            let first = span_of(*first_line);
            let (l, c) = line_column(text, first.start);
            Error::model(
                at(span_of(*line)),
                format!("{e} (the other transition is at line {l}, column {c})"),
            )
        }
        _ => Error::model(Location::file(origin), e.to_string()),
    })?;
    super::gen::drop_index_names(&mut a);
    let kind = match file.kind {
        None => Kind::Unspecified,
        Some(FileKind::Plant) => Kind::Plant,
        Some(FileKind::Spec) => Kind::Spec,
        Some(FileKind::Supervisor) => Kind::Supervisor,
        Some(FileKind::Property) => Kind::Property,
    };
    Ok(Component { kind, automaton: a })
}

/// Renders a component as native TOML (stable key order, one transition
/// per line).
pub fn write(c: &Component) -> String {
    let a = &c.automaton;
    let mut out = String::with_capacity(128 + a.num_transitions() * 32);
    out.push_str("name = ");
    put_string(&mut out, a.name());
    out.push('\n');
    if c.kind != Kind::Unspecified {
        let _ = writeln!(out, "kind = \"{}\"", c.kind);
    }
    let state = |s| a.state_name(s);
    if let Some(init) = a.initial() {
        out.push_str("initial = ");
        put_string(&mut out, &state(init));
        out.push('\n');
    }
    put_list(&mut out, "marked", a.marked_states().map(state));
    let events = |controllable: bool| {
        a.alphabet()
            .iter()
            .filter(move |(_, e)| e.controllable == controllable)
            .map(|(_, e)| std::borrow::Cow::Borrowed(e.name.as_str()))
    };
    put_list(&mut out, "controllable", events(true));
    put_list(&mut out, "uncontrollable", events(false));
    if a.alphabet().unobservable().next().is_some() {
        let hidden = a
            .alphabet()
            .unobservable()
            .map(|(_, e)| std::borrow::Cow::Borrowed(e.name.as_str()));
        put_list(&mut out, "unobservable", hidden);
    }
    put_list(&mut out, "states", a.states().map(state));
    if a.num_transitions() == 0 {
        out.push_str("transitions = []\n");
    } else {
        out.push_str("transitions = [\n");
        // Names are rendered once, not once per transition.
        let states: Vec<String> = a
            .states()
            .map(|s| {
                let mut q = String::new();
                put_string(&mut q, &state(s));
                q
            })
            .collect();
        let events: Vec<String> = a
            .alphabet()
            .iter()
            .map(|(_, e)| {
                let mut q = String::new();
                put_string(&mut q, &e.name);
                q
            })
            .collect();
        for (s, e, t) in a.iter_transitions() {
            out.push_str("  [");
            out.push_str(&states[s.index()]);
            out.push_str(", ");
            out.push_str(&events[e.index()]);
            out.push_str(", ");
            out.push_str(&states[t.index()]);
            out.push_str("],\n");
        }
        out.push_str("]\n");
    }
    out
}

/// `key = [..]` on one line when short, else one item per line.
fn put_list<'a>(
    out: &mut String,
    key: &str,
    items: impl Iterator<Item = std::borrow::Cow<'a, str>>,
) {
    let quoted: Vec<String> = items
        .map(|s| {
            let mut q = String::new();
            put_string(&mut q, &s);
            q
        })
        .collect();
    let width: usize = quoted.iter().map(|q| q.len() + 2).sum::<usize>() + key.len() + 5;
    out.push_str(key);
    if width <= 80 {
        out.push_str(" = [");
        out.push_str(&quoted.join(", "));
        out.push_str("]\n");
    } else {
        out.push_str(" = [\n");
        for q in &quoted {
            out.push_str("  ");
            out.push_str(q);
            out.push_str(",\n");
        }
        out.push_str("]\n");
    }
}

/// `s` as a TOML basic string on one line (usable as a key), every
/// character that needs it escaped.
pub fn basic_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    put_string(&mut out, s);
    out
}

/// A TOML basic string with every character that needs it escaped.
fn put_string(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::automaton::{Automaton, StateId};

    const MACH1: &str = r#"name = "MACH1"
initial = "idle"
marked = ["idle"]                      # optional, default: [initial]
controllable = ["start", "repair"]    # events listed here are controllable
uncontrollable = ["finish", "break"]  # every other event must be listed here
states = ["idle", "working", "down"]  # optional; if given, it lists every state
transitions = [
  ["idle", "start", "working"],
  ["working", "finish", "idle"],
  ["working", "break", "down"],
  ["down", "repair", "idle"],
]
"#;

    fn p() -> &'static Path {
        Path::new("m.toml")
    }

    fn err(text: &str) -> (u32, u32, String) {
        let e = read(text, p()).unwrap_err();
        let (l, m) = e.located().unwrap_or_else(|| panic!("unexpected {e:?}"));
        (l.line, l.column, m.to_owned())
    }

    #[test]
    fn the_documented_example_reads() {
        let c = read(MACH1, p()).unwrap();
        assert_eq!(c.kind, Kind::Unspecified);
        let a = &c.automaton;
        assert_eq!((a.num_states(), a.num_transitions()), (3, 4));
        assert_eq!(a.state_name(a.initial().unwrap()), "idle");
        assert!(a
            .alphabet()
            .is_controllable(a.alphabet().id("repair").unwrap()));
        assert!(!a
            .alphabet()
            .is_controllable(a.alphabet().id("break").unwrap()));
        assert_eq!(a.marked_states().collect::<Vec<_>>(), [StateId(0)]);
    }

    #[test]
    fn unobservable_events_round_trip_through_every_format_that_can_say_so() {
        let text = MACH1.replace(
            "states = [",
            "unobservable = [\"break\", \"repair\"]\nstates = [",
        );
        let c = read(&text, p()).unwrap();
        let hidden: Vec<&str> = c
            .automaton
            .alphabet()
            .unobservable()
            .map(|(_, e)| e.name.as_str())
            .collect();
        assert_eq!(hidden, ["repair", "break"]);
        let written = write(&c);
        assert!(
            written.contains("unobservable = [\"repair\", \"break\"]"),
            "{written}"
        );
        assert!(!write(&read(MACH1, p()).unwrap()).contains("unobservable"));
        use crate::formats::{read_str, write_string, Format};
        for format in [Format::Toml, Format::Gen, Format::Wmod] {
            let again = write_string(format, std::slice::from_ref(&c)).unwrap();
            let back = read_str(&again, format, p()).unwrap();
            assert_eq!(
                back[0].automaton.alphabet(),
                c.automaton.alphabet(),
                "{format:?}:\n{again}"
            );
        }
        let refused = write_string(Format::Ads, &[c]).unwrap_err().to_string();
        assert!(
            refused.contains("unobservable events (repair, break)"),
            "{refused}"
        );
        let (l, _, m) = err(&MACH1.replace("states = [", "unobservable = [\"brake\"]\nstates = ["));
        assert_eq!(l, 6, "{m}");
        assert!(m.contains("`brake` is not declared"), "{m}");
    }

    #[test]
    fn a_transition_of_other_than_three_elements_is_a_located_error() {
        for (row, n) in [
            (r#"["a", "e", "b", "c"]"#, "4 elements"),
            (r#"["a", "e"]"#, "2 elements"),
            (r#"["a"]"#, "1 element"),
        ] {
            let text = format!(
                "name = \"x\"\ninitial = \"a\"\ncontrollable = [\"e\"]\ntransitions = [{row}]\n"
            );
            let err = read(&text, p()).unwrap_err().to_string();
            assert!(err.contains(":4:16:"), "{err}");
            assert!(err.contains(n), "{err}");
        }
    }

    #[test]
    fn marked_defaults_to_the_initial_state_and_kind_is_read() {
        let text = "name = \"x\"\nkind = \"spec\"\ninitial = \"a\"\ncontrollable = [\"e\"]\ntransitions = [[\"a\", \"e\", \"b\"]]\n";
        let c = read(text, p()).unwrap();
        assert_eq!(c.kind, Kind::Spec);
        assert_eq!(
            c.automaton.marked_states().collect::<Vec<_>>(),
            [StateId(0)]
        );
        assert_eq!(c.automaton.num_states(), 2);
    }

    #[test]
    fn round_trip_including_the_empty_automaton() {
        let c = read(MACH1, p()).unwrap();
        assert_eq!(read(&write(&c), p()).unwrap(), c);
        let empty = Component {
            kind: Kind::Property,
            automaton: Automaton::empty("nothing", crate::automaton::Alphabet::new()),
        };
        let text = write(&empty);
        assert!(
            text.contains("states = []") && !text.contains("initial"),
            "{text}"
        );
        assert_eq!(read(&text, p()).unwrap(), empty);
    }

    #[test]
    fn errors_point_at_the_offending_entry() {
        let (l, c, m) = err(&MACH1.replace("\"finish\", \"idle\"", "\"finnish\", \"idle\""));
        assert_eq!((l, c), (9, 15), "{m}");
        assert!(m.contains("`finnish` is not declared"), "{m}");

        let (l, c, m) = err(&MACH1.replace("\"break\", \"down\"", "\"break\", \"dawn\""));
        assert_eq!((l, c), (10, 24), "{m}");
        assert!(m.contains("`dawn` is not declared"), "{m}");

        let (l, c, m) = err(&MACH1.replace("\"break\", \"down\"", "\"finish\", \"down\""));
        assert_eq!((l, c), (10, 3), "{m}");
        assert!(
            m.contains("nondeterministic") && m.contains("line 9"),
            "{m}"
        );

        let (l, _, m) = err(&MACH1.replace("[\"finish\", \"break\"]", "[\"finish\", \"start\"]"));
        assert_eq!(l, 5, "{m}");
        assert!(m.contains("both controllable and uncontrollable"), "{m}");

        let (l, c, m) = err(&MACH1.replace("initial", "inital"));
        assert_eq!((l, c), (2, 1), "{m}");
        assert!(m.contains("unknown field `inital`"), "{m}");

        let (l, _, m) =
            err(&MACH1.replace("[\"down\", \"repair\", \"idle\"]", "[\"down\", \"repair\"]"));
        assert_eq!(l, 11, "{m}");

        let (l, c, m) = err("name = \"x\"\nkind = \"plan\"\n");
        assert_eq!((l, c), (2, 8), "{m}");

        let (l, _, m) = err("name = \"x\"\ninitial = = 3\n");
        assert_eq!(l, 2, "{m}");
    }

    #[test]
    fn writer_escapes_names() {
        let mut b = AutomatonBuilder::new("q\"uote\\ \u{1}");
        let e = b.add_event("line\nbreak", false).unwrap();
        let s = b.add_state("tab\there");
        b.set_initial(s).unwrap();
        b.add_transition(s, e, s, 0);
        let c = Component::unspecified(b.build().unwrap());
        assert_eq!(read(&write(&c), p()).unwrap(), c);
    }
}
