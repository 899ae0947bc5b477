//! The exported Structured Text, executed: every seed project and the
//! boiler exported with `iec_export` (as `codegen st` writes it),
//! parsed and run by `iec-st` (an interpreter of the IEC 61131-3 subset,
//! written from the standard, which shares no code with the exporter or
//! the executor), in lockstep with host-sim's executor on the same
//! inputs. Every scan compares every output, every supervisor state (a
//! net's marking packed as the executor packs it), the executed and the
//! unexpected events in order, the fault and its cause, and the fault and
//! ignore counters.
//!
//! Inputs: host-sim's guided random sequences (every project, at least
//! 10,000 scans, with faults and resets), the press's recorded cycle, the
//! boiler's closed-loop scenarios with its plant, and the batch cell's
//! two-batch closed loop. The program POU (the one a PLC task runs) is
//! run too, on its located inputs with its own clock.

#[path = "common/lockstep.rs"]
mod lockstep;
#[path = "common/symbolic.rs"]
mod symbolic;

use host_sim::inputs::InputRow;
use host_sim::random_inputs::guided_inputs;
use host_sim::Sim;
use iec_export::{self as iec, IoMap};
use iec_st::{Instance, IntType, Slot, Value};
use lockstep::{blind_inputs, compare, load, pack_states, root, Coverage, Observed, PROJECTS};
use plc_project::Project;
use std::path::Path;

/// The exported ST text of `project` (default addresses).
fn st_text(project: &Project) -> String {
    let export = iec::export(project, &IoMap::sequential(), "codegen st (test)")
        .unwrap_or_else(|e| panic!("{}: {e}", project.name));
    iec::st::print(&export)
}

/// The controller function block of an exported file, run by the
/// interpreter, with the slots the comparison reads.
struct StController {
    fb: Instance,
    now: Slot,
    inputs: Vec<Slot>,
    outputs: Vec<Slot>,
    /// Automaton state variables.
    states: Vec<Slot>,
    /// Per net, a slot per place.
    markings: Vec<Vec<Slot>>,
    fault: Slot,
    cause: Slot,
    fault_event: Slot,
    faults: Slot,
    ignored: Slot,
    n_events: Slot,
    events: Vec<Slot>,
    n_unexpected: Slot,
    unexpected: Vec<Slot>,
}

fn int(v: Value) -> i64 {
    v.as_i64().expect("an integer")
}

impl StController {
    fn new(project: &Project, text: &str) -> StController {
        let names = iec::export(project, &IoMap::sequential(), "t")
            .expect("exports")
            .names;
        let file = iec_st::parse(text).unwrap_or_else(|e| panic!("{}: {e}", project.name));
        let fb = file
            .instantiate(&names.controller)
            .unwrap_or_else(|e| panic!("{}: {e}", project.name));
        let slot = |path: &str| {
            fb.slot(path)
                .unwrap_or_else(|e| panic!("{}: {path}: {e}", project.name))
        };
        let events = (1..=project.events.len().max(1))
            .map(|k| slot(&format!("EVENTS[{k}]")))
            .collect();
        let uncontrollable = project.events.iter().filter(|e| !e.controllable).count();
        let unexpected = (1..=uncontrollable.max(1))
            .map(|k| slot(&format!("UNEXPECTED[{k}]")))
            .collect();
        let markings = project
            .nets
            .iter()
            .enumerate()
            .map(|(n, net)| {
                (0..net.net.places().len())
                    .map(|p| slot(&format!("{}[{p}]", names.nets[n])))
                    .collect()
            })
            .collect();
        StController {
            now: slot("NOW_MS"),
            inputs: names.inputs.iter().map(|n| slot(n)).collect(),
            outputs: names.outputs.iter().map(|n| slot(n)).collect(),
            states: names.states.iter().map(|n| slot(n)).collect(),
            markings,
            fault: slot("FAULT"),
            cause: slot("FAULT_CAUSE"),
            fault_event: slot("FAULT_EVENT"),
            faults: slot("FAULTS"),
            ignored: slot("IGNORED"),
            n_events: slot("N_EVENTS"),
            events,
            n_unexpected: slot("N_UNEXPECTED"),
            unexpected,
            fb,
        }
    }

    fn scan(&mut self, time_ms: u64, raw: &[bool]) {
        self.fb
            .set_slot(
                self.now,
                Value::int(IntType::Udint, i128::from(time_ms as u32)).expect("in range"),
            )
            .expect("NOW_MS");
        for (slot, &v) in self.inputs.iter().zip(raw) {
            self.fb.set_slot(*slot, Value::Bool(v)).expect("input");
        }
        self.fb
            .call()
            .expect("the scan runs without a runtime error");
    }

    fn get(&self, slot: &Slot) -> Value {
        self.fb.get_slot(*slot).expect("a slot of this block")
    }

    fn list(&self, n: &Slot, items: &[Slot]) -> Vec<u16> {
        let n = int(self.get(n)) as usize;
        items[..n].iter().map(|s| int(self.get(s)) as u16).collect()
    }
}

fn observe_st(project: &Project, st: &StController) -> Observed {
    let automata: Vec<u32> = st.states.iter().map(|s| int(st.get(s)) as u32).collect();
    let markings: Vec<Vec<u32>> = st
        .markings
        .iter()
        .map(|m| m.iter().map(|s| int(st.get(s)) as u32).collect())
        .collect();
    let states = pack_states(project, &automata, &markings);
    let fault = st
        .get(&st.fault)
        .as_bool()
        .expect("FAULT is BOOL")
        .then(|| {
            let cause = int(st.get(&st.cause));
            let event = if cause == iec::scan::CAUSE_UNEXPECTED {
                int(st.get(&st.fault_event))
            } else {
                -1
            };
            (cause, event)
        });
    Observed {
        executed: st.list(&st.n_events, &st.events),
        unexpected: st.list(&st.n_unexpected, &st.unexpected),
        states,
        outputs: st
            .outputs
            .iter()
            .map(|s| st.get(s).as_bool().expect("outputs are BOOL"))
            .collect(),
        fault,
        faults: int(st.get(&st.faults)) as u32,
        ignored: int(st.get(&st.ignored)) as u32,
    }
}

/// Runs `rows` through a fresh host-sim and the exported ST; panics at
/// the first scan where they differ, naming everything.
fn lockstep(project: &Project, text: &str, rows: &[InputRow], what: &str) -> Coverage {
    let mut st = StController::new(project, text);
    compare(project, rows, what, |_, row| {
        st.scan(row.time_ms, &row.values);
        observe_st(project, &st)
    })
}

/// Scans of guided random input per project.
const RANDOM_SCANS: usize = 10_000;

fn random_lockstep(rel: &str, seed: u64) {
    let project = load(rel);
    let text = st_text(&project);
    // Mostly expected events, a noisier run, then inputs toggled blindly
    // (every input, the reset too, with probability 1/16 per scan), whose
    // stray edges provoke unexpected events, faults and resets.
    let mut total = Coverage::default();
    for (scans, noise) in [
        (RANDOM_SCANS, 40),
        (RANDOM_SCANS / 2, 3),
        (RANDOM_SCANS / 2, 0),
    ] {
        let rows = if noise == 0 {
            blind_inputs(&project, scans, seed, 0)
        } else {
            guided_inputs(&project, scans, seed, noise).expect("inputs")
        };
        let cov = lockstep(&project, &text, &rows, &format!("random, noise {noise}"));
        assert_eq!(cov.scans, scans);
        total.add(cov);
    }
    // The runs must have exercised what they compare (the boiler's deeper
    // sequences are the closed-loop test's; the boiler and the conveyor
    // expect every input edge in every state, so only a corrupt state
    // faults them: `a_corrupt_state_faults_to_the_safe_image_until_reset`).
    total.assert_exercised(&project, rel);
    println!("{rel}: {}, 0 differences", total.summary(&project));
}

macro_rules! random_tests {
    ($($name:ident: $index:expr, $seed:expr;)*) => {$(
        #[test]
        fn $name() {
            random_lockstep(PROJECTS[$index], $seed);
        }
    )*};
}

random_tests! {
    motivating_random_inputs_give_the_same_trace: 0, 1;
    press_random_inputs_give_the_same_trace: 1, 2;
    press7_random_inputs_give_the_same_trace: 2, 3;
    conveyor_random_inputs_give_the_same_trace: 3, 4;
    crane_random_inputs_give_the_same_trace: 4, 5;
    agv_random_inputs_give_the_same_trace: 5, 6;
    boiler_random_inputs_give_the_same_trace: 6, 7;
    boiler_mono_random_inputs_give_the_same_trace: 7, 8;
    mixers_random_inputs_give_the_same_trace: 8, 9;
    cell_random_inputs_give_the_same_trace: 9, 10;
    iec_names_random_inputs_give_the_same_trace: 10, 11;
    module_random_inputs_give_the_same_trace: 11, 12;
    testbed_random_inputs_give_the_same_trace: 12, 13;
    breakdown_random_inputs_give_the_same_trace: 14, 15;
}

#[test]
fn the_press_cycle_as_recorded_gives_the_same_trace() {
    let project = load("models/press.plc.toml");
    let path = root().join("models/press/cycle.inputs.csv");
    let text = std::fs::read_to_string(&path).expect("inputs");
    let rows = host_sim::inputs::parse(&text, &path, &project).expect("parses");
    let cov = lockstep(&project, &st_text(&project), &rows, "cycle.inputs.csv");
    assert_eq!(cov.scans, rows.len());
    assert!(!cov.executed.is_empty());
}

/// The boiler's closed-loop scenarios (all but the controller stall,
/// whose overrun a PLC's own task watchdog handles): host-sim runs each
/// with the plant, and its input image per scan is replayed into the ST.
#[test]
fn the_boilers_closed_loop_scenarios_give_the_same_trace() {
    let project = load("models/boiler/boiler.plc.toml");
    let text = st_text(&project);
    let mut total = 0;
    let (mut executed, mut faults, mut resets) = (std::collections::BTreeSet::new(), 0, 0);
    for (name, rows) in lockstep::boiler_scenarios(&project) {
        let cov = lockstep(&project, &text, &rows, name);
        assert!(!cov.executed.is_empty(), "{name}: nothing happened");
        total += cov.scans;
        executed.extend(cov.executed);
        faults += cov.faults;
        resets += cov.resets;
    }
    assert!(total >= 10_000, "{total} scans");
    println!(
        "boiler scenarios: {total} scans, {} of {} events, {faults} faults, {resets} resets, 0 differences",
        executed.len(),
        project.events.len()
    );
}

/// The batch cell's two batches in closed loop with its plant.
#[test]
fn the_cells_two_batches_in_closed_loop_give_the_same_trace() {
    use host_sim::cell::{self, CellParams, CellPlant, Operator, Unit, Watch};
    let project = load("models/petri/cell/cell.plc.toml");
    let params = CellParams::default();
    let watch = Watch::of_project(&project, &params).expect("watch");
    let mut sim = Sim::new(project.clone(), codegen::backend::Backend::Table).expect("sim");
    let mut plant = CellPlant::new(params);
    let both = Operator::new()
        .press(1_000, Unit::A, 1_000)
        .press(1_000, Unit::B, 1_000);
    let run = cell::run(&mut sim, &mut plant, &both, &watch, 1_500_000).expect("runs");
    let csv = run.inputs_csv(&project).expect("inputs");
    let rows =
        host_sim::inputs::parse(&csv, Path::new("cell.inputs.csv"), &project).expect("parses");
    let cov = lockstep(&project, &st_text(&project), &rows, "two batches");
    assert!(cov.scans >= 10_000, "{} scans", cov.scans);
    assert_eq!(run.batches(Unit::A).len(), 1);
}

/// The program POU a PLC task runs: located inputs in, the controller
/// called with the program's own clock (one period per call), located
/// outputs out; equal to host-sim scanning on its period grid.
#[test]
fn the_program_wires_the_controller_to_its_addresses_and_keeps_time() {
    for rel in ["models/press.plc.toml", "models/crane.plc.toml"] {
        let project = load(rel);
        // The first input left to the PLC tool (`%I*`), the others at
        // addresses in reverse order.
        let mut map = String::from("[inputs]\n");
        for (k, input) in project.inputs.iter().enumerate() {
            let n = project.inputs.len() - 1 - k;
            let address = if k == 0 {
                "%I*".to_owned()
            } else {
                format!("%IX{}.{}", n / 8, n % 8)
            };
            map.push_str(&format!("\"{}\" = \"{address}\"\n", input.name));
        }
        map.push_str("[outputs]\n");
        for (k, output) in project.outputs.iter().enumerate() {
            map.push_str(&format!(
                "\"{}\" = \"%QX{}.{}\"\n",
                output.name,
                k / 8,
                k % 8
            ));
        }
        let io = IoMap::parse(&map, Path::new("io.toml")).expect("a valid map");
        let export = iec::export(&project, &io, "t").expect("exports");
        let text = iec::st::print(&export);
        let file = iec_st::parse(&text).expect("parses");
        let mut program = file.instantiate(&export.names.program).expect("program");
        let inputs: Vec<Slot> = export
            .names
            .inputs
            .iter()
            .enumerate()
            .map(|(k, n)| {
                let slot = program.slot(n).expect("located input");
                if k > 0 {
                    let m = project.inputs.len() - 1 - k;
                    let at = program
                        .slot_at(&format!("%IX{}.{}", m / 8, m % 8))
                        .expect("address");
                    assert_eq!(at, slot, "{rel}: input {n} at its address");
                }
                slot
            })
            .collect();
        let outputs: Vec<Slot> = export
            .names
            .outputs
            .iter()
            .map(|n| program.slot(n).expect("located output"))
            .collect();
        let period = u64::from(project.scan_period_ms);
        let rows = guided_inputs(&project, 3_000, 11, 40).expect("inputs");
        let mut sim = Sim::new(project.clone(), codegen::backend::Backend::Table).expect("sim");
        sim.retain_trace(false);
        let mut changes = 0;
        for (k, row) in rows.iter().enumerate() {
            // The program's clock advances a period per call, so the
            // inputs are replayed on that grid.
            let time = k as u64 * period;
            let host = sim
                .scan_with(time, &row.values)
                .expect("scan")
                .outputs
                .clone();
            for (slot, &v) in inputs.iter().zip(&row.values) {
                program.force_slot(*slot, Value::Bool(v)).expect("input");
            }
            program.call().expect("runs");
            let plc: Vec<bool> = outputs
                .iter()
                .map(|s| program.get_slot(*s).expect("slot").as_bool().expect("BOOL"))
                .collect();
            assert_eq!(host, plc, "{rel}: scan {k}");
            changes += usize::from(k > 0 && host.iter().any(|&o| o));
        }
        assert!(changes > 0, "{rel}: no output ever rose");
    }
}

/// The configuration `codegen st --configuration` appends: one resource
/// whose cyclic task has the project's scan period and runs the program
/// POU, checked by iec-st against the POUs of the same file.
#[test]
fn the_configuration_runs_the_program_in_a_task_of_the_scan_period() {
    for rel in ["models/press.plc.toml", "models/petri/cell/cell.plc.toml"] {
        let project = load(rel);
        let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
        let text = iec::st::print(&export) + &iec::st::configuration(&export);
        let file = iec_st::parse(&text).unwrap_or_else(|e| panic!("{rel}: {e}"));
        let [configuration] = file.configurations() else {
            panic!("{rel}: one configuration expected")
        };
        let [resource] = &configuration.resources[..] else {
            panic!("{rel}: one resource expected")
        };
        let [task] = &resource.tasks[..] else {
            panic!("{rel}: one task expected")
        };
        assert_eq!(
            task.interval_ms,
            Some(u64::from(project.scan_period_ms)),
            "{rel}"
        );
        let [instance] = &resource.programs[..] else {
            panic!("{rel}: one program instance expected")
        };
        assert_eq!(instance.task.as_deref(), Some(task.name.as_str()), "{rel}");
        assert_eq!(instance.pou, export.names.program, "{rel}");
        let program = file.instantiate(&instance.pou).expect("the program");
        assert_eq!(program.pou_name(), export.names.program, "{rel}");
    }
}

/// The comparison itself can fail: the press exported with one
/// transition of its supervisor redirected differs from host-sim.
#[test]
fn a_wrong_transition_in_the_exported_table_is_found() {
    let project = load("models/press.plc.toml");
    let text = st_text(&project);
    let table = &iec::export(&project, &IoMap::sequential(), "t")
        .expect("exports")
        .names
        .tables[0];
    let broken = lockstep::mutant(&text, table);
    let rows = guided_inputs(&project, 2_000, 2, 40).expect("inputs");
    let outcome = std::panic::catch_unwind(|| lockstep(&project, &broken, &rows, "mutant"));
    let text = lockstep::panic_text(outcome.expect_err("the mutant must differ"));
    assert!(text.contains("differs"), "{text}");
}

/// The fault path of every project's block, which inputs cannot reach in
/// projects that expect every edge (the boiler, the conveyor): a state
/// forced out of range is `FAULT_CAUSE` 2 with every output at its safe
/// level until the reset input rises, which restores the initial states
/// and the initial output image.
#[test]
fn a_corrupt_state_faults_to_the_safe_image_until_reset() {
    use plc_project::Drive;
    for rel in PROJECTS {
        let project = load(rel);
        if project.supervisors.is_empty() {
            continue;
        }
        let names = iec::export(&project, &IoMap::sequential(), "t")
            .expect("exports")
            .names;
        let mut st = StController::new(&project, &st_text(&project));
        let zeros = vec![false; project.inputs.len()];
        let rows = guided_inputs(&project, 200, 5, 40).expect("inputs");
        for row in &rows {
            st.scan(row.time_ms, &row.values);
        }
        let mut time = rows.last().map_or(0, |r| r.time_ms);
        // Guided inputs may leave a project in fault mode (an unexpected
        // event: the breakdown cell's repair button on an idle machine):
        // reset it first, so that the corruption is what faults it.
        if let (Some(_), Some(reset)) = (observe_st(&project, &st).fault, project.reset) {
            let mut pressed = zeros.clone();
            pressed[reset] = true;
            time += 10;
            st.scan(time, &pressed);
            time += 10;
            st.scan(time, &zeros);
            assert_eq!(observe_st(&project, &st).fault, None, "{rel}: reset");
        }
        let out_of_range = project.supervisors[0].automaton.num_states() as i128;
        let ty = match st.get(&st.states[0]) {
            Value::Int { ty, .. } => ty,
            Value::Bool(_) => panic!("a state is an integer"),
        };
        st.fb
            .force(
                &names.states[0],
                Value::int(ty, out_of_range).expect("fits"),
            )
            .expect("forced");
        for _ in 0..3 {
            time += 10;
            st.scan(time, &zeros);
            let seen = observe_st(&project, &st);
            assert_eq!(seen.fault, Some((iec::scan::CAUSE_CORRUPT, -1)), "{rel}");
            let safe: Vec<bool> = project.outputs.iter().map(|o| o.safe).collect();
            assert_eq!(seen.outputs, safe, "{rel}");
            assert!(seen.executed.is_empty(), "{rel}");
        }
        let Some(reset) = project.reset else {
            continue;
        };
        let mut pressed = zeros.clone();
        pressed[reset] = true;
        st.scan(time + 10, &pressed);
        let seen = observe_st(&project, &st);
        assert_eq!(seen.fault, None, "{rel}: the reset leaves fault mode");
        assert!(
            seen.executed.is_empty(),
            "{rel}: the reset scan runs no event"
        );
        let initial: Vec<u32> = project
            .supervisors
            .iter()
            .map(|s| s.automaton.initial().expect("initial").0)
            .collect();
        assert_eq!(seen.states[..initial.len()], initial[..], "{rel}");
        let image: Vec<bool> = project
            .outputs
            .iter()
            .map(|o| match &o.drive {
                Drive::Actions { initial } => *initial,
                Drive::States(map) => map
                    .iter()
                    .any(|(j, states)| states.iter().any(|s| s.0 == initial[*j])),
                Drive::Places(map) => map.iter().any(|(n, places)| {
                    places
                        .iter()
                        .any(|&p| project.nets[*n].net.initial()[p] > 0)
                }),
            })
            .collect();
        assert_eq!(seen.outputs, image, "{rel}: the initial output image");
    }
}

/// The scans whose end state holds a command of a symbolic supervisor
/// back by its guard alone: every supervisor having it allows it, it was
/// not executed in the scan, and its guard does not hold. (With every
/// command allowed once per scan, as in the module, such a command was
/// infeasible in the scan's last round because of its guard.)
fn held_back(project: &Project, seen: &Observed) -> usize {
    if seen.fault.is_some() {
        return 0;
    }
    let states = &seen.states;
    project
        .guarded
        .iter()
        .flat_map(|g| g.guards.iter().map(move |eg| (g, eg)))
        .filter(|(g, eg)| {
            let allowed = project.supervisors.iter().enumerate().all(|(j, sup)| {
                sup.local(eg.event).is_none_or(|(_, id)| {
                    sup.automaton
                        .successor(des::automaton::StateId(states[j]), id)
                        .is_some()
                })
            });
            allowed && !seen.executed.contains(&(eg.event as u16)) && !g.allows(eg.event, states)
        })
        .count()
}

/// Guards in action: the conveyor module's ten guards, each an inline
/// state comparison, hold commands back in the exported ST exactly when
/// the executor's guards do, and the runs reach such states.
#[test]
fn the_modules_guards_hold_commands_back_as_the_executor_does() {
    let project = load("models/module.plc.toml");
    let text = st_text(&project);
    assert!(text.contains("(* guard of stop_1 (module): LS1 = off *)"));
    // Noisy guided inputs: sensors change where the plant would not let
    // them, which is where guards hold stops back.
    let rows = guided_inputs(&project, 2_000, 13, 3).expect("inputs");
    let mut st = StController::new(&project, &text);
    let mut held = 0;
    let cov = compare(&project, &rows, "guards", |_, row| {
        st.scan(row.time_ms, &row.values);
        let seen = observe_st(&project, &st);
        held += held_back(&project, &seen);
        seen
    });
    assert_eq!(cov.scans, rows.len());
    assert!(held > 0, "no guard ever held a command back");
}

/// The comparison sees guards: the module exported without them (its
/// components only) runs commands the executor holds back.
#[test]
fn a_dropped_guard_is_found() {
    let project = load("models/module.plc.toml");
    let mut unguarded = project.clone();
    unguarded.guarded.clear();
    let text = st_text(&unguarded);
    assert!(!text.contains("guard of"));
    let rows = guided_inputs(&project, 2_000, 13, 3).expect("inputs");
    let outcome = std::panic::catch_unwind(|| lockstep(&project, &text, &rows, "unguarded"));
    let text = lockstep::panic_text(outcome.expect_err("the unguarded export must differ"));
    assert!(text.contains("differs"), "{text}");
}

/// Guards too large for a sum of products, written as chains of
/// temporaries: the module's commands each given a random decision
/// diagram over the components' state bits (a valid node table, children
/// first), in lockstep with the executor running the same guards.
#[test]
fn guards_written_as_chains_give_the_same_trace() {
    let project = lockstep::module_with_random_guards(0x00C0_FFEE);
    let text = st_text(&project);
    let chains = text.matches("GN[0] := ").count();
    assert!(chains >= 5, "{chains} guards written as chains");
    let rows = guided_inputs(&project, 2_000, 14, 3).expect("inputs");
    let mut st = StController::new(&project, &text);
    let mut held = 0;
    let cov = compare(&project, &rows, "random guards", |_, row| {
        st.scan(row.time_ms, &row.values);
        let seen = observe_st(&project, &st);
        held += held_back(&project, &seen);
        seen
    });
    assert!(!cov.executed.is_empty());
    assert!(held > 0, "no random guard ever held a command back");
}

/// Guards as synthesis makes them: symbolic supervisors of the
/// `des_symbolic` families (rings of machines and buffers, transfer
/// lines, dining philosophers, the module), synthesised at build time,
/// exported and run in lockstep with the executor; their guards come out
/// inline (`¬(a ∧ b ∧ …)` as `(S_a <> 1) OR (S_b <> 1) OR …`) and, for
/// the rings' larger ones, as chains.
#[test]
fn synthesised_guards_of_the_families_give_the_same_trace() {
    let (mut inline, mut chains, mut held, mut scans) = (0, 0, 0, 0);
    for (k, (family, n)) in [
        ("ring", 5),
        ("ring", 8),
        ("ringb", 4),
        ("tline", 5),
        ("phil", 5),
        ("phil", 8),
        ("module", 3),
    ]
    .into_iter()
    .enumerate()
    {
        let f = des_symbolic::families::by_name(family, n)
            .expect("a family")
            .expect("an instance");
        let dir = tempfile::tempdir().expect("a temporary directory");
        let events = symbolic::write_models(dir.path(), &f.plants, &f.specs);
        let text = symbolic::project_text(&events, true, "ignore", 0);
        let project = plc_project::from_str(&text, &dir.path().join("x.plc.toml"))
            .unwrap_or_else(|e| panic!("{family} {n}: {e}"));
        let st = st_text(&project);
        let guards = project.guarded[0]
            .guards
            .iter()
            .filter(|g| g.root != 1)
            .count();
        let chained = st.matches("GN[0] := ").count();
        assert_eq!(st.matches("(* guard of ").count(), guards, "{family} {n}");
        chains += chained;
        inline += guards - chained;
        let rows = guided_inputs(&project, 1_000, 40 + k as u64, 3).expect("inputs");
        let mut plc = StController::new(&project, &st);
        let cov = compare(&project, &rows, &format!("{family} {n}"), |_, row| {
            plc.scan(row.time_ms, &row.values);
            let seen = observe_st(&project, &plc);
            held += held_back(&project, &seen);
            seen
        });
        assert!(!cov.executed.is_empty(), "{family} {n}: nothing executed");
        scans += cov.scans;
    }
    println!("{scans} scans, {inline} guards inline, {chains} as chains, {held} commands held back by guards");
    assert!(inline > 0 && chains > 0, "{inline} inline, {chains} chains");
    assert!(held > 0, "no guard ever held a command back");
}
