//! The testbed's physics: trains moving along the track at their speeds
//! and stopping at every sensor until their `go` output sends them on,
//! switches thrown by their motors' coils, cranes loading for a while
//! once told to; and the sensor faults a scenario injects.

use super::signals::{Commands, Inputs};
use super::track::{self, Next, Position, Train, Unit, SENSORS, UNITS};

/// The plant's numbers (ours: the paper gives none).
#[derive(Debug, Clone, PartialEq)]
pub struct TestbedParams {
    /// Length of the track between two consecutive sensors, mm.
    pub segment_mm: u64,
    /// Where the switch points are on a segment through a switch: this
    /// far after a diverging switch's approach sensor, this far before a
    /// merging switch's departure sensor, mm.
    pub points_mm: u64,
    /// Speed of each train, mm/s.
    pub speed_mm_s: [u64; 2],
    /// Time a switch motor takes from one position to the other, ms.
    pub throw_ms: u64,
    /// Time each crane takes to load a train, ms.
    pub load_ms: [u64; 3],
    /// A train standing this long while the controller is not in fault
    /// is stuck, ms.
    pub stuck_ms: u64,
}

impl Default for TestbedParams {
    fn default() -> TestbedParams {
        TestbedParams {
            segment_mm: 1_000,
            points_mm: 300,
            speed_mm_s: [1_000, 800],
            throw_ms: 200,
            load_ms: [2_000, 2_500, 1_500],
            stuck_ms: 60_000,
        }
    }
}

/// Where a train is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// Standing at a sensor since a time (ms).
    At {
        /// The sensor.
        sensor: u8,
        /// When it arrived there.
        since_ms: u64,
    },
    /// On the track after a sensor.
    Moving {
        /// The sensor it left.
        from: u8,
        /// The sensor ahead; `None` before the points of a diverging
        /// switch, whose position decides it.
        to: Option<u8>,
        /// Distance from `from`, mm.
        mm: u64,
    },
}

/// One train.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TrainState {
    /// Where it is.
    pub place: Place,
    /// When it last moved (or arrived), ms.
    pub still_since_ms: u64,
    /// Laps completed: arrivals back at its start sensor.
    pub laps: u32,
    /// Sensors passed.
    pub sensors_passed: u32,
}

/// One switch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SwitchState {
    /// Where its blades are (the position it is leaving while moving).
    pub position: Position,
    /// Moving to a position, done at a time (ms).
    pub moving: Option<(Position, u64)>,
}

/// One crane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CraneState {
    /// Loading since (ms), and the train at its sensor when it started.
    pub loading: Option<(u64, Option<Train>)>,
    /// Its `done` signal: on from the end of a load until `load` drops.
    pub done: bool,
    /// Loads completed, by train (a load with no train at the crane's
    /// sensor counts for neither).
    pub loads: [u32; 2],
}

/// A sensor fault.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SensorFault {
    /// The sensor reports the other train: train I at it raises the
    /// input of train J.
    WrongTrain {
        /// The sensor.
        sensor: u8,
    },
    /// The input of (sensor, train) is stuck on.
    StuckOn {
        /// The sensor.
        sensor: u8,
        /// The train whose input it is.
        train: Train,
    },
}

/// What a scenario does to the testbed at a given time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// A sensor goes wrong, from now on.
    Fault(SensorFault),
}

/// The testbed: trains, switches, cranes, on a millisecond clock.
#[derive(Debug, Clone)]
pub struct TestbedPlant {
    params: TestbedParams,
    time_ms: u64,
    /// Trains 1 and 2.
    pub trains: [TrainState; 2],
    /// Switches 1 … 6.
    pub switches: [SwitchState; 6],
    /// Cranes 1 … 3.
    pub cranes: [CraneState; 3],
    faults: Vec<SensorFault>,
    /// Every time a train ran over points that were moving or set
    /// against it: (time, train, switch).
    pub derailments: Vec<(u64, Train, u8)>,
    /// Sub-millimetre progress of each train, µm (so that slow trains and
    /// short steps still move).
    micro: [u64; 2],
}

impl TestbedPlant {
    /// Trains stopped at their start sensors, switches straight, cranes
    /// idle, at time 0.
    pub fn new(params: TestbedParams) -> TestbedPlant {
        let train = |t: Train| TrainState {
            place: Place::At {
                sensor: t.start(),
                since_ms: 0,
            },
            still_since_ms: 0,
            laps: 0,
            sensors_passed: 0,
        };
        TestbedPlant {
            params,
            time_ms: 0,
            trains: [train(Train::T1), train(Train::T2)],
            switches: [SwitchState {
                position: Position::Straight,
                moving: None,
            }; 6],
            cranes: [CraneState::default(); 3],
            faults: Vec::new(),
            derailments: Vec::new(),
            micro: [0; 2],
        }
    }

    /// Its numbers.
    pub fn params(&self) -> &TestbedParams {
        &self.params
    }

    /// Plant time, ms.
    pub fn time_ms(&self) -> u64 {
        self.time_ms
    }

    /// Applies `action` now.
    pub fn apply(&mut self, action: &Action) {
        match *action {
            Action::Fault(f) => self.faults.push(f),
        }
    }

    /// The switch `w` (1 … 6).
    pub fn switch(&self, w: u8) -> &SwitchState {
        &self.switches[usize::from(w.clamp(1, 6) - 1)]
    }

    /// The sensor a train stands at or is heading for (the position of a
    /// diverging switch not yet passed decides, its target while it
    /// moves): what a section supervisor counts it in.
    pub fn heading(&self, t: Train) -> u8 {
        match self.trains[t.index()].place {
            Place::At { sensor, .. }
            | Place::Moving {
                to: Some(sensor), ..
            } => sensor,
            Place::Moving { from, to: None, .. } => match track::next(from) {
                Next::To(k) => k,
                Next::Branch {
                    switch,
                    straight,
                    diverging,
                } => {
                    let s = self.switch(switch);
                    match s.moving.map_or(s.position, |(p, _)| p) {
                        Position::Straight => straight,
                        Position::Diverging => diverging,
                    }
                }
            },
        }
    }

    /// The input image: every (sensor, train) input and the cranes'
    /// `done`, faults included.
    pub fn inputs(&self) -> Inputs {
        let mut at = [[false; 2]; SENSORS as usize];
        for t in Train::BOTH {
            if let Place::At { sensor, .. } = self.trains[t.index()].place {
                let wrong = self.faults.contains(&SensorFault::WrongTrain { sensor });
                let shown = if wrong { t.other() } else { t };
                at[usize::from(sensor - 1)][shown.index()] = true;
            }
        }
        for f in &self.faults {
            if let SensorFault::StuckOn { sensor, train } = *f {
                at[usize::from(sensor.clamp(1, SENSORS) - 1)][train.index()] = true;
            }
        }
        Inputs {
            at,
            done: self.cranes.map(|c| c.done),
        }
    }

    /// Advances by `dt_ms` under `commands`, the output image of the scan
    /// at `scan_ms` (a train stopped at a sensor leaves only on a `go` of
    /// a scan that saw it there).
    pub fn step(&mut self, dt_ms: u64, scan_ms: u64, commands: &Commands) {
        let end = self.time_ms + dt_ms;
        self.step_switches(commands);
        self.step_cranes(commands);
        for t in Train::BOTH {
            self.step_train(t, dt_ms, scan_ms, commands.go[t.index()]);
        }
        self.time_ms = end;
        for s in &mut self.switches {
            if let Some((p, done)) = s.moving {
                if done <= end {
                    s.position = p;
                    s.moving = None;
                }
            }
        }
    }

    fn step_switches(&mut self, commands: &Commands) {
        let now = self.time_ms;
        for (s, coils) in self.switches.iter_mut().zip(commands.points) {
            let want = match coils {
                [true, false] => Some(Position::Straight),
                [false, true] => Some(Position::Diverging),
                _ => None,
            };
            let Some(want) = want else { continue };
            let heading = s.moving.map_or(s.position, |(p, _)| p);
            if heading != want {
                s.moving = Some((want, now + self.params.throw_ms));
            }
        }
    }

    fn step_cranes(&mut self, commands: &Commands) {
        let now = self.time_ms;
        for (c, unit) in UNITS.iter().enumerate() {
            let under = self.train_at(unit.crane_sensor);
            let params = &self.params;
            let crane = &mut self.cranes[c];
            match (commands.load[c], crane.loading, crane.done) {
                (true, None, false) => crane.loading = Some((now, under)),
                (true, Some((since, train)), _) if now >= since + params.load_ms[c] => {
                    crane.loading = None;
                    crane.done = true;
                    if let Some(t) = train {
                        crane.loads[t.index()] += 1;
                    }
                }
                (false, _, _) => {
                    crane.loading = None;
                    crane.done = false;
                }
                _ => {}
            }
        }
    }

    /// The train standing at `sensor`, if any.
    pub fn train_at(&self, sensor: u8) -> Option<Train> {
        Train::BOTH.into_iter().find(
            |t| matches!(self.trains[t.index()].place, Place::At { sensor: k, .. } if k == sensor),
        )
    }

    fn step_train(&mut self, t: Train, dt_ms: u64, scan_ms: u64, go: bool) {
        let i = t.index();
        let now = self.time_ms;
        let train = &mut self.trains[i];
        if let Place::At { sensor, since_ms } = train.place {
            if !(go && since_ms <= scan_ms) {
                return;
            }
            train.place = Place::Moving {
                from: sensor,
                to: match track::next(sensor) {
                    Next::To(k) => Some(k),
                    Next::Branch { .. } => None,
                },
                mm: 0,
            };
        }
        if !go {
            // Fault mode (or a controller gone wrong): brakes on, here.
            return;
        }
        let Place::Moving { from, to, mm } = train.place else {
            return;
        };
        let micro = self.micro[i] + self.params.speed_mm_s[i] * dt_ms;
        self.micro[i] = micro % 1_000;
        let mm2 = (mm + micro / 1_000).min(self.params.segment_mm);
        if mm2 > mm {
            train.still_since_ms = now;
        }
        self.over_points(t, from, to, mm, mm2);
        let mut to = to;
        if to.is_none() && mm2 >= self.params.points_mm {
            // Over the points of a diverging switch: its blades decide.
            if let Next::Branch {
                switch,
                straight,
                diverging,
            } = track::next(from)
            {
                let s = self.switches[usize::from(switch - 1)];
                to = Some(match s.position {
                    Position::Straight => straight,
                    Position::Diverging => diverging,
                });
            }
        }
        let train = &mut self.trains[i];
        if mm2 >= self.params.segment_mm {
            let sensor = to.unwrap_or(from);
            train.place = Place::At {
                sensor,
                since_ms: now + dt_ms,
            };
            train.still_since_ms = now + dt_ms;
            train.sensors_passed += 1;
            if sensor == t.start() {
                train.laps += 1;
            }
            self.micro[i] = 0;
        } else {
            train.place = Place::Moving { from, to, mm: mm2 };
        }
    }

    /// Records a derailment when train `t`, moving from `mm` to `mm2`
    /// after sensor `from` towards `to`, runs over points that are moving
    /// or (merging) set against it.
    fn over_points(&mut self, t: Train, from: u8, to: Option<u8>, mm: u64, mm2: u64) {
        let (switch, need, at) = match (track::next(from), to) {
            (Next::Branch { switch, .. }, _) => (switch, None, self.params.points_mm),
            (Next::To(k), _) => match track::points(from, k) {
                Some((w, p, false)) => (
                    w,
                    Some(p),
                    self.params.segment_mm.saturating_sub(self.params.points_mm),
                ),
                _ => return,
            },
        };
        if !(mm < at && mm2 >= at) {
            return;
        }
        let s = self.switches[usize::from(switch - 1)];
        if s.moving.is_some() || need.is_some_and(|p| p != s.position) {
            self.derailments.push((self.time_ms, t, switch));
        }
    }

    /// The work unit whose siding or bypass a train at `sensor` is on,
    /// with whether it is the siding.
    pub fn unit_branch(sensor: u8) -> Option<(&'static Unit, bool)> {
        UNITS.iter().find_map(|u| {
            if sensor == u.bypass {
                Some((u, false))
            } else if sensor == u.crane_sensor || sensor == u.exit {
                Some((u, true))
            } else {
                None
            }
        })
    }
}
