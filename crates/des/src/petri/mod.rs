//! Place/transition Petri nets: the model, its two file formats and its
//! reachability graph.
//!
//! - [`PetriNet`]: places with an initial marking, transitions marked
//!   controllable or not (and observable or not), weighted arcs; the
//!   incidence matrix, enabling and firing. Built through [`NetBuilder`],
//!   which refuses duplicate ids, arcs between two places or two
//!   transitions, zero weights and repeated arcs, each at its location.
//! - [`toml`]: the native form; [`pnml`]: PNML, the P/T-net type of
//!   ISO/IEC 15909-2, as Petri-net editors write it. [`read_file`] and
//!   [`write_file`] pick the format by extension (`.toml`, `.pnml`);
//!   [`control`]: which transitions are uncontrollable or unobservable,
//!   stated beside the file for nets whose file does not say
//!   ([`read_file_with`]).
//! - [`invariants`]: minimal place and transition semiflows (Farkas),
//!   with exact `u128` weights and bounded work.
//! - [`constraints`] and [`synth`]: linear marking constraints `L·m ≤ b`
//!   and place-invariant synthesis, one control place per constraint,
//!   for any net (it is algebra: boundedness is not needed);
//!   [`admissible`]: an inadmissible constraint made admissible (Moody–
//!   Antsaklis, greedy); [`compare`]: the result against supcon on the
//!   reachability graphs, where they are finite.
//! - [`reach`]: the reachability graph of a bounded net (or of a region
//!   of any net) as an automaton (one event per transition, its
//!   controllability kept), within limits on markings, memory and names,
//!   and a refusal for an unbounded net (the place that grows and a
//!   firing sequence that makes it grow).
//!
//! **Arithmetic.** Tokens and arc weights are `u32`, constraint weights
//! and bounds `i64`; everything derived from them (`L·m`, control places,
//! transformed weights, invariants, markings) is computed exactly, in a
//! wider type where needed, and what a net cannot hold is refused with
//! the limit named, never wrapped (`tests/petri_limits.rs` checks this at
//! the types' edges).

pub mod admissible;
pub mod compare;
pub mod constraints;
pub mod control;
pub mod invariants;
pub mod pnml;
pub mod reach;
pub mod synth;
pub mod toml;

use crate::error::{Error, Location, Result};
use rustc_hash::FxHashMap;
use std::path::Path;

/// Tokens per place, in place order.
pub type Marking = Vec<u32>;

/// A place.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Place {
    /// Its id, unique among places and transitions (PNML's `id`).
    pub id: String,
    /// Its display name, if the file gives one.
    pub name: Option<String>,
}

/// A transition with its arcs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Transition {
    /// Its id, unique among places and transitions.
    pub id: String,
    /// Its display name, if the file gives one.
    pub name: Option<String>,
    /// Whether a supervisor may prevent it from firing.
    pub controllable: bool,
    /// Whether a supervisor sees it fire.
    pub observable: bool,
    /// Input arcs: (place index, weight ≥ 1), in file order.
    pub input: Vec<(usize, u32)>,
    /// Output arcs: (place index, weight ≥ 1), in file order.
    pub output: Vec<(usize, u32)>,
}

/// A place/transition net with an initial marking.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PetriNet {
    name: String,
    places: Vec<Place>,
    transitions: Vec<Transition>,
    initial: Marking,
}

impl PetriNet {
    /// The net's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The places, in file order.
    pub fn places(&self) -> &[Place] {
        &self.places
    }

    /// The transitions, in file order.
    pub fn transitions(&self) -> &[Transition] {
        &self.transitions
    }

    /// The initial marking.
    pub fn initial(&self) -> &Marking {
        &self.initial
    }

    /// The index of the place with id `id`.
    pub fn place(&self, id: &str) -> Option<usize> {
        self.places.iter().position(|p| p.id == id)
    }

    /// The index of the transition with id `id`.
    pub fn transition(&self, id: &str) -> Option<usize> {
        self.transitions.iter().position(|t| t.id == id)
    }

    /// The incidence matrix `D = Post − Pre`: `D[p][t]` is the change of
    /// place `p`'s tokens when transition `t` fires.
    pub fn incidence(&self) -> Vec<Vec<i64>> {
        let columns: Vec<Vec<i64>> = (0..self.transitions.len())
            .map(|t| self.change(t))
            .collect();
        (0..self.places.len())
            .map(|p| columns.iter().map(|column| column[p]).collect())
            .collect()
    }

    /// Column `t` of the incidence matrix: the change of every place's
    /// tokens when transition `t` fires (`post − pre`).
    pub fn change(&self, t: usize) -> Vec<i64> {
        let mut change = vec![0i64; self.places.len()];
        let tr = &self.transitions[t];
        for &(p, w) in &tr.input {
            change[p] -= i64::from(w);
        }
        for &(p, w) in &tr.output {
            change[p] += i64::from(w);
        }
        change
    }

    /// Whether transition `t` may fire in marking `m`: every input place
    /// holds at least its arc's weight.
    pub fn is_enabled(&self, m: &[u32], t: usize) -> bool {
        self.transitions[t].input.iter().all(|&(p, w)| m[p] >= w)
    }

    /// The marking after `t` fires in `m`; `None` when `t` is not enabled
    /// or a place would overflow `u32`.
    pub fn fire(&self, m: &[u32], t: usize) -> Option<Marking> {
        if !self.is_enabled(m, t) {
            return None;
        }
        let mut next = m.to_vec();
        let tr = &self.transitions[t];
        for &(p, w) in &tr.input {
            next[p] -= w;
        }
        for &(p, w) in &tr.output {
            next[p] = next[p].checked_add(w)?;
        }
        Some(next)
    }

    /// A marking as text: the marked places in place order, `id` for one
    /// token and `k·id` for `k`, joined by `+`; `empty` when no place
    /// holds a token.
    ///
    /// The name is injective: two markings of a net never share it
    /// (states of the reachability graph are named by it). An id that
    /// could be misread — one holding `+`, `·`, `"` or `\`, or the id
    /// `empty` — is written quoted, `"a+b"`, with `\"` and `\\` for
    /// its quote and backslash; so the `+` between terms, the `·` after a
    /// count and the word `empty` only ever mean what they say, and the
    /// name reads back to one marking.
    pub fn marking_name(&self, m: &[u32]) -> String {
        let parts: Vec<String> = m
            .iter()
            .enumerate()
            .filter(|&(_, &k)| k > 0)
            .map(|(p, &k)| {
                let id = marking_term(&self.places[p].id, "empty");
                match k {
                    1 => id,
                    k => format!("{k}·{id}"),
                }
            })
            .collect();
        if parts.is_empty() {
            "empty".to_owned()
        } else {
            parts.join("+")
        }
    }
}

/// A place id as a term of a marking's name ([`PetriNet::marking_name`],
/// the trace names of a project's nets): bare unless it could be misread
/// (it holds `+`, `·`, `"` or `\`, is empty, or is `empty_word`, the
/// name of the empty marking), quoted then, `"a+b"`, with `\"` and `\\`
/// for its quote and backslash.
pub fn marking_term(id: &str, empty_word: &str) -> String {
    let special = |c: char| matches!(c, '+' | '·' | '"' | '\\');
    if id != empty_word && !id.is_empty() && !id.contains(special) {
        return id.to_owned();
    }
    let mut quoted = String::with_capacity(id.len() + 2);
    quoted.push('"');
    for c in id.chars() {
        if matches!(c, '"' | '\\') {
            quoted.push('\\');
        }
        quoted.push(c);
    }
    quoted.push('"');
    quoted
}

/// The place id of a term written by [`marking_term`] at the start of
/// `text`, and the rest of `text`; `None` for an unterminated quote.
pub fn read_marking_term<'t>(text: &'t str, separator: &str) -> Option<(String, &'t str)> {
    let Some(quoted) = text.strip_prefix('"') else {
        return Some(match text.find(separator) {
            Some(k) => (text[..k].to_owned(), &text[k..]),
            None => (text.to_owned(), ""),
        });
    };
    let mut id = String::new();
    let mut chars = quoted.char_indices();
    while let Some((k, c)) = chars.next() {
        match c {
            '\\' => id.push(chars.next()?.1),
            '"' => return Some((id, &quoted[k + 1..])),
            c => id.push(c),
        }
    }
    None
}

/// What an id names, for the builder's checks.
#[derive(Debug, Clone, Copy)]
enum Node {
    Place(usize),
    Transition(usize),
}

/// Builds a [`PetriNet`], refusing what a net cannot be, at the location
/// given with each element.
#[derive(Debug, Default)]
pub struct NetBuilder {
    name: String,
    places: Vec<Place>,
    initial: Marking,
    transitions: Vec<Transition>,
    ids: FxHashMap<String, (Node, Location)>,
}

impl NetBuilder {
    /// A builder for a net called `name`.
    pub fn new(name: impl Into<String>) -> NetBuilder {
        NetBuilder {
            name: name.into(),
            ..NetBuilder::default()
        }
    }

    fn claim(&mut self, id: &str, node: Node, at: Location) -> Result<()> {
        if id.is_empty() {
            return Err(Error::model(at, "an id must not be empty"));
        }
        if let Some((_, first)) = self.ids.get(id) {
            return Err(Error::model(
                at,
                format!(
                    "id `{id}` is already used at line {}; places and transitions need distinct ids",
                    first.line
                ),
            ));
        }
        self.ids.insert(id.to_owned(), (node, at));
        Ok(())
    }

    /// Adds a place holding `tokens` initially; its index.
    pub fn add_place(
        &mut self,
        id: &str,
        name: Option<String>,
        tokens: u32,
        at: Location,
    ) -> Result<usize> {
        let index = self.places.len();
        self.claim(id, Node::Place(index), at)?;
        self.places.push(Place {
            id: id.to_owned(),
            name,
        });
        self.initial.push(tokens);
        Ok(index)
    }

    /// Adds a transition without arcs; its index.
    pub fn add_transition(
        &mut self,
        id: &str,
        name: Option<String>,
        controllable: bool,
        observable: bool,
        at: Location,
    ) -> Result<usize> {
        let index = self.transitions.len();
        self.claim(id, Node::Transition(index), at)?;
        self.transitions.push(Transition {
            id: id.to_owned(),
            name,
            controllable,
            observable,
            input: Vec::new(),
            output: Vec::new(),
        });
        Ok(index)
    }

    /// Adds an arc of weight `weight` from the place or transition `source`
    /// to the transition or place `target` (both by id, declared before or
    /// after: call [`NetBuilder::add_arc`] once all nodes are in).
    pub fn add_arc(&mut self, source: &str, target: &str, weight: u32, at: Location) -> Result<()> {
        let node = |id: &str| {
            self.ids.get(id).map(|(n, _)| *n).ok_or_else(|| {
                Error::model(
                    at.clone(),
                    format!("arc names `{id}`, which is no place or transition"),
                )
            })
        };
        let (source_node, target_node) = (node(source)?, node(target)?);
        if weight == 0 {
            return Err(Error::model(at, "an arc's weight must be at least 1"));
        }
        let (t, p, input) = match (source_node, target_node) {
            (Node::Place(p), Node::Transition(t)) => (t, p, true),
            (Node::Transition(t), Node::Place(p)) => (t, p, false),
            (Node::Place(_), Node::Place(_)) => {
                return Err(Error::model(
                    at,
                    format!("arc from place `{source}` to place `{target}`: an arc joins a place and a transition"),
                ))
            }
            (Node::Transition(_), Node::Transition(_)) => {
                return Err(Error::model(
                    at,
                    format!("arc from transition `{source}` to transition `{target}`: an arc joins a place and a transition"),
                ))
            }
        };
        let tr = &mut self.transitions[t];
        let arcs = if input { &mut tr.input } else { &mut tr.output };
        if arcs.iter().any(|&(q, _)| q == p) {
            return Err(Error::model(
                at,
                format!(
                    "a second arc from `{source}` to `{target}`: give the one arc its total weight"
                ),
            ));
        }
        arcs.push((p, weight));
        Ok(())
    }

    /// The net.
    pub fn build(self) -> PetriNet {
        PetriNet {
            name: self.name,
            places: self.places,
            transitions: self.transitions,
            initial: self.initial,
        }
    }
}

/// A net file's format, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NetFormat {
    /// The native TOML form ([`toml`]).
    Toml,
    /// PNML ([`pnml`]).
    Pnml,
}

impl NetFormat {
    /// The format of `path` by its extension (case-insensitive).
    pub fn from_path(path: &Path) -> Result<NetFormat> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("toml") => Ok(NetFormat::Toml),
            Some("pnml") => Ok(NetFormat::Pnml),
            _ => Err(Error::Incompatible(format!(
                "{}: unknown Petri-net format (expected .pnml or .toml)",
                path.display()
            ))),
        }
    }
}

/// Reads the net in the file at `path` (format by extension; the same
/// limits as model files: a regular file of at most
/// [`crate::formats::MAX_MODEL_BYTES`]). Every transition must state its
/// controllability in the file.
pub fn read_file(path: &Path) -> Result<PetriNet> {
    read_file_with(path, &control::Control::default())
}

/// Reads the net in the file at `path` as [`read_file`] does, with the
/// controllability and observability of its transitions stated in
/// `control` ([`control`]'s rules).
pub fn read_file_with(path: &Path, control: &control::Control) -> Result<PetriNet> {
    let format = NetFormat::from_path(path)?;
    let text = crate::formats::read_model_text(path)?;
    read_str_with(&text, format, path, control)
}

/// Parses `text` as a net in `format`; `origin` names the file in errors.
pub fn read_str(text: &str, format: NetFormat, origin: &Path) -> Result<PetriNet> {
    read_str_with(text, format, origin, &control::Control::default())
}

/// Parses `text` as a net in `format` with `control` ([`read_file_with`]).
pub fn read_str_with(
    text: &str,
    format: NetFormat,
    origin: &Path,
    control: &control::Control,
) -> Result<PetriNet> {
    match format {
        NetFormat::Toml => toml::read_with(text, origin, control),
        NetFormat::Pnml => pnml::read_with(text, origin, control),
    }
}

/// Renders `net` in `format`; PNML refuses names XML cannot carry
/// ([`pnml::write`]).
pub fn write_string(format: NetFormat, net: &PetriNet) -> Result<String> {
    match format {
        NetFormat::Toml => Ok(toml::write(net)),
        NetFormat::Pnml => pnml::write(net),
    }
}

/// Writes `net` to `path` in the format its extension names.
pub fn write_file(path: &Path, net: &PetriNet) -> Result<()> {
    let text = write_string(NetFormat::from_path(path)?, net).map_err(|e| match e {
        Error::Incompatible(message) => {
            Error::Incompatible(format!("{}: {message}", path.display()))
        }
        e => e,
    })?;
    std::fs::write(path, text).map_err(|e| Error::io(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(line: u32) -> Location {
        Location::new("n.toml", line, 1)
    }

    /// A producer/consumer pair: `put` moves a token from `free` to `full`,
    /// `get` back; `put` is controllable, `get` not.
    fn buffer(slots: u32) -> PetriNet {
        let mut b = NetBuilder::new("buffer");
        b.add_place("free", None, slots, at(1)).unwrap();
        b.add_place("full", Some("Full slots".into()), 0, at(2))
            .unwrap();
        b.add_transition("put", None, true, true, at(3)).unwrap();
        b.add_transition("get", None, false, true, at(4)).unwrap();
        b.add_arc("free", "put", 1, at(5)).unwrap();
        b.add_arc("put", "full", 1, at(6)).unwrap();
        b.add_arc("full", "get", 1, at(7)).unwrap();
        b.add_arc("get", "free", 1, at(8)).unwrap();
        b.build()
    }

    #[test]
    fn incidence_enabling_and_firing_follow_the_arcs() {
        let net = buffer(2);
        assert_eq!(net.incidence(), [[-1, 1], [1, -1]]);
        let m = net.initial().clone();
        assert!(net.is_enabled(&m, 0) && !net.is_enabled(&m, 1));
        let m = net.fire(&m, 0).unwrap();
        assert_eq!(m, [1, 1]);
        assert_eq!(net.marking_name(&m), "free+full");
        let m = net.fire(&m, 0).unwrap();
        assert_eq!(net.marking_name(&m), "2·full");
        assert_eq!(net.fire(&m, 0), None, "no free slot");
        assert_eq!(net.marking_name(&[0, 0]), "empty");
    }

    #[test]
    fn what_a_net_cannot_be_is_refused_at_its_location() {
        let mut b = NetBuilder::new("bad");
        b.add_place("p", None, 0, at(1)).unwrap();
        b.add_transition("t", None, true, true, at(2)).unwrap();
        let err = |r: Result<usize>| r.unwrap_err().to_string();
        assert_eq!(
            err(b.add_transition("p", None, true, true, at(3))),
            "n.toml:3:1: id `p` is already used at line 1; places and transitions need distinct ids"
        );
        let arc = |b: &mut NetBuilder, s: &str, t: &str, w: u32| {
            b.add_arc(s, t, w, at(9)).unwrap_err().to_string()
        };
        assert!(arc(&mut b, "p", "q", 1).contains("`q`, which is no place or transition"));
        assert!(arc(&mut b, "p", "t", 0).contains("weight must be at least 1"));
        assert!(arc(&mut b, "p", "p", 1).contains("from place `p` to place `p`"));
        assert!(arc(&mut b, "t", "t", 1).contains("from transition `t` to transition `t`"));
        b.add_arc("p", "t", 2, at(5)).unwrap();
        assert!(arc(&mut b, "p", "t", 1).starts_with("n.toml:9:1: a second arc from `p` to `t`"));
        // The opposite direction is another arc (a self-loop).
        b.add_arc("t", "p", 2, at(6)).unwrap();
        assert_eq!(b.build().incidence(), [[0]]);
    }
}
