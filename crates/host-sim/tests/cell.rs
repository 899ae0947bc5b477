//! The batch process cell of seed D in closed loop (issue 13, item 6):
//! the PLC project `models/petri/cell/cell.plc.toml` (the recipe net with
//! the paper's five constraints, run as a controlled net) against the
//! plant simulation of `host_sim::cell`, every scan checked by its
//! invariants.

use codegen::backend::Backend;
use host_sim::cell::{self, CellParams, CellPlant, CellRun, Operator, Rule, Unit, Watch};
use host_sim::Sim;
use plc_project::Project;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn cell_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/petri/cell")
}

fn load(file: &str) -> Project {
    plc_project::load(&cell_dir().join(file)).unwrap_or_else(|e| panic!("{e}"))
}

fn project() -> &'static Project {
    static PROJECT: OnceLock<Project> = OnceLock::new();
    PROJECT.get_or_init(|| load("cell.plc.toml"))
}

/// Runs `project` against a fresh plant for `minutes` with `operator`.
fn run_on(project: &Project, operator: &Operator, minutes: u64) -> CellRun {
    let params = CellParams::default();
    let watch = Watch::of_project(project, &params).unwrap();
    let mut sim = Sim::new(project.clone(), Backend::Table).unwrap();
    let mut plant = CellPlant::new(params);
    cell::run(&mut sim, &mut plant, operator, &watch, minutes * 60_000).unwrap()
}

/// [`run_on`] the cell project, asserting that no invariant broke.
fn run(operator: &Operator, minutes: u64) -> CellRun {
    let run = run_on(project(), operator, minutes);
    assert!(
        run.violations.is_empty(),
        "{} violations, the first: {:?}",
        run.violations.len(),
        &run.violations[..run.violations.len().min(5)]
    );
    run
}

#[test]
fn one_batch_runs_the_recipe_to_the_end_and_leaves_the_cell_idle() {
    let run = run(&Operator::new().press(1_000, Unit::A, 1_000), 60);
    let batches = run.batches(Unit::A);
    assert_eq!(batches.len(), 1, "events: {:?}", run.events);
    assert!(run.batches(Unit::B).is_empty());
    println!(
        "one batch: {:?}, {} s",
        batches[0],
        batches[0].duration_ms() / 1000
    );
    println!("events: {:?}", run.events);
    assert_eq!(run.marking, "ra13+rb13+c1+c2+c3+c4+c5");
}

#[test]
fn two_batches_started_together_both_complete_where_the_paper_deadlocks() {
    let both = Operator::new()
        .press(1_000, Unit::A, 1_000)
        .press(1_000, Unit::B, 1_000);
    let run = run(&both, 24);
    assert_eq!(run.batches(Unit::A).len(), 1, "events: {:?}", run.events);
    assert_eq!(run.batches(Unit::B).len(), 1, "events: {:?}", run.events);
    // Both starts in the first scan, then mixing tank a takes substance B
    // (first in priority); mixing tank b may not take the other B (the
    // paper's deadlock) and prepares A instead.
    let first: Vec<&str> = run
        .events
        .iter()
        .take_while(|(t, _)| *t == 1_000)
        .map(|(_, e)| e.as_str())
        .collect();
    assert_eq!(first, ["t_ra8", "t_rb8", "t_ma2", "t_mb1"]);
    assert_eq!(run.marking, "ra13+rb13+c1+c2+c3+c4+c5");

    // Its inputs replayed open loop give the same events: the scenario the
    // QEMU harness replays (`cargo xtask qemu cell <this file>`).
    let csv = run.inputs_csv(project()).unwrap();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cell-two-batches.inputs.csv");
    std::fs::write(&path, &csv).unwrap();
    let rows = host_sim::inputs::parse(&csv, &path, project()).unwrap();
    let mut sim = Sim::new(project().clone(), Backend::Table).unwrap();
    let mut events = Vec::new();
    for r in &rows {
        let row = sim.scan_with(r.time_ms, &r.values).unwrap();
        events.extend(row.events.iter().map(|e| (r.time_ms, e.clone())));
    }
    assert_eq!(events, run.events);
    println!(
        "two batches: {} scans, last event at {} s; inputs in {}",
        run.scans,
        run.last_event_ms() / 1000,
        path.display()
    );
}

#[test]
fn without_the_deadlock_constraints_both_mixers_prepare_b_and_the_cell_stops() {
    // The same project with cell.resources.toml (heating, (7), (8) only).
    let dir = tempfile::tempdir().unwrap();
    let resources = variant(
        dir.path(),
        &format!(
            "[[net]]\nname = \"cell\"\nfile = {:?}\nconstraints = {:?}\n",
            cell_dir().join("cell.timed.toml"),
            cell_dir().join("cell.resources.toml")
        ),
    );
    let both = Operator::new()
        .press(1_000, Unit::A, 1_000)
        .press(1_000, Unit::B, 1_000);
    let run = run_on(&resources, &both, 120);
    assert!(run.violations.is_empty(), "{:?}", run.violations);
    assert!(run.batches(Unit::A).is_empty() && run.batches(Unit::B).is_empty());
    // Both mixing tanks hold substance B, both reactors wait for A: the
    // dead marking of the paper, reached within minutes and never left.
    assert_eq!(run.marking, "ma1+ma11+mb1+mb11+c1");
    assert!(
        run.last_event_ms() < 5 * 60_000,
        "last event at {} ms",
        run.last_event_ms()
    );
}

#[test]
fn batch_after_batch_in_both_reactors_for_hours_without_a_violation() {
    let solo = run(&Operator::new().press(1_000, Unit::A, 1_000), 60).batches(Unit::A)[0];
    let both = Operator::new().hold(1_000, Unit::A).hold(1_000, Unit::B);
    let run = run(&both, 6 * 60);
    for u in Unit::BOTH {
        let batches = run.batches(u);
        assert!(batches.len() >= 10, "reactor {}: {batches:?}", u.letter());
        for b in &batches {
            // Never faster than a batch alone, and never waiting more than
            // another batch's length for the shared mixing tanks and the
            // heat-up.
            assert!(b.duration_ms() >= solo.duration_ms(), "{b:?} vs {solo:?}");
            assert!(
                b.duration_ms() < 2 * solo.duration_ms(),
                "{b:?} vs {solo:?}"
            );
        }
    }
    // The reactors work in parallel: 20 batches take well under 20 alone.
    let twentieth = {
        let mut ends: Vec<u64> = Unit::BOTH
            .iter()
            .flat_map(|&u| run.batches(u).into_iter().map(|b| b.end_ms))
            .collect();
        ends.sort_unstable();
        ends[19]
    };
    assert!(
        twentieth < 20 * solo.duration_ms() * 3 / 4,
        "{twentieth} ms"
    );
    for (level, brim) in run.max_levels.iter().zip([0.8, 0.8, 1.4, 1.4]) {
        assert!(*level < brim, "{:?}", run.max_levels);
    }
    println!(
        "solo {} s; 20 batches in {} s; levels {:?}; reaction temperatures up to {:?}",
        solo.duration_ms() / 1000,
        twentieth / 1000,
        run.max_levels,
        run.max_reaction_temps
    );
}

#[test]
fn the_temperature_controller_heats_up_without_overshoot() {
    let params = CellParams::default();
    let run = run(&Operator::new().press(1_000, Unit::B, 1_000), 60);
    assert_eq!(run.batches(Unit::B).len(), 1);
    let peak = run.max_reaction_temps[1];
    assert!(peak > params.reaction_temp - params.setpoint_band, "{peak}");
    assert!(peak < params.reaction_temp + 0.1, "{peak}");
}

#[test]
fn the_timed_net_is_the_paper_net_with_uncontrollable_timers() {
    use des::petri;
    let paper = petri::read_file(&cell_dir().join("cell.toml")).unwrap();
    let timed = petri::read_file(&cell_dir().join("cell.timed.toml")).unwrap();
    assert_eq!(paper.places(), timed.places());
    assert_eq!(paper.initial(), timed.initial());
    let changed: Vec<&str> = paper
        .transitions()
        .iter()
        .zip(timed.transitions())
        .filter(|(p, t)| p != t)
        .map(|(p, t)| {
            let mut t = t.clone();
            t.controllable = p.controllable;
            assert_eq!(*p, t, "only controllability differs");
            p.id.as_str()
        })
        .collect();
    assert_eq!(changed, ["t_ra5", "t_rb5"]);
    assert!(timed.transitions().iter().all(|t| t.controllable
        != ["t_ra2", "t_ra3", "t_ra5", "t_rb2", "t_rb3", "t_rb5"].contains(&t.id.as_str())));
    // The controlled net the project runs: the paper's 265 markings.
    assert_eq!(project().nets[0].markings, 265);
    assert_eq!(project().nets[0].control_places, 5);
}

/// The project `cell.plc.toml` with its `[[net]]` table replaced by
/// `table` (model files by absolute path) and each line of its text
/// passed through `edit`, written into `dir` and loaded.
fn variant_with(dir: &Path, table: &str, edit: &dyn Fn(&str) -> String) -> Project {
    let text = std::fs::read_to_string(cell_dir().join("cell.plc.toml")).unwrap();
    let (head, tail) = text.split_once("[[net]]").unwrap();
    let board = &tail[tail.find("\n# Nucleo").unwrap()..];
    let head: String = head.lines().map(|l| edit(l) + "\n").collect();
    let path = dir.join("variant.plc.toml");
    std::fs::write(&path, format!("{head}{table}\n{board}")).unwrap();
    plc_project::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// [`variant_with`] the rest of the project as it is.
fn variant(dir: &Path, table: &str) -> Project {
    variant_with(dir, table, &|line| line.to_owned())
}

/// The same cell with its supervisor as an automaton: the reachability
/// graph of the controlled net (`codegen petri reach`; its states are
/// named by their markings), each output's place map turned into the
/// state map of the markings that mark the place.
fn automaton_project(dir: &Path) -> Project {
    use des::formats::{self, Component, Kind};
    let net = &project().nets[0].net;
    let reach = des::petri::reach::reachability(net, 100_000).unwrap();
    let file = dir.join("cell.supervisor.toml");
    let supervisor = Component {
        kind: Kind::Supervisor,
        automaton: reach.automaton.clone(),
    };
    formats::write_file(&file, &[supervisor]).unwrap();
    let state_map = |line: &str| {
        let Some((output, rest)) = line.split_once(" = { places = { cell = [\"") else {
            return line.to_owned();
        };
        let place = net.place(rest.split('"').next().unwrap()).unwrap();
        let states: Vec<String> = (0..reach.markings.len())
            .filter(|&i| reach.markings[i][place] > 0)
            .map(|i| format!("{:?}", reach.automaton.state_name(des::StateId(i as u32))))
            .collect();
        format!(
            "{output} = {{ states = {{ cell = [{}] }} }}",
            states.join(", ")
        )
    };
    let table = format!("[[supervisor]]\nname = \"cell\"\nfile = {file:?}\n");
    variant_with(dir, &table, &state_map)
}

#[test]
fn without_a_supervisor_the_checks_catch_the_double_booked_filling_valve() {
    let dir = tempfile::tempdir().unwrap();
    let timed = cell_dir().join("cell.timed.toml");
    let recipe = variant(
        dir.path(),
        &format!("[[net]]\nname = \"cell\"\nfile = {timed:?}\n"),
    );
    let params = CellParams::default();
    let watch = Watch::new(recipe.nets[0].net.clone(), Vec::new(), &params);
    let mut sim = Sim::new(recipe, Backend::Table).unwrap();
    let mut plant = CellPlant::new(params);
    let both = Operator::new()
        .press(1_000, Unit::A, 1_000)
        .press(1_000, Unit::B, 1_000);
    let run = cell::run(&mut sim, &mut plant, &both, &watch, 10 * 60_000).unwrap();
    // t_ma1 and t_ma2 in one scan: p_ma5 holds two tokens, components a
    // and b flow into mixing tank a together.
    let first = &run.violations[0];
    assert_eq!(first.time_ms, 1_000);
    let rules: Vec<&Rule> = run
        .violations
        .iter()
        .filter(|v| v.time_ms == 1_000)
        .map(|v| &v.rule)
        .collect();
    assert!(
        rules.contains(&&Rule::TwoSupplyValves(Unit::A)),
        "{rules:?}"
    );
    assert!(
        rules.contains(&&Rule::FillValveBooking(Unit::A)),
        "{rules:?}"
    );
}

#[test]
fn the_controlled_net_runs_in_a_fraction_of_the_automaton_supervisors_image() {
    // Kept after the test, for `cargo xtask qemu|size` on it.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cell-automaton");
    std::fs::create_dir_all(&dir).unwrap();
    let automaton = automaton_project(&dir);
    let figures = |p: &Project, states: usize| {
        let generated = codegen::emit::generate(p, Backend::Table, "cell.rs").unwrap();
        let tables: usize = generated.stats.iter().map(|s| s.table_bytes).sum();
        (states, tables, generated.image.image_bytes)
    };
    let net = figures(project(), project().nets[0].markings);
    let sup = figures(&automaton, automaton.supervisors[0].automaton.num_states());
    println!("| supervisor | states | table bytes | image bytes |");
    println!(
        "| controlled net (5 control places) | {} | {} | {} |",
        net.0, net.1, net.2
    );
    println!(
        "| automaton (reachability graph) | {} | {} | {} |",
        sup.0, sup.1, sup.2
    );
    // The same supervisor: as many markings as states ...
    assert_eq!(net.0, sup.0);
    // ... in fewer table bytes, and a fraction of the image: the
    // automaton's outputs need state maps of the markings.
    assert!(net.1 < sup.1, "{net:?} vs {sup:?}");
    assert!(net.2 * 2 < sup.2, "{net:?} vs {sup:?}");

    // And the same controller: two batches in closed loop give the same
    // events and outputs scan by scan, and the automaton's states read as
    // markings keep every invariant.
    let both = Operator::new()
        .press(1_000, Unit::A, 1_000)
        .press(1_000, Unit::B, 1_000);
    let params = CellParams::default();
    let watch = Watch::of_project(project(), &params).unwrap();
    let mut sim = Sim::new(automaton, Backend::Table).unwrap();
    let mut plant = CellPlant::new(params);
    let on_automaton = cell::run(&mut sim, &mut plant, &both, &watch, 24 * 60_000).unwrap();
    let on_net = run(&both, 24);
    assert!(
        on_automaton.violations.is_empty(),
        "{:?}",
        on_automaton.violations
    );
    assert_eq!(on_automaton.events, on_net.events);
    assert_eq!(on_automaton.commands, on_net.commands);
}
