//! Edge latching: IO_BANK0 latches a rising and a falling edge of every
//! GPIO (INTR registers, one bit each); the bank's interrupt
//! (IO_IRQ_BANK0) counts them for every edge-latched input
//! (`program::board::EDGE_LATCHED`), and a sample reads the pins and takes
//! the counts in one critical section, so each change belongs to exactly
//! one interval between samples.
//!
//! As on the STM32's EXTI, edges still latched (their interrupt not yet
//! taken) when a sample starts are counted first; a rising and a falling
//! edge latched together count two changes, and more edges of one kind
//! while interrupts are masked merge into one: a lost edge can go
//! unreported, never be reported falsely.

use super::pins::Io;
use crate::scan::{Changes, CHANGES, LINES};
use cortex_m::peripheral::NVIC;
use critical_section::CriticalSection;
use firmware::program::board::EDGE_LATCHED;
use firmware::program::INPUT_WORDS;
use rp2040_hal::gpio::Interrupt as Edge;
use rp2040_hal::pac::{self, interrupt, Interrupt};

/// The edge bits (EDGE_LOW, EDGE_HIGH: bits 2 and 3 of each GPIO's
/// nibble) of the latched GPIOs in INTR0–INTR3 (8 GPIOs each).
const EDGE_BITS: [u32; 4] = {
    let mask = LINES.mask();
    let mut bits = [0; 4];
    let mut gpio = 0;
    while gpio < 30 {
        if mask & (1 << gpio) != 0 {
            bits[gpio / 8] |= 0b1100 << (4 * (gpio % 8));
        }
        gpio += 1;
    }
    bits
};

/// Enables both edge interrupts of every edge-latched input and unmasks
/// the bank's interrupt.
pub fn start(io: &Io) {
    for (pin, latched) in io.inputs.iter().zip(EDGE_LATCHED) {
        if let (Some(pin), true) = (pin, latched) {
            pin.set_interrupt_enabled(Edge::EdgeLow, true);
            pin.set_interrupt_enabled(Edge::EdgeHigh, true);
        }
    }
    if LINES.mask() != 0 {
        critical_section::with(service);
        NVIC::unpend(Interrupt::IO_IRQ_BANK0);
        // SAFETY: the handler below only touches state behind
        // `critical_section::Mutex`es and the INTR bits of the latched
        // GPIOs, which nothing else uses.
        #[allow(unsafe_code)]
        unsafe {
            NVIC::unmask(Interrupt::IO_IRQ_BANK0)
        };
    }
}

/// Clears the latched edges of the latched GPIOs and counts them for
/// their inputs.
fn service(cs: CriticalSection<'_>) {
    // SAFETY: a shared reference to IO_BANK0's registers, used only for
    // the INTR edge bits of the latched GPIOs (read, then write 1 to
    // clear), inside a critical section; the pins own their other bits.
    #[allow(unsafe_code)]
    let bank = unsafe { &*pac::IO_BANK0::ptr() };
    let cell = CHANGES.borrow(cs);
    let mut counts = cell.get();
    for (reg, &mask) in EDGE_BITS.iter().enumerate() {
        if mask == 0 {
            continue;
        }
        let edges = bank.intr(reg).read().bits() & mask;
        if edges == 0 {
            continue;
        }
        // SAFETY: INTR bits are write-1-to-clear; only latched edges are
        // written.
        #[allow(unsafe_code)]
        bank.intr(reg).write(|w| unsafe { w.bits(edges) });
        for k in 0..8 {
            let n = ((edges >> (4 * k + 2)) & 0b11).count_ones();
            if let Some(i) = LINES.input(reg * 8 + k) {
                for _ in 0..n {
                    counts.record(i);
                }
            }
        }
    }
    cell.set(counts);
}

/// The raw input image and the changes since the previous sample, taken
/// together.
pub fn sample(io: &mut Io) -> ([u32; INPUT_WORDS], Changes) {
    critical_section::with(|cs| {
        service(cs);
        let raw = io.read();
        (raw, CHANGES.borrow(cs).take())
    })
}

#[interrupt]
fn IO_IRQ_BANK0() {
    critical_section::with(service);
}
