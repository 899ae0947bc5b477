//! The boiler's scenario suite (docs/seeds.md A, issue "The boiler"): the PLC
//! project `models/boiler/boiler.plc.toml` (seven modular supervisors) in
//! closed loop with the plant simulation, every scan checked by the safety
//! invariants, and every scenario run again on the monolithic variant
//! (`boiler_mono.plc.toml`) with the same executed events and outputs on
//! every scan.

use codegen::backend::Backend;
use host_sim::boiler::{
    self, scenarios, BoilerParams, BoilerPlant, Disturbance, Invariants, Output, Run, Script,
    Selector,
};
use host_sim::Sim;
use plc_project::Project;
use std::path::Path;
use std::sync::OnceLock;

fn project(file: &str) -> &'static Project {
    static MODULAR: OnceLock<Project> = OnceLock::new();
    static MONO: OnceLock<Project> = OnceLock::new();
    let cell = if file == "boiler.plc.toml" {
        &MODULAR
    } else {
        &MONO
    };
    cell.get_or_init(|| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../models/boiler")
            .join(file);
        plc_project::load(&path).unwrap_or_else(|e| panic!("{e}"))
    })
}

/// Runs `script` for `ms` against the modular project, checks the
/// invariants, runs it on the monolithic project too and compares.
fn run(script: &Script, ms: u64) -> Run {
    let run_on = |file: &str| {
        let mut sim = Sim::new(project(file).clone(), Backend::Table).unwrap();
        let mut plant = BoilerPlant::new(BoilerParams::default(), 1);
        boiler::run(&mut sim, &mut plant, script, ms).unwrap()
    };
    let modular = run_on("boiler.plc.toml");
    let violations = modular.violations(&Invariants::default());
    assert!(violations.is_empty(), "safety: {violations:#?}");
    let mono = run_on("boiler_mono.plc.toml");
    for (a, b) in modular.rows.iter().zip(&mono.rows) {
        assert_eq!(
            (&a.events, &a.outputs, &a.fault),
            (&b.events, &b.outputs, &b.fault),
            "modular and monolithic differ at scan {} ({} ms)",
            a.scan,
            a.time_ms
        );
    }
    modular
}

/// [`run`] of the named scenario of `host-sim boiler`.
fn named(name: &str) -> Run {
    let (script, ms) = scenarios::named(name).expect("a scenario of host-sim boiler");
    run(&script, ms)
}

/// Time of the first scan executing `event`.
fn when(run: &Run, event: &str) -> u64 {
    run.first(|r| r.events.iter().any(|e| e == event))
        .unwrap_or_else(|| panic!("`{event}` never executed"))
        .time_ms
}

fn happened(run: &Run, event: &str) -> bool {
    run.first(|r| r.events.iter().any(|e| e == event)).is_some()
}

fn on(run: &Run, at_ms: u64, output: Output) -> bool {
    run.first(|r| r.time_ms >= at_ms)
        .unwrap()
        .outputs
        .get(output)
}

/// The light-off sequence on `selector`: purge, pilot, main at the
/// selector's fire rate; returns the run.
fn light_off(selector: Selector, valve: &str, damper: &str) -> Run {
    let run = run(&Script::new().at(1_000, selector), 60_000);
    let purge = when(&run, "purge_start");
    assert!(when(&run, "purge_done") - purge >= 10_000, "full pre-purge");
    assert_eq!(
        when(&run, "pv_open"),
        when(&run, "purge_done"),
        "pilot gas after the purge"
    );
    assert_eq!(
        when(&run, "ign_on"),
        when(&run, "pv_open"),
        "spark with pilot gas"
    );
    let pilot = when(&run, "pf_on");
    assert_eq!(
        when(&run, "ign_off"),
        pilot,
        "spark off once the pilot is proven"
    );
    assert!(when(&run, damper) >= pilot && when(&run, "blow_on") >= pilot);
    assert!(
        when(&run, valve) >= when(&run, "blow_on"),
        "main gas after air"
    );
    assert!(when(&run, "mf_on") > when(&run, valve));
    let end = run.rows.last().unwrap();
    assert!(end.plant.main_flame && end.plant.pilot_flame);
    assert!(end.outputs.get(Output::Blower) && !end.outputs.get(Output::Alarm));
    run
}

#[test]
fn cold_start_on_high() {
    let run = light_off(Selector::High, "mv_hi", "dmp_hi");
    assert!(on(&run, 59_000, Output::MainValveHi) && !on(&run, 59_000, Output::MainValveLo));
    assert!(run.rows.last().unwrap().plant.firing_kw > 100.0);
}

#[test]
fn cold_start_on_low() {
    let run = light_off(Selector::Low, "mv_lo", "dmp_lo");
    assert!(on(&run, 59_000, Output::MainValveLo) && on(&run, 59_000, Output::DamperLo));
}

#[test]
fn high_and_low_while_running() {
    let run = named("high-low");
    assert!(on(&run, 54_000, Output::MainValveHi));
    assert!(on(&run, 56_000, Output::MainValveLo) && on(&run, 56_000, Output::DamperLo));
    assert!(on(&run, 114_000, Output::MainValveHi) && on(&run, 114_000, Output::DamperHi));
    assert!(!happened(&run, "sd1") && !happened(&run, "sd2"));
    assert!(run
        .rows
        .iter()
        .filter(|r| r.time_ms > 30_000)
        .all(|r| r.plant.main_flame));
}

#[test]
fn operator_off_in_every_state_the_supervisors_reach() {
    // The state vectors reached by a light-off, a run on both fire rates
    // and the shutdown paths; for each, a run that turns the selector off
    // right there. Enumerated from the supervisors' states, not hand-picked.
    let journeys = [
        Script::new()
            .at(1_000, Selector::High)
            .at(40_000, Selector::Low),
        Script::new()
            .at(1_000, Selector::Low)
            .at(2_000, Disturbance::FailIgnitions(9)),
        Script::new()
            .at(1_000, Selector::High)
            .at(35_000, Disturbance::MainFlameOut { for_ms: 5_000 }),
        scenarios::named("two-pilot-failures").unwrap().0,
    ];
    let mut cases = Vec::new();
    for script in &journeys {
        let run = run(script, 50_000);
        let mut seen = std::collections::HashSet::new();
        for row in &run.rows {
            if seen.insert(row.states.clone()) {
                cases.push((script.clone(), row.time_ms));
            }
        }
    }
    assert!(
        cases.len() >= 12,
        "the journeys reach {} state vectors",
        cases.len()
    );
    for (script, at) in cases {
        let script = script.at(at + 10, Selector::Off);
        let run = run(&script, at + 2_000);
        let off = run.first(|r| r.time_ms > at + 100).unwrap();
        for o in Output::ALL.into_iter().filter(|o| *o != Output::Alarm) {
            assert!(
                !off.outputs.get(o),
                "selector off at {at} ms: {} still on",
                o.name()
            );
        }
    }
}

#[test]
fn failed_ignition_times_out_then_a_new_start_succeeds() {
    // No pilot flame within the 15 s trial window: shutdown and alarm;
    // reset acknowledges (burner management), then a new start lights.
    let run = named("failed-ignition");
    let window = when(&run, "trial_done") - when(&run, "trial_start");
    assert_eq!(window, 15_000, "the trial window");
    assert_eq!(when(&run, "sd1"), when(&run, "trial_done"));
    assert!(on(&run, when(&run, "sd1") + 20, Output::Alarm));
    assert!(!on(&run, when(&run, "sd1") + 20, Output::PilotValve));
    assert!(when(&run, "bms") >= 40_000);
    assert!(!on(&run, 41_500, Output::Alarm), "acknowledged");
    assert_eq!(
        ignition_trials(&run, 0, 40_000),
        1,
        "no relight after a timeout"
    );
    assert!(
        run.rows.last().unwrap().plant.main_flame,
        "second start lights"
    );
}

/// Rising edges of `ignition` (spark trials) between two times.
fn ignition_trials(run: &Run, from_ms: u64, to_ms: u64) -> usize {
    run.rows
        .windows(2)
        .filter(|w| w[1].time_ms > from_ms && w[1].time_ms <= to_ms)
        .filter(|w| !w[0].outputs.get(Output::Ignition) && w[1].outputs.get(Output::Ignition))
        .count()
}

#[test]
fn one_pilot_loss_in_the_trial_window_then_success() {
    // The flame forms, goes out while being proven (trial 1 failed), the
    // spark comes on again in the same window (trial 2), and the pilot
    // proven when the window expires starts the main stage.
    let run = named("pilot-relight");
    let lost = when(&run, "pf_off");
    assert!(lost > when(&run, "pf_on") && lost < when(&run, "trial_done"));
    assert_eq!(when(&run, "ign_on"), when(&run, "trial_start"), "trial 1");
    assert!(
        on(&run, lost, Output::Ignition),
        "trial 2 sparks at the loss"
    );
    assert_eq!(ignition_trials(&run, 0, 60_000), 2);
    assert_eq!(
        when(&run, "trial_done") - when(&run, "trial_start"),
        15_000,
        "one window for both trials"
    );
    assert_eq!(when(&run, "mf_init"), when(&run, "trial_done"), "proven");
    assert!(!happened(&run, "sd1") && !happened(&run, "sd2"));
    let end = run.rows.last().unwrap();
    assert!(end.plant.main_flame && end.outputs.get(Output::MainValveLo));
}

#[test]
fn two_pilot_losses_shut_down_until_reset_then_restart() {
    // Two losses in one trial window: shutdown (sd1), alarm, every valve
    // closed and none opens before reset; reset acknowledges (burner
    // management, bms), and a new selection lights the boiler.
    let run = named("two-pilot-failures");
    let sd = when(&run, "sd1");
    assert!(sd > 21_000 && sd < 21_200, "at the second loss ({sd} ms)");
    assert_eq!(ignition_trials(&run, 0, sd), 2, "two trials");
    assert!(!happened(&run, "mf_init") || when(&run, "mf_init") > 30_000);
    assert!(on(&run, sd, Output::Alarm));
    assert!(run
        .rows
        .iter()
        .filter(|r| r.time_ms >= sd && r.time_ms < 30_000)
        .all(|r| !r.outputs.fuel_open() && !r.outputs.get(Output::Ignition)));
    let bms = when(&run, "bms");
    assert!((30_000..30_200).contains(&bms), "bms at reset ({bms} ms)");
    assert!(!on(&run, bms + 20, Output::Alarm), "acknowledged");
    assert!(when(&run, "mf_init") > 32_000);
    let end = run.rows.last().unwrap();
    assert!(end.plant.main_flame && !end.outputs.get(Output::Alarm));
}

#[test]
fn main_flame_failure_shuts_down() {
    let run = named("main-flame-failure");
    let sd = when(&run, "sd2");
    assert_eq!(sd, when(&run, "mf_off"));
    for o in [Output::PilotValve, Output::MainValveLo, Output::MainValveHi] {
        assert!(!on(&run, sd, o));
    }
    assert!(on(&run, sd, Output::Alarm));
}

#[test]
fn bath_over_temperature_shuts_down_until_reset() {
    let run = named("bath-over-temperature");
    let sd = when(&run, "bath_over");
    assert!(on(&run, sd, Output::Alarm) && !on(&run, sd, Output::MainValveHi));
    // The bath cooled below the limit, but the burner stays off until reset.
    assert!(run
        .rows
        .iter()
        .filter(|r| r.time_ms > sd && r.time_ms < 65_000)
        .all(|r| !r.outputs.fuel_open()));
    assert!(when(&run, "bms") >= 65_000);
}

#[test]
fn flue_gas_over_temperature_shuts_down() {
    let run = named("flue-over-temperature");
    let sd = when(&run, "flue_over");
    assert!(sd > 20_000);
    assert!(on(&run, sd, Output::Alarm) && !run.rows.last().unwrap().outputs.fuel_open());
}

#[test]
fn a_bouncing_flame_sensor_is_filtered() {
    // Bounce of one scan per half-period on the pilot flame detector: the
    // 2-scan debounce sees one clean edge.
    let run = named("bouncing-flame-sensor");
    let edges = run
        .rows
        .iter()
        .filter(|r| r.events.iter().any(|e| e == "pf_on" || e == "pf_off"))
        .count();
    assert_eq!(edges, 1, "one pf_on, no chatter");
    assert!(run.rows.last().unwrap().plant.main_flame);
}

#[test]
fn a_controller_stall_faults_to_the_safe_image_until_reset() {
    // docs/semantics.md, "Fault mode": a scan more than `overrun_limit` periods late is
    // an overrun, a fault with `overrun_fault = true`: the safe image
    // (every output off but `alarm`, whose safe level is 1) until the
    // rising edge of `reset` re-initialises the supervisors.
    let run = named("controller-stall");
    let faulted: Vec<_> = run.rows.iter().filter(|r| r.fault.is_some()).collect();
    let first = faulted.first().expect("a fault");
    assert_eq!(first.fault.as_deref(), Some("Overrun"));
    assert!(
        (40_300..40_400).contains(&first.time_ms),
        "{}",
        first.time_ms
    );
    for row in &faulted {
        for o in Output::ALL {
            assert_eq!(
                row.outputs.get(o),
                o == Output::Alarm,
                "{} at {}",
                o.name(),
                row.time_ms
            );
        }
        assert!(row.events.is_empty(), "nothing executes in fault mode");
    }
    let last = faulted.last().unwrap().time_ms;
    assert!(
        (50_000..50_100).contains(&(last + 10)),
        "until reset ({last} ms)"
    );
    let after = run.first(|r| r.time_ms > last).unwrap();
    assert!(after.fault.is_none() && !after.outputs.get(Output::Alarm));
    assert!(
        !run.first(|r| r.time_ms > 45_000).unwrap().plant.main_flame,
        "flames out"
    );
    // Re-initialised: a new selection runs the whole sequence again.
    let restart = run.first(|r| r.time_ms > 52_000 && r.events.iter().any(|e| e == "purge_start"));
    assert!(restart.is_some(), "restarts after reset");
    let end = run.rows.last().unwrap();
    assert!(end.plant.main_flame && end.outputs.get(Output::MainValveHi));
}

#[test]
fn random_inputs_never_raise_an_unexpected_event() {
    // Fault mode needs an uncontrollable event some supervisor does not
    // define where it occurs. The plant models cover everything the inputs
    // can do (edges of one input alternate; the selector's contacts in any
    // order; the limit switches any time), and supcon made the supervisors
    // controllable for them, so no input sequence faults the controller:
    // 50,000 scans of inputs toggling at random, noise included.
    let mut sim = Sim::new(project("boiler.plc.toml").clone(), Backend::Table).unwrap();
    let names: Vec<String> = sim
        .project()
        .inputs
        .iter()
        .map(|i| i.name.clone())
        .collect();
    let mut levels = vec![false; names.len()];
    let mut x: u64 = 0x2545_f491_4f6c_dd1d;
    let mut executed = 0;
    for _ in 0..50_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let i = (x % 40) as usize;
        if i < names.len() {
            levels[i] = !levels[i];
            sim.set(&names[i], levels[i]).unwrap();
        }
        let row = sim.scan();
        assert_eq!(row.fault, None, "scan {}: {:?}", row.scan, row.ignored);
        executed += row.events.len();
    }
    assert!(
        executed > 1_000,
        "the inputs drove the supervisors ({executed} events)"
    );
}
