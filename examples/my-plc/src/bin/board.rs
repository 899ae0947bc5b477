//! The conveyor's PLC on a Nucleo-F411RE: the same generated program and
//! scan cycle as `src/main.rs`, on the pins of the project's `[board]`
//! section (`ls` on PA0, `reset` on the blue button B1 = PC13, `belt` on
//! the green LED LD2 = PA5). Flash it with a probe attached:
//!
//! ```text
//! cargo flash-board
//! ```
//!
//! (an alias, `.cargo/config.toml`: `cargo run --release --features board
//! --bin board --target thumbv7em-none-eabihf`, run by `probe-rs`).
//!
//! Minimal on purpose. The repository's firmware (`crates/firmware`) adds
//! what a machine needs: a watchdog, edge latching between scans, overrun
//! and lost-edge reports, the background image check, logging.

#![no_std]
#![no_main]
#![deny(warnings)]
#![deny(unsafe_code)]

/// The program `build.rs` generated from `conveyor.plc.toml`.
mod conveyor {
    include!(concat!(env!("OUT_DIR"), "/conveyor.rs"));
}

use conveyor::board::{SignalPin, INPUT_PINS, OUTPUT_PINS};
use conveyor::{input, output, Memory, CONFIG, PROGRAM};
use cortex_m_rt::entry;
use executor::Controller;
use stm32f4xx_hal::{pac, prelude::*, rcc::Config};

/// Whether `signal` is wired to pin `number` of port `port`.
const fn on_pin(signal: Option<SignalPin>, port: char, number: u8) -> bool {
    matches!(signal, Some(s) if s.pin.port == port && s.pin.number == number)
}

// The pins taken below are the ones the project names: edit
// `conveyor.plc.toml` and this file together, or the build fails here.
const LS: usize = input::LS as usize;
const RESET: usize = input::RESET as usize;
const BELT: usize = output::BELT as usize;
const _: () = assert!(on_pin(INPUT_PINS[LS], 'A', 0), "ls is not on PA0");
const _: () = assert!(on_pin(INPUT_PINS[RESET], 'C', 13), "reset is not on PC13");
const _: () = assert!(on_pin(OUTPUT_PINS[BELT], 'A', 5), "belt is not on PA5");

/// Whether the signal on a pin is 1, given the pin's level.
fn signal(pin: Option<SignalPin>, high: bool) -> bool {
    high != pin.is_some_and(|p| p.active_low)
}

#[entry]
fn main() -> ! {
    let (Some(dp), Some(cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        panic!("peripherals taken twice");
    };
    // The 16 MHz internal oscillator: no crystal needed.
    let mut rcc = dp.RCC.freeze(Config::hsi());
    let gpioa = dp.GPIOA.split(&mut rcc);
    let gpioc = dp.GPIOC.split(&mut rcc);
    let ls = gpioa.pa0.into_floating_input();
    let reset = gpioc.pc13.into_pull_up_input();
    let mut belt = gpioa.pa5.into_push_pull_output();
    let mut delay = cp.SYST.delay(&rcc.clocks);

    // A generated program's structure was proven when it was generated:
    // the controller checks its CRC before it runs any of it, and the
    // structure check's code stays out of the flash.
    let mut plc = match Controller::new_proven(&PROGRAM, Memory::new()) {
        Ok(plc) => plc,
        Err(_) => panic!("the generated Memory does not fit the program"),
    };
    let mut raw = [false; input::COUNT];
    let mut now_ms: u32 = 0;
    loop {
        raw[LS] = signal(INPUT_PINS[LS], ls.is_high());
        raw[RESET] = signal(INPUT_PINS[RESET], reset.is_high());
        let record = plc.scan(now_ms, &raw);
        // In fault mode `outputs` is the safe image: the executor decides.
        let on = signal(OUTPUT_PINS[BELT], record.outputs[BELT]);
        belt.set_state(on.into());
        // The scan time is small next to the period: a plain delay paces
        // the scans (the firmware uses a millisecond clock and
        // `executor::pacing` instead).
        delay.delay_ms(CONFIG.scan_period_ms);
        now_ms = now_ms.wrapping_add(CONFIG.scan_period_ms);
    }
}

/// A panic resets the chip: every pin returns to its reset state (inputs,
/// so the belt's driver sees no signal) and the program starts again.
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    cortex_m::peripheral::SCB::sys_reset()
}
