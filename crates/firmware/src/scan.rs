//! The scan loop, the same on every board: generic over a [`Board`], which
//! gives embedded-hal 1.0 pins ([`Pins`]), a monotonic millisecond clock,
//! a free-running timer for scan durations, the watchdog and, optionally,
//! an edge latch (lost-edge counts, [`Board::sample`]). Logging is defmt
//! (`report`), whose transport (defmt-rtt) and time stamps the board
//! links.
//!
//! Every `scan_period_ms` the loop
//!
//! 1. waits ([`Board::wait`], `wfi`) until the executor's schedule says a
//!    scan is due (`Controller::scan_due`: the grid of `executor::pacing`,
//!    periods a late scan missed skipped, an overrun reported when it
//!    starts more than `overrun_limit` periods late) and logs an overrun;
//! 2. samples the pins (active-low inverted) together with the change
//!    counts the edge latch took, and reports a lost edge for each
//!    edge-latched input that changed more than once since the previous
//!    sample (`Controller::report_lost_edge`);
//! 3. runs the scan (`Controller::step_packed`) and writes its output
//!    image;
//! 4. logs executed and unexpected events by name and fault changes,
//!    feeds the watchdog, and every 10 s logs a status line.
//!
//! The loop decides nothing itself: the executor runs the program,
//! including fault mode and its safe outputs.

use crate::report;
use core::cell::Cell;
use critical_section::Mutex;
use embedded_hal::digital::{InputPin, OutputPin, PinState};
use executor::image::CrcEngine;
use executor::memory::Memory;
use executor::pacing::Pacer;
use executor::{Config, Controller, Program};
use firmware::edges::{ChangeCounts, LineMap};
use firmware::levels;
use firmware::program::board::{SignalPin, EDGE_LATCHED, INPUT_PINS, OUTPUT_PINS};
use firmware::program::{self, input, output, CONFIG, INPUT_WORDS};
use firmware::MCU;

/// Time between two status lines (ms).
const STATUS_PERIOD_MS: u32 = 10_000;

/// The watchdog timeout for the project's scan period (the board data's
/// `boards::Watchdog`).
pub const WATCHDOG_MS: u32 = MCU.watchdog.timeout_ms(CONFIG.scan_period_ms);
const _: () = assert!(
    WATCHDOG_MS <= MCU.watchdog.max_timeout_ms,
    "scan_period_ms is too long for the chip's watchdog (validation allows at most boards::Watchdog::max_scan_period_ms)"
);

/// Whether `part` starts with `chip`, ignoring case (`Chip::matches_part`,
/// at compile time).
const fn part_of(part: &str, chip: &str) -> bool {
    let (part, chip) = (part.as_bytes(), chip.as_bytes());
    if part.len() < chip.len() {
        return false;
    }
    let mut i = 0;
    while i < chip.len() {
        if !part[i].eq_ignore_ascii_case(&chip[i]) {
            return false;
        }
        i += 1;
    }
    true
}

const _: () = assert!(
    part_of(program::board::CHIP, MCU.name),
    "the project's [board] chip is not the chip of the board feature this firmware is built with (`nucleo-f411re`: STM32F411…, `pico`: RP2040)"
);

/// Changes per input since the last sample (edge latch).
pub type Changes = ChangeCounts<{ input::COUNT }>;

/// The edge line of each edge-latched input (`MCU.exti_line`: its pin
/// number; an EXTI line on the STM32F411, a GPIO on the RP2040).
const fn latched_lines() -> [Option<u8>; input::COUNT] {
    let mut lines = [None; input::COUNT];
    let mut i = 0;
    while i < input::COUNT {
        if let (Some(pin), true) = (INPUT_PINS[i], EDGE_LATCHED[i]) {
            lines[i] = Some(MCU.exti_line(pin.pin));
        }
        i += 1;
    }
    lines
}

/// Which input each edge line counts for, for a board's edge latch (fails
/// to build when two latched inputs share a line).
pub const LINES: LineMap = LineMap::new(&latched_lines());

/// Change counts, written by a board's edge interrupts, taken by its
/// `Board::sample` in the critical section that reads the pins.
pub static CHANGES: Mutex<Cell<Changes>> = Mutex::new(Cell::new(ChangeCounts::new()));

/// Why the chip started.
#[derive(Debug, Clone, Copy, PartialEq, Eq, defmt::Format)]
pub enum ResetCause {
    /// The watchdog expired: the scan loop stopped.
    Watchdog,
    /// The window watchdog (STM32; not used by this firmware).
    #[cfg_attr(feature = "pico", allow(dead_code))]
    WindowWatchdog,
    /// Software reset (a probe's `reset`, or a panic under probe-rs).
    Software,
    /// Low-power management reset (STM32).
    #[cfg_attr(feature = "pico", allow(dead_code))]
    LowPower,
    /// Power-on or brown-out.
    PowerOn,
    /// The reset pin (the Nucleo's black button B2, the Pico's RUN pin).
    Pin,
}

/// What a board tells about itself at start-up.
#[derive(Debug, Clone, Copy)]
pub struct Startup {
    /// Why the chip started.
    pub reset: ResetCause,
    /// The core clock (Hz).
    pub sysclk_hz: u32,
    /// Where the core clock comes from, in a word (`Hse`, `Hsi`, `Xosc`).
    pub clock_source: &'static str,
}

/// The configured pins: one slot per input and per output, indexed like
/// the executor's input and output images; `None` where the pin map has
/// no pin. Any embedded-hal 1.0 pin types; a board type-erases its HAL's
/// pins to one input and one output type.
pub struct Pins<I, O> {
    /// The pin of each input.
    pub inputs: [Option<I>; input::COUNT],
    /// The pin of each output.
    pub outputs: [Option<O>; output::COUNT],
}

impl<I: InputPin, O: OutputPin> Default for Pins<I, O> {
    fn default() -> Self {
        Pins {
            inputs: [const { None }; input::COUNT],
            outputs: [const { None }; output::COUNT],
        }
    }
}

/// The level an output pin shows before the first scan: its signal 0.
pub fn idle_state(spec: &SignalPin) -> PinState {
    PinState::from(levels::pin_high(false, spec.active_low))
}

impl<I: InputPin, O: OutputPin> Pins<I, O> {
    /// The raw input image, packed as the controller takes it (input `i`
    /// at bit `i % 32` of word `i / 32`): each wired input's signal
    /// (active-low pins inverted), 0 for inputs without a pin (and for a
    /// pin whose read fails, which no supported HAL's does).
    pub fn read(&mut self) -> [u32; INPUT_WORDS] {
        let mut raw = [0u32; INPUT_WORDS];
        for (i, (pin, spec)) in self.inputs.iter_mut().zip(&INPUT_PINS).enumerate() {
            if let (Some(pin), Some(spec)) = (pin, spec) {
                let on = levels::signal(pin.is_high().unwrap_or(false), spec.active_low);
                raw[i / 32] |= u32::from(on) << (i % 32);
            }
        }
        raw
    }

    /// Drives every wired output to the level of its signal in `image`.
    pub fn write(&mut self, image: &[bool]) {
        for ((pin, spec), &value) in self.outputs.iter_mut().zip(&OUTPUT_PINS).zip(image) {
            if let (Some(pin), Some(spec)) = (pin, spec) {
                let high = levels::pin_high(value, spec.active_low);
                // Infallible on every supported HAL; a failed write shows
                // on the pin, not in the program.
                let _ = pin.set_state(PinState::from(high));
            }
        }
    }
}

/// What a board gives the scan loop. A board module (`nucleo_f411re`,
/// `pico`) sets its chip up, configures the pins of the generated pin map
/// (`program::board`) and implements this; everything else is [`run`]'s.
pub trait Board {
    /// Its input pins, type-erased.
    type Input: InputPin;
    /// Its output pins (push-pull), type-erased.
    type Output: OutputPin;
    /// Ticks of [`Board::timer`] per microsecond.
    const TIMER_TICKS_PER_US: u32;

    /// The configured pins.
    fn pins(&mut self) -> &mut Pins<Self::Input, Self::Output>;

    /// The monotonic millisecond clock (wrapping `u32`; the executor
    /// handles the wrap).
    fn now_ms(&self) -> u32;

    /// A free-running counter for scan durations (wrapping), in
    /// [`Board::TIMER_TICKS_PER_US`] ticks per microsecond.
    fn timer(&self) -> u32;

    /// Starts the watchdog with `timeout_ms` (at most the board data's
    /// `max_timeout_ms`), paused while a debugger halts the core.
    fn start_watchdog(&mut self, timeout_ms: u32);

    /// Feeds the watchdog: called once per completed scan.
    fn feed_watchdog(&mut self);

    /// The raw input image and the changes of each edge-latched input
    /// since the previous sample, taken together (the edge-latch hook). A
    /// board without an edge latch reports no changes: lost edges then go
    /// undetected.
    fn sample(&mut self) -> ([u32; INPUT_WORDS], Changes) {
        (self.pins().read(), Changes::new())
    }

    /// Sleeps until an interrupt (the millisecond tick at the latest).
    fn wait(&mut self) {
        cortex_m::asm::wfi();
    }
}

/// What runs between two scans besides the scan itself: the field-update
/// link (feature `field-update`), or nothing (`()`, the built-in
/// program's loop, which it leaves as lean as before).
pub trait Link<B> {
    /// What ends the scan loop: the program to switch to.
    type Switch;

    /// After a scan's outputs are written and the watchdog fed: `Some`
    /// when the next scan is to run another program.
    fn after_scan(&mut self, board: &mut B) -> Option<Self::Switch>;
}

/// No link: the loop never ends.
impl<B> Link<B> for () {
    type Switch = core::convert::Infallible;

    #[inline(always)]
    fn after_scan(&mut self, _board: &mut B) -> Option<core::convert::Infallible> {
        None
    }
}

/// The built-in program's controller, its image CRC computed by `crc`;
/// panics (at start-up) when the generated memory does not fit it.
#[inline(always)]
pub fn built_in<C: CrcEngine>(crc: C) -> Controller<impl Program + 'static, program::Memory, C> {
    match Controller::new_proven_with_crc(&program::PROGRAM, program::Memory::new(), crc) {
        Ok(c) => c,
        Err(e) => defmt::panic!("the generated memory does not fit the program: {}", e),
    }
}

/// Runs the project's scan cycle on `board` forever (the built-in
/// program, its image CRC computed by `crc`: the chip's CRC unit where it
/// has one; with feature `field-update` the board runs
/// `crate::field::run` instead).
#[cfg_attr(feature = "field-update", allow(dead_code))]
pub fn run<B: Board, C: CrcEngine>(mut board: B, startup: Startup, crc: C) -> ! {
    report::startup(&startup, WATCHDOG_MS);
    let mut controller = built_in(crc);
    report::image_check(controller.fault(), program::PROGRAM.recorded_crc());
    board.start_watchdog(WATCHDOG_MS);
    match scan_loop(
        &mut board,
        &mut controller,
        &CONFIG,
        &report::BuiltIn,
        &mut (),
    ) {}
}

/// The scan cycle of `controller` (whose configuration is `config`, whose
/// names for the log are `names`) on `board`, the watchdog running, until
/// `link` asks for another program. Inlined: each caller has its own
/// program and memory types, and the built-in program's loop stays one
/// function as before.
#[inline(always)]
pub fn scan_loop<B: Board, P: Program, M: Memory, C: CrcEngine, N: report::Names, L: Link<B>>(
    board: &mut B,
    controller: &mut Controller<P, M, C>,
    config: &Config<'_>,
    names: &N,
    link: &mut L,
) -> L::Switch {
    let now = board.now_ms();
    let mut pacer = Pacer::for_config(config, now);
    let mut status = Pacer::new(now.wrapping_add(STATUS_PERIOD_MS), STATUS_PERIOD_MS, 0);
    let mut stats = report::ScanTimes::default();
    let mut fault = controller.fault();

    loop {
        let start = loop {
            if let Some(start) = controller.scan_due(&mut pacer, board.now_ms()) {
                break start;
            }
            board.wait();
        };
        let began = board.timer();

        if start.overrun {
            report::overrun(controller.next_scan(), &start, pacer.period_ms());
        }
        // The background image test's share first, so that the path from
        // sampling the inputs to writing the outputs does not include it.
        controller.check_image_share();
        let (raw, changes) = board.sample();
        for (input, count) in changes.lost() {
            controller.report_lost_edge();
            report::lost_edge(names, controller.next_scan(), input, count);
        }

        controller.step_packed(start.time_ms, &raw);
        let record = controller.record();
        board.pins().write(record.outputs);
        report::scan(names, &record, fault);
        fault = record.fault;

        stats.add(board.timer().wrapping_sub(began));
        board.feed_watchdog();
        if let Some(switch) = link.after_scan(board) {
            return switch;
        }
        if status.poll(board.now_ms()).is_some() {
            report::status(controller, &mut stats, B::TIMER_TICKS_PER_US);
        }
    }
}
