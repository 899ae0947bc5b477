//! The tokens of the plain format: sections, symbols, quoted strings,
//! attributes and `{…}` blocks, read lazily with one token of look-ahead;
//! the XML entities inside quoted strings and tag attributes.

use crate::error::{Error, Location, Result};
use std::borrow::Cow;
use std::path::Path;

/// One token of the plain format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Tok<'a> {
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

/// A token and where it starts.
#[derive(Debug, Clone, Copy)]
pub(super) struct Token<'a> {
    /// What was read.
    pub(super) tok: Tok<'a>,
    /// Byte offset of the token's first character.
    pub(super) pos: usize,
}

/// The token `t` as an error message names it (`None` is the end of the
/// file).
pub(super) fn describe(t: Option<&Token<'_>>) -> String {
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

/// `s`, cut after 40 characters for an error message.
pub(super) fn shorten(s: &str) -> Cow<'_, str> {
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
pub(super) struct Lexer<'a> {
    text: &'a str,
    pos: usize,
    peeked: Option<Option<Token<'a>>>,
    origin: &'a Path,
}

impl<'a> Lexer<'a> {
    /// A lexer at the start of `text` (after a byte-order mark);
    /// `origin` names the file in errors.
    pub(super) fn new(text: &'a str, origin: &'a Path) -> Self {
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

    /// The next token, left to be read again.
    pub(super) fn peek(&mut self) -> Result<Option<Token<'a>>> {
        if let Some(t) = self.peeked {
            return Ok(t);
        }
        let t = self.scan()?;
        self.peeked = Some(t);
        Ok(t)
    }

    /// The next token, consumed (`None` at the end of the file).
    pub(super) fn next(&mut self) -> Result<Option<Token<'a>>> {
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
pub(super) fn decode(raw: &str) -> Cow<'_, str> {
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
pub(super) fn attribute<'a>(attrs: &'a str, key: &str) -> Option<Cow<'a, str>> {
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
pub(super) fn split_explicit_index(s: &str) -> Option<(&str, u64)> {
    let (name, idx) = s.rsplit_once('#')?;
    if idx.is_empty() || !idx.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some((name, idx.parse().ok()?))
}

/// `true` for a non-empty run of ASCII digits: an unquoted state index.
pub(super) fn all_digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

#[cfg(test)]
mod tests {
    use super::super::{p, read};
    use crate::automaton::StateId;

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
}
