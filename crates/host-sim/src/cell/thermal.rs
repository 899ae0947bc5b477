//! A reactor's temperature (eq. 13 of the paper) and its temperature
//! controller: the PI controller the paper tunes "to perform a response
//! with no overshoot", opening the hot-water valve V_rd for a positive
//! output and the cold-water valve V_re for a negative one.

use super::params::CellParams;

/// The PI controller of one reactor's jacket.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TemperatureController {
    /// The integral part of the output.
    integral: f64,
    /// The last output: + hot valve opening, − cold valve opening, in
    /// −1 … 1.
    output: f64,
}

impl TemperatureController {
    /// The hot-water valve's opening, 0 … 1.
    pub fn hot_opening(&self) -> f64 {
        self.output.max(0.0)
    }

    /// The cold-water valve's opening, 0 … 1.
    pub fn cold_opening(&self) -> f64 {
        (-self.output).max(0.0)
    }

    /// One step of `dt` seconds towards `setpoint` from `temp`; `None`
    /// switches it off (valves closed, integral cleared).
    pub fn update(&mut self, p: &CellParams, setpoint: Option<f64>, temp: f64, dt: f64) {
        let Some(setpoint) = setpoint else {
            *self = TemperatureController::default();
            return;
        };
        let error = setpoint - temp;
        let proportional = p.pi_gain * error;
        let unclamped = proportional + self.integral;
        // Conditional integration: no windup while a valve is wide open
        // and the error would open it further. This is what keeps the
        // heat-up from overshooting.
        let saturated = (unclamped >= 1.0 && error > 0.0) || (unclamped <= -1.0 && error < 0.0);
        if !saturated {
            self.integral += p.pi_gain * error * dt / p.pi_integral_s;
        }
        self.output = (proportional + self.integral).clamp(-1.0, 1.0);
    }
}

/// dϑ/dt of a reactor (eq. 13, divided by m_mix·c_pmix) with `volume` m³
/// of mixture at `temp`, the jacket valves at the controller's openings,
/// and `inflow` m³/s of chemicals at ambient temperature mixing in.
pub fn temperature_rate(
    p: &CellParams,
    tc: &TemperatureController,
    volume: f64,
    temp: f64,
    inflow: f64,
) -> f64 {
    let hot = p.water_heat * tc.hot_opening() * p.jacket_flow * (p.hot_water - temp);
    let cold = p.water_heat * tc.cold_opening() * p.jacket_flow * (temp - p.cold_water);
    let loss = p.heat_loss * (temp - p.ambient);
    (hot - cold - loss) / (p.mixture_heat * volume) + inflow * (p.ambient - temp) / volume
}
