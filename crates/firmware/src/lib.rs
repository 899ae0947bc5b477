//! The PLC on a Cortex-M: the generated program of the project chosen at
//! build time (`PLC_PROJECT`, `PLC_BACKEND`; see `build.rs`), shared by
//! the board firmware (`src/main.rs`) and the QEMU replay harness, and
//! the board's edge bookkeeping as plain logic that the host tests
//! (`cargo test -p firmware --lib`):
//!
//! - [`MCU`]: the chip the board firmware is written for, as the board
//!   data describes it (crate `boards`: reserved pins, the EXTI rule, the
//!   watchdog timeout for a scan period);
//! - [`edges`]: change counts of edge-latched inputs, lost edges, the EXTI
//!   line map;
//! - [`levels`]: active-low pins;
//! - [`pause`]: the milliseconds a flash erase or write kept the
//!   millisecond clock's tick from counting;
//! - [`icount`]: instruction counts in QEMU (SysTick under `-icount`);
//! - [`slots`]: where the field-update slots are in each board's flash
//!   (feature `field-update`);
//! - [`rx_queue`]: the bytes a serial link's interrupt received, until the
//!   scan loop takes them;
//! - [`update`]: field update, what a loaded image must pass and the
//!   memory it runs in.
//!
//! No control logic lives here or in the binaries: every decision is the
//! executor's, including when scans start (`executor::pacing`: the fixed
//! grid, skipped periods, overruns), which host-sim's virtual clock
//! follows too.

#![cfg_attr(not(test), no_std)]
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod edges;
pub mod hostline;
pub mod icount;
pub mod levels;
pub mod pause;
pub mod rx_queue;
pub mod slots;
pub mod update;

/// The chip the board firmware is built for (feature `pico`: the RP2040;
/// otherwise the STM32F411, the default board's): the pins it keeps for
/// itself, its edge interrupt lines, its watchdog.
#[cfg(not(feature = "pico"))]
pub const MCU: &boards::Chip = &boards::STM32F411;
/// The chip the board firmware is built for (feature `pico`: the RP2040;
/// otherwise the STM32F411, the default board's): the pins it keeps for
/// itself, its edge interrupt lines, its watchdog.
#[cfg(feature = "pico")]
pub const MCU: &boards::Chip = &boards::RP2040;

/// The generated program: `PROGRAM`, `Memory`, `CONFIG`, the name
/// modules (`input`, `output`, `event`, `supervisor`, `states`) and, for a
/// project with a `[board]` section, the pin map (`board`).
#[allow(missing_docs, clippy::all)]
pub mod program {
    include!(concat!(env!("OUT_DIR"), "/program.rs"));
}
