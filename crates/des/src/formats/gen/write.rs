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
    let mut all = String::new();
    let mut append = |chunk: &str| {
        all.push_str(chunk);
        Ok(())
    };
    stream_with_kind(a, kind, &mut append).expect("appending to a string does not fail");
    all
}

/// Text is handed to the sink in pieces of about this many bytes.
const CHUNK: usize = 1 << 20;

/// [`write_with_kind`] in pieces: the text goes to `sink` a chunk at a
/// time, so a large automaton is written without its whole text (or all
/// its state names) in memory at once.
pub(super) fn stream_with_kind(
    a: &Automaton,
    kind: Kind,
    sink: &mut dyn FnMut(&str) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut out = String::with_capacity(CHUNK + 4096);
    let mut flush = |out: &mut String, force: bool| {
        if force || out.len() >= CHUNK {
            sink(out)?;
            out.clear();
        }
        Ok::<(), std::io::Error>(())
    };
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
        match (e.controllable, e.observable) {
            (true, true) => out.push_str(" +C+"),
            (true, false) => out.push_str(" +Co+"),
            (false, false) => out.push_str(" +o+"),
            (false, true) => {}
        }
        out.push('\n');
        flush(&mut out, false)?;
    }
    out.push_str("</Alphabet>\n\n<States>\n");
    let named = a.has_state_names();
    // A state's name, reused for every state (names are composed on
    // demand, never all held at once).
    let mut name = String::new();
    let token = |out: &mut String, name: &mut String, s: StateId| {
        if named {
            name.clear();
            a.write_state_name(s, name);
            put_name(out, name);
        } else {
            let _ = write!(out, "{}", s.0 as u64 + 1);
        }
    };
    if named {
        for s in a.states() {
            name.clear();
            a.write_state_name(s, &mut name);
            put_state_decl(&mut out, &name, s);
            out.push('\n');
            flush(&mut out, false)?;
        }
    } else if a.num_states() > 16 && a.num_states() as u64 <= MAX_RANGE_STATES {
        let _ = writeln!(out, "<Consecutive>\n1 {}\n</Consecutive>", a.num_states());
    } else {
        for s in a.states() {
            let _ = writeln!(out, "{}", s.0 as u64 + 1);
            flush(&mut out, false)?;
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
    let mut source = String::new();
    for s in a.states() {
        let row = a.transitions(s);
        if row.is_empty() {
            continue;
        }
        source.clear();
        token(&mut source, &mut name, s);
        for t in row {
            out.push_str(&source);
            out.push(' ');
            out.push_str(&events[t.event.index()]);
            out.push(' ');
            token(&mut out, &mut name, t.target);
            out.push('\n');
        }
        flush(&mut out, false)?;
    }
    out.push_str("</TransRel>\n\n<InitStates>\n");
    if let Some(s) = a.initial() {
        token(&mut out, &mut name, s);
        out.push('\n');
    }
    out.push_str("</InitStates>\n\n<MarkedStates>\n");
    for s in a.marked_states() {
        token(&mut out, &mut name, s);
        out.push('\n');
        flush(&mut out, false)?;
    }
    out.push_str("</MarkedStates>\n\n</Generator>\n");
    flush(&mut out, true)
}

/// Characters a libFAUDES symbol may consist of without quotes (a
/// conservative choice: anything else is quoted).
///
/// Read byte by byte: every byte of a non-ASCII character is outside the
/// set, as the character is.
fn is_plain_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric()
        || matches!(
            b,
            b'_' | b'.'
                | b'-'
                | b':'
                | b'['
                | b']'
                | b'('
                | b')'
                | b'/'
                | b','
                | b';'
                | b'='
                | b'@'
                | b'$'
                | b'!'
                | b'?'
                | b'*'
                | b'^'
                | b'~'
                | b'|'
        )
}

/// `true` when `name` can be written without quotes and libFAUDES reads
/// it back as the same name: not as an index, a real number or an
/// attribute (see the module docs).
fn is_plain_symbol(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && name.bytes().all(is_plain_byte)
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

/// Writes the `<States>` entry of state `s` named `name`: the name,
/// quoted when necessary.
///
/// A name ending in `#digits` would read back as an explicit index, so
/// such states get their (1-based) index appended explicitly: the name
/// contains `#`, hence is quoted, and the index goes inside the quotes.
fn put_state_decl(out: &mut String, name: &str, s: StateId) {
    put_name(out, name);
    if out.ends_with('"') && split_explicit_index(name).is_some() {
        out.pop();
        let _ = write!(out, "#{}\"", s.0 as u64 + 1);
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
