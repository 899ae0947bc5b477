//! Actions: what an executed event does, in a fixed order.
//!
//! The actions of an event are applied in this order:
//! 1. clears: the `clear` list, then the outputs lowered by the `switch`
//!    entries (other positions, or every position for `off`), in the order
//!    of the entries;
//! 2. sets: the `set` list, then the outputs raised by the `switch`
//!    entries;
//! 3. timer resets (`reset` list);
//! 4. timer starts (`start` list), so `reset` and `start` of one timer
//!    restart it.
//!
//! Validation guarantees that no event raises and lowers the same output,
//! so the order of clears and sets never changes the result; it is fixed
//! for reproducible tables. An output named twice in one list acts once.
//! `set` and `clear` may not name an output of a switch or one with a
//! state map ([`super::outputs`]).

use super::super::model::Action;
use super::super::parse::{names, RawEvent};
use super::events::Env;
use super::outputs::OutputUse;
use super::{Declared, Validator};
use des::error::Result;

impl Validator<'_> {
    /// The actions of event `ev`, in application order; records the
    /// outputs it sets or clears.
    pub(super) fn actions(
        &self,
        ev: &str,
        decl: &RawEvent,
        env: &Env<'_>,
        outputs: &mut Declared<OutputUse>,
    ) -> Result<Vec<Action>> {
        let mut clears = Vec::new();
        let mut sets = Vec::new();
        for (field, list) in [("clear", &decl.clear), ("set", &decl.set)] {
            for out in names(list.as_ref()) {
                let o = self.resolve(outputs, &out)?;
                let usage = &mut outputs.items[o];
                self.not_state_mapped(usage, &out)?;
                if let Some((s, pos)) = &usage.switch {
                    let sw = &env.switches.items[*s].name;
                    return Err(self.error(
                        &out.span(),
                        format!(
                            "output `{}` is position `{pos}` of switch `{sw}`: drive it with `switch = {{ {sw} = \"{pos}\" }}`, not with `{field}`",
                            out.get_ref()
                        ),
                    ));
                }
                usage.acted_on = true;
                if field == "set" && clears.contains(&o) {
                    return Err(self.error(
                        &out.span(),
                        format!(
                            "event `{ev}` both sets and clears output `{}`",
                            out.get_ref()
                        ),
                    ));
                }
                let list = if field == "clear" {
                    &mut clears
                } else {
                    &mut sets
                };
                if !list.contains(&o) {
                    list.push(o);
                }
            }
        }
        if let Some(entries) = &decl.switch {
            for (sw_name, pos) in &entries.get_ref().0 {
                let s = self.resolve(env.switches, sw_name)?;
                let switch = &env.switches.items[s];
                let position = pos.get_ref();
                if position == "off" {
                    clears.extend(switch.positions.iter().map(|&(_, o)| o));
                    continue;
                }
                let Some(&(_, chosen)) = switch.positions.iter().find(|(p, _)| p == position)
                else {
                    let known: Vec<&str> = switch
                        .positions
                        .iter()
                        .map(|(p, _)| p.as_str())
                        .chain(["off"])
                        .collect();
                    return Err(self.error(
                        &pos.span(),
                        format!(
                            "switch `{}` has no position `{position}` (positions: {})",
                            switch.name,
                            known.join(", ")
                        ),
                    ));
                };
                clears.extend(
                    switch
                        .positions
                        .iter()
                        .filter(|&&(_, o)| o != chosen)
                        .map(|&(_, o)| o),
                );
                sets.push(chosen);
            }
        }

        let mut actions: Vec<Action> = clears.into_iter().map(Action::Clear).collect();
        actions.extend(sets.into_iter().map(Action::Set));
        for t in names(decl.reset.as_ref()) {
            actions.push(Action::Reset(self.resolve(env.timers, &t)?));
        }
        for t in names(decl.start.as_ref()) {
            actions.push(Action::Start(self.resolve(env.timers, &t)?));
        }
        Ok(actions)
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::Action;
    use super::super::testing::{load, HEAD};

    #[test]
    fn duplicate_actions_collapse() {
        let p = load(&format!(
            "{HEAD}[inputs]\nx = {{}}\n[outputs]\no = {{}}\n[events]\ne = {{ rising = \"x\", set = [\"o\", \"o\"] }}\n"
        ))
        .unwrap();
        assert_eq!(p.events[0].actions, [Action::Set(0)]);
    }

    #[test]
    fn clears_come_before_sets_and_resets_before_starts() {
        let p = load(&format!(
            "{HEAD}[inputs]\nx = {{}}\n[outputs]\na = {{}}\nb = {{}}\nhi = {{}}\nlo = {{}}\n[timers]\nt = {{ preset_ms = 5 }}\n[switches]\nlevel = {{ hi = \"hi\", lo = \"lo\" }}\n[events]\ne = {{ rising = \"x\", start = \"t\", reset = \"t\", set = \"a\", switch = {{ level = \"hi\" }}, clear = \"b\" }}\n"
        ))
        .unwrap();
        let (a, b, hi, lo) = (0, 1, 2, 3);
        assert_eq!(
            p.events[0].actions,
            [
                Action::Clear(b),
                Action::Clear(lo),
                Action::Set(a),
                Action::Set(hi),
                Action::Reset(0),
                Action::Start(0)
            ]
        );
    }
}
