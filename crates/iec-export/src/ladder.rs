//! The supervisors of a project as a ladder diagram (IEC 61131-3 LD), in
//! PLCopen XML (TC6 XML v2.01): one `<pou>` whose body is `<LD>`.
//!
//! # The function block
//!
//! `<project>_ladder` is a FUNCTION_BLOCK:
//!
//! - `VAR_INPUT`: `INIT` (the thesis's x⁰: back to the initial states and
//!   the switches' initial positions) and `E_<event>` for every event, TRUE
//!   for the call in which the event executes;
//! - `VAR_OUTPUT`: `X_<state>` for every state of every supervisor
//!   (`X_<supervisor>_<state>` when there are several), one-hot per
//!   supervisor, initially the initial state; `EN_<event>` for every
//!   controllable event, TRUE while every supervisor that has it defines it
//!   in its current state; the outputs of `[switches]` (the thesis's
//!   x_σ) and the state-mapped outputs, under the project's names;
//! - `VAR`: `N_<state>`, a pending state bit, only where a cycle needs one
//!   (below).
//!
//! The controller ([`super::scan`]) decides which events execute (the
//! phases, priorities, requests and the command limit of
//! docs/semantics.md); the ladder is told and moves the state bits.
//! docs/ladder.md sets the rungs of the motivating example and of the
//! stamping press next to the thesis's and the lesson's. An
//! event that a supervisor does not define in its current state moves
//! nothing (the controller never passes one: it is unexpected).
//!
//! # Rungs, top to bottom
//!
//! 1. **Init** (thesis §3.3, Table 3.1 rung 1; the lesson's initialisation
//!    section): `INIT` → S the initial state bit, R every other state bit;
//!    one rung per supervisor, then one rung putting every switch output
//!    at its initial level.
//! 2. **Transitions**, grouped by event in execution order: uncontrollable
//!    events in declaration order, then controllable ones in declaration
//!    order (the thesis's rule that plant-event rungs come above command
//!    rungs, §3.3 and §3.4.1 assumption 6; docs/semantics.md steps 4–5).
//!    One rung per transition q –σ→ q′ with q ≠ q′ (Table 3.1's rows): the
//!    NO contacts `X_q` and `E_σ` in series, the coils S `X_q′` and R
//!    `X_q` (the thesis's "x_q′ latched while x_q is unlatched", §3.4.3).
//!    Self-loops get no rung: they change no state bit (§3.4.1
//!    assumption 3). After an event's transition rungs come its **switch**
//!    rungs, one per switch it moves: `E_σ` → S the chosen position's
//!    output, R the others (Table 3.1's latch and unlatch columns).
//! 3. **Enables**, one rung per controllable event: for each supervisor
//!    that has it, the `X_q` contacts of the states that define it in
//!    parallel; the supervisors' blocks in series; coil `EN_σ`. An event no
//!    supervisor restricts has a bare coil on the rail; one a supervisor
//!    never allows, an R coil (never enabled).
//! 4. **Outputs**, one rung per state-mapped output: its states' `X_q`
//!    contacts in parallel, a plain coil (the lesson's output logic,
//!    Fig. 20.7).
//!
//! # The sequential-evaluation hazard
//!
//! A PLC evaluates rungs top to bottom, so a rung that sets `X_q′` is seen
//! by every later rung that reads `X_q′` in the same call. Across events
//! that chaining is wanted: the events of one call execute one after the
//! other, each from the state the previous one left, as the thesis's
//! rungs 3 and 4 do within one scan. Within one event it would be wrong: a
//! chain q –σ→ q′ –σ→ q″ would take two steps for one σ. The rungs of one
//! event are therefore **ordered** (the thesis's own remedy, rung order,
//! §3.4.1 assumption 6): a rung reading `X_q′` comes before every rung of
//! the same event that sets `X_q′`. A cycle of transitions under one
//! event cannot be ordered so; one of its rungs sets the pending bit
//! `N_q′` instead of `X_q′`, and an **unpark** rung after the event's
//! other rungs moves it: `N_q′` → S `X_q′`, R `N_q′`. Next-state
//! temporaries for every state would remove the hazard too, but cost a
//! copy rung per state and event; ordering costs nothing where there is
//! no cycle, which is every seed model.
//!
//! So one call with one event moves each supervisor along δ(q, σ), and a
//! call with several events executes them in rung order, which is the
//! order of a scan whenever its commands ran in declaration order (always
//! under `max_commands_per_scan = 1`). `INIT` acts before the events of
//! its call. Enables and outputs are computed from the state after the
//! call (the lesson's order: transitions, states, outputs, Point to
//! Ponder 5A).
//!
//! # Size limit
//!
//! A ladder is for reading next to the automaton; past a few hundred
//! rungs nobody checks one by eye, and the transition arrays of the
//! Structured Text export say the same in far less space.
//! [`DEFAULT_RUNG_LIMIT`] is 200: eight times the motivating example (25
//! rungs), room for a supervisor the size of the thesis's pilot flame
//! supervisor (21 states, 75 transitions), and every small seed project
//! fits (press 12, press7 13, crane 16, conveyor 17), while the
//! synthesised ones do not (boiler 8,665, agv 11,349: refused).
//! [`render`] refuses a ladder over its limit naming the line of the
//! supervisor that makes most of the rungs, the rung count and the
//! limit. [`render_fitting`] tries the smaller forms of a synthesised
//! supervisor first (reduced, then localized, beside its plant
//! components: the same closed loop), and renders the first that fits,
//! saying so in the function block's documentation; its refusal lists
//! the forms tried. Petri nets (`[[net]]`) are not rendered: a project with one is
//! refused, since enables without the net's places would be wrong. Nor are
//! the guards of symbolic supervisors (`[[supervisor]]` with `guards` or a
//! symbolic `synthesize`): a guard is any Boolean function of the
//! components' states, which a rung of contacts in parallel and blocks in
//! series cannot state in general, so a project with a guard that does not
//! always hold is refused at the line of its `[[supervisor]]` rather than
//! rendered with enables that would allow what the guards hold back.

use super::comment_text;
use super::names::{identifier, Namer};
use des::automaton::StateId;
use des::{Error, Location, Result};
use plc_project::{Action, Drive, Project, Shrink, SupervisorSource};
use std::fmt::Write;

/// Rungs a ladder may have unless the caller says otherwise.
pub const DEFAULT_RUNG_LIMIT: usize = 200;

/// A ladder rendering of a project.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ladder {
    /// The function block's name.
    pub name: String,
    /// The `<pou>` element, PLCopen XML TC6 v2.01, in the default
    /// namespace of its enclosing `<project>`.
    pub pou_xml: String,
    /// The rungs, top to bottom.
    pub rungs: Vec<Rung>,
    /// The variables, by what they stand for.
    pub interface: Interface,
}

/// The function block's variables, by the project item they stand for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Interface {
    /// The input that puts everything back to its initial value.
    pub init: String,
    /// Each event's input, in declaration order.
    pub events: Vec<String>,
    /// Each supervisor's state bits, in state order.
    pub states: Vec<Vec<String>>,
    /// Each controllable event's enable output (`None`: uncontrollable).
    pub enables: Vec<Option<String>>,
    /// Each project output the ladder writes (switch positions and state
    /// maps; `None`: left to the controller).
    pub outputs: Vec<Option<String>>,
    /// The pending bits (locals), if any cycle needs one.
    pub pending: Vec<String>,
}

/// One rung: contacts, coils and what it stands for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rung {
    /// What it implements.
    pub kind: RungKind,
    /// Blocks in series, each a set of contacts in parallel; none: the
    /// coils hang on the rail.
    pub contacts: Vec<Vec<Contact>>,
    /// The coils, all fed by the last block.
    pub coils: Vec<Coil>,
    /// One line saying what it does (also its comment in the diagram).
    pub text: String,
}

/// What a rung implements.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RungKind {
    /// `INIT` puts supervisor `supervisor` in its initial state.
    Init {
        /// Index into [`Project::supervisors`].
        supervisor: usize,
    },
    /// `INIT` puts every switch output at its initial level.
    SwitchInit,
    /// Transition `from` –`event`→ `to` of a supervisor.
    Transition {
        /// Index into [`Project::supervisors`].
        supervisor: usize,
        /// Source state.
        from: StateId,
        /// Index into [`Project::events`].
        event: usize,
        /// Target state.
        to: StateId,
        /// Sets the pending bit of `to` instead of its state bit (a
        /// cycle under one event; an [`RungKind::Unpark`] follows).
        parked: bool,
    },
    /// Moves the pending bit of `to` into its state bit.
    Unpark {
        /// Index into [`Project::supervisors`].
        supervisor: usize,
        /// The event whose cycle needed it.
        event: usize,
        /// The state.
        to: StateId,
    },
    /// `event` moves switch `switch` to `position` (`off`: every output
    /// of the switch low).
    Switch {
        /// Index into [`Project::events`].
        event: usize,
        /// Index into [`Project::switches`].
        switch: usize,
        /// The position's name, or `off`.
        position: String,
    },
    /// The enable coil of controllable event `event`.
    Enable {
        /// Index into [`Project::events`].
        event: usize,
    },
    /// A state-mapped output.
    Output {
        /// Index into [`Project::outputs`].
        output: usize,
    },
}

/// A contact: closed while its variable (negated: while it is FALSE).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Contact {
    /// The BOOL variable read.
    pub variable: String,
    /// A normally closed contact.
    pub negated: bool,
}

/// How a coil stores its power.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Storage {
    /// The variable takes the rung's power.
    Plain,
    /// Set to TRUE while powered, else unchanged.
    Set,
    /// Reset to FALSE while powered, else unchanged.
    Reset,
}

/// A coil writing one variable.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Coil {
    /// The BOOL variable written.
    pub variable: String,
    /// Plain, set or reset.
    pub storage: Storage,
}

fn no(variable: &str) -> Contact {
    Contact {
        variable: variable.to_owned(),
        negated: false,
    }
}

fn coil(variable: &str, storage: Storage) -> Coil {
    Coil {
        variable: variable.to_owned(),
        storage,
    }
}

/// A BOOL of the interface.
struct BoolVar {
    name: String,
    init: bool,
    doc: String,
}

/// The identifiers of one rendering.
struct Names {
    events: Vec<String>,
    outputs: Vec<String>,
    /// Per supervisor, per state.
    states: Vec<Vec<String>>,
    /// Per event, `Some` for controllable ones.
    enables: Vec<Option<String>>,
}

/// The name of `project`'s ladder function block, which [`super::export`]
/// keeps free of every other POU and variable of the project.
pub fn pou_name(project: &Project) -> String {
    format!("{}_ladder", identifier(&project.name))
}

/// `project`'s supervisors as a ladder function block; refuses a project
/// with Petri nets, one with a symbolic supervisor whose guards do not
/// all always hold (at the line of its `[[supervisor]]`), and one whose
/// ladder would have more than `limit` rungs.
pub fn render(project: &Project, limit: usize) -> Result<Ladder> {
    let built = build(project)?;
    if built.rungs.len() > limit {
        return Err(over_limit(project, &built.rungs, limit, ""));
    }
    Ok(finish(project, built, None))
}

/// A ladder that fits its rung limit, and the project it renders.
#[derive(Debug, Clone)]
pub struct Fitted {
    /// The ladder.
    pub ladder: Ladder,
    /// `None`: the ladder renders the project as given. `Some`: only a
    /// smaller form of its synthesised supervisors fits, and the ladder
    /// renders that form.
    pub shrunk: Option<Shrunk>,
}

/// The smaller form a [`Fitted`] ladder renders instead of the full one.
#[derive(Debug, Clone)]
pub struct Shrunk {
    /// Reduced or localized.
    pub shrink: Shrink,
    /// The project with its synthesised supervisors in that form: the
    /// one the ladder's state bits and interface are of, and the one to
    /// export beside it.
    pub project: Project,
    /// The rungs of the full ladder (over the limit).
    pub full_rungs: usize,
    /// What was shrunk, one sentence: each synthesised supervisor with
    /// its states before and after, and the rungs before and after.
    pub summary: String,
}

/// [`render`], falling back on a smaller form of the project's
/// synthesised supervisors when the full ladder is over `limit`.
///
/// A supervisor synthesised without `reduce` or `localize`
/// (`synthesize = { … }`) can be run reduced, or as local controllers,
/// beside its plant components with the same closed-loop behaviour (the
/// project loader checks that equality whenever it builds either form).
/// When the full ladder is over the limit and the project has such a
/// supervisor, `shrunk` loads the project in the reduced form, then in
/// the localized one ([`plc_project::load_shrunk`] for a project file;
/// `Ok(None)` for a project without such a supervisor), and the first
/// whose ladder fits is rendered, its summary in the function block's
/// documentation. When none fits, the error is [`render`]'s, with the
/// rung count of each form tried (or why it could not be loaded).
pub fn render_fitting(
    project: &Project,
    limit: usize,
    shrunk: impl Fn(Shrink) -> Result<Option<Project>>,
) -> Result<Fitted> {
    let full = build(project)?;
    if full.rungs.len() <= limit {
        return Ok(Fitted {
            ladder: finish(project, full, None),
            shrunk: None,
        });
    }
    let candidates = shrinkable(project);
    let mut tried = String::new();
    if !candidates.is_empty() {
        for shrink in [Shrink::Reduce, Shrink::Localize] {
            let form = format!("{} (`{} = true`)", shrink.adjective(), shrink.key());
            let small = match shrunk(shrink) {
                Ok(Some(small)) => small,
                Ok(None) => continue,
                Err(e) => {
                    let _ = write!(tried, "; tried {form}: it does not load ({e})");
                    continue;
                }
            };
            let built = build(&small)?;
            if built.rungs.len() > limit {
                let _ = write!(tried, "; tried {form}: {} rungs", built.rungs.len());
                continue;
            }
            let summary = summary(project, &candidates, &small, shrink, &full, &built, limit);
            let ladder = finish(&small, built, Some(&summary));
            return Ok(Fitted {
                ladder,
                shrunk: Some(Shrunk {
                    shrink,
                    project: small,
                    full_rungs: full.rungs.len(),
                    summary,
                }),
            });
        }
    }
    Err(over_limit(project, &full.rungs, limit, &tried))
}

/// The supervisors of `project` synthesised as one automaton without
/// `reduce` or `localize`: those [`Shrink`] changes.
fn shrinkable(project: &Project) -> Vec<usize> {
    (0..project.supervisors.len())
        .filter(|&j| {
            matches!(
                project.supervisors[j].source,
                SupervisorSource::Synthesized {
                    reduced: false,
                    local: None,
                    ..
                }
            )
        })
        .collect()
}

/// The sentence saying what a fitted ladder renders instead of `full`.
fn summary(
    project: &Project,
    candidates: &[usize],
    small: &Project,
    shrink: Shrink,
    full: &Built,
    built: &Built,
    limit: usize,
) -> String {
    let parts: Vec<String> = candidates
        .iter()
        .map(|&j| {
            let sup = &project.supervisors[j];
            let mut plant = 0;
            let mut controllers = Vec::new();
            for s in &small.supervisors {
                match &s.source {
                    SupervisorSource::Plant { reduced, .. } if *reduced == sup.name => plant += 1,
                    SupervisorSource::Synthesized { .. }
                        if s.name == sup.name
                            || s.name.strip_prefix(sup.name.as_str())
                                .is_some_and(|rest| rest.starts_with('.')) =>
                    {
                        controllers.push(s.automaton.num_states())
                    }
                    _ => {}
                }
            }
            let after = match (shrink, controllers.as_slice()) {
                (Shrink::Reduce, [n]) => format!("{n} states"),
                _ => format!(
                    "{} local controllers of {} states in all",
                    controllers.len(),
                    controllers.iter().sum::<usize>()
                ),
            };
            format!(
                "supervisor '{}' (synthesised, {} states) runs {} as {after} beside its {plant} plant components",
                sup.name,
                sup.automaton.num_states(),
                shrink.adjective()
            )
        })
        .collect();
    format!(
        "{}, with the same closed-loop behaviour (checked when the project was loaded): {} rungs, where the full ladder would have {}, over the limit of {limit}.",
        parts.join("; "),
        built.rungs.len(),
        full.rungs.len()
    )
}

/// The rungs of a rendering before they are printed.
struct Built {
    name: String,
    init: String,
    names: Names,
    pending: Vec<(String, usize, StateId)>,
    rungs: Vec<Rung>,
}

/// The rungs of `project`'s ladder, whatever their number; refuses a
/// project with Petri nets or guards that matter ([`render`]).
fn build(project: &Project) -> Result<Built> {
    if let Some(net) = project.nets.first() {
        return Err(Error::model(
            Location::new(&project.path, net.line, 1),
            format!(
                "net `{}`: the ladder (LD) rendering covers automaton supervisors only; export this project as Structured Text",
                net.name
            ),
        ));
    }
    // A guard is any Boolean function of the components' states: its
    // enable would need a rung per path or coils of its own, which the
    // rungs here (contacts in parallel, blocks in series) do not have.
    if let Some(g) = project
        .guarded
        .iter()
        .find(|g| g.guards.iter().any(|eg| eg.root != 1))
    {
        let guarded = g.guards.iter().filter(|eg| eg.root != 1).count();
        return Err(Error::model(
            Location::new(&project.path, g.line, 1),
            format!(
                "symbolic supervisor `{}`: the ladder (LD) rendering has no rungs for guards ({guarded} command(s) guarded), and enables without them would allow what the guards hold back; export this project as Structured Text",
                g.name
            ),
        ));
    }
    let mut namer = Namer::new();
    let name = pou_name(project);
    namer.reserve(&name);
    let init = namer.name("", "INIT");
    let names = Names {
        events: project
            .events
            .iter()
            .map(|e| namer.name("", &format!("E_{}", e.name)))
            .collect(),
        outputs: project
            .outputs
            .iter()
            .map(|o| namer.name("", &o.name))
            .collect(),
        states: project
            .supervisors
            .iter()
            .map(|sup| {
                let a = &sup.automaton;
                a.states()
                    .map(|s| {
                        let state = a.state_name(s);
                        if project.supervisors.len() > 1 {
                            namer.name("", &format!("X_{}_{state}", sup.name))
                        } else {
                            namer.name("", &format!("X_{state}"))
                        }
                    })
                    .collect()
            })
            .collect(),
        enables: project
            .events
            .iter()
            .map(|e| {
                e.controllable
                    .then(|| namer.name("", &format!("EN_{}", e.name)))
            })
            .collect(),
    };
    let mut builder = Builder {
        project,
        names: &names,
        namer,
        pending: Vec::new(),
        rungs: Vec::new(),
    };
    builder.init_rungs(&init);
    builder.transition_rungs();
    builder.enable_rungs();
    builder.output_rungs();
    let Builder { rungs, pending, .. } = builder;
    Ok(Built {
        name,
        init,
        names,
        pending,
        rungs,
    })
}

/// The ladder of `built`; `note`, if any, joins the function block's
/// documentation.
fn finish(project: &Project, built: Built, note: Option<&str>) -> Ladder {
    let Built {
        name,
        init,
        names,
        pending,
        rungs,
    } = built;
    let pou_xml = pou_xml(project, &name, &init, &names, &pending, &rungs, note);
    let written = |o: usize| {
        let output = &project.outputs[o];
        matches!(output.drive, Drive::States(_))
            || project
                .switches
                .iter()
                .any(|s| s.positions.iter().any(|&(_, po)| po == o))
    };
    let interface = Interface {
        init,
        outputs: (0..project.outputs.len())
            .map(|o| written(o).then(|| names.outputs[o].clone()))
            .collect(),
        pending: pending.into_iter().map(|(bit, ..)| bit).collect(),
        events: names.events,
        states: names.states,
        enables: names.enables,
    };
    Ladder {
        name,
        pou_xml,
        rungs,
        interface,
    }
}

/// The refusal of `rungs`, over `limit`, at the line of the supervisor
/// that makes most of them; `tried` (empty, or starting with `; `) says
/// what else was tried.
fn over_limit(project: &Project, rungs: &[Rung], limit: usize, tried: &str) -> Error {
    let own = |j: usize| {
        rungs
            .iter()
            .filter(|r| match r.kind {
                RungKind::Init { supervisor }
                | RungKind::Transition { supervisor, .. }
                | RungKind::Unpark { supervisor, .. } => supervisor == j,
                _ => false,
            })
            .count()
    };
    let largest = (0..project.supervisors.len()).max_by_key(|&j| (own(j), usize::MAX - j));
    let (line, whose) = match largest {
        Some(j) => (
            project.supervisors[j].line,
            format!(
                "; supervisor `{}` declared here makes {} of them",
                project.supervisors[j].name,
                own(j)
            ),
        ),
        None => (0, String::new()),
    };
    Error::model(
        Location::new(&project.path, line, if line > 0 { 1 } else { 0 }),
        format!(
            "the ladder (LD) rendering would have {} rungs, over the limit of {limit}{whose}{tried}; export the supervisors as Structured Text (transition arrays) instead",
            rungs.len()
        ),
    )
}

struct Builder<'a> {
    project: &'a Project,
    names: &'a Names,
    namer: Namer,
    /// Pending bits declared: (name, supervisor, state).
    pending: Vec<(String, usize, StateId)>,
    rungs: Vec<Rung>,
}

impl Builder<'_> {
    fn state_name(&self, j: usize, s: StateId) -> String {
        comment_text(&self.project.supervisors[j].automaton.state_name(s))
    }

    fn sup_name(&self, j: usize) -> String {
        comment_text(&self.project.supervisors[j].name)
    }

    fn init_rungs(&mut self, init: &str) {
        for (j, sup) in self.project.supervisors.iter().enumerate() {
            let Some(q0) = sup.automaton.initial() else {
                continue;
            };
            let mut coils = vec![coil(&self.names.states[j][q0.index()], Storage::Set)];
            for s in sup.automaton.states().filter(|&s| s != q0) {
                coils.push(coil(&self.names.states[j][s.index()], Storage::Reset));
            }
            self.rungs.push(Rung {
                kind: RungKind::Init { supervisor: j },
                contacts: vec![vec![no(init)]],
                coils,
                text: format!(
                    "{}: INIT -> initial state {}",
                    self.sup_name(j),
                    self.state_name(j, q0)
                ),
            });
        }
        let mut coils = Vec::new();
        for switch in &self.project.switches {
            for &(_, o) in &switch.positions {
                let high = matches!(
                    self.project.outputs[o].drive,
                    Drive::Actions { initial: true }
                );
                let storage = if high { Storage::Set } else { Storage::Reset };
                coils.push(coil(&self.names.outputs[o], storage));
            }
        }
        if !coils.is_empty() {
            self.rungs.push(Rung {
                kind: RungKind::SwitchInit,
                contacts: vec![vec![no(init)]],
                coils,
                text: "switches: INIT -> initial positions".into(),
            });
        }
    }

    /// Events in execution order: uncontrollable, then controllable, each
    /// in declaration order.
    fn execution_order(&self) -> Vec<usize> {
        let events = &self.project.events;
        let (c, u): (Vec<usize>, Vec<usize>) =
            (0..events.len()).partition(|&e| events[e].controllable);
        u.into_iter().chain(c).collect()
    }

    fn transition_rungs(&mut self) {
        for e in self.execution_order() {
            let mut unparks = Vec::new();
            for j in 0..self.project.supervisors.len() {
                let sup = &self.project.supervisors[j];
                let Some((_, id)) = sup.local(e) else {
                    continue;
                };
                let a = &sup.automaton;
                let step: Vec<Option<StateId>> = a
                    .states()
                    .map(|s| a.successor(s, id).filter(|&t| t != s))
                    .collect();
                for (from, to, parked) in hazard_free_order(&step) {
                    let target = if parked {
                        let bit = self.pending_bit(j, to);
                        unparks.push((j, to, bit.clone()));
                        bit
                    } else {
                        self.names.states[j][to.index()].clone()
                    };
                    let via = if parked {
                        format!(" (pending {target})")
                    } else {
                        String::new()
                    };
                    self.rungs.push(Rung {
                        kind: RungKind::Transition {
                            supervisor: j,
                            from,
                            event: e,
                            to,
                            parked,
                        },
                        contacts: vec![
                            vec![no(&self.names.states[j][from.index()])],
                            vec![no(&self.names.events[e])],
                        ],
                        coils: vec![
                            coil(&target, Storage::Set),
                            coil(&self.names.states[j][from.index()], Storage::Reset),
                        ],
                        text: format!(
                            "{}: {} --{}--> {}{via}",
                            self.sup_name(j),
                            self.state_name(j, from),
                            comment_text(&self.project.events[e].name),
                            self.state_name(j, to)
                        ),
                    });
                }
            }
            for (j, to, bit) in unparks {
                self.rungs.push(Rung {
                    kind: RungKind::Unpark {
                        supervisor: j,
                        event: e,
                        to,
                    },
                    contacts: vec![vec![no(&bit)]],
                    coils: vec![
                        coil(&self.names.states[j][to.index()], Storage::Set),
                        coil(&bit, Storage::Reset),
                    ],
                    text: format!(
                        "{}: pending {bit} -> {} (end of the {} cycle)",
                        self.sup_name(j),
                        self.state_name(j, to),
                        comment_text(&self.project.events[e].name)
                    ),
                });
            }
            self.switch_rungs(e);
        }
    }

    /// The pending bit of state `to` of supervisor `j`, declared once.
    fn pending_bit(&mut self, j: usize, to: StateId) -> String {
        if let Some((bit, ..)) = self
            .pending
            .iter()
            .find(|(_, pj, ps)| *pj == j && *ps == to)
        {
            return bit.clone();
        }
        let state = &self.names.states[j][to.index()];
        let bit = self.namer.name(
            "",
            &format!("N_{}", state.strip_prefix("X_").unwrap_or(state)),
        );
        self.pending.push((bit.clone(), j, to));
        bit
    }

    fn switch_rungs(&mut self, e: usize) {
        let event = &self.project.events[e];
        for (s, switch) in self.project.switches.iter().enumerate() {
            let mut coils = Vec::new();
            let mut position = "off".to_owned();
            for action in &event.actions {
                let (o, storage) = match *action {
                    Action::Set(o) => (o, Storage::Set),
                    Action::Clear(o) => (o, Storage::Reset),
                    Action::Start(_) | Action::Reset(_) => continue,
                };
                let Some((pos, _)) = switch.positions.iter().find(|&&(_, po)| po == o) else {
                    continue;
                };
                if storage == Storage::Set {
                    position = pos.clone();
                }
                coils.push(coil(&self.names.outputs[o], storage));
            }
            if coils.is_empty() {
                continue;
            }
            self.rungs.push(Rung {
                kind: RungKind::Switch {
                    event: e,
                    switch: s,
                    position: position.clone(),
                },
                contacts: vec![vec![no(&self.names.events[e])]],
                coils,
                text: format!(
                    "switch {}: {} -> {}",
                    comment_text(&switch.name),
                    comment_text(&event.name),
                    comment_text(&position)
                ),
            });
        }
    }

    fn enable_rungs(&mut self) {
        for (e, event) in self.project.events.iter().enumerate() {
            let Some(enable) = &self.names.enables[e] else {
                continue;
            };
            let mut blocks = Vec::new();
            let mut parts = Vec::new();
            let mut never = false;
            for (j, sup) in self.project.supervisors.iter().enumerate() {
                let Some((_, id)) = sup.local(e) else {
                    continue;
                };
                let a = &sup.automaton;
                let defined: Vec<StateId> = a
                    .states()
                    .filter(|&s| a.successor(s, id).is_some())
                    .collect();
                never |= defined.is_empty();
                parts.push(format!(
                    "{} in {{{}}}",
                    self.sup_name(j),
                    defined
                        .iter()
                        .map(|&s| self.state_name(j, s))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
                blocks.push(
                    defined
                        .iter()
                        .map(|s| no(&self.names.states[j][s.index()]))
                        .collect(),
                );
            }
            let (contacts, coils, why) = if never {
                (
                    Vec::new(),
                    vec![coil(enable, Storage::Reset)],
                    "never".to_owned(),
                )
            } else if blocks.is_empty() {
                (
                    Vec::new(),
                    vec![coil(enable, Storage::Plain)],
                    "always (no supervisor has it)".to_owned(),
                )
            } else {
                (
                    blocks,
                    vec![coil(enable, Storage::Plain)],
                    parts.join(" and "),
                )
            };
            self.rungs.push(Rung {
                kind: RungKind::Enable { event: e },
                contacts,
                coils,
                text: format!("enable {}: {why}", comment_text(&event.name)),
            });
        }
    }

    fn output_rungs(&mut self) {
        for (o, output) in self.project.outputs.iter().enumerate() {
            let Drive::States(maps) = &output.drive else {
                continue;
            };
            let mut block = Vec::new();
            let mut parts = Vec::new();
            for (j, states) in maps {
                block.extend(states.iter().map(|s| no(&self.names.states[*j][s.index()])));
                parts.push(format!(
                    "{} in {{{}}}",
                    self.sup_name(*j),
                    states
                        .iter()
                        .map(|&s| self.state_name(*j, s))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
            self.rungs.push(Rung {
                kind: RungKind::Output { output: o },
                contacts: vec![block],
                coils: vec![coil(&self.names.outputs[o], Storage::Plain)],
                text: format!(
                    "output {}: {}",
                    comment_text(&output.name),
                    parts.join(" or ")
                ),
            });
        }
    }
}

/// The transitions of one event in one supervisor (`step[q]`: the target
/// from q, self-loops left out) as (from, to, parked), ordered so that no
/// rung reads a state bit an earlier rung of the list has set: an edge
/// p→q only after the edge leaving q. Where only cycles remain, the edge
/// leaving the lowest remaining state of the first one found is parked
/// (sets a pending bit), which frees the rest of its cycle.
pub fn hazard_free_order(step: &[Option<StateId>]) -> Vec<(StateId, StateId, bool)> {
    let n = step.len();
    let mut done: Vec<bool> = step.iter().map(Option::is_none).collect();
    let mut order = Vec::new();
    loop {
        let mut progress = false;
        for p in 0..n {
            if done[p] {
                continue;
            }
            let Some(q) = step[p] else { continue };
            if done[q.index()] {
                order.push((StateId(p as u32), q, false));
                done[p] = true;
                progress = true;
            }
        }
        if progress {
            continue;
        }
        // Every edge left waits on another: follow one chain to its cycle.
        let Some(start) = (0..n).find(|&p| !done[p]) else {
            break;
        };
        let mut seen = vec![false; n];
        let mut p = start;
        while !seen[p] {
            seen[p] = true;
            p = step[p].map_or(p, StateId::index);
        }
        let mut lowest = p;
        let mut c = step[p].map_or(p, StateId::index);
        while c != p {
            lowest = lowest.min(c);
            c = step[c].map_or(c, StateId::index);
        }
        let to = step[lowest].unwrap_or(StateId(lowest as u32));
        order.push((StateId(lowest as u32), to, true));
        done[lowest] = true;
    }
    order
}

// ---------------------------------------------------------------------
// PLCopen XML.

/// Layout grid (PLCopen coordinates): contacts and coils are `EL_W` ×
/// `EL_H`, columns `COL` apart, parallel branches `ROW` apart.
const EL_W: i64 = 21;
const EL_H: i64 = 16;
const PIN_Y: i64 = EL_H / 2;
const COL: i64 = 60;
const ROW: i64 = 30;
const RAIL_X: i64 = 20;
const RAIL_W: i64 = 3;
const FIRST_X: i64 = 60;
const COMMENT_H: i64 = 20;
const RUNG_GAP: i64 = 30;

const XHTML: &str = "http://www.w3.org/1999/xhtml";

fn esc(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn xhtml(text: &str) -> String {
    format!("<p xmlns=\"{XHTML}\">{}</p>", esc(&comment_text(text)))
}

fn pou_xml(
    project: &Project,
    name: &str,
    init: &str,
    names: &Names,
    pending: &[(String, usize, StateId)],
    rungs: &[Rung],
    note: Option<&str>,
) -> String {
    let mut inputs = vec![BoolVar {
        name: init.to_owned(),
        init: false,
        doc: "back to the initial states and switch positions (the thesis's x0)".into(),
    }];
    for (e, event) in project.events.iter().enumerate() {
        inputs.push(BoolVar {
            name: names.events[e].clone(),
            init: false,
            doc: format!(
                "event '{}' ({}) executes in this call",
                event.name,
                if event.controllable {
                    "controllable"
                } else {
                    "uncontrollable"
                }
            ),
        });
    }
    let mut outputs = Vec::new();
    for (j, sup) in project.supervisors.iter().enumerate() {
        let a = &sup.automaton;
        for s in a.states() {
            let initial = a.initial() == Some(s);
            outputs.push(BoolVar {
                name: names.states[j][s.index()].clone(),
                init: initial,
                doc: format!(
                    "supervisor '{}' is in state '{}'{}",
                    sup.name,
                    a.state_name(s),
                    if initial { " (initial)" } else { "" }
                ),
            });
        }
    }
    for (e, event) in project.events.iter().enumerate() {
        if let Some(enable) = &names.enables[e] {
            outputs.push(BoolVar {
                name: enable.clone(),
                init: false,
                doc: format!("the supervisors allow '{}' now", event.name),
            });
        }
    }
    for switch in &project.switches {
        for (pos, o) in &switch.positions {
            outputs.push(BoolVar {
                name: names.outputs[*o].clone(),
                init: matches!(project.outputs[*o].drive, Drive::Actions { initial: true }),
                doc: format!(
                    "output '{}': switch '{}' at '{pos}'",
                    project.outputs[*o].name, switch.name
                ),
            });
        }
    }
    for (o, output) in project.outputs.iter().enumerate() {
        if matches!(output.drive, Drive::States(_)) {
            outputs.push(BoolVar {
                name: names.outputs[o].clone(),
                init: false,
                doc: format!("output '{}' (state map)", output.name),
            });
        }
    }
    let locals: Vec<BoolVar> = pending
        .iter()
        .map(|(bit, j, s)| BoolVar {
            name: bit.clone(),
            init: false,
            doc: format!(
                "pending: supervisor '{}' enters '{}' (a cycle under one event)",
                project.supervisors[*j].name,
                project.supervisors[*j].automaton.state_name(*s)
            ),
        })
        .collect();

    let mut out = String::new();
    let _ = writeln!(
        out,
        "<pou name=\"{}\" pouType=\"functionBlock\">",
        esc(name)
    );
    out.push_str("  <interface>\n");
    for (tag, vars) in [
        ("inputVars", &inputs),
        ("outputVars", &outputs),
        ("localVars", &locals),
    ] {
        if vars.is_empty() {
            continue;
        }
        let _ = writeln!(out, "    <{tag}>");
        for v in vars {
            let _ = write!(
                out,
                "      <variable name=\"{}\"><type><BOOL/></type>",
                esc(&v.name)
            );
            if v.init {
                out.push_str("<initialValue><simpleValue value=\"TRUE\"/></initialValue>");
            }
            let _ = writeln!(
                out,
                "<documentation>{}</documentation></variable>",
                xhtml(&v.doc)
            );
        }
        let _ = writeln!(out, "    </{tag}>");
    }
    out.push_str("  </interface>\n  <body>\n    <LD>\n");
    let mut ids = 0u64;
    let mut top = RUNG_GAP;
    for (k, rung) in rungs.iter().enumerate() {
        top = print_rung(&mut out, &mut ids, top, k + 1, rung);
    }
    out.push_str("    </LD>\n  </body>\n");
    let _ = writeln!(
        out,
        "  <documentation>{}</documentation>",
        xhtml(&format!(
            "Supervisors of project '{}' as ladder logic: call once per scan with the events the controller executed (at most one command per call keeps the order of docs/semantics.md); {} rungs.{}",
            project.name,
            rungs.len(),
            note.map_or(String::new(), |n| format!(" {n}"))
        ))
    );
    out.push_str("</pou>\n");
    out
}

/// A connection from a consumer pin at `to` to the producer `from_id`
/// whose pin is at `from`, drawn with one vertical segment.
fn connection(out: &mut String, from_id: u64, from: (i64, i64), to: (i64, i64)) {
    let _ = write!(out, "<connection refLocalId=\"{from_id}\">");
    let mut points = vec![to];
    if from.1 != to.1 {
        let mid = from.0 + (to.0 - from.0) / 2;
        points.push((mid, to.1));
        points.push((mid, from.1));
    }
    points.push(from);
    for (x, y) in points {
        let _ = write!(out, "<position x=\"{x}\" y=\"{y}\"/>");
    }
    out.push_str("</connection>");
}

/// A node's id and the absolute position of its output pin.
type Pin = (u64, (i64, i64));

fn connection_point_in(out: &mut String, at: (i64, i64), feeds: &[Pin]) {
    let _ = write!(
        out,
        "<connectionPointIn><relPosition x=\"0\" y=\"{PIN_Y}\"/>"
    );
    for &(id, pin) in feeds {
        connection(out, id, pin, (at.0, at.1 + PIN_Y));
    }
    out.push_str("</connectionPointIn>");
}

/// Prints rung number `number` with its comment at `top`; returns the
/// top of the next rung.
fn print_rung(out: &mut String, ids: &mut u64, top: i64, number: usize, rung: &Rung) -> i64 {
    let mut next_id = || {
        *ids += 1;
        *ids
    };
    let rows = rung
        .contacts
        .iter()
        .map(Vec::len)
        .chain([rung.coils.len(), 1])
        .max()
        .unwrap_or(1) as i64;
    let height = rows * ROW;
    let _ = writeln!(
        out,
        "      <comment localId=\"{}\" height=\"{COMMENT_H}\" width=\"{}\"><position x=\"{RAIL_X}\" y=\"{top}\"/><content>{}</content></comment>",
        next_id(),
        COL * 6,
        xhtml(&format!("Rung {number}: {}", rung.text))
    );
    let y0 = top + COMMENT_H + 10;
    let rail = next_id();
    let _ = writeln!(
        out,
        "      <leftPowerRail localId=\"{rail}\" height=\"{height}\" width=\"{RAIL_W}\"><position x=\"{RAIL_X}\" y=\"{y0}\"/><connectionPointOut formalParameter=\"\"><relPosition x=\"{RAIL_W}\" y=\"{PIN_Y}\"/></connectionPointOut></leftPowerRail>"
    );
    let mut feeds: Vec<Pin> = vec![(rail, (RAIL_X + RAIL_W, y0 + PIN_Y))];
    for (b, block) in rung.contacts.iter().enumerate() {
        let x = FIRST_X + b as i64 * COL;
        let mut pins = Vec::new();
        for (r, contact) in block.iter().enumerate() {
            let id = next_id();
            let y = y0 + r as i64 * ROW;
            let _ = write!(
                out,
                "      <contact localId=\"{id}\" height=\"{EL_H}\" width=\"{EL_W}\" negated=\"{}\"><position x=\"{x}\" y=\"{y}\"/>",
                contact.negated
            );
            connection_point_in(out, (x, y), &feeds);
            let _ = writeln!(
                out,
                "<connectionPointOut><relPosition x=\"{EL_W}\" y=\"{PIN_Y}\"/></connectionPointOut><variable>{}</variable></contact>",
                esc(&contact.variable)
            );
            pins.push((id, (x + EL_W, y + PIN_Y)));
        }
        feeds = pins;
    }
    let x = FIRST_X + rung.contacts.len() as i64 * COL;
    let mut coil_pins = Vec::new();
    for (r, c) in rung.coils.iter().enumerate() {
        let id = next_id();
        let y = y0 + r as i64 * ROW;
        let storage = match c.storage {
            Storage::Plain => String::new(),
            Storage::Set => " storage=\"set\"".into(),
            Storage::Reset => " storage=\"reset\"".into(),
        };
        let _ = write!(
            out,
            "      <coil localId=\"{id}\" height=\"{EL_H}\" width=\"{EL_W}\"{storage}><position x=\"{x}\" y=\"{y}\"/>"
        );
        connection_point_in(out, (x, y), &feeds);
        let _ = writeln!(
            out,
            "<connectionPointOut><relPosition x=\"{EL_W}\" y=\"{PIN_Y}\"/></connectionPointOut><variable>{}</variable></coil>",
            esc(&c.variable)
        );
        coil_pins.push((id, (x + EL_W, y + PIN_Y)));
    }
    let right_x = x + COL;
    let _ = write!(
        out,
        "      <rightPowerRail localId=\"{}\" height=\"{height}\" width=\"{RAIL_W}\"><position x=\"{right_x}\" y=\"{y0}\"/>",
        next_id()
    );
    for (id, pin) in coil_pins {
        let _ = write!(
            out,
            "<connectionPointIn><relPosition x=\"0\" y=\"{}\"/>",
            pin.1 - y0
        );
        connection(out, id, pin, (right_x, pin.1));
        out.push_str("</connectionPointIn>");
    }
    out.push_str("</rightPowerRail>\n");
    y0 + height + RUNG_GAP
}

#[cfg(test)]
mod tests {
    use super::*;

    fn order(step: &[Option<u32>]) -> Vec<(u32, u32, bool)> {
        let step: Vec<Option<StateId>> = step.iter().map(|s| s.map(StateId)).collect();
        hazard_free_order(&step)
            .into_iter()
            .map(|(f, t, p)| (f.0, t.0, p))
            .collect()
    }

    /// Executes the rungs of one event, as (from, to, parked), on a
    /// one-hot state `q` top to bottom, pending bits last.
    fn run(rungs: &[(u32, u32, bool)], n: usize, q: usize) -> usize {
        let mut x = vec![false; n];
        let mut pending = vec![false; n];
        x[q] = true;
        for &(f, t, parked) in rungs {
            if x[f as usize] {
                if parked {
                    pending[t as usize] = true;
                } else {
                    x[t as usize] = true;
                }
                x[f as usize] = false;
            }
        }
        for s in 0..n {
            if pending[s] {
                x[s] = true;
            }
        }
        assert_eq!(x.iter().filter(|&&b| b).count(), 1, "not one-hot: {x:?}");
        x.iter().position(|&b| b).unwrap()
    }

    #[test]
    fn a_chain_under_one_event_is_ordered_from_its_end() {
        // 0 -> 1 -> 2 -> 3 under one event: read 2 before setting it.
        let rungs = order(&[Some(1), Some(2), Some(3), None]);
        assert_eq!(rungs, vec![(2, 3, false), (1, 2, false), (0, 1, false)]);
        for q in 0..4 {
            let expect = [1, 2, 3, 3][q];
            assert_eq!(run(&rungs, 4, q), expect, "from {q}");
        }
    }

    #[test]
    fn cycles_under_one_event_park_one_edge_and_still_take_one_step() {
        // A 3-cycle 0 -> 1 -> 2 -> 0, a tree 3 -> 4 -> 1 into it, a
        // 2-cycle 5 <-> 6, and 7 without the event.
        let step = [
            Some(1),
            Some(2),
            Some(0),
            Some(4),
            Some(1),
            Some(6),
            Some(5),
            None,
        ];
        let rungs = order(&step);
        assert_eq!(rungs.len(), 7);
        assert_eq!(rungs.iter().filter(|r| r.2).count(), 2, "{rungs:?}");
        for (q, next) in step.iter().enumerate() {
            let expect = next.map_or(q, |t| t as usize);
            assert_eq!(run(&rungs, 8, q), expect, "from {q}: {rungs:?}");
        }
    }
}
