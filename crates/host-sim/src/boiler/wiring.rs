//! The field wiring between the plant and the PLC's input card, where
//! sensor faults live: contact bounce, a signal stuck at a level, a
//! dropout. Faults apply to the level the PLC reads, never to the physics.

use super::signals::{Input, Inputs};

/// A fault on one input signal, installed at the plant's current time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SensorFault {
    /// No fault: the PLC reads the true level (clears an earlier fault).
    None,
    /// Contact bounce: for `for_ms` after each change of the true level, the
    /// read level alternates every `toggle_ms`, starting with the new level
    /// (new, old, new, … for `toggle_ms` each), then settles on the new
    /// level. A `toggle_ms` equal to the scan period shows one flip per
    /// scan; a divisor of it may alias to no visible bounce.
    Bounce {
        /// How long each change bounces.
        for_ms: u64,
        /// Duration of each bounce half-period (at least 1 ms).
        toggle_ms: u64,
    },
    /// The PLC reads this level from now on (a welded contact, a broken
    /// wire), until another fault replaces it.
    StuckAt(bool),
    /// The PLC reads 0 for `for_ms` from now (a loose connection), then
    /// the true level again.
    Dropout {
        /// Length of the dropout.
        for_ms: u64,
    },
}

/// A fault as installed: a dropout knows its end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Installed {
    None,
    Bounce { for_ms: u64, toggle_ms: u64 },
    StuckAt(bool),
    DropoutUntil(u64),
}

/// The true level of one input and the fault between it and the PLC.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Line {
    truth: bool,
    /// Time of the last change of the true level (none yet: no bounce).
    changed_ms: Option<u64>,
    fault: Installed,
}

/// Every input line of the boiler.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Wiring {
    lines: [Line; Input::ALL.len()],
}

impl Wiring {
    /// Fault-free wiring carrying `truth`.
    pub(crate) fn new(truth: &Inputs) -> Wiring {
        Wiring {
            lines: Input::ALL.map(|i| Line {
                truth: truth.get(i),
                changed_ms: None,
                fault: Installed::None,
            }),
        }
    }

    /// Installs `fault` on `input` at `now_ms`, replacing any earlier one.
    pub(crate) fn install(&mut self, input: Input, fault: SensorFault, now_ms: u64) {
        self.lines[input.index()].fault = match fault {
            SensorFault::None => Installed::None,
            SensorFault::Bounce { for_ms, toggle_ms } => Installed::Bounce {
                for_ms,
                toggle_ms: toggle_ms.max(1),
            },
            SensorFault::StuckAt(level) => Installed::StuckAt(level),
            SensorFault::Dropout { for_ms } => Installed::DropoutUntil(now_ms + for_ms),
        };
    }

    /// Records the true levels at `now_ms` (change times for bounce).
    pub(crate) fn update(&mut self, truth: &Inputs, now_ms: u64) {
        for input in Input::ALL {
            let line = &mut self.lines[input.index()];
            let level = truth.get(input);
            if level != line.truth {
                line.truth = level;
                line.changed_ms = Some(now_ms);
            }
        }
    }

    /// The levels the PLC reads at `now_ms`.
    pub(crate) fn read(&self, now_ms: u64) -> Inputs {
        let mut image = Inputs::default();
        for input in Input::ALL {
            image.set(input, self.lines[input.index()].read(now_ms));
        }
        image
    }
}

impl Line {
    fn read(&self, now_ms: u64) -> bool {
        match self.fault {
            Installed::None => self.truth,
            Installed::StuckAt(level) => level,
            Installed::DropoutUntil(end) => self.truth && now_ms >= end,
            Installed::Bounce { for_ms, toggle_ms } => match self.changed_ms {
                Some(at) if now_ms - at < for_ms => {
                    let half_periods = (now_ms - at) / toggle_ms;
                    self.truth ^ (half_periods % 2 == 1)
                }
                _ => self.truth,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reads(wiring: &Wiring, input: Input, times: &[u64]) -> Vec<bool> {
        times.iter().map(|&t| wiring.read(t).get(input)).collect()
    }

    #[test]
    fn bounce_alternates_from_the_new_level_then_settles() {
        let mut truth = Inputs::default();
        let mut w = Wiring::new(&truth);
        w.install(
            Input::PilotFlame,
            SensorFault::Bounce {
                for_ms: 40,
                toggle_ms: 10,
            },
            0,
        );
        truth.pilot_flame = true;
        w.update(&truth, 100);
        assert_eq!(
            reads(&w, Input::PilotFlame, &[100, 110, 120, 130, 140, 150]),
            [true, false, true, false, true, true]
        );
        truth.pilot_flame = false;
        w.update(&truth, 200);
        assert_eq!(
            reads(&w, Input::PilotFlame, &[200, 210, 240]),
            [false, true, false]
        );
    }

    #[test]
    fn a_dropout_ends_and_a_stuck_level_stays_until_replaced() {
        let truth = Inputs {
            main_flame: true,
            ..Inputs::default()
        };
        let mut w = Wiring::new(&truth);
        w.install(Input::MainFlame, SensorFault::Dropout { for_ms: 50 }, 10);
        assert_eq!(
            reads(&w, Input::MainFlame, &[10, 59, 60]),
            [false, false, true]
        );
        w.install(Input::MainFlame, SensorFault::StuckAt(false), 100);
        assert!(!w.read(1_000_000).main_flame);
        w.install(Input::MainFlame, SensorFault::None, 200);
        assert!(w.read(200).main_flame);
    }
}
