//! The boiler's named scenarios, shared by `host-sim boiler --scenario`
//! and the documentation: a script and how long to run it.

use super::physics::Disturbance;
use super::script::{Action, Script};
use super::signals::{Input, Selector};
use super::wiring::SensorFault;

/// Scenario names, in the order `host-sim boiler` lists them.
pub const NAMES: [&str; 12] = [
    "cold-start-high",
    "cold-start-low",
    "high-low",
    "failed-ignition",
    "pilot-relight",
    "two-pilot-failures",
    "main-flame-failure",
    "bath-over-temperature",
    "flue-over-temperature",
    "bouncing-flame-sensor",
    "operator-off",
    "controller-stall",
];

/// What scenario `name` shows, in one line (`host-sim boiler --list`).
pub fn about(name: &str) -> Option<&'static str> {
    Some(match name {
        "cold-start-high" => "selector on high: pre-purge, pilot, proving, main flame on high fire",
        "cold-start-low" => "the same on low fire",
        "high-low" => "high to low and back while firing (gas first down, air first up)",
        "failed-ignition" => {
            "no pilot flame in the 15 s window: shutdown, reset, a new start lights"
        }
        "pilot-relight" => "pilot lost while proving: a second trial in the same window, then main",
        "two-pilot-failures" => "pilot lost twice: shutdown, reset (BMS), a new selection lights",
        "main-flame-failure" => "main flame lost while firing: shutdown, alarm, reset",
        "bath-over-temperature" => "bath limit trips while firing: shutdown until reset",
        "flue-over-temperature" => "fouled flue, flue-gas limit trips: shutdown",
        "bouncing-flame-sensor" => "a bouncing pilot flame detector: debounce gives one clean edge",
        "operator-off" => "selector off while firing: everything closes, no alarm",
        "controller-stall" => {
            "controller hangs 300 ms: overrun fault, safe outputs, reset, restart"
        }
        _ if name.starts_with("random-") => "ten minutes of random actions and faults",
        _ => return None,
    })
}

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
                .at(55_000, Selector::Low)
                .at(85_000, Selector::High),
            115_000,
        ),
        "failed-ignition" => (
            Script::new()
                .at(1_000, Selector::Low)
                .at(2_000, Disturbance::FailIgnitions(1))
                .at(40_000, Action::Reset)
                .at(41_000, Selector::Off)
                .at(42_000, Selector::Low),
            90_000,
        ),
        // The pilot flame forms at about 13 s and goes out at 16 s, inside
        // the 15 s trial window (pilot proving): trial 2 sparks again, the
        // window expires with the flame and the main stage starts.
        "pilot-relight" => (
            Script::new()
                .at(1_000, Selector::Low)
                .at(16_000, Disturbance::PilotFlameOut { for_ms: 1_000 }),
            60_000,
        ),
        // Two losses in one window: shutdown, alarm; reset acknowledges
        // (burner management), the operator selects again and it lights.
        "two-pilot-failures" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(16_000, Disturbance::PilotFlameOut { for_ms: 1_000 })
                .at(21_000, Disturbance::PilotFlameOut { for_ms: 1_000 })
                .at(30_000, Action::Reset)
                .at(31_000, Selector::Off)
                .at(32_000, Selector::High),
            90_000,
        ),
        "main-flame-failure" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(45_000, Disturbance::MainFlameOut { for_ms: 60_000 })
                .at(60_000, Action::Reset),
            75_000,
        ),
        "bath-over-temperature" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(45_000, Disturbance::BathTemperature(90.0))
                .at(50_000, Disturbance::BathTemperature(60.0))
                .at(65_000, Action::Reset),
            85_000,
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
                .at(45_000, Selector::Off),
            55_000,
        ),
        // The controller hangs for 300 ms while firing on high: the next
        // scan is an overrun (more than 5 periods late), fault mode puts
        // out the safe image (every valve closed, alarm on) until reset,
        // which re-initialises the supervisors; the operator selects again.
        "controller-stall" => (
            Script::new()
                .at(1_000, Selector::High)
                .at(40_000, Action::Stall { ms: 300 })
                .at(50_000, Action::Reset)
                .at(51_000, Selector::Off)
                .at(52_000, Selector::High),
            90_000,
        ),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_listed_scenario_has_a_script_and_a_description() {
        for name in NAMES.into_iter().chain(["random-7"]) {
            assert!(named(name).is_some(), "{name}");
            assert!(about(name).is_some(), "{name}");
        }
        assert!(named("random-x").is_none() && about("nope").is_none());
    }
}
