//! Edge latching: EXTI interrupts on both edges of every edge-latched
//! input (`program::board::EDGE_LATCHED`) count its changes; a sample
//! reads the pins and takes the counts in one critical section, so each
//! change belongs to exactly one interval between samples.
//!
//! A change that is still pending in the EXTI (its interrupt not yet
//! taken) when a sample starts is counted first, so only a change in the
//! few bus cycles between that and the pin read can land in the next
//! interval. While interrupts are masked (a critical section, a defmt log
//! frame), two edges of one line merge into one pending bit: a lost edge
//! can then go unreported, never be reported falsely.

use super::pins::Io;
use crate::scan::{Changes, CHANGES, LINES};
use cortex_m::peripheral::NVIC;
use critical_section::CriticalSection;
use firmware::program::INPUT_WORDS;
use stm32f4xx_hal::interrupt;
use stm32f4xx_hal::pac::{Interrupt, EXTI};

/// The NVIC interrupts of the lines in use.
fn interrupts(mask: u32) -> impl Iterator<Item = Interrupt> {
    [
        (1 << 0, Interrupt::EXTI0),
        (1 << 1, Interrupt::EXTI1),
        (1 << 2, Interrupt::EXTI2),
        (1 << 3, Interrupt::EXTI3),
        (1 << 4, Interrupt::EXTI4),
        (0x03e0, Interrupt::EXTI9_5),
        (0xfc00, Interrupt::EXTI15_10),
    ]
    .into_iter()
    .filter(move |&(lines, _)| mask & lines != 0)
    .map(|(_, irq)| irq)
}

/// Hands the EXTI (configured by [`super::pins::latch_edges`]) to the
/// handlers and unmasks the interrupts of the lines in use. The handlers
/// reach its pending register through its address ([`pending_register`]):
/// the peripheral is consumed here, so nothing else can touch it, and no
/// `RefCell` (whose borrow panics link `core::fmt`'s padding code, 1.3 KB)
/// guards it.
pub fn start(_exti: EXTI) {
    for irq in interrupts(LINES.mask()) {
        NVIC::unpend(irq);
        // SAFETY: the handlers below only touch state behind
        // `critical_section::Mutex`es, so unmasking them cannot break a
        // critical section in progress.
        #[allow(unsafe_code)]
        unsafe {
            NVIC::unmask(irq)
        };
    }
}

/// The EXTI's registers, which [`start`] consumed.
fn pending_register() -> &'static stm32f4xx_hal::pac::exti::RegisterBlock {
    // SAFETY: `start` consumed the only `EXTI` value; from then on only
    // `service`, inside a critical section, reads and clears (write 1)
    // its pending bits of the latched lines.
    #[allow(unsafe_code)]
    unsafe {
        &*EXTI::ptr()
    }
}

/// Clears the pending changes of the lines in `mask` and counts them for
/// their inputs.
fn service(cs: CriticalSection<'_>, mask: u32) {
    let exti = pending_register();
    let pending = exti.pr().read().bits() & mask & 0xffff;
    if pending == 0 {
        return;
    }
    exti.pr().write(|w| {
        for line in 0..16 {
            if pending & (1 << line) != 0 {
                w.pr(line).clear();
            }
        }
        w
    });
    let cell = CHANGES.borrow(cs);
    let mut counts = cell.get();
    for i in LINES.inputs_of(pending) {
        counts.record(i);
    }
    cell.set(counts);
}

/// The raw input image and the changes since the previous sample, taken
/// together.
pub fn sample(io: &mut Io) -> ([u32; INPUT_WORDS], Changes) {
    critical_section::with(|cs| {
        service(cs, LINES.mask());
        let raw = io.read();
        (raw, CHANGES.borrow(cs).take())
    })
}

fn on_lines(mask: u32) {
    critical_section::with(|cs| service(cs, mask));
}

#[interrupt]
fn EXTI0() {
    on_lines(1 << 0);
}

#[interrupt]
fn EXTI1() {
    on_lines(1 << 1);
}

#[interrupt]
fn EXTI2() {
    on_lines(1 << 2);
}

#[interrupt]
fn EXTI3() {
    on_lines(1 << 3);
}

#[interrupt]
fn EXTI4() {
    on_lines(1 << 4);
}

#[interrupt]
fn EXTI9_5() {
    on_lines(0x03e0);
}

#[interrupt]
fn EXTI15_10() {
    on_lines(0xfc00);
}
