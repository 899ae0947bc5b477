//! The controller function block: the whole scan of docs/semantics.md
//! ("One scan", "Fault mode") in Structured Text.
//!
//! Signals, timers, events and supervisors become arrays indexed by
//! named constants (`FILT[IN_start]`, `T_RUN[TM_runon]`, `EVENTS[n] :=
//! EV_go`), each automaton a state variable `S_<name>` and a constant
//! transition array `D_<name>[state, local event]` (−1: no transition)
//! or, where that is smaller ([`sparse_layout`]), a sparse table (row starts
//! `DR_<name>`, local events `DE_<name>`, targets `DT_<name>`) searched
//! into `NX_<name>`; each Petri net a marking array `M_<name>[place]`.
//! A command of a symbolic supervisor also needs its guards to hold:
//! each is written by [`super::guards`] over the components' state
//! variables, inline or as a chain of temporaries `GN[k]` computed just
//! before the command's test.
//! Steps are written in the order of the specification, each event as
//! its own block, so a reader can follow one event from its occurrence
//! to its actions.
//!
//! The text is meant for every IEC compiler, the strictest included
//! (matiec, the 2nd-edition compiler of OpenPLC and Beremiz): every
//! assignment is between variables of one type (no implicit widening),
//! every constant fits its declared type (`DINT` where a count can pass
//! `INT`), no statement or branch is empty, and no `FOR` loop runs once
//! (a one-trip loop is written out; matiec of October 2024 runs
//! `FOR i := 1 TO 1` zero times).

use super::names::Namer;
use super::pou::{Init, Pou, PouKind, Section, Type, Var, VarBlock};
use super::{comment_text, guards, Names, SparseNames};
use des::automaton::StateId;
use plc_project::{Action, Drive, Event, Project, Supervisor, Trigger, Unexpected};

/// Fault cause numbers of the `FAULT_CAUSE` output.
pub const CAUSE_UNEXPECTED: i64 = 1;
/// A supervisor state out of range (corrupt memory).
pub const CAUSE_CORRUPT: i64 = 2;

/// The `UDINT` half range: a difference of clock readings below it is a
/// time at or after the other (wrap-safe, docs/semantics.md).
const HALF: &str = "UDINT#16#80000000";

/// Statements with indentation.
#[derive(Default)]
struct Body {
    lines: Vec<String>,
    depth: usize,
    /// Statements written (comments and blank lines aside).
    statements: usize,
}

impl Body {
    /// A body nested one level in `outer`.
    fn nested(outer: &Body) -> Body {
        Body {
            depth: outer.depth + 1,
            ..Body::default()
        }
    }
    fn line(&mut self, text: impl AsRef<str>) {
        self.statements += 1;
        self.comment(text);
    }
    fn comment(&mut self, text: impl AsRef<str>) {
        self.lines
            .push(format!("{}{}", "    ".repeat(self.depth), text.as_ref()));
    }
    fn append(&mut self, inner: Body) {
        self.statements += inner.statements;
        self.lines.extend(inner.lines);
    }
    fn open(&mut self, text: impl AsRef<str>) {
        self.line(text);
        self.depth += 1;
    }
    fn mid(&mut self, text: impl AsRef<str>) {
        self.depth -= 1;
        self.line(text);
        self.depth += 1;
    }
    fn close(&mut self, text: impl AsRef<str>) {
        self.depth -= 1;
        self.line(text);
    }
    fn blank(&mut self) {
        self.lines.push(String::new());
    }
}

/// The controller function block of `project` with the identifiers of
/// `names`.
pub fn controller(project: &Project, names: &Names) -> Pou {
    let b = Builder {
        project,
        names,
        position: position_type(
            &project
                .supervisors
                .iter()
                .map(Shape::of)
                .collect::<Vec<_>>(),
        ),
        guards: event_guards(project, names),
    };
    Pou {
        name: names.controller.clone(),
        kind: PouKind::FunctionBlock,
        doc: vec![
            format!(
                "The supervisory controller of project '{}': one call is one scan",
                comment_text(&project.name)
            ),
            format!(
                "(docs/semantics.md). Call it once per task cycle, every {} ms, with NOW_MS",
                project.scan_period_ms
            ),
            "a millisecond clock (wrapping UDINT).".into(),
        ],
        blocks: b.declarations(),
        body: b.body(),
    }
}

struct Builder<'a> {
    project: &'a Project,
    names: &'a Names,
    /// The type of sparse tables' row starts and of `J`.
    position: Type,
    /// Per event, its guards as written (commands of symbolic
    /// supervisors).
    guards: Vec<Vec<Guard>>,
}

/// The temporaries of guards written as chains ([`guards::Form::Chain`]):
/// one array, each command's guards using it from index 0 when it is
/// tested.
pub const GUARD_NODES: &str = "GN";

/// One guard of a command, as the block writes it.
struct Guard {
    /// The symbolic supervisor's name.
    supervisor: String,
    /// Its text for the comment ([`guards::text`]).
    text: String,
    /// The expression or the chain.
    form: guards::Form,
    /// The term of the feasibility test: the expression, or the
    /// temporary of the chain's root.
    term: String,
}

/// The guards of every event of `project` that has one that does not
/// always hold, as the block writes them: in the order of
/// `project.guarded`, chains of one event numbered on from each other.
fn event_guards(project: &Project, names: &Names) -> Vec<Vec<Guard>> {
    let sizes: Vec<usize> = project
        .supervisors
        .iter()
        .map(|s| s.automaton.num_states())
        .collect();
    let mut out: Vec<Vec<Guard>> = project.events.iter().map(|_| Vec::new()).collect();
    for g in &project.guarded {
        for eg in &g.guards {
            if eg.root == 1 {
                continue;
            }
            let diagram = guards::Diagram::of(eg, &g.bits, &sizes);
            let first: usize = out[eg.event]
                .iter()
                .map(|guard: &Guard| match &guard.form {
                    guards::Form::Chain { nodes, .. } => *nodes,
                    guards::Form::Inline(_) => 0,
                })
                .sum();
            let form = guards::form(&diagram, &names.states, &sizes, GUARD_NODES, first);
            let term = match &form {
                guards::Form::Inline(e) => e.clone(),
                guards::Form::Chain { root, .. } => format!("{GUARD_NODES}[{root}]"),
            };
            out[eg.event].push(Guard {
                supervisor: comment_text(&g.name),
                text: guards::text(&eg.text),
                form,
                term,
            });
        }
    }
    out
}

fn bool_lit(b: bool) -> String {
    if b { "TRUE" } else { "FALSE" }.into()
}

/// The type of indices and counts up to `max`: `INT`, a PLC's usual
/// word, or `DINT` past it.
fn index_type(max: usize) -> Type {
    if max <= i16::MAX as usize {
        Type::Int
    } else {
        Type::Dint
    }
}

/// The type of a supervisor's state variable and of its table entries:
/// its states and −1 (one type, so that `S := D[S, k]` needs no
/// conversion).
fn state_type(states: usize) -> Type {
    Type::signed_for(-1, states as i64)
}

/// The element type of a net's marking array: at least `INT`, wide
/// enough for every bound, initial marking and arc weight.
fn marking_type(net: &plc_project::Net) -> Type {
    let arcs = net
        .net
        .transitions()
        .iter()
        .flat_map(|t| t.input.iter().chain(&t.output).map(|&(_, w)| i64::from(w)));
    let largest = net
        .bounds
        .iter()
        .chain(net.net.initial())
        .map(|&m| i64::from(m))
        .chain(arcs)
        .max()
        .unwrap_or(0);
    match Type::signed_for(0, largest) {
        Type::Sint => Type::Int,
        t => t,
    }
}

/// A supervisor's transition function as the export sees it.
struct Shape {
    states: usize,
    columns: usize,
    transitions: usize,
}

impl Shape {
    fn of(sup: &Supervisor) -> Shape {
        let a = &sup.automaton;
        let transitions = (0..a.num_states() as u32)
            .map(|s| {
                sup.local_events
                    .iter()
                    .filter(|&&(_, id)| a.successor(StateId(s), id).is_some())
                    .count()
            })
            .sum();
        Shape {
            states: a.num_states(),
            columns: sup.local_events.len(),
            transitions,
        }
    }

    fn dense_bytes(&self) -> usize {
        self.states * self.columns * state_type(self.states).bytes()
    }

    /// Row starts, then events and targets each with their −1.
    fn sparse_bytes(&self, position: &Type) -> usize {
        (self.states + 1) * position.bytes()
            + (self.transitions + 1)
                * (Type::signed_for(-1, self.columns as i64).bytes()
                    + state_type(self.states).bytes())
    }
}

/// The type of sparse tables' row starts and of their search index `J`:
/// one for the project, wide enough for its largest supervisor.
fn position_type(shapes: &[Shape]) -> Type {
    index_type(shapes.iter().map(|s| s.transitions).max().unwrap_or(0))
}

/// Dense arrays up to this many bytes stay dense whatever a sparse table
/// would save: a few hundred bytes, and the array reads as the
/// supervisor's table (every seed).
const ALWAYS_DENSE: usize = 1024;

/// For each supervisor of `project`, whether it is exported as a sparse
/// table (row starts, events, targets) rather than a dense `[state,
/// event]` array: when that takes at most two thirds of the dense array's
/// bytes. A sparse table costs a search per lookup and its code, so a
/// table that saves less stays dense (the boiler's seven, half their
/// entries defined, would save at most a fifth), as do arrays of at most
/// 1 KB; the AGV's saves four fifths, the monolithic boiler's two
/// fifths.
pub fn sparse_layout(project: &Project) -> Vec<bool> {
    let shapes: Vec<Shape> = project.supervisors.iter().map(Shape::of).collect();
    let position = position_type(&shapes);
    shapes
        .iter()
        .map(|shape| {
            shape.dense_bytes() > ALWAYS_DENSE
                && 3 * shape.sparse_bytes(&position) <= 2 * shape.dense_bytes()
        })
        .collect()
}

impl Builder<'_> {
    fn ni(&self) -> usize {
        self.project.inputs.len()
    }

    /// The type of event numbers and counts: `EV_` constants, `EVENTS`,
    /// `FAULT_EVENT`, `CMD`.
    fn event_type(&self) -> Type {
        index_type(self.project.events.len().max(1))
    }

    /// The function block's VAR blocks: inputs, outputs, locals and, when
    /// there are any, constants.
    fn declarations(&self) -> Vec<VarBlock> {
        let mut blocks = vec![
            VarBlock {
                section: Section::Input,
                vars: self.input_vars(),
            },
            VarBlock {
                section: Section::Output,
                vars: self.output_vars(),
            },
            VarBlock {
                section: Section::Local,
                vars: self.local_vars(),
            },
        ];
        let constants = self.constant_vars();
        if !constants.is_empty() {
            blocks.push(VarBlock {
                section: Section::Constant,
                vars: constants,
            });
        }
        blocks
    }

    /// `VAR_INPUT`: the clock, then the project's inputs.
    fn input_vars(&self) -> Vec<Var> {
        let mut inputs = vec![Var::new(
            "NOW_MS",
            Type::Udint,
            "millisecond clock: wraps at 2^32",
        )];
        for (i, input) in self.project.inputs.iter().enumerate() {
            inputs.push(Var::new(
                &self.names.inputs[i],
                Type::Bool,
                format!("input '{}'", comment_text(&input.name)),
            ));
        }
        inputs
    }

    /// `VAR_OUTPUT`: the project's outputs, the fault and event
    /// diagnostics, the supervisors' states and the nets' markings.
    fn output_vars(&self) -> Vec<Var> {
        let mut outputs = Vec::new();
        for (o, output) in self.project.outputs.iter().enumerate() {
            outputs.push(Var::new(
                &self.names.outputs[o],
                Type::Bool,
                format!(
                    "output '{}' (safe level {})",
                    comment_text(&output.name),
                    u8::from(output.safe)
                ),
            ));
        }
        outputs.extend(self.diagnostic_vars());
        outputs.extend(self.state_vars());
        outputs
    }

    /// The outputs saying what a scan did: fault mode and its cause,
    /// counters, the events executed and the unexpected ones.
    fn diagnostic_vars(&self) -> [Var; 9] {
        let p = self.project;
        let ne = p.events.len().max(1);
        let nu = p.events.iter().filter(|e| !e.controllable).count().max(1);
        let event_ty = self.event_type();
        let events = |n: usize| Type::Array {
            dims: vec![(1, n as i64)],
            elem: Box::new(event_ty.clone()),
        };
        [
            Var::new(
                "FAULT",
                Type::Bool,
                "in fault mode: every output at its safe level",
            ),
            Var::new(
                "FAULT_CAUSE",
                Type::Int,
                "0 none, 1 unexpected event (FAULT_EVENT), 2 supervisor state out of range",
            ),
            Var::new(
                "FAULT_EVENT",
                event_ty.clone(),
                "the unexpected event, -1 if none",
            )
            .init(Init::Value("-1".into())),
            Var::new("FAULTS", Type::Udint, "faults entered since power-on"),
            Var::new(
                "IGNORED",
                Type::Udint,
                "unexpected events ignored since power-on",
            ),
            Var::new("N_EVENTS", event_ty.clone(), "events executed in this scan"),
            Var::new(
                "EVENTS",
                events(ne),
                "the events executed in this scan, in order (EV_ constants)",
            ),
            Var::new(
                "N_UNEXPECTED",
                event_ty.clone(),
                "unexpected events in this scan",
            ),
            Var::new(
                "UNEXPECTED",
                events(nu),
                "the unexpected events of this scan, in order",
            ),
        ]
    }

    /// Each supervisor's state variable and each net's marking array,
    /// initialised to the initial state and marking.
    fn state_vars(&self) -> Vec<Var> {
        let mut vars = Vec::new();
        for (j, sup) in self.project.supervisors.iter().enumerate() {
            let a = &sup.automaton;
            let initial = a.initial().map_or(0, |s| s.0);
            let about = format!(
                "state of supervisor '{}' ({} states)",
                comment_text(&sup.name),
                a.num_states()
            );
            vars.push(
                Var::new(&self.names.states[j], state_type(a.num_states()), about)
                    .init(Init::Value(initial.to_string())),
            );
        }
        for (k, net) in self.project.nets.iter().enumerate() {
            let places = net.net.places();
            let ids: Vec<String> = places.iter().map(|pl| comment_text(&pl.id)).collect();
            let marking = net.net.initial().iter().map(|m| m.to_string()).collect();
            let about = format!(
                "marking of net '{}': tokens per place",
                comment_text(&net.name)
            );
            vars.push(
                Var::new(
                    &self.names.nets[k],
                    Type::array(places.len(), marking_type(net)),
                    about,
                )
                .init(Init::Rows(vec![(ids.join(" "), marking)])),
            );
        }
        vars
    }

    /// `VAR`: the input images, latched outputs, timers, event flags, the
    /// loop index, the command count and what sparse lookups need.
    fn local_vars(&self) -> Vec<Var> {
        let p = self.project;
        let mut locals = vec![
            Var::new("FIRST", Type::Bool, "scan 0: no edges").init(Init::Value("TRUE".into()))
        ];
        locals.extend(self.image_vars());
        if !p.outputs.is_empty() {
            let latched = p
                .outputs
                .iter()
                .map(|o| bool_lit(matches!(o.drive, Drive::Actions { initial: true })))
                .collect();
            locals.push(
                Var::new(
                    "LATCH",
                    Type::array(p.outputs.len(), Type::Bool),
                    "levels of action-driven outputs",
                )
                .init(Init::Rows(vec![(String::new(), latched)])),
            );
        }
        if !p.timers.is_empty() {
            let timers = |elem| Type::array(p.timers.len(), elem);
            locals.push(Var::new("T_RUN", timers(Type::Bool), "timer running"));
            locals.push(Var::new(
                "T_DL",
                timers(Type::Udint),
                "timer deadline (NOW_MS at start + preset)",
            ));
        }
        let ne = p.events.len().max(1);
        locals.push(Var::new(
            "OCC",
            Type::array(ne, Type::Bool),
            "uncontrollable events that occurred in this scan",
        ));
        if self.uses_done() {
            locals.push(Var::new(
                "DONE",
                Type::array(ne, Type::Bool),
                "commands executed in this scan",
            ));
        }
        let loops = self.ni().max(p.timers.len());
        locals.push(Var::new("I", index_type(loops), "loop index"));
        if self.commands().count() > 0 && self.command_limit() > 1 {
            let about = "commands chosen in this scan";
            locals.push(Var::new("CMD", self.event_type(), about));
        }
        locals.extend(self.search_vars());
        locals
    }

    /// The raw, filtered and previous input images and the debounce
    /// counters (none without inputs).
    fn image_vars(&self) -> Vec<Var> {
        let mut vars = Vec::new();
        if self.ni() > 0 {
            let arr = || Type::array(self.ni(), Type::Bool);
            vars.push(Var::new("RAW", arr(), "raw input image"));
            vars.push(Var::new("FILT", arr(), "filtered input image of this scan"));
            vars.push(Var::new(
                "PREV",
                arr(),
                "filtered input image of the last scan",
            ));
            if self.debounced() {
                vars.push(Var::new(
                    "DEB",
                    Type::array(self.ni(), Type::Int),
                    "debounce: consecutive scans the raw value has differed",
                ));
            }
        }
        vars
    }

    /// What sparse tables' searches and guard chains need: the position
    /// `J`, the `CHOSEN` flag, the guard temporaries `GN` and each sparse
    /// supervisor's last target.
    fn search_vars(&self) -> Vec<Var> {
        let mut vars = Vec::new();
        if self.names.sparse.iter().any(Option::is_some) {
            vars.push(Var::new(
                "J",
                self.position.clone(),
                "position in a sparse table",
            ));
        }
        if self.chosen_flag() {
            vars.push(Var::new(
                "CHOSEN",
                Type::Bool,
                "a command was executed in this round",
            ));
        }
        let nodes = self.guard_nodes();
        if nodes > 0 {
            vars.push(Var::new(
                GUARD_NODES,
                Type::array(nodes, Type::Bool),
                "the guard nodes of the command being tested, children first",
            ));
        }
        for (j, sup) in self.project.supervisors.iter().enumerate() {
            if let Some(sparse) = &self.names.sparse[j] {
                vars.push(Var::new(
                    &sparse.next,
                    state_type(sup.automaton.num_states()),
                    format!(
                        "supervisor '{}': target of the last lookup, -1 none",
                        comment_text(&sup.name)
                    ),
                ));
            }
        }
        vars
    }

    /// `VAR CONSTANT`: the index constants, the debounce scans and the
    /// transition tables.
    fn constant_vars(&self) -> Vec<Var> {
        let p = self.project;
        let mut constants = self.index_constants();
        if self.debounced() {
            let scans = p.inputs.iter().map(|i| i.debounce_scans.to_string());
            constants.push(
                Var::new(
                    "DEBOUNCE",
                    Type::array(self.ni(), Type::Int),
                    "debounce scans per input (0 and 1: none)",
                )
                .init(Init::Rows(vec![(String::new(), scans.collect())])),
            );
        }
        for (j, sup) in p.supervisors.iter().enumerate() {
            match &self.names.sparse[j] {
                Some(sparse) => constants.extend(self.sparse_table(sparse, sup)),
                None => constants.push(self.table(j, sup)),
            }
        }
        constants
    }

    /// The index of every input, latched output, timer and event, named.
    fn index_constants(&self) -> Vec<Var> {
        let p = self.project;
        let n = self.names;
        let index = |name: &str, ty: Type, about: String, i: usize| {
            Var::new(name, ty, about).init(Init::Value(i.to_string()))
        };
        let mut constants = Vec::new();
        for (i, input) in p.inputs.iter().enumerate() {
            let about = format!("input '{}'", comment_text(&input.name));
            constants.push(index(&n.input_index[i], index_type(self.ni()), about, i));
        }
        for (o, output) in p.outputs.iter().enumerate() {
            if matches!(output.drive, Drive::Actions { .. }) {
                let about = format!("output '{}'", comment_text(&output.name));
                let ty = index_type(p.outputs.len());
                constants.push(index(&n.output_index[o], ty, about, o));
            }
        }
        for (t, timer) in p.timers.iter().enumerate() {
            let name = comment_text(&timer.name);
            let about = format!("timer '{name}', {} ms", timer.preset_ms);
            constants.push(index(&n.timers[t], index_type(p.timers.len()), about, t));
        }
        for (e, event) in p.events.iter().enumerate() {
            let kind = if event.controllable {
                "controllable"
            } else {
                "uncontrollable"
            };
            let about = format!("event '{}', {kind}", comment_text(&event.name));
            constants.push(index(&n.events[e], self.event_type(), about, e));
        }
        constants
    }

    /// Supervisor `j`'s transition array: a row per state, a column per
    /// local event, the target state or −1.
    fn table(&self, j: usize, sup: &plc_project::Supervisor) -> Var {
        let a = &sup.automaton;
        let columns: Vec<String> = sup
            .local_events
            .iter()
            .map(|&(g, _)| comment_text(&self.project.events[g].name))
            .collect();
        let rows = (0..a.num_states() as u32)
            .map(|s| {
                let targets = sup
                    .local_events
                    .iter()
                    .map(|&(_, id)| {
                        a.successor(StateId(s), id)
                            .map_or("-1".to_owned(), |t| t.0.to_string())
                    })
                    .collect();
                (state_label(a, s), targets)
            })
            .collect();
        Var::new(
            &self.names.tables[j],
            Type::Array {
                dims: vec![
                    (0, a.num_states() as i64 - 1),
                    (0, sup.local_events.len() as i64 - 1),
                ],
                elem: Box::new(state_type(a.num_states())),
            },
            format!(
                "supervisor '{}': next state by [state, event], -1 none; events {}",
                comment_text(&sup.name),
                columns.join(", ")
            ),
        )
        .init(Init::Rows(rows))
    }

    /// Supervisor `sup`'s transitions as a sparse table: row starts, then
    /// the local event and the target of each transition (state by state,
    /// events in column order), each list ending in −1 so that a search
    /// past a row's last entry stays inside the arrays.
    fn sparse_table(&self, names: &SparseNames, sup: &Supervisor) -> [Var; 3] {
        let a = &sup.automaton;
        let mut starts = vec!["0".to_owned()];
        let (mut columns, mut targets) = (Vec::new(), Vec::new());
        let mut count = 0usize;
        for s in 0..a.num_states() as u32 {
            let (mut cols, mut tos) = (Vec::new(), Vec::new());
            for (k, &(_, id)) in sup.local_events.iter().enumerate() {
                if let Some(t) = a.successor(StateId(s), id) {
                    cols.push(k.to_string());
                    tos.push(t.0.to_string());
                }
            }
            count += cols.len();
            starts.push(count.to_string());
            if !cols.is_empty() {
                // The state's name once, on its targets.
                columns.push((s.to_string(), cols));
                targets.push((state_label(a, s), tos));
            }
        }
        columns.push(("end".into(), vec!["-1".into()]));
        targets.push(("end".into(), vec!["-1".into()]));
        // Row starts sixteen to a line, labelled with their first state.
        let starts: Vec<(String, Vec<String>)> = starts
            .chunks(16)
            .enumerate()
            .map(|(k, chunk)| (format!("{}..", 16 * k), chunk.to_vec()))
            .collect();
        let n = a.num_states();
        let event_list: Vec<String> = sup
            .local_events
            .iter()
            .map(|&(g, _)| comment_text(&self.project.events[g].name))
            .collect();
        let who = comment_text(&sup.name);
        [
            Var::new(
                &names.rows,
                Type::array(n + 1, self.position.clone()),
                format!(
                    "supervisor '{who}': the transitions of state s are entries {r}[s] to {r}[s + 1] - 1 of {} and {}",
                    names.columns,
                    names.targets,
                    r = names.rows
                ),
            )
            .init(Init::Rows(starts)),
            Var::new(
                &names.columns,
                Type::array(count + 1, Type::signed_for(-1, sup.local_events.len() as i64)),
                format!(
                    "supervisor '{who}': local event of each transition, then -1; events {}",
                    event_list.join(", ")
                ),
            )
            .init(Init::Rows(columns)),
            Var::new(
                &names.targets,
                Type::array(count + 1, state_type(n)),
                format!("supervisor '{who}': target state of each transition, then -1"),
            )
            .init(Init::Rows(targets)),
        ]
    }

    /// Whether the controllable phase needs the `CHOSEN` flag: some
    /// command looks its target up in a sparse table or computes a guard
    /// as a chain of temporaries, which takes statements that an `ELSIF`
    /// chain has no room for.
    fn chosen_flag(&self) -> bool {
        self.commands().any(|(e, _)| {
            self.columns(e).any(|(j, _)| self.names.sparse[j].is_some()) || self.chained(e)
        })
    }

    /// Whether a guard of event `e` is written as a chain of temporaries.
    fn chained(&self, e: usize) -> bool {
        self.guards[e]
            .iter()
            .any(|g| matches!(g.form, guards::Form::Chain { .. }))
    }

    /// The temporaries the longest chains of one command take.
    fn guard_nodes(&self) -> usize {
        self.guards
            .iter()
            .map(|gs| {
                gs.iter()
                    .map(|g| match &g.form {
                        guards::Form::Chain { nodes, .. } => *nodes,
                        guards::Form::Inline(_) => 0,
                    })
                    .sum::<usize>()
            })
            .max()
            .unwrap_or(0)
    }

    /// A comment per guard of command `e`: the symbolic supervisor and
    /// the guard's text.
    fn guard_comments(&self, b: &mut Body, e: usize) {
        for g in &self.guards[e] {
            b.comment(format!(
                "(* guard of {} ({}): {} *)",
                comment_text(&self.project.events[e].name),
                g.supervisor,
                g.text
            ));
        }
    }

    /// The comments of command `e`'s guards and the statements computing
    /// the temporaries of those written as chains, from the current
    /// states: written just before its feasibility test, so each test
    /// sees the states the commands before it left.
    fn guard_chains(&self, b: &mut Body, e: usize) {
        self.guard_comments(b, e);
        for g in &self.guards[e] {
            if let guards::Form::Chain { statements, .. } = &g.form {
                for statement in statements {
                    b.line(statement);
                }
            }
        }
    }

    /// The number of commands the controllable phase may execute per scan.
    fn command_limit(&self) -> usize {
        let commands = self.commands().count();
        match self.project.max_commands_per_scan {
            0 => commands,
            n => usize::from(n).min(commands),
        }
    }

    /// Statements finding event `e`'s target in every sparse table having
    /// it, into its `NX_` variable (−1: none).
    fn lookups(&self, b: &mut Body, e: usize) {
        for (j, k) in self.columns(e) {
            let Some(t) = &self.names.sparse[j] else {
                continue;
            };
            let s = &self.names.states[j];
            b.line(format!("J := {}[{s}];", t.rows));
            b.open(format!(
                "WHILE J < {}[{s} + 1] AND {}[J] <> {k} DO",
                t.rows, t.columns
            ));
            b.line("J := J + 1;");
            b.close("END_WHILE;");
            b.open(format!("IF J < {}[{s} + 1] THEN", t.rows));
            b.line(format!("{} := {}[J];", t.next, t.targets));
            b.mid("ELSE");
            b.line(format!("{} := -1;", t.next));
            b.close("END_IF;");
        }
    }

    fn debounced(&self) -> bool {
        self.project.inputs.iter().any(|i| i.debounce_scans >= 2)
    }

    fn uses_done(&self) -> bool {
        self.project.max_commands_per_scan != 1 && self.commands().count() > 0
    }

    fn commands(&self) -> impl Iterator<Item = (usize, &Event)> {
        self.project
            .events
            .iter()
            .enumerate()
            .filter(|(_, e)| e.controllable)
    }

    fn filt(&self, i: usize) -> String {
        format!("FILT[{}]", self.names.input_index[i])
    }

    fn prev(&self, i: usize) -> String {
        format!("PREV[{}]", self.names.input_index[i])
    }

    /// OR of the inputs, in `image` (FILT or PREV).
    fn any(&self, inputs: &[usize], image: &str) -> String {
        let terms: Vec<String> = inputs
            .iter()
            .map(|&i| format!("{image}[{}]", self.names.input_index[i]))
            .collect();
        if terms.len() == 1 {
            terms[0].clone()
        } else {
            format!("({})", terms.join(" OR "))
        }
    }

    /// The `when`/`unless` conditions of `event`, `None` when it has none.
    fn conditions(&self, event: &Event) -> Option<String> {
        let terms: Vec<String> = event
            .when
            .iter()
            .map(|&i| self.filt(i))
            .chain(
                event
                    .unless
                    .iter()
                    .map(|&i| format!("NOT {}", self.filt(i))),
            )
            .collect();
        (!terms.is_empty()).then(|| terms.join(" AND "))
    }

    fn due(&self, t: &str) -> String {
        format!("T_RUN[{t}] AND NOW_MS - T_DL[{t}] < {HALF}")
    }

    /// The automata having event `e`: (supervisor, its column for `e`).
    fn columns(&self, e: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.project
            .supervisors
            .iter()
            .enumerate()
            .filter_map(move |(j, sup)| sup.local(e).map(|(k, _)| (j, k)))
    }

    /// The net transitions that are event `e`: (net, transition).
    fn transitions(&self, e: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.project
            .nets
            .iter()
            .enumerate()
            .flat_map(move |(n, net)| {
                (0..net.events.len())
                    .filter(move |&t| net.events[t] == e)
                    .map(move |t| (n, t))
            })
    }

    /// Whether every supervisor and net having event `e` lets it occur
    /// and, for a command of a symbolic supervisor, its guards hold (the
    /// chains' temporaries computed first by [`Builder::guard_chains`]).
    fn feasible(&self, e: usize) -> String {
        let mut terms: Vec<String> = self
            .columns(e)
            .map(|(j, k)| match &self.names.sparse[j] {
                Some(t) => format!("{} >= 0", t.next),
                None => format!(
                    "{}[{}, {k}] >= 0",
                    self.names.tables[j], self.names.states[j]
                ),
            })
            .collect();
        for (n, t) in self.transitions(e) {
            for &(place, w) in &self.project.nets[n].net.transitions()[t].input {
                terms.push(format!("{}[{place}] >= {w}", self.names.nets[n]));
            }
        }
        terms.extend(self.guards[e].iter().map(|g| g.term.clone()));
        if terms.is_empty() {
            "TRUE".into()
        } else {
            terms.join(" AND ")
        }
    }

    /// Executes event `e`: every supervisor and net having it moves, then
    /// its actions apply, then it is recorded.
    fn execute(&self, body: &mut Body, e: usize) {
        let p = self.project;
        let n = self.names;
        for (j, k) in self.columns(e) {
            match &n.sparse[j] {
                Some(t) => body.line(format!("{} := {};", n.states[j], t.next)),
                None => body.line(format!(
                    "{s} := {d}[{s}, {k}];",
                    s = n.states[j],
                    d = n.tables[j]
                )),
            }
        }
        for (k, t) in self.transitions(e) {
            let net = &p.nets[k].net;
            for (place, d) in net
                .change(t)
                .into_iter()
                .enumerate()
                .filter(|&(_, d)| d != 0)
            {
                let sign = if d < 0 { '-' } else { '+' };
                body.line(format!(
                    "{m}[{place}] := {m}[{place}] {sign} {}; (* {} *)",
                    d.abs(),
                    comment_text(&net.places()[place].id),
                    m = n.nets[k],
                ));
            }
        }
        for action in &p.events[e].actions {
            match *action {
                Action::Clear(o) => body.line(format!("LATCH[{}] := FALSE;", n.output_index[o])),
                Action::Set(o) => body.line(format!("LATCH[{}] := TRUE;", n.output_index[o])),
                Action::Reset(t) => body.line(format!("T_RUN[{}] := FALSE;", n.timers[t])),
                Action::Start(t) => {
                    body.line(format!("T_RUN[{}] := TRUE;", n.timers[t]));
                    body.line(format!(
                        "T_DL[{}] := NOW_MS + UDINT#{};",
                        n.timers[t], p.timers[t].preset_ms
                    ));
                }
            }
        }
        body.line("N_EVENTS := N_EVENTS + 1;");
        body.line(format!("EVENTS[N_EVENTS] := {};", n.events[e]));
    }

    /// Re-initialisation after a reset: initial states and markings,
    /// timers stopped, action-driven outputs at their initial levels.
    fn initialise(&self, body: &mut Body) {
        let p = self.project;
        for (j, sup) in p.supervisors.iter().enumerate() {
            let initial = sup.automaton.initial().map_or(0, |s| s.0);
            body.line(format!("{} := {initial};", self.names.states[j]));
        }
        for (k, net) in p.nets.iter().enumerate() {
            for (place, m) in net.net.initial().iter().enumerate() {
                body.line(format!("{}[{place}] := {m};", self.names.nets[k]));
            }
        }
        if !p.timers.is_empty() {
            for_each(body, p.timers.len(), |b| b.line("T_RUN[I] := FALSE;"));
        }
        for (o, output) in p.outputs.iter().enumerate() {
            if let Drive::Actions { initial } = output.drive {
                body.line(format!(
                    "LATCH[{}] := {};",
                    self.names.output_index[o],
                    bool_lit(initial)
                ));
            }
        }
        body.line("FAULT := FALSE;");
        body.line("FAULT_CAUSE := 0;");
        body.line("FAULT_EVENT := -1;");
    }

    fn body(&self) -> Vec<String> {
        let mut b = Body::default();
        self.sample(&mut b);
        b.blank();
        self.integrity(&mut b);
        b.blank();
        let mut scan = Body::nested(&b);
        self.occurrences(&mut scan);
        scan.blank();
        self.uncontrollable(&mut scan);
        scan.blank();
        self.controllable(&mut scan);
        match self.project.reset {
            Some(r) => {
                b.comment(
                    "(* 2. Fault mode: the scan ends here, on a reset with the initial state. *)",
                );
                b.open("IF FAULT THEN");
                b.open(format!("IF {} AND NOT {} THEN", self.filt(r), self.prev(r)));
                self.initialise(&mut b);
                b.close("END_IF;");
                if scan.statements > 0 {
                    b.mid("ELSE");
                    b.append(scan);
                }
                b.close("END_IF;");
            }
            None => {
                b.comment("(* 2. Fault mode: the scan ends here (no reset input: fault mode until");
                b.comment("   power-off). *)");
                if scan.statements > 0 {
                    b.open("IF NOT FAULT THEN");
                    b.append(scan);
                    b.close("END_IF;");
                }
            }
        }
        b.blank();
        self.outputs(&mut b);
        b.lines
    }

    fn sample(&self, b: &mut Body) {
        let p = self.project;
        b.line("N_EVENTS := 0;");
        b.line("N_UNEXPECTED := 0;");
        b.blank();
        b.comment("(* 1. Sample: raw image, debounce, the last scan's filtered image. *)");
        for i in 0..p.inputs.len() {
            b.line(format!(
                "RAW[{}] := {};",
                self.names.input_index[i], self.names.inputs[i]
            ));
        }
        if p.inputs.is_empty() {
            b.line("FIRST := FALSE;");
            return;
        }
        let inputs = p.inputs.len();
        b.open("IF FIRST THEN");
        b.line("FIRST := FALSE;");
        for_each(b, inputs, |b| {
            b.line("FILT[I] := RAW[I];");
            b.line("PREV[I] := RAW[I];");
        });
        b.mid("ELSE");
        let debounced = self.debounced();
        for_each(b, inputs, |b| {
            b.line("PREV[I] := FILT[I];");
            if debounced {
                b.open("IF DEBOUNCE[I] < 2 THEN");
                b.line("FILT[I] := RAW[I];");
                b.mid("ELSIF RAW[I] <> FILT[I] THEN");
                b.line("DEB[I] := DEB[I] + 1;");
                b.open("IF DEB[I] >= DEBOUNCE[I] THEN");
                b.line("FILT[I] := RAW[I];");
                b.line("DEB[I] := 0;");
                b.close("END_IF;");
                b.mid("ELSE");
                b.line("DEB[I] := 0;");
                b.close("END_IF;");
            } else {
                b.line("FILT[I] := RAW[I];");
            }
        });
        b.close("END_IF;");
    }

    fn integrity(&self, b: &mut Body) {
        let p = self.project;
        if p.supervisors.is_empty() {
            return;
        }
        b.comment("(* 2. Integrity: a state out of range can only be corrupt memory. *)");
        let terms: Vec<String> = p
            .supervisors
            .iter()
            .enumerate()
            .map(|(j, sup)| {
                format!(
                    "{s} < 0 OR {s} > {}",
                    sup.automaton.num_states() - 1,
                    s = self.names.states[j]
                )
            })
            .collect();
        b.open(format!("IF ({}) AND NOT FAULT THEN", terms.join(" OR ")));
        b.line("FAULT := TRUE;");
        b.line(format!("FAULT_CAUSE := {CAUSE_CORRUPT};"));
        b.line("FAULTS := FAULTS + 1;");
        b.close("END_IF;");
    }

    fn occurrences(&self, b: &mut Body) {
        let p = self.project;
        b.comment("(* 3. Occurrences: edges of the filtered image, timers run out; then every");
        b.comment("   timer run out stops. *)");
        for (e, event) in p.events.iter().enumerate() {
            let source = match &event.trigger {
                Trigger::Command => continue,
                Trigger::Rising(inputs) => format!(
                    "{} AND NOT {}",
                    self.any(inputs, "FILT"),
                    self.any(inputs, "PREV")
                ),
                Trigger::Falling(inputs) => format!(
                    "NOT {} AND {}",
                    self.any(inputs, "FILT"),
                    self.any(inputs, "PREV")
                ),
                Trigger::Expired(t) => self.due(&self.names.timers[*t]),
            };
            let cond = match self.conditions(event) {
                Some(c) => format!(" AND {c}"),
                None => String::new(),
            };
            b.line(format!("OCC[{}] := {source}{cond};", self.names.events[e]));
        }
        if !p.timers.is_empty() {
            let due = self.due("I");
            for_each(b, p.timers.len(), |b| {
                b.open(format!("IF {due} THEN"));
                b.line("T_RUN[I] := FALSE;");
                b.close("END_IF;");
            });
        }
    }

    fn uncontrollable(&self, b: &mut Body) {
        let p = self.project;
        let fault = p.unexpected == Unexpected::Fault;
        b.comment("(* 4. Uncontrollable phase, in declaration order: execute an event every");
        b.comment(if fault {
            "   supervisor having it allows, else fault mode. *)"
        } else {
            "   supervisor having it allows, else ignore and count it. *)"
        });
        for (e, event) in p.events.iter().enumerate() {
            if event.controllable {
                continue;
            }
            let ev = &self.names.events[e];
            b.open(if fault {
                format!("IF OCC[{ev}] AND NOT FAULT THEN")
            } else {
                format!("IF OCC[{ev}] THEN")
            });
            self.lookups(b, e);
            b.open(format!("IF {} THEN", self.feasible(e)));
            self.execute(b, e);
            b.mid("ELSE");
            b.line("N_UNEXPECTED := N_UNEXPECTED + 1;");
            b.line(format!("UNEXPECTED[N_UNEXPECTED] := {ev};"));
            if fault {
                b.line("FAULT := TRUE;");
                b.line(format!("FAULT_CAUSE := {CAUSE_UNEXPECTED};"));
                b.line(format!("FAULT_EVENT := {ev};"));
                b.line("FAULTS := FAULTS + 1;");
            } else {
                b.line("IGNORED := IGNORED + 1;");
            }
            b.close("END_IF;");
            b.close("END_IF;");
        }
    }

    fn controllable(&self, b: &mut Body) {
        let p = self.project;
        let commands: Vec<(usize, &Event)> = self.commands().collect();
        b.comment("(* 5. Controllable phase: the first command in declaration order that every");
        if self.guards.iter().any(|g| !g.is_empty()) {
            b.comment("   supervisor having it allows, whose guards hold and, if it has a request");
            b.comment("   input, is requested;");
        } else {
            b.comment(
                "   supervisor having it allows and, if it has a request input, is requested;",
            );
        }
        let limit = self.command_limit();
        b.comment(format!(
            "   at most {} per scan{}. *)",
            limit,
            if self.uses_done() { ", each once" } else { "" }
        ));
        if commands.is_empty() {
            return;
        }
        // Under the fault policy an unexpected event may have ended the
        // scan in step 4.
        let guarded = p.unexpected == Unexpected::Fault;
        if guarded {
            b.open("IF NOT FAULT THEN");
        }
        if self.uses_done() {
            for &(e, _) in &commands {
                b.line(format!("DONE[{}] := FALSE;", self.names.events[e]));
            }
        }
        // One command needs no loop (and a one-trip loop is what some
        // compilers get wrong).
        let looped = limit > 1;
        if looped {
            b.open(format!("FOR CMD := 1 TO {limit} DO"));
        }
        if self.chosen_flag() {
            self.first_command_by_flag(b, &commands, looped);
        } else {
            self.first_command_by_chain(b, &commands, looped);
        }
        if looped {
            b.close("END_FOR;");
        }
        if guarded {
            b.close("END_IF;");
        }
    }

    /// What must hold, besides feasibility, for command `e` to be
    /// chosen: not done yet in this scan, requested.
    fn wanted(&self, e: usize, event: &Event) -> Vec<String> {
        let mut terms = Vec::new();
        if self.uses_done() {
            terms.push(format!("NOT DONE[{}]", self.names.events[e]));
        }
        if let Some(r) = event.request {
            terms.push(self.filt(r));
        }
        terms
    }

    fn executed(&self, b: &mut Body, e: usize) {
        self.execute(b, e);
        if self.uses_done() {
            b.line(format!("DONE[{}] := TRUE;", self.names.events[e]));
        }
    }

    /// The first feasible command as one `IF … ELSIF …` chain (every
    /// supervisor a dense array, so feasibility is an expression).
    fn first_command_by_chain(&self, b: &mut Body, commands: &[(usize, &Event)], looped: bool) {
        for (k, &(e, event)) in commands.iter().enumerate() {
            let mut terms = self.wanted(e, event);
            let feasible = self.feasible(e);
            if feasible != "TRUE" || terms.is_empty() {
                terms.push(feasible);
            }
            if k == 0 {
                self.guard_comments(b, e);
            } else {
                b.depth -= 1;
                self.guard_comments(b, e);
                b.depth += 1;
            }
            let keyword = if k == 0 { "IF" } else { "ELSIF" };
            let head = format!(
                "{keyword} {} THEN (* {} *)",
                terms.join(" AND "),
                comment_text(&event.name)
            );
            if k == 0 {
                b.open(head);
            } else {
                b.mid(head);
            }
            self.executed(b, e);
        }
        if looped {
            b.mid("ELSE");
            b.line("EXIT;");
        }
        b.close("END_IF;");
    }

    /// The first feasible command, each tried in turn while `CHOSEN` is
    /// false: a command whose supervisors include a sparse table looks
    /// its targets up first.
    fn first_command_by_flag(&self, b: &mut Body, commands: &[(usize, &Event)], looped: bool) {
        b.line("CHOSEN := FALSE;");
        for &(e, event) in commands {
            let mut terms = vec!["NOT CHOSEN".to_owned()];
            terms.extend(self.wanted(e, event));
            b.open(format!(
                "IF {} THEN (* {} *)",
                terms.join(" AND "),
                comment_text(&event.name)
            ));
            self.lookups(b, e);
            self.guard_chains(b, e);
            b.open(format!("IF {} THEN", self.feasible(e)));
            self.executed(b, e);
            b.line("CHOSEN := TRUE;");
            b.close("END_IF;");
            b.close("END_IF;");
        }
        if looped {
            b.open("IF NOT CHOSEN THEN");
            b.line("EXIT;");
            b.close("END_IF;");
        }
    }

    fn outputs(&self, b: &mut Body) {
        let p = self.project;
        let n = self.names;
        b.comment(
            "(* 6. Outputs: safe levels in fault mode, else latched levels and state maps. *)",
        );
        if p.outputs.is_empty() {
            return;
        }
        b.open("IF FAULT THEN");
        for (o, output) in p.outputs.iter().enumerate() {
            b.line(format!("{} := {};", n.outputs[o], bool_lit(output.safe)));
        }
        b.mid("ELSE");
        for (o, output) in p.outputs.iter().enumerate() {
            let value = match &output.drive {
                Drive::Actions { .. } => format!("LATCH[{}]", n.output_index[o]),
                Drive::States(map) => {
                    let terms: Vec<String> = map
                        .iter()
                        .flat_map(|(j, states)| {
                            states
                                .iter()
                                .map(move |s| format!("({} = {})", n.states[*j], s.0))
                        })
                        .collect();
                    or_terms(terms)
                }
                Drive::Places(map) => {
                    let terms: Vec<String> = map
                        .iter()
                        .flat_map(|(k, places)| {
                            places
                                .iter()
                                .map(move |pl| format!("({}[{pl}] >= 1)", n.nets[*k]))
                        })
                        .collect();
                    or_terms(terms)
                }
            };
            b.line(format!("{} := {value};", n.outputs[o]));
        }
        b.close("END_IF;");
    }
}

/// The longest state name a table row is labelled with: longer ones are
/// composite states of large products (850 characters a state in the
/// monolithic boiler), which would make up most of the file; their rows
/// carry the state number, the state's position in the supervisor.
const MAX_LABEL: usize = 80;

/// The comment labelling state `s`'s row: its number, and its name
/// when that differs and is at most [`MAX_LABEL`] characters.
fn state_label(a: &des::automaton::Automaton, s: u32) -> String {
    let name = a.state_name(StateId(s));
    if name == s.to_string() || name.chars().count() > MAX_LABEL {
        s.to_string()
    } else {
        format!("{s}: {}", comment_text(&name))
    }
}

/// `body` for `I` from 0 to `count - 1`: a `FOR` loop, or for one
/// element `I := 0;` and the body (a one-trip loop is what matiec of
/// October 2024 runs zero times).
fn for_each(b: &mut Body, count: usize, body: impl FnOnce(&mut Body)) {
    if count == 1 {
        b.line("I := 0;");
        body(b);
    } else {
        b.open(format!("FOR I := 0 TO {} DO", count - 1));
        body(b);
        b.close("END_FOR;");
    }
}

fn or_terms(terms: Vec<String>) -> String {
    if terms.is_empty() {
        "FALSE".into()
    } else {
        terms.join(" OR ")
    }
}

/// Registers every identifier the controller and the program use in
/// `namer` and returns them.
pub fn names(project: &Project, namer: &mut Namer, program_ids: &[&str]) -> Names {
    for id in [
        "NOW_MS",
        "FAULT",
        "FAULT_CAUSE",
        "FAULT_EVENT",
        "FAULTS",
        "IGNORED",
        "N_EVENTS",
        "EVENTS",
        "N_UNEXPECTED",
        "UNEXPECTED",
        "FIRST",
        "RAW",
        "FILT",
        "PREV",
        "DEB",
        "DEBOUNCE",
        "LATCH",
        "T_RUN",
        "T_DL",
        "OCC",
        "DONE",
        "I",
        "CMD",
        "J",
        "CHOSEN",
        GUARD_NODES,
    ]
    .iter()
    .chain(program_ids)
    {
        namer.reserve(id);
    }
    let inputs = project
        .inputs
        .iter()
        .map(|i| namer.name("", &i.name))
        .collect();
    let outputs = project
        .outputs
        .iter()
        .map(|o| namer.name("", &o.name))
        .collect();
    let input_index = project
        .inputs
        .iter()
        .map(|i| namer.name("IN_", &i.name))
        .collect();
    let output_index = project
        .outputs
        .iter()
        .map(|o| namer.name("Q_", &o.name))
        .collect();
    let timers = project
        .timers
        .iter()
        .map(|t| namer.name("TM_", &t.name))
        .collect();
    let events = project
        .events
        .iter()
        .map(|e| namer.name("EV_", &e.name))
        .collect();
    let states = project
        .supervisors
        .iter()
        .map(|s| namer.name("S_", &s.name))
        .collect();
    let tables = project
        .supervisors
        .iter()
        .map(|s| namer.name("D_", &s.name))
        .collect();
    let sparse = project
        .supervisors
        .iter()
        .zip(sparse_layout(project))
        .map(|(s, sparse)| {
            sparse.then(|| SparseNames {
                rows: namer.name("DR_", &s.name),
                columns: namer.name("DE_", &s.name),
                targets: namer.name("DT_", &s.name),
                next: namer.name("NX_", &s.name),
            })
        })
        .collect();
    let nets = project
        .nets
        .iter()
        .map(|n| namer.name("M_", &n.name))
        .collect();
    Names {
        controller: String::new(),
        program: String::new(),
        configuration: Default::default(),
        inputs,
        outputs,
        input_index,
        output_index,
        timers,
        events,
        states,
        tables,
        sparse,
        nets,
    }
}
