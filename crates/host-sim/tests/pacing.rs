//! One pacing rule on the board and on the host (`executor::pacing`):
//! host-sim's virtual clock with controller stalls gives the same scan
//! times, the same scan starts (lateness, skipped periods, overruns) and
//! the same trace as the firmware's scan loop (`crates/firmware/src/main.rs`)
//! on a simulated millisecond clock.
//!
//! The firmware's loop, as modelled here: until `Controller::scan_due`
//! says a scan is due, sleep to the next SysTick (1 ms); then sample the
//! inputs and run the scan at the time it was found due. A stall is the
//! loop hanging right after a scan (a scan that overruns into a blocking
//! driver, say): the clock moves on with no poll. `Sim::stall` is that
//! hang.

use codegen::backend::Backend;
use codegen::lower::{Lowered, NetLayout, Supervisors};
use executor::memory::HeapMemory;
use executor::pacing::{Pacer, ScanStart};
use executor::{Controller, Program};
use host_sim::boiler::{
    self, Action, BoilerController, BoilerParams, BoilerPlant, Inputs, Plc, Script, Selector,
};
use host_sim::{Sim, TraceRow};
use plc_project::{self as project, Project};
use std::path::Path;

fn project(name: &str) -> Project {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(name);
    project::load(&path).unwrap()
}

/// The firmware's scan loop on a simulated SysTick millisecond clock.
struct BoardLoop {
    project: Project,
    /// The program's net layouts, to name its supervisors.
    nets: Vec<NetLayout>,
    controller: Controller<Lowered, HeapMemory>,
    pacer: Pacer,
    /// SysTick's millisecond count.
    now_ms: u32,
    trace: Vec<TraceRow>,
    starts: Vec<ScanStart>,
}

impl BoardLoop {
    /// Starts at millisecond 0, the schedule's first deadline.
    fn new(project: &Project) -> BoardLoop {
        let program = Lowered::new(project, Backend::Table, &()).unwrap();
        let pacer = Pacer::for_config(&program.config(), 0);
        let memory = HeapMemory::for_config(&program.config());
        BoardLoop {
            project: project.clone(),
            nets: program.pools().nets.clone(),
            controller: Controller::new(program, memory).unwrap(),
            pacer,
            now_ms: 0,
            trace: Vec::new(),
            starts: Vec::new(),
        }
    }

    /// One pass of the loop: wait for the due scan, run it on `raw`, then
    /// hang for `hang_ms` before polling again.
    fn pass(&mut self, raw: &[bool], hang_ms: u32) {
        let start = loop {
            if let Some(start) = self.controller.scan_due(&mut self.pacer, self.now_ms) {
                break start;
            }
            self.now_ms += 1; // wfi until the next SysTick
        };
        let record = self.controller.scan(start.time_ms, raw);
        let supervisors = Supervisors::new(&self.project, &self.nets);
        let row = TraceRow::from_record(&record, u64::from(start.time_ms), supervisors);
        self.trace.push(row);
        self.starts.push(start);
        self.now_ms += hang_ms;
    }
}

/// One scan's input levels (by name; the others 0) and the stall after it.
struct Pass {
    high: &'static [&'static str],
    stall_ms: u32,
}

/// `scans` passes with `high` inputs at 1 and no stall.
fn steady(high: &'static [&'static str], scans: usize) -> impl Iterator<Item = Pass> {
    (0..scans).map(move |_| Pass { high, stall_ms: 0 })
}

fn stall(high: &'static [&'static str], stall_ms: u32) -> Pass {
    Pass { high, stall_ms }
}

/// The passes on the board loop and on a `Sim` (inputs set, `scan`,
/// `stall`); both traces must be equal row by row, and so must the scan
/// starts. Returns the trace and the starts.
fn both(
    project: &Project,
    passes: impl IntoIterator<Item = Pass>,
) -> (Vec<TraceRow>, Vec<ScanStart>) {
    let mut board = BoardLoop::new(project);
    let mut sim = Sim::new(project.clone(), Backend::Table).unwrap();
    let mut sim_starts = Vec::new();
    for pass in passes {
        let raw: Vec<bool> = project
            .inputs
            .iter()
            .map(|i| pass.high.contains(&i.name.as_str()))
            .collect();
        board.pass(&raw, pass.stall_ms);
        for (input, &level) in project.inputs.iter().zip(&raw) {
            sim.set(&input.name, level).unwrap();
        }
        sim.scan();
        sim_starts.push(sim.last_start().unwrap());
        sim.stall(u64::from(pass.stall_ms));
    }
    for (k, (b, s)) in board.trace.iter().zip(sim.trace()).enumerate() {
        assert_eq!(b, s, "scan {k}: board loop and host-sim differ");
    }
    assert_eq!(board.trace.len(), sim.trace().len());
    assert_eq!(board.starts, sim_starts);
    assert_eq!(board.controller.counters(), sim.controller().counters());
    (board.trace, board.starts)
}

fn times(trace: &[TraceRow]) -> Vec<u64> {
    trace.iter().map(|r| r.time_ms).collect()
}

fn late(starts: &[ScanStart]) -> Vec<(u32, u32, bool)> {
    starts
        .iter()
        .map(|s| (s.late_ms, s.skipped, s.overrun))
        .collect()
}

/// The first row from `from_ms` on that executed `event`.
fn first_event(trace: &[TraceRow], event: &str, from_ms: u64) -> Option<u64> {
    trace
        .iter()
        .find(|r| r.time_ms >= from_ms && r.events.iter().any(|e| e == event))
        .map(|r| r.time_ms)
}

#[test]
fn a_stall_of_two_and_a_half_periods_starts_the_next_scan_late_and_the_grid_resumes() {
    // The boiler: 10 ms period, overrun beyond 5 periods. The selector goes
    // to high in the scan at 20 ms, which hangs for 25 ms: the next scan
    // starts when the hang ends (45 ms, 15 ms after its deadline at 30 ms,
    // the one at 40 ms skipped), then the grid goes on at 50 ms.
    let boiler = project("boiler/boiler.plc.toml");
    let passes = steady(&[], 2)
        .chain([stall(&["sel_high"], 25)])
        .chain(steady(&["sel_high"], 1_100));
    let (trace, starts) = both(&boiler, passes);
    assert_eq!(times(&trace[..6]), [0, 10, 20, 45, 50, 60]);
    assert_eq!(
        late(&starts[2..5]),
        [(0, 0, false), (15, 1, false), (0, 0, false)]
    );
    assert!(trace.iter().all(|r| r.fault.is_none()));
    assert!(
        trace[4..].iter().all(|r| r.time_ms % 10 == 0),
        "on the grid"
    );
    // The late scan sees the selector (debounced over two scans) and starts
    // the 10 s purge; it expires at 10,045 ms, seen by the scan at 10,050.
    assert_eq!(first_event(&trace, "purge_start", 0), Some(45));
    assert_eq!(first_event(&trace, "purge_done", 0), Some(10_050));
}

#[test]
fn a_stall_over_the_overrun_limit_faults_the_late_scan_until_reset() {
    // 67 ms after the scan at 30 ms: the scan at 97 ms is 57 ms late, more
    // than 5 periods: an overrun, and with `overrun_fault` that scan runs
    // in fault mode (safe outputs, alarm on); five periods are skipped and
    // the grid resumes at 100 ms. The reset button's edge clears it.
    let boiler = project("boiler/boiler.plc.toml");
    let passes = steady(&["sel_high"], 3)
        .chain([stall(&["sel_high"], 67)])
        .chain(steady(&["sel_high"], 5))
        .chain(steady(&["sel_high", "reset"], 2))
        .chain(steady(&[], 3));
    let (trace, starts) = both(&boiler, passes);
    assert_eq!(times(&trace[..7]), [0, 10, 20, 30, 97, 100, 110]);
    assert_eq!(late(&starts[4..6]), [(57, 5, true), (0, 0, false)]);
    assert_eq!(trace[3].fault, None);
    for row in &trace[4..9] {
        assert_eq!(row.fault.as_deref(), Some("Overrun"), "at {}", row.time_ms);
        let alarm = boiler.output("alarm").unwrap();
        assert!(row
            .outputs
            .iter()
            .enumerate()
            .all(|(o, &v)| v == (o == alarm)));
    }
    assert_eq!(trace[9].fault, None, "the reset edge re-initialises");
}

#[test]
fn a_stall_of_exactly_the_overrun_limit_is_not_an_overrun() {
    // Hanging 60 ms after the scan at 30 ms: the scan at 90 ms is 50 ms
    // (exactly 5 periods) late; 61 ms makes it 51 ms late, an overrun.
    let boiler = project("boiler/boiler.plc.toml");
    let (trace, starts) = both(
        &boiler,
        steady(&[], 3).chain([stall(&[], 60)]).chain(steady(&[], 3)),
    );
    assert_eq!(times(&trace[3..6]), [30, 90, 100]);
    assert_eq!(late(&starts[4..5]), [(50, 5, false)]);
    assert!(trace.iter().all(|r| r.fault.is_none()));
    let (trace, starts) = both(
        &boiler,
        steady(&[], 3).chain([stall(&[], 61)]).chain(steady(&[], 3)),
    );
    assert_eq!(times(&trace[3..6]), [30, 91, 100]);
    assert_eq!(late(&starts[4..5]), [(51, 5, true)]);
    assert_eq!(trace[4].fault.as_deref(), Some("Overrun"));
}

#[test]
fn a_stall_that_ends_before_the_next_deadline_changes_nothing() {
    let press = project("press.plc.toml");
    let (trace, starts) = both(
        &press,
        steady(&[], 2).chain([stall(&[], 9)]).chain(steady(&[], 2)),
    );
    assert_eq!(times(&trace), [0, 10, 20, 30, 40]);
    assert!(starts.iter().all(|s| s.late_ms == 0));
}

#[test]
fn overruns_are_only_counted_when_the_project_says_so() {
    // The press: overrun_limit 1 (the default), no overrun_fault. The scan
    // after a 35 ms hang is 25 ms late: counted, two periods skipped, no
    // fault; the press goes on running its cycle.
    let press = project("press.plc.toml");
    let passes = steady(&["top_ls"], 2)
        .chain([stall(&["top_ls", "auto_pb"], 35)])
        .chain(steady(&["top_ls"], 3));
    let (trace, starts) = both(&press, passes);
    assert_eq!(times(&trace), [0, 10, 20, 55, 60, 70]);
    assert_eq!(late(&starts[3..4]), [(25, 2, true)]);
    assert!(trace.iter().all(|r| r.fault.is_none()));
    // The same through `Sim` alone: the counters say what happened.
    let mut sim = Sim::new(press, Backend::Table).unwrap();
    sim.set("top_ls", true).unwrap();
    sim.run(3);
    sim.stall(35);
    sim.run(3);
    let n = sim.controller().counters();
    assert_eq!((n.overruns, n.skipped_periods, n.faults), (1, 2, 0));
}

#[test]
fn stalls_add_up_and_a_stall_before_the_first_scan_delays_it() {
    let press = project("press.plc.toml");
    let mut sim = Sim::new(press, Backend::Table).unwrap();
    sim.stall(4);
    assert_eq!(sim.time_ms(), 4);
    assert_eq!(sim.scan().time_ms, 4);
    assert_eq!(sim.last_start().map(|s| s.late_ms), Some(4));
    // The grid keeps its phase from time 0.
    assert_eq!(sim.time_ms(), 10);
    sim.scan();
    sim.stall(8);
    sim.stall(8);
    assert_eq!(sim.time_ms(), 26);
    sim.run(2);
    assert_eq!(times(&sim.trace()[2..]), [26, 30]);
    let start = sim.last_start().unwrap();
    assert_eq!((start.late_ms, start.skipped), (0, 0));
}

#[test]
fn replays_with_explicit_times_bypass_the_schedule() {
    // `scan_with` runs at the caller's times; the virtual clock stays.
    let press = project("press.plc.toml");
    let mut sim = Sim::new(press.clone(), Backend::Table).unwrap();
    let raw = vec![false; press.inputs.len()];
    assert_eq!(sim.scan_with(1_234, &raw).unwrap().time_ms, 1_234);
    assert_eq!(sim.scan_with(7, &raw).unwrap().time_ms, 7);
    assert_eq!(sim.time_ms(), 0);
    assert_eq!(sim.last_start(), None);
}

#[test]
#[should_panic(expected = "a stall must be shorter than 2^31 ms")]
fn stalls_beyond_the_clock_horizon_are_refused() {
    let mut sim = Sim::new(project("press.plc.toml"), Backend::Table).unwrap();
    sim.scan();
    sim.stall(1 << 30);
    sim.stall(1 << 30);
}

#[test]
fn in_closed_loop_the_plant_follows_the_controller_through_a_stall() {
    // The scan at 40 s hangs for 300 ms: the plant runs on its outputs
    // until the late scan at 40.3 s (an overrun: 290 ms late), then the
    // scans go on every 10 ms and the plant reads at each scan's time.
    let boiler = project("boiler/boiler.plc.toml");
    let mut sim = Sim::new(boiler, Backend::Table).unwrap();
    let mut plant = BoilerPlant::new(BoilerParams::default(), 1);
    let script = Script::new()
        .at(1_000, Selector::High)
        .at(40_000, Action::Stall { ms: 300 });
    let run = boiler::run(&mut sim, &mut plant, &script, 41_000).unwrap();
    assert!(run.rows.iter().all(|r| r.plant.time_ms == r.time_ms));
    let at = run.rows.iter().position(|r| r.time_ms == 40_000).unwrap();
    let times: Vec<u64> = run.rows[at..at + 4].iter().map(|r| r.time_ms).collect();
    assert_eq!(times, [40_000, 40_300, 40_310, 40_320]);
    assert_eq!(run.rows[at].fault, None);
    assert_eq!(run.rows[at + 1].fault.as_deref(), Some("Overrun"));
    let n = sim.controller().counters();
    assert_eq!((n.overruns, n.skipped_periods), (1, 29));
}

#[test]
fn an_overrun_ended_by_a_reset_edge_in_its_own_scan_reinitialises() {
    // The fault starts as the late scan starts and the reset edge of that
    // scan ends it: the scan's record shows no fault, yet the controller
    // re-initialised, which the safety checker must know.
    let boiler = project("boiler/boiler.plc.toml");
    let mut sim = Sim::new(boiler, Backend::Table).unwrap();
    let mut plc = Plc::new(&mut sim).unwrap();
    let idle = Inputs::default();
    for _ in 0..3 {
        assert!(!plc.scan(&idle).unwrap().reinitialised);
    }
    plc.stall(100);
    let pressed = Inputs {
        reset: true,
        ..Inputs::default()
    };
    let scan = plc.scan(&pressed).unwrap();
    assert_eq!((scan.time_ms, scan.fault), (120, None));
    assert!(scan.reinitialised);
    assert!(!plc.scan(&pressed).unwrap().reinitialised);
}
