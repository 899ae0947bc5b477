//! `codegen dot` as a reader sees it: self-loops listed in their states
//! instead of drawn, parallel edges merged, the events a supervisor
//! disables, Petri nets, and the strongly connected components of large
//! automata. The assertions read the DOT text and the `--json` listing;
//! where Graphviz is installed, one test renders a real supervisor and
//! checks the picture shrank.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn codegen(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_codegen"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("the codegen binary runs")
}

/// The DOT text `codegen dot ARGS` prints (it must succeed).
fn dot(args: &[&str]) -> String {
    let run = codegen(&[&["dot"], args].concat());
    assert_eq!(
        run.status.code(),
        Some(0),
        "dot {args:?}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).expect("UTF-8")
}

/// The one graph of `codegen --json dot ARGS`.
fn listing(args: &[&str]) -> serde_json::Value {
    let run = codegen(&[&["--json", "dot"], args].concat());
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut graphs: Vec<serde_json::Value> = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(graphs.len(), 1);
    graphs.remove(0)
}

/// The edges of a DOT text: `(from, to)` node ids.
fn edges(dot: &str) -> Vec<(String, String)> {
    dot.lines()
        .filter_map(|l| {
            let (from, rest) = l.trim().split_once(" -> ")?;
            let to = rest.split([' ', ';']).next()?;
            Some((from.to_owned(), to.to_owned()))
        })
        .filter(|(from, _)| from != "__initial")
        .collect()
}

/// The lines declaring nodes whose id starts with `prefix` and a digit.
fn nodes<'d>(dot: &'d str, prefix: &str) -> Vec<&'d str> {
    dot.lines()
        .map(str::trim)
        .filter(|l| {
            l.strip_prefix(prefix)
                .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
                && !l.contains(" -> ")
        })
        .collect()
}

/// A file `name` with `text` in a fresh directory (kept alive by the
/// returned guard).
fn file(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path.to_str().unwrap().to_owned())
}

/// A door: `open` and `close` controllable, `beep` (uncontrollable) and
/// `tick` (controllable) looping in `shut`, `lock` never possible
/// anywhere, two events from `open` back to `shut`.
const DOOR: &str = r#"
name = "door"
initial = "shut"
controllable = ["open", "close", "slam", "tick", "lock"]
uncontrollable = ["beep"]
transitions = [
  ["shut", "open", "open"],
  ["shut", "beep", "shut"],
  ["shut", "tick", "shut"],
  ["open", "close", "shut"],
  ["open", "slam", "shut"],
]
"#;

#[test]
fn self_loops_are_listed_in_their_state_unless_drawn() {
    let (_dir, door) = file("door.toml", DOOR);
    let hidden = dot(&[&door]);
    assert!(
        !edges(&hidden).contains(&("s0".into(), "s0".into())),
        "{hidden}"
    );
    assert!(hidden.contains("⟲ tick, beep"), "{hidden}");
    assert!(hidden.contains("self-loops: tick, beep"), "{hidden}");
    assert!(hidden.contains("2 self-loops listed"), "{hidden}");

    let drawn = dot(&[&door, "--self-loops"]);
    let loops = edges(&drawn)
        .into_iter()
        .filter(|(a, b)| a == "s0" && b == "s0")
        .count();
    // One solid edge for `tick`, one dashed for `beep`.
    assert_eq!(loops, 2, "{drawn}");
    assert!(!drawn.contains('⟲'), "{drawn}");
    assert!(drawn.contains("s0 -> s0 [label=\"beep\", style=dashed];"));

    let graph = listing(&[&door]);
    assert_eq!(
        graph["states"],
        serde_json::json!([{ "state": "shut", "self_loops": ["tick", "beep"], "disabled": [] }])
    );
}

#[test]
fn parallel_edges_are_one_edge_with_one_event_per_line() {
    let (_dir, door) = file("door.toml", DOOR);
    let text = dot(&[&door]);
    assert!(
        text.contains("  s1 -> s0 [label=\"close\\nslam\"];"),
        "{text}"
    );
    assert_eq!(edges(&text).len(), 2, "{text}");
}

#[test]
fn a_real_supervisor_keeps_every_self_loop_in_its_labels() {
    // 32 states, 325 transitions of which 149 self-loops.
    let sup = "models/boiler/sup/sup_main_start.toml";
    let graph = listing(&[sup]);
    assert_eq!(graph["view"], "full");
    assert_eq!(graph["nodes"], 32);
    let text = graph["dot"].as_str().unwrap();
    assert!(edges(text).iter().all(|(a, b)| a != b), "no loop drawn");
    let listed: usize = graph["states"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["self_loops"].as_array().unwrap().len())
        .sum();
    assert_eq!(listed, 149);
    // The rest, merged: 197 edges with the loops (37 of them), 160 without.
    assert_eq!(graph["edges"], 160);
    assert_eq!(listing(&[sup, "--self-loops"])["edges"], 197);
}

#[test]
fn disabled_events_without_a_plant_are_the_controllable_ones_not_possible() {
    let (_dir, door) = file("door.toml", DOOR);
    let graph = listing(&[&door, "--disabled"]);
    assert_eq!(
        graph["states"],
        serde_json::json!([
            { "state": "shut", "self_loops": ["tick", "beep"], "disabled": ["close", "slam", "lock"] },
            { "state": "open", "self_loops": [], "disabled": ["open", "tick", "lock"] },
        ])
    );
    let text = graph["dot"].as_str().unwrap();
    assert!(
        text.contains("<FONT POINT-SIZE=\"10\" COLOR=\"red\">✗ close, slam, lock</FONT>"),
        "{text}"
    );
    // Without the flag nothing is said about disabled events.
    assert!(!dot(&[&door]).contains('✗'));
    // A net's flags are refused on an automaton.
    let run = codegen(&["dot", &door, "--uncontrollable", "open"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("door.toml: --uncontrollable"), "{stderr}");
}

#[test]
fn disabled_events_with_a_plant_are_those_of_condat() {
    let dir = tempfile::tempdir().unwrap();
    let sup = dir.path().join("sup.gen");
    let sup = sup.to_str().unwrap();
    let sf = "models/bench/smallfactory";
    let (m1, m2) = (format!("{sf}/MACH1.gen"), format!("{sf}/MACH2.gen"));
    let run = codegen(&[
        "synth",
        "--plant",
        &m1,
        &m2,
        "--spec",
        &format!("{sf}/BUFSPEC.gen"),
        &format!("{sf}/BRSPEC.gen"),
        "-o",
        sup,
    ]);
    assert_eq!(run.status.code(), Some(0));
    let graph = listing(&[sup, "--disabled", "--plant", &m1, &m2]);
    let disabled: Vec<(String, Vec<String>)> = graph["states"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let events = s["disabled"].as_array().unwrap();
            let events = events.iter().map(|e| e.as_str().unwrap().to_owned());
            (s["state"].as_str().unwrap().to_owned(), events.collect())
        })
        .collect();
    let expected = [
        ("0.0.0.0", "e21"),
        ("1.0.0.0", "e21"),
        ("0.0.1.0", "e11"),
        ("2.0.0.0", "e21"),
        ("0.1.1.0", "e11"),
        ("0.2.1.1", "e11"),
        ("2.2.0.1", "e13"),
    ];
    let expected: Vec<(String, Vec<String>)> = expected
        .iter()
        .map(|(s, e)| (s.to_string(), vec![e.to_string()]))
        .collect();
    assert_eq!(disabled, expected);

    // --plant without --disabled is a usage error.
    let run = codegen(&["dot", sup, "--plant", &m1]);
    assert_eq!(run.status.code(), Some(2));
}

/// A net with an arc of weight 2 and 3 tokens in one place.
const NET: &str = r#"
name = "pairs"
places = [
  { id = "parts", tokens = 3 },
  { id = "pairs" },
]
transitions = [
  { id = "pair", controllable = true, input = { parts = 2 }, output = { pairs = 1 } },
  { id = "ship", controllable = false, input = { pairs = 1 } },
]
"#;

#[test]
fn a_net_has_one_node_per_place_and_transition_and_its_arc_weights() {
    let (_dir, net) = file("pairs.toml", NET);
    let text = dot(&[&net]);
    assert_eq!(nodes(&text, "p").len(), 2, "{text}");
    assert_eq!(nodes(&text, "t").len(), 2, "{text}");
    assert!(
        text.contains("p0 [shape=circle, label=\"parts\\n●●●\"]"),
        "{text}"
    );
    assert!(text.contains("p0 -> t0 [label=\"2\"];"), "{text}");
    assert!(text.contains("t0 -> p1;"), "{text}");
    assert!(text.contains("p1 -> t1;"), "{text}");
    assert!(
        text.contains("t1 [shape=box, height=0.3, label=\"ship\", style=dashed]"),
        "{text}"
    );
    assert_eq!(edges(&text).len(), 3);

    // Automaton flags are refused on a net, with the file named.
    let run = codegen(&["dot", &net, "--self-loops"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("pairs.toml: --self-loops"), "{stderr}");
}

#[test]
fn a_bad_net_is_refused_at_its_line() {
    let (_dir, net) = file("bad.toml", &NET.replace("parts = 2", "nowhere = 2"));
    let run = codegen(&["dot", &net]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("bad.toml:8:"), "{stderr}");
    assert!(stderr.contains("`nowhere`"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn the_control_places_of_a_supervised_net_are_red() {
    let text = dot(&[
        "models/petri/mixers.toml",
        "--constraints",
        "models/petri/mixers.constraints.toml",
    ]);
    // 9 plant places and the constraint's control place; 8 transitions.
    assert_eq!(nodes(&text, "p").len(), 10, "{text}");
    assert_eq!(nodes(&text, "t").len(), 8, "{text}");
    let red: Vec<&str> = nodes(&text, "p")
        .into_iter()
        .filter(|l| l.contains("color=red"))
        .collect();
    assert_eq!(red.len(), 1, "{text}");
    assert!(red[0].starts_with("p9 "), "{red:?}");
    // D_c = [-1 1 0 0 -1 1 0 0]: four arcs, all red.
    let arcs = text.lines().filter(|l| l.contains("p9")).count();
    assert_eq!(arcs, 1 + 4, "{text}");
    assert!(
        text.contains("1 control place (red) added by the constraints"),
        "{text}"
    );
    let plain = dot(&["models/petri/mixers.toml"]);
    assert!(!plain.contains("red"), "{plain}");
}

/// Two cycles and a dead end: 0 <-> 1 -> 2 <-> 3 -> 4.
const CHAIN: &str = r#"
name = "chain"
initial = "0"
controllable = ["a", "b"]
transitions = [
  ["0", "a", "1"], ["1", "a", "0"], ["1", "b", "2"],
  ["2", "a", "3"], ["3", "a", "2"], ["3", "b", "4"], ["2", "b", "2"],
]
"#;

#[test]
fn the_summary_has_one_node_per_strongly_connected_component() {
    let (_dir, chain) = file("chain.toml", CHAIN);
    let graph = listing(&[&chain, "--summary"]);
    assert_eq!(graph["view"], "summary");
    assert_eq!(graph["nodes"], 3);
    assert_eq!(graph["edges"], 2);
    let text = graph["dot"].as_str().unwrap();
    assert_eq!(nodes(text, "c").len(), 3, "{text}");
    assert!(
        text.contains("c1 [label=\"2 and 1 more\\n2 states, 3 transitions inside\"]"),
        "{text}"
    );
    assert!(text.contains("c0 -> c1 [label=\"1 transition\\nb\"];"));
    assert!(text.contains("5 states and 7 transitions as 3 strongly connected components"));

    // Chosen by size beyond --max-states, unless --full.
    let graph = listing(&[&chain, "--max-states", "4"]);
    assert_eq!(graph["view"], "summary");
    assert!(graph["dot"]
        .as_str()
        .unwrap()
        .contains("5 states, more than --max-states 4"));
    assert_eq!(
        listing(&[&chain, "--max-states", "4", "--full"])["view"],
        "full"
    );
    assert_eq!(listing(&[&chain, "--max-edges", "3"])["view"], "summary");
    assert_eq!(listing(&[&chain])["view"], "full");
    // Flags about states are not dropped unsaid.
    let graph = listing(&[&chain, "--summary", "--disabled"]);
    assert!(graph["dot"]
        .as_str()
        .unwrap()
        .contains("--disabled and --self-loops apply with --full"));
}

#[test]
fn a_large_strongly_connected_supervisor_is_summarised_as_such() {
    // 406 states, 5,525 transitions: one component.
    let graph = listing(&["models/boiler/sup/sup_pilot_seq.toml"]);
    assert_eq!(graph["view"], "summary");
    assert_eq!(graph["nodes"], 1);
    let text = graph["dot"].as_str().unwrap();
    assert!(
        text.contains("406 states, more than --max-states 100"),
        "{text}"
    );
    assert!(text.contains("strongly connected: every state reaches every other"));
}

/// Width × height in points of an SVG Graphviz wrote.
fn svg_area(svg: &str) -> f64 {
    let attribute = |name: &str| -> f64 {
        let start = svg.find(&format!("{name}=\"")).unwrap() + name.len() + 2;
        let value: String = svg[start..]
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        value.parse().unwrap()
    };
    attribute("width") * attribute("height")
}

/// Renders `dot_text` with Graphviz; `None` when it is not installed.
fn render(dot_text: &str) -> Option<String> {
    use std::io::Write as _;
    let mut child = Command::new("dot")
        .arg("-Tsvg")
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .ok()?;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(dot_text.as_bytes())
        .unwrap();
    let output = child.wait_with_output().unwrap();
    assert!(output.status.success());
    Some(String::from_utf8(output.stdout).unwrap())
}

#[test]
fn graphviz_draws_the_32_state_supervisor_in_less_than_half_the_area() {
    let sup = "models/boiler/sup/sup_main_start.toml";
    // The drawing before self-loops were hidden: every loop an edge,
    // events separated by commas, circles, ranks left to right.
    let before = dot(&[sup, "--self-loops"])
        .replace("rankdir=TB", "rankdir=LR")
        .replace("\\n", ", ")
        .replace("node [shape=ellipse]", "node [shape=circle]")
        .replace("peripheries=2", "shape=doublecircle");
    let Some(before) = render(&before) else {
        eprintln!("Graphviz `dot` is not installed: rendering not checked");
        return;
    };
    let after = render(&dot(&[sup])).unwrap();
    let (before, after) = (svg_area(&before), svg_area(&after));
    assert!(
        after * 2.0 < before,
        "{after} pt² is not half of {before} pt²"
    );
}
