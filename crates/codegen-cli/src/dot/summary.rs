//! A large automaton as its condensation: one node per strongly connected
//! component (SCC), with its state count, a representative state and the
//! number of transitions inside it; one edge per pair of components
//! connected by transitions, with how many transitions and which events.
//!
//! A picture Graphviz lays out in seconds whatever the automaton's size,
//! which still shows its phases (start-up, running, shut-down) and where
//! it cannot come back from. The title says what was summarised.

use super::automaton::compact;
use super::{graph_header, Drawing, Graph};
use des::automaton::{Automaton, StateId};
use des::dot::quote;
use std::collections::BTreeMap;
use std::fmt::Write;

/// The strongly connected components of `a`: for each state its
/// component's number, components numbered in topological order (every
/// transition between two components goes from a lower number to a
/// higher one), and the number of components.
pub fn components(a: &Automaton) -> (Vec<usize>, usize) {
    // Tarjan's algorithm without recursion: a frame is a state and the
    // position of the next transition to follow.
    const UNSEEN: usize = usize::MAX;
    let n = a.num_states();
    let mut index = vec![UNSEEN; n];
    let mut low = vec![0; n];
    let mut on_stack = vec![false; n];
    let mut stack: Vec<usize> = Vec::new();
    let mut component = vec![UNSEEN; n];
    let mut found = 0;
    let mut next = 0;
    for root in 0..n {
        if index[root] != UNSEEN {
            continue;
        }
        let mut frames: Vec<(usize, usize)> = vec![(root, 0)];
        index[root] = next;
        low[root] = next;
        next += 1;
        stack.push(root);
        on_stack[root] = true;
        while let Some(&mut (v, ref mut position)) = frames.last_mut() {
            let transitions = a.transitions(StateId(v as u32));
            if let Some(t) = transitions.get(*position) {
                *position += 1;
                let w = t.target.index();
                if index[w] == UNSEEN {
                    index[w] = next;
                    low[w] = next;
                    next += 1;
                    stack.push(w);
                    on_stack[w] = true;
                    frames.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            frames.pop();
            if let Some(&(parent, _)) = frames.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component[w] = found;
                    if w == v {
                        break;
                    }
                }
                found += 1;
            }
        }
    }
    // Tarjan finds sinks first: reverse for the topological order.
    for c in &mut component {
        *c = found - 1 - *c;
    }
    (component, found)
}

/// One component of the condensation.
struct Component {
    states: usize,
    /// The initial state if the component holds it, else its first state.
    representative: StateId,
    internal: usize,
    marked: bool,
}

/// The condensation of `a`; `why` says in the title why it was chosen.
pub fn draw(a: &Automaton, drawing: &Drawing, why: &str) -> Graph {
    let (of, count) = components(a);
    let mut parts: Vec<Option<Component>> = (0..count).map(|_| None).collect();
    for s in a.states() {
        let part = parts[of[s.index()]].get_or_insert(Component {
            states: 0,
            representative: s,
            internal: 0,
            marked: false,
        });
        part.states += 1;
        part.marked |= a.is_marked(s);
        if a.initial() == Some(s) {
            part.representative = s;
        }
    }
    // (from, to) -> (transitions, events in alphabet order).
    let mut between: BTreeMap<(usize, usize), (usize, Vec<u32>)> = BTreeMap::new();
    for (s, e, t) in a.iter_transitions() {
        let (from, to) = (of[s.index()], of[t.index()]);
        if from == to {
            if let Some(part) = &mut parts[from] {
                part.internal += 1;
            }
            continue;
        }
        let entry = between.entry((from, to)).or_default();
        entry.0 += 1;
        entry.1.push(e.0);
    }
    let mut title = vec![format!(
        "summary ({why}): {} states and {} transitions as {count} strongly connected \
         component{}, a state of each named (--full draws every state)",
        a.num_states(),
        a.num_transitions(),
        if count == 1 { "" } else { "s" },
    )];
    if count == 1 {
        // Nonblocking supervisors often are: every state can come back to
        // the initial one.
        title.push(
            "strongly connected: every state reaches every other \
             (--full --layout sfdp draws them all in seconds)"
                .to_owned(),
        );
    }
    let mut out = graph_header(a.name(), drawing, "TB", &title);
    out.push_str("  node [shape=box, style=rounded];\n");
    if let Some(init) = a.initial() {
        out.push_str("  __initial [shape=point, label=\"\"];\n");
        writeln!(out, "  __initial -> c{};", of[init.index()]).unwrap();
    }
    for (k, part) in parts.iter().enumerate() {
        let Some(part) = part else { continue };
        let name = a.state_name(part.representative);
        let label = if part.states == 1 {
            format!("{name}\n{} inside", transitions(part.internal))
        } else {
            format!(
                "{name} and {} more\n{} states, {} inside",
                part.states - 1,
                part.states,
                transitions(part.internal)
            )
        };
        let marked = if part.marked { ", peripheries=2" } else { "" };
        writeln!(out, "  c{k} [label={}{marked}];", quote(&label)).unwrap();
    }
    for ((from, to), (n, events)) in &mut between {
        events.sort_unstable();
        events.dedup();
        let names: Vec<String> = events
            .iter()
            .map(|&e| a.alphabet().name(des::EventId(e)).to_owned())
            .collect();
        write!(out, "  c{from} -> c{to}").unwrap();
        if drawing.edge_labels {
            let label = format!("{}\n{}", transitions(*n), compact(&names));
            write!(out, " [label={}]", quote(&label)).unwrap();
        }
        out.push_str(";\n");
    }
    out.push_str("}\n");
    Graph {
        dot: out,
        nodes: count,
        edges: between.len(),
        notes: Vec::new(),
    }
}

/// `1 transition`, `n transitions`.
fn transitions(n: usize) -> String {
    if n == 1 {
        "1 transition".to_owned()
    } else {
        format!("{n} transitions")
    }
}

#[cfg(test)]
mod tests {
    use super::components;
    use des::AutomatonBuilder;

    #[test]
    fn two_cycles_and_a_sink_are_three_components_in_topological_order() {
        // 0 <-> 1 -> 2 <-> 3 -> 4
        let mut b = AutomatonBuilder::new("A");
        for e in ["a", "b"] {
            b.add_event(e, true).unwrap();
        }
        b.set_initial_by_name("0").unwrap();
        for (s, e, t) in [
            ("0", "a", "1"),
            ("1", "a", "0"),
            ("1", "b", "2"),
            ("2", "a", "3"),
            ("3", "a", "2"),
            ("3", "b", "4"),
        ] {
            b.add_transition_by_name(s, e, t, 0).unwrap();
        }
        let a = b.build().unwrap();
        let (of, count) = components(&a);
        let at = |name: &str| of[a.state_by_name(name).unwrap().index()];
        assert_eq!(count, 3);
        assert_eq!(at("0"), at("1"));
        assert_eq!(at("2"), at("3"));
        assert!(at("0") < at("2") && at("2") < at("4"));
    }
}
