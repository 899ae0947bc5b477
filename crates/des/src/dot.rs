//! Graphviz (DOT) rendering of automata.
//!
//! Conventions of the textbooks: an arrow from nowhere into the initial
//! state, marked states as double circles, controllable transitions solid
//! and uncontrollable ones dashed. Several events between the same two
//! states share one edge when they share the line style. Every name is
//! written as a quoted, escaped DOT string, so no name can break the graph.

use crate::automaton::Automaton;
use std::collections::BTreeMap;
use std::fmt::Write;

/// A DOT string literal for `text` (quotes and backslashes escaped,
/// newlines as `\n`).
pub fn quote(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => {}
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The automaton as a DOT digraph.
pub fn to_dot(a: &Automaton) -> String {
    let mut out = String::new();
    writeln!(out, "digraph {} {{", quote(a.name())).unwrap();
    out.push_str("  rankdir=LR;\n  node [shape=circle];\n");
    if let Some(init) = a.initial() {
        out.push_str("  __initial [shape=point, label=\"\"];\n");
        writeln!(out, "  __initial -> s{};", init.0).unwrap();
    }
    for s in a.states() {
        let shape = if a.is_marked(s) {
            ", shape=doublecircle"
        } else {
            ""
        };
        writeln!(
            out,
            "  s{} [label={}{shape}];",
            s.0,
            quote(&a.state_name(s))
        )
        .unwrap();
    }
    for s in a.states() {
        // (target, controllable) -> labels, in a stable order.
        let mut grouped: BTreeMap<(u32, bool), Vec<&str>> = BTreeMap::new();
        for t in a.transitions(s) {
            let controllable = a.alphabet().is_controllable(t.event);
            grouped
                .entry((t.target.0, !controllable))
                .or_default()
                .push(a.alphabet().name(t.event));
        }
        for ((target, uncontrollable), labels) in grouped {
            let style = if uncontrollable { ", style=dashed" } else { "" };
            writeln!(
                out,
                "  s{} -> s{target} [label={}{style}];",
                s.0,
                quote(&labels.join(", "))
            )
            .unwrap();
        }
    }
    out.push_str("}\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::auto;

    #[test]
    fn initial_arrow_marked_double_circle_and_dashed_uncontrollable_edges() {
        let g = auto(
            "MACH \"1\"",
            &[("start", true), ("finish", false), ("break", false)],
            &[
                ("0", "start", "1"),
                ("1", "finish", "0"),
                ("1", "break", "0"),
            ],
            &["0"],
        );
        let dot = to_dot(&g);
        assert!(dot.starts_with("digraph \"MACH \\\"1\\\"\" {"), "{dot}");
        assert!(dot.contains("__initial -> s0;"));
        assert!(dot.contains("s0 [label=\"0\", shape=doublecircle];"));
        assert!(dot.contains("s1 [label=\"1\"];"));
        assert!(dot.contains("s0 -> s1 [label=\"start\"];"));
        assert!(
            dot.contains("s1 -> s0 [label=\"finish, break\", style=dashed];"),
            "{dot}"
        );
    }

    #[test]
    fn hostile_names_stay_inside_their_strings() {
        let g = auto("x\"];evil", &[("a\\\"", true)], &[("0", "a\\\"", "0")], &[]);
        let dot = to_dot(&g);
        assert!(dot.contains("label=\"a\\\\\\\"\""), "{dot}");
        assert_eq!(dot.matches("digraph").count(), 1);
    }
}
