//! Symbolic supervisors against the project (their guard files are read,
//! or their guards synthesised, before validation:
//! [`super::super::sources`]).
//!
//! - A symbolic supervisor is named by `name`, or else by its guard
//!   file's `name`; a synthesised one needs `name`. The name joins the
//!   shared namespace ([`super::names`]), and so does each component's,
//!   `name.component`.
//! - Each component is checked as any supervisor ([`super::supervisors`]):
//!   its events declared, controllability as its model file states it.
//! - Each guard's event is declared in `[events]` and controllable: a
//!   guard can only hold a command back.

use super::super::model::{Event, EventGuard, Guarded, Supervisor, SupervisorSource};
use super::super::parse::RawSupervisor;
use super::super::sources::{LoadedGuarded, LoadedSupervisor};
use super::{Declared, Validator};
use crate::model::GuardedSource;
use des::error::Result;
use toml::Spanned;

impl Validator<'_> {
    /// The symbolic supervisor of `raw`; its components are pushed onto
    /// `supervisors`.
    pub(super) fn guarded(
        &mut self,
        raw: &Spanned<RawSupervisor>,
        loaded: LoadedGuarded,
        events: &Declared<Event>,
        supervisors: &mut Declared<Supervisor>,
    ) -> Result<Guarded> {
        let header = raw.span();
        let LoadedGuarded {
            file,
            components,
            origins,
            source,
            span,
        } = loaded;
        let (name, name_span) =
            match (&raw.get_ref().name, &source) {
                (Some(n), _) => (n.get_ref().clone(), n.span()),
                (None, GuardedSource::File(_)) => (file.name.clone(), span.clone()),
                (None, GuardedSource::Synthesized { .. }) => return Err(self.error(
                    &header,
                    "a symbolic supervisor needs `name = \"…\"`: its components are named after it",
                )),
            };
        self.claim("supervisor", &name, &name_span)?;
        let max_logic_effort = self.max_logic_effort(raw.get_ref())?;

        let first = supervisors.items.len();
        for ((automaton, model), origin) in components.into_iter().zip(origins) {
            let component = format!("{name}.{}", automaton.name());
            self.claim("supervisor", &component, &span)?;
            let loaded = LoadedSupervisor {
                automaton,
                source: SupervisorSource::Component {
                    guarded: name.clone(),
                    file: model,
                },
                origins: vec![origin],
            };
            let sup = self.supervisor(&header, component, loaded, events, max_logic_effort)?;
            let component = sup.name.clone();
            supervisors.push(&component, header.clone(), sup);
        }

        let bits = file
            .bit_places()
            .into_iter()
            .map(|(c, shift)| (first + c, shift))
            .collect();

        let mut guards = Vec::with_capacity(file.guards.len());
        for g in &file.guards {
            let Some(&event) = events.index.get(&g.event) else {
                return Err(self.error(
                    &span,
                    format!(
                        "the guard of `{}` in symbolic supervisor `{name}`: the event is not declared in [events]",
                        g.event
                    ),
                ));
            };
            if !events.items[event].controllable {
                return Err(self.error(
                    &events.spans[event],
                    format!(
                        "event `{}` is uncontrollable here, but symbolic supervisor `{name}` guards it: a guard can only hold back a command",
                        g.event
                    ),
                ));
            }
            guards.push(EventGuard {
                event,
                text: g.text.clone(),
                root: g.root,
                nodes: g.nodes.clone(),
            });
        }
        guards.sort_by_key(|g| g.event);

        Ok(Guarded {
            name,
            components: first..supervisors.items.len(),
            bits,
            guards,
            closed_loop_states: file.supervisor_states,
            source,
            line: self.line(&header),
        })
    }
}
