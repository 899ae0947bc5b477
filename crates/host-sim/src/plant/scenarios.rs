//! The boiler's named scenarios, shared by `host-sim boiler --scenario`
//! and the documentation: a script and how long to run it.

use super::boiler::Disturbance;
use super::script::{Action, Script};
use super::signals::{Input, Selector};
use super::wiring::SensorFault;

/// Scenario names, in the order `host-sim boiler` lists them.
pub const NAMES: [&str; 9] = [
    "cold-start-high",
    "cold-start-low",
    "high-low",
    "failed-ignition",
    "main-flame-failure",
    "bath-over-temperature",
    "flue-over-temperature",
    "bouncing-flame-sensor",
    "operator-off",
];

/// The script and duration (ms) of scenario `name`; `random-<seed>` gives
/// a ten-minute random script.
pub fn named(name: &str) -> Option<(Script, u64)> {
    if let Some(seed) = name.strip_prefix("random-") {
        let seed = seed.parse().ok()?;
        return Some((Script::random(seed, 600_000), 600_000));
    }
    Some(match name {
        "cold-start-high" => (Script::new().at(1_000, Selector::High), 60_000),
        "cold-start-low" => (Script::new().at(1_000, Selector::Low), 60_000),
        "high-low" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(40_000, Selector::Low)
                .at(70_000, Selector::High),
            100_000,
        ),
        "failed-ignition" => (
            Script::new()
                .at(1_000, Selector::Low)
                .at(2_000, Disturbance::FailIgnitions(1))
                .at(40_000, Action::Reset)
                .at(41_000, Selector::Off)
                .at(42_000, Selector::Low),
            80_000,
        ),
        "main-flame-failure" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(30_000, Disturbance::MainFlameOut { for_ms: 60_000 })
                .at(45_000, Action::Reset),
            60_000,
        ),
        "bath-over-temperature" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(30_000, Disturbance::BathTemperature(90.0))
                .at(35_000, Disturbance::BathTemperature(60.0))
                .at(50_000, Action::Reset),
            70_000,
        ),
        "flue-over-temperature" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(20_000, Disturbance::FlueFouling(250.0)),
            90_000,
        ),
        "bouncing-flame-sensor" => (
            Script::new()
                .at(
                    0,
                    Action::SensorFault(
                        Input::PilotFlame,
                        SensorFault::Bounce {
                            for_ms: 60,
                            toggle_ms: 10,
                        },
                    ),
                )
                .at(1_000, Selector::Low),
            40_000,
        ),
        "operator-off" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(30_000, Selector::Off),
            40_000,
        ),
        _ => return None,
    })
}
