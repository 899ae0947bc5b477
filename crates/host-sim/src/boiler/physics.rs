//! The gas-fired water-bath boiler (docs/seeds.md A, thesis chapter 4) as a
//! physical plant: pilot and main flames, the bath and flue-gas
//! temperatures with their limit switches, the operator panel, and the
//! sensor wiring with its faults.
//!
//! The model is qualitative but dimensioned like a small regeneration
//! heater: a 2,000 l water bath fired at 60 kW (low) or 150 kW (high)
//! through a fire tube, a process coil drawing 30 kW, losses to 20 °C
//! ambient. It is deterministic: the only randomness (ignition failures
//! with a probability) comes from a generator seeded at construction.

use super::flame::Flame;
use super::signals::{Input, Inputs, Outputs, Selector};
use super::wiring::{SensorFault, Wiring};
use crate::rng::Rng;

/// Specific heat of water per litre (≈ 1 kg/l × 4.186 kJ/(kg·K)).
const WATER_KJ_PER_L_K: f64 = 4.186;

/// The longest step of the temperature integration (ms); longer steps are
/// split so that large `dt` stays accurate.
const MAX_THERMAL_STEP_MS: u64 = 1_000;

/// The constants of the plant. The defaults describe the boiler of the
/// module documentation; every delay is in milliseconds.
#[derive(Debug, Clone, PartialEq)]
pub struct BoilerParams {
    /// Gas (`pilot_valve`) and spark (`ignition`) must both be on this long
    /// before the pilot flame forms (default 2 s).
    pub pilot_ignition_ms: u64,
    /// The pilot flame dies this long after its gas valve closes; it holds
    /// while the valve is open, spark or not (default 0.3 s).
    pub pilot_extinction_ms: u64,
    /// Probability that an ignition trial (a rising edge of `ignition`)
    /// fails, drawn from the plant's seeded generator (default 0).
    pub ignition_failure_probability: f64,
    /// Ignition trials, numbered from 1 since the plant was created, that
    /// fail whatever the probability (default none).
    pub failing_trials: Vec<u32>,
    /// Pilot flame, combustion air (blower on and a damper position open)
    /// and main gas (a main valve position open) must all be present this
    /// long before the main flame forms (default 1 s).
    pub main_ignition_ms: u64,
    /// The main flame dies this long after its gas or its air goes
    /// (default 0.2 s).
    pub main_extinction_ms: u64,
    /// Water in the bath (default 2,000 l, about 8.4 MJ/K).
    pub bath_volume_l: f64,
    /// Burner input at low fire (default 60 kW).
    pub low_fire_kw: f64,
    /// Burner input at high fire (default 150 kW).
    pub high_fire_kw: f64,
    /// Burner input of the pilot flame alone (default 1.5 kW).
    pub pilot_kw: f64,
    /// Fraction of the burner input that reaches the bath; the rest leaves
    /// with the flue gas (default 0.85).
    pub efficiency: f64,
    /// Heat loss of the bath to ambient per kelvin above it (default
    /// 0.05 kW/K: an insulated tank loses about 3 kW at 85 °C).
    pub loss_kw_per_k: f64,
    /// Ambient air temperature (default 20 °C).
    pub ambient_c: f64,
    /// Bath temperature at the start (default 20 °C).
    pub initial_bath_c: f64,
    /// Heat drawn by the process coil at the start (default 30 kW); change
    /// it with [`Disturbance::Load`]. A positive load fades out as the
    /// bath approaches ambient (within 5 K), a negative one (hot process
    /// fluid returning heat) does not.
    pub process_load_kw: f64,
    /// `bath_hot` switches on at this bath temperature (default 85 °C).
    pub bath_limit_c: f64,
    /// … and off again this far below it (default 5 K).
    pub bath_hysteresis_k: f64,
    /// Time constant of the flue-gas temperature towards its target
    /// (default 20 s).
    pub flue_tau_ms: u64,
    /// Flue gas above the bath temperature with the pilot flame alone
    /// (default 40 K).
    pub flue_rise_pilot_k: f64,
    /// … at low fire (default 120 K).
    pub flue_rise_low_k: f64,
    /// … at high fire (default 170 K: 255 °C over an 85 °C bath).
    pub flue_rise_high_k: f64,
    /// Extra flue-gas temperature with excess air, the damper on high
    /// while the gas is on low (default 30 K): the thesis's reason for
    /// watching the flue gas.
    pub flue_excess_air_k: f64,
    /// `flue_hot` switches on at this flue-gas temperature (default 300 °C).
    pub flue_limit_c: f64,
    /// … and off again this far below it (default 20 K).
    pub flue_hysteresis_k: f64,
    /// Length of an operator reset pulse (default 0.2 s).
    pub reset_pulse_ms: u64,
}

impl Default for BoilerParams {
    fn default() -> Self {
        BoilerParams {
            pilot_ignition_ms: 2_000,
            pilot_extinction_ms: 300,
            ignition_failure_probability: 0.0,
            failing_trials: Vec::new(),
            main_ignition_ms: 1_000,
            main_extinction_ms: 200,
            bath_volume_l: 2_000.0,
            low_fire_kw: 60.0,
            high_fire_kw: 150.0,
            pilot_kw: 1.5,
            efficiency: 0.85,
            loss_kw_per_k: 0.05,
            ambient_c: 20.0,
            initial_bath_c: 20.0,
            process_load_kw: 30.0,
            bath_limit_c: 85.0,
            bath_hysteresis_k: 5.0,
            flue_tau_ms: 20_000,
            flue_rise_pilot_k: 40.0,
            flue_rise_low_k: 120.0,
            flue_rise_high_k: 170.0,
            flue_excess_air_k: 30.0,
            flue_limit_c: 300.0,
            flue_hysteresis_k: 20.0,
            reset_pulse_ms: 200,
        }
    }
}

/// A physical fault or a change of operating conditions, injected at the
/// plant's current time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Disturbance {
    /// The next `n` ignition trials fail (no flame however long the spark).
    FailIgnitions(u32),
    /// The pilot flame blows out now and cannot form again for `for_ms`;
    /// afterwards it needs gas and spark like any ignition.
    PilotFlameOut {
        /// How long the pilot cannot light.
        for_ms: u64,
    },
    /// The main flame goes out now and cannot form again for `for_ms`
    /// (a failing main burner); afterwards the pilot relights it if gas and
    /// air are still on.
    MainFlameOut {
        /// How long the main burner cannot light.
        for_ms: u64,
    },
    /// The process load becomes this many kW (negative: heat flows into
    /// the bath from the process).
    Load(f64),
    /// The bath is at this temperature now (a temperature excursion).
    BathTemperature(f64),
    /// A fouled or blocked flue: the flue gas runs this many kelvin hotter
    /// while the main flame burns (0 = clean).
    FlueFouling(f64),
}

/// The true physical state at one instant, for timelines and plots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoilerState {
    /// Plant time.
    pub time_ms: u64,
    /// Bath temperature (°C).
    pub bath_c: f64,
    /// Flue-gas temperature (°C).
    pub flue_c: f64,
    /// The pilot flame burns.
    pub pilot_flame: bool,
    /// The main flame burns.
    pub main_flame: bool,
    /// Burner input (kW).
    pub firing_kw: f64,
    /// Process load (kW).
    pub load_kw: f64,
    /// The selector position the operator set.
    pub selector: Selector,
}

/// The boiler with its operator panel and sensor wiring.
///
/// Each [`BoilerPlant::step`] applies the controller's output image for
/// `dt_ms` and returns the input image the PLC reads afterwards; the
/// operator acts through [`BoilerPlant::set_selector`] and
/// [`BoilerPlant::press_reset`], faults come in through
/// [`BoilerPlant::disturb`] and [`BoilerPlant::install_sensor_fault`].
#[derive(Debug, Clone)]
pub struct BoilerPlant {
    params: BoilerParams,
    rng: Rng,
    time_ms: u64,
    selector: Selector,
    reset_until_ms: Option<u64>,
    spark_was_on: bool,
    trials: u32,
    trial_fails: bool,
    failing_next: u32,
    pilot: Flame,
    main: Flame,
    firing_kw: f64,
    bath_c: f64,
    flue_c: f64,
    load_kw: f64,
    fouling_k: f64,
    bath_hot: bool,
    flue_hot: bool,
    wiring: Wiring,
}

impl BoilerPlant {
    /// A cold boiler at time 0 (bath at `initial_bath_c`, flue gas at
    /// ambient, selector off); `seed` drives random ignition failures.
    pub fn new(params: BoilerParams, seed: u64) -> BoilerPlant {
        let mut plant = BoilerPlant {
            rng: Rng::new(seed),
            time_ms: 0,
            selector: Selector::Off,
            reset_until_ms: None,
            spark_was_on: false,
            trials: 0,
            trial_fails: false,
            failing_next: 0,
            pilot: Flame::default(),
            main: Flame::default(),
            firing_kw: 0.0,
            bath_c: params.initial_bath_c,
            flue_c: params.ambient_c,
            load_kw: params.process_load_kw,
            fouling_k: 0.0,
            bath_hot: false,
            flue_hot: false,
            wiring: Wiring::new(&Inputs::default()),
            params,
        };
        plant.limit_switches();
        plant.wiring = Wiring::new(&plant.truth());
        plant
    }

    /// The parameters.
    pub fn params(&self) -> &BoilerParams {
        &self.params
    }

    /// Plant time: 0 at construction, advanced by every step.
    pub fn time_ms(&self) -> u64 {
        self.time_ms
    }

    /// The input image the PLC reads now (sensor faults applied).
    pub fn inputs(&self) -> Inputs {
        self.wiring.read(self.time_ms)
    }

    /// The true levels of the inputs now (no sensor faults).
    pub fn truth(&self) -> Inputs {
        let (sel_high, sel_low) = match self.selector {
            Selector::Off => (false, false),
            Selector::Low => (false, true),
            Selector::High => (true, false),
        };
        Inputs {
            sel_high,
            sel_low,
            pilot_flame: self.pilot.lit(),
            main_flame: self.main.lit(),
            bath_hot: self.bath_hot,
            flue_hot: self.flue_hot,
            reset: self.reset_until_ms.is_some(),
        }
    }

    /// The physical state now.
    pub fn state(&self) -> BoilerState {
        BoilerState {
            time_ms: self.time_ms,
            bath_c: self.bath_c,
            flue_c: self.flue_c,
            pilot_flame: self.pilot.lit(),
            main_flame: self.main.lit(),
            firing_kw: self.firing_kw,
            load_kw: self.load_kw,
            selector: self.selector,
        }
    }

    /// Ignition trials (rising edges of `ignition`) so far.
    pub fn ignition_trials(&self) -> u32 {
        self.trials
    }

    /// The operator turns the selector to `position` now.
    pub fn set_selector(&mut self, position: Selector) {
        self.selector = position;
        self.settle();
    }

    /// The operator presses reset now: the contact closes for
    /// [`BoilerParams::reset_pulse_ms`].
    pub fn press_reset(&mut self) {
        self.reset_until_ms = Some(self.time_ms + self.params.reset_pulse_ms);
        self.settle();
    }

    /// Injects a physical fault or a change of operating conditions now.
    pub fn disturb(&mut self, disturbance: Disturbance) {
        let now = self.time_ms;
        match disturbance {
            Disturbance::FailIgnitions(n) => self.failing_next += n,
            Disturbance::PilotFlameOut { for_ms } => self.pilot.blow_out(now + for_ms),
            Disturbance::MainFlameOut { for_ms } => self.main.blow_out(now + for_ms),
            Disturbance::Load(kw) => self.load_kw = kw,
            Disturbance::BathTemperature(c) => self.bath_c = c,
            Disturbance::FlueFouling(k) => self.fouling_k = k,
        }
        self.settle();
    }

    /// Installs `fault` on the wiring of `input` now, replacing any earlier
    /// one there ([`SensorFault::None`] clears it).
    pub fn install_sensor_fault(&mut self, input: Input, fault: SensorFault) {
        self.wiring.install(input, fault, self.time_ms);
        self.settle();
    }

    /// Brings the limit switches and the wiring up to date after a change
    /// made from outside.
    fn settle(&mut self) {
        self.limit_switches();
        self.wiring.update(&self.truth(), self.time_ms);
    }

    /// Applies the output image `outputs` for `dt_ms`; the input image the
    /// PLC reads at the end.
    pub fn step(&mut self, dt_ms: u64, outputs: &Outputs) -> Inputs {
        self.count_trial(outputs.ignition);
        let now = self.time_ms;
        let p = &self.params;
        let pilot_gas = outputs.pilot_valve;
        let spark_lights = outputs.ignition && !self.trial_fails;
        self.pilot.step(
            now,
            dt_ms,
            pilot_gas && spark_lights,
            pilot_gas,
            p.pilot_ignition_ms,
            p.pilot_extinction_ms,
        );
        let main_gas = outputs.main_open();
        let air = outputs.air();
        self.main.step(
            now,
            dt_ms,
            self.pilot.lit() && main_gas && air,
            main_gas && air,
            p.main_ignition_ms,
            p.main_extinction_ms,
        );
        self.firing_kw = self.firing(outputs);
        self.heat(dt_ms, outputs);
        self.time_ms += dt_ms;
        if self.reset_until_ms.is_some_and(|end| self.time_ms >= end) {
            self.reset_until_ms = None;
        }
        self.settle();
        self.inputs()
    }

    /// A rising edge of the spark starts a trial, which may be doomed.
    fn count_trial(&mut self, spark: bool) {
        if spark && !self.spark_was_on {
            self.trials += 1;
            // Draw on every trial so that the sequence of draws does not
            // depend on the other failure sources.
            let unlucky = self.rng.unit() < self.params.ignition_failure_probability;
            let scripted = self.params.failing_trials.contains(&self.trials);
            let injected = self.failing_next > 0;
            if injected {
                self.failing_next -= 1;
            }
            self.trial_fails = unlucky || scripted || injected;
        }
        self.spark_was_on = spark;
    }

    /// Burner input with the flames as they are now.
    fn firing(&self, outputs: &Outputs) -> f64 {
        let p = &self.params;
        let main = match (
            self.main.lit(),
            outputs.main_valve_hi,
            outputs.main_valve_lo,
        ) {
            (true, true, _) => p.high_fire_kw,
            (true, false, true) => p.low_fire_kw,
            _ => 0.0,
        };
        let pilot = if self.pilot.lit() && outputs.pilot_valve {
            p.pilot_kw
        } else {
            0.0
        };
        main + pilot
    }

    /// The first-order heat balances of the bath and the flue gas.
    fn heat(&mut self, dt_ms: u64, outputs: &Outputs) {
        let p = &self.params;
        let capacity_kj_per_k = p.bath_volume_l * WATER_KJ_PER_L_K;
        let mut left = dt_ms;
        while left > 0 {
            let h_ms = left.min(MAX_THERMAL_STEP_MS);
            left -= h_ms;
            let h_s = h_ms as f64 / 1_000.0;
            let load = if self.load_kw > 0.0 {
                self.load_kw * ((self.bath_c - p.ambient_c) / 5.0).clamp(0.0, 1.0)
            } else {
                self.load_kw
            };
            let loss = p.loss_kw_per_k * (self.bath_c - p.ambient_c);
            self.bath_c += (p.efficiency * self.firing_kw - load - loss) * h_s / capacity_kj_per_k;
            let target = self.flue_target(outputs);
            let approach = 1.0 - (-(h_ms as f64) / p.flue_tau_ms.max(1) as f64).exp();
            self.flue_c += (target - self.flue_c) * approach;
        }
    }

    /// Where the flue-gas temperature is heading: the bath temperature
    /// plus a rise that grows with the fire, ambient without a flame.
    fn flue_target(&self, outputs: &Outputs) -> f64 {
        let p = &self.params;
        if self.main.lit() && outputs.main_open() {
            let rise = if outputs.main_valve_hi {
                p.flue_rise_high_k
            } else {
                p.flue_rise_low_k
            };
            let excess_air = if outputs.damper_hi && !outputs.main_valve_hi {
                p.flue_excess_air_k
            } else {
                0.0
            };
            self.bath_c + rise + excess_air + self.fouling_k
        } else if self.pilot.lit() {
            self.bath_c + p.flue_rise_pilot_k
        } else {
            p.ambient_c
        }
    }

    /// The limit switches: on at the limit, off the hysteresis below it.
    fn limit_switches(&mut self) {
        let p = &self.params;
        self.bath_hot = hysteresis(
            self.bath_hot,
            self.bath_c,
            p.bath_limit_c,
            p.bath_hysteresis_k,
        );
        self.flue_hot = hysteresis(
            self.flue_hot,
            self.flue_c,
            p.flue_limit_c,
            p.flue_hysteresis_k,
        );
    }
}

/// A limit switch that is `on`: on at `limit`, off at `limit - band`.
fn hysteresis(on: bool, value: f64, limit: f64, band: f64) -> bool {
    if on {
        value > limit - band
    } else {
        value >= limit
    }
}
