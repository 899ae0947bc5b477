//! What must hold on every scan of the testbed in closed loop: no two
//! trains in one track section, no switch thrown under a train, no train
//! over points set against it, each train on its route, cranes loading
//! only a train held at their sensor, and no train standing for ever
//! while the controller is not in fault.

use super::plant::{Place, TestbedPlant};
use super::signals::Commands;
use super::track::{self, Next, Train, UNITS};
use std::fmt;

/// One invariant.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Rule {
    /// Both trains in one track section (its name, as `13_14`).
    Collision(String),
    /// A switch's motor commanded to the other position while a train is
    /// on the track through it (switch 1 … 6, the train).
    SwitchUnderTrain(u8, Train),
    /// A train ran over the points of a switch that was moving or set
    /// against it (switch, train).
    Derailed(u8, Train),
    /// A train arrived on a siding or bypass its route does not take
    /// (the sensor).
    OffRoute(Train, u8),
    /// A crane loads with no train standing at its sensor, or the train
    /// it loads left (the crane).
    CraneWithoutTrain(u8),
    /// A train has stood still for longer than the plant's `stuck_ms`
    /// while the controller was not in fault.
    Stuck(Train),
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rule::Collision(s) => write!(f, "both trains in section {s}"),
            Rule::SwitchUnderTrain(w, t) => {
                write!(f, "switch {w} thrown under train {}", t.number())
            }
            Rule::Derailed(w, t) => write!(f, "train {} derailed at switch {w}", t.number()),
            Rule::OffRoute(t, k) => {
                write!(f, "train {} off its route at sensor {k}", t.number())
            }
            Rule::CraneWithoutTrain(u) => write!(f, "crane {u} loading without its train"),
            Rule::Stuck(t) => write!(f, "train {} stuck", t.number()),
        }
    }
}

/// A broken invariant and the time of the scan that found it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Violation {
    /// Plant time of the scan, ms.
    pub time_ms: u64,
    /// What broke.
    pub rule: Rule,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:.2} s: {}", self.time_ms as f64 / 1000.0, self.rule)
    }
}

/// The invariants, checked scan by scan; it remembers what it needs of
/// earlier scans (derailments seen, arrivals checked, stuck trains
/// reported).
#[derive(Debug, Clone, Default)]
pub struct Checker {
    derailments_seen: usize,
    passed_checked: [u32; 2],
    stuck_reported: [bool; 2],
}

impl Checker {
    /// A checker that has seen nothing yet.
    pub fn new() -> Checker {
        Checker::default()
    }

    /// The invariants broken in one scan at `time_ms`: `before` is the
    /// plant when the controller read its inputs, `commands` the output
    /// image the scan wrote, `after` the plant advanced under it to the
    /// next scan, `faulted` whether the controller is in fault mode.
    pub fn check(
        &mut self,
        time_ms: u64,
        before: &TestbedPlant,
        commands: &Commands,
        after: &TestbedPlant,
        faulted: bool,
    ) -> Vec<Rule> {
        let mut broken = Vec::new();
        for p in [before, after] {
            let (a, b) = (p.heading(Train::T1), p.heading(Train::T2));
            let s = track::section(a);
            if s == track::section(b) && !broken.contains(&Rule::Collision(track::section_name(s)))
            {
                broken.push(Rule::Collision(track::section_name(s)));
            }
        }
        self.switches(before, commands, &mut broken);
        for &(_, t, w) in &after.derailments[self.derailments_seen.min(after.derailments.len())..] {
            broken.push(Rule::Derailed(w, t));
        }
        self.derailments_seen = after.derailments.len();
        for t in Train::BOTH {
            let train = &after.trains[t.index()];
            if train.sensors_passed != self.passed_checked[t.index()] {
                self.passed_checked[t.index()] = train.sensors_passed;
                if let Place::At { sensor, .. } = train.place {
                    if let Some((unit, siding)) = TestbedPlant::unit_branch(sensor) {
                        if siding != t.takes_siding(unit) {
                            broken.push(Rule::OffRoute(t, sensor));
                        }
                    }
                }
            }
            let still = time_ms.saturating_sub(train.still_since_ms);
            if faulted || still < after.params().stuck_ms {
                self.stuck_reported[t.index()] = false;
            } else if !self.stuck_reported[t.index()] {
                self.stuck_reported[t.index()] = true;
                broken.push(Rule::Stuck(t));
            }
        }
        for (c, unit) in UNITS.iter().enumerate() {
            if let Some((_, train)) = after.cranes[c].loading {
                if train.is_none() || after.train_at(unit.crane_sensor) != train {
                    broken.push(Rule::CraneWithoutTrain(unit.crane));
                }
            }
        }
        broken
    }

    /// A switch commanded away from where it is (or is going) while a
    /// train is on the track through it.
    fn switches(&self, before: &TestbedPlant, commands: &Commands, broken: &mut Vec<Rule>) {
        for (i, coils) in commands.points.iter().enumerate() {
            let w = i as u8 + 1;
            let s = before.switch(w);
            let heading = s.moving.map_or(s.position, |(p, _)| p);
            let want = match coils {
                [true, false] => track::Position::Straight,
                [false, true] => track::Position::Diverging,
                _ => continue,
            };
            if want == heading {
                continue;
            }
            for t in Train::BOTH {
                if on_switch(before, t, w) {
                    broken.push(Rule::SwitchUnderTrain(w, t));
                }
            }
        }
    }
}

/// Whether train `t` is on the track through switch `w`: moving from a
/// sensor whose next track crosses it.
fn on_switch(plant: &TestbedPlant, t: Train, w: u8) -> bool {
    let Place::Moving { from, .. } = plant.trains[t.index()].place else {
        return false;
    };
    match track::next(from) {
        Next::Branch { switch, .. } => switch == w,
        Next::To(k) => track::points(from, k).is_some_and(|(s, _, _)| s == w),
    }
}
