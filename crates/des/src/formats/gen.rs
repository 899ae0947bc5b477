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

use super::{parse_kind, Component, Kind, KINDS};
use crate::automaton::{Automaton, AutomatonBuilder, BuildError, StateId};
use crate::error::{line_column, Error, Location, Result};
use rustc_hash::{FxHashMap, FxHashSet};
use std::borrow::Cow;
use std::fmt::Write as _;
use std::path::Path;

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
    if looks_like_xml(text) {
        return read_xml(text, origin);
    }
    Parser::new(text, origin).generator()
}

/// Renders `a` in the plain-token style of libFAUDES 2.x.
pub fn write(a: &Automaton) -> String {
    write_with_kind(a, Kind::Unspecified)
}

/// [`write()`], recording the component's kind in a `kind` attribute.
pub fn write_component(c: &Component) -> String {
    write_with_kind(&c.automaton, c.kind)
}

fn write_with_kind(a: &Automaton, kind: Kind) -> String {
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

// ---------------------------------------------------------------------
// Writing helpers

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

// ---------------------------------------------------------------------
// Tokens

/// One token of the plain format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tok<'a> {
    /// `<name attrs>` or `<name attrs/>` (then `empty`).
    Begin {
        name: &'a str,
        attrs: &'a str,
        empty: bool,
    },
    /// `</name>`.
    End(&'a str),
    /// `"…"`, raw (entities not decoded).
    Quoted(&'a str),
    /// An unquoted symbol or number.
    Symbol(&'a str),
    /// `+…+`.
    Attr(&'a str),
    /// A `{…}` block (skipped).
    Block,
}

#[derive(Debug, Clone, Copy)]
struct Token<'a> {
    tok: Tok<'a>,
    /// Byte offset of the token's first character.
    pos: usize,
}

fn describe(t: Option<&Token<'_>>) -> String {
    match t.map(|t| t.tok) {
        None => "end of file".to_owned(),
        Some(Tok::Begin { name, .. }) => format!("`<{name}>`"),
        Some(Tok::End(name)) => format!("`</{name}>`"),
        Some(Tok::Quoted(s)) => format!("\"{}\"", shorten(s)),
        Some(Tok::Symbol(s)) => format!("`{}`", shorten(s)),
        Some(Tok::Attr(s)) => format!("attribute `{}`", shorten(s)),
        Some(Tok::Block) => "a `{…}` block".to_owned(),
    }
}

fn shorten(s: &str) -> Cow<'_, str> {
    if s.chars().count() <= 40 {
        Cow::Borrowed(s)
    } else {
        Cow::Owned(format!("{}…", s.chars().take(40).collect::<String>()))
    }
}

fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r' | 0x0b | 0x0c)
}

/// Splits the text into tokens, lazily, with one token of look-ahead.
struct Lexer<'a> {
    text: &'a str,
    pos: usize,
    peeked: Option<Option<Token<'a>>>,
    origin: &'a Path,
}

impl<'a> Lexer<'a> {
    fn new(text: &'a str, origin: &'a Path) -> Self {
        let pos = if text.starts_with('\u{feff}') { 3 } else { 0 };
        Lexer {
            text,
            pos,
            peeked: None,
            origin,
        }
    }

    fn error(&self, pos: usize, msg: impl Into<String>) -> Error {
        Error::syntax(Location::at_offset(self.origin, self.text, pos), msg)
    }

    fn peek(&mut self) -> Result<Option<Token<'a>>> {
        if let Some(t) = self.peeked {
            return Ok(t);
        }
        let t = self.scan()?;
        self.peeked = Some(t);
        Ok(t)
    }

    fn next(&mut self) -> Result<Option<Token<'a>>> {
        match self.peeked.take() {
            Some(t) => Ok(t),
            None => self.scan(),
        }
    }

    fn scan(&mut self) -> Result<Option<Token<'a>>> {
        let bytes = self.text.as_bytes();
        // Whitespace and comments.
        loop {
            match bytes.get(self.pos) {
                Some(&b) if is_space(b) => self.pos += 1,
                Some(b'%') => {
                    self.pos = memchr_from(bytes, b'\n', self.pos).unwrap_or(bytes.len());
                }
                _ => break,
            }
        }
        let start = self.pos;
        let Some(&b) = bytes.get(start) else {
            return Ok(None);
        };
        let tok = match b {
            b'"' => {
                let body = start + 1;
                let mut i = body;
                loop {
                    match bytes.get(i) {
                        Some(b'"') => break,
                        Some(b'\n') | None => return Err(self.error(
                            start,
                            "unterminated quoted string (expected a closing `\"` on the same line)",
                        )),
                        Some(_) => i += 1,
                    }
                }
                self.pos = i + 1;
                Tok::Quoted(&self.text[body..i])
            }
            b'+' => {
                let mut i = start + 1;
                loop {
                    match bytes.get(i) {
                        Some(b'+') => break,
                        Some(&c) if !is_space(c) && c != b'<' => i += 1,
                        _ => {
                            return Err(self.error(
                                start,
                                "unterminated attribute (expected `+…+`, e.g. `+C+`)",
                            ))
                        }
                    }
                }
                self.pos = i + 1;
                Tok::Attr(&self.text[start..=i])
            }
            b'{' => {
                let mut depth = 0usize;
                let mut i = start;
                loop {
                    match bytes.get(i) {
                        Some(b'{') => depth += 1,
                        Some(b'}') => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        Some(b'"') => {
                            i = memchr_from(bytes, b'"', i + 1).ok_or_else(|| {
                                self.error(i, "unterminated quoted string in `{…}` block")
                            })?;
                        }
                        Some(_) => {}
                        None => {
                            return Err(self.error(start, "unterminated `{…}` block (expected `}`)"))
                        }
                    }
                    i += 1;
                }
                self.pos = i + 1;
                Tok::Block
            }
            b'<' => self.scan_tag(start)?,
            b'>' => return Err(self.error(start, "unexpected `>` outside a section tag")),
            _ => {
                let mut i = start;
                while let Some(&c) = bytes.get(i) {
                    if is_space(c) || matches!(c, b'<' | b'>' | b'"' | b'%') {
                        break;
                    }
                    i += 1;
                }
                self.pos = i;
                Tok::Symbol(&self.text[start..i])
            }
        };
        Ok(Some(Token { tok, pos: start }))
    }

    fn scan_tag(&mut self, start: usize) -> Result<Tok<'a>> {
        let bytes = self.text.as_bytes();
        let closing = bytes.get(start + 1) == Some(&b'/');
        let name_start = start + 1 + usize::from(closing);
        let mut i = name_start;
        while let Some(&c) = bytes.get(i) {
            if is_space(c) || matches!(c, b'/' | b'>' | b'<' | b'"' | b'=') {
                break;
            }
            i += 1;
        }
        let name = &self.text[name_start..i];
        if name.is_empty() || !name.bytes().all(|c| c.is_ascii_alphanumeric() || c == b'_') {
            return Err(self.error(
                start,
                "malformed section tag (expected `<Name>`, `</Name>` or `<Name/>`)",
            ));
        }
        let attrs_start = i;
        // Find the closing '>' outside quoted attribute values.
        let mut quote: Option<u8> = None;
        loop {
            match (bytes.get(i), quote) {
                (None, _) => {
                    return Err(
                        self.error(start, format!("unterminated tag `<{name}` (expected `>`)"))
                    )
                }
                (Some(&q), Some(open)) if q == open => quote = None,
                (Some(_), Some(_)) => {}
                (Some(&q @ (b'"' | b'\'')), None) => quote = Some(q),
                (Some(b'>'), None) => break,
                (Some(b'<'), None) => {
                    return Err(
                        self.error(start, format!("unterminated tag `<{name}` (expected `>`)"))
                    )
                }
                (Some(_), None) => {}
            }
            i += 1;
        }
        self.pos = i + 1;
        let inner = &self.text[attrs_start..i];
        if closing {
            if !inner.trim().is_empty() {
                return Err(self.error(start, format!("unexpected text in end tag `</{name}>`")));
            }
            return Ok(Tok::End(name));
        }
        let (attrs, empty) = match inner.strip_suffix('/') {
            Some(a) => (a, true),
            None => (inner, false),
        };
        Ok(Tok::Begin { name, attrs, empty })
    }
}

fn memchr_from(bytes: &[u8], needle: u8, from: usize) -> Option<usize> {
    bytes
        .get(from..)?
        .iter()
        .position(|&b| b == needle)
        .map(|p| p + from)
}

/// Decodes the XML entities libFAUDES decodes (plus numeric references);
/// anything else is kept literally.
fn decode(raw: &str) -> Cow<'_, str> {
    if !raw.contains('&') {
        return Cow::Borrowed(raw);
    }
    let mut out = String::with_capacity(raw.len());
    let mut rest = raw;
    while let Some(amp) = rest.find('&') {
        out.push_str(&rest[..amp]);
        let tail = &rest[amp..];
        let decoded = tail.find(';').and_then(|semi| {
            let entity = &tail[1..semi];
            let c = match entity {
                "amp" => Some('&'),
                "quot" => Some('"'),
                "lt" => Some('<'),
                "gt" => Some('>'),
                "apos" => Some('\''),
                _ => {
                    let num = entity.strip_prefix('#')?;
                    let code = match num.strip_prefix(['x', 'X']) {
                        Some(hex) => u32::from_str_radix(hex, 16).ok()?,
                        None => num.parse::<u32>().ok()?,
                    };
                    char::from_u32(code)
                }
            }?;
            Some((c, semi + 1))
        });
        match decoded {
            Some((c, len)) => {
                out.push(c);
                rest = &tail[len..];
            }
            None => {
                out.push('&');
                rest = &tail[1..];
            }
        }
    }
    out.push_str(rest);
    Cow::Owned(out)
}

/// The value of attribute `key` in the raw attribute text of a tag.
fn attribute<'a>(attrs: &'a str, key: &str) -> Option<Cow<'a, str>> {
    let mut rest = attrs;
    loop {
        rest = rest.trim_start();
        let eq = rest.find('=')?;
        let k = rest[..eq].trim();
        let after = rest[eq + 1..].trim_start();
        let q = after.chars().next().filter(|&c| c == '"' || c == '\'')?;
        let body = &after[1..];
        let end = body.find(q)?;
        if k == key {
            return Some(decode(&body[..end]));
        }
        rest = &body[end + 1..];
    }
}

/// `name#17` -> `("name", 17)`.
fn split_explicit_index(s: &str) -> Option<(&str, u64)> {
    let (name, idx) = s.rsplit_once('#')?;
    if idx.is_empty() || !idx.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some((name, idx.parse().ok()?))
}

fn all_digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

fn looks_like_xml(text: &str) -> bool {
    let t = text.trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n']);
    t.starts_with("<?xml") || t.starts_with("<!DOCTYPE") || text.contains("<StateSet")
}

/// Clamps a byte offset into the `u32` "line" tag the builder carries.
fn tag(pos: usize) -> u32 {
    u32::try_from(pos).unwrap_or(u32::MAX)
}

// ---------------------------------------------------------------------
// State declarations (shared by the token and the XML reader)

/// One state as declared in a file.
struct StateDecl<'a> {
    name: Option<Cow<'a, str>>,
    index: Option<u64>,
    pos: usize,
    initial: bool,
    marked: bool,
}

/// The declared states, turned into builder states.
#[derive(Default)]
struct States {
    by_index: FxHashMap<u64, StateId>,
}

impl States {
    /// Adds `decls` to `b` (see the module docs for the naming rule).
    fn commit(
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
fn build_error(e: BuildError, text: &str, origin: &Path) -> Error {
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

fn default_name(origin: &Path) -> String {
    origin
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("generator")
        .to_owned()
}

// ---------------------------------------------------------------------
// The token-format parser

struct Parser<'a> {
    lx: Lexer<'a>,
    text: &'a str,
    origin: &'a Path,
    b: AutomatonBuilder,
    states: Option<States>,
    /// Some event carried an attribute (`+C+`, `+oF+`, …).
    attributed: bool,
}

impl<'a> Parser<'a> {
    fn new(text: &'a str, origin: &'a Path) -> Self {
        Parser {
            lx: Lexer::new(text, origin),
            text,
            origin,
            b: AutomatonBuilder::new(""),
            states: None,
            attributed: false,
        }
    }

    fn syntax(&self, pos: usize, msg: impl Into<String>) -> Error {
        Error::syntax(Location::at_offset(self.origin, self.text, pos), msg)
    }

    fn model(&self, pos: usize, msg: impl Into<String>) -> Error {
        Error::model(Location::at_offset(self.origin, self.text, pos), msg)
    }

    fn end_pos(&self) -> usize {
        self.text.len()
    }

    fn pos_of(&self, t: Option<&Token<'_>>) -> usize {
        t.map_or(self.end_pos(), |t| t.pos)
    }

    fn generator(mut self) -> Result<Component> {
        let first = self.lx.next()?;
        let tag_pos = self.pos_of(first.as_ref());
        let (attrs, empty) = match first.map(|t| t.tok) {
            Some(Tok::Begin {
                name: "Generator",
                attrs,
                empty,
            }) => (attrs, empty),
            _ => {
                return Err(self.syntax(
                    self.pos_of(first.as_ref()),
                    format!("expected `<Generator>`, found {}", describe(first.as_ref())),
                ))
            }
        };
        let mut name = attribute(attrs, "name").map(Cow::into_owned);
        let system = attribute(attrs, "ftype").is_some_and(|t| t == "System");
        let kind = match attribute(attrs, "kind") {
            None => Kind::Unspecified,
            Some(k) => parse_kind(&k).ok_or_else(|| {
                self.model(
                    tag_pos,
                    format!("unknown kind `{}` (expected {KINDS})", shorten(&k)),
                )
            })?,
        };
        if !empty {
            if let Some(t) = self.lx.peek()? {
                if let Tok::Quoted(_) | Tok::Symbol(_) = t.tok {
                    self.lx.next()?;
                    if name.is_none() {
                        name = Some(self.value(&t).into_owned());
                    }
                }
            }
        }
        self.b
            .set_name(name.unwrap_or_else(|| default_name(self.origin)));
        if !empty {
            self.sections()?;
        }
        // A plain generator without any event attribute does not state
        // controllability (typically a specification): it defers to the
        // automata it is combined with.
        if !system && !self.attributed {
            self.b.set_controllability_stated(false);
        }
        if let Some(t) = self.lx.next()? {
            return Err(self.syntax(
                t.pos,
                format!("unexpected {} after `</Generator>`", describe(Some(&t))),
            ));
        }
        let text = self.text;
        let origin = self.origin;
        let mut a = self.b.build().map_err(|e| build_error(e, text, origin))?;
        drop_index_names(&mut a);
        Ok(Component { kind, automaton: a })
    }

    fn value(&self, t: &Token<'a>) -> Cow<'a, str> {
        match t.tok {
            Tok::Quoted(s) => decode(s),
            Tok::Symbol(s) => Cow::Borrowed(s),
            _ => Cow::Borrowed(""),
        }
    }

    fn sections(&mut self) -> Result<()> {
        let mut seen: Vec<&'a str> = Vec::new();
        loop {
            let t = self.lx.next()?;
            let Some(tok) = t else {
                return Err(self.syntax(
                    self.end_pos(),
                    "unexpected end of file (expected `</Generator>`)",
                ));
            };
            match tok.tok {
                Tok::End("Generator") => return Ok(()),
                Tok::Begin { name, empty, .. } => {
                    if seen.contains(&name) {
                        return Err(self.syntax(tok.pos, format!("duplicate section `<{name}>`")));
                    }
                    seen.push(name);
                    match name {
                        "Alphabet" => self.alphabet(empty)?,
                        "States" => self.state_decls(empty)?,
                        "TransRel" => self.trans_rel(empty)?,
                        "InitStates" => self.state_list(empty, "InitStates", true)?,
                        "MarkedStates" => self.state_list(empty, "MarkedStates", false)?,
                        _ => {
                            return Err(self.syntax(
                                tok.pos,
                                format!(
                                    "unsupported section `<{name}>` (expected <Alphabet>, <States>, <TransRel>, <InitStates>, <MarkedStates> or </Generator>)"
                                ),
                            ))
                        }
                    }
                }
                _ => {
                    return Err(self.syntax(
                        tok.pos,
                        format!(
                            "expected a section (<Alphabet>, <States>, <TransRel>, <InitStates>, <MarkedStates>) or `</Generator>`, found {}",
                            describe(Some(&tok))
                        ),
                    ))
                }
            }
        }
    }

    /// Skips an attribute (`+…+`, `{…}` or a nested section) if one comes
    /// next; returns whether it did.
    fn skip_attribute(&mut self) -> Result<bool> {
        let Some(t) = self.lx.peek()? else {
            return Ok(false);
        };
        match t.tok {
            Tok::Attr(_) | Tok::Block => {
                self.lx.next()?;
                Ok(true)
            }
            Tok::Begin { name, empty, .. } if name != "Consecutive" => {
                self.lx.next()?;
                if !empty {
                    self.skip_element(name, t.pos)?;
                }
                Ok(true)
            }
            _ => Ok(false),
        }
    }

    /// Skips to the `</name>` matching an already consumed `<name>`.
    fn skip_element(&mut self, name: &str, pos: usize) -> Result<()> {
        let mut depth = 1usize;
        loop {
            match self.lx.next()?.map(|t| t.tok) {
                None => return Err(self.syntax(pos, format!("section `<{name}>` is never closed"))),
                Some(Tok::Begin { empty: false, .. }) => depth += 1,
                Some(Tok::End(_)) => {
                    depth -= 1;
                    if depth == 0 {
                        return Ok(());
                    }
                }
                Some(_) => {}
            }
        }
    }

    /// The next token inside `<section>`: `None` at its end tag.
    fn item(&mut self, section: &str) -> Result<Option<Token<'a>>> {
        let t = self.lx.next()?;
        match t.map(|t| t.tok) {
            None => Err(self.syntax(
                self.end_pos(),
                format!("unexpected end of file (expected `</{section}>`)"),
            )),
            Some(Tok::End(name)) if name == section => Ok(None),
            Some(Tok::End(name)) => Err(self.syntax(
                self.pos_of(t.as_ref()),
                format!("expected `</{section}>`, found `</{name}>`"),
            )),
            _ => Ok(t),
        }
    }

    fn alphabet(&mut self, empty: bool) -> Result<()> {
        if empty {
            return Ok(());
        }
        while let Some(t) = self.item("Alphabet")? {
            match t.tok {
                Tok::Quoted(_) | Tok::Symbol(_) => {
                    let name = self.value(&t);
                    let controllable = match self.lx.peek()? {
                        Some(Token {
                            tok: Tok::Attr(a), ..
                        }) => {
                            self.lx.next()?;
                            self.attributed = true;
                            a.contains('C')
                        }
                        _ => false,
                    };
                    while self.skip_attribute()? {}
                    self.b
                        .add_event(&name, controllable)
                        .map_err(|e| self.model(t.pos, e.to_string()))?;
                }
                _ => {
                    return Err(self.syntax(
                        t.pos,
                        format!(
                            "expected an event name or `</Alphabet>`, found {}",
                            describe(Some(&t))
                        ),
                    ))
                }
            }
        }
        Ok(())
    }

    fn index(&self, t: &Token<'_>, s: &str) -> Result<u64> {
        s.parse::<u64>()
            .map_err(|_| self.syntax(t.pos, format!("state index `{}` is too large", shorten(s))))
    }

    fn state_decls(&mut self, empty: bool) -> Result<()> {
        let mut decls: Vec<StateDecl<'a>> = Vec::new();
        let mut range_states: u64 = 0;
        if !empty {
            while let Some(t) = self.item("States")? {
                match t.tok {
                    Tok::Symbol(s) if all_digits(s) => {
                        let index = self.index(&t, s)?;
                        decls.push(StateDecl {
                            name: None,
                            index: Some(index),
                            pos: t.pos,
                            initial: false,
                            marked: false,
                        });
                    }
                    Tok::Quoted(_) | Tok::Symbol(_) => {
                        let v = self.value(&t);
                        let (name, index) = match split_explicit_index(&v) {
                            Some((n, i)) => (Cow::Owned(n.to_owned()), Some(i)),
                            None => (v, None),
                        };
                        decls.push(StateDecl {
                            name: Some(name),
                            index,
                            pos: t.pos,
                            initial: false,
                            marked: false,
                        });
                    }
                    Tok::Attr(_) | Tok::Block => {}
                    Tok::Begin {
                        name: "Consecutive",
                        empty,
                        ..
                    } => {
                        let mut bounds = [0u64; 2];
                        if empty {
                            return Err(self.syntax(
                                t.pos,
                                "`<Consecutive/>` needs two indices (expected `<Consecutive> first last </Consecutive>`)",
                            ));
                        }
                        for bound in &mut bounds {
                            let n = self.lx.next()?;
                            match n.map(|n| n.tok) {
                                Some(Tok::Symbol(s)) if all_digits(s) => {
                                    *bound = self.index(n.as_ref().unwrap_or(&t), s)?;
                                }
                                _ => {
                                    return Err(self.syntax(
                                        self.pos_of(n.as_ref()),
                                        format!(
                                            "expected a state index in `<Consecutive>`, found {}",
                                            describe(n.as_ref())
                                        ),
                                    ))
                                }
                            }
                        }
                        let n = self.lx.next()?;
                        if !matches!(n.map(|n| n.tok), Some(Tok::End("Consecutive"))) {
                            return Err(self.syntax(
                                self.pos_of(n.as_ref()),
                                format!(
                                    "expected `</Consecutive>`, found {}",
                                    describe(n.as_ref())
                                ),
                            ));
                        }
                        let [first, last] = bounds;
                        if first > last {
                            return Err(self.syntax(
                                t.pos,
                                format!("empty index range {first} to {last} in `<Consecutive>`"),
                            ));
                        }
                        range_states = range_states.saturating_add(last - first + 1);
                        if range_states > MAX_RANGE_STATES {
                            return Err(self.model(
                                t.pos,
                                format!(
                                    "too many states declared by `<Consecutive>` ranges (at most {MAX_RANGE_STATES} are supported)"
                                ),
                            ));
                        }
                        decls.extend((first..=last).map(|i| StateDecl {
                            name: None,
                            index: Some(i),
                            pos: t.pos,
                            initial: false,
                            marked: false,
                        }));
                    }
                    Tok::Begin { name, empty, .. } => {
                        // An attribute of the previous state.
                        if !empty {
                            self.skip_element(name, t.pos)?;
                        }
                    }
                    Tok::End(_) => {} // `item` consumed the end tag
                }
            }
        }
        let text = self.text;
        let origin = self.origin;
        let err =
            |pos: usize, msg: String| Error::model(Location::at_offset(origin, text, pos), msg);
        self.states = Some(States::commit(&mut self.b, &decls, &err)?);
        self.b.close_states();
        Ok(())
    }

    /// Resolves a state reference (a name, or an unquoted index).
    fn state_ref(&self, t: &Token<'a>) -> Result<StateId> {
        let by_index = |i: u64| {
            self.states
                .as_ref()
                .and_then(|s| s.by_index.get(&i).copied())
        };
        let found = match t.tok {
            Tok::Symbol(s) if all_digits(s) => s
                .parse::<u64>()
                .ok()
                .and_then(by_index)
                .or_else(|| self.b.find_state(s)),
            Tok::Quoted(_) | Tok::Symbol(_) => {
                let v = self.value(t);
                self.b.find_state(&v).or_else(|| {
                    if all_digits(&v) {
                        v.parse::<u64>().ok().and_then(by_index)
                    } else {
                        split_explicit_index(&v)
                            .and_then(|(n, i)| by_index(i).or_else(|| self.b.find_state(n)))
                    }
                })
            }
            _ => {
                return Err(self.syntax(
                    t.pos,
                    format!("expected a state, found {}", describe(Some(t))),
                ))
            }
        };
        found.ok_or_else(|| {
            let what = match t.tok {
                Tok::Symbol(s) if all_digits(s) => format!("state index {s}"),
                _ => format!("state `{}`", self.value(t)),
            };
            self.model(t.pos, format!("{what} is not declared in <States>"))
        })
    }

    fn trans_rel(&mut self, empty: bool) -> Result<()> {
        if empty {
            return Ok(());
        }
        while let Some(t) = self.item("TransRel")? {
            match t.tok {
                Tok::Quoted(_) | Tok::Symbol(_) => {}
                Tok::Attr(_) | Tok::Block => continue,
                Tok::Begin { name, empty, .. } => {
                    if !empty {
                        self.skip_element(name, t.pos)?;
                    }
                    continue;
                }
                Tok::End(_) => {} // `item` consumed the end tag
            }
            let source = self.state_ref(&t)?;
            let et = self.lx.next()?;
            let event = match et {
                Some(
                    et @ Token {
                        tok: Tok::Quoted(_) | Tok::Symbol(_),
                        ..
                    },
                ) => {
                    let name = self.value(&et);
                    self.b.alphabet().id(&name).ok_or_else(|| {
                        self.model(et.pos, format!("event `{name}` is not in the <Alphabet>"))
                    })?
                }
                _ => {
                    return Err(self.syntax(
                        self.pos_of(et.as_ref()),
                        format!(
                            "expected the event of the transition, found {}",
                            describe(et.as_ref())
                        ),
                    ))
                }
            };
            let tt = self.lx.next()?;
            let target = match tt {
                Some(
                    tt @ Token {
                        tok: Tok::Quoted(_) | Tok::Symbol(_),
                        ..
                    },
                ) => self.state_ref(&tt)?,
                _ => {
                    return Err(self.syntax(
                        self.pos_of(tt.as_ref()),
                        format!(
                            "expected the target state of the transition, found {}",
                            describe(tt.as_ref())
                        ),
                    ))
                }
            };
            self.b.add_transition(source, event, target, tag(t.pos));
        }
        Ok(())
    }

    fn state_list(&mut self, empty: bool, section: &str, initial: bool) -> Result<()> {
        if empty {
            return Ok(());
        }
        while let Some(t) = self.item(section)? {
            match t.tok {
                Tok::Quoted(_) | Tok::Symbol(_) => {
                    let s = self.state_ref(&t)?;
                    if initial {
                        self.b
                            .set_initial(s)
                            .map_err(|e| self.model(t.pos, e.to_string()))?;
                    } else {
                        self.b.mark(s);
                    }
                }
                Tok::Attr(_) | Tok::Block => {}
                Tok::Begin { name, empty, .. } => {
                    if !empty {
                        self.skip_element(name, t.pos)?;
                    }
                }
                Tok::End(_) => {} // `item` consumed the end tag
            }
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------
// The XML flavour

fn read_xml(text: &str, origin: &Path) -> Result<Component> {
    let doc = super::parse_xml(text, origin)?;
    let at = |node: roxmltree::Node<'_, '_>| {
        let p = doc.text_pos_at(node.range().start);
        Location::new(origin, p.row, p.col)
    };
    let root = doc.root_element();
    if root.tag_name().name() != "Generator" {
        return Err(Error::syntax(
            at(root),
            format!(
                "expected a `<Generator>` root element, found `<{}>`",
                root.tag_name().name()
            ),
        ));
    }
    let attr = |node: roxmltree::Node<'_, '_>, key: &str| -> Result<String> {
        node.attribute(key).map(str::to_owned).ok_or_else(|| {
            Error::syntax(
                at(node),
                format!(
                    "element `<{}>` lacks its `{key}` attribute",
                    node.tag_name().name()
                ),
            )
        })
    };
    let index = |node: roxmltree::Node<'_, '_>, key: &str| -> Result<u64> {
        let v = attr(node, key)?;
        v.trim().parse::<u64>().map_err(|_| {
            Error::syntax(
                at(node),
                format!(
                    "attribute `{key}` must be a state index, found `{}`",
                    shorten(&v)
                ),
            )
        })
    };
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
                at(root),
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
            "Alphabet" => {
                for ev in section.children().filter(|n| n.is_element()) {
                    if ev.tag_name().name() != "Event" {
                        return Err(Error::syntax(
                            at(ev),
                            format!("expected `<Event>` in `<Alphabet>`, found `<{}>`", ev.tag_name().name()),
                        ));
                    }
                    let name = attr(ev, "name")?;
                    attributed |= ev.children().any(|c| c.is_element());
                    let controllable = ev
                        .children()
                        .any(|c| c.is_element() && c.tag_name().name() == "Controllable");
                    b.add_event(&name, controllable)
                        .map_err(|e| Error::model(at(ev), e.to_string()))?;
                }
            }
            "StateSet" => {
                for st in section.children().filter(|n| n.is_element()) {
                    let pos = st.range().start;
                    match st.tag_name().name() {
                        "State" => {
                            let flag = |f: &str| {
                                st.children().any(|c| c.is_element() && c.tag_name().name() == f)
                            };
                            decls.push(StateDecl {
                                name: st.attribute("name").map(Cow::Borrowed),
                                index: Some(index(st, "id")?),
                                pos,
                                initial: flag("Initial"),
                                marked: flag("Marked"),
                            });
                        }
                        "Consecutive" => {
                            let (first, last) = (index(st, "from")?, index(st, "to")?);
                            if first > last {
                                return Err(Error::syntax(
                                    at(st),
                                    format!("empty index range {first} to {last} in `<Consecutive>`"),
                                ));
                            }
                            range_states = range_states.saturating_add(last - first + 1);
                            if range_states > MAX_RANGE_STATES {
                                return Err(Error::model(
                                    at(st),
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
                            return Err(Error::syntax(
                                at(st),
                                format!("expected `<State>` or `<Consecutive>` in `<StateSet>`, found `<{other}>`"),
                            ))
                        }
                    }
                }
            }
            "TransitionRelation" | "TransRel" => {
                for tr in section.children().filter(|n| n.is_element()) {
                    if tr.tag_name().name() != "Transition" {
                        return Err(Error::syntax(
                            at(tr),
                            format!(
                                "expected `<Transition>` in `<{}>`, found `<{}>`",
                                section.tag_name().name(),
                                tr.tag_name().name()
                            ),
                        ));
                    }
                    transitions.push((index(tr, "x1")?, attr(tr, "event")?, index(tr, "x2")?, tr));
                }
            }
            other => {
                return Err(Error::syntax(
                    at(section),
                    format!("unsupported element `<{other}>` (expected <Alphabet>, <StateSet> or <TransitionRelation>)"),
                ))
            }
        }
    }
    let err = |pos: usize, msg: String| Error::model(Location::at_offset(origin, text, pos), msg);
    let states = States::commit(&mut b, &decls, &err)?;
    for (x1, event, x2, node) in transitions {
        let resolve = |i: u64| {
            states.by_index.get(&i).copied().ok_or_else(|| {
                Error::model(
                    at(node),
                    format!("state index {i} is not declared in <StateSet>"),
                )
            })
        };
        let (s, t) = (resolve(x1)?, resolve(x2)?);
        let e = b.alphabet().id(&event).ok_or_else(|| {
            Error::model(
                at(node),
                format!("event `{event}` is not in the <Alphabet>"),
            )
        })?;
        b.add_transition(s, e, t, tag(node.range().start));
    }
    if !system && !attributed {
        b.set_controllability_stated(false);
    }
    let mut a = b.build().map_err(|e| build_error(e, text, origin))?;
    drop_index_names(&mut a);
    Ok(Component { kind, automaton: a })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> &'static Path {
        Path::new("t.gen")
    }

    fn err_at(text: &str) -> (u32, u32, String) {
        let e = read(text, p()).unwrap_err();
        let (l, m) = e.located().unwrap_or_else(|| panic!("unexpected {e:?}"));
        (l.line, l.column, m.to_owned())
    }

    #[test]
    fn old_style_file_with_quoted_names_reads() {
        let a = read(
            "<Generator>\n\"MACH1\"\n<Alphabet>\n\"e10\" \n\"e11\" +C+\n</Alphabet>\n<States>\n\"0\"\n\"1\"\n</States>\n<TransRel>\n\"0\" \"e11\" \"1\"\n\"1\" \"e10\" \"0\"\n</TransRel>\n<InitStates>\n\"0\"\n</InitStates>\n<MarkedStates>\n\"0\"\n</MarkedStates>\n</Generator>\n",
            p(),
        )
        .unwrap();
        assert_eq!(a.name(), "MACH1");
        assert_eq!((a.num_states(), a.num_transitions()), (2, 2));
        assert!(!a.has_state_names(), "names 0, 1 in order read as indices");
        let e11 = a.alphabet().id("e11").unwrap();
        assert!(a.alphabet().is_controllable(e11));
        assert!(!a
            .alphabet()
            .is_controllable(a.alphabet().id("e10").unwrap()));
        assert_eq!(a.initial(), Some(StateId(0)));
        assert!(a.is_marked(StateId(0)) && !a.is_marked(StateId(1)));
    }

    #[test]
    fn explicit_indices_ranges_attributes_and_comments() {
        let text = r#"% a comment
<Generator name="my gen" ftype="System">
<Alphabet> a +C+ "b" +oF+ c {x y} </Alphabet>   % trailing comment
<States>
1 2 <Consecutive> 4 6 </Consecutive> "idle#9" busy#12 +S+
</States>
<TransRel>
idle a busy
12 b 4 {attr}
4 c "idle"
2 a 1 <Attr> 1 2 </Attr>
</TransRel>
<InitStates> 9 </InitStates>
<MarkedStates/>
</Generator>"#;
        let a = read(text, p()).unwrap();
        assert_eq!(a.name(), "my gen");
        assert_eq!((a.num_states(), a.num_transitions()), (7, 4));
        let names: Vec<_> = a.states().map(|s| a.state_name(s).into_owned()).collect();
        assert_eq!(names, ["1", "2", "4", "5", "6", "idle", "busy"]);
        assert_eq!(a.initial(), a.state_by_name("idle"));
        assert!(a.alphabet().is_controllable(a.alphabet().id("a").unwrap()));
        assert!(!a.alphabet().is_controllable(a.alphabet().id("b").unwrap()));
        let busy = a.state_by_name("busy").unwrap();
        let b = a.alphabet().id("b").unwrap();
        assert_eq!(a.successor(busy, b), a.state_by_name("4"));
        assert_eq!(a.marked_states().count(), 0);
    }

    #[test]
    fn unnamed_states_are_renumbered_densely() {
        let a = read(
            "<Generator name=\"g\"><Alphabet>a</Alphabet><States>3 7 <Consecutive>10 11</Consecutive></States><TransRel>3 a 11</TransRel><InitStates>7</InitStates><MarkedStates>10</MarkedStates></Generator>",
            p(),
        )
        .unwrap();
        assert!(!a.has_state_names());
        assert_eq!(a.num_states(), 4);
        assert_eq!(a.initial(), Some(StateId(1)));
        assert!(a.is_marked(StateId(2)));
        assert_eq!(a.iter_transitions().next().map(|t| t.2), Some(StateId(3)));
    }

    #[test]
    fn entities_are_decoded_in_quoted_strings() {
        let a = read(
            "<Generator name=\"a&amp;b\"><Alphabet>\"x&lt;y\" +C+</Alphabet><States>\"s&#32;1\"</States><TransRel/><InitStates>\"s 1\"</InitStates><MarkedStates/></Generator>",
            p(),
        )
        .unwrap();
        assert_eq!(a.name(), "a&b");
        assert!(a.alphabet().contains("x<y"));
        assert_eq!(a.state_name(StateId(0)), "s 1");
    }

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

    #[test]
    fn errors_name_line_and_column() {
        let (l, c, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x </States>\n<TransRel>\nx b x\n</TransRel>\n</Generator>");
        assert_eq!((l, c), (5, 3), "{m}");
        assert!(m.contains("event `b`"), "{m}");

        let (l, c, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x </States>\n<TransRel>\nx a y\n</TransRel>\n</Generator>");
        assert_eq!((l, c), (5, 5), "{m}");
        assert!(m.contains("state `y` is not declared"), "{m}");

        let (l, _, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x y </States>\n<TransRel>\nx a y\nx a x\n</TransRel>\n</Generator>");
        assert_eq!(l, 6, "{m}");
        assert!(
            m.contains("nondeterministic") && m.contains("line 5"),
            "{m}"
        );

        let (l, c, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x y </States>\n<InitStates>\nx\n  y\n</InitStates>\n</Generator>");
        assert_eq!((l, c), (6, 3), "{m}");
        assert!(m.contains("two initial states"), "{m}");

        let (l, c, m) = err_at("<Generator>\n<Alphabet>\n \"a\n</Alphabet>");
        assert_eq!((l, c), (3, 2), "{m}");
        assert!(m.contains("unterminated"), "{m}");

        let (l, c, m) = err_at("<Generator>\n<Alphabet> a +C </Alphabet>\n");
        assert_eq!((l, c), (2, 14), "{m}");

        let (l, _, m) =
            err_at("<Generator>\n<Alphabet> a </Alphabet>\n<Clocks> x </Clocks>\n</Generator>");
        assert_eq!(l, 3, "{m}");

        let (l, _, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n</Generator>\nextra");
        assert_eq!(l, 4, "{m}");

        let (l, _, m) =
            err_at("<Generator>\n<States>\n<Consecutive> 1 99999999999 </Consecutive>\n</States>\n</Generator>");
        assert_eq!(l, 3, "{m}");
        assert!(m.contains("too many states"), "{m}");

        let (l, _, m) = err_at("<Generator>\n<States> x#1 y#1 </States>\n</Generator>");
        assert_eq!(l, 2, "{m}");
        assert!(m.contains("index 1"), "{m}");
    }

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
