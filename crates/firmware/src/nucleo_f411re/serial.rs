//! The field-update link (feature `field-update`): USART2 on PA2 (TX) and
//! PA3 (RX), which the Nucleo-F411RE wires to the ST-LINK's virtual COM
//! port, at 115,200 baud, 8 data bits, no parity, 1 stop bit (8N1).
//!
//! Received bytes go into a queue from the USART2 interrupt (one byte
//! lasts 87 µs on the line, a scan 10 ms: the one-byte data register
//! would overrun between scans); the scan loop takes them without
//! blocking. Answers are sent without blocking too: as many bytes as the
//! transmit register takes after each scan.

use core::cell::RefCell;
use cortex_m::peripheral::NVIC;
use critical_section::Mutex;
use field_update::frame::MAX_FRAME;
use stm32f4xx_hal::gpio::{gpioa, Input};
use stm32f4xx_hal::interrupt;
use stm32f4xx_hal::nb;
use stm32f4xx_hal::pac::{Interrupt, USART2};
use stm32f4xx_hal::prelude::{
    _embedded_hal_serial_nb_Read as NbRead, _embedded_hal_serial_nb_Write as NbWrite,
    _stm32f4xx_hal_serial_SerialExt,
};
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

/// Bytes received and not taken yet: a request's frame and more.
const QUEUE: usize = 2 * MAX_FRAME;

/// Received bytes, a ring.
struct Queue {
    bytes: [u8; QUEUE],
    head: usize,
    len: usize,
}

impl Queue {
    fn push(&mut self, byte: u8) {
        if self.len < QUEUE {
            self.bytes[(self.head + self.len) % QUEUE] = byte;
            self.len += 1;
        }
        // Full: the byte is dropped; its frame fails its CRC and the PC
        // sends the request again.
    }

    fn pop(&mut self) -> Option<u8> {
        if self.len == 0 {
            return None;
        }
        let byte = self.bytes[self.head];
        self.head = (self.head + 1) % QUEUE;
        self.len -= 1;
        Some(byte)
    }
}

/// The receiver and the bytes it received.
type Receiver = (Rx<USART2>, Queue);

/// The receiver and its queue, shared with the interrupt.
static RX: Mutex<RefCell<Option<Receiver>>> = Mutex::new(RefCell::new(None));

/// The link's transmit side and the answer being sent.
pub struct Port {
    tx: Tx<USART2>,
    out: [u8; MAX_FRAME],
    len: usize,
    sent: usize,
}

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
    critical_section::with(|cs| {
        RX.borrow_ref_mut(cs).replace((
            rx,
            Queue {
                bytes: [0; QUEUE],
                head: 0,
                len: 0,
            },
        ));
    });
    NVIC::unpend(Interrupt::USART2);
    // SAFETY: the handler only touches `RX`, behind a critical-section
    // mutex, so unmasking it cannot break a critical section in progress.
    #[allow(unsafe_code)]
    unsafe {
        NVIC::unmask(Interrupt::USART2)
    };
    Port {
        tx,
        out: [0; MAX_FRAME],
        len: 0,
        sent: 0,
    }
}

impl Port {
    /// The next received byte, if any (never blocks).
    pub fn read(&mut self) -> Option<u8> {
        critical_section::with(|cs| {
            RX.borrow_ref_mut(cs)
                .as_mut()
                .and_then(|(_, queue)| queue.pop())
        })
    }

    /// Queues `frame` to be sent (an answer not sent yet is dropped: the
    /// PC waits for each answer before its next request).
    pub fn send(&mut self, frame: &[u8]) {
        let len = frame.len().min(MAX_FRAME);
        self.out[..len].copy_from_slice(&frame[..len]);
        self.len = len;
        self.sent = 0;
    }

    /// Sends what the transmit register takes now (never blocks).
    pub fn flush(&mut self) {
        while self.sent < self.len {
            match NbWrite::write(&mut self.tx, self.out[self.sent]) {
                Ok(()) => self.sent += 1,
                Err(_) => break,
            }
        }
    }
}

#[interrupt]
fn USART2() {
    critical_section::with(|cs| {
        if let Some((rx, queue)) = RX.borrow_ref_mut(cs).as_mut() {
            // Reading the data register clears the interrupt; a read
            // error (overrun, noise, framing) is cleared by the read too,
            // and its byte lost: the frame's CRC refuses it.
            loop {
                match NbRead::read(rx) {
                    Ok(byte) => queue.push(byte),
                    Err(nb::Error::WouldBlock) => break,
                    Err(nb::Error::Other(_)) => {}
                }
            }
        }
    });
}
