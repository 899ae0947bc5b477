//! Board data: what the PLC toolchain knows about the MCUs and boards the
//! board firmware runs on, in one place, as const data.
//!
//! - pins by name ([`PinId`], `PC13`), the bias resistor of an input
//!   ([`Pull`]) and a signal's pin in a generated pin map ([`SignalPin`]);
//! - each supported chip ([`Chip`], [`CHIPS`]: the [`STM32F411`] and the
//!   [`RP2040`]):
//!   its GPIO ports, which pins each package bonds out ([`Package`]), the
//!   pins the firmware keeps for itself ([`Reserved`]: SWD, the clock
//!   input), the EXTI rule ([`Chip::exti_line`]: line *n* listens to pin
//!   *n* of one port) and the watchdog ([`Watchdog`]: its timeout for a
//!   scan period, and from it the longest scan period a board project may
//!   have, [`MAX_BOARD_SCAN_PERIOD_MS`]);
//! - development boards ([`DevBoard`], [`DEV_BOARDS`]: the
//!   [`NUCLEO_F411RE`] and the Raspberry Pi [`PICO`]): the pins they wire to something by default and
//!   where pins are on their headers.
//!
//! Project validation (`plc-project`) checks a `[board]` section against
//! it, code generation (`codegen`) words the pin map and the wiring table
//! with it, and the firmware sets its watchdog, claims its pins and maps
//! its EXTI lines from it. `#![no_std]`, no dependencies, no `unsafe`.
//!
//! ```
//! use boards::{chip_of, Pull, DEFAULT_CHIP, NUCLEO_F411RE, STM32F411};
//!
//! let chip = chip_of(DEFAULT_CHIP).unwrap();
//! assert_eq!(chip, &STM32F411);
//! let pin = chip.pin("pc13").unwrap();
//! assert_eq!(pin.to_string(), "PC13");
//! assert_eq!(chip.exti_line(pin), 13);
//! assert!(chip.package("STM32F411CEUx").unwrap().has(pin));
//! assert_eq!(NUCLEO_F411RE.place(pin), Some("user button B1 (low while pressed)"));
//! assert_eq!(Pull::from_name("up"), Some(Pull::Up));
//! assert_eq!(chip.watchdog.timeout_ms(10), 50);
//! ```

#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

#[cfg(test)]
extern crate std;

mod chip;
mod dev_board;
mod nucleo_f411re;
mod pico;
mod pin;
mod rp2040;
mod stm32f411;

pub use chip::{Chip, Package, PinError, PinErrorKind, PinNaming, Port, Reserved, Watchdog};
pub use dev_board::{DevBoard, PinNote};
pub use nucleo_f411re::NUCLEO_F411RE;
pub use pico::PICO;
pub use pin::{NotAPinName, PinId, Pull, SignalPin};
pub use rp2040::RP2040;
pub use stm32f411::STM32F411;

/// Every chip the board firmware is written for.
pub const CHIPS: &[&Chip] = &[&STM32F411, &RP2040];

/// Every development board whose default wiring is known.
pub const DEV_BOARDS: &[&DevBoard] = &[&NUCLEO_F411RE, &PICO];

/// The chip (part name, as probe-rs names it) when a project names none:
/// the Nucleo-F411RE's.
pub const DEFAULT_CHIP: &str = NUCLEO_F411RE.part;

/// Longest scan period a Nucleo-F411RE project may have (ms; each chip's
/// is its [`Watchdog::max_scan_period_ms`], the RP2040's 2000 ms): the
/// STM32F411's independent watchdog waits 4 periods for a scan to complete and cannot
/// wait longer than 32.7 s ([`Watchdog::max_scan_period_ms`]).
pub const MAX_BOARD_SCAN_PERIOD_MS: u32 = STM32F411.watchdog.max_scan_period_ms();

/// The chip the part name `part` (case-insensitive, such as
/// `STM32F411CEUx`) belongs to, if it is one of [`CHIPS`].
pub fn chip_of(part: &str) -> Option<&'static Chip> {
    CHIPS.iter().copied().find(|c| c.matches_part(part))
}

/// The development board that may carry the part `part`
/// ([`DevBoard::carries`]), if one of [`DEV_BOARDS`] does.
pub fn dev_board_of(part: &str) -> Option<&'static DevBoard> {
    DEV_BOARDS.iter().copied().find(|b| b.carries(part))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::{String, ToString};
    use std::vec::Vec;

    #[test]
    fn the_scan_period_limit_follows_from_the_watchdog() {
        let w = &STM32F411.watchdog;
        // 32 767 ms / 4 periods = 8191 ms, in whole seconds.
        assert_eq!(MAX_BOARD_SCAN_PERIOD_MS, 8000);
        assert!(w.timeout_ms(MAX_BOARD_SCAN_PERIOD_MS) <= w.max_timeout_ms);
        assert!(w.timeout_ms(8192) > w.max_timeout_ms);
    }

    #[test]
    fn the_watchdog_waits_four_periods_and_at_least_50_ms() {
        let w = &STM32F411.watchdog;
        assert_eq!(w.timeout_ms(1), 50);
        assert_eq!(w.timeout_ms(10), 50);
        assert_eq!(w.timeout_ms(13), 52);
        assert_eq!(w.timeout_ms(100), 400);
        assert_eq!(w.timeout_ms(8000), 32_000);
        assert_eq!(w.timeout_ms(u32::MAX), u32::MAX);
    }

    fn pin_error(name: &str) -> String {
        STM32F411.pin(name).unwrap_err().to_string()
    }

    #[test]
    fn a_pin_name_is_checked_against_the_chip_in_this_order() {
        assert_eq!(
            pin_error("A0"),
            "`A0` is not a pin name: expected `P<port><number>` such as `PA0` or `PC13` (ports A–E and H, pins 0–15)"
        );
        assert_eq!(
            pin_error("PF16"),
            "`PF16`: the STM32F411 has no GPIO port F (ports A–E and H)"
        );
        assert_eq!(pin_error("PH16"), "`PH16`: a port has pins 0–15");
        assert_eq!(
            pin_error("ph2"),
            "`ph2`: port H of the STM32F411 has only PH0 and PH1"
        );
        assert_eq!(STM32F411.pin(" pe15"), Ok(PinId::new('E', 15)));
        assert_eq!(STM32F411.pin("PH1"), Ok(PinId::new('H', 1)));
    }

    #[test]
    fn packages_bond_out_what_their_summaries_say() {
        let pins = |part: &str| -> Vec<String> {
            let package = STM32F411.package(part).unwrap();
            STM32F411
                .ports
                .iter()
                .flat_map(|p| (0..p.pins).map(|n| PinId::new(p.letter, n)))
                .filter(|&pin| package.has(pin))
                .map(|pin| pin.to_string())
                .collect()
        };
        let r = pins("STM32F411RETx");
        assert_eq!(r.len(), 3 * 16 + 1 + 2);
        assert!(r.contains(&"PD2".to_string()) && !r.contains(&"PD3".to_string()));
        let c = pins("stm32f411ceux");
        assert_eq!(c.len(), 16 + 15 + 3 + 2);
        assert!(!c.contains(&"PB11".to_string()) && !c.contains(&"PC12".to_string()));
        assert!(c.contains(&"PC13".to_string()) && c.contains(&"PH1".to_string()));
        // `V` (100 pins) and unknown letters: every pin.
        assert_eq!(STM32F411.package("STM32F411VET6"), None);
        assert_eq!(STM32F411.package("STM32F411"), None);
    }

    #[test]
    fn the_firmware_keeps_swd_and_the_clock_input() {
        for (pin, start) in [
            (PinId::new('A', 13), "PA13 is SWDIO"),
            (PinId::new('A', 14), "PA14 is SWCLK"),
            (PinId::new('H', 0), "PH0 is OSC_IN"),
        ] {
            assert!(STM32F411.reserved(pin).unwrap().starts_with(start));
        }
        assert_eq!(STM32F411.reserved(PinId::new('H', 1)), None);
        assert_eq!(STM32F411.reserved(PinId::new('A', 15)), None);
    }

    #[test]
    fn parts_name_their_chip_and_board() {
        assert_eq!(chip_of("stm32f411ceux"), Some(&STM32F411));
        assert_eq!(chip_of("STM32F103C8"), None);
        assert_eq!(chip_of("STM32F4"), None);
        assert_eq!(dev_board_of(DEFAULT_CHIP), Some(&NUCLEO_F411RE));
        assert_eq!(dev_board_of("stm32f411rc"), Some(&NUCLEO_F411RE));
        assert_eq!(dev_board_of("STM32F411CEUx"), None);
        assert_eq!(dev_board_of("STM32F411"), None);
    }

    #[test]
    fn the_nucleo_notes_pc13_for_outputs_only() {
        let b = &NUCLEO_F411RE;
        let pc13 = PinId::new('C', 13);
        assert_eq!(b.note(pc13, false), None);
        assert!(b
            .note(pc13, true)
            .unwrap()
            .starts_with("is the user button B1"));
        assert_eq!(
            b.note(PinId::new('A', 3), false),
            b.note(PinId::new('A', 2), true)
        );
        assert_eq!(
            b.place(PinId::new('A', 5)),
            Some("Arduino D13, user LED LD2")
        );
        assert_eq!(b.place(PinId::new('A', 11)), None);
    }

    #[test]
    fn the_rp2040_names_its_pins_gp0_to_gp29() {
        let chip = chip_of("rp2040").unwrap();
        assert_eq!(chip, &RP2040);
        assert_eq!(chip.pin("gp28"), Ok(PinId::gp(28)));
        assert_eq!(chip.pin("GP28").unwrap().to_string(), "GP28");
        let error = |name: &str| chip.pin(name).unwrap_err().to_string();
        assert_eq!(
            error("PA0"),
            "`PA0` is not a pin name of the RP2040: expected `GP<number>` such as `GP0` or `GP15` (GP0–GP29)"
        );
        assert_eq!(error("GP30"), "`GP30`: the RP2040 has GP0–GP29");
        assert!(STM32F411.pin("GP3").is_err());
        for n in [23, 24, 29] {
            let why = chip.reserved(PinId::gp(n)).unwrap();
            assert!(why.starts_with(&std::format!("GP{n} ")), "{why}");
        }
        assert_eq!(chip.reserved(PinId::gp(25)), None);
        assert_eq!(chip.package("RP2040"), None);
        assert_eq!(dev_board_of("RP2040"), Some(&PICO));
        assert_eq!(PICO.place(PinId::gp(22)), Some("pin 29"));
        assert!(PICO.note(PinId::gp(25), false).is_some());
        assert_eq!(PICO.note(PinId::gp(25), true), None);
    }

    #[test]
    fn the_rp2040_watchdog_allows_scans_up_to_two_seconds() {
        let w = &RP2040.watchdog;
        assert_eq!(w.max_scan_period_ms(), 2000);
        assert!(w.timeout_ms(2000) <= w.max_timeout_ms);
        // 0xffffff / 2 µs, what rp2040-hal's Watchdog::start accepts.
        assert_eq!(w.max_timeout_ms, 0xff_ffff / 2 / 1000);
    }

    #[test]
    fn edge_lines_are_pin_numbers() {
        for port in STM32F411.ports {
            for n in 0..port.pins {
                let line = STM32F411.exti_line(PinId::new(port.letter, n));
                assert_eq!(line, n);
                assert!(line < STM32F411.exti_lines);
            }
        }
    }
}
