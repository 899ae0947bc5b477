//! Keys to composite state names.
//!
//! A composition names its states `a.b.c` after its components' states
//! (`des::ops::sync`), so `0.1.2` means nothing without the components in
//! order. [`Key`] pairs every component with its state. It is found by
//! following the same events in each component rather than by splitting
//! the name at dots, which would go wrong when a component's own state
//! names contain dots (a supervisor written by `synth`, for instance).

use des::ops::{self, ComposeOptions, Composition};
use des::{Automaton, Error, StateId};
use serde::ser::SerializeMap;

/// The state of each component in one composite state, in composition
/// order. Serialises as a JSON object in that order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Key(Vec<(String, String)>);

impl Key {
    /// The states `components` reach after `path`, each taking the events
    /// of its alphabet and ignoring the others (as `sync` does). `None` if
    /// a component cannot follow the path (it was not part of the
    /// composition that produced it).
    pub fn after(components: &[&Automaton], path: &[String]) -> Option<Key> {
        let mut pairs = Vec::with_capacity(components.len());
        for a in components {
            let mut state = a.initial()?;
            for event in path {
                if let Some(e) = a.alphabet().id(event) {
                    state = a.successor(state, e)?;
                }
            }
            pairs.push((a.name().to_owned(), a.state_name(state).into_owned()));
        }
        Some(Key(pairs))
    }

    /// `(MACH1 0, MACH2 1)`.
    pub fn describe(&self) -> String {
        let parts: Vec<String> = self.0.iter().map(|(c, s)| format!("{c} {s}")).collect();
        format!("({})", parts.join(", "))
    }

    /// `(0, 1)`: the states alone, for rows under a header naming the
    /// components.
    pub fn states(&self) -> String {
        let parts: Vec<&str> = self.0.iter().map(|(_, s)| s.as_str()).collect();
        format!("({})", parts.join(", "))
    }
}

impl serde::Serialize for Key {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (component, state) in &self.0 {
            map.serialize_entry(component, state)?;
        }
        map.end()
    }
}

/// For each state of `sup`, the plant states (one [`Key`] over `plants`
/// each) it occurs with in the closed loop `plants ‖ sup`, in the order
/// the closed loop reaches them. A supervisor synthesised for these plants
/// has exactly one per state.
pub fn plant_states_per_supervisor_state(
    plants: &[Automaton],
    sup: &Automaton,
) -> Result<Vec<Vec<Key>>, Error> {
    let mut all: Vec<&Automaton> = plants.iter().collect();
    all.push(sup);
    let closed = ops::compose(
        &all,
        Composition::Sync,
        ComposeOptions {
            name_states: false,
            ..ComposeOptions::default()
        },
    )?;
    let mut per_state = vec![Vec::new(); sup.num_states()];
    for s in closed.automaton.states() {
        let tuple = closed.tuple(s);
        let (plant_tuple, sup_state) = tuple.split_at(plants.len());
        let key = Key(plants
            .iter()
            .zip(plant_tuple)
            .map(|(a, &q)| (a.name().to_owned(), a.state_name(StateId(q)).into_owned()))
            .collect());
        per_state[sup_state[0] as usize].push(key);
    }
    Ok(per_state)
}

#[cfg(test)]
mod tests {
    use super::*;
    use des::formats::{read_str, Format};
    use std::path::Path;

    fn machine(name: &str, start: &str, finish: &str, states: [&str; 2]) -> Automaton {
        let [idle, busy] = states;
        let text = format!(
            "name = \"{name}\"\ninitial = \"{idle}\"\nmarked = [\"{idle}\"]\n\
             controllable = [\"{start}\"]\nuncontrollable = [\"{finish}\"]\n\
             transitions = [[\"{idle}\", \"{start}\", \"{busy}\"], [\"{busy}\", \"{finish}\", \"{idle}\"]]\n"
        );
        toml(&text)
    }

    fn toml(text: &str) -> Automaton {
        let mut c = read_str(text, Format::Toml, Path::new("m.toml")).unwrap();
        c.remove(0).automaton
    }

    #[test]
    fn a_path_gives_each_component_its_state_even_with_dotted_names() {
        let m1 = machine("M1", "s1", "f1", ["0", "1"]);
        let m2 = machine("M2", "s2", "f2", ["a.idle", "a.busy"]);
        let path = ["s1".to_owned(), "s2".to_owned(), "f1".to_owned()];
        let key = Key::after(&[&m1, &m2], &path).unwrap();
        assert_eq!(key.describe(), "(M1 0, M2 a.busy)");
        assert_eq!(key.states(), "(0, a.busy)");
        assert_eq!(
            serde_json::to_string(&key).unwrap(),
            r#"{"M1":"0","M2":"a.busy"}"#
        );
        // M1 cannot finish before it starts: not a path of M1.
        assert_eq!(Key::after(&[&m1], &["f1".to_owned()]), None);
    }

    #[test]
    fn supervisor_states_are_paired_with_the_plant_states_they_occur_with() {
        let m1 = machine("M1", "s1", "f1", ["0", "1"]);
        let m2 = machine("M2", "s2", "f2", ["0", "1"]);
        // Never lets M2 start: one plant state per supervisor state.
        let sup = toml(
            "name = \"S\"\ninitial = \"ready\"\nmarked = [\"ready\"]\n\
             controllable = [\"s1\", \"s2\"]\nuncontrollable = [\"f1\"]\n\
             transitions = [[\"ready\", \"s1\", \"waiting\"], [\"waiting\", \"f1\", \"ready\"]]\n",
        );
        let per_state = plant_states_per_supervisor_state(&[m1, m2], &sup).unwrap();
        let described: Vec<Vec<String>> = per_state
            .iter()
            .map(|keys| keys.iter().map(Key::states).collect())
            .collect();
        assert_eq!(described, [vec!["(0, 0)"], vec!["(1, 0)"]]);
    }
}
