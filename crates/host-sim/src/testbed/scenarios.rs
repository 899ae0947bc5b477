//! Named scenarios of the testbed (`host-sim testbed SCENARIO`): the
//! plant's numbers, what happens to it when, and how long it runs.

use super::plant::{Action, SensorFault, TestbedParams};
use super::track::Train;

/// A scenario: the plant's numbers, actions at plant times (in time
/// order), and the run's length.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The plant's numbers.
    pub params: TestbedParams,
    /// What happens when (ms).
    pub actions: Vec<(u64, Action)>,
    /// Length of the run, ms.
    pub duration_ms: u64,
}

/// The scenarios' names.
pub const NAMES: [&str; 4] = ["laps", "crane-cycles", "wrong-train", "stuck-sensor"];

/// One line about scenario `name`.
pub fn about(name: &str) -> Option<&'static str> {
    Some(match name {
        "laps" => "both trains round their routes for 2 minutes, train 2 slower",
        "crane-cycles" => "slow cranes: trains queue at crane 1 and wait for each other",
        "wrong-train" => "sensor 9 reports the other train from 15 s on: the controller faults",
        "stuck-sensor" => "sensor 20's input of train 1 sticks on at 10 s: the controller faults",
        _ => return None,
    })
}

/// Scenario `name`, or `None` for a name not in [`NAMES`].
pub fn named(name: &str) -> Option<Scenario> {
    let params = TestbedParams::default();
    Some(match name {
        "laps" => Scenario {
            params,
            actions: Vec::new(),
            duration_ms: 120_000,
        },
        "crane-cycles" => Scenario {
            params: TestbedParams {
                load_ms: [12_000, 6_000, 7_000],
                speed_mm_s: [1_000, 1_000],
                ..params
            },
            actions: Vec::new(),
            duration_ms: 120_000,
        },
        "wrong-train" => Scenario {
            params,
            actions: vec![(15_000, Action::Fault(SensorFault::WrongTrain { sensor: 9 }))],
            duration_ms: 60_000,
        },
        "stuck-sensor" => Scenario {
            params,
            actions: vec![(
                10_000,
                Action::Fault(SensorFault::StuckOn {
                    sensor: 20,
                    train: Train::T1,
                }),
            )],
            duration_ms: 30_000,
        },
        _ => return None,
    })
}
