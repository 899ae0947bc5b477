//! Linear marking constraints `L·m ≤ b`, the input of place-invariant
//! synthesis ([`super::synth`]).
//!
//! ```toml
//! [[constraint]]
//! name = "one mixer on the supply"   # also the control place's name
//! weights = { m3 = 1 }                # place = integer weight (may be negative)
//! bound = 1
//! ```
//!
//! Places are named by id, or by name where exactly one place has it. A
//! constraint with no weight, an unknown or ambiguous place, a place
//! weighed twice (once by id and once by name: summing the two would
//! hide a slip, and a cancelling pair would weigh nothing), or a name
//! used twice is refused at its file, line and column.
//!
//! Weights and the bound are TOML integers (`i64`). The arithmetic on
//! them is exact: `L·m` is computed in `i128` ([`Constraint::weighted`]),
//! and what synthesis derives from it is checked against the limits of a
//! net (arc weights and tokens of at most 2^32 − 1) before it is used.

use super::PetriNet;
use crate::error::{Error, Location, Result};
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// One constraint `Σ weights[p]·m[p] ≤ bound`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Constraint {
    /// Its name (unique in the file).
    pub name: String,
    /// `L`: (place index, weight ≠ 0), in file order.
    pub weights: Vec<(usize, i64)>,
    /// `b`.
    pub bound: i64,
    /// Where it is declared.
    pub location: Location,
}

impl Constraint {
    /// `L·m`, exactly: each term is below 2^95 in magnitude (an `i64`
    /// weight times a `u32` count) and a constraint weighs each place once,
    /// so the sum stays far inside `i128` for any net that fits in memory.
    pub fn weighted(&self, m: &[u32]) -> i128 {
        self.weights
            .iter()
            .map(|&(p, w)| i128::from(w) * i128::from(m[p]))
            .sum()
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    #[serde(default)]
    constraint: Vec<Spanned<RawConstraint>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConstraint {
    name: String,
    weights: toml::Table,
    bound: i64,
}

/// Reads the constraints file at `path` against `net`'s places.
pub fn read_file(path: &Path, net: &PetriNet) -> Result<Vec<Constraint>> {
    let text = crate::formats::read_model_text(path)?;
    read(&text, path, net)
}

/// Parses constraints over `net`'s places; `origin` names the file.
pub fn read(text: &str, origin: &Path, net: &PetriNet) -> Result<Vec<Constraint>> {
    let at = |offset: usize| Location::at_offset(origin, text, offset);
    let file: File = crate::formats::toml::parse(text, origin)?;
    let mut out: Vec<Constraint> = Vec::new();
    for raw in &file.constraint {
        let location = at(raw.span().start);
        let c = raw.get_ref();
        if let Some(first) = out.iter().find(|o| o.name == c.name) {
            return Err(Error::model(
                location,
                format!(
                    "constraint `{}` is already declared at line {}",
                    c.name, first.location.line
                ),
            ));
        }
        let mut weights = Vec::new();
        let mut named: Vec<(usize, &str)> = Vec::new();
        for (place, weight) in &c.weights {
            let p = place_index(net, place).map_err(|m| Error::model(location.clone(), m))?;
            if let Some(&(_, first)) = named.iter().find(|&&(q, _)| q == p) {
                return Err(Error::model(
                    location,
                    format!(
                        "constraint `{}` weighs place `{}` twice (as `{first}` and as `{place}`): \
                         give it one weight",
                        c.name,
                        net.places()[p].id
                    ),
                ));
            }
            named.push((p, place));
            let w = weight.as_integer().ok_or_else(|| {
                Error::model(
                    location.clone(),
                    format!(
                        "constraint `{}`: the weight of `{place}` must be an integer",
                        c.name
                    ),
                )
            })?;
            if w != 0 {
                weights.push((p, w));
            }
        }
        if weights.is_empty() {
            return Err(Error::model(
                location,
                format!("constraint `{}` weighs no place", c.name),
            ));
        }
        out.push(Constraint {
            name: c.name.clone(),
            weights,
            bound: c.bound,
            location,
        });
    }
    if out.is_empty() {
        return Err(Error::model(
            Location::file(origin),
            "no [[constraint]]: nothing to enforce",
        ));
    }
    Ok(out)
}

/// The place `key` names: its id, or else its name when one place alone
/// has it.
fn place_index(net: &PetriNet, key: &str) -> std::result::Result<usize, String> {
    if let Some(p) = net.place(key) {
        return Ok(p);
    }
    let named: Vec<usize> = (0..net.places().len())
        .filter(|&p| net.places()[p].name.as_deref() == Some(key))
        .collect();
    match named[..] {
        [p] => Ok(p),
        [] => Err(format!("`{key}` is no place of net `{}`", net.name())),
        _ => Err(format!(
            "`{key}` names {} places of net `{}`: use the id",
            named.len(),
            net.name()
        )),
    }
}
