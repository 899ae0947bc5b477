//! What happens to the boiler from outside the control loop: operator
//! actions, physical disturbances and sensor faults at given plant times,
//! written by hand or drawn from a seed.

use super::physics::{BoilerPlant, Disturbance};
use super::signals::{Input, Selector};
use super::wiring::SensorFault;
use crate::rng::Rng;

/// One thing that happens to the plant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action {
    /// The operator turns the selector.
    Selector(Selector),
    /// The operator presses reset (a pulse of
    /// [`BoilerParams::reset_pulse_ms`](super::BoilerParams::reset_pulse_ms)).
    Reset,
    /// A physical fault or a change of operating conditions.
    Disturb(Disturbance),
    /// A fault on one input's wiring (replacing any earlier one there).
    SensorFault(Input, SensorFault),
    /// The controller hangs for `ms` (a blocking driver, an interrupt
    /// storm) right after the first scan at or after the action's time:
    /// no scans, its outputs hold, the plant goes on. The next scan starts
    /// when the hang ends, `ms` minus one period after its deadline, and is
    /// an overrun when that is more than the project's `overrun_limit`
    /// periods (docs/semantics.md, "Scan pacing").
    Stall {
        /// How long no scan runs.
        ms: u64,
    },
}

impl Action {
    /// Applies this action to `plant` now. A [`Action::Stall`] is the
    /// controller's, not the plant's: it changes nothing here (see
    /// [`run_with`](super::run_with)).
    pub fn apply_to(&self, plant: &mut BoilerPlant) {
        match *self {
            Action::Selector(position) => plant.set_selector(position),
            Action::Reset => plant.press_reset(),
            Action::Disturb(d) => plant.disturb(d),
            Action::SensorFault(input, fault) => plant.install_sensor_fault(input, fault),
            Action::Stall { .. } => {}
        }
    }
}

impl From<Selector> for Action {
    fn from(position: Selector) -> Action {
        Action::Selector(position)
    }
}

impl From<Disturbance> for Action {
    fn from(disturbance: Disturbance) -> Action {
        Action::Disturb(disturbance)
    }
}

/// Actions at plant times, kept in time order (actions at the same time in
/// the order they were added).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Script {
    actions: Vec<(u64, Action)>,
}

impl Script {
    /// An empty script.
    pub fn new() -> Script {
        Script::default()
    }

    /// This script with `action` at `time_ms`:
    /// `Script::new().at(1_000, Selector::High).at(60_000, Action::Reset)`.
    #[must_use]
    pub fn at(mut self, time_ms: u64, action: impl Into<Action>) -> Script {
        self.push(time_ms, action);
        self
    }

    /// Adds `action` at `time_ms`.
    pub fn push(&mut self, time_ms: u64, action: impl Into<Action>) {
        let k = self.actions.partition_point(|&(t, _)| t <= time_ms);
        self.actions.insert(k, (time_ms, action.into()));
    }

    /// The actions in time order.
    pub fn actions(&self) -> &[(u64, Action)] {
        &self.actions
    }

    /// A random script over `[0, duration_ms)`, the same for the same
    /// seed: the operator switches on (low or high) within the first 5 s;
    /// then, every 3–43 s, one of: a selector change (off for 2–20 s now
    /// and then), a reset, failing ignition trials, a pilot or main
    /// flame-out, a process-load change (-40…140 kW), a bath-temperature
    /// excursion (70…90 °C, relieved 20–60 s later), a fouled flue (for
    /// 10–70 s), or a sensor fault (bounce, stuck-at, dropout) on a random
    /// input, cleared after 1–30 s. Most disturbances are followed by a
    /// reset some seconds after they are over, so the run goes on.
    pub fn random(seed: u64, duration_ms: u64) -> Script {
        let mut draw = Draw {
            rng: Rng::new(seed),
            script: Script::new(),
            duration_ms,
        };
        let mut t = 500 + draw.below(4_500);
        let on = draw.on_position();
        draw.add(t, on);
        loop {
            t += 3_000 + draw.below(40_000);
            if t >= duration_ms {
                break;
            }
            draw.event(t);
        }
        draw.script
    }
}

/// The state of [`Script::random`].
struct Draw {
    rng: Rng,
    script: Script,
    duration_ms: u64,
}

impl Draw {
    fn below(&mut self, n: u64) -> u64 {
        self.rng.next_u64() % n.max(1)
    }

    fn add(&mut self, t: u64, action: impl Into<Action>) {
        if t < self.duration_ms {
            self.script.push(t, action);
        }
    }

    fn on_position(&mut self) -> Selector {
        if self.below(2) == 0 {
            Selector::Low
        } else {
            Selector::High
        }
    }

    /// A reset some seconds after `t`, most of the time.
    fn reset_later(&mut self, t: u64) {
        if self.below(10) < 7 {
            let at = t + 3_000 + self.below(12_000);
            self.add(at, Action::Reset);
        }
    }

    fn event(&mut self, t: u64) {
        match self.below(100) {
            0..=19 => {
                if self.below(4) == 0 {
                    self.add(t, Selector::Off);
                    let back = t + 2_000 + self.below(18_000);
                    let on = self.on_position();
                    self.add(back, on);
                } else {
                    let on = self.on_position();
                    self.add(t, on);
                }
            }
            20..=29 => self.add(t, Action::Reset),
            30..=39 => {
                let n = 1 + self.below(2) as u32;
                self.add(t, Disturbance::FailIgnitions(n));
                self.reset_later(t + 20_000);
            }
            40..=47 => {
                let for_ms = self.below(5_000);
                self.add(t, Disturbance::PilotFlameOut { for_ms });
                self.reset_later(t);
            }
            48..=55 => {
                let for_ms = self.below(5_000);
                self.add(t, Disturbance::MainFlameOut { for_ms });
                self.reset_later(t);
            }
            56..=65 => {
                let kw = self.below(180) as f64 - 40.0;
                self.add(t, Disturbance::Load(kw));
            }
            66..=71 => {
                let c = 70.0 + self.below(200) as f64 / 10.0;
                self.add(t, Disturbance::BathTemperature(c));
                let relief = t + 20_000 + self.below(40_000);
                let cool = 50.0 + self.below(250) as f64 / 10.0;
                self.add(relief, Disturbance::BathTemperature(cool));
                self.reset_later(relief);
            }
            72..=77 => {
                let k = 80.0 + self.below(150) as f64;
                self.add(t, Disturbance::FlueFouling(k));
                let clean = t + 10_000 + self.below(60_000);
                self.add(clean, Disturbance::FlueFouling(0.0));
                self.reset_later(clean);
            }
            78..=81 => {
                let ms = 20 + self.below(480);
                self.add(t, Action::Stall { ms });
                self.reset_later(t);
            }
            _ => self.sensor_fault(t),
        }
    }

    fn sensor_fault(&mut self, t: u64) {
        let input = Input::ALL[self.below(Input::ALL.len() as u64) as usize];
        let fault = match self.below(4) {
            0 | 1 => SensorFault::Bounce {
                for_ms: 10 + self.below(90),
                toggle_ms: 3 + self.below(12),
            },
            2 => SensorFault::StuckAt(self.below(2) == 1),
            _ => SensorFault::Dropout {
                for_ms: 10 + self.below(3_000),
            },
        };
        self.add(t, Action::SensorFault(input, fault));
        let clear = t + 1_000 + self.below(29_000);
        self.add(clear, Action::SensorFault(input, SensorFault::None));
        self.reset_later(clear);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn actions_stay_in_time_order_and_ties_keep_their_order() {
        let s = Script::new()
            .at(2_000, Selector::Off)
            .at(1_000, Selector::High)
            .at(2_000, Action::Reset);
        let times: Vec<u64> = s.actions().iter().map(|a| a.0).collect();
        assert_eq!(times, [1_000, 2_000, 2_000]);
        assert_eq!(s.actions()[1].1, Action::Selector(Selector::Off));
        assert_eq!(s.actions()[2].1, Action::Reset);
    }

    #[test]
    fn a_random_script_is_a_function_of_its_seed() {
        let a = Script::random(3, 600_000);
        assert_eq!(a, Script::random(3, 600_000));
        assert_ne!(a, Script::random(4, 600_000));
        assert!(a.actions().len() > 10);
        assert!(a.actions().iter().all(|&(t, _)| t < 600_000));
    }
}
