//! libFAUDES generator files (`.gen`).
//!
//! # The token format
//!
//! A generator file is a stream of whitespace-separated tokens:
//!
//! - sections, opened by `<Name>` (optionally with XML-style attributes,
//!   `<Generator name="m1" ftype="System">`) and closed by `</Name>`; an
//!   empty section may be written `<Name/>`;
//! - symbols (`idle`, `e11`) and quoted strings (`"e11"`, `"my state"`);
//!   quoted strings have no backslash escapes, but the XML entities
//!   `&amp;`, `&quot;`, `&lt;`, `&gt;`, `&apos;` and numeric references
//!   `&#10;` are decoded;
//! - unquoted integers, which stand for state *indices* (`3`), whereas a
//!   quoted `"3"` is a state *name*;
//! - attributes between plus signs (`+C+`, `+oF+`);
//! - comments from `%` to the end of the line.
//!
//! A generator consists of an optional name (the `name` attribute, or a
//! string right after an attribute-less `<Generator>`), an optional
//! `kind` attribute of ours (`plant`, `spec`, `supervisor` or `property`,
//! as in the native TOML format; libFAUDES ignores it) and the sections
//! `<Alphabet>` (events, each optionally followed by an attribute: an
//! event is controllable when its attribute contains an upper-case `C`),
//! `<States>` (state names or indices; `name#7` gives the state `name`
//! the explicit index 7; `<Consecutive> 4 9 </Consecutive>` declares the
//! unnamed indices 4 to 9), `<TransRel>` (`source event target` triples),
//! `<InitStates>` and `<MarkedStates>`. Attributes of states and
//! transitions (`+…+`, `{…}` blocks or nested sections) are skipped.
//!
//! libFAUDES' XML flavour (written by its `XWrite`, recognised by a leading
//! `<?xml` or a `<StateSet>` element) is read as well.
//!
//! # How files map to automata
//!
//! - States are numbered in the order of `<States>`; every state used in
//!   the other sections must be declared there (libFAUDES itself would add
//!   undeclared states silently; we treat them as typos).
//! - When no state has a name the automaton is unnamed and the libFAUDES
//!   indices are dropped (they are only numbers). When some states carry
//!   names, the unnamed ones are named after their libFAUDES index.
//! - More than one initial state is rejected: automata here are
//!   deterministic.
//! - A file whose state names are exactly `"0"`, `"1"`, … in order (as in
//!   TCT-derived benchmark files) reads as an unnamed automaton: a state
//!   named after its own index is indistinguishable from an unnamed one.
//!
//! # Writing
//!
//! [`write()`] produces the plain-token style current libFAUDES versions
//! read: `<Generator name="…">`, one event per line with `+C+` for
//! controllable events, then the states, transitions, initial and marked
//! states. [`write_component`] adds the component's `kind`. Unnamed
//! automata are written with indices starting at 1 (index 0 is invalid in
//! libFAUDES).
//!
//! A name is written bare only when libFAUDES reads it back as the same
//! symbol: it starts with an ASCII letter or `_`, every character is a
//! plain one (`is_plain_symbol`), and it is not `inf`. Everything else
//! is quoted and XML-escaped. libFAUDES's tokenizer reads bare digits as
//! a state index (`12`), `0x1F` as a hexadecimal index, digits around one
//! dot as a real number (`0.0`, `2.0`, `.5`, `1.`; composite state names
//! such as `0.0` became the invalid index 0 or an unnamed state 2), `inf`
//! and `-inf` as reals, and `+…` as an attribute; names starting with a
//! letter are none of these. libFAUDES refuses some names however they
//! are written (those with spaces, `"`, `#` or non-ASCII characters):
//! such names are still written, quoted, and this reader gets them back,
//! but libFAUDES will reject the file.
//!
//! # Where the code is
//!
//! [`read_component`] picks the reader: the token format goes through
//! `lex.rs` (tokens, entities, tag attributes) and `parse.rs` (one method
//! per section), the XML flavour through `xml.rs` (one function per
//! element); both declare their states through `states.rs`, which also
//! builds the automaton. `write.rs` renders an automaton in the token
//! format.

mod lex;
mod parse;
mod states;
mod write;
mod xml;

use super::{Component, Kind};
use crate::automaton::Automaton;
use crate::error::Result;
use std::path::Path;

pub(crate) use states::drop_index_names;

/// The most states a file may declare through index ranges
/// (`<Consecutive>`), so that a few bytes cannot demand gigabytes; states
/// listed one by one are limited only by the file size.
pub const MAX_RANGE_STATES: u64 = 1 << 22;

/// Parses the text of a libFAUDES `.gen` file (token or XML flavour);
/// `origin` names the file in errors.
pub fn read(text: &str, origin: &Path) -> Result<Automaton> {
    read_component(text, origin).map(|c| c.automaton)
}

/// [`read`], with the `kind` attribute ([`Kind::Unspecified`] without).
pub fn read_component(text: &str, origin: &Path) -> Result<Component> {
    if xml::looks_like_xml(text) {
        return xml::read(text, origin);
    }
    parse::Parser::new(text, origin).generator()
}

/// Renders `a` in the plain-token style of libFAUDES 2.x.
pub fn write(a: &Automaton) -> String {
    write::write_with_kind(a, Kind::Unspecified)
}

/// [`write()`], recording the component's kind in a `kind` attribute.
pub fn write_component(c: &Component) -> String {
    write::write_with_kind(&c.automaton, c.kind)
}

/// [`write_component()`] to `sink` a piece at a time, without the whole
/// text in memory.
pub(crate) fn stream_component(
    c: &Component,
    sink: &mut dyn FnMut(&str) -> std::io::Result<()>,
) -> std::io::Result<()> {
    write::stream_with_kind(&c.automaton, c.kind, sink)
}

/// The file the unit tests' texts come from, as errors name it.
#[cfg(test)]
fn p() -> &'static Path {
    Path::new("t.gen")
}
