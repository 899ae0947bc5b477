//! The native Petri-net format: TOML.
//!
//! ```toml
//! name = "two mixers"
//! places = [
//!   { id = "ma1", tokens = 1, name = "mixer A idle" },   # name: optional
//!   { id = "ma2" },                                      # tokens: default 0
//!   { id = "m3" },
//! ]
//! transitions = [
//!   # input / output: place = arc weight; observable: default true
//!   { id = "ta1", controllable = true, input = { ma1 = 1 }, output = { ma2 = 1, m3 = 1 } },
//!   { id = "ta2", controllable = false, input = { ma2 = 1, m3 = 1 }, output = { ma1 = 1 } },
//! ]
//! ```
//!
//! `[[places]]` and `[[transitions]]` tables are the same thing spelled
//! long. Places and transitions keep their file order (the order of
//! markings and of the incidence matrix). `controllable` is required (or
//! stated beside the file, [`super::control`]): a transition silently
//! taken as controllable would let a supervisor count on disabling what it
//! cannot. Unknown keys are errors; every error
//! carries the file, line and column of the offending entry.

use super::control::{Control, Stated};
use super::{NetBuilder, PetriNet};
use crate::error::{Error, Location, Result};
use crate::formats::toml::basic_string as quoted;
use serde::Deserialize;
use std::fmt::Write as _;
use std::path::Path;
use toml::Spanned;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    name: Spanned<String>,
    #[serde(default)]
    places: Vec<Spanned<RawPlace>>,
    #[serde(default)]
    transitions: Vec<Spanned<RawTransition>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlace {
    id: String,
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    tokens: u32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTransition {
    id: String,
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    controllable: Option<bool>,
    #[serde(default)]
    observable: Option<bool>,
    #[serde(default)]
    input: Option<Spanned<toml::Table>>,
    #[serde(default)]
    output: Option<Spanned<toml::Table>>,
}

/// Parses a native TOML net; `origin` names the file in errors.
pub fn read(text: &str, origin: &Path) -> Result<PetriNet> {
    read_with(text, origin, &Control::default())
}

/// Parses a native TOML net with the controllability and observability of
/// transitions stated in `control` too ([`super::control`]: where both
/// state it they must agree); `origin` names the file in errors.
pub fn read_with(text: &str, origin: &Path, control: &Control) -> Result<PetriNet> {
    let at = |offset: usize| Location::at_offset(origin, text, offset);
    let file: File = crate::formats::toml::parse(text, origin)?;
    let mut b = NetBuilder::new(file.name.into_inner());
    for p in &file.places {
        let place = p.get_ref();
        b.add_place(
            &place.id,
            place.name.clone(),
            place.tokens,
            at(p.span().start),
        )?;
    }
    for t in &file.transitions {
        let tr = t.get_ref();
        let here = at(t.span().start);
        let stated = Stated {
            controllable: tr.controllable,
            observable: tr.observable,
        };
        let (controllable, observable) = control.resolve(&tr.id, stated, &here)?;
        b.add_transition(&tr.id, tr.name.clone(), controllable, observable, here)?;
    }
    for t in &file.transitions {
        let tr = t.get_ref();
        for (arcs, input) in [(&tr.input, true), (&tr.output, false)] {
            let Some(arcs) = arcs else { continue };
            let here = at(arcs.span().start);
            for (place, weight) in arcs.get_ref() {
                let weight = weight
                    .as_integer()
                    .and_then(|w| u32::try_from(w).ok())
                    .ok_or_else(|| {
                        Error::syntax(
                            here.clone(),
                            format!("the weight of the arc of `{place}` must be a whole number from 1 to 2^32 - 1"),
                        )
                    })?;
                let (source, target) = if input {
                    (place.as_str(), tr.id.as_str())
                } else {
                    (tr.id.as_str(), place.as_str())
                };
                b.add_arc(source, target, weight, here.clone())?;
            }
        }
    }
    let net = b.build();
    control.check_names(&net, origin)?;
    Ok(net)
}

/// Renders `net` in the native form (inline tables, one line per place
/// and per transition).
pub fn write(net: &PetriNet) -> String {
    let mut out = format!("name = {}\nplaces = [\n", quoted(net.name()));
    for (p, place) in net.places().iter().enumerate() {
        let _ = write!(out, "  {{ id = {}", quoted(&place.id));
        if net.initial()[p] > 0 {
            let _ = write!(out, ", tokens = {}", net.initial()[p]);
        }
        if let Some(name) = &place.name {
            let _ = write!(out, ", name = {}", quoted(name));
        }
        out.push_str(" },\n");
    }
    out.push_str("]\ntransitions = [\n");
    for t in net.transitions() {
        let _ = write!(
            out,
            "  {{ id = {}, controllable = {}",
            quoted(&t.id),
            t.controllable
        );
        if !t.observable {
            out.push_str(", observable = false");
        }
        if let Some(name) = &t.name {
            let _ = write!(out, ", name = {}", quoted(name));
        }
        for (side, arcs) in [("input", &t.input), ("output", &t.output)] {
            if arcs.is_empty() {
                continue;
            }
            let list: Vec<String> = arcs
                .iter()
                .map(|&(p, w)| format!("{} = {w}", key(&net.places()[p].id)))
                .collect();
            let _ = write!(out, ", {side} = {{ {} }}", list.join(", "));
        }
        out.push_str(" },\n");
    }
    out.push_str("]\n");
    out
}

/// A TOML key: bare when TOML allows it, quoted otherwise.
fn key(id: &str) -> String {
    let bare = !id.is_empty()
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        id.to_owned()
    } else {
        quoted(id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MIXERS: &str = r#"name = "two mixers"
places = [
  { id = "ma1", tokens = 1, name = "mixer A idle" },
  { id = "ma2" },
  { id = "m3" },
]
transitions = [
  { id = "ta1", controllable = true, input = { ma1 = 1 }, output = { ma2 = 1, m3 = 1 } },
  { id = "ta2", controllable = false, observable = false, input = { ma2 = 1, m3 = 1 }, output = { ma1 = 1 } },
]
"#;

    fn read_str(text: &str) -> Result<PetriNet> {
        read(text, Path::new("n.toml"))
    }

    #[test]
    fn a_net_reads_in_file_order_and_writes_back_to_itself() {
        let net = read_str(MIXERS).unwrap();
        assert_eq!(net.name(), "two mixers");
        assert_eq!(net.initial(), &[1, 0, 0]);
        assert_eq!(net.places()[0].name.as_deref(), Some("mixer A idle"));
        let (ta1, ta2) = (&net.transitions()[0], &net.transitions()[1]);
        assert!(ta1.controllable && ta1.observable);
        assert!(!ta2.controllable && !ta2.observable);
        assert_eq!(net.incidence(), [[-1, 1], [1, -1], [1, -1]]);
        let written = write(&net);
        assert_eq!(read_str(&written).unwrap(), net, "{written}");
        assert_eq!(write(&read_str(&written).unwrap()), written);
    }

    #[test]
    fn mistakes_are_located() {
        let cases = [
            (
                MIXERS.replace("controllable = false, ", ""),
                "n.toml:9:3: transition `ta2` does not say whether it is controllable: state which transitions are uncontrollable beside the file",
            ),
            (
                MIXERS.replace("output = { ma1 = 1 }", "output = { ma9 = 1 }"),
                "n.toml:9:97: arc names `ma9`, which is no place or transition",
            ),
            (
                MIXERS.replace("input = { ma1 = 1 }", "input = { ma1 = 0 }"),
                "n.toml:8:46: an arc's weight must be at least 1",
            ),
            (
                MIXERS.replace("input = { ma1 = 1 }", "input = { ma1 = -1 }"),
                "n.toml:8:46: the weight of the arc of `ma1` must be a whole number from 1 to 2^32 - 1",
            ),
            (
                MIXERS.replace("{ id = \"m3\" }", "{ id = \"ma2\" }"),
                "n.toml:5:3: id `ma2` is already used at line 4; places and transitions need distinct ids",
            ),
            (
                MIXERS.replace("{ id = \"ma2\" }", "{ id = \"ma2\", colour = 1 }"),
                "n.toml:4:17: unknown field `colour`, expected one of `id`, `name`, `tokens`",
            ),
        ];
        for (text, expected) in cases {
            assert_eq!(read_str(&text).unwrap_err().to_string(), expected, "{text}");
        }
    }
}
