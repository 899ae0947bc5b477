//! The cell's physical parameters. The paper gives the equations (9)–(13)
//! but no numbers; every value here is ours, chosen so that a batch takes
//! about a quarter of an hour and each phase is many scans long.

/// Tank sizes, flows, temperatures and the temperature controller's
/// tuning. Lengths in m, areas in m², flows in m³/s, temperatures in °C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellParams {
    /// A_m: cross-section of a mixing tank.
    pub mixer_area: f64,
    /// φ_a, φ_b, φ_c: the constant supply flows (eq. 9), by component.
    pub supply_flow: [f64; 3],
    /// K_mr: the outflow constant of a mixing tank into a reactor (eq. 10,
    /// 11), pipe and valves.
    pub mixer_outflow: f64,
    /// Level switch "component a or b filled".
    pub mixer_level1: f64,
    /// Level switch "full" (component c added).
    pub mixer_full: f64,
    /// Level switch "empty": the level at or below which it reads 1.
    pub mixer_empty: f64,
    /// Overflow: the brim of a mixing tank.
    pub mixer_height: f64,
    /// A_r: cross-section of a reactor.
    pub reactor_area: f64,
    /// K_r: the drain constant of a reactor (eq. 12).
    pub reactor_outflow: f64,
    /// Minimum level switch: the reactor reads empty at or below it.
    pub reactor_empty: f64,
    /// Overflow: the brim of a reactor.
    pub reactor_height: f64,
    /// ϑ_d: the hot water of the jacket.
    pub hot_water: f64,
    /// ϑ_e: the cold water.
    pub cold_water: f64,
    /// ϑ_0: the ambient temperature, also that of the chemicals flowing in.
    pub ambient: f64,
    /// The largest flow of the proportional valves V_rd (hot) and V_re
    /// (cold).
    pub jacket_flow: f64,
    /// ρ_w·c_pw of the jacket water, J/(m³·K).
    pub water_heat: f64,
    /// ρ·c_p of the mixture (m_mix·c_pmix = this × volume), J/(m³·K).
    pub mixture_heat: f64,
    /// A_rl·K_l: heat loss to the environment, W/K.
    pub heat_loss: f64,
    /// The reaction temperature (the controller's setpoint while heating
    /// and reacting).
    pub reaction_temp: f64,
    /// The output temperature (its setpoint while cooling).
    pub output_temp: f64,
    /// The switches "setpoint reached" and "output temperature reached"
    /// read 1 within this of their temperature (the controller approaches
    /// both without overshoot, so never quite reaches them).
    pub setpoint_band: f64,
    /// PI gain (valve opening per K).
    pub pi_gain: f64,
    /// PI integral time, s.
    pub pi_integral_s: f64,
    /// Heat-up as constraint (6) means it: a reactor heats up while its
    /// hot-water valve is open more than this (holding the reaction
    /// temperature needs a few per cent).
    pub heating_up_opening: f64,
    /// Integration step of the plant, ms.
    pub step_ms: u64,
}

impl Default for CellParams {
    fn default() -> Self {
        CellParams {
            mixer_area: 0.5,
            supply_flow: [0.005, 0.005, 0.005],
            mixer_outflow: 0.0025,
            mixer_level1: 0.3,
            mixer_full: 0.6,
            mixer_empty: 0.002,
            mixer_height: 0.8,
            reactor_area: 0.6,
            reactor_outflow: 0.003,
            reactor_empty: 0.01,
            reactor_height: 1.4,
            hot_water: 95.0,
            cold_water: 10.0,
            ambient: 20.0,
            jacket_flow: 0.005,
            water_heat: 4.18e6,
            mixture_heat: 4.0e6,
            heat_loss: 500.0,
            reaction_temp: 80.0,
            output_temp: 35.0,
            setpoint_band: 0.5,
            pi_gain: 0.2,
            pi_integral_s: 600.0,
            heating_up_opening: 0.5,
            step_ms: 100,
        }
    }
}
