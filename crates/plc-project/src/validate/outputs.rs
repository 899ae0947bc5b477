//! Outputs: what drives each one.
//!
//! An output is driven by actions (`set`, `clear`, switch positions), by
//! a state map ([`super::state_maps`]) or by a place map (1 while a listed
//! place of a `[[net]]` holds a token), never two of these. An output
//! belongs to at
//! most one switch, and an output of a switch is driven only through that
//! switch (never by `set` or `clear`), so the switch always knows its
//! position ([`super::switches`], [`super::actions`]). An output with a
//! state map takes no `initial`. An output driven by nothing is a warning.

use super::super::model::{Drive, Net, Output, Supervisor};
use super::super::parse::{Entries, Name, RawOutput};
use super::{Declared, Validator};
use des::error::Result;
use std::ops::Range;
use toml::Spanned;

/// What validation knows of an output before the supervisors are checked.
pub(super) struct OutputUse {
    /// Span of the output's `states` table, if it has one.
    pub state_map: Option<Range<usize>>,
    /// The switch (index) and position that drive it.
    pub switch: Option<(usize, String)>,
    /// Some event sets or clears it.
    pub acted_on: bool,
}

impl Validator<'_> {
    /// Claims the output names; drives are settled by [`Self::outputs`].
    pub(super) fn declare_outputs(
        &mut self,
        raw: &Entries<RawOutput>,
    ) -> Result<Declared<OutputUse>> {
        let mut outputs = Declared::new("output", "outputs");
        for (name, decl) in &raw.0 {
            self.claim("output", name.get_ref(), &name.span())?;
            let decl = decl.get_ref();
            if let (Some(_), Some(places)) = (&decl.states, &decl.places) {
                return Err(self.error(
                    &places.span(),
                    format!(
                        "output `{}` has a state map: it is driven by states or by places, not both (output driven twice)",
                        name.get_ref()
                    ),
                ));
            }
            let map = decl.states.as_ref().or(decl.places.as_ref());
            if let (Some(_), Some(initial)) = (map, &decl.initial) {
                let (kind, follows) = match decl.states {
                    Some(_) => ("state", "the supervisor states"),
                    None => ("place", "the net's marking"),
                };
                return Err(self.error(
                    &initial.span(),
                    format!(
                        "output `{}` has a {kind} map (a Moore output): it takes no `initial`, its level follows {follows}",
                        name.get_ref()
                    ),
                ));
            }
            let usage = OutputUse {
                state_map: map.map(Spanned::span),
                switch: None,
                acted_on: false,
            };
            outputs.push(name.get_ref(), name.span(), usage);
        }
        Ok(outputs)
    }

    /// Refuses an action or switch position on `out`, written at its span,
    /// when the output has a state map.
    pub(super) fn not_state_mapped(&self, usage: &OutputUse, out: &Name) -> Result<()> {
        if usage.state_map.is_some() {
            return Err(self.error(
                &out.span(),
                format!(
                    "output `{}` has a state map: an output is driven by actions or by a state map, not both (output driven twice)",
                    out.get_ref()
                ),
            ));
        }
        Ok(())
    }

    /// The outputs with their drives, now that state maps can be resolved.
    pub(super) fn outputs(
        &mut self,
        raw: &Entries<RawOutput>,
        uses: &[OutputUse],
        supervisors: &Declared<Supervisor>,
        nets: &Declared<Net>,
    ) -> Result<Vec<Output>> {
        let mut outputs = Vec::with_capacity(uses.len());
        for ((name, decl), usage) in raw.0.iter().zip(uses) {
            let decl = decl.get_ref();
            let drive = match (&decl.states, &decl.places) {
                (Some(map), _) => Drive::States(self.state_map(name, map, supervisors)?),
                (None, Some(map)) => Drive::Places(self.place_map(name, map, nets)?),
                (None, None) => {
                    if usage.switch.is_none() && !usage.acted_on {
                        self.warn(
                            &name.span(),
                            format!(
                                "output `{}` is driven by nothing (no action, switch or state map): it stays at its initial level",
                                name.get_ref()
                            ),
                        );
                    }
                    Drive::Actions {
                        initial: decl.initial.as_ref().is_some_and(|i| *i.get_ref()),
                    }
                }
            };
            outputs.push(Output {
                name: name.get_ref().clone(),
                safe: decl.safe,
                drive,
                line: self.line(&name.span()),
            });
        }
        Ok(outputs)
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::Drive;
    use super::super::testing::{load, HEAD};

    #[test]
    fn an_output_driven_by_nothing_is_a_warning() {
        let p = load(&format!(
            "{HEAD}\n[outputs]\nspare = {{ initial = true }}\n"
        ))
        .unwrap();
        assert_eq!(p.warnings.len(), 1);
        assert_eq!(p.warnings[0].line, 5);
        assert!(p.warnings[0].message.contains("driven by nothing"));
        assert_eq!(p.outputs[0].drive, Drive::Actions { initial: true });
    }
}
