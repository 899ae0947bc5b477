//! The JSON the page reads: the project's description
//! ([`model`], fetched once) and the simulation's state ([`state`], the
//! reply to every request). docs/simulator.md lists every field.

use super::explain::{self, Disabler};
use super::session::{Driver, LogEntry, Session};
use codegen::lower::Supervisors;
use des::automaton::{Automaton, StateId};
use plc_project::{Drive, Origin, Trigger};
use serde::Serialize;

/// Supervisors with at most this many states come with their diagram.
pub const DIAGRAM_STATES: usize = 40;

/// The project's description.
#[derive(Debug, Serialize)]
pub struct Model {
    project: ProjectInfo,
    plant: PlantInfo,
    inputs: Vec<InputInfo>,
    outputs: Vec<OutputInfo>,
    timers: Vec<TimerInfo>,
    events: Vec<EventInfo>,
    supervisors: Vec<SupervisorInfo>,
    nets: Vec<NetInfo>,
}

#[derive(Debug, Serialize)]
struct ProjectInfo {
    name: String,
    file: String,
    scan_period_ms: u32,
    backend: String,
    unexpected: &'static str,
    reset: Option<String>,
}

#[derive(Debug, Serialize)]
struct PlantInfo {
    kind: &'static str,
    text: String,
    components: Vec<String>,
    actions: Vec<ActionInfo>,
    analog: Vec<AnalogInfo>,
}

#[derive(Debug, Serialize)]
struct ActionInfo {
    name: String,
    label: String,
}

#[derive(Debug, Serialize)]
struct AnalogInfo {
    name: &'static str,
    label: &'static str,
    unit: &'static str,
    min: f64,
    max: f64,
}

#[derive(Debug, Serialize)]
struct InputInfo {
    name: String,
    debounce_scans: u8,
    reset: bool,
}

#[derive(Debug, Serialize)]
struct OutputInfo {
    name: String,
    safe: bool,
    drive: &'static str,
}

#[derive(Debug, Serialize)]
struct TimerInfo {
    name: String,
    preset_ms: u32,
}

#[derive(Debug, Serialize)]
struct EventInfo {
    name: String,
    controllable: bool,
    origin: &'static str,
    trigger: String,
    request: Option<String>,
    clickable: bool,
}

#[derive(Debug, Serialize)]
struct SupervisorInfo {
    name: String,
    kind: &'static str,
    states: usize,
    diagram: Option<Diagram>,
}

/// A small automaton's states and edges, for the page to lay out.
#[derive(Debug, Serialize)]
struct Diagram {
    states: Vec<DiagramState>,
    edges: Vec<DiagramEdge>,
}

#[derive(Debug, Serialize)]
struct DiagramState {
    name: String,
    initial: bool,
    marked: bool,
}

#[derive(Debug, Serialize)]
struct DiagramEdge {
    from: usize,
    to: usize,
    events: Vec<String>,
    controllable: bool,
}

#[derive(Debug, Serialize)]
struct NetInfo {
    name: String,
    places: Vec<PlaceInfo>,
    transitions: Vec<TransitionInfo>,
    arcs: Vec<ArcInfo>,
}

#[derive(Debug, Serialize)]
struct PlaceInfo {
    name: String,
    initial: u32,
    control: bool,
}

#[derive(Debug, Serialize)]
struct TransitionInfo {
    name: String,
    controllable: bool,
}

#[derive(Debug, Serialize)]
struct ArcInfo {
    place: usize,
    transition: usize,
    weight: u32,
    to_transition: bool,
}

fn diagram(a: &Automaton) -> Option<Diagram> {
    if a.num_states() > DIAGRAM_STATES {
        return None;
    }
    let states = (0..a.num_states())
        .map(|s| {
            let s = StateId(s as u32);
            DiagramState {
                name: a.state_name(s).into_owned(),
                initial: a.initial() == Some(s),
                marked: a.is_marked(s),
            }
        })
        .collect();
    let mut edges: Vec<DiagramEdge> = Vec::new();
    for from in 0..a.num_states() {
        for t in a.transitions(StateId(from as u32)) {
            let to = t.target.0 as usize;
            let name = a.alphabet().name(t.event).to_owned();
            let controllable = a.alphabet().is_controllable(t.event);
            match edges.iter_mut().find(|e| e.from == from && e.to == to) {
                Some(edge) => {
                    edge.events.push(name);
                    edge.controllable &= controllable;
                }
                None => edges.push(DiagramEdge {
                    from,
                    to,
                    events: vec![name],
                    controllable,
                }),
            }
        }
    }
    Some(Diagram { states, edges })
}

/// The description of `session`'s project, loaded from `file`.
pub fn model(session: &Session, file: &str) -> Model {
    let project = session.project();
    let machine = session.machine();
    let sim = session.sim();
    let supervisors = sim.supervisors();
    let name = |i: usize| project.inputs[i].name.clone();
    let names = |list: &[usize]| {
        list.iter()
            .map(|&i| name(i))
            .collect::<Vec<_>>()
            .join(" | ")
    };
    Model {
        project: ProjectInfo {
            name: project.name.clone(),
            file: file.to_owned(),
            scan_period_ms: sim.config().scan_period_ms,
            backend: sim.controller().program().backend().name().to_owned(),
            unexpected: match project.unexpected {
                plc_project::Unexpected::Fault => "fault",
                plc_project::Unexpected::Ignore => "ignore",
            },
            reset: project.reset.map(name),
        },
        plant: PlantInfo {
            kind: machine.kind(),
            text: machine.text(),
            components: match machine {
                super::machine::Machine::Automata(a) => {
                    a.components().iter().map(|c| c.name().to_owned()).collect()
                }
                _ => Vec::new(),
            },
            actions: session
                .actions()
                .iter()
                .map(|a| ActionInfo {
                    name: a.name.clone(),
                    label: a.label.clone(),
                })
                .collect(),
            analog: machine
                .analog()
                .iter()
                .map(|a| AnalogInfo {
                    name: a.name,
                    label: a.label,
                    unit: a.unit,
                    min: a.min,
                    max: a.max,
                })
                .collect(),
        },
        inputs: project
            .inputs
            .iter()
            .enumerate()
            .map(|(i, input)| InputInfo {
                name: input.name.clone(),
                debounce_scans: input.debounce_scans,
                reset: project.reset == Some(i),
            })
            .collect(),
        outputs: project
            .outputs
            .iter()
            .map(|o| OutputInfo {
                name: o.name.clone(),
                safe: o.safe,
                drive: match o.drive {
                    Drive::Actions { .. } => "actions",
                    Drive::States(_) => "states",
                    Drive::Places(_) => "places",
                },
            })
            .collect(),
        timers: project
            .timers
            .iter()
            .map(|t| TimerInfo {
                name: t.name.clone(),
                preset_ms: t.preset_ms,
            })
            .collect(),
        events: project
            .events
            .iter()
            .enumerate()
            .map(|(e, ev)| EventInfo {
                name: ev.name.clone(),
                controllable: ev.controllable,
                origin: match ev.origin {
                    Origin::Controller => "controller",
                    Origin::Operator => "operator",
                    Origin::Plant => "plant",
                },
                trigger: match &ev.trigger {
                    Trigger::Command => "command".to_owned(),
                    Trigger::Rising(list) => format!("rising {}", names(list)),
                    Trigger::Falling(list) => format!("falling {}", names(list)),
                    Trigger::Expired(t) => format!("expired {}", project.timers[*t].name),
                },
                request: ev.request.map(name),
                clickable: session.clickable(e),
            })
            .collect(),
        supervisors: (0..supervisors.len())
            .map(|j| supervisor_info(&supervisors, j))
            .collect(),
        nets: project
            .nets
            .iter()
            .map(|net| {
                let places = net.net.places();
                let control_from = places.len() - net.control_places;
                let mut arcs = Vec::new();
                for (t, tr) in net.net.transitions().iter().enumerate() {
                    for &(p, w) in &tr.input {
                        arcs.push(ArcInfo {
                            place: p,
                            transition: t,
                            weight: w,
                            to_transition: true,
                        });
                    }
                    for &(p, w) in &tr.output {
                        arcs.push(ArcInfo {
                            place: p,
                            transition: t,
                            weight: w,
                            to_transition: false,
                        });
                    }
                }
                NetInfo {
                    name: net.name.clone(),
                    places: places
                        .iter()
                        .enumerate()
                        .map(|(p, place)| PlaceInfo {
                            name: place.id.clone(),
                            initial: net.net.initial()[p],
                            control: p >= control_from,
                        })
                        .collect(),
                    transitions: net
                        .net
                        .transitions()
                        .iter()
                        .map(|t| TransitionInfo {
                            name: t.id.clone(),
                            controllable: t.controllable,
                        })
                        .collect(),
                    arcs,
                }
            })
            .collect(),
    }
}

fn supervisor_info(supervisors: &Supervisors<'_>, j: usize) -> SupervisorInfo {
    let project = supervisors.project();
    match supervisors.net_group(j) {
        Some(_) => SupervisorInfo {
            name: supervisors.name(j),
            kind: "net",
            states: 0,
            diagram: None,
        },
        None => {
            let sup = &project.supervisors[j];
            let component = matches!(
                sup.source,
                plc_project::SupervisorSource::Component { .. }
                    | plc_project::SupervisorSource::Plant { .. }
            );
            SupervisorInfo {
                name: sup.name.clone(),
                kind: if component { "component" } else { "automaton" },
                states: sup.automaton.num_states(),
                diagram: diagram(&sup.automaton),
            }
        }
    }
}

/// The simulation's state.
#[derive(Debug, Serialize)]
pub struct State<'a> {
    scan: u64,
    time_ms: u64,
    inputs: &'a [bool],
    outputs: Vec<bool>,
    timers: Vec<TimerState>,
    supervisors: Vec<SupervisorState>,
    markings: Vec<Vec<u32>>,
    fault: Option<FaultState>,
    commands: Vec<CommandState>,
    uncontrollable: Vec<EventState>,
    plant: PlantState,
    log: Vec<&'a LogEntry>,
    counters: CountersState,
    driver: Driver,
    /// Scans a fast-forward ran (only in its reply).
    #[serde(skip_serializing_if = "Option::is_none")]
    ran: Option<u64>,
    /// Its wall time on the server, µs.
    #[serde(skip_serializing_if = "Option::is_none")]
    elapsed_us: Option<u64>,
}

impl State<'_> {
    /// Adds a fast-forward's figures.
    pub fn with_run(mut self, ran: u64, elapsed_us: u64) -> Self {
        self.ran = Some(ran);
        self.elapsed_us = Some(elapsed_us);
        self
    }
}

#[derive(Debug, Serialize)]
struct TimerState {
    running: bool,
    remaining_ms: u32,
}

#[derive(Debug, Serialize)]
struct SupervisorState {
    state: u32,
    name: String,
}

#[derive(Debug, Serialize)]
struct FaultState {
    cause: String,
}

#[derive(Debug, Serialize)]
struct CommandState {
    event: String,
    enabled: bool,
    requested: Option<bool>,
    disabled_by: Vec<Disabler>,
}

#[derive(Debug, Serialize)]
struct EventState {
    event: String,
    expected: bool,
    needs: Option<String>,
}

#[derive(Debug, Serialize)]
struct PlantState {
    states: Vec<String>,
    analog: Vec<f64>,
}

#[derive(Debug, Serialize)]
struct CountersState {
    ignored: u32,
    overruns: u32,
    lost_edges: u32,
    faults: u32,
}

/// The state of `session` now.
pub fn state(session: &Session) -> State<'_> {
    let project = session.project();
    let sim = session.sim();
    let controller = sim.controller();
    let states = controller.states();
    let supervisors = sim.supervisors();
    let fault = session.fault();
    let now = session.time_ms() as u32;
    let raw = session.raw();
    let commands = project
        .events
        .iter()
        .enumerate()
        .filter(|(_, ev)| ev.controllable)
        .map(|(e, ev)| {
            let mut disabled_by = explain::disablers(&supervisors, sim.nets(), e, states);
            if let Some(cause) = &fault {
                disabled_by.insert(
                    0,
                    Disabler {
                        supervisor: "fault mode".to_owned(),
                        why: format!("no command runs in fault mode ({cause})"),
                    },
                );
            }
            CommandState {
                event: ev.name.clone(),
                enabled: disabled_by.is_empty(),
                requested: ev.request.map(|r| raw[r]),
                disabled_by,
            }
        })
        .collect();
    let uncontrollable = project
        .events
        .iter()
        .enumerate()
        .filter(|(_, ev)| !ev.controllable)
        .map(|(e, ev)| {
            let mut needs: Vec<String> = Vec::new();
            if let Some(unmet) = super::stimulus::unmet_conditions(project, e, raw) {
                needs.push(unmet);
            }
            if let super::machine::Machine::Automata(plant) = session.machine() {
                if let Some((component, state)) = plant.refuses(e) {
                    needs.push(format!("plant {component} in `{state}` cannot do it"));
                }
            }
            EventState {
                event: ev.name.clone(),
                expected: fault.is_none() && session.expected(e),
                needs: (!needs.is_empty()).then(|| needs.join("; ")),
            }
        })
        .collect();
    let counters = controller.counters();
    State {
        scan: session.scans(),
        time_ms: session.time_ms(),
        inputs: raw,
        outputs: controller.outputs().to_vec(),
        timers: (0..project.timers.len())
            .map(|t| match controller.timer_deadline(t) {
                Some(deadline) => TimerState {
                    running: true,
                    remaining_ms: deadline.wrapping_sub(now).min(1 << 31),
                },
                None => TimerState {
                    running: false,
                    remaining_ms: 0,
                },
            })
            .collect(),
        supervisors: (0..supervisors.len())
            .map(|j| SupervisorState {
                state: states[j],
                name: supervisors.state_name(j, states[j]),
            })
            .collect(),
        markings: sim
            .nets()
            .iter()
            .enumerate()
            .map(|(n, layout)| layout.unpack(&states[supervisors.net_supervisors(n)]))
            .collect(),
        fault: fault.map(|cause| FaultState { cause }),
        commands,
        uncontrollable,
        plant: PlantState {
            states: match session.machine() {
                super::machine::Machine::Automata(a) => a.state_names(),
                _ => Vec::new(),
            },
            analog: session.machine().analog_values(),
        },
        log: session.log().collect(),
        counters: CountersState {
            ignored: counters.ignored,
            overruns: counters.overruns,
            lost_edges: counters.lost_edges,
            faults: counters.faults,
        },
        driver: session.driver(),
        ran: None,
        elapsed_us: None,
    }
}
