//! The PLC on a board: the project chosen at build time (`PLC_PROJECT`,
//! which needs a `[board]` section for the board's chip) runs its scan
//! cycle on the pins of its pin map. See `docs/board.md`.
//!
//! The scan loop is the same on every board (`scan::run`, generic over
//! `scan::Board`: embedded-hal 1.0 pins, a millisecond clock, a timer,
//! the watchdog, an optional edge latch); a board module sets its chip up
//! and implements `Board`, and a feature picks it:
//!
//! - `nucleo-f411re` (the default): the STM32F411 on a Nucleo-F411RE,
//!   `thumbv7em-none-eabihf`;
//! - `pico`: the RP2040 on a Raspberry Pi Pico, `thumbv6m-none-eabi`.
//!
//! With feature `field-update` the program may come from a flash slot and
//! be replaced over the serial link while the PLC scans (`field`, over
//! the board's `field::UpdateBoard`; docs/field-update.md).
//!
//! The program image is checked when the controller starts (a mismatch
//! starts it in fault mode, `Corrupt`), which the log reports.
//!
//! On a host this binary is a stub, so `cargo clippy --workspace` and
//! `cargo test --workspace` need no cross toolchain.

#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(unsafe_code)]

#[cfg(all(target_os = "none", feature = "nucleo-f411re", feature = "pico"))]
compile_error!("the board firmware is built for one board: features `nucleo-f411re` and `pico` exclude each other (`--no-default-features --features pico`)");
#[cfg(all(
    target_os = "none",
    not(any(feature = "nucleo-f411re", feature = "pico"))
))]
compile_error!("the board firmware needs a board feature: `nucleo-f411re` (the default) or `pico` (field update: `--features field-update` on the Nucleo, `--no-default-features --features pico,field-update` on the Pico)");

#[cfg(all(target_os = "none", feature = "nucleo-f411re"))]
mod nucleo_f411re;
#[cfg(all(target_os = "none", feature = "nucleo-f411re"))]
use nucleo_f411re as board;
#[cfg(all(target_os = "none", feature = "pico"))]
mod pico;
#[cfg(all(target_os = "none", feature = "pico", not(feature = "nucleo-f411re")))]
use pico as board;
#[cfg(all(target_os = "none", feature = "field-update"))]
mod field;
#[cfg(all(target_os = "none", feature = "field-update"))]
mod link;
#[cfg(target_os = "none")]
mod panic;
#[cfg(target_os = "none")]
mod report;
#[cfg(target_os = "none")]
mod scan;
#[cfg(target_os = "none")]
mod systick;

#[cfg(target_os = "none")]
#[cortex_m_rt::entry]
fn main() -> ! {
    use defmt_rtt as _;

    let (board, startup, crc) = board::init();
    #[cfg(feature = "field-update")]
    {
        field::run(board, startup, crc)
    }
    #[cfg(not(feature = "field-update"))]
    {
        scan::run(board, startup, crc)
    }
}

/// On a host: the firmware only runs on the board.
#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "the board firmware runs on a board: cargo run -p firmware --release --target thumbv7em-none-eabihf (Nucleo-F411RE), or --no-default-features --features pico --target thumbv6m-none-eabi (Raspberry Pi Pico); see docs/board.md"
    );
    std::process::exit(2);
}
