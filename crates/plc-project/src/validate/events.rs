//! Events: their sources and conditions, and what no supervisor knows.
//!
//! - A controllable event has no source (`rising`, `falling`, `expired`),
//!   no level conditions and no `origin`; only it may have a `request`.
//!   An uncontrollable event has exactly one source; `origin` defaults to
//!   `plant`.
//! - A controllable event in no supervisor's alphabet is an error (nothing
//!   could ever allow it); an uncontrollable one is always feasible and
//!   only warned about when it has no actions either. (Every event of a
//!   supervisor's alphabet must be declared, and controllability must
//!   agree with the models: [`super::supervisors`].)
//! - Several events may share a source (the same input edge or timer
//!   expiry) with different `when`/`unless` conditions.
//! - A timer whose expiry an event observes but that no action starts is a
//!   warning (the event can never occur). An input in both `when` and
//!   `unless` of one event is a warning too.
//!
//! What an event does is checked in [`super::actions`].

use super::super::model::{Action, Event, Input, Net, Origin, Supervisor, Switch, Timer, Trigger};
use super::super::parse::{names, Entries, Name, Names, RawEvent};
use super::outputs::OutputUse;
use super::{Declared, Validator};
use des::error::Result;
use std::ops::Range;
use toml::Spanned;

/// The declarations an event's bindings and actions resolve against
/// (besides the outputs, whose use events record).
pub(super) struct Env<'a> {
    pub inputs: &'a Declared<Input>,
    pub timers: &'a Declared<Timer>,
    pub switches: &'a Declared<Switch>,
}

impl Validator<'_> {
    /// Validates `[events]`, recording which outputs they act on.
    pub(super) fn events(
        &mut self,
        raw: &Entries<RawEvent>,
        env: &Env<'_>,
        outputs: &mut Declared<OutputUse>,
    ) -> Result<Declared<Event>> {
        let mut events = Declared::new("event", "events");
        for (name, decl) in &raw.0 {
            self.claim("event", name.get_ref(), &name.span())?;
            let event = self.event(name, decl.get_ref(), env, outputs)?;
            events.push(name.get_ref(), name.span(), event);
        }
        Ok(events)
    }

    fn event(
        &mut self,
        name: &Name,
        decl: &RawEvent,
        env: &Env<'_>,
        outputs: &mut Declared<OutputUse>,
    ) -> Result<Event> {
        let ev = name.get_ref();
        let controllable = decl.controllable.as_ref().is_some_and(|c| *c.get_ref());
        let (trigger, origin) = if controllable {
            self.command(ev, decl)?
        } else {
            self.source(name, decl, env)?
        };

        let when = self.inputs_of(&decl.when, env)?;
        let unless = self.inputs_of(&decl.unless, env)?;
        for input in names(decl.unless.as_ref()) {
            if when.contains(&self.resolve(env.inputs, &input)?) {
                self.warn(
                    &input.span(),
                    format!(
                        "input `{}` is in both `when` and `unless` of event `{ev}`: the event can never occur",
                        input.get_ref()
                    ),
                );
            }
        }
        let request = match &decl.request {
            None => None,
            Some(r) => Some(self.resolve(env.inputs, r)?),
        };
        let actions = self.actions(ev, decl, env, outputs)?;

        Ok(Event {
            name: ev.clone(),
            controllable,
            origin,
            trigger,
            when,
            unless,
            request,
            actions,
            line: self.line(&name.span()),
        })
    }

    /// The inputs a list field names.
    fn inputs_of(&self, field: &Option<Spanned<Names>>, env: &Env<'_>) -> Result<Vec<usize>> {
        names(field.as_ref())
            .iter()
            .map(|n| self.resolve(env.inputs, n))
            .collect()
    }

    /// A controllable event: the controller chooses it, so it is bound to
    /// nothing.
    fn command(&self, ev: &str, decl: &RawEvent) -> Result<(Trigger, Origin)> {
        let forbidden: [(&str, Option<Range<usize>>); 6] = [
            ("rising", decl.rising.as_ref().map(Spanned::span)),
            ("falling", decl.falling.as_ref().map(Spanned::span)),
            ("expired", decl.expired.as_ref().map(Spanned::span)),
            ("when", decl.when.as_ref().map(Spanned::span)),
            ("unless", decl.unless.as_ref().map(Spanned::span)),
            ("origin", decl.origin.as_ref().map(Spanned::span)),
        ];
        if let Some((field, Some(span))) = forbidden.iter().find(|(_, s)| s.is_some()) {
            let why = if *field == "origin" {
                "the origin of a controllable event is the controller"
            } else {
                "the controller chooses controllable events; only uncontrollable events are bound to inputs, timers and level conditions"
            };
            return Err(self.error(
                span,
                format!("controllable event `{ev}` cannot have `{field}`: {why}"),
            ));
        }
        Ok((Trigger::Command, Origin::Controller))
    }

    /// The one source and the origin of an uncontrollable event.
    fn source(&self, name: &Name, decl: &RawEvent, env: &Env<'_>) -> Result<(Trigger, Origin)> {
        let ev = name.get_ref();
        if let Some(r) = &decl.request {
            return Err(self.error(
                &r.span(),
                format!(
                    "uncontrollable event `{ev}` cannot have `request`: request inputs (manual mode) are only for controllable events"
                ),
            ));
        }
        let sources: Vec<(&str, Range<usize>)> = [
            ("rising", decl.rising.as_ref().map(Spanned::span)),
            ("falling", decl.falling.as_ref().map(Spanned::span)),
            ("expired", decl.expired.as_ref().map(Spanned::span)),
        ]
        .into_iter()
        .filter_map(|(f, s)| s.map(|s| (f, s)))
        .collect();
        match sources.as_slice() {
            [] => {
                return Err(self.error(
                    &name.span(),
                    format!(
                        "uncontrollable event `{ev}` needs a source: exactly one of `rising`, `falling` or `expired` (or `controllable = true`)"
                    ),
                ))
            }
            [(first, _), (second, span), ..] => {
                return Err(self.error(
                    span,
                    format!(
                        "uncontrollable event `{ev}` has both `{first}` and `{second}`: it needs exactly one source"
                    ),
                ))
            }
            [_] => {}
        }
        let edge = |field: &Option<Spanned<Names>>, which: &str| -> Result<Vec<usize>> {
            let list = self.inputs_of(field, env)?;
            match field {
                Some(f) if list.is_empty() => Err(self.error(
                    &f.span(),
                    format!("`{which}` of event `{ev}` names no input"),
                )),
                _ => Ok(list),
            }
        };
        let trigger = if decl.rising.is_some() {
            Trigger::Rising(edge(&decl.rising, "rising")?)
        } else if decl.falling.is_some() {
            Trigger::Falling(edge(&decl.falling, "falling")?)
        } else {
            let t = decl.expired.as_ref().expect("one source");
            Trigger::Expired(self.resolve(env.timers, t)?)
        };
        let origin = match &decl.origin {
            None => Origin::Plant,
            Some(o) => match o.get_ref().as_str() {
                "plant" => Origin::Plant,
                "operator" => Origin::Operator,
                other => {
                    return Err(self.error(
                        &o.span(),
                        format!("origin must be \"operator\" or \"plant\", found {other:?}"),
                    ))
                }
            },
        };
        Ok((trigger, origin))
    }

    /// Events in no supervisor's alphabet: an error if controllable, a
    /// warning if they do nothing either.
    pub(super) fn events_no_supervisor_knows(
        &mut self,
        events: &Declared<Event>,
        supervisors: &[Supervisor],
        nets: &[Net],
    ) -> Result<()> {
        let mut in_alphabet = vec![false; events.items.len()];
        for sup in supervisors {
            for &(g, _) in &sup.local_events {
                in_alphabet[g] = true;
            }
        }
        for net in nets {
            for &g in &net.events {
                in_alphabet[g] = true;
            }
        }
        for (e, event) in events.items.iter().enumerate() {
            if in_alphabet[e] {
                continue;
            }
            if event.controllable {
                return Err(self.error(
                    &events.spans[e],
                    format!(
                        "controllable event `{}` is in no supervisor's alphabet (controllable event in no alphabet): no supervisor could ever allow it",
                        event.name
                    ),
                ));
            }
            if event.actions.is_empty() {
                self.warn(
                    &events.spans[e],
                    format!(
                        "uncontrollable event `{}` is in no supervisor's alphabet and has no actions: it executes, moves nothing and does nothing",
                        event.name
                    ),
                );
            }
        }
        Ok(())
    }

    /// Warns about timers whose expiry some event observes but that no
    /// action starts.
    pub(super) fn timers_nothing_starts(&mut self, timers: &Declared<Timer>, events: &[Event]) {
        let mut started = vec![false; timers.items.len()];
        let mut first_observer: Vec<Option<usize>> = vec![None; timers.items.len()];
        for (e, event) in events.iter().enumerate() {
            for action in &event.actions {
                if let Action::Start(t) = action {
                    started[*t] = true;
                }
            }
            if let Trigger::Expired(t) = event.trigger {
                first_observer[t].get_or_insert(e);
            }
        }
        for (t, observer) in first_observer.into_iter().enumerate() {
            if let (Some(e), false) = (observer, started[t]) {
                self.warn(
                    &timers.spans[t],
                    format!(
                        "timer `{}` is never started by any action, so event `{}` (line {}) can never occur",
                        timers.items[t].name, events[e].name, events[e].line
                    ),
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::Trigger;
    use super::super::testing::{load, HEAD};

    #[test]
    fn an_input_both_required_and_forbidden_is_a_warning() {
        let p = load(&format!(
            "{HEAD}[inputs]\na = {{}}\nb = {{}}\n[outputs]\no = {{}}\n[events]\ne = {{ rising = \"a\", when = [\"b\"],\n  unless = [\"b\"], set = [\"o\"] }}\n"
        ))
        .unwrap();
        assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
        assert_eq!(p.warnings[0].line, 10);
        assert!(p.warnings[0].message.contains("can never occur"));
    }

    #[test]
    fn several_events_may_share_a_source() {
        let p = load(&format!(
            "{HEAD}[inputs]\nx = {{}}\nmode = {{}}\n[outputs]\no = {{}}\n[timers]\nt = {{ preset_ms = 5 }}\n[events]\nstart = {{ rising = \"x\", start = [\"t\"] }}\nlate = {{ expired = \"t\", when = [\"mode\"], set = \"o\" }}\nearly = {{ expired = \"t\", unless = [\"mode\"], clear = \"o\" }}\n"
        ))
        .unwrap();
        assert_eq!(p.events[1].trigger, Trigger::Expired(0));
        assert_eq!(p.events[2].trigger, Trigger::Expired(0));
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    }

    #[test]
    fn a_timer_nothing_starts_is_a_warning_at_the_timer() {
        let p = load(&format!(
            "{HEAD}[inputs]\nx = {{}}\n[outputs]\no = {{}}\n[timers]\nt = {{ preset_ms = 5 }}\n[events]\non = {{ rising = \"x\", reset = \"t\" }}\nlate = {{ expired = \"t\", set = \"o\" }}\nlater = {{ expired = \"t\", clear = \"o\" }}\n"
        ))
        .unwrap();
        assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
        assert_eq!(p.warnings[0].line, 8);
        assert_eq!(
            p.warnings[0].message,
            "timer `t` is never started by any action, so event `late` (line 11) can never occur"
        );
    }
}
