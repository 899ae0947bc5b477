//! Automaton file formats, chosen by file extension.
//!
//! | extension | format | components per file |
//! |---|---|---|
//! | `.toml` | native ([`toml`]) | one |
//! | `.gen` | libFAUDES generator ([`gen`]) | one |
//! | `.ads` | TCT ASCII description ([`ads`]) | one |
//! | `.wmod` | Supremica / Waters module ([`wmod`]) | many |
//!
//! Readers never panic: malformed input is an [`Error`] naming the file,
//! the line and (where the format has one) the column.

pub mod ads;
pub mod gen;
pub mod toml;
pub mod wmod;

use crate::automaton::Automaton;
use crate::error::{Error, Location, Result};
use std::fmt;
use std::path::Path;

/// A supported file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Native TOML.
    Toml,
    /// libFAUDES `.gen`.
    Gen,
    /// TCT `.ads`.
    Ads,
    /// Supremica / Waters `.wmod`.
    Wmod,
}

impl Format {
    /// The format named by `path`'s extension.
    pub fn from_path(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("toml") => Ok(Format::Toml),
            Some("gen") => Ok(Format::Gen),
            Some("ads") => Ok(Format::Ads),
            Some("wmod") => Ok(Format::Wmod),
            _ => Err(Error::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }

    /// `true` when one file can hold several automata.
    pub fn holds_many(self) -> bool {
        self == Format::Wmod
    }
}

/// The role of an automaton in a file that says so (Waters modules and,
/// optionally, native TOML).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// A plant component.
    Plant,
    /// A specification.
    Spec,
    /// A supervisor.
    Supervisor,
    /// A property (Waters `PROPERTY`), checked rather than enforced.
    Property,
    /// The file does not say.
    Unspecified,
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Kind::Plant => "plant",
            Kind::Spec => "spec",
            Kind::Supervisor => "supervisor",
            Kind::Property => "property",
            Kind::Unspecified => "unspecified",
        })
    }
}

/// The kinds a file may state, as they are written in `kind` fields.
pub(crate) const KINDS: &str = "plant, spec, supervisor or property";

/// The kind written `name` (as [`Kind`]'s `Display` writes it), if any.
pub(crate) fn parse_kind(name: &str) -> Option<Kind> {
    [Kind::Plant, Kind::Spec, Kind::Supervisor, Kind::Property]
        .into_iter()
        .find(|k| k.to_string() == name)
}

/// An automaton with the role its file gives it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Component {
    /// The role.
    pub kind: Kind,
    /// The automaton.
    pub automaton: Automaton,
}

impl Component {
    /// An automaton whose role is not stated.
    pub fn unspecified(automaton: Automaton) -> Self {
        Component {
            kind: Kind::Unspecified,
            automaton,
        }
    }
}

/// Parses `text` in `format`; `origin` names the file in errors.
pub fn read_str(text: &str, format: Format, origin: &Path) -> Result<Vec<Component>> {
    match format {
        Format::Toml => toml::read(text, origin).map(|c| vec![c]),
        Format::Gen => gen::read_component(text, origin).map(|c| vec![c]),
        Format::Ads => ads::read_component(text, origin).map(|c| vec![c]),
        Format::Wmod => wmod::read(text, origin),
    }
}

/// Reads every automaton in the file at `path` (format by extension).
pub fn read_file(path: &Path) -> Result<Vec<Component>> {
    let format = Format::from_path(path)?;
    let text = read_model_text(path)?;
    read_str(&text, format, path)
}

/// The text of the model file at `path` ([`MODEL_FILE`]'s rules: a
/// regular file of at most [`MAX_MODEL_BYTES`]), UTF-8 or else read as
/// ISO-8859-1. Nets and constraints files are read the same way.
pub(crate) fn read_model_text(path: &Path) -> Result<String> {
    let bytes = crate::files::read_bytes(path, MODEL_FILE)?;
    // libFAUDES writes ISO-8859-1; accept it by mapping bytes to chars
    // when the file is not UTF-8 (names stay intact for ASCII input).
    Ok(match String::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
    })
}

/// The largest model file [`read_file`] reads (256 MiB: the largest
/// benchmark results, phil10's 459,250 transitions, take 12 MiB as `.gen`).
pub const MAX_MODEL_BYTES: u64 = 256 << 20;

/// Model files (automata, nets, constraints) as [`crate::files`] reads
/// them.
pub const MODEL_FILE: crate::files::FileKind =
    crate::files::FileKind::new("model file", MAX_MODEL_BYTES);

/// Reads the file at `path`, which must hold exactly one automaton.
pub fn read_automaton(path: &Path) -> Result<Automaton> {
    let mut components = read_file(path)?;
    if components.len() != 1 {
        return Err(Error::model(
            crate::error::Location::file(path),
            format!(
                "expected one automaton, found {} (name the component to use)",
                components.len()
            ),
        ));
    }
    Ok(components.remove(0).automaton)
}

/// Renders `components` in `format`; single-automaton formats take one.
pub fn write_string(format: Format, components: &[Component]) -> Result<String> {
    if !format.holds_many() && components.len() != 1 {
        return Err(Error::Incompatible(format!(
            "{format:?} files hold exactly one automaton, got {}",
            components.len()
        )));
    }
    if format == Format::Wmod {
        if let Some(why) = wmod::unwritable_name(components) {
            return Err(Error::Incompatible(why));
        }
    }
    if format == Format::Ads {
        if let Some(why) = ads::unwritable_observability(&components[0].automaton) {
            return Err(Error::Incompatible(why));
        }
    }
    Ok(match format {
        Format::Toml => toml::write(&components[0]),
        Format::Gen => gen::write_component(&components[0]),
        Format::Ads => ads::write_component(&components[0]),
        Format::Wmod => wmod::write(components),
    })
}

/// Writes `components` to `path` in the format its extension names.
pub fn write_file(path: &Path, components: &[Component]) -> Result<()> {
    let format = Format::from_path(path)?;
    if let (Format::Gen, [one]) = (format, components) {
        // Streamed: a large supervisor's text is never whole in memory.
        use std::io::Write as _;
        let file = std::fs::File::create(path).map_err(|e| Error::io(path, e))?;
        let mut file = std::io::BufWriter::new(file);
        return gen::stream_component(one, &mut |chunk| file.write_all(chunk.as_bytes()))
            .and_then(|()| file.flush())
            .map_err(|e| Error::io(path, e));
    }
    // A name the format cannot carry is an error about this file.
    let text = write_string(format, components).map_err(|e| match e {
        Error::Incompatible(message) => {
            Error::Incompatible(format!("{}: {message}", path.display()))
        }
        e => e,
    })?;
    std::fs::write(path, text).map_err(|e| Error::io(path, e))
}

/// An XML file being read: its text and name, to locate errors at a node.
pub(crate) struct XmlSource<'a> {
    /// The whole text.
    pub(crate) text: &'a str,
    /// The file, as errors name it.
    pub(crate) origin: &'a Path,
}

impl XmlSource<'_> {
    /// Where `node` starts.
    pub(crate) fn at(&self, node: roxmltree::Node<'_, '_>) -> Location {
        Location::at_offset(self.origin, self.text, node.range().start)
    }

    /// A syntax error at `node`.
    pub(crate) fn syntax(&self, node: roxmltree::Node<'_, '_>, msg: impl Into<String>) -> Error {
        Error::syntax(self.at(node), msg)
    }

    /// A model error at `node`.
    pub(crate) fn model(&self, node: roxmltree::Node<'_, '_>, msg: impl Into<String>) -> Error {
        Error::model(self.at(node), msg)
    }
}

/// Parses XML (DTDs allowed, as Supremica and libFAUDES write them, but no
/// entity declarations), with a syntax error at the offending line and
/// column of `origin`.
pub(crate) fn parse_xml<'t>(text: &'t str, origin: &Path) -> Result<roxmltree::Document<'t>> {
    // Entities are the one way a small XML file expands into gigabytes
    // (flat repetition as well as nesting); no model format needs them.
    if let Some(at) = text.find("<!ENTITY") {
        return Err(Error::syntax(
            Location::at_offset(origin, text, at),
            "XML entity declarations are not accepted (they can expand a small file into gigabytes): write the text out",
        ));
    }
    let opts = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    roxmltree::Document::parse_with_options(text, opts).map_err(|e| {
        let pos = e.pos();
        let msg = e.to_string();
        let suffix = format!(" at {pos}");
        let msg = msg.strip_suffix(&suffix).unwrap_or(&msg).to_owned();
        Error::syntax(
            Location::new(origin, pos.row, pos.col),
            format!("malformed XML: {msg}"),
        )
    })
}
