//! Shorthand for building automata in unit tests.

use crate::automaton::{Automaton, AutomatonBuilder};

/// An automaton from its events, transitions and marked states; the
/// initial state is `"0"`.
pub fn auto(
    name: &str,
    events: &[(&str, bool)],
    trans: &[(&str, &str, &str)],
    marked: &[&str],
) -> Automaton {
    let mut b = AutomatonBuilder::new(name);
    for &(e, c) in events {
        b.add_event(e, c).unwrap();
    }
    b.set_initial_by_name("0").unwrap();
    for &(s, e, t) in trans {
        b.add_transition_by_name(s, e, t, 0).unwrap();
    }
    for m in marked {
        b.mark_by_name(m);
    }
    b.build().unwrap()
}
