//! `codegen dot`: Graphviz drawings of automata.
//!
//! Graphviz reads one graph per file, so a file holding several
//! components (a Waters module) gives either one component (`--component`)
//! or one `.dot` file per component (`--output-dir`), never several graphs
//! in one stream. Large automata are refused beyond `--max-states`: `dot`
//! needs minutes for a few hundred states with thousands of edges; the
//! message says what to do instead (see `codegen dot --help`).

use super::error::CliError;
use super::output::{outln, Out};
use super::{load_components, Outcome};
use des::dot::{to_dot_with, DotOptions, Layout};
use des::formats::Component;
use des::Error;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The default `--max-states`.
const MAX_STATES: usize = 100;

/// Arguments of `codegen dot`.
#[derive(Debug, clap::Args)]
#[command(after_long_help = AFTER_HELP)]
pub struct DotArgs {
    /// Model file.
    file: PathBuf,
    /// Only this component (for files holding several).
    #[arg(long)]
    component: Option<String>,
    /// Write the graph to this file instead of stdout.
    #[arg(short = 'o', long = "output", conflicts_with = "output_dir")]
    output: Option<PathBuf>,
    /// Write one file per component into this directory (created if
    /// missing), each named after its component: `MACH1.dot`.
    #[arg(long, value_name = "DIR")]
    output_dir: Option<PathBuf>,
    /// Refuse automata with more states than this (0: no limit); Graphviz
    /// takes minutes on larger ones.
    #[arg(long, default_value_t = MAX_STATES, value_name = "N")]
    max_states: usize,
    /// Layout engine the graph asks for (`dot` honours it through the
    /// graph's `layout` attribute; `sfdp` draws large graphs in seconds).
    #[arg(long, value_enum, default_value_t = EngineArg::Dot)]
    layout: EngineArg,
    /// Leave the event names off the edges (line styles still tell
    /// controllable from uncontrollable).
    #[arg(long)]
    no_labels: bool,
    /// A quicker layered layout for large automata: edge labels placed
    /// after the layout (`xlabel`) and Graphviz's optimisation bounded
    /// (`nslimit=1`, `mclimit=0.1`).
    #[arg(long)]
    quick: bool,
}

const AFTER_HELP: &str = "\
Output: one graph on stdout; with -o FILE, in FILE; with --output-dir DIR,
every component of the file in DIR/NAME.dot. A file with several
components needs --component NAME or --output-dir.

Drawing: controllable events solid, uncontrollable dashed, marked states
as double circles, an arrow into the initial state. Events between the
same two states share one edge per line style.

Large automata: `dot -Tsvg` needs minutes for a graph with a hundred
states or more and a thousand edges (a 144-state boiler supervisor: over
two and a half minutes; its 406-state one: not done after ten), because
every edge label becomes a node of the layered layout. Such automata are
refused unless --max-states allows them. Then --quick keeps the layered
drawing with floating edge labels and a bounded optimisation (4 s and
25 s for those two), and --layout sfdp draws them in well under a second
(force-directed, no ranks); --no-labels leaves only the shape of a dense
graph.

Example:
  codegen dot sup.gen -o sup.dot && dot -Tsvg sup.dot -o sup.svg
  codegen dot plant.wmod --output-dir graphs/
  codegen dot big.gen --max-states 0 --quick -o big.dot && dot -Tsvg big.dot -o big.svg
  codegen dot big.gen --max-states 0 --layout sfdp -o big.dot";

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum EngineArg {
    /// Layered (Graphviz `dot`): the clearest for small automata.
    Dot,
    /// Force-directed, scalable (Graphviz `sfdp`).
    Sfdp,
    /// Force-directed (Graphviz `neato`).
    Neato,
}

impl DotArgs {
    fn options(&self) -> DotOptions {
        DotOptions {
            edge_labels: !self.no_labels,
            quick: self.quick,
            layout: match self.layout {
                EngineArg::Dot => Layout::Dot,
                EngineArg::Sfdp => Layout::Sfdp,
                EngineArg::Neato => Layout::Neato,
            },
        }
    }
}

pub fn run(args: &DotArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let components = load_components(&args.file, args.component.as_deref())?;
    for c in &components {
        check_size(args, c)?;
    }
    let options = args.options();
    let graphs: Vec<(&Component, String)> = components
        .iter()
        .map(|c| (c, to_dot_with(&c.automaton, &options)))
        .collect();
    if let Some(dir) = &args.output_dir {
        return write_dir(dir, &graphs, json, out);
    }
    if json && args.output.is_none() {
        // One JSON document holds any number of graphs, each its own text.
        let listed: Vec<_> = graphs
            .iter()
            .map(|(c, dot)| serde_json::json!({ "name": c.automaton.name(), "dot": dot }))
            .collect();
        out.json(&listed);
        return Ok(Outcome::Holds);
    }
    let [(component, dot)] = graphs.as_slice() else {
        let names: Vec<&str> = components.iter().map(|c| c.automaton.name()).collect();
        return Err(CliError::Usage(format!(
            "{}: holds {} automata ({}), and Graphviz reads one graph per file: \
             choose one with --component NAME, or write each to its own file with \
             --output-dir DIR",
            args.file.display(),
            names.len(),
            names.join(", ")
        )));
    };
    match &args.output {
        None => out.push_str(dot),
        Some(path) => {
            write(path, dot)?;
            report(json, out, &[(component.automaton.name(), path.clone())]);
        }
    }
    Ok(Outcome::Holds)
}

/// Refuses automata beyond `--max-states`, saying what to do instead.
fn check_size(args: &DotArgs, c: &Component) -> Result<(), CliError> {
    let a = &c.automaton;
    if args.max_states == 0 || a.num_states() <= args.max_states {
        return Ok(());
    }
    Err(CliError::Usage(format!(
        "{}: `{}` has {} states and {} transitions, more than --max-states {} \
         (Graphviz `dot` takes minutes on graphs this size): draw it anyway with \
         --max-states {} (or 0), with --quick (a layered drawing in seconds) or \
         --layout sfdp (force-directed, under a second); --no-labels helps a dense \
         graph",
        args.file.display(),
        a.name(),
        a.num_states(),
        a.num_transitions(),
        args.max_states,
        a.num_states(),
    )))
}

/// A file name for component `name`: the name with every character
/// outside `[A-Za-z0-9_.-]` replaced by `_`, and `.dot`.
fn file_name(name: &str) -> String {
    let stem: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "_.-".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    let stem = stem.trim_start_matches('.');
    if stem.is_empty() {
        "automaton.dot".to_owned()
    } else {
        format!("{stem}.dot")
    }
}

fn write_dir(
    dir: &Path,
    graphs: &[(&Component, String)],
    json: bool,
    out: &mut Out,
) -> Result<Outcome, CliError> {
    let mut files: BTreeMap<String, &str> = BTreeMap::new();
    for (c, _) in graphs {
        let name = c.automaton.name();
        if let Some(other) = files.insert(file_name(name), name) {
            return Err(CliError::Usage(format!(
                "components `{other}` and `{name}` would both be written to {}; \
                 write them one at a time with --component NAME -o FILE",
                dir.join(file_name(name)).display()
            )));
        }
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let mut written = Vec::new();
    for (c, dot) in graphs {
        let path = dir.join(file_name(c.automaton.name()));
        write(&path, dot)?;
        written.push((c.automaton.name(), path));
    }
    report(json, out, &written);
    Ok(Outcome::Holds)
}

fn write(path: &Path, dot: &str) -> Result<(), Error> {
    std::fs::write(path, dot).map_err(|e| Error::io(path, e))
}

/// Says which files were written.
fn report(json: bool, out: &mut Out, written: &[(&str, PathBuf)]) {
    if json {
        let files: Vec<_> = written
            .iter()
            .map(|(name, path)| {
                serde_json::json!({ "name": name, "file": path.display().to_string() })
            })
            .collect();
        out.json(&files);
    } else {
        for (name, path) in written {
            outln!(out, "wrote {} ({name})", path.display());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::file_name;

    #[test]
    fn file_names_keep_plain_component_names_and_replace_the_rest() {
        assert_eq!(file_name("MACH1"), "MACH1.dot");
        assert_eq!(file_name("sup.v2"), "sup.v2.dot");
        assert_eq!(file_name("a/b c"), "a_b_c.dot");
        assert_eq!(file_name("../x"), "_x.dot");
        assert_eq!(file_name(""), "automaton.dot");
    }
}
