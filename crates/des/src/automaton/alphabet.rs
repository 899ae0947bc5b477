//! Event alphabets: interned event names with their controllability and
//! observability.

use rustc_hash::FxHashMap;
use std::fmt;

/// Index of an event in one automaton's [`Alphabet`] (dense, from 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct EventId(pub u32);

impl EventId {
    /// The index as `usize`.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for EventId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

/// One event: its name, whether the controller may disable it, and
/// whether the controller sees it.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Event {
    /// The event's name, free text.
    pub name: String,
    /// `true` for Σc (the controller may disable it), `false` for Σu.
    pub controllable: bool,
    /// `true` for Σo (the controller sees it occur, the default), `false`
    /// for an unobservable event.
    pub observable: bool,
}

/// The same event name was declared controllable in one place and
/// uncontrollable in another.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("event `{name}` is declared both controllable and uncontrollable")]
pub struct ControllabilityConflict {
    /// The event.
    pub name: String,
}

/// An ordered set of events with name lookup.
///
/// Event ids are positions in insertion order, so an alphabet built in the
/// same order always numbers its events the same way.
///
/// Some files do not state controllability at all (a plain libFAUDES
/// generator, typically a specification). Their alphabet is marked
/// *unstated*: its events read as uncontrollable, and when it is combined
/// with alphabets that do state controllability, theirs wins without a
/// conflict.
///
/// Events are observable unless a source says otherwise; an event one
/// source declares unobservable is unobservable wherever alphabets meet
/// (insertion and union): a file that does not mention observability
/// makes no claim to overrule it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Alphabet {
    events: Vec<Event>,
    by_name: FxHashMap<String, EventId>,
    stated: bool,
}

impl Default for Alphabet {
    fn default() -> Self {
        Alphabet {
            events: Vec::new(),
            by_name: FxHashMap::default(),
            stated: true,
        }
    }
}

impl Alphabet {
    /// An empty alphabet (controllability stated).
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether the source stated the events' controllability (see the type
    /// docs).
    pub fn controllability_stated(&self) -> bool {
        self.stated
    }

    /// Records whether the source stated controllability.
    pub fn set_controllability_stated(&mut self, stated: bool) {
        self.stated = stated;
    }

    /// Number of events.
    #[inline]
    pub fn len(&self) -> usize {
        self.events.len()
    }

    /// `true` when there are no events.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    /// Adds `name` (or finds it) and returns its id; the controllability
    /// must agree with an earlier declaration of the same name. A new
    /// event is observable.
    pub fn insert(
        &mut self,
        name: &str,
        controllable: bool,
    ) -> Result<EventId, ControllabilityConflict> {
        if let Some(&id) = self.by_name.get(name) {
            if self.events[id.index()].controllable != controllable {
                return Err(ControllabilityConflict {
                    name: name.to_owned(),
                });
            }
            return Ok(id);
        }
        let id = EventId(u32::try_from(self.events.len()).expect("more than 2^32 events"));
        self.events.push(Event {
            name: name.to_owned(),
            controllable,
            observable: true,
        });
        self.by_name.insert(name.to_owned(), id);
        Ok(id)
    }

    /// [`Alphabet::insert`] of `event` with its observability: an
    /// unobservable event makes the name unobservable here too.
    pub fn insert_event(&mut self, event: &Event) -> Result<EventId, ControllabilityConflict> {
        let id = self.insert(&event.name, event.controllable)?;
        if !event.observable {
            self.set_unobservable(id);
        }
        Ok(id)
    }

    /// Makes event `id` unobservable.
    pub fn set_unobservable(&mut self, id: EventId) {
        self.events[id.index()].observable = false;
    }

    /// Whether event `id` is observable.
    #[inline]
    pub fn is_observable(&self, id: EventId) -> bool {
        self.events[id.index()].observable
    }

    /// The unobservable events, in id order.
    pub fn unobservable(&self) -> impl Iterator<Item = (EventId, &Event)> + '_ {
        self.iter().filter(|(_, e)| !e.observable)
    }

    /// The id of `name`, if present.
    #[inline]
    pub fn id(&self, name: &str) -> Option<EventId> {
        self.by_name.get(name).copied()
    }

    /// `true` when `name` is in the alphabet.
    #[inline]
    pub fn contains(&self, name: &str) -> bool {
        self.by_name.contains_key(name)
    }

    /// The event with id `id`.
    #[inline]
    pub fn event(&self, id: EventId) -> &Event {
        &self.events[id.index()]
    }

    /// The name of event `id`.
    #[inline]
    pub fn name(&self, id: EventId) -> &str {
        &self.events[id.index()].name
    }

    /// Whether event `id` is controllable.
    #[inline]
    pub fn is_controllable(&self, id: EventId) -> bool {
        self.events[id.index()].controllable
    }

    /// All events with their ids, in id order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (EventId, &Event)> + '_ {
        self.events
            .iter()
            .enumerate()
            .map(|(i, e)| (EventId(i as u32), e))
    }

    /// All event ids in order.
    pub fn ids(&self) -> impl ExactSizeIterator<Item = EventId> {
        (0..self.events.len() as u32).map(EventId)
    }

    /// Number of controllable events.
    pub fn controllable_count(&self) -> usize {
        self.events.iter().filter(|e| e.controllable).count()
    }

    /// The union of several alphabets: events in order of first appearance.
    ///
    /// Controllability comes from the alphabets that state it, which must
    /// agree; an event only unstated alphabets know is uncontrollable. The
    /// union states controllability when any part does (or there are none).
    /// An event is unobservable when any part says so.
    pub fn union<'a>(
        alphabets: impl IntoIterator<Item = &'a Alphabet> + Clone,
    ) -> Result<Alphabet, ControllabilityConflict> {
        let mut stated = Alphabet::new();
        let mut any_stated = false;
        let mut any = false;
        for a in alphabets.clone() {
            any = true;
            if a.stated {
                any_stated = true;
                for e in &a.events {
                    stated.insert(&e.name, e.controllable)?;
                }
            }
        }
        let mut out = Alphabet::new();
        for a in alphabets {
            for e in &a.events {
                let controllable = stated
                    .id(&e.name)
                    .map_or(a.stated && e.controllable, |id| stated.is_controllable(id));
                let id = out
                    .insert(&e.name, controllable)
                    .expect("controllability is fixed by the first pass");
                if !e.observable {
                    out.set_unobservable(id);
                }
            }
        }
        out.stated = any_stated || !any;
        Ok(out)
    }

    /// `true` when every event of `self` is in `other` (names only).
    pub fn is_subset_of(&self, other: &Alphabet) -> bool {
        self.events.iter().all(|e| other.contains(&e.name))
    }

    /// `true` when both hold the same event names with the same
    /// controllability (where both state it) and observability, in any
    /// order.
    pub fn same_events(&self, other: &Alphabet) -> bool {
        let compare = self.stated && other.stated;
        self.len() == other.len()
            && self.events.iter().all(|e| {
                other.id(&e.name).is_some_and(|id| {
                    (!compare || other.is_controllable(id) == e.controllable)
                        && other.is_observable(id) == e.observable
                })
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_follow_insertion_order_and_repeat_inserts_find_the_same_id() {
        let mut a = Alphabet::new();
        let start = a.insert("start", true).unwrap();
        let finish = a.insert("finish", false).unwrap();
        assert_eq!((start, finish), (EventId(0), EventId(1)));
        assert_eq!(a.insert("start", true).unwrap(), start);
        assert_eq!(a.id("finish"), Some(finish));
        assert_eq!(a.id("nope"), None);
        assert_eq!(a.controllable_count(), 1);
    }

    #[test]
    fn conflicting_controllability_is_an_error() {
        let mut a = Alphabet::new();
        a.insert("e", true).unwrap();
        let err = a.insert("e", false).unwrap_err();
        assert_eq!(err.name, "e");
    }

    #[test]
    fn union_keeps_first_appearance_order_and_detects_conflicts() {
        let mut a = Alphabet::new();
        a.insert("x", true).unwrap();
        a.insert("y", false).unwrap();
        let mut b = Alphabet::new();
        b.insert("z", false).unwrap();
        b.insert("x", true).unwrap();
        let u = Alphabet::union([&a, &b]).unwrap();
        let names: Vec<_> = u.iter().map(|(_, e)| e.name.as_str()).collect();
        assert_eq!(names, ["x", "y", "z"]);
        assert!(a.is_subset_of(&u) && b.is_subset_of(&u) && !u.is_subset_of(&a));

        let mut c = Alphabet::new();
        c.insert("y", true).unwrap();
        assert!(Alphabet::union([&a, &c]).is_err());
    }

    #[test]
    fn an_event_unobservable_anywhere_is_unobservable_where_alphabets_meet() {
        let mut a = Alphabet::new();
        let x = a.insert("x", true).unwrap();
        a.insert("y", false).unwrap();
        assert!(a.is_observable(x));
        a.set_unobservable(x);
        let mut b = Alphabet::new();
        b.insert("x", true).unwrap();
        b.insert("z", false).unwrap();
        for u in [
            Alphabet::union([&a, &b]).unwrap(),
            Alphabet::union([&b, &a]).unwrap(),
        ] {
            let names: Vec<&str> = u.unobservable().map(|(_, e)| e.name.as_str()).collect();
            assert_eq!(names, ["x"]);
        }
        let mut c = b.clone();
        c.insert_event(a.event(x)).unwrap();
        assert!(!c.is_observable(c.id("x").unwrap()));
        assert!(!b.same_events(&c), "observability differs");
        assert_eq!(a.unobservable().count(), 1);
    }

    #[test]
    fn unstated_controllability_defers_to_stated_alphabets() {
        let mut spec = Alphabet::new();
        spec.insert("start", false).unwrap();
        spec.insert("note", false).unwrap();
        spec.set_controllability_stated(false);
        let mut plant = Alphabet::new();
        plant.insert("start", true).unwrap();
        let u = Alphabet::union([&spec, &plant]).unwrap();
        assert!(u.controllability_stated());
        assert!(u.is_controllable(u.id("start").unwrap()));
        assert!(!u.is_controllable(u.id("note").unwrap()));
        // Alone, an unstated alphabet stays unstated.
        assert!(!Alphabet::union([&spec]).unwrap().controllability_stated());
        assert!(spec.same_events(&{
            let mut p = plant.clone();
            p.insert("note", false).unwrap();
            p
        }));
    }
}
