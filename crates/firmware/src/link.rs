//! The field-update link's port on every board (feature `field-update`):
//! the bytes the board's UART interrupt queued ([`firmware::rx_queue`]),
//! taken without blocking, and the answer being sent, as many bytes after
//! each scan as the UART's transmitter takes. Both HALs implement
//! embedded-hal-nb's `serial::Read` and `serial::Write`, so a board's
//! `serial.rs` only sets its UART up and names its interrupt.

use core::cell::RefCell;
use cortex_m::interrupt::InterruptNumber;
use cortex_m::peripheral::NVIC;
use critical_section::Mutex;
use embedded_hal_nb::nb;
use embedded_hal_nb::serial::{Read, Write};
use field_update::frame::MAX_FRAME;
use firmware::rx_queue::RxQueue;

/// A board's receiver and the bytes it received, shared between its
/// UART interrupt and the scan loop.
pub type Received<R> = Mutex<RefCell<Option<(R, RxQueue)>>>;

/// Hands `rx` (receive interrupt enabled) to `shared` and unmasks its
/// interrupt `irq`, whose handler calls [`on_interrupt`] with `shared`.
pub fn listen<R, I: InterruptNumber>(shared: &Received<R>, rx: R, irq: I) {
    critical_section::with(|cs| {
        shared.borrow_ref_mut(cs).replace((rx, RxQueue::new()));
    });
    NVIC::unpend(irq);
    // SAFETY: the handler only touches `shared`, behind a
    // critical-section mutex, so unmasking it cannot break a critical
    // section in progress.
    #[allow(unsafe_code)]
    unsafe {
        NVIC::unmask(irq)
    };
}

/// The UART interrupt's work: every byte the receiver holds goes to the
/// queue. Reading empties the receive register (or FIFO), which clears
/// the interrupt; a byte read with an error (overrun, noise, break,
/// parity, framing) is dropped: its frame then fails its CRC.
pub fn on_interrupt<R: Read<u8>>(shared: &Received<R>) {
    critical_section::with(|cs| {
        if let Some((rx, queue)) = shared.borrow_ref_mut(cs).as_mut() {
            loop {
                match rx.read() {
                    Ok(byte) => queue.push(byte),
                    Err(nb::Error::WouldBlock) => break,
                    Err(nb::Error::Other(_)) => {}
                }
            }
        }
    });
}

/// The next byte `shared`'s queue holds, if any (never blocks).
pub fn take<R>(shared: &Received<R>) -> Option<u8> {
    critical_section::with(|cs| {
        shared
            .borrow_ref_mut(cs)
            .as_mut()
            .and_then(|(_, queue)| queue.pop())
    })
}

/// The link's transmit side, the answer being sent, and where the
/// received bytes are.
pub struct Port<T> {
    tx: T,
    /// Takes the next received byte (the board's [`take`]).
    received: fn() -> Option<u8>,
    out: [u8; MAX_FRAME],
    len: usize,
    sent: usize,
}

impl<T: Write<u8>> Port<T> {
    /// The port over `tx`, reading what `received` hands over.
    pub fn new(tx: T, received: fn() -> Option<u8>) -> Port<T> {
        Port {
            tx,
            received,
            out: [0; MAX_FRAME],
            len: 0,
            sent: 0,
        }
    }

    /// The next received byte, if any (never blocks).
    pub fn read(&mut self) -> Option<u8> {
        (self.received)()
    }

    /// Queues `frame` to be sent (an answer not sent yet is dropped: the
    /// PC waits for each answer before its next request).
    pub fn send(&mut self, frame: &[u8]) {
        let len = frame.len().min(MAX_FRAME);
        self.out[..len].copy_from_slice(&frame[..len]);
        self.len = len;
        self.sent = 0;
    }

    /// Sends what the transmitter takes now (never blocks).
    pub fn flush(&mut self) {
        while self.sent < self.len {
            match self.tx.write(self.out[self.sent]) {
                Ok(()) => self.sent += 1,
                Err(_) => break,
            }
        }
    }
}
