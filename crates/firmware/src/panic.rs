//! The board firmware's panic handler: the file and line of the panic and
//! its message when it is a plain string, logged with defmt as `{=str}`,
//! then a permanent undefined instruction (a HardFault, which `probe-rs
//! run` reports and stops at, as with panic-probe).
//!
//! No `core::fmt`: panic-probe's `print-defmt` logged the whole
//! `PanicInfo` through `Display2Format`, which linked the formatting
//! machinery (`fmt::write`, `Formatter::pad`, `pad_integral`, about 3 KB)
//! into every board image. A message with arguments (an index out of
//! bounds, an `unwrap` of an `Err`) is not formatted: the file and line
//! say where it was. `defmt::panic!` logs its own message first.

use core::panic::PanicInfo;

#[panic_handler]
fn panic(info: &PanicInfo<'_>) -> ! {
    cortex_m::interrupt::disable();
    let message = info
        .message()
        .as_str()
        .unwrap_or("(message with arguments)");
    match info.location() {
        Some(at) => defmt::error!(
            "panicked at {=str}:{=u32}: {=str}",
            at.file(),
            at.line(),
            message
        ),
        None => defmt::error!("panicked: {=str}", message),
    }
    stop()
}

/// Where `defmt::panic!` and a failed `defmt::assert!` end, after logging
/// their message.
#[defmt::panic_handler]
fn defmt_panic() -> ! {
    cortex_m::interrupt::disable();
    stop()
}

/// Stops for good: `udf` raises a HardFault, which the default handler
/// turns into a loop; the watchdog then resets the board unless a
/// debugger holds it (`probe-rs run` stops there and prints the log).
fn stop() -> ! {
    cortex_m::asm::udf()
}
