//! The writer: an automaton in the plain-token style of libFAUDES 2.x,
//! names quoted where libFAUDES would read them as something else (see
//! the module docs of [`super`]).

use super::lex::split_explicit_index;
use super::{Kind, MAX_RANGE_STATES};
use crate::automaton::{Automaton, StateId};
use std::fmt::Write as _;

/// [`super::write()`] and [`super::write_component()`]: `kind` is
/// recorded unless [`Kind::Unspecified`].
pub(super) fn write_with_kind(a: &Automaton, kind: Kind) -> String {
    let mut out = String::with_capacity(64 + a.num_transitions() * 16 + a.num_states() * 8);
    out.push_str("<Generator name=\"");
    escape_into(&mut out, a.name());
    out.push('"');
    // `ftype="System"` states controllability (even with no +C+ at all);
    // a plain generator leaves it to the automata it meets.
    if a.alphabet().controllability_stated() {
        out.push_str(" ftype=\"System\"");
    }
    if kind != Kind::Unspecified {
        let _ = write!(out, " kind=\"{kind}\"");
    }
    out.push_str(">\n");
    let _ = writeln!(
        out,
        "% {} states, {} events, {} transitions",
        a.num_states(),
        a.alphabet().len(),
        a.num_transitions()
    );

    out.push_str("\n<Alphabet>\n");
    for (_, e) in a.alphabet().iter() {
        put_name(&mut out, &e.name);
        if e.controllable {
            out.push_str(" +C+");
        }
        out.push('\n');
    }
    out.push_str("</Alphabet>\n\n<States>\n");
    let names = state_tokens(a);
    match &names {
        Some(names) => {
            for (s, n) in a.states().zip(names) {
                put_state_decl(&mut out, a, s, n);
                out.push('\n');
            }
        }
        None if a.num_states() > 16 && a.num_states() as u64 <= MAX_RANGE_STATES => {
            let _ = writeln!(out, "<Consecutive>\n1 {}\n</Consecutive>", a.num_states());
        }
        None => {
            for s in a.states() {
                let _ = writeln!(out, "{}", s.0 as u64 + 1);
            }
        }
    }
    out.push_str("</States>\n\n<TransRel>\n");
    // Event tokens are rendered once, not once per transition.
    let events: Vec<String> = a
        .alphabet()
        .iter()
        .map(|(_, e)| {
            let mut s = String::new();
            put_name(&mut s, &e.name);
            s
        })
        .collect();
    let put_state = |out: &mut String, s: StateId| match &names {
        Some(names) => out.push_str(&names[s.index()]),
        None => {
            let _ = write!(out, "{}", s.0 as u64 + 1);
        }
    };
    for (s, e, t) in a.iter_transitions() {
        put_state(&mut out, s);
        out.push(' ');
        out.push_str(&events[e.index()]);
        out.push(' ');
        put_state(&mut out, t);
        out.push('\n');
    }
    out.push_str("</TransRel>\n\n<InitStates>\n");
    if let Some(s) = a.initial() {
        put_state(&mut out, s);
        out.push('\n');
    }
    out.push_str("</InitStates>\n\n<MarkedStates>\n");
    for s in a.marked_states() {
        put_state(&mut out, s);
        out.push('\n');
    }
    out.push_str("</MarkedStates>\n\n</Generator>\n");
    out
}

/// Characters a libFAUDES symbol may consist of without quotes (a
/// conservative choice: anything else is quoted).
fn is_plain_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || "_.-:[]()/,;=@$!?*^~|".contains(c)
}

/// `true` when `name` can be written without quotes and libFAUDES reads
/// it back as the same name: not as an index, a real number or an
/// attribute (see the module docs).
fn is_plain_symbol(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(is_plain_char)
        && name != "inf"
}

/// Writes `name` as a symbol, quoted when necessary.
fn put_name(out: &mut String, name: &str) {
    if is_plain_symbol(name) {
        out.push_str(name);
    } else {
        out.push('"');
        escape_into(out, name);
        out.push('"');
    }
}

/// XML-style escaping as libFAUDES decodes it inside quoted strings and
/// attribute values; control characters become numeric references
/// (which libFAUDES does not decode, but it refuses such names anyway).
fn escape_into(out: &mut String, s: &str) {
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '"' => out.push_str("&quot;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            c if c.is_control() => {
                let _ = write!(out, "&#{};", c as u32);
            }
            c => out.push(c),
        }
    }
}

/// How each state of a named automaton is referred to (`None` when
/// unnamed): its name, quoted when necessary.
fn state_tokens(a: &Automaton) -> Option<Vec<String>> {
    if !a.has_state_names() {
        return None;
    }
    Some(
        a.states()
            .map(|s| {
                let mut tok = String::new();
                put_name(&mut tok, &a.state_name(s));
                tok
            })
            .collect(),
    )
}

/// Writes the `<States>` entry of state `s` whose reference is `tok`.
///
/// A name ending in `#digits` would read back as an explicit index, so
/// such states get their (1-based) index appended explicitly: the name
/// contains `#`, hence is quoted, and the index goes inside the quotes.
fn put_state_decl(out: &mut String, a: &Automaton, s: StateId, tok: &str) {
    match tok.strip_suffix('"') {
        Some(open) if split_explicit_index(&a.state_name(s)).is_some() => {
            out.push_str(open);
            let _ = write!(out, "#{}\"", s.0 as u64 + 1);
        }
        _ => out.push_str(tok),
    }
}

#[cfg(test)]
mod tests {
    use super::super::{p, read, write};
    use crate::automaton::AutomatonBuilder;

    #[test]
    fn writer_quotes_what_needs_quoting_and_round_trips() {
        let mut b = AutomatonBuilder::new("we\"ird <name>");
        let e1 = b.add_event("sp ace", true).unwrap();
        let e2 = b.add_event("7", false).unwrap();
        let e3 = b.add_event("+C+", false).unwrap();
        let s0 = b.add_state("a#7");
        let s1 = b.add_state("3");
        let s2 = b.add_state("line\nbreak");
        b.set_initial(s1).unwrap();
        b.mark(s0);
        b.add_transition(s0, e1, s1, 0);
        b.add_transition(s1, e2, s2, 0);
        b.add_transition(s2, e3, s0, 0);
        let a = b.build().unwrap();
        let text = write(&a);
        assert!(text.contains("\"sp ace\" +C+"), "{text}");
        assert!(text.contains("\"a#7#1\""), "{text}");
        let back = read(&text, p()).unwrap();
        assert_eq!(back, a);
    }

    #[test]
    fn unnamed_automata_are_written_from_index_one() {
        let mut b = AutomatonBuilder::new("u");
        let s0 = b.add_anonymous_state();
        let s1 = b.add_anonymous_state();
        let e = b.add_event("a", true).unwrap();
        b.add_transition(s0, e, s1, 0);
        b.set_initial(s0).unwrap();
        b.mark(s1);
        let a = b.build().unwrap();
        let text = write(&a);
        assert!(text.contains("<TransRel>\n1 a 2\n</TransRel>"), "{text}");
        assert_eq!(read(&text, p()).unwrap(), a);
    }
}
