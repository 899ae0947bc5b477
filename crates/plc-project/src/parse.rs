//! The project file as written: TOML deserialised into raw structs that
//! keep the byte span of every name and value, so that validation can point
//! at the offending line and column.
//!
//! Only the shape is checked here (known sections and fields, value
//! types); whether names resolve and values make sense is
//! [`super::validate`]'s job. Tables whose order matters (every section
//! of declarations, above all `[events]`, whose order is the priority
//! order) are read as [`Entries`], a list in file order; this needs the
//! `preserve_order` feature of the `toml` crate, without which tables come
//! out sorted by key.
//!
//! Leniency (docs/formats.md, "PLC project"): every list of names (`rising`, `when`,
//! `set`, `plants`, …) also accepts a single name (`set = "lamp"`).
//!
//! `[board]` (docs/formats.md, "[board]"; see [`super::validate::board`])
//! maps each signal to a pin given as a table (`{ pin = "PA0", pull =
//! "up", active_low = true }`) or as a bare pin name (`"PA0"`).

use des::error::{Error, Location, Result};
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use std::fmt;
use std::marker::PhantomData;
use std::path::Path;
use toml::Spanned;

/// A name or other string with its span in the project file.
pub(crate) type Name = Spanned<String>;

/// The entries of a TOML table in file order: (key, value), both spanned.
#[derive(Debug)]
pub(crate) struct Entries<T>(pub Vec<(Name, Spanned<T>)>);

impl<T> Default for Entries<T> {
    fn default() -> Self {
        Entries(Vec::new())
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Entries<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct EntriesVisitor<T>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>> Visitor<'de> for EntriesVisitor<T> {
            type Value = Entries<T>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a table")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Entries<T>, A::Error> {
                let mut entries = Vec::new();
                while let Some(entry) = map.next_entry()? {
                    entries.push(entry);
                }
                Ok(Entries(entries))
            }
        }
        deserializer.deserialize_map(EntriesVisitor(PhantomData))
    }
}

/// A list of names that may also be written as a single name.
#[derive(Debug)]
pub(crate) enum Names {
    /// `x = "a"`: its span is the span of the whole value.
    One(String),
    /// `x = ["a", "b"]`.
    Many(Vec<Name>),
}

impl<'de> Deserialize<'de> for Names {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NamesVisitor;
        impl<'de> Visitor<'de> for NamesVisitor {
            type Value = Names;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a name or a list of names")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Names, E> {
                Ok(Names::One(s.to_owned()))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Names, A::Error> {
                let mut names = Vec::new();
                while let Some(name) = seq.next_element()? {
                    names.push(name);
                }
                Ok(Names::Many(names))
            }
        }
        deserializer.deserialize_any(NamesVisitor)
    }
}

/// The names of an optional list field, each with its span (empty when
/// the field is absent).
pub(crate) fn names(field: Option<&Spanned<Names>>) -> Vec<Name> {
    match field {
        None => Vec::new(),
        Some(spanned) => match spanned.get_ref() {
            Names::One(name) => vec![Spanned::new(spanned.span(), name.clone())],
            Names::Many(list) => list.clone(),
        },
    }
}

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawProject {
    pub plc: Spanned<RawPlc>,
    #[serde(default)]
    pub inputs: Entries<RawInput>,
    #[serde(default)]
    pub outputs: Entries<RawOutput>,
    #[serde(default)]
    pub timers: Entries<RawTimer>,
    #[serde(default)]
    pub switches: Entries<Entries<String>>,
    #[serde(default)]
    pub events: Entries<RawEvent>,
    #[serde(default)]
    pub supervisor: Vec<Spanned<RawSupervisor>>,
    #[serde(default)]
    pub net: Vec<Spanned<RawNet>>,
    #[serde(default)]
    pub board: Option<Spanned<RawBoard>>,
}

/// `[plc]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPlc {
    pub name: Name,
    #[serde(default)]
    pub scan_period_ms: Option<Spanned<i64>>,
    #[serde(default)]
    pub max_commands_per_scan: Option<Spanned<i64>>,
    #[serde(default)]
    pub unexpected: Option<Name>,
    #[serde(default)]
    pub reset: Option<Name>,
    #[serde(default)]
    pub overrun_limit: Option<Spanned<i64>>,
    #[serde(default)]
    pub overrun_fault: bool,
    #[serde(default)]
    pub lost_edge_fault: bool,
    #[serde(default)]
    pub rom_test_bytes_per_scan: Option<Spanned<i64>>,
    #[serde(default)]
    pub stored_sets_bytes: Option<Spanned<i64>>,
    #[serde(default)]
    pub check_nonconflicting: Option<Spanned<bool>>,
}

/// An entry of `[inputs]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawInput {
    #[serde(default)]
    pub debounce_scans: Option<Spanned<i64>>,
}

/// An entry of `[outputs]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawOutput {
    #[serde(default)]
    pub safe: bool,
    #[serde(default)]
    pub initial: Option<Spanned<bool>>,
    /// State map: supervisor → state names.
    #[serde(default)]
    pub states: Option<Spanned<Entries<Names>>>,
    /// Place map: net → place ids.
    #[serde(default)]
    pub places: Option<Spanned<Entries<Names>>>,
}

/// An entry of `[timers]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTimer {
    pub preset_ms: Spanned<i64>,
}

/// An entry of `[events]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawEvent {
    #[serde(default)]
    pub controllable: Option<Spanned<bool>>,
    #[serde(default)]
    pub origin: Option<Name>,
    #[serde(default)]
    pub rising: Option<Spanned<Names>>,
    #[serde(default)]
    pub falling: Option<Spanned<Names>>,
    #[serde(default)]
    pub expired: Option<Name>,
    #[serde(default)]
    pub when: Option<Spanned<Names>>,
    #[serde(default)]
    pub unless: Option<Spanned<Names>>,
    #[serde(default)]
    pub request: Option<Name>,
    #[serde(default)]
    pub set: Option<Spanned<Names>>,
    #[serde(default)]
    pub clear: Option<Spanned<Names>>,
    #[serde(default)]
    pub start: Option<Spanned<Names>>,
    #[serde(default)]
    pub reset: Option<Spanned<Names>>,
    /// Switch → position.
    #[serde(default)]
    pub switch: Option<Spanned<Entries<String>>>,
}

/// A `[[supervisor]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSupervisor {
    #[serde(default)]
    pub name: Option<Name>,
    #[serde(default)]
    pub file: Option<Name>,
    #[serde(default)]
    pub component: Option<Name>,
    #[serde(default)]
    pub synthesize: Option<Spanned<RawSynthesize>>,
    /// A guard file (`*.guards.toml`): a symbolic supervisor.
    #[serde(default)]
    pub guards: Option<Name>,
    /// The logic backend's effort limit for this supervisor (default:
    /// the backend's, `codegen::backend::logic::DEFAULT_MAX_EFFORT`).
    #[serde(default)]
    pub max_logic_effort: Option<Spanned<u64>>,
}

/// A `[[net]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawNet {
    pub name: Name,
    pub file: Name,
    #[serde(default)]
    pub constraints: Option<Name>,
    #[serde(default)]
    pub transform: Option<Spanned<bool>>,
    /// The uncontrollable transitions, for a net file that does not say
    /// (every other transition is then controllable).
    #[serde(default)]
    pub uncontrollable: Option<Spanned<Names>>,
    /// The unobservable transitions (every other one is then observable).
    #[serde(default)]
    pub unobservable: Option<Spanned<Names>>,
    /// A control file stating both instead.
    #[serde(default)]
    pub control: Option<Name>,
    /// The most markings the reachability analysis may reach (default
    /// [`des::petri::reach::DEFAULT_MAX_STATES`]).
    #[serde(default)]
    pub max_markings: Option<Spanned<u64>>,
}

/// `synthesize = { plants, specs, minimize, reduce, max_states }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSynthesize {
    pub plants: Spanned<Names>,
    #[serde(default)]
    pub specs: Option<Spanned<Names>>,
    #[serde(default)]
    pub minimize: bool,
    /// Reduce the supervisor (its closed loop checked equal).
    #[serde(default)]
    pub reduce: Option<Spanned<bool>>,
    /// Localize the supervisor: one local controller per controllable
    /// event (their closed loop checked equal).
    #[serde(default)]
    pub localize: Option<Spanned<bool>>,
    /// Synthesise symbolically: components and guards, not one automaton.
    #[serde(default)]
    pub symbolic: Option<Spanned<bool>>,
    /// The most states a composition may reach (default
    /// [`des::ops::sync::DEFAULT_MAX_STATES`]).
    #[serde(default)]
    pub max_states: Option<Spanned<u64>>,
}

/// `[board]`: the chip and the pin of each signal.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBoard {
    #[serde(default)]
    pub chip: Option<Name>,
    #[serde(default)]
    pub inputs: Entries<RawPin<RawInputPin>>,
    #[serde(default)]
    pub outputs: Entries<RawPin<RawOutputPin>>,
}

/// A pin mapping: a bare pin name (`part = "PA1"`, every option at its
/// default) or a table of options.
#[derive(Debug)]
pub(crate) enum RawPin<T> {
    /// `signal = "PA1"`: its span is the span of the whole value.
    Bare(String),
    /// `signal = { pin = "PA1", … }`.
    Table(T),
}

/// `{ pin, pull, active_low }` of `[board.inputs]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawInputPin {
    pub pin: Name,
    #[serde(default)]
    pub pull: Option<Name>,
    #[serde(default)]
    pub active_low: bool,
}

/// `{ pin, active_low }` of `[board.outputs]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawOutputPin {
    pub pin: Name,
    #[serde(default)]
    pub active_low: bool,
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for RawPin<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct PinVisitor<T>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>> Visitor<'de> for PinVisitor<T> {
            type Value = RawPin<T>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a pin name such as \"PA0\" or a table such as `{ pin = \"PA0\", active_low = true }`")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<RawPin<T>, E> {
                Ok(RawPin::Bare(s.to_owned()))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<RawPin<T>, A::Error> {
                T::deserialize(de::value::MapAccessDeserializer::new(map)).map(RawPin::Table)
            }
        }
        deserializer.deserialize_any(PinVisitor(PhantomData))
    }
}

/// What serde calls our structs, and what a user should read instead.
const STRUCT_NAMES: [(&str, &str); 12] = [
    ("struct RawProject", "a project file"),
    ("struct RawPlc", "the `[plc]` table"),
    (
        "struct RawInput",
        "an input table such as `{ debounce_scans = 3 }`",
    ),
    (
        "struct RawOutput",
        "an output table such as `{ safe = false }`",
    ),
    (
        "struct RawTimer",
        "a timer table such as `{ preset_ms = 1000 }`",
    ),
    (
        "struct RawEvent",
        "an event table such as `{ rising = \"x\" }`",
    ),
    ("struct RawSupervisor", "a supervisor table"),
    ("struct RawNet", "a net table"),
    (
        "struct RawSynthesize",
        "a table such as `{ plants = [...], specs = [...] }`",
    ),
    ("struct RawBoard", "the `[board]` table"),
    (
        "struct RawInputPin",
        "an input pin such as `{ pin = \"PA0\", pull = \"up\", active_low = true }`",
    ),
    (
        "struct RawOutputPin",
        "an output pin such as `{ pin = \"PB0\", active_low = false }`",
    ),
];

/// Parses `text`; `path` names the file in errors.
pub(crate) fn parse(text: &str, path: &Path) -> Result<RawProject> {
    ::toml::from_str(text).map_err(|e| {
        let location = match e.span() {
            Some(span) => Location::at_offset(path, text, span.start),
            None => Location::file(path),
        };
        let mut message = e.message().trim_end().to_owned();
        for (internal, shown) in STRUCT_NAMES {
            message = message.replace(internal, shown);
        }
        Error::syntax(location, message)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_ok(text: &str) -> RawProject {
        parse(text, Path::new("p.plc.toml")).unwrap()
    }

    fn parse_err(text: &str) -> String {
        parse(text, Path::new("p.plc.toml"))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn tables_keep_file_order() {
        let raw = parse_ok(
            "[plc]\nname = \"x\"\n[events]\nzeta = {}\nalpha = {}\nmid = {}\n[[supervisor]]\nfile = \"a.toml\"\n",
        );
        let keys: Vec<&str> = raw
            .events
            .0
            .iter()
            .map(|(k, _)| k.get_ref().as_str())
            .collect();
        assert_eq!(keys, ["zeta", "alpha", "mid"]);
        assert_eq!(raw.supervisor.len(), 1);
    }

    #[test]
    fn dotted_tables_keep_file_order_too() {
        let raw = parse_ok("[plc]\nname = \"x\"\n[events.b]\n[events.a]\n");
        let keys: Vec<&str> = raw
            .events
            .0
            .iter()
            .map(|(k, _)| k.get_ref().as_str())
            .collect();
        assert_eq!(keys, ["b", "a"]);
    }

    #[test]
    fn a_single_name_counts_as_a_list_with_its_span() {
        let text = "[plc]\nname = \"x\"\n[events]\ne = { rising = \"a\", when = [\"b\", \"c\"] }\n";
        let raw = parse_ok(text);
        let e = raw.events.0[0].1.get_ref();
        let rising = names(e.rising.as_ref());
        assert_eq!(rising.len(), 1);
        assert_eq!(&text[rising[0].span()], "\"a\"");
        let when = names(e.when.as_ref());
        assert_eq!(&text[when[1].span()], "\"c\"");
        assert!(names(e.unless.as_ref()).is_empty());
    }

    #[test]
    fn unknown_fields_are_errors_at_their_line() {
        let msg = parse_err("[plc]\nname = \"x\"\n[events]\ne = { rising = \"a\", raising = 1 }\n");
        assert!(
            msg.starts_with("p.plc.toml:4:21: unknown field `raising`"),
            "{msg}"
        );
        let msg = parse_err("[plc]\nname = \"x\"\n\n[event]\n");
        assert!(
            msg.starts_with("p.plc.toml:4:2: unknown field `event`"),
            "{msg}"
        );
    }

    #[test]
    fn wrong_shapes_are_described_in_project_words() {
        let msg = parse_err("[plc]\nname = \"x\"\n[events]\ne = 5\n");
        assert!(msg.contains("expected an event table"), "{msg}");
        assert!(msg.starts_with("p.plc.toml:4:5:"), "{msg}");
        let msg = parse_err("[plc]\nname = \"x\"\n[events]\ne = { rising = 5 }\n");
        assert!(msg.contains("expected a name or a list of names"), "{msg}");
    }

    #[test]
    fn the_plc_table_and_its_name_are_required() {
        assert!(parse_err("").contains("missing field `plc`"));
        let msg = parse_err("[plc]\nscan_period_ms = 5\n");
        assert!(
            msg.starts_with("p.plc.toml:1:1: missing field `name`"),
            "{msg}"
        );
    }
}
