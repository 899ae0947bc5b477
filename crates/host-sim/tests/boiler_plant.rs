//! The boiler plant of `host_sim::boiler`: physics that behaves like a
//! water-bath boiler, sensor faults as specified, determinism, the closed
//! loop through the executor, and the safety checker, which passes a
//! hand-written reference controller and catches each of its deliberately
//! broken variants.

use codegen::backend::Backend;
use host_sim::boiler::{
    self, Action, BoilerController, BoilerError, BoilerParams, BoilerPlant, Checker,
    ControllerScan, Disturbance, Input, Inputs, Invariants, Outputs, Rule, Run, Script, Selector,
    SensorFault, Violation,
};
use host_sim::{Lockstep, Sim};
use std::path::PathBuf;

const SCAN_MS: u64 = 10;

fn data(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(file)
}

fn model(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(file)
}

// ---------------------------------------------------------------- physics

/// A new plant at the default parameters.
fn fresh() -> BoilerPlant {
    BoilerPlant::new(BoilerParams::default(), 1)
}

/// Steps `plant` under `outputs` for `ms` in scans of 10 ms; the input
/// image after each scan.
fn hold(plant: &mut BoilerPlant, outputs: Outputs, ms: u64) -> Vec<Inputs> {
    (0..ms / SCAN_MS)
        .map(|_| plant.step(SCAN_MS, &outputs))
        .collect()
}

const GAS_AND_SPARK: Outputs = Outputs {
    pilot_valve: true,
    ignition: true,
    ..NOTHING
};
const PILOT_GAS: Outputs = Outputs {
    pilot_valve: true,
    ..NOTHING
};
const NOTHING: Outputs = Outputs {
    pilot_valve: false,
    ignition: false,
    main_valve_lo: false,
    main_valve_hi: false,
    damper_lo: false,
    damper_hi: false,
    blower: false,
    alarm: false,
};
const LOW_FIRE: Outputs = Outputs {
    pilot_valve: true,
    main_valve_lo: true,
    damper_lo: true,
    blower: true,
    ..NOTHING
};
const HIGH_FIRE: Outputs = Outputs {
    pilot_valve: true,
    main_valve_hi: true,
    damper_hi: true,
    blower: true,
    ..NOTHING
};

/// A plant with the pilot lit and the spark off again.
fn lit_pilot() -> BoilerPlant {
    let mut p = fresh();
    hold(&mut p, GAS_AND_SPARK, 2_000);
    assert!(p.inputs().pilot_flame);
    p
}

#[test]
fn the_pilot_lights_after_two_seconds_of_gas_and_spark() {
    let mut p = fresh();
    let seen = hold(&mut p, GAS_AND_SPARK, 2_500);
    let lit = seen.iter().position(|i| i.pilot_flame).unwrap();
    assert_eq!((lit as u64 + 1) * SCAN_MS, 2_000);
    assert!(seen[lit..].iter().all(|i| i.pilot_flame));
}

#[test]
fn gas_alone_or_a_spark_alone_lights_nothing() {
    let mut p = fresh();
    assert!(hold(&mut p, PILOT_GAS, 10_000)
        .iter()
        .all(|i| !i.pilot_flame));
    let spark = Outputs {
        ignition: true,
        ..NOTHING
    };
    assert!(hold(&mut p, spark, 10_000).iter().all(|i| !i.pilot_flame));
    // Interrupting the spark restarts the two seconds.
    hold(&mut p, GAS_AND_SPARK, 1_500);
    hold(&mut p, PILOT_GAS, 10);
    assert!(!hold(&mut p, GAS_AND_SPARK, 1_500)
        .iter()
        .any(|i| i.pilot_flame));
}

#[test]
fn the_pilot_holds_on_its_gas_and_dies_shortly_after_the_valve_closes() {
    let mut p = lit_pilot();
    assert!(hold(&mut p, PILOT_GAS, 60_000)
        .iter()
        .all(|i| i.pilot_flame));
    let after = hold(&mut p, NOTHING, 1_000);
    let out = after.iter().position(|i| !i.pilot_flame).unwrap();
    assert_eq!((out as u64 + 1) * SCAN_MS, 300, "pilot_extinction_ms");
}

#[test]
fn a_scripted_trial_fails_and_the_next_one_lights() {
    let params = BoilerParams {
        failing_trials: vec![1],
        ..BoilerParams::default()
    };
    let mut p = BoilerPlant::new(params, 1);
    assert!(hold(&mut p, GAS_AND_SPARK, 5_000)
        .iter()
        .all(|i| !i.pilot_flame));
    hold(&mut p, PILOT_GAS, 100);
    assert!(
        hold(&mut p, GAS_AND_SPARK, 2_000)
            .last()
            .unwrap()
            .pilot_flame
    );
    assert_eq!(p.ignition_trials(), 2);
}

#[test]
fn injected_ignition_failures_take_the_next_trials() {
    let mut p = fresh();
    p.disturb(Disturbance::FailIgnitions(2));
    for _ in 0..2 {
        assert!(hold(&mut p, GAS_AND_SPARK, 4_000)
            .iter()
            .all(|i| !i.pilot_flame));
        hold(&mut p, NOTHING, 500);
    }
    assert!(
        hold(&mut p, GAS_AND_SPARK, 2_000)
            .last()
            .unwrap()
            .pilot_flame
    );
}

/// Which of `trials` ignition trials light, with failure probability `p`.
fn trial_outcomes(seed: u64, p: f64, trials: usize) -> Vec<bool> {
    let params = BoilerParams {
        ignition_failure_probability: p,
        ..BoilerParams::default()
    };
    let mut plant = BoilerPlant::new(params, seed);
    (0..trials)
        .map(|_| {
            let lit = hold(&mut plant, GAS_AND_SPARK, 2_000)
                .last()
                .unwrap()
                .pilot_flame;
            hold(&mut plant, NOTHING, 1_000);
            lit
        })
        .collect()
}

#[test]
fn random_ignition_failures_follow_the_seed() {
    let a = trial_outcomes(7, 0.5, 24);
    assert_eq!(a, trial_outcomes(7, 0.5, 24));
    assert_ne!(a, trial_outcomes(8, 0.5, 24));
    assert!(a.contains(&true) && a.contains(&false));
    assert!(trial_outcomes(7, 0.0, 5).iter().all(|&lit| lit));
    assert!(trial_outcomes(7, 1.0, 5).iter().all(|&lit| !lit));
}

#[test]
fn a_blown_out_pilot_needs_a_new_spark() {
    let mut p = lit_pilot();
    p.disturb(Disturbance::PilotFlameOut { for_ms: 3_000 });
    assert!(!p.inputs().pilot_flame);
    assert!(hold(&mut p, PILOT_GAS, 5_000)
        .iter()
        .all(|i| !i.pilot_flame));
    p.disturb(Disturbance::PilotFlameOut { for_ms: 3_000 });
    // The burner cannot light for 3 s, then needs the usual 2 s of spark.
    let seen = hold(&mut p, GAS_AND_SPARK, 6_000);
    let lit = seen.iter().position(|i| i.pilot_flame).unwrap();
    assert_eq!((lit as u64 + 1) * SCAN_MS, 5_000);
}

#[test]
fn the_main_flame_needs_pilot_air_and_gas() {
    let without = |o: Outputs| {
        let mut p = lit_pilot();
        hold(&mut p, o, 5_000).iter().any(|i| i.main_flame)
    };
    assert!(!without(Outputs {
        blower: false,
        ..LOW_FIRE
    }));
    assert!(!without(Outputs {
        damper_lo: false,
        ..LOW_FIRE
    }));
    assert!(!without(Outputs {
        main_valve_lo: false,
        ..LOW_FIRE
    }));
    let mut cold = fresh();
    let no_pilot = Outputs {
        pilot_valve: false,
        ..LOW_FIRE
    };
    assert!(hold(&mut cold, no_pilot, 5_000)
        .iter()
        .all(|i| !i.main_flame));

    let mut p = lit_pilot();
    let seen = hold(&mut p, LOW_FIRE, 2_000);
    let lit = seen.iter().position(|i| i.main_flame).unwrap();
    assert_eq!((lit as u64 + 1) * SCAN_MS, 1_000, "main_ignition_ms");
    assert_eq!(p.state().firing_kw, 60.0 + 1.5);
    hold(&mut p, HIGH_FIRE, 10);
    assert_eq!(p.state().firing_kw, 150.0 + 1.5);
}

/// A plant burning at low fire.
fn burning() -> BoilerPlant {
    let mut p = lit_pilot();
    hold(&mut p, LOW_FIRE, 1_000);
    assert!(p.inputs().main_flame);
    p
}

#[test]
fn the_main_flame_dies_when_its_air_or_gas_goes() {
    for starved in [
        Outputs {
            blower: false,
            ..LOW_FIRE
        },
        Outputs {
            damper_lo: false,
            ..LOW_FIRE
        },
        Outputs {
            main_valve_lo: false,
            ..LOW_FIRE
        },
    ] {
        let mut p = burning();
        let seen = hold(&mut p, starved, 1_000);
        let out = seen.iter().position(|i| !i.main_flame).unwrap();
        assert_eq!((out as u64 + 1) * SCAN_MS, 200, "main_extinction_ms");
    }
    // Low to high in one scan keeps the flame.
    let mut p = burning();
    assert!(hold(&mut p, HIGH_FIRE, 5_000).iter().all(|i| i.main_flame));
}

#[test]
fn an_injected_main_flame_failure_lasts_its_time_then_the_pilot_relights_it() {
    let mut p = burning();
    p.disturb(Disturbance::MainFlameOut { for_ms: 4_000 });
    assert!(!p.inputs().main_flame);
    let seen = hold(&mut p, LOW_FIRE, 6_000);
    let relit = seen.iter().position(|i| i.main_flame).unwrap();
    assert_eq!((relit as u64 + 1) * SCAN_MS, 5_000);
}

/// The bath temperature change over `minutes` under `outputs`, starting
/// at 60 °C with the default 30 kW process load.
fn bath_change(outputs: Outputs, minutes: u64) -> f64 {
    let params = BoilerParams {
        initial_bath_c: 60.0,
        ..BoilerParams::default()
    };
    let mut p = BoilerPlant::new(params, 1);
    hold(&mut p, GAS_AND_SPARK, 2_000);
    hold(&mut p, outputs, 1_000);
    let start = p.state().bath_c;
    for _ in 0..minutes * 600 {
        p.step(100, &outputs);
    }
    p.state().bath_c - start
}

#[test]
fn the_bath_heats_faster_on_high_fire_than_on_low_and_cools_with_the_fire_off() {
    let high = bath_change(HIGH_FIRE, 10);
    let low = bath_change(LOW_FIRE, 10);
    let off = bath_change(NOTHING, 10);
    // 2,000 l: high fire nets ~95 kW (≈ 6.8 K in 10 min), low fire ~19 kW,
    // off loses the 30 kW process load plus ~2 kW to ambient.
    assert!(high > 5.0 && high < 9.0, "high fire: {high:.2} K");
    assert!(low > 0.5 && low < 2.5, "low fire: {low:.2} K");
    assert!(off < -1.5 && off > -3.5, "fire off: {off:.2} K");
}

#[test]
fn the_bath_limit_switch_has_five_kelvin_of_hysteresis() {
    let mut p = fresh();
    let mut bath_hot_at = |c: f64| {
        p.disturb(Disturbance::BathTemperature(c));
        p.inputs().bath_hot
    };
    assert!(!bath_hot_at(84.5));
    assert!(bath_hot_at(85.0));
    assert!(bath_hot_at(81.0), "still on within the hysteresis");
    assert!(!bath_hot_at(80.0));
    assert!(!bath_hot_at(84.0), "off until the limit again");
}

#[test]
fn a_fouled_flue_trips_the_flue_limit_which_resets_twenty_kelvin_below() {
    let mut p = burning();
    hold(&mut p, HIGH_FIRE, 120_000);
    let clean = p.state().flue_c;
    assert!(
        clean > 150.0 && clean < 300.0 && !p.inputs().flue_hot,
        "{clean}"
    );
    p.disturb(Disturbance::FlueFouling(150.0));
    let mut last = p.state().flue_c;
    let on = loop {
        let seen = p.step(SCAN_MS, &HIGH_FIRE);
        let now = p.state().flue_c;
        if seen.flue_hot {
            break (last, now);
        }
        last = now;
        assert!(p.time_ms() < 400_000, "flue_hot never came: {now}");
    };
    assert!(on.0 < 300.0 && on.1 >= 300.0, "on at the limit: {on:?}");
    p.disturb(Disturbance::FlueFouling(0.0));
    let mut last = p.state().flue_c;
    let off = loop {
        let seen = p.step(SCAN_MS, &HIGH_FIRE);
        let now = p.state().flue_c;
        if !seen.flue_hot {
            break (last, now);
        }
        last = now;
        assert!(p.time_ms() < 800_000, "flue_hot never went: {now}");
    };
    assert!(off.0 > 280.0 && off.1 <= 280.0, "off 20 K below: {off:?}");
}

#[test]
fn a_bouncing_flame_detector_flickers_after_each_change_then_settles() {
    let mut p = fresh();
    p.install_sensor_fault(
        Input::PilotFlame,
        SensorFault::Bounce {
            for_ms: 50,
            toggle_ms: 10,
        },
    );
    let seen: Vec<bool> = hold(&mut p, GAS_AND_SPARK, 2_100)
        .iter()
        .map(|i| i.pilot_flame)
        .collect();
    let first = seen.iter().position(|&v| v).unwrap();
    assert_eq!(
        &seen[first..first + 8],
        [true, false, true, false, true, true, true, true]
    );
    assert!(p.truth().pilot_flame);
}

#[test]
fn a_stuck_detector_reads_its_level_from_the_injection_until_cleared() {
    let mut p = fresh();
    hold(&mut p, NOTHING, 1_000);
    p.install_sensor_fault(Input::MainFlame, SensorFault::StuckAt(true));
    assert!(hold(&mut p, NOTHING, 5_000).iter().all(|i| i.main_flame));
    assert!(!p.truth().main_flame);
    p.install_sensor_fault(Input::MainFlame, SensorFault::None);
    assert!(!p.inputs().main_flame);
}

#[test]
fn a_dropout_reads_zero_for_its_interval_only() {
    let mut p = fresh();
    p.set_selector(Selector::Low);
    hold(&mut p, NOTHING, 1_000);
    p.install_sensor_fault(Input::SelLow, SensorFault::Dropout { for_ms: 300 });
    assert!(!p.inputs().sel_low);
    let seen = hold(&mut p, NOTHING, 1_000);
    let back = seen.iter().position(|i| i.sel_low).unwrap();
    assert_eq!((back as u64 + 1) * SCAN_MS, 300);
    assert!(seen[back..].iter().all(|i| i.sel_low));
}

#[test]
fn the_operator_panel_sets_the_selector_contacts_and_pulses_reset() {
    let mut p = fresh();
    p.set_selector(Selector::High);
    assert_eq!(p.inputs().selector(), Selector::High);
    assert!(p.inputs().sel_high && !p.inputs().sel_low);
    p.press_reset();
    let seen = hold(&mut p, NOTHING, 500);
    assert!(p.truth().sel_high);
    let released = seen.iter().position(|i| !i.reset).unwrap();
    assert_eq!((released as u64 + 1) * SCAN_MS, 200, "reset_pulse_ms");
}

// ------------------------------------------------ the reference controller

const PURGE_MS: u64 = 10_000;
const TRIAL_MS: u64 = 5_000;
const TRIAL_GAP_MS: u64 = 1_000;
const TRIAL_WINDOW_MS: u64 = 15_000;
const MAIN_TRIAL_MS: u64 = 3_000;

/// One deliberate mistake of the reference controller.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Flaw {
    None,
    /// Re-strikes the spark once while the pilot burns.
    SparkIntoFlame,
    /// Starts the spark one scan before the pilot gas.
    SparkBeforeGas,
    /// Purges 5 s.
    ShortPurge,
    /// Starts the blower one scan after the main valve.
    MainBeforeBlower,
    /// Changes the fire rate by opening the new valve position one scan
    /// before closing the old one.
    OverlappingPositions,
    /// Keeps everything on for 5 scans after a shutdown.
    SlowShutdown,
    /// Shuts down without the alarm.
    SilentShutdown,
    /// Leaves the lockout when the selector goes off: no reset needed.
    OffClearsLockout,
    /// Runs the blower 10 scans after the selector goes off (post-purge).
    PostPurge,
    /// Allows three ignition trials.
    ThreeTrials,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Idle,
    Purge { since: u64 },
    Ignite { trial: u32, since: u64 },
    Gap { trial: u32, since: u64 },
    PilotLit,
    MainTrial { since: u64 },
    Running,
    Lockout { since: u64 },
}

/// A hand-written burner controller after the thesis's sequence: on a
/// start request, purge (damper low, blower), then pilot gas and spark for
/// at most two trials of 5 s within 15 s, then main valve at the selected
/// rate; a rising bath or flue limit, or the main flame dropping with the
/// valve open, locks out with the alarm until reset; so does any failed
/// step. Off closes everything.
struct Reference {
    flaw: Flaw,
    time_ms: u64,
    prev: Option<Inputs>,
    out: Outputs,
    phase: Phase,
    /// A start request waits for the limits to clear.
    requested: bool,
    window_start: u64,
    fire: Selector,
    fire_before: Selector,
    restruck: bool,
    post_purge: u32,
}

impl Reference {
    fn new(flaw: Flaw) -> Reference {
        Reference {
            flaw,
            time_ms: 0,
            prev: None,
            out: Outputs::default(),
            phase: Phase::Idle,
            requested: false,
            window_start: 0,
            fire: Selector::Low,
            fire_before: Selector::Low,
            restruck: false,
            post_purge: 0,
        }
    }

    fn lock_out(&mut self, t: u64) {
        self.phase = Phase::Lockout { since: t };
    }

    fn transition(&mut self, i: &Inputs, p: &Inputs, t: u64) {
        let rose = |f: fn(&Inputs) -> bool| f(i) && !f(p);
        let on = i.selector_on();
        let tripped = (on && (rose(|x| x.bath_hot) || rose(|x| x.flue_hot)))
            || (p.main_flame && !i.main_flame && self.out.main_open());
        if tripped && !matches!(self.phase, Phase::Lockout { .. }) {
            return self.lock_out(t);
        }
        if let Phase::Lockout { .. } = self.phase {
            if rose(|x| x.reset) {
                self.phase = Phase::Idle;
                self.requested = on;
            } else if !on && self.flaw == Flaw::OffClearsLockout {
                self.phase = Phase::Idle;
            }
            return;
        }
        if !on {
            if self.phase != Phase::Idle && self.flaw == Flaw::PostPurge {
                self.post_purge = 10;
            }
            self.phase = Phase::Idle;
            self.requested = false;
            return;
        }
        let purge_ms = if self.flaw == Flaw::ShortPurge {
            PURGE_MS / 2
        } else {
            PURGE_MS
        };
        let (trials, window) = if self.flaw == Flaw::ThreeTrials {
            (3, u64::MAX)
        } else {
            (2, TRIAL_WINDOW_MS)
        };
        match self.phase {
            Phase::Idle => {
                self.requested |= !p.selector_on();
                if self.requested && !i.bath_hot && !i.flue_hot {
                    self.requested = false;
                    self.phase = Phase::Purge { since: t };
                }
            }
            Phase::Purge { since } if t - since >= purge_ms => {
                if i.pilot_flame {
                    // A flame before ignition: the detector lies.
                    return self.lock_out(t);
                }
                self.window_start = t;
                self.phase = Phase::Ignite { trial: 1, since: t };
            }
            Phase::Ignite { trial, since } => {
                if i.pilot_flame {
                    self.phase = Phase::PilotLit;
                } else if t - since >= TRIAL_MS || t - self.window_start >= window {
                    if trial < trials && t - self.window_start < window {
                        self.phase = Phase::Gap { trial, since: t };
                    } else {
                        self.lock_out(t);
                    }
                }
            }
            Phase::Gap { trial, since } if t - since >= TRIAL_GAP_MS => {
                if i.pilot_flame {
                    return self.lock_out(t);
                }
                self.phase = Phase::Ignite {
                    trial: trial + 1,
                    since: t,
                };
            }
            Phase::PilotLit | Phase::MainTrial { .. } if !i.pilot_flame => self.lock_out(t),
            Phase::PilotLit => {
                self.fire = i.selector();
                self.phase = Phase::MainTrial { since: t };
            }
            Phase::MainTrial { since } => {
                if i.main_flame {
                    self.phase = Phase::Running;
                } else if t - since >= MAIN_TRIAL_MS {
                    self.lock_out(t);
                }
            }
            Phase::Running => {
                self.fire_before = self.fire;
                self.fire = i.selector();
            }
            Phase::Purge { .. } | Phase::Gap { .. } | Phase::Lockout { .. } => {}
        }
    }

    fn outputs(&mut self, t: u64) -> Outputs {
        let mut o = Outputs::default();
        let purge_air = |o: &mut Outputs| {
            o.damper_lo = true;
            o.blower = true;
        };
        let high = self.fire == Selector::High;
        match self.phase {
            Phase::Idle => {
                if self.post_purge > 0 {
                    self.post_purge -= 1;
                    purge_air(&mut o);
                }
            }
            Phase::Purge { .. } | Phase::Gap { .. } => purge_air(&mut o),
            Phase::Ignite { trial, since } => {
                purge_air(&mut o);
                o.ignition = true;
                o.pilot_valve = !(self.flaw == Flaw::SparkBeforeGas && trial == 1 && t == since);
            }
            Phase::PilotLit => {
                purge_air(&mut o);
                o.pilot_valve = true;
                o.blower = self.flaw != Flaw::MainBeforeBlower;
            }
            Phase::MainTrial { since } => {
                o.pilot_valve = true;
                o.blower = !(self.flaw == Flaw::MainBeforeBlower && t == since);
                (o.damper_hi, o.damper_lo) = (high, !high);
                (o.main_valve_hi, o.main_valve_lo) = (high, !high);
            }
            Phase::Running => {
                o.pilot_valve = true;
                o.blower = true;
                (o.damper_hi, o.damper_lo) = (high, !high);
                (o.main_valve_hi, o.main_valve_lo) = (high, !high);
                if self.flaw == Flaw::OverlappingPositions && self.fire != self.fire_before {
                    (o.main_valve_hi, o.main_valve_lo) = (true, true);
                }
                if self.flaw == Flaw::SparkIntoFlame && !self.restruck {
                    self.restruck = true;
                    o.ignition = true;
                }
            }
            Phase::Lockout { since } => {
                if self.flaw == Flaw::SlowShutdown && t - since < 5 * SCAN_MS {
                    o = self.out;
                }
                o.alarm = self.flaw != Flaw::SilentShutdown;
            }
        }
        o
    }
}

impl BoilerController for Reference {
    fn scan_period_ms(&self) -> u32 {
        SCAN_MS as u32
    }

    fn scan(&mut self, inputs: &Inputs) -> Result<ControllerScan, BoilerError> {
        let t = self.time_ms;
        self.time_ms += SCAN_MS;
        let prev = self.prev.replace(*inputs).unwrap_or(*inputs);
        self.transition(inputs, &prev, t);
        self.out = self.outputs(t);
        Ok(ControllerScan {
            time_ms: t,
            outputs: self.out,
            states: vec![("reference".into(), format!("{:?}", self.phase))],
            ..ControllerScan::default()
        })
    }
}

fn run_reference(flaw: Flaw, params: BoilerParams, script: &Script, ms: u64) -> Run {
    let mut plant = BoilerPlant::new(params, 1);
    boiler::run_with(&mut Reference::new(flaw), &mut plant, script, ms).unwrap()
}

fn listing(violations: &[Violation]) -> String {
    violations
        .iter()
        .map(|v| format!("\n  {v}"))
        .collect::<String>()
}

/// `flaw` breaks `rule` and nothing else in `script`, which the reference
/// controller runs without a violation.
fn assert_only(flaw: Flaw, script: &Script, ms: u64, rule: Rule) {
    let rules = Invariants::default();
    let good = run_reference(Flaw::None, BoilerParams::default(), script, ms);
    let v = good.violations(&rules);
    assert!(v.is_empty(), "reference: {}", listing(&v));
    let bad = run_reference(flaw, BoilerParams::default(), script, ms);
    let v = bad.violations(&rules);
    assert!(!v.is_empty(), "{flaw:?} is not caught");
    assert!(
        v.iter().all(|x| x.rule == rule),
        "{flaw:?}: expected only {rule}: {}",
        listing(&v)
    );
}

/// Low fire at 1 s, high at 40 s, low at 60 s, off at 80 s.
fn normal_day() -> Script {
    Script::new()
        .at(1_000, Selector::Low)
        .at(40_000, Selector::High)
        .at(60_000, Selector::Low)
        .at(80_000, Selector::Off)
}

/// Low fire; the bath overheats at 40 s, is relieved at 50 s and the
/// operator resets at 60 s.
fn bath_trip() -> Script {
    Script::new()
        .at(1_000, Selector::Low)
        .at(40_000, Disturbance::BathTemperature(86.0))
        .at(50_000, Disturbance::BathTemperature(70.0))
        .at(60_000, Action::Reset)
}

#[test]
fn the_reference_controller_fires_low_and_high_and_stops() {
    let run = run_reference(Flaw::None, BoilerParams::default(), &normal_day(), 90_000);
    assert!(run.violations(&Invariants::default()).is_empty());
    let gas = run.first(|r| r.outputs.pilot_valve).unwrap();
    assert_eq!(gas.time_ms, 11_000, "request at 1 s, 10 s purge");
    let pilot = run.first(|r| r.plant.pilot_flame).unwrap();
    assert_eq!(pilot.time_ms - gas.time_ms, 2_000);
    let high = run.first(|r| r.outputs.main_valve_hi).unwrap();
    assert_eq!(high.time_ms, 40_000);
    assert_eq!(
        run.first(|r| r.time_ms == 50_000).unwrap().plant.firing_kw,
        151.5
    );
    let stop = run.first(|r| r.time_ms == 80_000).unwrap();
    assert_eq!(stop.outputs, Outputs::default());
    assert!(!run.rows.last().unwrap().plant.main_flame);
    let csv = run.to_csv();
    assert!(csv.starts_with("scan,time_ms,sel_high,sel_low,pilot_flame"));
    assert_eq!(csv.lines().count(), run.rows.len() + 1);
}

#[test]
fn the_reference_controller_passes_every_shutdown_scenario() {
    let scripts = [
        bath_trip(),
        // The main flame fails; reset after 10 s.
        Script::new()
            .at(1_000, Selector::Low)
            .at(40_000, Disturbance::MainFlameOut { for_ms: 5_000 })
            .at(50_000, Action::Reset),
        // A fouled flue at high fire; cleaned and reset.
        Script::new()
            .at(1_000, Selector::High)
            .at(20_000, Disturbance::FlueFouling(200.0))
            .at(70_000, Disturbance::FlueFouling(0.0))
            .at(90_000, Action::Reset),
        // Both ignition trials fail: lockout; reset, and it lights.
        Script::new()
            .at(0, Disturbance::FailIgnitions(2))
            .at(1_000, Selector::Low)
            .at(40_000, Action::Reset),
    ];
    for (k, script) in scripts.iter().enumerate() {
        let run = run_reference(Flaw::None, BoilerParams::default(), script, 120_000);
        let v = run.violations(&Invariants::default());
        assert!(v.is_empty(), "scenario {k}: {}", listing(&v));
        let alarm = run.first(|r| r.outputs.alarm);
        assert!(alarm.is_some(), "scenario {k} shuts down");
        let relit = run.first(|r| r.time_ms > alarm.unwrap().time_ms && r.plant.main_flame);
        assert!(relit.is_some(), "scenario {k} restarts after the reset");
    }
}

#[test]
fn the_reference_controller_is_safe_under_random_scripts() {
    let params = BoilerParams {
        ignition_failure_probability: 0.2,
        ..BoilerParams::default()
    };
    let (mut alarms, mut burning, mut bounced) = (0, 0, 0);
    for seed in 1..=8 {
        let script = Script::random(seed, 600_000);
        let mut plant = BoilerPlant::new(params.clone(), seed);
        let mut reference = Reference::new(Flaw::None);
        let run = boiler::run_with(&mut reference, &mut plant, &script, 600_000).unwrap();
        let v = run.violations(&Invariants::default());
        assert!(v.is_empty(), "seed {seed}: {}", listing(&v));
        let rises = |f: fn(&Outputs) -> bool| {
            run.rows
                .windows(2)
                .filter(|w| f(&w[1].outputs) && !f(&w[0].outputs))
                .count()
        };
        alarms += rises(|o| o.alarm);
        burning += run.rows.iter().filter(|r| r.plant.main_flame).count();
        bounced += run.rows.iter().filter(|r| r.inputs != truth_of(r)).count();
    }
    assert!(alarms >= 8, "random scripts provoke shutdowns ({alarms})");
    assert!(burning > 100_000, "and the burner runs ({burning} scans)");
    assert!(bounced > 0, "and sensors misbehave");
}

/// The inputs the plant's truth would give (no sensor faults), as far as
/// the recorded state tells.
fn truth_of(r: &boiler::RunRow) -> Inputs {
    Inputs {
        pilot_flame: r.plant.pilot_flame,
        main_flame: r.plant.main_flame,
        ..r.inputs
    }
}

#[test]
fn a_run_is_a_function_of_its_seeds() {
    let params = BoilerParams {
        ignition_failure_probability: 0.3,
        ..BoilerParams::default()
    };
    let go = |seed: u64| {
        let script = Script::random(seed, 300_000);
        let mut plant = BoilerPlant::new(params.clone(), seed);
        boiler::run_with(
            &mut Reference::new(Flaw::None),
            &mut plant,
            &script,
            300_000,
        )
        .unwrap()
    };
    assert_eq!(go(11), go(11));
    assert_ne!(go(11).rows, go(12).rows);
}

// ----------------------------------------------- each rule, broken alone

#[test]
fn the_spark_is_never_switched_on_into_a_pilot_flame() {
    assert_only(
        Flaw::SparkIntoFlame,
        &normal_day(),
        90_000,
        Rule::IgnitionIntoFlame,
    );
}

#[test]
fn the_spark_is_only_on_with_pilot_gas() {
    assert_only(
        Flaw::SparkBeforeGas,
        &normal_day(),
        90_000,
        Rule::IgnitionWithoutPilotGas,
    );
}

#[test]
fn no_fuel_before_a_full_pre_purge() {
    assert_only(
        Flaw::ShortPurge,
        &normal_day(),
        90_000,
        Rule::FuelBeforePurge,
    );
}

#[test]
fn the_main_valve_opens_only_with_air_and_a_pilot_flame() {
    assert_only(
        Flaw::MainBeforeBlower,
        &normal_day(),
        90_000,
        Rule::MainWithoutPermit,
    );
}

#[test]
fn main_valve_positions_never_overlap() {
    assert_only(
        Flaw::OverlappingPositions,
        &normal_day(),
        90_000,
        Rule::BothPositions,
    );
}

#[test]
fn a_shutdown_closes_the_fuel_within_two_scans() {
    assert_only(Flaw::SlowShutdown, &bath_trip(), 90_000, Rule::FuelNotShut);
}

#[test]
fn a_shutdown_raises_the_alarm_within_two_scans() {
    assert_only(Flaw::SilentShutdown, &bath_trip(), 90_000, Rule::NoAlarm);
}

#[test]
fn after_a_shutdown_only_a_reset_allows_fuel_again() {
    let script = Script::new()
        .at(1_000, Selector::Low)
        .at(40_000, Disturbance::BathTemperature(86.0))
        .at(45_000, Disturbance::BathTemperature(70.0))
        .at(50_000, Selector::Off)
        .at(52_000, Selector::Low);
    assert_only(
        Flaw::OffClearsLockout,
        &script,
        90_000,
        Rule::RestartWithoutReset,
    );
}

#[test]
fn selector_off_switches_everything_but_the_alarm_off_within_five_scans() {
    assert_only(
        Flaw::PostPurge,
        &normal_day(),
        90_000,
        Rule::OutputsOnWhileOff,
    );
}

#[test]
fn at_most_two_ignition_trials_per_start() {
    let script = Script::new()
        .at(0, Disturbance::FailIgnitions(2))
        .at(1_000, Selector::Low);
    assert_only(Flaw::ThreeTrials, &script, 60_000, Rule::TooManyTrials);
}

#[test]
fn the_main_flame_dropping_with_the_valve_open_is_a_shutdown() {
    let script = Script::new()
        .at(1_000, Selector::Low)
        .at(40_000, Disturbance::MainFlameOut { for_ms: 5_000 });
    assert_only(Flaw::SilentShutdown, &script, 60_000, Rule::NoAlarm);
}

// ------------------------------------------------- the checker on its own

fn selector_on_at_scan_1() -> Vec<Inputs> {
    let on = Inputs {
        sel_low: true,
        ..Inputs::default()
    };
    std::iter::once(Inputs::default())
        .chain(std::iter::repeat(on))
        .take(1_200)
        .collect()
}

/// Checks scans of 10 ms with `inputs`, and `outputs(k)` in scan `k`.
fn check(
    rules: Invariants,
    debounce: [u8; 7],
    inputs: &[Inputs],
    outputs: impl Fn(u64) -> Outputs,
) -> Vec<Violation> {
    let mut c = Checker::with_debounce(rules, debounce);
    for (k, i) in inputs.iter().enumerate() {
        c.observe(k as u64 * SCAN_MS, i, &outputs(k as u64));
    }
    c.finish()
}

#[test]
fn the_pre_purge_counts_from_the_scan_of_the_start_request() {
    let inputs = selector_on_at_scan_1();
    let gas_from = |k0: u64| {
        move |k: u64| Outputs {
            pilot_valve: k >= k0,
            ..Outputs::default()
        }
    };
    // Request in scan 1 (10 ms): 10 s later is scan 1001.
    assert!(check(Invariants::default(), [0; 7], &inputs, gas_from(1_001)).is_empty());
    let early = check(Invariants::default(), [0; 7], &inputs, gas_from(1_000));
    assert_eq!(early.len(), 1);
    assert_eq!(
        (early[0].scan, early[0].rule),
        (1_000, Rule::FuelBeforePurge)
    );
    assert!(early[0].message.contains("9990 ms"), "{}", early[0]);
}

#[test]
fn with_purge_needs_blower_the_air_must_run_through_the_purge() {
    let rules = Invariants {
        purge_needs_blower: true,
        ..Invariants::default()
    };
    let inputs = selector_on_at_scan_1();
    let plan = |blower_from: u64| {
        move |k: u64| Outputs {
            blower: k >= blower_from,
            damper_lo: k >= blower_from,
            pilot_valve: k >= 1_001,
            ..Outputs::default()
        }
    };
    assert!(check(rules.clone(), [0; 7], &inputs, plan(1)).is_empty());
    let late = check(rules, [0; 7], &inputs, plan(2));
    assert_eq!(late.len(), 1, "{}", listing(&late));
    assert!(late[0].message.contains("9990 ms of blower"), "{}", late[0]);
}

#[test]
fn a_shutdown_counts_from_the_debounced_edge() {
    let mut inputs = selector_on_at_scan_1();
    for i in &mut inputs[20..] {
        i.bath_hot = true;
    }
    let burner = |closed_from: u64| {
        move |k: u64| Outputs {
            pilot_valve: (2..closed_from).contains(&k),
            alarm: k >= closed_from,
            ..Outputs::default()
        }
    };
    // Raw bath_hot rises at scan 20; the controller, debouncing over 3
    // scans, sees it at scan 22 and may close until scan 24.
    let rules = Invariants {
        purge_ms: 0,
        ..Invariants::default()
    };
    let mut debounce = [0; 7];
    debounce[Input::BathHot.index()] = 3;
    assert!(check(rules.clone(), debounce, &inputs, burner(24)).is_empty());
    let v = check(rules.clone(), debounce, &inputs, burner(25));
    assert_eq!(
        v.iter().map(|v| (v.scan, v.rule)).collect::<Vec<_>>(),
        [(24, Rule::FuelNotShut), (24, Rule::NoAlarm)]
    );
    assert!(!check(rules, [0; 7], &inputs, burner(24)).is_empty());
}

#[test]
fn a_selector_on_when_the_controller_reinitialises_demands_no_heat_until_switched_on() {
    // Selector on from scan 1; the controller re-initialises at scan 100
    // (leaves fault mode); the bath limit rises at scan 200, the selector
    // is switched off at 300 and on at 301, the flue limit rises at 400.
    let mut inputs = selector_on_at_scan_1();
    for i in &mut inputs[200..] {
        i.bath_hot = true;
    }
    inputs[300].sel_low = false;
    for i in &mut inputs[400..] {
        i.flue_hot = true;
    }
    let judge = |inputs: &[Inputs], reinit: Option<usize>| {
        let mut c = Checker::new(Invariants::default());
        for (k, i) in inputs.iter().enumerate() {
            if Some(k) == reinit {
                c.reinitialised();
            }
            c.observe(k as u64 * SCAN_MS, i, &Outputs::default());
        }
        c.finish()
    };
    let scans = |v: &[Violation]| v.iter().map(|v| (v.scan, v.rule)).collect::<Vec<_>>();
    // Without re-initialisation the bath limit is a shutdown: no alarm.
    assert_eq!(
        scans(&judge(&inputs, None)),
        [(202, Rule::NoAlarm), (402, Rule::NoAlarm)]
    );
    // After it, the controller has seen no selector edge: only the flue
    // limit, after the selector was switched on again, must alarm.
    assert_eq!(scans(&judge(&inputs, Some(100))), [(402, Rule::NoAlarm)]);
    // A contact rising in the re-initialising scan itself is discarded
    // with that scan's other edges: no demand either.
    for i in &mut inputs[..300] {
        i.sel_low = false;
    }
    for i in &mut inputs[100..300] {
        i.sel_low = true;
    }
    assert_eq!(scans(&judge(&inputs, Some(100))), [(402, Rule::NoAlarm)]);
    assert_eq!(
        scans(&judge(&inputs, Some(99))),
        [(202, Rule::NoAlarm), (402, Rule::NoAlarm)]
    );
}

// ------------------------------------------- through the executor

#[test]
fn a_project_without_the_boiler_signals_is_refused_by_name() {
    let mut sim = Sim::load(&model("conveyor.plc.toml"), Backend::Table).unwrap();
    let mut plant = fresh();
    let err = boiler::run(&mut sim, &mut plant, &Script::new(), 1_000).unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, BoilerError::MissingSignals { .. }));
    for name in [
        "conveyor",
        "input `sel_high`",
        "input `main_flame`",
        "output `alarm`",
    ] {
        assert!(text.contains(name), "{text}");
    }
    assert!(!text.contains("input `reset`"), "{text}");
}

#[test]
fn the_executor_lights_the_burner_in_closed_loop() {
    let mut sim = Sim::load(&data("pilot_burner.plc.toml"), Backend::Table).unwrap();
    let mut plant = fresh();
    let script = Script::new()
        .at(1_000, Selector::Low)
        .at(40_000, Selector::Off);
    let run = boiler::run(&mut sim, &mut plant, &script, 45_000).unwrap();
    assert!(run.rows.iter().all(|r| r.fault.is_none()));
    let on = run.first(|r| r.events.iter().any(|e| e == "on")).unwrap();
    assert_eq!(on.time_ms, 1_000);
    let gas = run.first(|r| r.outputs.pilot_valve).unwrap();
    assert_eq!(gas.time_ms, 11_000);
    let flame = run
        .first(|r| r.events.iter().any(|e| e == "flame"))
        .unwrap();
    assert_eq!(flame.time_ms, 13_010, "spark one scan after the gas, 2 s");
    let lit = run.first(|r| r.events.iter().any(|e| e == "lit")).unwrap();
    assert_eq!(lit.state("burner"), Some("running"));
    assert!(run.rows[3_500].plant.firing_kw > 60.0);
    assert!(run.rows[3_500].plant.bath_c > 20.0);
    let off = run.first(|r| r.events.iter().any(|e| e == "off")).unwrap();
    assert_eq!((off.time_ms, off.outputs), (40_000, Outputs::default()));
    let v = run.violations(&Invariants::default());
    assert!(v.is_empty(), "{}", listing(&v));
}

#[test]
fn both_backends_run_the_same_closed_loop() {
    let script = Script::random(5, 120_000);
    let mut sim = Sim::load(&data("pilot_burner.plc.toml"), Backend::Table).unwrap();
    let mut plant = fresh();
    let single = boiler::run(&mut sim, &mut plant, &script, 120_000).unwrap();
    let mut ls = Lockstep::load(&data("pilot_burner.plc.toml")).unwrap();
    let mut plant = fresh();
    let both = boiler::run_with(
        &mut boiler::Plc::lockstep(&mut ls).unwrap(),
        &mut plant,
        &script,
        120_000,
    )
    .unwrap();
    assert_eq!(single, both);
}

#[test]
fn the_checker_reads_a_replay_trace_like_the_closed_loop() {
    let path = data("pilot_burner.plc.toml");
    let mut sim = Sim::load(&path, Backend::Table).unwrap();
    let mut plant = fresh();
    let script = Script::new().at(1_000, Selector::High);
    let run = boiler::run(&mut sim, &mut plant, &script, 30_000).unwrap();
    // A stricter purge, so that there is something to find.
    let rules = Invariants {
        purge_ms: 20_000,
        ..Invariants::default()
    };
    let expected = run.violations(&rules);
    assert_eq!(expected.len(), 2, "{}", listing(&expected));

    let project = sim.project().clone();
    let io = boiler::IoMap::new(&project).unwrap();
    let rows = run.input_rows(&io);
    let mut replay = Sim::new(project.clone(), Backend::Logic).unwrap();
    let trace = host_sim::replay::replay(&mut replay, &rows).unwrap();
    let found = boiler::check_replay(&project, &replay.config(), rules, &rows, &trace).unwrap();
    assert_eq!(found, expected);
}
