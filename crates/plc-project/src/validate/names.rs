//! Names and generated identifiers.
//!
//! Inputs, outputs, timers, switches, events and supervisors share **one
//! namespace**: every name is sanitised with [`sanitize`], and no two
//! names of any of these kinds may give the same identifier (`valve-1` and
//! `valve_1` collide, and so do an input `part` and an event `part`). This
//! is stricter than the Rust emitter needs (it puts each kind in its own
//! module) but keeps every backend free to use one flat namespace (ST
//! globals, DOT nodes, trace columns), where an input and an event of the
//! same name would clash. A name without an ASCII letter or digit (`""`,
//! `"***"`) is not a valid identifier.
//!
//! Switch positions are checked within their switch: each is a valid
//! identifier, no two collide, and none may sanitise to `OFF`, the
//! implicit position. State names and the project name are not
//! identifiers (the emitter writes them as escaped string literals).
//!
//! A net `name` also reserves the names of its groups, `name.1`, `name.2`,
//! … (identifiers `NAME_1`, `NAME_2`, …): lowering packs a net into as
//! many executor supervisors as its counters need, each named so when
//! there is more than one, so every such name is kept free whatever the
//! count.

use super::super::ident::sanitize;
use super::super::parse::Name;
use super::Validator;
use des::error::Result;
use std::collections::HashMap;
use std::ops::Range;

/// Identifiers the generated code declares next to the names of each kind
/// (`input::COUNT`, `input::NAMES`, …).
pub(crate) const RESERVED: &[&str] = &["COUNT", "NAMES"];

/// The most names of one kind (inputs, events, …): the executor's
/// indices are 16 bits.
pub(crate) const MAX_PER_KIND: usize = u16::MAX as usize;

/// A name declared in the shared namespace (or a net's, for its groups).
pub(super) struct Claim {
    kind: &'static str,
    name: String,
    line: u32,
}

impl Validator<'_> {
    /// Enters `name` into the shared namespace.
    pub(super) fn claim(
        &mut self,
        kind: &'static str,
        name: &str,
        span: &Range<usize>,
    ) -> Result<()> {
        let Some(ident) = sanitize(name) else {
            return Err(self.error(
                span,
                format!(
                    "{kind} name `{name}` is not a valid identifier: it needs at least one ASCII letter or digit"
                ),
            ));
        };
        // Each kind's module also holds these generated items.
        if RESERVED.contains(&ident.as_str()) {
            return Err(self.error(
                span,
                format!(
                    "{kind} name `{name}` becomes the identifier `{ident}`, which generated code reserves (next to {}); rename it",
                    RESERVED.join(", ")
                ),
            ));
        }
        if let Some(net) = self
            .groups
            .iter()
            .find(|net| is_group_of(&ident, &net.name))
        {
            return Err(self.error(
                span,
                format!(
                    "{kind} name `{name}` becomes the identifier `{ident}`, which net `{n}` (line {}) reserves for its groups (`{n}.1`, `{n}.2`, …); rename one",
                    net.line,
                    n = net.name
                ),
            ));
        }
        if kind == "net" {
            if let Some(c) = self
                .namespace
                .iter()
                .find_map(|(id, c)| is_group_of(id, name).then_some(c))
            {
                return Err(self.error(
                    span,
                    format!(
                        "net `{name}` reserves `{name}.1`, `{name}.2`, … for its groups, and {} `{}` (line {}) becomes one of their identifiers; rename one",
                        c.kind, c.name, c.line
                    ),
                ));
            }
        }
        if let Some(c) = self.namespace.get(&ident) {
            let message = if c.name == name && c.kind == kind {
                format!(
                    "{kind} name `{name}` is already used at line {}; {kind} names must be unique",
                    c.line
                )
            } else if c.name == name {
                format!(
                    "`{name}` names both the {} at line {} and this {kind}; inputs, outputs, timers, switches, events and supervisors share one namespace",
                    c.kind, c.line
                )
            } else {
                format!(
                    "{kind} `{name}` and {} `{}` (line {}) both become the identifier `{ident}` in generated code; rename one",
                    c.kind, c.name, c.line
                )
            };
            return Err(self.error(span, message));
        }
        let claimed = self.claimed.entry(kind).or_default();
        *claimed += 1;
        if *claimed > MAX_PER_KIND {
            return Err(self.error(
                span,
                format!(
                    "more than {MAX_PER_KIND} {kind}s: the executor numbers each kind with 16 bits"
                ),
            ));
        }
        let line = self.line(span);
        if kind == "net" {
            self.groups.push(Claim {
                kind,
                name: name.to_owned(),
                line,
            });
        }
        self.namespace.insert(
            ident,
            Claim {
                kind,
                name: name.to_owned(),
                line,
            },
        );
        Ok(())
    }

    /// Checks the name of position `pos` of switch `switch`; `seen` maps
    /// the identifiers of its earlier positions to their names.
    pub(super) fn position_name(
        &self,
        switch: &str,
        pos: &Name,
        seen: &mut HashMap<String, String>,
    ) -> Result<()> {
        let ident = sanitize(pos.get_ref()).ok_or_else(|| {
            self.error(
                &pos.span(),
                format!(
                    "position name `{}` of switch `{switch}` is not a valid identifier: it needs at least one ASCII letter or digit",
                    pos.get_ref()
                ),
            )
        })?;
        if ident == "OFF" {
            return Err(self.error(
                &pos.span(),
                format!(
                    "switch `{switch}` declares position `{}`: `off` is implicit (it lowers every position) and may not be declared",
                    pos.get_ref()
                ),
            ));
        }
        if let Some(other) = seen.insert(ident.clone(), pos.get_ref().clone()) {
            return Err(self.error(
                &pos.span(),
                format!(
                    "positions `{other}` and `{}` of switch `{switch}` both become the identifier `{ident}`; rename one",
                    pos.get_ref()
                ),
            ));
        }
        Ok(())
    }
}

/// Whether `ident` is the identifier of a group of net `net`
/// (`net.1`, `net.2`, …: `NET_1`, `NET_2`, …).
fn is_group_of(ident: &str, net: &str) -> bool {
    let Some(net) = sanitize(net) else {
        return false;
    };
    ident
        .strip_prefix(net.as_str())
        .and_then(|rest| rest.strip_prefix('_'))
        .is_some_and(|k| {
            !k.is_empty() && !k.starts_with('0') && k.bytes().all(|b| b.is_ascii_digit())
        })
}

#[cfg(test)]
mod tests {
    use super::super::testing::{load, HEAD};

    #[test]
    fn switches_share_the_namespace() {
        let err = load(&format!(
            "{HEAD}[outputs]\nvalve = {{}}\n[switches]\nVALVE = {{ on = \"valve\" }}\n"
        ))
        .unwrap_err()
        .to_string();
        assert!(
            err.starts_with("dir/p.plc.toml:6:1: switch `VALVE` and output `valve` (line 4)"),
            "{err}"
        );
    }

    #[test]
    fn a_net_reserves_its_group_names() {
        use super::is_group_of;
        assert!(is_group_of("CELL_1", "cell"));
        assert!(is_group_of("CELL_12", "cell"));
        assert!(!is_group_of("CELL_0", "cell"));
        assert!(!is_group_of("CELL_01", "cell"));
        assert!(!is_group_of("CELL_", "cell"));
        assert!(!is_group_of("CELL", "cell"));
        assert!(!is_group_of("CELL_1A", "cell"));
        assert!(is_group_of("_2ND_NET_3", "2nd net"));
    }
}
