//! Graphviz (DOT) text: names as quoted strings and the layout engines
//! a graph may ask for. The drawings themselves (automata, their
//! strongly connected components, Petri nets) are the `codegen dot`
//! command's (`crates/codegen-cli/src/dot/`).
//!
//! Measured with Graphviz 2.43 on a 144-state boiler supervisor (1,337
//! edges), the layered layout (`dot`) spends 20 s ordering the ranks and
//! then does not finish placing them: every edge label is a node of its
//! own, which doubles the ranks, and the long edges become 144,536
//! virtual nodes for the network simplex that places them. Labels placed
//! after the layout (`xlabel`) with a bounded network simplex
//! (`nslimit=1`) and crossing minimisation (`mclimit=0.1`): 4 s. `sfdp`:
//! 0.1 s.

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
    /// Layered drawing (`dot`): the clearest for small automata, slow
    /// (minutes) for hundreds of states with thousands of edges.
    #[default]
    Dot,
    /// Scalable force-directed drawing (`sfdp`): seconds for such graphs.
    Sfdp,
    /// Force-directed drawing (`neato`).
    Neato,
}

#[cfg(test)]
mod tests {
    use super::quote;

    #[test]
    fn hostile_names_stay_inside_their_strings() {
        assert_eq!(quote("x\"];evil"), "\"x\\\"];evil\"");
        assert_eq!(quote("a\\\""), "\"a\\\\\\\"\"");
        assert_eq!(quote("two\nlines\r"), "\"two\\nlines\"");
    }
}
