//! One automaton, every state drawn.
//!
//! Self-loops are hidden unless asked for: a supervisor that self-loops
//! the events it does not care about (most do) otherwise draws one loop
//! per state and event, and Graphviz widens the picture for each. A
//! hidden loop is not lost: the state's label lists the events that loop
//! there (`⟲ a, b, +3`, all of them in the tooltip). Events between the
//! same two states share one edge per line style, one event per line.
//! The controllable events a supervisor disables in a state, when asked
//! for, stand in its label in red (`✗ c`).

use super::{graph_header, html, Drawing, Graph, MAX_LISTED};
use des::automaton::{Automaton, EventId, StateId};
use des::dot::quote;
use std::collections::BTreeMap;
use std::fmt::Write;

/// The longest state name drawn in a circle (when every state's is no
/// longer and no state has notes); otherwise states are ellipses.
const MAX_CIRCLED: usize = 4;

/// What a state's label says beyond its name.
#[derive(Debug, Default, Clone, serde::Serialize)]
pub struct StateNotes {
    /// The state's name.
    pub state: String,
    /// Events that loop on the state and are not drawn as edges.
    pub self_loops: Vec<String>,
    /// Controllable events the supervisor disables in the state.
    pub disabled: Vec<String>,
}

impl StateNotes {
    fn is_empty(&self) -> bool {
        self.self_loops.is_empty() && self.disabled.is_empty()
    }
}

/// The controllable events a supervisor disables, per state.
pub struct Disabled {
    /// Indexed by state.
    pub events: Vec<Vec<EventId>>,
    /// What "disabled" means here, for the graph's title.
    pub meaning: &'static str,
}

/// Draws `a`, with the events it disables in each state if given.
pub fn draw(a: &Automaton, drawing: &Drawing, disabled: Option<&Disabled>) -> Graph {
    let names = |events: &[EventId]| -> Vec<String> {
        events
            .iter()
            .map(|&e| a.alphabet().name(e).to_owned())
            .collect()
    };
    let mut notes: Vec<StateNotes> = a
        .states()
        .map(|s| StateNotes {
            state: a.state_name(s).into_owned(),
            self_loops: Vec::new(),
            disabled: disabled.map_or_else(Vec::new, |d| names(&d.events[s.index()])),
        })
        .collect();
    let mut edges = String::new();
    let mut edge_count = 0;
    let mut hidden = 0;
    for s in a.states() {
        // (target, uncontrollable) -> events, in a stable order.
        let mut grouped: BTreeMap<(u32, bool), Vec<&str>> = BTreeMap::new();
        for t in a.transitions(s) {
            let name = a.alphabet().name(t.event);
            if t.target == s && !drawing.self_loops {
                notes[s.index()].self_loops.push(name.to_owned());
                hidden += 1;
                continue;
            }
            let uncontrollable = !a.alphabet().is_controllable(t.event);
            grouped
                .entry((t.target.0, uncontrollable))
                .or_default()
                .push(name);
        }
        for ((target, uncontrollable), events) in grouped {
            edge_count += 1;
            edge(&mut edges, drawing, s, target, uncontrollable, &events);
        }
    }

    let mut title = Vec::new();
    if hidden > 0 {
        title.push(format!(
            "{hidden} self-loops listed in their states (⟲), not drawn (--self-loops draws them)"
        ));
    }
    if let Some(d) = disabled {
        title.push(format!("✗: {}", d.meaning));
    }
    // Top to bottom: a supervisor's composite state names make wide
    // nodes, which side by side in left-to-right ranks gave a picture
    // five times wider than high. Circles fit short names; longer ones
    // and the notes fit an ellipse far better (a circle is as tall as
    // its name is wide).
    let mut out = graph_header(a.name(), drawing, "TB", &title);
    let circles = notes
        .iter()
        .all(|n| n.is_empty() && n.state.chars().count() <= MAX_CIRCLED);
    let (shape, marked) = if circles {
        ("circle", ", shape=doublecircle")
    } else {
        ("ellipse", ", peripheries=2")
    };
    writeln!(out, "  node [shape={shape}];").unwrap();
    if let Some(init) = a.initial() {
        out.push_str("  __initial [shape=point, label=\"\"];\n");
        writeln!(out, "  __initial -> s{};", init.0).unwrap();
    }
    for (s, note) in a.states().zip(&notes) {
        let marked = if a.is_marked(s) { marked } else { "" };
        writeln!(out, "  s{} [{}{marked}];", s.0, state_label(note)).unwrap();
    }
    out.push_str(&edges);
    out.push_str("}\n");
    notes.retain(|n| !n.is_empty());
    Graph {
        dot: out,
        nodes: a.num_states(),
        edges: edge_count,
        notes,
    }
}

/// The number of edges [`draw`] would draw (parallel edges merged,
/// self-loops hidden unless `self_loops`), without drawing them.
pub fn edge_count(a: &Automaton, self_loops: bool) -> usize {
    let mut pairs: Vec<(u32, bool)> = Vec::new();
    a.states()
        .map(|s| {
            pairs.clear();
            pairs.extend(
                a.transitions(s)
                    .iter()
                    .filter(|t| self_loops || t.target != s)
                    .map(|t| (t.target.0, a.alphabet().is_controllable(t.event))),
            );
            pairs.sort_unstable();
            pairs.dedup();
            pairs.len()
        })
        .sum()
}

/// One edge from `s` to `target` carrying `events`, one per line.
fn edge(
    out: &mut String,
    drawing: &Drawing,
    s: StateId,
    target: u32,
    uncontrollable: bool,
    events: &[&str],
) {
    let mut attributes = Vec::new();
    if drawing.edge_labels {
        let key = if drawing.floating_labels() {
            "xlabel"
        } else {
            "label"
        };
        attributes.push(format!("{key}={}", quote(&events.join("\n"))));
    }
    if uncontrollable {
        attributes.push("style=dashed".to_owned());
    }
    write!(out, "  s{} -> s{target}", s.0).unwrap();
    if !attributes.is_empty() {
        write!(out, " [{}]", attributes.join(", ")).unwrap();
    }
    out.push_str(";\n");
}

/// `label=…` for a state: its name alone as a plain string, or with its
/// hidden self-loops and disabled events as an HTML-like label (the
/// disabled ones red), every event in the tooltip.
fn state_label(note: &StateNotes) -> String {
    if note.is_empty() {
        return format!("label={}", quote(&note.state));
    }
    let mut label = html(&note.state);
    let mut tooltip = vec![note.state.clone()];
    let lines = [
        (&note.self_loops, "⟲", "", "self-loops"),
        (&note.disabled, "✗", " COLOR=\"red\"", "disabled"),
    ];
    for (events, sign, colour, what) in lines {
        if events.is_empty() {
            continue;
        }
        let shown = html(&compact(events));
        write!(
            label,
            "<BR/><FONT POINT-SIZE=\"10\"{colour}>{sign} {shown}</FONT>"
        )
        .unwrap();
        tooltip.push(format!("{what}: {}", events.join(", ")));
    }
    format!("label=<{label}>, tooltip={}", quote(&tooltip.join("\n")))
}

/// The first [`MAX_LISTED`] names and how many more: `a, b, c, +3`.
pub fn compact(names: &[String]) -> String {
    let shown = names.len().min(MAX_LISTED);
    let mut text = names[..shown].join(", ");
    if names.len() > shown {
        write!(text, ", +{}", names.len() - shown).unwrap();
    }
    text
}

/// The controllable events of `a`'s alphabet with no transition in each
/// state: what a supervisor disables when no plant says what could
/// happen.
pub fn disabled_without_plant(a: &Automaton) -> Disabled {
    let controllable: Vec<EventId> = a
        .alphabet()
        .ids()
        .filter(|&e| a.alphabet().is_controllable(e))
        .collect();
    let events = a
        .states()
        .map(|s| {
            controllable
                .iter()
                .copied()
                .filter(|&e| a.successor(s, e).is_none())
                .collect()
        })
        .collect();
    Disabled {
        events,
        meaning: "controllable events of the alphabet with no transition in the state",
    }
}

#[cfg(test)]
mod tests {
    use super::compact;

    #[test]
    fn long_lists_are_cut_after_three_names_and_say_how_many_more() {
        let names = |n: usize| (0..n).map(|i| format!("e{i}")).collect::<Vec<_>>();
        assert_eq!(compact(&names(1)), "e0");
        assert_eq!(compact(&names(3)), "e0, e1, e2");
        assert_eq!(compact(&names(6)), "e0, e1, e2, +3");
    }
}
