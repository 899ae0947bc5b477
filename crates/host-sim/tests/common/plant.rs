//! A plant played by its automata: the model files a supervisor was
//! synthesised from, each automaton in its current state, moved by name.

use des::automaton::StateId;
use des::Automaton;
use std::path::PathBuf;

/// The plant automata and their states.
pub struct Plant {
    automata: Vec<Automaton>,
    states: Vec<StateId>,
}

impl Plant {
    /// Every automaton of the files `plants`, in its initial state.
    pub fn of_files(plants: &[PathBuf]) -> Plant {
        let automata: Vec<Automaton> = plants
            .iter()
            .flat_map(|p| des::formats::read_file(p).unwrap())
            .map(|c| c.automaton)
            .collect();
        let states = automata.iter().map(|a| a.initial().unwrap()).collect();
        Plant { automata, states }
    }

    /// How many automata.
    pub fn len(&self) -> usize {
        self.automata.len()
    }

    /// Whether every automaton having `event` allows it now.
    pub fn allows(&self, event: &str) -> bool {
        self.automata.iter().zip(&self.states).all(|(a, &s)| {
            a.alphabet()
                .id(event)
                .is_none_or(|e| a.successor(s, e).is_some())
        })
    }

    /// Moves every automaton having `event`; `false` (nothing moved) if
    /// one refuses.
    pub fn take(&mut self, event: &str) -> bool {
        if !self.allows(event) {
            return false;
        }
        for (a, s) in self.automata.iter().zip(self.states.iter_mut()) {
            if let Some(e) = a.alphabet().id(event) {
                *s = a.successor(*s, e).expect("allowed");
            }
        }
        true
    }

    /// The state name of automaton `name`.
    pub fn state(&self, name: &str) -> String {
        let k = self.automata.iter().position(|a| a.name() == name).unwrap();
        self.automata[k].state_name(self.states[k]).into_owned()
    }
}
