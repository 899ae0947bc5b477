//! The program a PLC task runs: the controller called once per cycle,
//! its inputs and outputs at direct addresses, and the millisecond clock.
//!
//! Addresses come from an I/O map file (docs/formats.md, "I/O map"):
//!
//! ```toml
//! [inputs]
//! start = "%IX0.0"
//! stop  = "%IX0.1"
//! [outputs]
//! motor = "%QX0.0"
//! ```
//!
//! Without one, inputs take `%IX0.0`, `%IX0.1`, … `%IX0.7`, `%IX1.0`, …
//! and outputs `%QX0.0`, … in declaration order. `%I*` and `%Q*` leave
//! the address to the PLC tool (TwinCAT links them in its I/O tree).

use super::pou::{Pou, PouKind, Section, Type, Var, VarBlock};
use super::{comment_text, Names};
use des::error::LineIndex;
use des::{Error, Result};
use plc_project::Project;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Where each signal is wired.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct IoMap {
    file: Option<PathBuf>,
    /// (signal, address, line) of `[inputs]`.
    inputs: Vec<(String, String, u32)>,
    /// (signal, address, line) of `[outputs]`.
    outputs: Vec<(String, String, u32)>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMap {
    #[serde(default)]
    inputs: BTreeMap<String, Spanned<String>>,
    #[serde(default)]
    outputs: BTreeMap<String, Spanned<String>>,
}

/// I/O map files as [`des::files`] reads them: a regular file of at most
/// 4 MiB (an address for each of 65,535 inputs and outputs takes about
/// 2 MiB).
pub const IO_MAP_FILE: des::files::FileKind = des::files::FileKind::new("I/O map", 4 << 20);

impl IoMap {
    /// The default addresses (no file).
    pub fn sequential() -> IoMap {
        IoMap::default()
    }

    /// Reads an I/O map file ([`IO_MAP_FILE`]).
    pub fn load(path: &Path) -> Result<IoMap> {
        let text = des::files::read_text(path, IO_MAP_FILE)?;
        IoMap::parse(&text, path)
    }

    /// Parses the text of an I/O map file read from `path`.
    pub fn parse(text: &str, path: &Path) -> Result<IoMap> {
        let index = LineIndex::new(text);
        let raw: RawMap = toml::from_str(text).map_err(|e| {
            let offset = e.span().map_or(0, |s| s.start);
            Error::syntax(index.location(path, offset), e.message().to_owned())
        })?;
        let entries = |m: BTreeMap<String, Spanned<String>>| {
            let mut v: Vec<(String, String, u32)> = m
                .into_iter()
                .map(|(k, s)| {
                    let line = index.line_column(s.span().start).0;
                    (k, s.into_inner(), line)
                })
                .collect();
            v.sort_by_key(|e| e.2);
            v
        };
        Ok(IoMap {
            file: Some(path.to_path_buf()),
            inputs: entries(raw.inputs),
            outputs: entries(raw.outputs),
        })
    }

    fn error(&self, line: u32, message: String) -> Error {
        let file = self.file.clone().unwrap_or_default();
        Error::model(des::Location::new(file, line, 1), message)
    }

    /// The address of every input and output of `project`, in declaration
    /// order; an error names the line of a bad address, an unknown
    /// signal, an address used twice, or the signals the file leaves out.
    pub fn addresses(&self, project: &Project) -> Result<(Vec<String>, Vec<String>)> {
        if self.file.is_none() {
            let seq = |kind: char, n: usize| {
                (0..n)
                    .map(|k| format!("%{kind}X{}.{}", k / 8, k % 8))
                    .collect::<Vec<_>>()
            };
            return Ok((
                seq('I', project.inputs.len()),
                seq('Q', project.outputs.len()),
            ));
        }
        let mut used: HashMap<String, u32> = HashMap::new();
        let inputs: Vec<&str> = project.inputs.iter().map(|i| i.name.as_str()).collect();
        let outputs: Vec<&str> = project.outputs.iter().map(|o| o.name.as_str()).collect();
        let ins = self.section(&self.inputs, &inputs, 'I', "input", &mut used)?;
        let outs = self.section(&self.outputs, &outputs, 'Q', "output", &mut used)?;
        Ok((ins, outs))
    }

    fn section(
        &self,
        entries: &[(String, String, u32)],
        signals: &[&str],
        kind: char,
        what: &str,
        used: &mut HashMap<String, u32>,
    ) -> Result<Vec<String>> {
        let mut address: Vec<Option<String>> = vec![None; signals.len()];
        for (name, addr, line) in entries {
            let Some(k) = signals.iter().position(|s| s == name) else {
                return Err(self.error(*line, format!("`{name}` is not an {what} of the project")));
            };
            let canonical = parse_address(addr, kind).map_err(|m| self.error(*line, m))?;
            if !canonical.ends_with('*') {
                if let Some(first) = used.insert(canonical.clone(), *line) {
                    return Err(self.error(
                        *line,
                        format!("address {canonical} is already given on line {first}"),
                    ));
                }
            }
            address[k] = Some(canonical);
        }
        let missing: Vec<&str> = signals
            .iter()
            .zip(&address)
            .filter(|(_, a)| a.is_none())
            .map(|(s, _)| *s)
            .collect();
        if !missing.is_empty() {
            return Err(self.error(
                1,
                format!(
                    "no address for the {what}s {} (every {what} needs one; `%{kind}*` leaves it to the PLC tool)",
                    missing.join(", ")
                ),
            ));
        }
        Ok(address.into_iter().flatten().collect())
    }
}

/// A bit address `%IX<byte>.<bit>` / `%QX…` (bit 0–7) or `%I*` / `%Q*`,
/// upper case.
fn parse_address(text: &str, kind: char) -> std::result::Result<String, String> {
    let upper = text.trim().to_ascii_uppercase();
    let shape = || {
        format!("`{text}` is not a bit address: expected `%{kind}X<byte>.<bit>` (bit 0-7) or `%{kind}*`")
    };
    if upper == format!("%{kind}*") {
        return Ok(upper);
    }
    let rest = upper.strip_prefix(&format!("%{kind}X")).ok_or_else(shape)?;
    let (byte, bit) = rest.split_once('.').ok_or_else(shape)?;
    let digits = |s: &str| !s.is_empty() && s.len() <= 5 && s.bytes().all(|b| b.is_ascii_digit());
    if !digits(byte) || !digits(bit) {
        return Err(shape());
    }
    let (byte, bit): (u32, u32) = (
        byte.parse().map_err(|_| shape())?,
        bit.parse().map_err(|_| shape())?,
    );
    if bit > 7 || byte > 65_535 {
        return Err(shape());
    }
    Ok(format!("%{kind}X{byte}.{bit}"))
}

/// The program: located variables, the controller instance and the
/// clock; `ids` are its instance and clock names.
pub fn program(
    project: &Project,
    names: &Names,
    (inputs, outputs): &(Vec<String>, Vec<String>),
    ids: &[&str; 2],
) -> Pou {
    let [ctrl, clock] = *ids;
    let mut io = Vec::new();
    for (i, input) in project.inputs.iter().enumerate() {
        let mut v = Var::new(
            &names.inputs[i],
            Type::Bool,
            format!("input '{}'", comment_text(&input.name)),
        );
        v.address = Some(inputs[i].clone());
        io.push(v);
    }
    for (o, output) in project.outputs.iter().enumerate() {
        let mut v = Var::new(
            &names.outputs[o],
            Type::Bool,
            format!("output '{}'", comment_text(&output.name)),
        );
        v.address = Some(outputs[o].clone());
        io.push(v);
    }
    let locals = vec![
        Var::new(
            ctrl,
            Type::Instance(names.controller.clone()),
            "the supervisory controller",
        ),
        Var::new(
            clock,
            Type::Udint,
            format!(
                "milliseconds: one scan period ({} ms) per call",
                project.scan_period_ms
            ),
        ),
    ];
    let mut call: Vec<String> = vec![format!("NOW_MS := {clock}")];
    call.extend(names.inputs.iter().map(|n| format!("{n} := {n}")));
    let mut body = vec![
        "(* One scan per task cycle: run this program in a cyclic task whose".to_owned(),
        format!(
            "   interval is the project's scan period, {} ms. *)",
            project.scan_period_ms
        ),
        format!("{ctrl}("),
    ];
    let last = call.len() - 1;
    for (k, arg) in call.iter().enumerate() {
        body.push(format!("    {arg}{}", if k == last { ");" } else { "," }));
    }
    body.extend(names.outputs.iter().map(|n| format!("{n} := {ctrl}.{n};")));
    body.push(format!(
        "{clock} := {clock} + UDINT#{};",
        project.scan_period_ms
    ));
    let mut blocks = Vec::new();
    if !io.is_empty() {
        blocks.push(VarBlock {
            section: Section::Local,
            vars: io,
        });
    }
    blocks.push(VarBlock {
        section: Section::Local,
        vars: locals,
    });
    Pou {
        name: names.program.clone(),
        kind: PouKind::Program,
        doc: vec![format!(
            "Runs '{}' on the PLC's inputs and outputs.",
            comment_text(&project.name)
        )],
        blocks,
        body,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_addresses_are_checked_and_made_canonical() {
        assert_eq!(parse_address("%ix2.7", 'I').unwrap(), "%IX2.7");
        assert_eq!(parse_address("%I*", 'I').unwrap(), "%I*");
        for bad in [
            "%IX2.8",
            "%QX0.0",
            "%IX",
            "%IX1",
            "IX0.0",
            "%IX0.-1",
            "%IX99999999.0",
        ] {
            assert!(parse_address(bad, 'I').is_err(), "{bad}");
        }
    }
}
