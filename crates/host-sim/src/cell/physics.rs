//! The cell's continuous part (section 4.3 of the paper): two mixing
//! tanks filled from the supply tanks at constant flows (eq. 9) and
//! discharged by gravity into a reactor (eq. 10, 11), two reactors drained
//! by gravity (eq. 12), their temperatures (eq. 13, [`super::thermal`]),
//! the valves (they follow the output image at once; the reactor inlets'
//! limit switches report their position) and the switches the PLC reads.
//!
//! Mixing tank a feeds reactor a's inlet A and reactor b's inlet B; mixing
//! tank b feeds reactor b's inlet A and reactor a's inlet B.

use super::params::CellParams;
use super::signals::{Commands, MixerSensors, ReactorSensors, Sensors, Unit};
use super::thermal::{temperature_rate, TemperatureController};

/// Standard gravity, m/s².
const G: f64 = 9.81;

/// Torricelli's outflow through an opening of constant `k` (m²) under a
/// head of `level` m.
fn torricelli(k: f64, level: f64) -> f64 {
    k * (2.0 * G * level.max(0.0)).sqrt()
}

/// One reactor's state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReactorState {
    /// Level, m.
    pub level: f64,
    /// Temperature of the contents, °C.
    pub temp: f64,
    /// Its temperature controller.
    pub tc: TemperatureController,
}

/// The cell's state at one instant (what a record keeps per scan).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CellState {
    /// Plant time, ms.
    pub time_ms: u64,
    /// Mixing tank levels, m.
    pub mixer_levels: [f64; 2],
    /// The reactors.
    pub reactors: [ReactorState; 2],
    /// The valve positions and drives (the last output image applied).
    pub valves: Commands,
}

/// The plant: tanks, reactors and their valves.
#[derive(Debug, Clone)]
pub struct CellPlant {
    params: CellParams,
    state: CellState,
    /// The operator's start buttons, by reactor.
    buttons: [bool; 2],
}

impl CellPlant {
    /// Empty tanks and reactors at ambient temperature, valves closed, at
    /// time 0.
    pub fn new(params: CellParams) -> CellPlant {
        let reactor = ReactorState {
            temp: params.ambient,
            ..ReactorState::default()
        };
        CellPlant {
            state: CellState {
                reactors: [reactor; 2],
                ..CellState::default()
            },
            params,
            buttons: [false; 2],
        }
    }

    /// The parameters.
    pub fn params(&self) -> &CellParams {
        &self.params
    }

    /// The state now.
    pub fn state(&self) -> CellState {
        self.state
    }

    /// Plant time, ms.
    pub fn time_ms(&self) -> u64 {
        self.state.time_ms
    }

    /// Presses (`true`) or releases the start button of `reactor`.
    pub fn press(&mut self, reactor: Unit, pressed: bool) {
        self.buttons[reactor as usize] = pressed;
    }

    /// The switches and buttons as the PLC reads them now.
    pub fn sensors(&self) -> Sensors {
        let p = &self.params;
        let s = &self.state;
        let mixer = |h: f64| MixerSensors {
            level1: h >= p.mixer_level1,
            full: h >= p.mixer_full,
            empty: h <= p.mixer_empty,
        };
        let reactor = |u: Unit| {
            let r = &s.reactors[u as usize];
            let v = &s.valves.reactors[u as usize];
            ReactorSensors {
                setpoint: r.temp >= p.reaction_temp - p.setpoint_band,
                output_temp: r.temp <= p.output_temp + p.setpoint_band,
                empty: r.level <= p.reactor_empty,
                inlet_a_open: v.inlet_a,
                inlet_b_open: v.inlet_b,
            }
        };
        Sensors {
            start: self.buttons,
            mixers: [mixer(s.mixer_levels[0]), mixer(s.mixer_levels[1])],
            reactors: [reactor(Unit::A), reactor(Unit::B)],
        }
    }

    /// The flow from mixing tank `m` into each reactor now, m³/s: into
    /// its own reactor's inlet A and the other reactor's inlet B.
    pub fn discharge_flows(&self, m: Unit) -> [f64; 2] {
        let s = &self.state;
        if !s.valves.mixers[m as usize].discharge {
            return [0.0; 2];
        }
        let q = torricelli(self.params.mixer_outflow, s.mixer_levels[m as usize]);
        let mut flows = [0.0; 2];
        flows[m as usize] = if s.valves.reactors[m as usize].inlet_a {
            q
        } else {
            0.0
        };
        flows[m.other() as usize] = if s.valves.reactors[m.other() as usize].inlet_b {
            q
        } else {
            0.0
        };
        flows
    }

    /// Runs the plant for `ms` under `commands` (the valves take their
    /// positions at once), in steps of at most `step_ms`.
    pub fn step(&mut self, ms: u64, commands: &Commands) {
        self.state.valves = *commands;
        let end = self.state.time_ms + ms;
        while self.state.time_ms < end {
            let dt_ms = self.params.step_ms.max(1).min(end - self.state.time_ms);
            self.integrate(dt_ms as f64 / 1000.0);
            self.state.time_ms += dt_ms;
        }
    }

    /// One explicit Euler step of `dt` seconds.
    fn integrate(&mut self, dt: f64) {
        let p = self.params;
        let into_reactor = {
            let (a, b) = (self.discharge_flows(Unit::A), self.discharge_flows(Unit::B));
            [a[0] + b[0], a[1] + b[1]]
        };
        for m in Unit::BOTH {
            let v = &self.state.valves.mixers[m as usize];
            let inflow: f64 = if v.fill {
                (0..3)
                    .filter(|&k| v.supply[k])
                    .map(|k| p.supply_flow[k])
                    .sum()
            } else {
                0.0
            };
            let outflow: f64 = self.discharge_flows(m).iter().sum();
            let h = &mut self.state.mixer_levels[m as usize];
            *h = (*h + (inflow - outflow) * dt / p.mixer_area).max(0.0);
        }
        for r in Unit::BOTH {
            let v = self.state.valves.reactors[r as usize];
            let reactor = &mut self.state.reactors[r as usize];
            let inflow = into_reactor[r as usize];
            let outflow = if v.drain {
                torricelli(p.reactor_outflow, reactor.level)
            } else {
                0.0
            };
            let setpoint = v.tc_on.then_some(if v.tc_cool {
                p.output_temp
            } else {
                p.reaction_temp
            });
            reactor.tc.update(&p, setpoint, reactor.temp, dt);
            // A nearly empty vessel still holds a film: the temperature
            // equation keeps a finite heat capacity.
            let volume = (reactor.level * p.reactor_area).max(p.reactor_empty * p.reactor_area);
            reactor.temp += temperature_rate(&p, &reactor.tc, volume, reactor.temp, inflow) * dt;
            reactor.level = (reactor.level + (inflow - outflow) * dt / p.reactor_area).max(0.0);
        }
    }
}
