//! The field-update link (feature `field-update`): UART0 on GP0 (TX,
//! header pin 1) and GP1 (RX, pin 2), at 115,200 baud, 8 data bits, no
//! parity, 1 stop bit (8N1). A 3.3 V USB-serial adapter connects it to
//! the PC (its RX to GP0, its TX to GP1, ground to a GND pin).
//!
//! Received bytes go into a queue from the UART0 interrupt
//! (`firmware::rx_queue`: the 32-byte receive FIFO would overrun between
//! scans); the scan loop takes them without blocking. Answers are sent
//! without blocking too (`crate::link`).

use crate::link::{self, Received};
use core::cell::RefCell;
use critical_section::Mutex;
use fugit::HertzU32;
use rp2040_hal::gpio::bank0::{Gpio0, Gpio1};
use rp2040_hal::gpio::{FunctionUart, Pin, PullNone, PullUp};
use rp2040_hal::pac::{self, interrupt, Interrupt, UART0};
use rp2040_hal::uart::{DataBits, Reader, StopBits, UartConfig, UartPeripheral, Writer};

/// The link's baud rate.
pub const BAUD: u32 = 115_200;

/// The link's pins: GP0 transmits, GP1 receives (pulled up: the line
/// idles high when no adapter is connected).
pub type LinkPins = (
    Pin<Gpio0, FunctionUart, PullNone>,
    Pin<Gpio1, FunctionUart, PullUp>,
);

/// UART0's receiver and the bytes it received, shared with the
/// interrupt.
static RX: Received<Reader<UART0, LinkPins>> = Mutex::new(RefCell::new(None));

/// The link's port: UART0's transmitter, [`RX`]'s bytes.
pub type Port = crate::link::Port<Writer<UART0, LinkPins>>;

/// Sets UART0 up on GP0/GP1 (clocked by the peripheral clock,
/// `peripheral_hz`) and starts receiving.
pub fn start(uart: UART0, pins: LinkPins, resets: &mut pac::RESETS, peripheral_hz: u32) -> Port {
    let config = UartConfig::new(
        HertzU32::from_raw(BAUD),
        DataBits::Eight,
        None,
        StopBits::One,
    );
    let Ok(uart) =
        UartPeripheral::new(uart, pins, resets).enable(config, HertzU32::from_raw(peripheral_hz))
    else {
        defmt::panic!("UART0: invalid configuration");
    };
    let (mut rx, tx) = uart.split();
    rx.enable_rx_interrupt();
    link::listen(&RX, rx, Interrupt::UART0_IRQ);
    Port::new(tx, || link::take(&RX))
}

#[interrupt]
fn UART0_IRQ() {
    link::on_interrupt(&RX);
}
