//! Switches: an (n+1)-position selector, each named position raising one
//! output, `off` (implicit) lowering them all.
//!
//! A switch has at least one position; position names follow
//! [`super::names`]. Each position names a declared output without a state
//! map, and an output belongs to at most one switch position (see
//! [`super::outputs`]).

use super::super::model::Switch;
use super::super::parse::{Entries, Name};
use super::outputs::OutputUse;
use super::{Declared, Validator};
use des::error::Result;
use std::collections::HashMap;
use toml::Spanned;

impl Validator<'_> {
    /// Validates `[switches]`, recording which outputs they drive.
    pub(super) fn switches(
        &mut self,
        raw: &Entries<Entries<String>>,
        outputs: &mut Declared<OutputUse>,
    ) -> Result<Declared<Switch>> {
        let mut switches = Declared::new("switch", "switches");
        for (name, decl) in &raw.0 {
            self.claim("switch", name.get_ref(), &name.span())?;
            let switch = self.switch(&switches.items, name, decl, outputs)?;
            switches.push(name.get_ref(), name.span(), switch);
        }
        Ok(switches)
    }

    /// One switch; `done` are the switches before it.
    fn switch(
        &self,
        done: &[Switch],
        name: &Name,
        decl: &Spanned<Entries<String>>,
        outputs: &mut Declared<OutputUse>,
    ) -> Result<Switch> {
        let sw = name.get_ref();
        if decl.get_ref().0.is_empty() {
            return Err(self.error(
                &decl.span(),
                format!("switch `{sw}` needs at least one position (`off` is implicit)"),
            ));
        }
        let mut positions = Vec::new();
        let mut seen: HashMap<String, String> = HashMap::new();
        for (pos, out) in &decl.get_ref().0 {
            self.position_name(sw, pos, &mut seen)?;
            let o = self.resolve(outputs, out)?;
            let usage = &mut outputs.items[o];
            self.not_state_mapped(usage, out)?;
            if let Some((other, other_pos)) = &usage.switch {
                let whose = match done.get(*other) {
                    Some(sw) => format!("switch `{}` (line {})", sw.name, sw.line),
                    None => "this switch".to_owned(),
                };
                return Err(self.error(
                    &out.span(),
                    format!(
                        "output `{}` is already position `{other_pos}` of {whose}: an output belongs to at most one switch position",
                        out.get_ref()
                    ),
                ));
            }
            usage.switch = Some((done.len(), pos.get_ref().clone()));
            positions.push((pos.get_ref().clone(), o));
        }
        Ok(Switch {
            name: sw.clone(),
            positions,
            line: self.line(&name.span()),
        })
    }
}
