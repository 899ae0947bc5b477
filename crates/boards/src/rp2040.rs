//! The RP2040 (Raspberry Pi RP2040 datasheet) as the Raspberry Pi Pico's
//! firmware uses it.

use crate::chip::{Chip, PinNaming, Port, Reserved, Watchdog};
use crate::pin::PinId;

/// The RP2040: one bank of 30 GPIOs, `GP0`–`GP29` (QSPI flash, USB and
/// SWD have pins of their own, so no GPIO carries them). The firmware is
/// the Raspberry Pi Pico's, which wires GP23, GP24 and GP29 on the board
/// (they are not on its headers): those are kept.
pub const RP2040: Chip = Chip {
    name: "RP2040",
    naming: PinNaming::Bank,
    ports: &[Port {
        letter: PinId::BANK,
        pins: 30,
    }],
    port_width: 30,
    packages: &[],
    reserved: &[
        Reserved {
            pin: PinId::gp(23),
            why: "GP23 drives the power-save input of the Pico's SMPS regulator and is not on the headers",
        },
        Reserved {
            pin: PinId::gp(24),
            why: "GP24 senses VBUS (USB power) on the Pico and is not on the headers",
        },
        Reserved {
            pin: PinId::gp(29),
            why: "GP29 measures VSYS/3 on the Pico (ADC3) and is not on the headers",
        },
    ],
    // Every GPIO has edge interrupts of its own (IO_BANK0 INTR, one
    // interrupt for the bank): no two inputs share a line.
    exti_lines: 30,
    edge_line: "GPIO",
    // The watchdog counts microseconds in a 24-bit register that runs down
    // by 2 each tick (erratum RP2040-E1): at most 0xffffff / 2 µs, 8.388 s.
    watchdog: Watchdog {
        periods: 4,
        min_timeout_ms: 50,
        max_timeout_ms: 8_388,
    },
};
