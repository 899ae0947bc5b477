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
//! - A supervisor the executor runs moves on observable events only. An
//!   event a model of a synthesised supervisor declares unobservable may
//!   not be declared in `[events]` (the controller cannot see it: no
//!   input edge, no command); synthesis runs the projected supervisor.

use super::super::model::{Event, Guarded, Supervisor, SupervisorSource};
use super::super::parse::RawSupervisor;
use super::super::sources::{LoadedEntry, LoadedSupervisor};
use super::{Declared, Validator};
use des::automaton::EventId;
use des::error::Result;
use std::ops::Range;
use toml::Spanned;

impl Validator<'_> {
    /// Checks every `[[supervisor]]` (`raw`) and what it loaded (`loaded`,
    /// one per entry) against the events: the supervisors (a symbolic
    /// supervisor's components among them) and the symbolic supervisors.
    pub(super) fn supervisors(
        &mut self,
        raw: &[Spanned<RawSupervisor>],
        loaded: Vec<LoadedEntry>,
        events: &Declared<Event>,
    ) -> Result<(Declared<Supervisor>, Vec<Guarded>)> {
        let mut supervisors = Declared::new("supervisor", "[supervisor]");
        let mut guarded = Vec::new();
        for (raw, loaded) in raw.iter().zip(loaded) {
            match loaded {
                LoadedEntry::Automaton(loaded) => {
                    let header = raw.span();
                    let (name, name_span) = match &raw.get_ref().name {
                        Some(n) => (n.get_ref().clone(), n.span()),
                        None => (loaded.automaton.name().to_owned(), header.clone()),
                    };
                    self.claim("supervisor", &name, &name_span)?;
                    let max_logic_effort = self.max_logic_effort(raw.get_ref())?;
                    let sup = self.supervisor(&header, name, loaded, events, max_logic_effort)?;
                    let name = sup.name.clone();
                    supervisors.push(&name, header, sup);
                }
                LoadedEntry::Guarded(loaded) => {
                    let g = self.guarded(raw, loaded, events, &mut supervisors)?;
                    guarded.push(g);
                }
                LoadedEntry::Reduced(controllers, plant) => {
                    let header = raw.span();
                    let (name, name_span) = match (&raw.get_ref().name, controllers.first()) {
                        (Some(n), _) => (n.get_ref().clone(), n.span()),
                        (None, Some((None, loaded))) => {
                            (loaded.automaton.name().to_owned(), header.clone())
                        }
                        (None, _) => {
                            return Err(self.error(
                                &header,
                                "a localized supervisor needs `name = \"…\"`: its local controllers are named after it",
                            ))
                        }
                    };
                    self.claim("supervisor", &name, &name_span)?;
                    let max_logic_effort = self.max_logic_effort(raw.get_ref())?;
                    let components: Vec<String> =
                        plant.iter().map(|(a, _)| a.name().to_owned()).collect();
                    for (automaton, origin) in plant {
                        let component = format!("{name}.{}", automaton.name());
                        self.claim("supervisor", &component, &header)?;
                        let loaded = LoadedSupervisor {
                            automaton,
                            source: SupervisorSource::Plant {
                                reduced: name.clone(),
                                file: origin.file.clone(),
                            },
                            origins: vec![origin],
                        };
                        let sup =
                            self.supervisor(&header, component, loaded, events, max_logic_effort)?;
                        let component = sup.name.clone();
                        supervisors.push(&component, header.clone(), sup);
                    }
                    for (event, loaded) in controllers {
                        let local = match event {
                            Some(event) => {
                                // A plant component named like the event
                                // (the boiler's `bms`) keeps `name.bms`.
                                let local = if components.contains(&event) {
                                    format!("{name}.{event}.local")
                                } else {
                                    format!("{name}.{event}")
                                };
                                self.claim("supervisor", &local, &header)?;
                                local
                            }
                            None => name.clone(),
                        };
                        let sup =
                            self.supervisor(&header, local, loaded, events, max_logic_effort)?;
                        let local = sup.name.clone();
                        supervisors.push(&local, header.clone(), sup);
                    }
                }
            }
        }
        Ok((supervisors, guarded))
    }

    /// `max_logic_effort` of an entry, positive when given.
    pub(super) fn max_logic_effort(&self, sup: &RawSupervisor) -> Result<Option<u64>> {
        match &sup.max_logic_effort {
            None => Ok(None),
            Some(n) if *n.get_ref() > 0 => Ok(Some(*n.get_ref())),
            Some(n) => Err(self.error(&n.span(), "max_logic_effort must be a positive number")),
        }
    }

    /// One supervisor, named `name` (already claimed), declared at
    /// `header`.
    pub(super) fn supervisor(
        &mut self,
        header: &Range<usize>,
        name: String,
        loaded: LoadedSupervisor,
        events: &Declared<Event>,
        max_logic_effort: Option<u64>,
    ) -> Result<Supervisor> {
        let header = header.clone();
        let LoadedSupervisor {
            automaton,
            source,
            origins,
        } = loaded;
        let described = match &source {
            SupervisorSource::File(p) => format!("supervisor `{name}` (`{}`)", p.display()),
            SupervisorSource::Synthesized { .. } => format!("synthesised supervisor `{name}`"),
            SupervisorSource::Plant { reduced, file } => format!(
                "plant component `{name}` of reduced supervisor `{reduced}` (`{}`)",
                file.display()
            ),
            SupervisorSource::Component { guarded, file } => format!(
                "component `{name}` of symbolic supervisor `{guarded}` (`{}`)",
                file.display()
            ),
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
                    SupervisorSource::File(_)
                    | SupervisorSource::Component { .. }
                    | SupervisorSource::Plant { .. } => None,
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
            if !e.observable {
                let synthesized = matches!(source, SupervisorSource::Synthesized { .. });
                let whose = origins
                    .iter()
                    .filter(|_| synthesized)
                    .find(|o| {
                        o.alphabet
                            .id(&e.name)
                            .is_some_and(|id| !o.alphabet.is_observable(id))
                    })
                    .map(|o| format!(" (unobservable in `{}`, `{}`)", o.name, o.file.display()))
                    .unwrap_or_default();
                return Err(self.error(
                    &header,
                    format!(
                        "event `{}` of {described}{whose} is unobservable: the executor sees only \
                         the events it detects, so a supervisor it runs may not move on one \
                         (project the supervisor onto its observable events first)",
                        e.name
                    ),
                ));
            }
            local_events.push((g, id));
        }
        local_events.sort_by_key(|&(g, _)| g);

        // What the models say the controller cannot see, it may not declare.
        if matches!(source, SupervisorSource::Synthesized { .. }) {
            for o in &origins {
                for (_, e) in o.alphabet.unobservable() {
                    let Some(&g) = events.index.get(&e.name) else {
                        continue;
                    };
                    return Err(self.error(
                        &events.spans[g],
                        format!(
                            "event `{}` is unobservable in `{}` (`{}`), a model of {described}: \
                             the controller cannot see it, so it is no input edge and no \
                             command; remove it from [events] (the supervisor runs on the \
                             events the controller sees)",
                            e.name,
                            o.name,
                            o.file.display()
                        ),
                    ));
                }
            }
        }

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
                        SupervisorSource::File(_)
                        | SupervisorSource::Component { .. }
                        | SupervisorSource::Plant { .. } => described.clone(),
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
