//! The testbed's track as `models/testbed/README.md` draws it: 26
//! sensors, one way round, three work units (a diverging switch after the
//! approach sensor, a siding with the crane's sensor, a merging switch
//! before the departure sensor), the 14 track sections of the collision
//! supervisors, and the two trains' routes.

/// Sensors on the track, numbered 1 … 26.
pub const SENSORS: u8 = 26;

/// One of the two trains.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Train {
    /// Train 1: loaded by cranes 1 and 2, starts at sensor 1.
    T1 = 0,
    /// Train 2: loaded by cranes 1 and 3, starts at sensor 16.
    T2 = 1,
}

impl Train {
    /// Both, in order.
    pub const BOTH: [Train; 2] = [Train::T1, Train::T2];

    /// 0 for train 1, 1 for train 2.
    pub fn index(self) -> usize {
        self as usize
    }

    /// 1 or 2, as in event names (`t1_at5`).
    pub fn number(self) -> u8 {
        self as u8 + 1
    }

    /// The other train.
    pub fn other(self) -> Train {
        match self {
            Train::T1 => Train::T2,
            Train::T2 => Train::T1,
        }
    }

    /// The sensor it stands at at power-on (the initial state of its
    /// sensor order, `order_tI`).
    pub fn start(self) -> u8 {
        match self {
            Train::T1 => 1,
            Train::T2 => 16,
        }
    }

    /// Whether its route takes the siding of `unit` (and is loaded by
    /// that unit's crane) rather than the bypass.
    pub fn takes_siding(self, unit: &Unit) -> bool {
        match self {
            Train::T1 => unit.crane != 3,
            Train::T2 => unit.crane != 2,
        }
    }
}

/// A work unit: sensors and switches (the README's table).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unit {
    /// Its crane, 1 … 3.
    pub crane: u8,
    /// Approach sensor `A`, before the diverging switch.
    pub approach: u8,
    /// Bypass sensor `B` (switch straight).
    pub bypass: u8,
    /// The crane's sensor `C` on the siding (switch diverging).
    pub crane_sensor: u8,
    /// The siding's exit sensor `X`.
    pub exit: u8,
    /// Departure sensor `E`, after the merging switch.
    pub departure: u8,
    /// The diverging switch, 1 … 6.
    pub diverging: u8,
    /// The merging switch, 1 … 6.
    pub merging: u8,
}

/// The three work units, in the order of their cranes.
pub const UNITS: [Unit; 3] = [
    Unit {
        crane: 1,
        approach: 11,
        bypass: 12,
        crane_sensor: 13,
        exit: 14,
        departure: 15,
        diverging: 1,
        merging: 2,
    },
    Unit {
        crane: 2,
        approach: 4,
        bypass: 5,
        crane_sensor: 6,
        exit: 7,
        departure: 8,
        diverging: 3,
        merging: 4,
    },
    Unit {
        crane: 3,
        approach: 19,
        bypass: 20,
        crane_sensor: 21,
        exit: 22,
        departure: 23,
        diverging: 5,
        merging: 6,
    },
];

/// The unit of crane `crane` (1 … 3).
pub fn unit(crane: u8) -> &'static Unit {
    &UNITS[usize::from(crane.clamp(1, 3) - 1)]
}

/// A switch position.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Position {
    /// Straight: main line, bypass (`swW_s`).
    Straight,
    /// Diverging: the siding (`swW_d`).
    Diverging,
}

impl Position {
    /// `s` or `d`, as in event names.
    pub fn letter(self) -> char {
        match self {
            Position::Straight => 's',
            Position::Diverging => 'd',
        }
    }
}

/// Where a train goes from a sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Next {
    /// Plain track to this sensor.
    To(u8),
    /// Through diverging switch `switch`: to `straight` or `diverging`.
    Branch {
        /// The switch.
        switch: u8,
        /// The sensor with the switch straight.
        straight: u8,
        /// The sensor with the switch diverging.
        diverging: u8,
    },
}

/// Where a train goes from `sensor` (1 … 26).
pub fn next(sensor: u8) -> Next {
    if let Some(u) = UNITS.iter().find(|u| u.approach == sensor) {
        return Next::Branch {
            switch: u.diverging,
            straight: u.bypass,
            diverging: u.crane_sensor,
        };
    }
    if let Some(u) = UNITS
        .iter()
        .find(|u| u.bypass == sensor || u.exit == sensor)
    {
        return Next::To(u.departure);
    }
    Next::To(if sensor >= SENSORS { 1 } else { sensor + 1 })
}

/// The switch on the track from `from` to `to` and the position a train
/// needs there: the diverging switch on the way out of an approach
/// sensor, the merging switch on the way into a departure sensor; and
/// whether the points come early on that track (diverging) or late
/// (merging).
pub fn points(from: u8, to: u8) -> Option<(u8, Position, bool)> {
    UNITS.iter().find_map(|u| {
        if from == u.approach && to == u.bypass {
            Some((u.diverging, Position::Straight, true))
        } else if from == u.approach && to == u.crane_sensor {
            Some((u.diverging, Position::Diverging, true))
        } else if from == u.bypass && to == u.departure {
            Some((u.merging, Position::Straight, false))
        } else if from == u.exit && to == u.departure {
            Some((u.merging, Position::Diverging, false))
        } else {
            None
        }
    })
}

/// The track sections of the collision supervisors
/// (`sup_section_<first>_<last>`), sensors in order.
pub const SECTIONS: [&[u8]; 14] = [
    &[4],
    &[5],
    &[6, 7],
    &[8, 9, 10],
    &[11],
    &[12],
    &[13, 14],
    &[15, 16],
    &[17, 18],
    &[19],
    &[20],
    &[21, 22],
    &[23, 24, 25],
    &[26, 1, 2, 3],
];

/// The index in [`SECTIONS`] of the section holding `sensor`.
pub fn section(sensor: u8) -> usize {
    SECTIONS
        .iter()
        .position(|s| s.contains(&sensor))
        .unwrap_or(0)
}

/// A section's name as in its supervisor's: `13_14`, `26_3`.
pub fn section_name(index: usize) -> String {
    let s = SECTIONS[index.min(SECTIONS.len() - 1)];
    format!("{}_{}", s[0], s[s.len() - 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_sensor_is_in_one_section_and_the_track_is_one_loop_per_route() {
        for k in 1..=SENSORS {
            assert_eq!(SECTIONS.iter().filter(|s| s.contains(&k)).count(), 1);
        }
        // Following each train's route from its start comes back to it
        // after visiting 22 sensors.
        for t in Train::BOTH {
            let (mut at, mut seen) = (t.start(), 0);
            loop {
                at = match next(at) {
                    Next::To(k) => k,
                    Next::Branch {
                        straight,
                        diverging,
                        ..
                    } => {
                        let u = UNITS.iter().find(|u| u.bypass == straight).unwrap();
                        if t.takes_siding(u) {
                            diverging
                        } else {
                            straight
                        }
                    }
                };
                seen += 1;
                if at == t.start() {
                    break;
                }
                assert!(seen < 40);
            }
            assert_eq!(seen, 22);
        }
        assert_eq!(points(11, 13), Some((1, Position::Diverging, true)));
        assert_eq!(points(14, 15), Some((2, Position::Diverging, false)));
        assert_eq!(points(9, 10), None);
    }
}
