//! The boiler of docs/seeds.md A (`models/boiler/`): plant and specification
//! models reconstructed from the thesis's requirements, synthesised here
//! and checked against `models/boiler/README.md` and the committed
//! supervisors in `models/boiler/sup/`.
//!
//! - pilot, main and complete boiler: monolithic supcon, non-empty,
//!   controllable, nonblocking, trim, and equal to the plain closed loop
//!   `plant ‖ spec` (the specifications need no pruning); sizes as in the
//!   README's table;
//! - the modular set for the complete boiler: each a supcon of its local
//!   plant, nonconflicting, their synchronous composition language-equal
//!   to the monolithic complete supervisor; sizes as in the README;
//! - the committed `sup/*.toml` isomorphic to a fresh synthesis;
//! - the README's event table lists exactly the plant events;
//! - no command loops (a cycle of controllable events would keep a PLC
//!   busy forever);
//! - scenarios run through the modular set with the PLC's choice rule
//!   (first feasible command in declaration order) give the command
//!   sequences the README describes, and never an unexpected event.
//!
//! Regenerate the committed supervisors after a model change with
//! `cargo test -p des --test boiler_models -- --ignored write_supervisors`.

use des::formats::read_file;
use des::ops::{self, ComposeOptions, Composition};
use des::{Automaton, StateId};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

// ------------------------------------------------------------- the models

const PILOT_PLANT: &[&str] = &[
    "selector",
    "pilot_flame",
    "purge_timer",
    "trial_timer",
    "pilot_valve",
    "ignition",
    "sd1",
    "bms",
];

const PILOT_SPECS: &[&str] = &[
    "pilot_seq",
    "rest_pilot_valve",
    "rest_ignition",
    "rest_purge_timer",
    "rest_trial_timer",
    "spark_needs_pilot_gas",
];

const MAIN_PLANT: &[&str] = &[
    "selector",
    "pilot_flame",
    "main_flame",
    "main_trial_timer",
    "damper",
    "blower",
    "main_valve",
    "bath_limit",
    "flue_limit",
    "sd2",
    "bms",
];

const MAIN_SPECS: &[&str] = &[
    "main_seq",
    "main_permit",
    "limit_bath",
    "limit_flue",
    "rest_damper",
    "rest_blower",
    "rest_main_valve",
    "rest_main_trial_timer",
    "damper_follows_selector",
    "blower_needs_damper",
    "gas_needs_blower",
    "gas_within_air",
    "main_alone",
];

/// The complete boiler's plant: every device.
const BOILER_PLANT: &[&str] = &[
    "selector",
    "pilot_flame",
    "main_flame",
    "purge_timer",
    "trial_timer",
    "main_trial_timer",
    "pilot_valve",
    "ignition",
    "main_valve",
    "damper",
    "blower",
    "bath_limit",
    "flue_limit",
    "sd1",
    "sd2",
    "bms",
    "reset_button",
];

/// The modular set for the complete boiler: supervisor name and its
/// specifications. The complete boiler's specification is all of them.
const MODULES: &[(&str, &[&str])] = &[
    ("sup_pilot_seq", &["boiler_pilot_seq"]),
    ("sup_main_seq", &["main_seq"]),
    (
        "sup_pilot_rest",
        &[
            "rest_pilot_valve",
            "rest_ignition",
            "rest_purge_timer",
            "rest_trial_timer",
        ],
    ),
    (
        "sup_main_rest",
        &[
            "rest_damper",
            "rest_blower",
            "rest_main_valve",
            "rest_main_trial_timer",
        ],
    ),
    (
        "sup_interlocks",
        &[
            "spark_needs_pilot_gas",
            "main_needs_pilot_gas",
            "damper_follows_selector",
            "blower_needs_damper",
            "gas_needs_blower",
            "gas_within_air",
        ],
    ),
    (
        "sup_main_start",
        &["main_permit", "limit_bath", "limit_flue"],
    ),
    ("sup_bms", &["bms_after_reset"]),
];

fn boiler_specs() -> Vec<&'static str> {
    MODULES
        .iter()
        .flat_map(|(_, s)| s.iter().copied())
        .collect()
}

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/boiler")
}

fn load(rel: &str) -> Automaton {
    let path = dir().join(rel);
    let mut components = read_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(components.len(), 1, "{}", path.display());
    components.remove(0).automaton
}

fn plants(names: &[&str]) -> Vec<Automaton> {
    names
        .iter()
        .map(|n| load(&format!("plant/{n}.toml")))
        .collect()
}

fn specs(names: &[&str]) -> Vec<Automaton> {
    names
        .iter()
        .map(|n| load(&format!("spec/{n}.toml")))
        .collect()
}

/// Synchronous composition with states named `a.b.c` after the parts.
fn compose(parts: &[&Automaton]) -> Automaton {
    ops::compose(parts, Composition::Sync, ComposeOptions::default())
        .unwrap()
        .automaton
}

/// One synthesis: the plant's and the specification's compositions, the
/// supcon result and its minimisation, with the component automata (for
/// state names).
struct Synthesis {
    plants: Vec<Automaton>,
    specs: Vec<Automaton>,
    plant: Automaton,
    spec: Automaton,
    sup: Automaton,
    min: Automaton,
}

impl Synthesis {
    fn new(plants: Vec<Automaton>, specs: Vec<Automaton>) -> Synthesis {
        let plant = compose(&plants.iter().collect::<Vec<_>>());
        let spec = compose(&specs.iter().collect::<Vec<_>>());
        let sup = ops::supcon(&plant, &spec).unwrap();
        let min = ops::minstate(&sup);
        Synthesis {
            plants,
            specs,
            plant,
            spec,
            sup,
            min,
        }
    }
}

/// The plant components that share an event with one of `specs`: the
/// local plant of a modular supervisor.
fn local_plant(specs: &[Automaton]) -> Vec<Automaton> {
    plants(BOILER_PLANT)
        .into_iter()
        .filter(|p| {
            specs.iter().any(|s| {
                s.alphabet()
                    .iter()
                    .any(|(_, e)| p.alphabet().contains(&e.name))
            })
        })
        .collect()
}

fn pilot() -> &'static Synthesis {
    static S: OnceLock<Synthesis> = OnceLock::new();
    S.get_or_init(|| Synthesis::new(plants(PILOT_PLANT), specs(PILOT_SPECS)))
}

fn main_flame() -> &'static Synthesis {
    static S: OnceLock<Synthesis> = OnceLock::new();
    S.get_or_init(|| Synthesis::new(plants(MAIN_PLANT), specs(MAIN_SPECS)))
}

fn boiler() -> &'static Synthesis {
    static S: OnceLock<Synthesis> = OnceLock::new();
    S.get_or_init(|| Synthesis::new(plants(BOILER_PLANT), specs(&boiler_specs())))
}

fn modules() -> &'static [(&'static str, Synthesis)] {
    static S: OnceLock<Vec<(&'static str, Synthesis)>> = OnceLock::new();
    S.get_or_init(|| {
        MODULES
            .iter()
            .map(|&(name, names)| {
                let specs = specs(names);
                (name, Synthesis::new(local_plant(&specs), specs))
            })
            .collect()
    })
}

fn size(a: &Automaton) -> (usize, usize) {
    (a.num_states(), a.num_transitions())
}

// ----------------------------------------------------------- the README

fn readme() -> String {
    std::fs::read_to_string(dir().join("README.md")).unwrap()
}

/// The rows of the Markdown table whose header row has `first` as its
/// first cell: header cells → values, keyed by the row's first cell
/// (backticks removed).
fn table(text: &str, first: &str) -> BTreeMap<String, HashMap<String, String>> {
    let cells = |line: &str| -> Vec<String> {
        line.trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().replace('`', ""))
            .collect()
    };
    let mut lines = text.lines().skip_while(|l| {
        !(l.starts_with('|') && cells(l).first().map(String::as_str) == Some(first))
    });
    let header = cells(lines.next().unwrap_or_else(|| panic!("no table `{first}`")));
    lines
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let row = cells(l);
            let map = header.iter().cloned().zip(row.iter().cloned()).collect();
            (row[0].clone(), map)
        })
        .collect()
}

/// "71 / 453" → (71, 453).
fn pair(cell: &str) -> (usize, usize) {
    let (a, b) = cell
        .split_once('/')
        .unwrap_or_else(|| panic!("`{cell}` is not `states / transitions`"));
    (a.trim().parse().unwrap(), b.trim().parse().unwrap())
}

// ---------------------------------------------------------------- tests

/// Non-empty, controllable, nonblocking, trim, and nothing pruned: the
/// specifications already are controllable and nonblocking, so the
/// supervisor's behaviour is exactly the designed one.
fn check_monolithic(name: &str, s: &Synthesis) {
    assert!(!s.sup.is_empty(), "{name}: empty supervisor");
    assert!(ops::is_trim(&s.sup), "{name}: not trim");
    assert_eq!(
        ops::check_controllable(&s.plant, &s.sup).unwrap(),
        None,
        "{name}"
    );
    assert_eq!(ops::check_nonblocking(&s.sup), None, "{name}");
    let closed_loop = compose(&[&s.plant, &s.spec]);
    assert_eq!(
        ops::language_difference(&closed_loop, &s.sup),
        None,
        "{name}: supcon pruned the specification"
    );
    assert!(ops::language_equal(&s.sup, &s.min), "{name}: minstate");
}

#[test]
fn monolithic_supervisors_are_correct_and_sized_as_in_the_readme() {
    let rows = table(&readme(), "controller");
    for (name, s) in [
        ("pilot", pilot()),
        ("main", main_flame()),
        ("complete", boiler()),
    ] {
        check_monolithic(name, s);
        let row = &rows[name];
        assert_eq!(pair(&row["our plant"]), size(&s.plant), "{name}: plant");
        assert_eq!(pair(&row["our spec"]), size(&s.spec), "{name}: spec");
        assert_eq!(pair(&row["our supcon"]), size(&s.sup), "{name}: supcon");
        assert_eq!(pair(&row["our minstate"]), size(&s.min), "{name}: minstate");
    }
}

#[test]
fn modular_set_is_nonconflicting_and_equals_the_complete_supervisor() {
    let rows = table(&readme(), "supervisor");
    let mods = modules();
    assert_eq!(rows.len(), mods.len(), "README module table rows");
    for (name, m) in mods {
        assert!(!m.sup.is_empty(), "{name}");
        assert_eq!(
            ops::check_controllable(&m.plant, &m.sup).unwrap(),
            None,
            "{name}"
        );
        assert_eq!(ops::check_nonblocking(&m.sup), None, "{name}");
        let row = &rows[*name];
        let specs: Vec<&str> = m.specs.iter().map(|s| s.name()).collect();
        let local: Vec<&str> = m.plants.iter().map(|p| p.name()).collect();
        assert_eq!(row["specifications"], specs.join(", "), "{name}");
        assert_eq!(row["local plant"], local.join(", "), "{name}");
        assert_eq!(pair(&row["plant"]), size(&m.plant), "{name}: plant");
        assert_eq!(pair(&row["supcon"]), size(&m.sup), "{name}: supcon");
        assert_eq!(pair(&row["minstate"]), size(&m.min), "{name}: minstate");
    }
    // Every device is in some local plant, so the modules' composition
    // contains the whole plant.
    let covered: BTreeSet<&str> = mods
        .iter()
        .flat_map(|(_, m)| m.plants.iter().map(|p| p.name()))
        .collect();
    assert_eq!(covered, BOILER_PLANT.iter().copied().collect());

    let sups: Vec<&Automaton> = mods.iter().map(|(_, m)| &m.sup).collect();
    assert_eq!(ops::check_nonconflicting(&sups).unwrap(), None);
    let together = compose(&sups);
    let complete = boiler();
    assert_eq!(
        ops::language_difference(&together, &complete.sup),
        None,
        "the modular set is not control-equivalent to the complete supervisor"
    );
    assert_eq!(
        ops::check_controllable(&complete.plant, &together).unwrap(),
        None
    );
    let row = &table(&readme(), "controller")["modular set"];
    assert_eq!(pair(&row["our supcon"]), size(&together), "modular meet");
}

#[test]
fn committed_supervisors_equal_a_fresh_synthesis() {
    let fresh =
        std::iter::once(("sup_pilot", pilot())).chain(modules().iter().map(|(n, m)| (*n, m)));
    for (name, s) in fresh {
        let committed = load(&format!("sup/{name}.toml"));
        assert_eq!(committed.name(), name);
        assert!(
            ops::isomorphic(&committed, &s.sup),
            "sup/{name}.toml is stale: regenerate it (see the top of this file)"
        );
    }
}

#[test]
fn readme_event_table_lists_the_plant_events() {
    let rows = table(&readme(), "event");
    let mut events = BTreeMap::new();
    for p in plants(BOILER_PLANT) {
        for (_, e) in p.alphabet().iter() {
            let kind = if e.controllable {
                "controllable"
            } else {
                "uncontrollable"
            };
            events.insert(e.name.clone(), kind.to_owned());
        }
    }
    let documented: BTreeMap<String, String> = rows
        .iter()
        .map(|(e, row)| (e.clone(), row["kind"].clone()))
        .collect();
    assert_eq!(documented, events);
}

/// Whether `a` has a cycle of controllable transitions (a self-loop
/// included): a PLC that may always issue one more command never waits.
fn command_cycle(a: &Automaton) -> Option<StateId> {
    // Iterative three-colour depth-first search.
    let n = a.num_states();
    let mut colour = vec![0u8; n];
    let next = |s: StateId| -> Vec<StateId> {
        a.transitions(s)
            .iter()
            .filter(|t| a.alphabet().is_controllable(t.event))
            .map(|t| t.target)
            .collect()
    };
    for root in a.states() {
        if colour[root.index()] != 0 {
            continue;
        }
        let mut stack = vec![(root, next(root), 0usize)];
        colour[root.index()] = 1;
        while let Some((s, succ, i)) = stack.last_mut() {
            if let Some(&t) = succ.get(*i) {
                *i += 1;
                match colour[t.index()] {
                    0 => {
                        colour[t.index()] = 1;
                        let succ = next(t);
                        stack.push((t, succ, 0));
                    }
                    1 => return Some(t),
                    _ => {}
                }
            } else {
                colour[s.index()] = 2;
                stack.pop();
            }
        }
    }
    None
}

#[test]
fn no_supervisor_allows_a_loop_of_commands() {
    for (name, s) in [
        ("pilot", pilot()),
        ("main", main_flame()),
        ("complete", boiler()),
    ] {
        if let Some(x) = command_cycle(&s.sup) {
            panic!(
                "{name}: a cycle of commands through {}",
                s.sup.state_name(x)
            );
        }
    }
}

/// Shutdown and closing commands: the only ones a supervisor may offer
/// together with another command.
const SHUTDOWN_AND_CLOSING: &[&str] = &[
    "sd1",
    "sd2",
    "mv_off",
    "ign_off",
    "pv_close",
    "blow_off",
    "dmp_off",
    "purge_reset",
    "trial_reset",
    "mtrial_reset",
];

#[test]
fn commands_compete_only_when_shutting_down_or_closing() {
    // So the PLC's declaration order never chooses the sequence, only
    // which valve closes first.
    for (name, s) in [
        ("pilot", pilot()),
        ("main", main_flame()),
        ("complete", boiler()),
    ] {
        let a = &s.sup;
        for x in a.states() {
            let enabled: Vec<&str> = a
                .transitions(x)
                .iter()
                .filter(|t| a.alphabet().is_controllable(t.event))
                .map(|t| a.alphabet().name(t.event))
                .collect();
            assert!(
                enabled.len() < 2 || enabled.iter().all(|e| SHUTDOWN_AND_CLOSING.contains(e)),
                "{name}: {enabled:?} enabled together in {}",
                a.state_name(x)
            );
        }
    }
}

// ------------------------------------------------------------ scenarios

/// The recommended declaration order of the controllable events in the
/// PLC project (the executor takes the first feasible one): shutdowns,
/// then closing, then BMS, then the sequence.
const COMMAND_ORDER: &[&str] = &[
    "sd1",
    "sd2",
    "mv_off",
    "ign_off",
    "pv_close",
    "blow_off",
    "dmp_off",
    "purge_reset",
    "trial_reset",
    "mtrial_reset",
    "bms",
    "pf_init",
    "mf_init",
    "purge_start",
    "pv_open",
    "trial_start",
    "ign_on",
    "dmp_lo",
    "dmp_hi",
    "blow_on",
    "mtrial_start",
    "mv_lo",
    "mv_hi",
];

/// A modular controller as the executor runs it (docs/semantics.md): an event
/// is feasible when every supervisor that has it can take it.
struct Plc<'a> {
    sups: Vec<&'a Automaton>,
    state: Vec<StateId>,
    /// `reset` in the previous scan (for `rst`, its rising edge).
    reset: bool,
}

impl<'a> Plc<'a> {
    fn new(sups: Vec<&'a Automaton>) -> Plc<'a> {
        let state = sups.iter().map(|s| s.initial().unwrap()).collect();
        Plc {
            sups,
            state,
            reset: false,
        }
    }

    fn step(&self, e: &str) -> Option<Vec<StateId>> {
        // A command no supervisor knows is a project validation error.
        if !self.sups.iter().any(|s| s.alphabet().contains(e)) {
            return None;
        }
        let mut next = self.state.clone();
        for (j, s) in self.sups.iter().enumerate() {
            if let Some(id) = s.alphabet().id(e) {
                next[j] = s.successor(self.state[j], id)?;
            }
        }
        Some(next)
    }

    /// One scan: the uncontrollable `inputs` in order (each must be
    /// feasible), then `rst` if `reset` rose and the supervisors know it
    /// (last of the inputs, as in the PLC projects), then every command
    /// that becomes feasible, first in [`COMMAND_ORDER`], each at most
    /// once; `bms` only while `reset` is held. Returns the commands.
    fn scan(&mut self, inputs: &[&str], reset: bool) -> Vec<&'static str> {
        for e in inputs {
            self.state = self
                .step(e)
                .unwrap_or_else(|| panic!("unexpected event `{e}`"));
        }
        if reset && !self.reset && self.sups.iter().any(|s| s.alphabet().contains("rst")) {
            self.state = self.step("rst").expect("`rst` is always possible");
        }
        self.reset = reset;
        let mut done = Vec::new();
        while let Some((e, next)) = COMMAND_ORDER
            .iter()
            .filter(|e| !done.contains(*e) && (**e != "bms" || reset))
            .find_map(|e| self.step(e).map(|n| (*e, n)))
        {
            self.state = next;
            done.push(e);
        }
        done
    }

    fn marked(&self) -> bool {
        self.sups
            .iter()
            .zip(&self.state)
            .all(|(s, &x)| s.is_marked(x))
    }
}

/// Runs `steps` (inputs, reset held, expected commands) on `sups`.
fn run<'a>(sups: Vec<&'a Automaton>, steps: &[(&[&str], bool, &[&str])]) -> Plc<'a> {
    let mut plc = Plc::new(sups);
    for (k, (inputs, reset, expected)) in steps.iter().enumerate() {
        assert_eq!(
            plc.scan(inputs, *reset),
            *expected,
            "scan {k}, inputs {inputs:?}"
        );
    }
    plc
}

/// Both the modular set and the monolithic supervisor.
/// The pre-purge expires: pilot gas, the trial timer, the spark.
const PURGED: (&[&str], bool, &[&str]) = (
    &["purge_done"],
    false,
    &["pv_open", "trial_start", "ign_on"],
);

fn run_boiler(steps: &[(&[&str], bool, &[&str])]) {
    let modular = run(modules().iter().map(|(_, m)| &m.sup).collect(), steps);
    let mono = run(vec![&boiler().sup], steps);
    assert_eq!(modular.marked(), mono.marked());
}

const NONE: &[&str] = &[];

#[test]
fn boiler_starts_runs_changes_fire_and_stops() {
    run_boiler(&[
        (&["op_high"], false, &["pf_init", "purge_start"]),
        (NONE, false, NONE),
        PURGED,
        (&["pf_on"], false, &["ign_off"]),
        // Pilot proving: the trial window expires with the flame.
        (
            &["trial_done"],
            false,
            &["mf_init", "dmp_hi", "blow_on", "mtrial_start", "mv_hi"],
        ),
        (&["mf_on"], false, &["mtrial_reset"]),
        (&["op_low"], false, &["mv_lo", "dmp_lo"]),
        (&["op_high"], false, &["dmp_hi", "mv_hi"]),
        (
            &["op_off"],
            false,
            &["mv_off", "pv_close", "blow_off", "dmp_off"],
        ),
        (NONE, true, NONE),
    ]);
}

#[test]
fn selection_changes_during_light_off_wait_for_the_main_flame() {
    run_boiler(&[
        (&["op_low"], false, &["pf_init", "purge_start"]),
        PURGED,
        (&["pf_on"], false, &["ign_off"]),
        // Pilot proving: the trial window expires with the flame.
        (
            &["trial_done"],
            false,
            &["mf_init", "dmp_lo", "blow_on", "mtrial_start", "mv_lo"],
        ),
        (&["op_high"], false, NONE),
        (&["mf_on"], false, &["mtrial_reset", "dmp_hi", "mv_hi"]),
    ]);
}

#[test]
fn ignition_timeout_shuts_down_until_bms_and_a_new_selection() {
    run_boiler(&[
        (&["op_low"], false, &["pf_init", "purge_start"]),
        PURGED,
        (&["trial_done"], false, &["sd1", "ign_off", "pv_close"]),
        (&["op_off"], false, NONE),
        (&["op_high"], false, NONE),
        (NONE, true, &["bms"]),
        (NONE, false, NONE),
        (&["op_low"], false, &["pf_init", "purge_start"]),
        (&["op_off"], false, &["purge_reset"]),
    ]);
}

#[test]
fn pilot_flame_losses_in_the_trial_window() {
    run_boiler(&[
        // One loss while the pilot is being proven: trial 2 sparks again
        // in the same window, and the pilot proven when the window expires
        // starts the main stage; a pilot loss then is a flame failure (sd2).
        (&["op_high"], false, &["pf_init", "purge_start"]),
        PURGED,
        (&["pf_on"], false, &["ign_off"]),
        (&["pf_off"], false, &["ign_on"]),
        (&["pf_on"], false, &["ign_off"]),
        (
            &["trial_done"],
            false,
            &["mf_init", "dmp_hi", "blow_on", "mtrial_start", "mv_hi"],
        ),
        (
            &["pf_off"],
            false,
            &[
                "sd2",
                "mv_off",
                "pv_close",
                "blow_off",
                "dmp_off",
                "mtrial_reset",
            ],
        ),
        (NONE, true, &["bms"]),
        // Two losses in one window: shutdown (sd1), burner management
        // after reset, and a new selection starts again.
        (&["op_low"], false, &["pf_init", "purge_start"]),
        PURGED,
        (&["pf_on"], false, &["ign_off"]),
        (&["pf_off"], false, &["ign_on"]),
        (&["pf_on"], false, &["ign_off"]),
        (&["pf_off"], false, &["sd1", "pv_close", "trial_reset"]),
        (NONE, true, &["bms"]),
        (&["op_high"], false, &["pf_init", "purge_start"]),
    ]);
}

#[test]
fn a_hot_limit_holds_the_start_and_a_rising_one_shuts_down_in_every_stage() {
    run_boiler(&[
        // Selector off: a limit edge is only remembered.
        (&["bath_over"], false, NONE),
        // Start interlock: the start waits with nothing open ...
        (&["op_high"], false, NONE),
        // ... and purges in full once the limit clears.
        (&["bath_ok"], false, &["pf_init", "purge_start"]),
        // Pre-purge.
        (&["flue_over"], false, &["sd1", "purge_reset"]),
        (&["op_off"], false, NONE),
        (&["flue_ok"], true, &["bms"]),
        // Pilot stage, sparking (pilot gas open).
        (&["op_low"], false, &["pf_init", "purge_start"]),
        PURGED,
        (
            &["bath_over"],
            false,
            &["sd1", "ign_off", "pv_close", "trial_reset"],
        ),
        // Reset with the selector on: idle, and a limit edge shuts down
        // again; a new selection while hot waits.
        (NONE, true, &["bms"]),
        (&["bath_ok"], false, NONE),
        (&["bath_over"], false, &["sd1"]),
        (NONE, true, &["bms"]),
        (&["op_high"], false, NONE),
        (&["bath_ok"], false, &["pf_init", "purge_start"]),
        (&["op_off"], false, &["purge_reset"]),
        // The limit rising in the scan the selector comes on (op_high is
        // declared before the limit edges): the selector is on, shutdown.
        (&["op_high", "bath_over"], false, &["sd1"]),
        (&["bath_ok"], true, &["bms"]),
        // Pilot established, main stage light-off.
        (&["op_low"], false, &["pf_init", "purge_start"]),
        PURGED,
        (&["pf_on"], false, &["ign_off"]),
        // Pilot proving: the trial window expires with the flame.
        (
            &["trial_done"],
            false,
            &["mf_init", "dmp_lo", "blow_on", "mtrial_start", "mv_lo"],
        ),
        (
            &["flue_over"],
            false,
            &[
                "sd2",
                "mv_off",
                "pv_close",
                "blow_off",
                "dmp_off",
                "mtrial_reset",
            ],
        ),
        (&["op_off"], true, &["bms"]),
    ]);
}

#[test]
fn main_flame_faults_and_over_temperature_shut_down() {
    let to_firing: &[(&[&str], bool, &[&str])] = &[
        (&["op_low"], false, &["pf_init", "purge_start"]),
        PURGED,
        (&["pf_on"], false, &["ign_off"]),
        // Pilot proving: the trial window expires with the flame.
        (
            &["trial_done"],
            false,
            &["mf_init", "dmp_lo", "blow_on", "mtrial_start", "mv_lo"],
        ),
    ];
    let shutdown: &[&str] = &["sd2", "mv_off", "pv_close", "blow_off", "dmp_off"];
    // The main flame does not form in time.
    let mut steps = to_firing.to_vec();
    steps.push((&["mtrial_done"], false, shutdown));
    steps.push((NONE, true, &["bms"]));
    run_boiler(&steps);
    // It forms, then fails.
    let mut steps = to_firing.to_vec();
    steps.push((&["mf_on"], false, &["mtrial_reset"]));
    steps.push((&["mf_off"], false, shutdown));
    run_boiler(&steps);
    // Off and a flame failure in the same scan: taken in declaration
    // order, fault first (lockout), or off first (closing, no alarm).
    let mut steps = to_firing.to_vec();
    steps.push((&["mf_on"], false, &["mtrial_reset"]));
    steps.push((&["mf_off", "op_off"], false, shutdown));
    run_boiler(&steps);
    let mut steps = to_firing.to_vec();
    steps.push((&["mf_on"], false, &["mtrial_reset"]));
    steps.push((&["op_off", "mf_off"], false, &shutdown[1..]));
    steps.push((NONE, true, NONE));
    run_boiler(&steps);
    // Flue gas over its limit while running.
    let mut steps = to_firing.to_vec();
    steps.push((&["mf_on"], false, &["mtrial_reset"]));
    steps.push((&["flue_over"], false, shutdown));
    steps.push((&["op_off"], true, &["bms"]));
    run_boiler(&steps);
    // A main flame signal before the main valve opened (false flame).
    run_boiler(&[
        (&["op_low"], false, &["pf_init", "purge_start"]),
        PURGED,
        (&["mf_on"], false, NONE),
        (&["pf_on"], false, &["ign_off"]),
        (&["trial_done"], false, NONE),
        (
            &["mf_off"],
            false,
            &["mf_init", "dmp_lo", "blow_on", "mtrial_start", "mv_lo"],
        ),
    ]);
}

#[test]
fn signals_the_models_must_tolerate_are_never_unexpected() {
    // Inputs already at 1 at power-up fall without having risen; both
    // selector contacts closed give repeated edges.
    run_boiler(&[
        (
            &["op_off", "pf_off", "mf_off", "bath_ok", "flue_ok"],
            false,
            NONE,
        ),
        (
            &["op_high", "op_low", "op_low"],
            false,
            &["pf_init", "purge_start"],
        ),
        (
            &["op_high", "op_high", "bath_over", "bath_over"],
            false,
            &["sd1", "purge_reset"],
        ),
    ]);
}

#[test]
fn pilot_and_main_controllers_alone() {
    let pilot = run(
        vec![&pilot().sup],
        &[
            (&["op_high"], false, &["pf_init", "purge_start"]),
            PURGED,
            (&["pf_on"], false, &["ign_off"]),
            (&["pf_off"], false, &["ign_on"]),
            (&["pf_on"], false, &["ign_off"]),
            (&["pf_off"], false, &["sd1", "pv_close", "trial_reset"]),
            (NONE, true, &["bms"]),
        ],
    );
    assert!(pilot.marked());
    let main = run(
        vec![&main_flame().sup],
        &[
            (&["op_low"], false, NONE),
            (
                &["pf_on"],
                false,
                &["mf_init", "dmp_lo", "blow_on", "mtrial_start", "mv_lo"],
            ),
            (&["mf_on"], false, &["mtrial_reset"]),
            (
                &["bath_over"],
                false,
                &["sd2", "mv_off", "blow_off", "dmp_off"],
            ),
            (&["mf_off"], true, &["bms"]),
            (
                &["bath_ok"],
                false,
                &["mf_init", "dmp_lo", "blow_on", "mtrial_start", "mv_lo"],
            ),
            (
                &["op_off"],
                false,
                &["mv_off", "blow_off", "dmp_off", "mtrial_reset"],
            ),
        ],
    );
    assert!(main.marked());
}

// ----------------------------------------------- writing sup/*.toml

/// Short names of the devices in state names.
fn short(device: &str) -> &str {
    match device {
        "pilot_flame" => "pf",
        "main_flame" => "mf",
        "purge_timer" => "purge",
        "trial_timer" => "trial",
        "main_trial_timer" => "mtrial",
        "pilot_valve" => "pv",
        "ignition" => "ign",
        "main_valve" => "mv",
        "damper" => "dmp",
        "blower" => "blow",
        other => other,
    }
}

/// A readable name for every state of `s.sup`: the specification states
/// joined by `.`, then `/device:state` for each device not in its initial
/// state (the supcon state names are the component states joined by `.`).
fn readable_names(s: &Synthesis) -> Vec<String> {
    let parts: Vec<&Automaton> = s.plants.iter().chain(&s.specs).collect();
    for a in &parts {
        for x in a.states() {
            assert!(
                !a.state_name(x).contains('.'),
                "{}: a `.` in a state",
                a.name()
            );
        }
    }
    s.sup
        .states()
        .map(|x| {
            let name = s.sup.state_name(x);
            let cells: Vec<&str> = name.split('.').collect();
            assert_eq!(cells.len(), parts.len(), "{name}");
            let (plant, spec) = cells.split_at(s.plants.len());
            let mut out = spec.join(".");
            for (p, cell) in s.plants.iter().zip(plant) {
                if *cell != p.state_name(p.initial().unwrap()) {
                    write!(out, "/{}:{cell}", short(p.name())).unwrap();
                }
            }
            out
        })
        .collect()
}

fn quoted(names: impl IntoIterator<Item = impl AsRef<str>>) -> String {
    names
        .into_iter()
        .map(|n| format!("\"{}\"", n.as_ref()))
        .collect::<Vec<_>>()
        .join(", ")
}

fn supervisor_toml(name: &str, what: &str, s: &Synthesis) -> String {
    let names = readable_names(s);
    assert_eq!(
        names.iter().collect::<BTreeSet<_>>().len(),
        names.len(),
        "{name}: state names not unique"
    );
    let a = &s.sup;
    let mut out = String::new();
    writeln!(out, "# {what}").unwrap();
    writeln!(
        out,
        "# supcon of the plant ({}) against the specifications ({}).",
        s.plants
            .iter()
            .map(|p| p.name())
            .collect::<Vec<_>>()
            .join(", "),
        s.specs
            .iter()
            .map(|p| p.name())
            .collect::<Vec<_>>()
            .join(", ")
    )
    .unwrap();
    writeln!(
        out,
        "# State names: specification states joined by `.`, then `/device:state`\n\
         # for every device not in its initial state. Generated by\n\
         # crates/des/tests/boiler_models.rs (write_supervisors), which also\n\
         # checks that this file equals a fresh synthesis: do not edit."
    )
    .unwrap();
    writeln!(out, "name = \"{name}\"").unwrap();
    writeln!(out, "kind = \"supervisor\"").unwrap();
    writeln!(out, "initial = \"{}\"", names[a.initial().unwrap().index()]).unwrap();
    writeln!(
        out,
        "marked = [{}]",
        quoted(a.marked_states().map(|x| &names[x.index()]))
    )
    .unwrap();
    let events = |c: bool| {
        quoted(
            a.alphabet()
                .iter()
                .filter(|(_, e)| e.controllable == c)
                .map(|(_, e)| e.name.clone()),
        )
    };
    writeln!(out, "controllable = [{}]", events(true)).unwrap();
    writeln!(out, "uncontrollable = [{}]", events(false)).unwrap();
    writeln!(out, "states = [").unwrap();
    for n in &names {
        writeln!(out, "  \"{n}\",").unwrap();
    }
    writeln!(out, "]").unwrap();
    writeln!(out, "transitions = [").unwrap();
    for (x, e, y) in a.iter_transitions() {
        writeln!(
            out,
            "  [\"{}\", \"{}\", \"{}\"],",
            names[x.index()],
            a.alphabet().name(e),
            names[y.index()]
        )
        .unwrap();
    }
    writeln!(out, "]").unwrap();
    out
}

#[test]
#[ignore = "writes models/boiler/sup/*.toml"]
fn write_supervisors() {
    let out = dir().join("sup");
    std::fs::create_dir_all(&out).unwrap();
    let mut files = vec![(
        "sup_pilot",
        "Pilot flame controller alone (thesis 4.4.2, PILOTSUPERVISOR).".to_owned(),
        pilot(),
    )];
    for (name, m) in modules() {
        files.push((
            name,
            format!("Complete boiler, modular supervisor {name} (see ../README.md)."),
            m,
        ));
    }
    for (name, what, s) in files {
        let text = supervisor_toml(name, &what, s);
        std::fs::write(out.join(format!("{name}.toml")), text).unwrap();
    }
}
