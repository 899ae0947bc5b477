//! Graphviz (DOT) rendering of automata.
//!
//! Conventions of the textbooks: an arrow from nowhere into the initial
//! state, marked states as double circles, controllable transitions solid
//! and uncontrollable ones dashed. Several events between the same two
//! states share one edge when they share the line style. Every name is
//! written as a quoted, escaped DOT string, so no name can break the graph.
//!
//! [`DotOptions`] adapt the drawing to large automata: the layout engine
//! the graph asks for (Graphviz honours a graph's `layout` attribute
//! whichever command reads it), edges without event names, and a quick
//! layered layout. Measured with Graphviz 2.43 on a 144-state boiler
//! supervisor (1,337 edges), `dot` spends 20 s ordering the ranks and then
//! does not finish placing them: every edge label is a node of its own,
//! which doubles the ranks (258), and the long edges become 144,536
//! virtual nodes for the network simplex that places them. The quick
//! layout writes the labels as `xlabel`s (placed after the layout instead
//! of taking part in it) and bounds the network simplex (`nslimit=1`) and
//! the crossing minimisation (`mclimit=0.1`): 4 s. `sfdp`: 0.1 s.

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

/// The Graphviz layout engine a graph asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Layout {
    /// Layered drawing (`dot`), left to right: the clearest for small
    /// automata, slow (minutes) for hundreds of states with thousands of
    /// edges.
    #[default]
    Dot,
    /// Scalable force-directed drawing (`sfdp`): seconds for such graphs.
    Sfdp,
    /// Force-directed drawing (`neato`).
    Neato,
}

/// How [`to_dot_with`] draws an automaton.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DotOptions {
    /// Write the events on the edges (otherwise only the line style tells
    /// controllable from uncontrollable).
    pub edge_labels: bool,
    /// The layout engine the graph asks for.
    pub layout: Layout,
    /// With [`Layout::Dot`]: edge labels placed after the layout, and the
    /// layout's optimisation bounded (see the module docs).
    pub quick: bool,
}

impl Default for DotOptions {
    fn default() -> Self {
        DotOptions {
            edge_labels: true,
            layout: Layout::Dot,
            quick: false,
        }
    }
}

/// The automaton as a DOT digraph, drawn with the default options.
pub fn to_dot(a: &Automaton) -> String {
    to_dot_with(a, &DotOptions::default())
}

/// The automaton as a DOT digraph.
pub fn to_dot_with(a: &Automaton, options: &DotOptions) -> String {
    let mut out = String::new();
    writeln!(out, "digraph {} {{", quote(a.name())).unwrap();
    let quick = options.quick && options.layout == Layout::Dot;
    out.push_str(match options.layout {
        Layout::Dot if quick => "  rankdir=LR;\n  nslimit=1;\n  mclimit=0.1;\n",
        Layout::Dot => "  rankdir=LR;\n",
        // Without `overlap=false` the force-directed engines let nodes
        // overlap; straight edges keep the routing fast.
        Layout::Sfdp => "  layout=sfdp;\n  overlap=false;\n  splines=false;\n",
        Layout::Neato => "  layout=neato;\n  overlap=false;\n  splines=false;\n",
    });
    out.push_str("  node [shape=circle];\n");
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
            let mut attributes = Vec::new();
            if options.edge_labels {
                let key = if quick { "xlabel" } else { "label" };
                attributes.push(format!("{key}={}", quote(&labels.join(", "))));
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
    fn large_graph_options_choose_the_engine_and_drop_edge_labels() {
        let g = auto(
            "M",
            &[("start", true), ("finish", false)],
            &[("0", "start", "1"), ("1", "finish", "0")],
            &["0"],
        );
        let options = DotOptions {
            edge_labels: false,
            layout: Layout::Sfdp,
            quick: false,
        };
        let dot = to_dot_with(&g, &options);
        assert!(dot.contains("  layout=sfdp;\n"), "{dot}");
        assert!(!dot.contains("rankdir"), "{dot}");
        assert!(dot.contains("  s0 -> s1;\n"), "{dot}");
        assert!(dot.contains("  s1 -> s0 [style=dashed];\n"), "{dot}");
        // States keep their names.
        assert!(dot.contains("s1 [label=\"1\"];"), "{dot}");
        assert_eq!(to_dot(&g), to_dot_with(&g, &DotOptions::default()));
        assert!(to_dot(&g).contains("rankdir=LR;"));

        let quick = DotOptions {
            quick: true,
            ..DotOptions::default()
        };
        let dot = to_dot_with(&g, &quick);
        assert!(dot.contains("  nslimit=1;\n  mclimit=0.1;\n"), "{dot}");
        assert!(dot.contains("  s0 -> s1 [xlabel=\"start\"];\n"), "{dot}");
        assert!(
            dot.contains("  s1 -> s0 [xlabel=\"finish\", style=dashed];\n"),
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
