//! The Raspberry Pi Pico (Raspberry Pi's "Raspberry Pi Pico Datasheet").

use crate::dev_board::{DevBoard, PinNote};
use crate::pin::PinId;
use crate::RP2040;

/// [`PinId::gp`], short for the tables below.
const fn gp(number: u8) -> PinId {
    PinId::gp(number)
}

/// The Raspberry Pi Pico: an RP2040 with 2 MB of QSPI flash, a 12 MHz
/// crystal, the LED on GP25 and 26 GPIOs on its 40-pin edge (GP0–GP22,
/// GP26–GP28); SWD on its three debug pins.
pub const PICO: DevBoard = DevBoard {
    name: "Raspberry Pi Pico",
    short_name: "Pico",
    chip: &RP2040,
    part: "RP2040",
    notes: &[PinNote {
        pins: &[gp(25)],
        outputs_only: false,
        inputs_only: true,
        text: "drives the Pico's LED (through a resistor to ground) and is not on the headers: an input there reads the LED",
    }],
    places: &[
        (gp(0), "pin 1"),
        (gp(1), "pin 2"),
        (gp(2), "pin 4"),
        (gp(3), "pin 5"),
        (gp(4), "pin 6"),
        (gp(5), "pin 7"),
        (gp(6), "pin 9"),
        (gp(7), "pin 10"),
        (gp(8), "pin 11"),
        (gp(9), "pin 12"),
        (gp(10), "pin 14"),
        (gp(11), "pin 15"),
        (gp(12), "pin 16"),
        (gp(13), "pin 17"),
        (gp(14), "pin 19"),
        (gp(15), "pin 20"),
        (gp(16), "pin 21"),
        (gp(17), "pin 22"),
        (gp(18), "pin 24"),
        (gp(19), "pin 25"),
        (gp(20), "pin 26"),
        (gp(21), "pin 27"),
        (gp(22), "pin 29"),
        (gp(25), "user LED"),
        (gp(26), "pin 31"),
        (gp(27), "pin 32"),
        (gp(28), "pin 34"),
    ],
};
