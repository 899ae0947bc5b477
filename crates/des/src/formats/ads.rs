//! TCT ASCII description files (`.ads`).
//!
//! # The format
//!
//! An ADS file is line-based. The first line that is neither blank nor a
//! comment (`#` …) names the automaton. Four sections follow, each opened
//! by a header line ending in a colon:
//!
//! - `State size (…):` — one number `n`; the states are `0 … n-1` and the
//!   initial state is `0` (`n = 0` is the empty automaton);
//! - `Marker states:` — marked states, one per line, or `*` for all;
//! - `Vocal states:` — `state output` pairs (read and checked, then
//!   ignored: vocal outputs are not part of our automaton model);
//! - `Transitions:` — `exit label entrance` triples.
//!
//! A list section ends at the first blank line or at the next header;
//! comment lines may appear anywhere. Event labels are non-negative
//! integers: **odd labels are controllable, even labels uncontrollable**.
//!
//! # Names
//!
//! ADS has no event or state names. By default the event with label `11`
//! is called `11` and states are unnamed. To make round trips exact, the
//! writer adds comment lines that this reader (and only this reader)
//! understands, each with a JSON string:
//!
//! - `# event 11 = "e11"` — label 11 is the event `e11`;
//! - `# state 3 = "working"` — state 3 is called `working`;
//! - `# name = "my plant"` — the automaton's name, when the name line
//!   cannot hold it (empty, multi-line, looks like a comment or a header);
//! - `# kind = "supervisor"` — the component's kind (`plant`, `spec`,
//!   `supervisor` or `property`, as in the native TOML format), written by
//!   [`write_component`] when it is known.
//!
//! TCT ignores these comments, so files stay valid TCT input; files
//! written by TCT carry none and read with numeric event names.
//!
//! # Writing
//!
//! [`write()`] gives every event a label of the parity its controllability
//! demands: a name that is a number (`11`) or `e` followed by a number
//! (`e11`), as in TCT-derived benchmarks, keeps that number when the
//! parity fits and no other event took it; every other event gets the
//! smallest free label of the right parity. The mapping is recorded in
//! `# event` comments whenever it is not the identity (then for every
//! event, in alphabet order, so that the alphabet reads back in the same
//! order, including events on no transition).
//!
//! The initial state must be state 0 in ADS: the writer swaps the initial
//! state with state 0 when needed (names travel with their states). An
//! automaton without an initial state generates the empty language and
//! is written as the empty automaton (state size 0). State sizes above
//! [`MAX_STATES`] are refused (TCT itself stops at 2,000,000).

use super::{parse_kind, Component, Kind, KINDS};
use crate::automaton::{Automaton, AutomatonBuilder, BuildError, EventId, StateId};
use crate::error::{line_column, Error, Location, Result};
use rustc_hash::{FxHashMap, FxHashSet};
use std::fmt::Write as _;
use std::path::Path;

/// The largest state size the reader accepts (so that a few bytes cannot
/// demand gigabytes; TCT itself stops at 2,000,000).
pub const MAX_STATES: u64 = 1 << 22;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Section {
    Size,
    Marker,
    Vocal,
    Transitions,
}

impl Section {
    fn title(self) -> &'static str {
        match self {
            Section::Size => "State size",
            Section::Marker => "Marker states",
            Section::Vocal => "Vocal states",
            Section::Transitions => "Transitions",
        }
    }

    /// The section a header line opens, if it is one.
    fn of_header(line: &str) -> Option<Section> {
        let t = line.trim();
        if !t.ends_with(':') {
            return None;
        }
        let lower = t.to_ascii_lowercase();
        [
            Section::Size,
            Section::Marker,
            Section::Vocal,
            Section::Transitions,
        ]
        .into_iter()
        .find(|s| lower.starts_with(&s.title().to_ascii_lowercase()))
    }
}

/// One of our comment lines.
enum Mapping {
    Event(u64, String),
    State(u64, String),
    Name(String),
    Kind(String),
}

/// Recognises `# event N = "…"`, `# state N = "…"`, `# name = "…"` and
/// `# kind = "…"`.
/// `Ok(None)` for ordinary comments; an error for a mapping comment
/// whose JSON string is malformed.
fn parse_mapping(line: &str) -> std::result::Result<Option<Mapping>, String> {
    let Some(body) = line.trim().strip_prefix('#') else {
        return Ok(None);
    };
    let body = body.trim_start();
    let json = |rest: &str| -> std::result::Result<String, String> {
        serde_json::from_str::<String>(rest.trim())
            .map_err(|e| format!("expected a quoted name (a JSON string) after `=`: {e}"))
    };
    for (kw, mapping) in [
        ("name", Mapping::Name as fn(String) -> Mapping),
        ("kind", Mapping::Kind),
    ] {
        if let Some(rest) = body.strip_prefix(kw) {
            return match rest.trim_start().strip_prefix('=') {
                Some(v) => json(v).map(|n| Some(mapping(n))),
                None => Ok(None),
            };
        }
    }
    for (kw, is_event) in [("event", true), ("state", false)] {
        let Some(rest) = body.strip_prefix(kw) else {
            continue;
        };
        if !rest.starts_with([' ', '\t']) {
            return Ok(None);
        }
        let rest = rest.trim_start();
        let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
        let Some(value) = rest[digits..].trim_start().strip_prefix('=') else {
            return Ok(None);
        };
        if digits == 0 {
            return Ok(None);
        }
        let n: u64 = rest[..digits]
            .parse()
            .map_err(|_| format!("{kw} number `{}` is too large", &rest[..digits]))?;
        let name = json(value)?;
        return Ok(Some(if is_event {
            Mapping::Event(n, name)
        } else {
            Mapping::State(n, name)
        }));
    }
    Ok(None)
}

/// A line with its byte offset in the file.
#[derive(Clone, Copy)]
struct Line<'a> {
    text: &'a str,
    offset: usize,
}

impl<'a> Line<'a> {
    fn is_blank(&self) -> bool {
        self.text.trim().is_empty()
    }

    fn is_comment(&self) -> bool {
        self.text.trim_start().starts_with('#')
    }

    /// Whitespace-separated fields with their byte offsets in the file.
    fn fields(&self) -> impl Iterator<Item = (&'a str, usize)> + 'a {
        let base = self.offset;
        let text = self.text;
        text.split(|c: char| c.is_whitespace())
            .filter(|f| !f.is_empty())
            .map(move |f| (f, base + (f.as_ptr() as usize - text.as_ptr() as usize)))
    }
}

struct Reader<'a> {
    text: &'a str,
    origin: &'a Path,
}

impl<'a> Reader<'a> {
    fn syntax(&self, offset: usize, msg: impl Into<String>) -> Error {
        Error::syntax(Location::at_offset(self.origin, self.text, offset), msg)
    }

    fn model(&self, offset: usize, msg: impl Into<String>) -> Error {
        Error::model(Location::at_offset(self.origin, self.text, offset), msg)
    }

    fn number(&self, field: (&str, usize), what: &str) -> Result<u64> {
        let (f, at) = field;
        if f.is_empty() || !f.bytes().all(|b| b.is_ascii_digit()) {
            return Err(self.syntax(
                at,
                format!("expected {what} (a non-negative integer), found `{f}`"),
            ));
        }
        f.parse::<u64>()
            .map_err(|_| self.syntax(at, format!("{what} `{f}` is too large")))
    }

    fn state(&self, field: (&str, usize), size: u64, what: &str) -> Result<u64> {
        let s = self.number(field, what)?;
        if s >= size {
            return Err(self.model(
                field.1,
                format!(
                    "{what} {s} is out of range (the state size is {size}, so states are 0 to {})",
                    size.saturating_sub(1)
                ),
            ));
        }
        Ok(s)
    }
}

/// Parses a TCT `.ads` file; `origin` names the file in errors.
pub fn read(text: &str, origin: &Path) -> Result<Automaton> {
    read_component(text, origin).map(|c| c.automaton)
}

/// [`read`], with the kind of a `# kind` comment ([`Kind::Unspecified`]
/// without).
pub fn read_component(text: &str, origin: &Path) -> Result<Component> {
    let r = Reader { text, origin };
    let mut lines = Vec::new();
    let mut offset = 0;
    for raw in text.split('\n') {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        lines.push(Line { text: line, offset });
        offset += raw.len() + 1;
    }
    if let Some(first) = lines.first_mut() {
        if let Some(rest) = first.text.strip_prefix('\u{feff}') {
            first.text = rest;
            first.offset += 3;
        }
    }

    // Pass 1: our comment mappings.
    let mut event_names: Vec<(u64, String, usize)> = Vec::new();
    let mut state_names: FxHashMap<u64, (String, usize)> = FxHashMap::default();
    let mut name_comment: Option<String> = None;
    let mut kind = Kind::Unspecified;
    let mut named_labels: FxHashSet<u64> = FxHashSet::default();
    for l in lines.iter().filter(|l| l.is_comment()) {
        match parse_mapping(l.text).map_err(|m| r.syntax(l.offset, m))? {
            None => {}
            Some(Mapping::Name(n)) => name_comment = Some(n),
            Some(Mapping::Kind(k)) => {
                kind = parse_kind(&k).ok_or_else(|| {
                    r.syntax(
                        l.offset,
                        format!("unknown kind {} (expected {KINDS})", json(&k)),
                    )
                })?;
            }
            Some(Mapping::Event(label, _)) if !named_labels.insert(label) => {
                return Err(r.syntax(l.offset, format!("event label {label} is named twice")));
            }
            Some(Mapping::Event(label, name)) => event_names.push((label, name, l.offset)),
            Some(Mapping::State(s, _)) if state_names.contains_key(&s) => {
                return Err(r.syntax(l.offset, format!("state {s} is named twice")));
            }
            Some(Mapping::State(s, name)) => {
                state_names.insert(s, (name, l.offset));
            }
        }
    }

    // Pass 2: name line and sections.
    let mut name_line: Option<&str> = None;
    let mut size: Option<u64> = None;
    let mut marked_all = false;
    let mut marked: Vec<u64> = Vec::new();
    let mut transitions: Vec<(u64, u64, u64, usize)> = Vec::new();
    let mut seen: Vec<Section> = Vec::new();
    let mut current: Option<Section> = None;
    // The size section holds exactly one number.
    let mut size_done = false;
    for l in &lines {
        if l.is_comment() {
            continue;
        }
        if let Some(sec) = Section::of_header(l.text) {
            if seen.contains(&sec) {
                return Err(r.syntax(l.offset, format!("duplicate `{}:` section", sec.title())));
            }
            if sec != Section::Size && size.is_none() {
                return Err(r.syntax(
                    l.offset,
                    format!(
                        "the `State size` section must come before `{}:`",
                        sec.title()
                    ),
                ));
            }
            seen.push(sec);
            current = Some(sec);
            continue;
        }
        if l.is_blank() {
            // A blank line ends a list; the size section may have blank
            // lines before its number.
            if current != Some(Section::Size) || size_done {
                current = None;
            }
            continue;
        }
        let fields: Vec<(&str, usize)> = l.fields().collect();
        let first = fields.first().copied().unwrap_or(("", l.offset));
        match current {
            None => {
                if name_line.is_none() && seen.is_empty() {
                    name_line = Some(l.text.trim());
                } else {
                    return Err(r.syntax(
                        first.1,
                        format!(
                            "expected a section header (`State size …:`, `Marker states:`, `Vocal states:` or `Transitions:`), found `{}`",
                            l.text.trim()
                        ),
                    ));
                }
            }
            Some(Section::Size) => {
                if size_done {
                    return Err(r.syntax(
                        first.1,
                        "the state size is a single number (expected a blank line or the next section header)",
                    ));
                }
                if fields.len() != 1 {
                    return Err(r.syntax(
                        fields.get(1).map_or(first.1, |f| f.1),
                        "expected a single number, the state size",
                    ));
                }
                let n = r.number(first, "state size")?;
                if n > MAX_STATES {
                    return Err(r.model(
                        first.1,
                        format!("state size {n} is too large (at most {MAX_STATES} states are supported)"),
                    ));
                }
                size = Some(n);
                size_done = true;
            }
            Some(Section::Marker) => {
                let n = size.unwrap_or(0);
                if fields.len() == 1 && first.0 == "*" {
                    marked_all = true;
                    continue;
                }
                for f in fields {
                    marked.push(r.state(f, n, "marker state")?);
                }
            }
            Some(Section::Vocal) => {
                let n = size.unwrap_or(0);
                if fields.len() != 2 {
                    return Err(r.syntax(
                        first.1,
                        "expected a vocal state as `state output` (two numbers)",
                    ));
                }
                r.state(fields[0], n, "vocal state")?;
                r.number(fields[1], "vocal output")?;
            }
            Some(Section::Transitions) => {
                let n = size.unwrap_or(0);
                if fields.len() != 3 {
                    return Err(r.syntax(
                        fields.get(3).map_or(first.1, |f| f.1),
                        format!(
                            "expected a transition as `exit label entrance` (three numbers), found {} field{}",
                            fields.len(),
                            if fields.len() == 1 { "" } else { "s" }
                        ),
                    ));
                }
                let s = r.state(fields[0], n, "exit state")?;
                let label = r.number(fields[1], "transition label")?;
                let t = r.state(fields[2], n, "entrance state")?;
                transitions.push((s, label, t, fields[0].1));
            }
        }
    }
    let Some(size) = size else {
        return Err(r.syntax(
            text.len(),
            "missing `State size` section (expected `State size (…):` followed by the number of states)",
        ));
    };
    // TCT writes every section; a file without `Transitions:` was cut
    // short, and reading it as a model without transitions would be wrong
    // without a word.
    if !seen.contains(&Section::Transitions) {
        return Err(r.syntax(
            text.len(),
            "missing `Transitions:` section (is the file cut short? TCT writes it even when empty)",
        ));
    }

    let name = name_comment
        .or(name_line.map(str::to_owned))
        .unwrap_or_else(|| {
            origin
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("ads")
                .to_owned()
        });
    let mut b = AutomatonBuilder::new(name);

    // Events: named ones first, in comment order, then by first use.
    let mut label_event: FxHashMap<u64, EventId> = FxHashMap::default();
    let mut name_label: FxHashMap<String, u64> = FxHashMap::default();
    let mut add_event = |b: &mut AutomatonBuilder,
                         label_event: &mut FxHashMap<u64, EventId>,
                         label: u64,
                         name: String,
                         at: usize|
     -> Result<EventId> {
        if let Some(&other) = name_label.get(&name) {
            return Err(r.model(
                at,
                format!("event labels {other} and {label} both stand for event `{name}`"),
            ));
        }
        let e = b
            .add_event(&name, label % 2 == 1)
            .map_err(|e| r.model(at, e.to_string()))?;
        name_label.insert(name, label);
        label_event.insert(label, e);
        Ok(e)
    };
    for (label, name, at) in event_names {
        add_event(&mut b, &mut label_event, label, name, at)?;
    }
    let mut edges = Vec::with_capacity(transitions.len());
    for (s, label, t, at) in transitions {
        let e = match label_event.get(&label) {
            Some(&e) => e,
            None => add_event(&mut b, &mut label_event, label, label.to_string(), at)?,
        };
        edges.push((s, e, t, at));
    }

    // States.
    if let Some((s, (_, at))) = state_names.iter().find(|(s, _)| **s >= size) {
        return Err(r.model(
            *at,
            format!("state {s} is named but the state size is {size}"),
        ));
    }
    let mut ids = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
    for i in 0..size {
        let id = if state_names.is_empty() {
            b.add_anonymous_state()
        } else {
            let (name, at) = match state_names.get(&i) {
                Some((n, at)) => (n.clone(), *at),
                None => (i.to_string(), text.len()),
            };
            if b.find_state(&name).is_some() {
                return Err(r.model(at, format!("two states are called `{name}`")));
            }
            b.add_state(&name)
        };
        ids.push(id);
    }
    let id = |s: u64| ids[s as usize];
    if size > 0 {
        b.set_initial(StateId(0))
            .map_err(|e| r.model(0, e.to_string()))?;
    }
    if marked_all {
        for &s in &ids {
            b.mark(s);
        }
    }
    for s in marked {
        b.mark(id(s));
    }
    for (s, e, t, at) in edges {
        b.add_transition(id(s), e, id(t), u32::try_from(at).unwrap_or(u32::MAX));
    }
    let mut a = b.build().map_err(|e| match &e {
        BuildError::Nondeterministic {
            line, first_line, ..
        } => {
            let (l, c) = line_column(text, *first_line as usize);
            r.model(
                *line as usize,
                format!("{e} (the other transition is at line {l}, column {c})"),
            )
        }
        _ => Error::model(Location::file(origin), e.to_string()),
    })?;
    super::gen::drop_index_names(&mut a);
    Ok(Component { kind, automaton: a })
}

/// The TCT label of each event (indexed by event id); see the module docs.
pub fn labels(a: &Automaton) -> Vec<u64> {
    let alphabet = a.alphabet();
    let natural = |name: &str| -> Option<u64> {
        let digits = name.strip_prefix('e').unwrap_or(name);
        let n: u64 = digits.parse().ok()?;
        (n.to_string() == digits).then_some(n)
    };
    let mut labels: Vec<Option<u64>> = vec![None; alphabet.len()];
    let mut taken: FxHashSet<u64> = FxHashSet::default();
    for (id, e) in alphabet.iter() {
        if let Some(n) = natural(&e.name) {
            if (n % 2 == 1) == e.controllable && taken.insert(n) {
                labels[id.index()] = Some(n);
            }
        }
    }
    let mut next = [0u64, 1u64]; // next candidate: [uncontrollable, controllable]
    labels
        .iter()
        .zip(alphabet.iter())
        .map(|(l, (_, e))| {
            l.unwrap_or_else(|| {
                let slot = &mut next[usize::from(e.controllable)];
                while taken.contains(slot) {
                    *slot += 2;
                }
                let n = *slot;
                taken.insert(n);
                n
            })
        })
        .collect()
}

/// Whether `name` can stand on the name line and read back unchanged.
fn plain_name(name: &str) -> bool {
    !name.is_empty()
        && name.trim() == name
        && !name.starts_with('#')
        && !name.chars().any(char::is_control)
        && Section::of_header(name).is_none()
}

fn json(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".to_owned())
}

/// Why `a` cannot be written as a TCT `.ads` file without losing what it
/// says: the format has no way to mark an event unobservable (TCT takes
/// the observable events as an argument of its operations instead).
pub fn unwritable_observability(a: &Automaton) -> Option<String> {
    let hidden: Vec<&str> = a
        .alphabet()
        .unobservable()
        .map(|(_, e)| e.name.as_str())
        .collect();
    (!hidden.is_empty()).then(|| {
        format!(
            "`{}` has unobservable events ({}), which a TCT .ads file cannot mark; write .toml, .gen or .wmod",
            a.name(),
            hidden.join(", ")
        )
    })
}

/// Renders `a` as a TCT `.ads` file (see the module docs for names; its
/// events' observability is not written: [`unwritable_observability`]).
pub fn write(a: &Automaton) -> String {
    write_with_kind(a, Kind::Unspecified)
}

/// [`write()`], recording the component's kind in a `# kind` comment.
pub fn write_component(c: &Component) -> String {
    write_with_kind(&c.automaton, c.kind)
}

fn write_with_kind(a: &Automaton, kind: Kind) -> String {
    let n = if a.initial().is_some() {
        a.num_states()
    } else {
        0
    };
    // ADS states: the initial state must be 0; swap it with state 0.
    let init = a.initial().map_or(0, |s| s.index());
    let ads = |s: StateId| -> usize {
        match s.index() {
            i if i == init => 0,
            0 => init,
            i => i,
        }
    };
    let original = |i: usize| -> StateId { StateId(ads(StateId(i as u32)) as u32) };
    let labels = labels(a);

    let mut out = String::with_capacity(256 + a.num_transitions() * 12);
    out.push_str("# TCT ADS file written by codegen\n");
    if !plain_name(a.name()) {
        let _ = writeln!(out, "# name = {}", json(a.name()));
    }
    if kind != Kind::Unspecified {
        let _ = writeln!(out, "# kind = {}", json(&kind.to_string()));
    }
    // Event comments: needed unless every label is the event's own name,
    // every event occurs (in n > 0 transitions) and the order of first
    // use is the alphabet order.
    let mut first_use: Vec<EventId> = Vec::new();
    let mut used = vec![false; a.alphabet().len()];
    if n > 0 {
        for i in 0..n {
            for t in a.transitions(original(i)) {
                if !used[t.event.index()] {
                    used[t.event.index()] = true;
                    first_use.push(t.event);
                }
            }
        }
    }
    let identity = a
        .alphabet()
        .iter()
        .all(|(id, e)| e.name == labels[id.index()].to_string());
    let in_order = first_use.len() == a.alphabet().len()
        && first_use.iter().enumerate().all(|(i, e)| e.index() == i);
    if !(identity && in_order) {
        for (id, e) in a.alphabet().iter() {
            let _ = writeln!(out, "# event {} = {}", labels[id.index()], json(&e.name));
        }
    }
    if n > 0 && a.has_state_names() {
        for i in 0..n {
            let name = a.state_name(original(i));
            if name != i.to_string() {
                let _ = writeln!(out, "# state {i} = {}", json(&name));
            }
        }
    }
    out.push('\n');
    if plain_name(a.name()) {
        out.push_str(a.name());
    } else {
        let cleaned: String = a
            .name()
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect();
        let cleaned = cleaned.trim().trim_start_matches('#').trim();
        if cleaned.is_empty() || Section::of_header(cleaned).is_some() {
            out.push_str("unnamed");
        } else {
            out.push_str(cleaned);
        }
    }
    out.push_str("\n\nState size (State set will be (0,1....,size-1)):\n");
    let _ = writeln!(out, "{n}");
    out.push_str("\nMarker states:\n");
    if n > 0 {
        let marked = a.marked_states().count();
        if marked == n {
            out.push_str("*\n");
        } else {
            let mut m: Vec<usize> = a.marked_states().map(ads).collect();
            m.sort_unstable();
            for s in m {
                let _ = writeln!(out, "{s}");
            }
        }
    }
    out.push_str("\nVocal states:\n\nTransitions:\n");
    if n > 0 {
        for i in 0..n {
            for t in a.transitions(original(i)) {
                let _ = writeln!(out, "{i} {} {}", labels[t.event.index()], ads(t.target));
            }
        }
    }
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const TCT: &str = "# CTCT ADS auto-generated\n\nMACH1\n\nState size (State set will be (0,1....,size-1)):\n# <-- the size\n3\n\nMarker states:\n# comment\n0\n\nVocal states:\n# comment\n\nTransitions:\n# comment\n0 11 1\n1 10 0\n1 12 2\n2 13 0\n";

    fn p() -> &'static Path {
        Path::new("m.ads")
    }

    fn err(text: &str) -> (u32, u32, String) {
        let e = read(text, p()).unwrap_err();
        let (l, m) = e.located().unwrap_or_else(|| panic!("unexpected {e:?}"));
        (l.line, l.column, m.to_owned())
    }

    #[test]
    fn a_tct_file_reads_with_numeric_event_names() {
        let a = read(TCT, p()).unwrap();
        assert_eq!(a.name(), "MACH1");
        assert_eq!((a.num_states(), a.num_transitions()), (3, 4));
        assert!(!a.has_state_names());
        let e11 = a.alphabet().id("11").unwrap();
        assert!(a.alphabet().is_controllable(e11));
        assert!(!a.alphabet().is_controllable(a.alphabet().id("12").unwrap()));
        assert_eq!(a.initial(), Some(StateId(0)));
        assert_eq!(a.marked_states().collect::<Vec<_>>(), [StateId(0)]);
        // Identity labels in first-use order: no comments needed.
        let text = write(&a);
        assert!(!text.contains("# event"), "{text}");
        assert_eq!(read(&text, p()).unwrap(), a);
    }

    #[test]
    fn a_file_cut_before_its_transitions_is_an_error() {
        let cut = &TCT[..TCT.find("Transitions:").unwrap()];
        let err = read(cut, p()).unwrap_err().to_string();
        assert!(err.contains("missing `Transitions:` section"), "{err}");
        assert!(read(TCT, p()).is_ok());
    }

    #[test]
    fn star_marks_all_and_size_zero_is_empty() {
        let a = read(&TCT.replace("\n0\n\nVocal", "\n*\n\nVocal"), p()).unwrap();
        assert_eq!(a.marked_states().count(), 3);
        let e = read(
            "EMPTY\nState size (State set will be (0,1....,size-1)):\n0\n\nMarker states:\n\nVocal states:\n\nTransitions:\n\n",
            p(),
        )
        .unwrap();
        assert!(e.is_empty() && e.initial().is_none());
    }

    #[test]
    fn labels_keep_numbers_of_the_right_parity_and_allocate_the_rest() {
        let mut b = AutomatonBuilder::new("x");
        for (n, c) in [
            ("e11", true),
            ("e10", false),
            ("12", true),
            ("go", true),
            ("stop", false),
            ("e011", true),
            ("1", true),
        ] {
            b.add_event(n, c).unwrap();
        }
        let a = b.build().unwrap();
        assert_eq!(labels(&a), [11, 10, 3, 5, 0, 7, 1]);
    }

    #[test]
    fn named_round_trip_through_comments() {
        let mut b = AutomatonBuilder::new("  odd name");
        let go = b.add_event("go", true).unwrap();
        let done = b.add_event("done", false).unwrap();
        let _unused = b.add_event("e13", true).unwrap();
        let w = b.add_state("working");
        let i = b.add_state("idle");
        b.set_initial(i).unwrap();
        b.mark(i);
        b.add_transition(i, go, w, 0);
        b.add_transition(w, done, i, 0);
        let a = b.build().unwrap();
        let text = write(&a);
        assert!(text.contains("# event 1 = \"go\""), "{text}");
        assert!(text.contains("# name = \"  odd name\""), "{text}");
        let back = read(&text, p()).unwrap();
        assert_eq!(back.name(), a.name());
        assert_eq!(back.alphabet(), a.alphabet());
        // The initial state became state 0; names travel along.
        assert_eq!(back.state_name(StateId(0)), "idle");
        assert_eq!(back.state_name(StateId(1)), "working");
        assert_eq!(back.num_transitions(), 2);
        assert!(back.is_marked(StateId(0)) && !back.is_marked(StateId(1)));
    }

    #[test]
    fn errors_name_line_and_column() {
        let (l, c, m) = err(&TCT.replace("1 12 2", "1 x2 2"));
        assert_eq!((l, c), (20, 3), "{m}");
        assert!(m.contains("transition label"), "{m}");

        let (l, c, m) = err(&TCT.replace("2 13 0", "2 13 3"));
        assert_eq!((l, c), (21, 6), "{m}");
        assert!(m.contains("out of range"), "{m}");

        let (l, _, m) = err(&TCT.replace("1 12 2", "1 10 2"));
        assert_eq!(l, 20, "{m}");
        assert!(
            m.contains("nondeterministic") && m.contains("line 19"),
            "{m}"
        );

        let (l, c, m) = err(&TCT.replace("1 12 2", "1 12"));
        assert_eq!((l, c), (20, 1), "{m}");

        let (l, _, m) = err(&TCT.replace("\n3\n", "\n-3\n"));
        assert_eq!(l, 7, "{m}");

        let (l, _, m) = err(&TCT.replace("\n0\n\nVocal", "\n0\nstray words\nVocal"));
        assert_eq!(l, 12, "{m}");

        let (l, _, m) = err(&TCT.replace("# CTCT", "# event 11 = e11\n# CTCT"));
        assert_eq!(l, 1, "{m}");
        assert!(m.contains("JSON"), "{m}");

        let (_, _, m) = err("NAME\n\nMarker states:\n0\n");
        assert!(m.contains("State size"), "{m}");

        let (l, _, m) = err("BIG\nState size (State set will be (0,1....,size-1)):\n99999999\n");
        assert_eq!(l, 3, "{m}");
        assert!(m.contains("too large"), "{m}");
    }
}
