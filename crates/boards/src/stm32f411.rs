//! The STM32F411 (RM0383, DS10314): the chip of the Nucleo-F411RE and of
//! the "Black Pill" boards.

use crate::chip::{Chip, Package, PinNaming, Port, Reserved, Watchdog};
use crate::pin::PinId;

/// Every pin of a 16-pin port.
const ALL: u16 = 0xffff;

/// The STM32F411: ports A–E with 16 pins each and port H with PH0/PH1;
/// the 64-pin (`R`) and 48-pin (`C`) packages bond out fewer (`V`, 100
/// pins, has them all); SWD and the clock input are the firmware's.
pub const STM32F411: Chip = Chip {
    name: "STM32F411",
    naming: PinNaming::Ports,
    ports: &[
        Port { letter: 'A', pins: 16 },
        Port { letter: 'B', pins: 16 },
        Port { letter: 'C', pins: 16 },
        Port { letter: 'D', pins: 16 },
        Port { letter: 'E', pins: 16 },
        Port { letter: 'H', pins: 2 },
    ],
    port_width: 16,
    packages: &[
        // LQFP64, the Nucleo-F411RE's.
        Package {
            letter: 'R',
            pins: 64,
            bonded: &[('A', ALL), ('B', ALL), ('C', ALL), ('D', 1 << 2), ('H', 0b11)],
            summary: "the 64-pin package has ports A–C, PD2, PH0 and PH1",
        },
        // UFQFPN48 / WLCSP49 ("Black Pill").
        Package {
            letter: 'C',
            pins: 48,
            bonded: &[
                ('A', ALL),
                ('B', ALL & !(1 << 11)),
                ('C', (1 << 13) | (1 << 14) | (1 << 15)),
                ('H', 0b11),
            ],
            summary: "the 48-pin package has port A, port B without PB11, PC13–PC15, PH0 and PH1",
        },
    ],
    reserved: &[
        Reserved {
            pin: PinId::new('A', 13),
            why: "PA13 is SWDIO of the debug port: the probe (the Nucleo's ST-LINK) flashes the board and reads the defmt log through it",
        },
        Reserved {
            pin: PinId::new('A', 14),
            why: "PA14 is SWCLK of the debug port: the probe (the Nucleo's ST-LINK) flashes the board and reads the defmt log through it",
        },
        Reserved {
            pin: PinId::new('H', 0),
            why: "PH0 is OSC_IN: the firmware clocks the chip from the ST-LINK's 8 MHz clock on PH0 (HSE bypass)",
        },
    ],
    exti_lines: 16,
    edge_line: "EXTI",
    // The IWDG runs on the 32 kHz LSI; with prescaler 256 and its 12-bit
    // reload it counts at most 32 767 ms (the HAL refuses 32 768 ms and
    // more).
    watchdog: Watchdog {
        periods: 4,
        min_timeout_ms: 50,
        max_timeout_ms: 32_767,
    },
};
