//! The Nucleo-F411RE (ST's UM1724).

use crate::dev_board::{DevBoard, PinNote};
use crate::pin::PinId;
use crate::STM32F411;

/// [`PinId::new`], short for the tables below.
const fn p(port: char, number: u8) -> PinId {
    PinId::new(port, number)
}

/// The Nucleo-F411RE (ST's UM1724): an STM32F411RE in LQFP64, an
/// ST-LINK that flashes it, clocks it on PH0 and carries USART2, the user
/// button B1 on PC13, the LED LD2 on PA5 and Arduino headers.
pub const NUCLEO_F411RE: DevBoard = DevBoard {
    name: "Nucleo-F411RE",
    short_name: "Nucleo",
    chip: &STM32F411,
    part: "STM32F411RETx",
    notes: &[
        PinNote {
            pins: &[p('A', 2), p('A', 3)],
            outputs_only: false,
            inputs_only: false,
            text: "carries USART2 to the ST-LINK virtual COM port on a Nucleo-F411RE and reaches the headers only after changing solder bridges (UM1724)",
        },
        PinNote {
            pins: &[p('C', 14), p('C', 15)],
            outputs_only: false,
            inputs_only: false,
            text: "is wired to the 32.768 kHz crystal X2 on a Nucleo-F411RE and is not on the headers by default (UM1724)",
        },
        PinNote {
            pins: &[p('C', 13)],
            outputs_only: true,
            inputs_only: false,
            text: "is the user button B1 on a Nucleo-F411RE: pressing it shorts the output to ground",
        },
    ],
    places: &[
        (p('A', 0), "Arduino A0"),
        (p('A', 1), "Arduino A1"),
        (p('A', 4), "Arduino A2"),
        (p('B', 0), "Arduino A3"),
        (p('C', 1), "Arduino A4"),
        (p('C', 0), "Arduino A5"),
        (p('A', 3), "Arduino D0 (ST-LINK VCP RX by default)"),
        (p('A', 2), "Arduino D1 (ST-LINK VCP TX by default)"),
        (p('A', 10), "Arduino D2"),
        (p('B', 3), "Arduino D3"),
        (p('B', 5), "Arduino D4"),
        (p('B', 4), "Arduino D5"),
        (p('B', 10), "Arduino D6"),
        (p('A', 8), "Arduino D7"),
        (p('A', 9), "Arduino D8"),
        (p('C', 7), "Arduino D9"),
        (p('B', 6), "Arduino D10"),
        (p('A', 7), "Arduino D11"),
        (p('A', 6), "Arduino D12"),
        (p('A', 5), "Arduino D13, user LED LD2"),
        (p('B', 9), "Arduino D14"),
        (p('B', 8), "Arduino D15"),
        (p('C', 13), "user button B1 (low while pressed)"),
    ],
};
