//! `codegen dot`: Graphviz drawings of automata and Petri nets.
//!
//! Graphviz reads one graph per file, so a file holding several
//! components (a Waters module) gives either one component (`--component`)
//! or one `.dot` file per component (`--output-dir`), never several graphs
//! in one stream.
//!
//! - [`automaton`]: every state, self-loops listed in their states rather
//!   than drawn (unless `--self-loops`), and with `--disabled` the
//!   controllable events each state disables.
//! - [`summary`]: beyond `--max-states` states or `--max-edges` edges
//!   (or with `--summary`), the condensation into strongly connected
//!   components, which Graphviz lays out in seconds (`dot` needs minutes
//!   for a few hundred states with thousands of edges); `--full` draws
//!   every state anyway.
//! - [`net`]: a Petri net file (`.pnml`, or a `.toml` with `places`),
//!   with the control places `--constraints` adds highlighted.

mod automaton;
mod net;
mod summary;

use super::error::CliError;
use super::net_control::ControlArgs;
use super::output::{outln, Out};
use super::{load, load_components, Outcome, Role};
use des::dot::{quote, Layout};
use des::{ops, Automaton, Error};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// The default `--max-states`.
const MAX_STATES: usize = 100;

/// The default `--max-edges`.
const MAX_EDGES: usize = 1000;

/// How many events a state's label or a summary edge names before it
/// says how many more there are.
const MAX_LISTED: usize = 3;

/// Arguments of `codegen dot`.
#[derive(Debug, clap::Args)]
#[command(after_long_help = AFTER_HELP)]
pub struct DotArgs {
    /// Model file, or Petri net (`.pnml`, or `.toml` with `places`).
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
    /// Draw automata with more states than this as their strongly
    /// connected components (0: no limit); Graphviz takes minutes on
    /// larger ones.
    #[arg(long, default_value_t = MAX_STATES, value_name = "N")]
    max_states: usize,
    /// Draw automata with more edges than this (parallel edges merged,
    /// self-loops hidden unless drawn) as their strongly connected
    /// components (0: no limit).
    #[arg(long, default_value_t = MAX_EDGES, value_name = "N")]
    max_edges: usize,
    /// Always draw the strongly connected components, one node each.
    #[arg(long, conflicts_with = "full")]
    summary: bool,
    /// Always draw every state, whatever the size.
    #[arg(long)]
    full: bool,
    /// Draw self-loops as edges (by default each state lists the events
    /// that loop on it: `⟲ a, b, +3`).
    #[arg(long)]
    self_loops: bool,
    /// Show in each state the controllable events the supervisor disables
    /// there (`✗ c`, red): those of its alphabet it has no transition for,
    /// or with --plant those the plant could do there.
    #[arg(long)]
    disabled: bool,
    /// Plant component files for --disabled: a controllable event is
    /// disabled in a state when the plant enables it there in the closed
    /// loop and the supervisor does not (`codegen condat`).
    #[arg(long = "plant", num_args = 1.., value_name = "FILES", requires = "disabled")]
    plants: Vec<PathBuf>,
    /// For a Petri net: the constraints (`[[constraint]]`, as for `petri
    /// synth`) whose control places are added to the net and drawn red.
    #[arg(long, value_name = "FILE")]
    constraints: Option<PathBuf>,
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
    #[command(flatten)]
    net_control: ControlArgs,
}

const AFTER_HELP: &str = "\
Output: one graph on stdout; with -o FILE, in FILE; with --output-dir DIR,
every component of the file in DIR/NAME.dot. A file with several
components needs --component NAME or --output-dir.

Drawing: controllable events solid, uncontrollable dashed, marked states
as double circles, an arrow into the initial state. Events between the
same two states share one edge per line style, one event per line.
Self-loops are not drawn: each state lists the events that loop on it
(⟲ a, b, +3; every one in the tooltip), unless --self-loops. --disabled
adds the controllable events each state disables (✗, red).

Petri nets (.pnml, or .toml with `places`): places as circles with their
initial tokens, transitions as boxes (dashed: uncontrollable), arc
weights above 1 written; --constraints FILE adds the control places of
place-invariant synthesis and draws them red. A net whose file does not
say which transitions are controllable takes --uncontrollable or
--control as `petri` does.

Large automata: `dot -Tsvg` needs minutes for a graph with a few hundred
states and thousands of edges (every edge label becomes a node of the
layered layout). Beyond --max-states (100) states or --max-edges (1000)
edges, the graph is the automaton's strongly connected components, one
node each (its size, a state of it, its internal transitions), titled as
a summary; --full draws every state anyway, --summary always summarises.
With --full, --quick keeps the layered drawing with floating edge labels
and a bounded optimisation (12 s for a 406-state supervisor), --layout
sfdp draws it in well under a second (force-directed, no ranks) and
--no-labels leaves only the shape of a dense graph.

Example:
  codegen dot sup.gen -o sup.dot && dot -Tsvg sup.dot -o sup.svg
  codegen dot sup.gen --disabled --plant M1.gen M2.gen -o sup.dot
  codegen dot plant.wmod --output-dir graphs/
  codegen dot net.pnml --constraints net.constraints.toml -o net.dot
  codegen dot big.gen --full --layout sfdp -o big.dot";

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum EngineArg {
    /// Layered (Graphviz `dot`): the clearest for small automata.
    Dot,
    /// Force-directed, scalable (Graphviz `sfdp`).
    Sfdp,
    /// Force-directed (Graphviz `neato`).
    Neato,
}

/// How every graph is drawn: the options shared by automata, summaries
/// and nets.
#[derive(Debug, Clone, Copy)]
pub struct Drawing {
    /// The layout engine the graph asks for.
    pub layout: Layout,
    /// Write the events on the edges.
    pub edge_labels: bool,
    /// Edge labels after the layout and a bounded optimisation.
    pub quick: bool,
    /// Draw self-loops as edges instead of listing them in their states.
    pub self_loops: bool,
}

impl Drawing {
    /// Edge labels as `xlabel`s (the quick layered layout).
    fn floating_labels(&self) -> bool {
        self.quick && self.layout == Layout::Dot
    }
}

/// A drawn graph and what it holds.
#[derive(Debug, serde::Serialize)]
pub struct Graph {
    /// The DOT text.
    pub dot: String,
    /// Nodes drawn (states, components, or places and transitions).
    pub nodes: usize,
    /// Edges drawn (merged parallel edges count once).
    pub edges: usize,
    /// The states whose label lists hidden self-loops or disabled events.
    pub notes: Vec<automaton::StateNotes>,
}

/// `digraph NAME {`, the layout's attributes (ranks in direction
/// `rankdir` for the layered layout), and `title` (if any lines) as the
/// graph's label on top.
fn graph_header(name: &str, drawing: &Drawing, rankdir: &str, title: &[String]) -> String {
    let mut out = String::new();
    writeln!(out, "digraph {} {{", quote(name)).unwrap();
    match drawing.layout {
        Layout::Dot => writeln!(out, "  rankdir={rankdir};").unwrap(),
        Layout::Sfdp | Layout::Neato => {}
    }
    out.push_str(match drawing.layout {
        Layout::Dot if drawing.floating_labels() => "  nslimit=1;\n  mclimit=0.1;\n",
        Layout::Dot => "",
        // Without `overlap=false` the force-directed engines let nodes
        // overlap; straight edges keep the routing fast.
        Layout::Sfdp => "  layout=sfdp;\n  overlap=false;\n  splines=false;\n",
        Layout::Neato => "  layout=neato;\n  overlap=false;\n  splines=false;\n",
    });
    if !title.is_empty() {
        writeln!(
            out,
            "  labelloc=t;\n  label={};",
            quote(&format!("{name}\n{}", title.join("\n")))
        )
        .unwrap();
    }
    out
}

/// `text` for an HTML-like Graphviz label: `&`, `<`, `>` and `"` as
/// entities, line breaks as `<BR/>`.
fn html(text: &str) -> String {
    let entity = |c: char| match c {
        '&' => "&amp;".to_owned(),
        '<' => "&lt;".to_owned(),
        '>' => "&gt;".to_owned(),
        '"' => "&quot;".to_owned(),
        c => c.to_string(),
    };
    let lines: Vec<String> = text
        .lines()
        .map(|line| line.chars().map(entity).collect())
        .collect();
    lines.join("<BR/>")
}

impl DotArgs {
    fn drawing(&self) -> Drawing {
        Drawing {
            edge_labels: !self.no_labels,
            quick: self.quick,
            self_loops: self.self_loops,
            layout: match self.layout {
                EngineArg::Dot => Layout::Dot,
                EngineArg::Sfdp => Layout::Sfdp,
                EngineArg::Neato => Layout::Neato,
            },
        }
    }

    /// Why `a` is drawn as its components, or `None` to draw it whole.
    fn summary_reason(&self, a: &Automaton) -> Option<String> {
        if self.summary {
            return Some("--summary".to_owned());
        }
        if self.full {
            return None;
        }
        if self.max_states != 0 && a.num_states() > self.max_states {
            return Some(format!(
                "{} states, more than --max-states {}",
                a.num_states(),
                self.max_states
            ));
        }
        let edges = automaton::edge_count(a, self.self_loops);
        if self.max_edges != 0 && edges > self.max_edges {
            return Some(format!(
                "{edges} edges, more than --max-edges {}",
                self.max_edges
            ));
        }
        None
    }

    /// The controllable events `sup` disables in each state, if asked.
    fn disabled(&self, sup: &Automaton) -> Result<Option<automaton::Disabled>, CliError> {
        if !self.disabled {
            return Ok(None);
        }
        if self.plants.is_empty() {
            return Ok(Some(automaton::disabled_without_plant(sup)));
        }
        let plants = load(&self.plants, Role::Plant)?;
        let refs: Vec<&Automaton> = plants.iter().collect();
        let plant = ops::sync(&refs)?;
        Ok(Some(automaton::Disabled {
            events: ops::condat(&plant, sup)?.disabled,
            meaning: "controllable events the plant could do in the closed loop and the \
                      supervisor disables",
        }))
    }

    /// Flags that only a net, or only an automaton, takes.
    fn refuse_flags(&self, net: bool) -> Result<(), CliError> {
        let (misplaced, what) = if net {
            let flags = [
                (self.component.is_some(), "--component"),
                (self.disabled, "--disabled"),
                (self.summary, "--summary"),
                (self.self_loops, "--self-loops"),
            ];
            (flags.into_iter().find(|(set, _)| *set), "a Petri net")
        } else {
            let flags = [
                (self.constraints.is_some(), "--constraints"),
                (
                    self.net_control.given(),
                    "--uncontrollable, --unobservable or --control",
                ),
            ];
            (flags.into_iter().find(|(set, _)| *set), "an automaton")
        };
        match misplaced {
            Some((_, flag)) => Err(CliError::Usage(format!(
                "{}: {flag} does not apply to {what}",
                self.file.display()
            ))),
            None => Ok(()),
        }
    }
}

/// Whether `path` holds a Petri net: a `.pnml` file, or a `.toml` file
/// with a `places` table (automata have none). A file that cannot be
/// read or parsed is left to the automaton reader, which says where it
/// is wrong.
fn is_net(path: &Path) -> bool {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("pnml") => true,
        Some("toml") => des::files::read_text(path, des::formats::MODEL_FILE)
            .ok()
            .and_then(|text| text.parse::<toml::Table>().ok())
            .is_some_and(|table| table.contains_key("places")),
        _ => false,
    }
}

pub fn run(args: &DotArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let net = is_net(&args.file);
    args.refuse_flags(net)?;
    let drawing = args.drawing();
    let mut graphs: Vec<(String, &'static str, Graph)> = Vec::new();
    if net {
        let mut plant = args.net_control.read_net(&args.file)?;
        let mut control = Vec::new();
        if let Some(constraints) = &args.constraints {
            let cs = des::petri::constraints::read_file(constraints, &plant)?;
            let supervised = des::petri::synth::synthesize(&plant, &cs)?;
            control = (plant.places().len()..supervised.net.places().len()).collect();
            plant = supervised.net;
        }
        let graph = net::draw(&plant, &drawing, &control);
        graphs.push((plant.name().to_owned(), "net", graph));
    } else {
        for c in load_components(&args.file, args.component.as_deref())? {
            let a = &c.automaton;
            let graph = match args.summary_reason(a) {
                Some(mut why) => {
                    if args.disabled || args.self_loops {
                        // Both are about states, which a summary does not
                        // draw: say so rather than drop them unsaid.
                        why.push_str("; --disabled and --self-loops apply with --full");
                    }
                    (summary::draw(a, &drawing, &why), "summary")
                }
                None => (
                    automaton::draw(a, &drawing, args.disabled(a)?.as_ref()),
                    "full",
                ),
            };
            graphs.push((a.name().to_owned(), graph.1, graph.0));
        }
    }
    if let Some(dir) = &args.output_dir {
        return write_dir(dir, &graphs, json, out);
    }
    if json && args.output.is_none() {
        // One JSON document holds any number of graphs, each its own text.
        let listed: Vec<_> = graphs
            .iter()
            .map(|(name, view, graph)| {
                serde_json::json!({
                    "name": name,
                    "view": view,
                    "nodes": graph.nodes,
                    "edges": graph.edges,
                    "states": graph.notes,
                    "dot": graph.dot,
                })
            })
            .collect();
        out.json(&listed);
        return Ok(Outcome::Holds);
    }
    let [(name, _, graph)] = graphs.as_slice() else {
        let names: Vec<&str> = graphs.iter().map(|(name, _, _)| name.as_str()).collect();
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
        None => out.push_str(&graph.dot),
        Some(path) => {
            write(path, &graph.dot)?;
            report(json, out, &[(name, path.clone())]);
        }
    }
    Ok(Outcome::Holds)
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
    graphs: &[(String, &str, Graph)],
    json: bool,
    out: &mut Out,
) -> Result<Outcome, CliError> {
    let mut files: BTreeMap<String, &str> = BTreeMap::new();
    for (name, _, _) in graphs {
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
    for (name, _, graph) in graphs {
        let path = dir.join(file_name(name));
        write(&path, &graph.dot)?;
        written.push((name.as_str(), path));
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
    use super::{file_name, html};

    #[test]
    fn html_labels_escape_markup_and_break_lines() {
        assert_eq!(
            html("a<b>&\"c\"\r\nd"),
            "a&lt;b&gt;&amp;&quot;c&quot;<BR/>d"
        );
    }

    #[test]
    fn file_names_keep_plain_component_names_and_replace_the_rest() {
        assert_eq!(file_name("MACH1"), "MACH1.dot");
        assert_eq!(file_name("sup.v2"), "sup.v2.dot");
        assert_eq!(file_name("a/b c"), "a_b_c.dot");
        assert_eq!(file_name("../x"), "_x.dot");
        assert_eq!(file_name(""), "automaton.dot");
    }
}
