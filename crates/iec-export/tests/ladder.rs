//! The ladder (LD) rendering (`iec_export::ladder`) executed from its
//! PLCopen XML: a small ladder interpreter reads the `<LD>` body as a PLC
//! tool would (rungs from the power rails, contacts and coils joined by
//! their connections), runs the rungs top to bottom, and must agree with
//! the automata on every state and every event, exhaustively.
//!
//! Every test also writes its rendering wrapped in a minimal TC6 project
//! to `$CARGO_TARGET_TMPDIR/ladder/<name>.xml`, for validation against the
//! official schema (docs/ladder.md has the command).

use des::automaton::StateId;
use iec_export::ladder::{self, Ladder, RungKind, DEFAULT_RUNG_LIMIT};
use plc_project::{self as project, Action, Drive, Project};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

const TC6: &str = "http://www.plcopen.org/xml/tc6_0201";

fn models() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models")
}

fn load(name: &str) -> Project {
    project::load(&models().join(name)).expect("seed project loads")
}

/// `ladder` alone in a TC6 v2.01 project, written for schema validation.
fn wrapped(ladder: &Ladder, file: &str) -> String {
    let xml = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<project xmlns="{TC6}">
  <fileHeader companyName="codegen tests" productName="codegen" productVersion="0" creationDateTime="2024-01-01T00:00:00"/>
  <contentHeader name="{name}">
    <coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo>
  </contentHeader>
  <types>
    <dataTypes/>
    <pous>
{pou}    </pous>
  </types>
  <instances><configurations/></instances>
</project>
"#,
        name = ladder.name,
        pou = ladder.pou_xml
    );
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("ladder");
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join(file), &xml).expect("write the wrapped XML");
    xml
}

// ---------------------------------------------------------------------
// A ladder interpreter over PLCopen XML.

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Storage {
    Plain,
    Set,
    Reset,
}

#[derive(Debug)]
enum Node {
    Rail,
    Contact { var: String, negated: bool },
    Coil { var: String, storage: Storage },
}

/// One rung: its coils in document order, and its comment.
#[derive(Debug)]
struct XmlRung {
    coils: Vec<u64>,
    comment: String,
}

/// A function block read from its XML: declared variables, every node
/// with what feeds it, the rungs in scan order.
#[derive(Debug)]
struct Plc {
    inputs: Vec<String>,
    outputs: Vec<String>,
    locals: Vec<String>,
    vars: BTreeMap<String, bool>,
    nodes: HashMap<u64, (Node, Vec<u64>)>,
    rungs: Vec<XmlRung>,
}

fn attr<'a>(node: roxmltree::Node<'a, '_>, name: &str) -> &'a str {
    node.attribute(name)
        .unwrap_or_else(|| panic!("<{}> has no {name}", node.tag_name().name()))
}

fn child<'a, 'i>(node: roxmltree::Node<'a, 'i>, name: &str) -> Option<roxmltree::Node<'a, 'i>> {
    node.children().find(|c| c.tag_name().name() == name)
}

fn text_of(node: roxmltree::Node<'_, '_>) -> String {
    node.descendants()
        .filter(|n| n.is_text())
        .map(|n| n.text().unwrap_or(""))
        .collect()
}

impl Plc {
    fn parse(xml: &str) -> Plc {
        let doc = roxmltree::Document::parse(xml).expect("well-formed XML");
        let pou = doc
            .descendants()
            .find(|n| n.has_tag_name((TC6, "pou")))
            .expect("a <pou> in the TC6 namespace");
        assert_eq!(attr(pou, "pouType"), "functionBlock");
        let interface = child(pou, "interface").expect("<interface>");
        let mut vars = BTreeMap::new();
        let mut section = |tag: &str| -> Vec<String> {
            let mut names = Vec::new();
            for list in interface.children().filter(|c| c.tag_name().name() == tag) {
                for v in list.children().filter(|c| c.is_element()) {
                    let ty = child(v, "type").expect("<type>");
                    assert!(child(ty, "BOOL").is_some(), "every variable is a BOOL");
                    let init = child(v, "initialValue")
                        .and_then(|i| child(i, "simpleValue"))
                        .map(|s| attr(s, "value"));
                    let name = attr(v, "name").to_owned();
                    vars.insert(name.clone(), init == Some("TRUE"));
                    names.push(name);
                }
            }
            names
        };
        let inputs = section("inputVars");
        let outputs = section("outputVars");
        let locals = section("localVars");

        let ld = child(child(pou, "body").expect("<body>"), "LD").expect("an <LD> body");
        let mut nodes = HashMap::new();
        let mut rails = Vec::new();
        let mut comments = Vec::new();
        let mut coils = Vec::new();
        for el in ld.children().filter(|c| c.is_element()) {
            let id: u64 = attr(el, "localId").parse().expect("numeric localId");
            let feeds: Vec<u64> = child(el, "connectionPointIn")
                .map(|cp| {
                    cp.children()
                        .filter(|c| c.tag_name().name() == "connection")
                        .map(|c| attr(c, "refLocalId").parse().expect("numeric refLocalId"))
                        .collect()
                })
                .unwrap_or_default();
            let var = || text_of(child(el, "variable").expect("<variable>"));
            let node = match el.tag_name().name() {
                "comment" => {
                    comments.push(text_of(el));
                    continue;
                }
                "rightPowerRail" => continue,
                "leftPowerRail" => {
                    let pos = child(el, "position").expect("<position>");
                    let y: f64 = attr(pos, "y").parse().expect("numeric y");
                    rails.push((id, y));
                    Node::Rail
                }
                "contact" => Node::Contact {
                    var: var(),
                    negated: el.attribute("negated") == Some("true"),
                },
                "coil" => {
                    coils.push(id);
                    Node::Coil {
                        var: var(),
                        storage: match el.attribute("storage").unwrap_or("none") {
                            "none" => Storage::Plain,
                            "set" => Storage::Set,
                            "reset" => Storage::Reset,
                            other => panic!("storage {other}"),
                        },
                    }
                }
                other => panic!("unexpected LD element <{other}>"),
            };
            assert!(
                nodes.insert(id, (node, feeds)).is_none(),
                "localId {id} twice"
            );
        }
        // A coil belongs to the rung of the rail its power comes from.
        let rail_of = |mut id: u64| loop {
            let (node, feeds) = &nodes[&id];
            if matches!(node, Node::Rail) {
                return id;
            }
            id = *feeds.first().expect("every contact and coil is fed");
        };
        let mut by_rail: HashMap<u64, Vec<u64>> = HashMap::new();
        for c in coils {
            by_rail.entry(rail_of(c)).or_default().push(c);
        }
        assert_eq!(comments.len(), rails.len(), "one comment per rung");
        let mut order: Vec<usize> = (0..rails.len()).collect();
        order.sort_by(|&a, &b| rails[a].1.total_cmp(&rails[b].1));
        assert!(
            order.iter().copied().eq(0..rails.len()),
            "rungs are written top to bottom"
        );
        let rungs = rails
            .iter()
            .zip(comments)
            .map(|(&(rail, _), comment)| XmlRung {
                coils: by_rail.remove(&rail).expect("every rung has a coil"),
                comment,
            })
            .collect();
        assert!(by_rail.is_empty());
        Plc {
            inputs,
            outputs,
            locals,
            vars,
            nodes,
            rungs,
        }
    }

    /// Whether node `id` is powered; `known` holds the nodes of the rung
    /// already evaluated (series blocks of parallel contacts share their
    /// feeds: without it the work would grow as the product of the
    /// blocks' sizes).
    fn power(&self, id: u64, known: &mut HashMap<u64, bool>) -> bool {
        if let Some(&p) = known.get(&id) {
            return p;
        }
        let (node, feeds) = &self.nodes[&id];
        let mut fed = || feeds.iter().any(|&f| self.power(f, known));
        let p = match node {
            Node::Rail => true,
            Node::Contact { var, negated } => fed() && (self.vars[var] != *negated),
            Node::Coil { .. } => fed(),
        };
        known.insert(id, p);
        p
    }

    /// One call: the inputs in `on` TRUE, every other input FALSE; the
    /// rungs top to bottom, each rung's coils from the power its contacts
    /// give before any of them writes.
    fn call(&mut self, on: &[&str]) {
        for input in &self.inputs {
            self.vars
                .insert(input.clone(), on.contains(&input.as_str()));
        }
        for rung in &self.rungs {
            let mut known = HashMap::new();
            let powered: Vec<(String, Storage, bool)> = rung
                .coils
                .iter()
                .map(|&c| match &self.nodes[&c].0 {
                    Node::Coil { var, storage } => {
                        (var.clone(), *storage, self.power(c, &mut known))
                    }
                    _ => unreachable!(),
                })
                .collect();
            for (var, storage, power) in powered {
                assert!(self.vars.contains_key(&var), "coil of undeclared {var}");
                match (storage, power) {
                    (Storage::Plain, p) => {
                        self.vars.insert(var, p);
                    }
                    (Storage::Set, true) => {
                        self.vars.insert(var, true);
                    }
                    (Storage::Reset, true) => {
                        self.vars.insert(var, false);
                    }
                    (_, false) => {}
                }
            }
        }
    }

    fn get(&self, var: &str) -> bool {
        *self
            .vars
            .get(var)
            .unwrap_or_else(|| panic!("{var} declared"))
    }

    fn set(&mut self, var: &str, value: bool) {
        assert!(self.vars.contains_key(var), "{var} declared");
        self.vars.insert(var.to_owned(), value);
    }
}

// ---------------------------------------------------------------------
// The reference: the automata, the project's actions and state maps.

/// What the controller's state would be: one state per supervisor and
/// the level of every output the ladder writes.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Expected {
    states: Vec<StateId>,
    levels: BTreeMap<usize, bool>,
}

/// Events in execution order (uncontrollable, then controllable, each in
/// declaration order).
fn execution_order(p: &Project) -> Vec<usize> {
    let u = (0..p.events.len()).filter(|&e| !p.events[e].controllable);
    let c = (0..p.events.len()).filter(|&e| p.events[e].controllable);
    u.chain(c).collect()
}

fn local(p: &Project, j: usize, e: usize) -> Option<des::EventId> {
    p.supervisors[j].local(e).map(|(_, id)| id)
}

/// Whether every supervisor that has `e` defines it in `states`.
fn feasible(p: &Project, states: &[StateId], e: usize) -> bool {
    (0..p.supervisors.len()).all(|j| {
        local(p, j, e).is_none_or(|id| {
            p.supervisors[j]
                .automaton
                .successor(states[j], id)
                .is_some()
        })
    })
}

/// `e` executed: each supervisor along δ (an undefined event moves
/// nothing), then the event's switch actions.
fn execute(p: &Project, x: &mut Expected, e: usize) {
    for j in 0..p.supervisors.len() {
        if let Some(id) = local(p, j, e) {
            if let Some(t) = p.supervisors[j].automaton.successor(x.states[j], id) {
                x.states[j] = t;
            }
        }
    }
    for action in &p.events[e].actions {
        match *action {
            Action::Set(o) if x.levels.contains_key(&o) => {
                x.levels.insert(o, true);
            }
            Action::Clear(o) if x.levels.contains_key(&o) => {
                x.levels.insert(o, false);
            }
            _ => {}
        }
    }
}

fn switch_outputs(p: &Project) -> Vec<usize> {
    p.switches
        .iter()
        .flat_map(|s| s.positions.iter().map(|&(_, o)| o))
        .collect()
}

/// Every state vector of the project's supervisors.
fn state_vectors(p: &Project) -> Vec<Vec<StateId>> {
    let mut all = vec![Vec::new()];
    for sup in &p.supervisors {
        all = all
            .into_iter()
            .flat_map(|v| {
                sup.automaton.states().map(move |s| {
                    let mut v = v.clone();
                    v.push(s);
                    v
                })
            })
            .collect();
    }
    all
}

/// Loads `x` into the PLC's memory: one-hot state bits, switch outputs.
fn preset(plc: &mut Plc, ladder: &Ladder, x: &Expected) {
    for (j, bits) in ladder.interface.states.iter().enumerate() {
        for (s, bit) in bits.iter().enumerate() {
            plc.set(bit, s == x.states[j].index());
        }
    }
    for (&o, &level) in &x.levels {
        plc.set(ladder.interface.outputs[o].as_ref().unwrap(), level);
    }
}

/// The PLC's memory agrees with `x`: state bits one-hot at `x`, enables
/// the events every supervisor defines, switch outputs at `x`'s levels,
/// state-mapped outputs from `x`'s states, pending bits clear.
fn check(plc: &Plc, ladder: &Ladder, p: &Project, x: &Expected, what: &str) {
    for (j, bits) in ladder.interface.states.iter().enumerate() {
        let on: Vec<usize> = (0..bits.len()).filter(|&s| plc.get(&bits[s])).collect();
        assert_eq!(on, vec![x.states[j].index()], "{what}: supervisor {j}");
    }
    for (e, enable) in ladder.interface.enables.iter().enumerate() {
        if let Some(enable) = enable {
            assert_eq!(
                plc.get(enable),
                feasible(p, &x.states, e),
                "{what}: {enable}"
            );
        }
    }
    for (&o, &level) in &x.levels {
        let var = ladder.interface.outputs[o].as_ref().unwrap();
        assert_eq!(plc.get(var), level, "{what}: {var}");
    }
    for (o, output) in p.outputs.iter().enumerate() {
        if let Drive::States(maps) = &output.drive {
            let level = maps
                .iter()
                .any(|(j, states)| states.contains(&x.states[*j]));
            let var = ladder.interface.outputs[o].as_ref().unwrap();
            assert_eq!(plc.get(var), level, "{what}: {var}");
        }
    }
    for bit in &ladder.interface.pending {
        assert!(!plc.get(bit), "{what}: pending {bit} left set");
    }
}

/// Every rung of the list is the rung of the XML at the same place, and
/// the interface declares exactly the variables the rendering names.
fn xml_matches_the_rung_list(plc: &Plc, ladder: &Ladder) {
    assert_eq!(plc.rungs.len(), ladder.rungs.len());
    for (k, (xml, rung)) in plc.rungs.iter().zip(&ladder.rungs).enumerate() {
        assert_eq!(xml.comment, format!("Rung {}: {}", k + 1, rung.text));
        assert_eq!(xml.coils.len(), rung.coils.len(), "rung {}", k + 1);
    }
    let i = &ladder.interface;
    let mut inputs = vec![i.init.clone()];
    inputs.extend(i.events.iter().cloned());
    assert_eq!(plc.inputs, inputs);
    let mut outputs: Vec<String> = i.states.iter().flatten().cloned().collect();
    outputs.extend(i.enables.iter().flatten().cloned());
    outputs.extend(i.outputs.iter().flatten().cloned());
    let mut declared = plc.outputs.clone();
    declared.sort();
    outputs.sort();
    assert_eq!(declared, outputs);
    assert_eq!(plc.locals, i.pending);
}

/// The exhaustive check: from every state vector (and every level of the
/// switch outputs), a call with no event, with each single event, with
/// each pair of events in rung order that can execute one after the
/// other, and with INIT, leaves the memory the automata and the project's
/// actions prescribe. Returns the number of calls checked.
fn exhaustive(p: &Project, ladder: &Ladder) -> usize {
    let mut plc = Plc::parse(&wrapped(ladder, &format!("{}.xml", ladder.name)));
    xml_matches_the_rung_list(&plc, ladder);
    let outs = switch_outputs(p);
    let order = execution_order(p);
    let initial: Vec<StateId> = p
        .supervisors
        .iter()
        .map(|s| s.automaton.initial().unwrap())
        .collect();
    let mut calls = 0;
    for states in state_vectors(p) {
        for mask in 0..1u32 << outs.len() {
            let levels: BTreeMap<usize, bool> = outs
                .iter()
                .enumerate()
                .map(|(k, &o)| (o, mask >> k & 1 == 1))
                .collect();
            let start = Expected {
                states: states.clone(),
                levels,
            };
            let mut cases: Vec<Vec<usize>> = vec![vec![]];
            cases.extend(order.iter().map(|&e| vec![e]));
            for (a, &e1) in order.iter().enumerate() {
                for &e2 in &order[a + 1..] {
                    let mut after = start.clone();
                    if feasible(p, &after.states, e1) {
                        execute(p, &mut after, e1);
                        if feasible(p, &after.states, e2) {
                            cases.push(vec![e1, e2]);
                        }
                    }
                }
            }
            for events in cases {
                let mut expect = start.clone();
                for &e in &events {
                    execute(p, &mut expect, e);
                }
                preset(&mut plc, ladder, &start);
                let on: Vec<&str> = events
                    .iter()
                    .map(|&e| ladder.interface.events[e].as_str())
                    .collect();
                plc.call(&on);
                let names: Vec<&str> = events.iter().map(|&e| p.events[e].name.as_str()).collect();
                check(&plc, ladder, p, &expect, &format!("{start:?} + {names:?}"));
                calls += 1;
            }
            preset(&mut plc, ladder, &start);
            plc.call(&[&ladder.interface.init]);
            let reset = Expected {
                states: initial.clone(),
                levels: outs
                    .iter()
                    .map(|&o| {
                        (
                            o,
                            matches!(p.outputs[o].drive, Drive::Actions { initial: true }),
                        )
                    })
                    .collect(),
            };
            check(&plc, ladder, p, &reset, &format!("{start:?} + INIT"));
            calls += 1;
        }
    }
    println!("{}: {calls} calls checked", ladder.name);
    calls
}

/// The transitions the rung list implements, (supervisor, from, event,
/// to), parked or not.
fn transition_rungs(ladder: &Ladder) -> Vec<(usize, StateId, usize, StateId)> {
    ladder
        .rungs
        .iter()
        .filter_map(|r| match r.kind {
            RungKind::Transition {
                supervisor,
                from,
                event,
                to,
                ..
            } => Some((supervisor, from, event, to)),
            _ => None,
        })
        .collect()
}

/// One transition rung per transition that changes state, none for a
/// self-loop.
fn one_rung_per_moving_transition(p: &Project, ladder: &Ladder) {
    let mut rungs = transition_rungs(ladder);
    let mut moving = Vec::new();
    for (j, sup) in p.supervisors.iter().enumerate() {
        for &(e, id) in &sup.local_events {
            for s in sup.automaton.states() {
                if let Some(t) = sup.automaton.successor(s, id).filter(|&t| t != s) {
                    moving.push((j, s, e, t));
                }
            }
        }
    }
    rungs.sort();
    moving.sort();
    assert_eq!(rungs, moving);
}

#[test]
fn the_motivating_example_ladder_is_the_automaton_on_every_state_and_event() {
    let p = load("motivating.plc.toml");
    let ladder = ladder::render(&p, DEFAULT_RUNG_LIMIT).unwrap();
    one_rung_per_moving_transition(&p, &ladder);
    // Init, switch init, 13 transitions (Table 3.1 rungs 2-14), a switch
    // rung for each of the 5 commands, 5 enables.
    assert_eq!(ladder.rungs.len(), 1 + 1 + 13 + 5 + 5);
    assert!(ladder.interface.pending.is_empty());
    // 10 states x 8 switch levels x (no event, 9 single, feasible pairs, INIT).
    let calls = exhaustive(&p, &ladder);
    assert!(calls > 10 * 8 * 11, "{calls}");
}

#[test]
fn the_press_ladder_is_the_lessons_state_machine_on_every_state_and_event() {
    let p = load("press.plc.toml");
    let ladder = ladder::render(&p, DEFAULT_RUNG_LIMIT).unwrap();
    one_rung_per_moving_transition(&p, &ladder);
    // The lesson's transitions A-G, in execution order of their events.
    let names: Vec<String> = transition_rungs(&ladder)
        .iter()
        .map(|&(j, s, e, t)| {
            let a = &p.supervisors[j].automaton;
            format!(
                "{}-{}-{}",
                a.state_name(s),
                p.events[e].name,
                a.state_name(t)
            )
        })
        .collect();
    assert_eq!(
        names,
        [
            "1-auto-2",
            "3-stop-5",
            "5-reset-1",
            "2-part_in-3",
            "6-part_out-2",
            "3-at_bottom-4",
            "4-at_top-6",
        ]
        .map(String::from)
        .to_vec()
    );
    // Init, 7 transitions, 4 outputs (Fig. 20.7's output logic).
    assert_eq!(ladder.rungs.len(), 1 + 7 + 4);
    exhaustive(&p, &ladder);
}

#[test]
fn the_state7_press_ladder_holds_too() {
    let p = load("press7.plc.toml");
    let ladder = ladder::render(&p, DEFAULT_RUNG_LIMIT).unwrap();
    one_rung_per_moving_transition(&p, &ladder);
    exhaustive(&p, &ladder);
}

/// A project made to trip the evaluation order: a chain and a cycle under
/// one event in one supervisor, a cycle under the same event in another,
/// a controllable self-loop, a command one supervisor never allows, a
/// switch, and an output mapped on both.
fn hazards(dir: &Path) -> Project {
    std::fs::write(
        dir.join("chain.toml"),
        r#"name = "chain"
initial = "0"
marked = ["0"]
controllable = ["go_hi", "go_lo", "close"]
uncontrollable = ["t", "u", "v"]
states = ["0", "1", "2", "3", "4", "5"]
transitions = [
  ["0", "t", "1"], ["1", "t", "2"], ["2", "t", "3"], ["4", "t", "4"],
  ["3", "u", "4"], ["4", "u", "5"], ["5", "u", "3"], ["1", "u", "4"],
  ["0", "go_hi", "2"], ["2", "go_lo", "0"], ["5", "close", "0"],
  ["3", "v", "0"],
]
"#,
    )
    .unwrap();
    std::fs::write(
        dir.join("ring.toml"),
        r#"name = "ring"
initial = "r0"
marked = ["r0"]
controllable = ["go_hi", "go_lo", "close"]
uncontrollable = ["t", "v"]
states = ["r0", "r1", "r2"]
transitions = [
  ["r0", "t", "r1"], ["r1", "t", "r2"], ["r2", "t", "r0"],
  ["r1", "v", "r0"], ["r0", "go_hi", "r0"], ["r2", "go_lo", "r1"],
]
"#,
    )
    .unwrap();
    let path = dir.join("hazards.plc.toml");
    std::fs::write(
        &path,
        r#"[plc]
name = "hazards"
scan_period_ms = 10

[inputs]
i_t = {}
i_u = {}
i_v = {}

[outputs]
hi = {}
lo = {}
lamp = { states = { chain = ["2", "3"], ring = ["r1"] } }

[switches]
valve = { hi = "hi", lo = "lo" }

[events]
t = { rising = "i_t" }
u = { rising = "i_u" }
v = { falling = "i_v" }
go_hi = { controllable = true, switch = { valve = "hi" } }
go_lo = { controllable = true, switch = { valve = "lo" } }
close = { controllable = true, switch = { valve = "off" } }

[[supervisor]]
name = "chain"
file = "chain.toml"

[[supervisor]]
name = "ring"
file = "ring.toml"
"#,
    )
    .unwrap();
    project::load(&path).expect("the hazard project loads")
}

#[test]
fn chains_and_cycles_under_one_event_take_one_step_per_event() {
    let dir = tempfile::tempdir().unwrap();
    let p = hazards(dir.path());
    let ladder = ladder::render(&p, DEFAULT_RUNG_LIMIT).unwrap();
    one_rung_per_moving_transition(&p, &ladder);
    // The u-cycle of `chain` and the t-cycle of `ring` each park once.
    let parked = ladder
        .rungs
        .iter()
        .filter(|r| matches!(r.kind, RungKind::Transition { parked: true, .. }))
        .count();
    let unparks = ladder
        .rungs
        .iter()
        .filter(|r| matches!(r.kind, RungKind::Unpark { .. }))
        .count();
    assert_eq!((parked, unparks), (2, 2));
    assert_eq!(ladder.interface.pending.len(), 2);
    // `close`: `ring` has it and never allows it.
    let enable = |name: &str| {
        let e = p.event(name).unwrap();
        ladder
            .rungs
            .iter()
            .find(|r| r.kind == RungKind::Enable { event: e })
            .unwrap()
    };
    assert!(enable("close").contacts.is_empty());
    assert_eq!(enable("close").coils[0].storage, ladder::Storage::Reset);
    assert_eq!(
        enable("go_hi").contacts.len(),
        2,
        "one block per supervisor"
    );
    exhaustive(&p, &ladder);
}

#[test]
fn a_ladder_over_the_limit_is_refused_naming_the_supervisor_line() {
    let p = load("press.plc.toml");
    let rungs = ladder::render(&p, DEFAULT_RUNG_LIMIT).unwrap().rungs.len();
    assert!(ladder::render(&p, rungs).is_ok());
    let err = ladder::render(&p, rungs - 1).unwrap_err();
    let (location, message) = err.located().expect("a located error");
    assert!(location.file.ends_with("press.plc.toml"), "{err}");
    assert_eq!(location.line, p.supervisors[0].line, "{err}");
    assert!(
        message.contains(&format!("{rungs} rungs"))
            && message.contains(&format!("limit of {}", rungs - 1))
            && message.contains("`press`"),
        "{err}"
    );
}

#[test]
fn a_project_with_a_petri_net_is_refused() {
    let p = project::load(&models().join("petri/mixers.plc.toml")).unwrap();
    let err = ladder::render(&p, DEFAULT_RUNG_LIMIT).unwrap_err();
    let (location, message) = err.located().expect("a located error");
    assert_eq!(location.line, p.nets[0].line, "{err}");
    assert!(message.contains("net `mixers`"), "{err}");
}

/// A symbolic supervisor's guards have no rungs: the conveyor module is
/// refused at the line of its `[[supervisor]]`, whatever the rung limit;
/// with guards that always hold it is its components' ladder.
#[test]
fn a_project_with_guards_is_refused_at_its_supervisor() {
    let p = load("module.plc.toml");
    let g = &p.guarded[0];
    let err = ladder::render(&p, usize::MAX).unwrap_err();
    let (location, message) = err.located().expect("a located error");
    assert!(location.file.ends_with("module.plc.toml"), "{err}");
    assert_eq!(location.line, g.line, "{err}");
    assert!(
        message.contains("symbolic supervisor `module`")
            && message.contains("10 command(s) guarded")
            && message.contains("Structured Text"),
        "{err}"
    );
    let mut always = p.clone();
    for eg in &mut always.guarded[0].guards {
        eg.root = 1;
        eg.nodes.clear();
    }
    let ladder = ladder::render(&always, usize::MAX).expect("no guard that matters");
    assert_eq!(ladder.interface.states.len(), p.supervisors.len());
}

/// `codegen plcopen --ladder`'s document: the controller, the program and
/// the ladder function block side by side in one project, the ladder's
/// rungs as rendered alone.
#[test]
fn the_ladder_joins_the_exported_project_as_a_third_pou() {
    use iec_export::{self as iec, IoMap};
    let p = load("motivating.plc.toml");
    let export = iec::export(&p, &IoMap::sequential(), "t").expect("exports");
    let ladder = ladder::render(&p, DEFAULT_RUNG_LIMIT).expect("renders");
    let xml = iec::plcopen::print_with(&export, std::slice::from_ref(&ladder.pou_xml));
    let doc = roxmltree::Document::parse(&xml).expect("well-formed");
    let pous: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("pou"))
        .map(|n| attr(n, "name"))
        .collect();
    assert_eq!(
        pous,
        [
            export.names.controller.as_str(),
            export.names.program.as_str(),
            ladder.name.as_str()
        ]
    );
    let count = |doc: &roxmltree::Document, tag: &str| {
        doc.descendants()
            .filter(|n| n.has_tag_name("pou") && attr(*n, "name") == ladder.name)
            .flat_map(|pou| pou.descendants())
            .filter(|n| n.has_tag_name(tag))
            .count()
    };
    let alone = wrapped(&ladder, "motivating.joined.xml");
    let alone = roxmltree::Document::parse(&alone).expect("well-formed");
    for tag in [
        "leftPowerRail",
        "contact",
        "coil",
        "rightPowerRail",
        "connection",
    ] {
        assert_eq!(count(&doc, tag), count(&alone, tag), "{tag}");
        assert!(count(&doc, tag) > 0, "{tag}");
    }
}

// ---------------------------------------------------------------------
// The fallback on reduced and localized supervisors.

/// The small factory (two machines and a buffer, models/bench) as a
/// project whose supervisor is synthesised, in a fresh directory.
fn small_factory(dir: &Path) -> PathBuf {
    let bench = models().join("bench/smallfactory");
    let bench = bench.display();
    let path = dir.join("factory.plc.toml");
    std::fs::write(
        &path,
        format!(
            r#"[plc]
name = "factory"
scan_period_ms = 10
max_commands_per_scan = 1

[inputs]
done1 = {{}}
break1 = {{}}
done2 = {{}}
break2 = {{}}

[events]
e10 = {{ rising = "done1" }}
e12 = {{ rising = "break1" }}
e20 = {{ rising = "done2" }}
e22 = {{ rising = "break2" }}
e11 = {{ controllable = true }}
e13 = {{ controllable = true }}
e21 = {{ controllable = true }}
e23 = {{ controllable = true }}

[[supervisor]]
name = "factory"
synthesize = {{ plants = ["{bench}/MACH?.gen"], specs = ["{bench}/*SPEC.gen"] }}
"#
        ),
    )
    .unwrap();
    path
}

/// The controllable events a project's supervisors allow in `states`.
fn allowed(p: &Project, states: &[StateId]) -> Vec<String> {
    (0..p.events.len())
        .filter(|&e| p.events[e].controllable && feasible(p, states, e))
        .map(|e| p.events[e].name.clone())
        .collect()
}

/// `steps` calls of the fitted ladder of `small` (the shrunk project),
/// one event each, chosen at random among those the full project's
/// supervisors allow, in lockstep with both projects' automata: the
/// ladder's state bits follow `small`'s automata, and its enables are
/// the events the *full* supervisor allows (the same closed loop).
/// Returns the number of events of each kind executed.
fn lockstep_with_the_full_supervisor(
    full: &Project,
    small: &Project,
    ladder: &Ladder,
    steps: usize,
) -> (usize, usize) {
    let mut plc = Plc::parse(&wrapped(ladder, &format!("{}.fitted.xml", ladder.name)));
    xml_matches_the_rung_list(&plc, ladder);
    let initial = |p: &Project| Expected {
        states: p
            .supervisors
            .iter()
            .map(|s| s.automaton.initial().unwrap())
            .collect(),
        levels: BTreeMap::new(),
    };
    let (mut big, mut x) = (initial(full), initial(small));
    plc.call(&[&ladder.interface.init]);
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut executed = (0, 0);
    for step in 0..steps {
        check(&plc, ladder, small, &x, &format!("step {step}"));
        let enables: Vec<String> = (0..small.events.len())
            .filter(|&e| {
                ladder.interface.enables[e]
                    .as_ref()
                    .is_some_and(|en| plc.get(en))
            })
            .map(|e| small.events[e].name.clone())
            .collect();
        assert_eq!(enables, allowed(full, &big.states), "step {step}");
        let possible: Vec<usize> = (0..full.events.len())
            .filter(|&e| feasible(full, &big.states, e))
            .collect();
        assert!(!possible.is_empty(), "step {step}: the closed loop blocks");
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let e = possible[(seed % possible.len() as u64) as usize];
        let name = &full.events[e].name;
        let se = small.event(name).expect("the same events");
        assert!(feasible(small, &x.states, se), "step {step}: {name}");
        execute(full, &mut big, e);
        execute(small, &mut x, se);
        plc.call(&[&ladder.interface.events[se]]);
        if full.events[e].controllable {
            executed.1 += 1;
        } else {
            executed.0 += 1;
        }
    }
    executed
}

/// The small factory's 12-state supervisor makes 29 rungs; reduced it is
/// 3 states beside the two machines, 20 rungs: under a limit of 28 the
/// ladder renders that form, says so, agrees with the automata on every
/// state and event, and allows what the full supervisor allows along a
/// random run.
#[test]
fn a_ladder_over_the_limit_falls_back_on_the_reduced_supervisor() {
    let dir = tempfile::tempdir().unwrap();
    let path = small_factory(dir.path());
    let full = project::load(&path).unwrap();
    let full_rungs = ladder::render(&full, usize::MAX).unwrap().rungs.len();
    assert_eq!(full_rungs, 29);
    let fitted =
        ladder::render_fitting(&full, full_rungs, |s| project::load_shrunk(&path, s)).unwrap();
    assert!(fitted.shrunk.is_none(), "the full ladder fits its own size");
    let limit = full_rungs - 1;
    assert!(ladder::render(&full, limit).is_err());
    let fitted = ladder::render_fitting(&full, limit, |s| project::load_shrunk(&path, s)).unwrap();
    let shrunk = fitted.shrunk.as_ref().expect("a smaller form fits");
    assert_eq!(shrunk.shrink, project::Shrink::Reduce);
    assert_eq!(shrunk.full_rungs, full_rungs);
    let ladder = &fitted.ladder;
    assert_eq!(ladder.rungs.len(), 20);
    let small = &shrunk.project;
    let names: Vec<&str> = small.supervisors.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["factory.MACH1", "factory.MACH2", "factory"]);
    let reduced = small.supervisors[2].automaton.num_states();
    assert!(reduced < full.supervisors[0].automaton.num_states());
    for said in [
        format!(
            "supervisor 'factory' (synthesised, {} states) runs reduced as {reduced} states beside its 2 plant components",
            full.supervisors[0].automaton.num_states()
        ),
        format!("{} rungs, where the full", ladder.rungs.len()),
        format!("would have {full_rungs}, over the limit of {limit}"),
    ] {
        assert!(shrunk.summary.contains(&said), "{said}: {}", shrunk.summary);
        assert!(ladder.pou_xml.contains(&said), "{said} in the documentation");
    }
    one_rung_per_moving_transition(small, ladder);
    exhaustive(small, ladder);
    let (u, c) = lockstep_with_the_full_supervisor(&full, small, ladder, 2_000);
    assert!(u > 500 && c > 500, "{u} uncontrollable, {c} controllable");
}

/// The AGV: 11,349 rungs in full, 3,100 reduced, 750 localized; each
/// limit takes the first form that fits, and the localized ladder's
/// enables are the full supervisor's along a random run.
#[test]
fn the_agv_ladder_is_reduced_or_localized_as_its_limit_requires() {
    let path = models().join("agv.plc.toml");
    let full = project::load(&path).unwrap();
    let shrink = |s| project::load_shrunk(&path, s);
    let reduced = ladder::render_fitting(&full, 3_200, shrink).unwrap();
    let r = reduced.shrunk.as_ref().expect("reduced");
    assert_eq!(
        (r.shrink, r.full_rungs, reduced.ladder.rungs.len()),
        (project::Shrink::Reduce, 11_349, 3_100)
    );
    let localized = ladder::render_fitting(&full, 800, shrink).unwrap();
    let l = localized.shrunk.as_ref().expect("localized");
    assert_eq!(
        (l.shrink, localized.ladder.rungs.len()),
        (project::Shrink::Localize, 750)
    );
    assert!(
        l.summary.contains("runs localized as 10 local controllers"),
        "{}",
        l.summary
    );
    let (u, c) = lockstep_with_the_full_supervisor(&full, &l.project, &localized.ladder, 3_000);
    assert!(u > 500 && c > 500, "{u} uncontrollable, {c} controllable");
}

/// When no form fits, the refusal is the full ladder's, at the line of
/// its supervisor, with the rungs of each form tried; a project with no
/// synthesised supervisor tries none.
#[test]
fn when_no_form_fits_the_refusal_names_each_form_tried() {
    let path = models().join("conveyor.plc.toml");
    let full = project::load(&path).unwrap();
    let err = ladder::render_fitting(&full, 10, |s| project::load_shrunk(&path, s)).unwrap_err();
    let (location, message) = err.located().expect("a located error");
    assert_eq!(location.line, full.supervisors[0].line, "{err}");
    assert!(
        message.contains("17 rungs, over the limit of 10")
            && message.contains("tried reduced (`reduce = true`): 18 rungs")
            && message.contains("tried localized (`localize = true`): 27 rungs")
            && message.contains("Structured Text"),
        "{err}"
    );
    let press = load("press.plc.toml");
    let err = ladder::render_fitting(&press, 5, |_| panic!("nothing to shrink")).unwrap_err();
    assert!(!err.to_string().contains("tried"), "{err}");
    // A form that does not load is named with its error.
    let err = ladder::render_fitting(&full, 10, |s| {
        Err(des::Error::Incompatible(format!("no {}", s.key())))
    })
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("tried reduced (`reduce = true`): it does not load (")
            && err.contains("no localize"),
        "{err}"
    );
}
