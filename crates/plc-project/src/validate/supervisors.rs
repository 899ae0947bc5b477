//! Supervisors against the declared events (their automata are read or
//! synthesised before validation: [`super::super::sources`]).
//!
//! - A supervisor is named by `name`, or else by its automaton; the name
//!   joins the shared namespace ([`super::names`]).
//! - Its automaton has states and an initial state.
//! - Every event of its alphabet must be declared in `[events]`.
//! - Controllability must agree with every automaton that has the event
//!   and states controllability (for a synthesised supervisor: every plant
//!   and specification file it was synthesised from).

use super::super::model::{Event, Supervisor, SupervisorSource};
use super::super::parse::RawSupervisor;
use super::super::sources::LoadedSupervisor;
use super::{Declared, Validator};
use des::automaton::EventId;
use des::error::Result;
use toml::Spanned;

impl Validator<'_> {
    /// Checks every `[[supervisor]]` (`raw`) and its automaton (`loaded`,
    /// one per supervisor) against the events.
    pub(super) fn supervisors(
        &mut self,
        raw: &[Spanned<RawSupervisor>],
        loaded: Vec<LoadedSupervisor>,
        events: &Declared<Event>,
    ) -> Result<Declared<Supervisor>> {
        let mut supervisors = Declared::new("supervisor", "[supervisor]");
        for (raw, loaded) in raw.iter().zip(loaded) {
            let sup = self.supervisor(raw, loaded, events)?;
            let name = sup.name.clone();
            supervisors.push(&name, raw.span(), sup);
        }
        Ok(supervisors)
    }

    fn supervisor(
        &mut self,
        sup: &Spanned<RawSupervisor>,
        loaded: LoadedSupervisor,
        events: &Declared<Event>,
    ) -> Result<Supervisor> {
        let header = sup.span();
        let LoadedSupervisor {
            automaton,
            source,
            origins,
        } = loaded;
        let (name, name_span) = match &sup.get_ref().name {
            Some(n) => (n.get_ref().clone(), n.span()),
            None => (automaton.name().to_owned(), header.clone()),
        };
        self.claim("supervisor", &name, &name_span)?;
        let described = match &source {
            SupervisorSource::File(p) => format!("supervisor `{name}` (`{}`)", p.display()),
            SupervisorSource::Synthesized { .. } => format!("synthesised supervisor `{name}`"),
        };
        if automaton.is_empty() {
            return Err(self.error(&header, format!("{described} has no states")));
        }
        if automaton.initial().is_none() {
            return Err(self.error(&header, format!("{described} has no initial state")));
        }

        let alphabet = automaton.alphabet();
        let mut local_events: Vec<(usize, EventId)> = Vec::with_capacity(alphabet.len());
        for (id, e) in alphabet.iter() {
            let Some(&g) = events.index.get(&e.name) else {
                let whose = match source {
                    SupervisorSource::File(_) => None,
                    SupervisorSource::Synthesized { .. } => {
                        origins.iter().find(|o| o.alphabet.contains(&e.name))
                    }
                }
                .map(|o| format!(" (from `{}` in `{}`)", o.name, o.file.display()))
                .unwrap_or_default();
                return Err(self.error(
                    &header,
                    format!(
                        "event `{}` of {described}{whose} is not declared in [events]",
                        e.name
                    ),
                ));
            };
            local_events.push((g, id));
        }
        local_events.sort_by_key(|&(g, _)| g);

        // Controllability against every source that states it.
        for &(g, _) in &local_events {
            let event = &events.items[g];
            for o in origins
                .iter()
                .filter(|o| o.alphabet.controllability_stated())
            {
                let Some(id) = o.alphabet.id(&event.name) else {
                    continue;
                };
                let theirs = o.alphabet.is_controllable(id);
                if theirs != event.controllable {
                    let word = |c: bool| if c { "controllable" } else { "uncontrollable" };
                    let model = match source {
                        SupervisorSource::File(_) => described.clone(),
                        SupervisorSource::Synthesized { .. } => format!(
                            "`{}` (`{}`), a model of {described}",
                            o.name,
                            o.file.display()
                        ),
                    };
                    return Err(self.error(
                        &events.spans[g],
                        format!(
                            "event `{}` is {} here but {} in {model}",
                            event.name,
                            word(event.controllable),
                            word(theirs),
                        ),
                    ));
                }
            }
        }

        let max_logic_effort = match &sup.get_ref().max_logic_effort {
            None => None,
            Some(n) if *n.get_ref() > 0 => Some(*n.get_ref()),
            Some(n) => {
                return Err(self.error(&n.span(), "max_logic_effort must be a positive number"))
            }
        };
        Ok(Supervisor {
            name,
            automaton,
            local_events,
            source,
            line: self.line(&header),
            max_logic_effort,
        })
    }
}
