//! The field-update link (feature `field-update`): USART2 on PA2 (TX) and
//! PA3 (RX), which the Nucleo-F411RE wires to the ST-LINK's virtual COM
//! port, at 115,200 baud, 8 data bits, no parity, 1 stop bit (8N1).
//!
//! Received bytes go into a queue from the USART2 interrupt
//! (`firmware::rx_queue`: the one-byte data register would overrun
//! between scans); the scan loop takes them without blocking. Answers are
//! sent without blocking too (`crate::link`).

use crate::link::{self, Received};
use core::cell::RefCell;
use critical_section::Mutex;
use stm32f4xx_hal::gpio::{gpioa, Input};
use stm32f4xx_hal::interrupt;
use stm32f4xx_hal::pac::{Interrupt, USART2};
use stm32f4xx_hal::prelude::_stm32f4xx_hal_serial_SerialExt;
use stm32f4xx_hal::rcc::Rcc;
use stm32f4xx_hal::serial::{self, Rx, RxListen, Tx};
use stm32f4xx_hal::time::Bps;

/// The link's baud rate.
pub const BAUD: u32 = 115_200;

/// APB1, USART2's clock (`clocks`: 50 MHz).
const APB1_HZ: u32 = super::clocks::SYSCLK_HZ / 2;
/// The APB1 clock the HAL computes divisors for: `clocks::init` sets the
/// clock tree by hand and leaves the HAL's `Clocks` at their reset
/// values (HSI, 16 MHz on every bus).
const HAL_APB1_HZ: u32 = 16_000_000;
/// The rate asked of the HAL so that its divisor, computed for
/// [`HAL_APB1_HZ`], is the one [`BAUD`] needs at [`APB1_HZ`].
const HAL_BAUD: u32 = BAUD / (APB1_HZ / 1_000_000) * (HAL_APB1_HZ / 1_000_000);
const _: () = assert!(
    HAL_BAUD as u64 * APB1_HZ as u64 == BAUD as u64 * HAL_APB1_HZ as u64,
    "the scaled baud rate gives the exact divisor"
);

/// USART2's receiver and the bytes it received, shared with the
/// interrupt.
static RX: Received<Rx<USART2>> = Mutex::new(RefCell::new(None));

/// The link's port: USART2's transmitter, [`RX`]'s bytes.
pub type Port = crate::link::Port<Tx<USART2>>;

/// Sets USART2 up on PA2/PA3 and starts receiving.
pub fn start(usart: USART2, pa2: gpioa::PA2<Input>, pa3: gpioa::PA3<Input>, rcc: &mut Rcc) -> Port {
    let config = serial::Config::default()
        .baudrate(Bps(HAL_BAUD))
        .wordlength_8()
        .parity_none();
    let Ok(serial) = usart.serial::<u8>((pa2, pa3), config, rcc) else {
        defmt::panic!("USART2: invalid configuration");
    };
    let (tx, mut rx) = serial.split();
    rx.listen();
    link::listen(&RX, rx, Interrupt::USART2);
    Port::new(tx, || link::take(&RX))
}

#[interrupt]
fn USART2() {
    link::on_interrupt(&RX);
}
