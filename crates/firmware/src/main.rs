//! The PLC on an STM32F411 board (Nucleo-F411RE): the project chosen at
//! build time (`PLC_PROJECT`, which needs a `[board]` section) runs its
//! scan cycle on the pins of its pin map. See `docs/board.md`.
//!
//! Every `scan_period_ms` (SysTick millisecond clock) the loop
//!
//! 1. waits (`wfi`) until the executor's schedule says a scan is due
//!    (`Controller::scan_due`: the grid of `executor::pacing`, periods a
//!    late scan missed skipped, an overrun reported when it starts more
//!    than `overrun_limit` periods late) and logs an overrun;
//! 2. samples the pins (active-low inverted) together with the change
//!    counts the EXTI interrupts latched, and reports a lost edge for each
//!    edge-latched input that changed more than once since the previous
//!    sample (`Controller::report_lost_edge`);
//! 3. runs the scan (`Controller::scan`) and writes its output image;
//! 4. logs executed and unexpected events by name and fault changes
//!    (defmt over RTT), feeds the watchdog, and every 10 s logs a status
//!    line.
//!
//! The firmware decides nothing itself: the executor runs the program,
//! including fault mode and its safe outputs. The program image is checked
//! when the controller starts (a mismatch starts it in fault mode,
//! `Corrupt`), which the log reports.
//!
//! On a host this binary is a stub, so `cargo clippy --workspace` and
//! `cargo test --workspace` need no cross toolchain.

#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(unsafe_code)]

#[cfg(target_os = "none")]
mod board;
#[cfg(target_os = "none")]
mod report;

/// Time between two status lines (ms).
#[cfg(target_os = "none")]
const STATUS_PERIOD_MS: u32 = 10_000;

#[cfg(target_os = "none")]
#[cortex_m_rt::entry]
fn main() -> ! {
    use board::{clocks, edges, pins, time, watchdog};
    use defmt_rtt as _;
    use executor::pacing::Pacer;
    use executor::Controller;
    use firmware::program::{self, CONFIG};
    use firmware::MCU;
    use panic_probe as _;
    use stm32f4xx_hal::gpio::GpioExt;
    use stm32f4xx_hal::pac;
    use stm32f4xx_hal::syscfg::SysCfgExt;

    const WATCHDOG_MS: u32 = MCU.watchdog.timeout_ms(CONFIG.scan_period_ms);
    const _: () = assert!(
        WATCHDOG_MS <= MCU.watchdog.max_timeout_ms,
        "scan_period_ms is too long for the independent watchdog (at most 8000 ms)"
    );

    let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        defmt::panic!("peripherals taken twice");
    };
    let reset = watchdog::last_reset(&dp.RCC);
    let (mut rcc, source) = clocks::init(dp.RCC);
    clocks::keep_debug_in_sleep(&dp.DBGMCU, &mut rcc);

    let mut syscfg = dp.SYSCFG.constrain(&mut rcc);
    let mut exti = dp.EXTI;
    let mut io = pins::Io::new(pins::Ports {
        a: dp.GPIOA.split(&mut rcc),
        b: dp.GPIOB.split(&mut rcc),
        c: dp.GPIOC.split(&mut rcc),
        d: dp.GPIOD.split(&mut rcc),
        e: dp.GPIOE.split(&mut rcc),
        h: dp.GPIOH.split(&mut rcc),
    });
    io.latch_edges(&mut syscfg, &mut exti);
    edges::start(exti);

    // Scan times for the status line, from the cycle counter.
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();
    time::start(cp.SYST, rcc.clocks.sysclk().raw());

    report::startup(reset, source, rcc.clocks.sysclk().raw(), WATCHDOG_MS);
    let mut controller = match Controller::new(&program::PROGRAM, program::Memory::new()) {
        Ok(c) => c,
        Err(e) => defmt::panic!("the generated memory does not fit the program: {}", e),
    };
    report::image_check(controller.fault());

    let mut watchdog = watchdog::start(dp.IWDG, &dp.DBGMCU, WATCHDOG_MS);
    let now = time::now_ms();
    let mut pacer = Pacer::for_config(&CONFIG, now);
    let mut status = Pacer::new(now.wrapping_add(STATUS_PERIOD_MS), STATUS_PERIOD_MS, 0);
    let mut stats = report::ScanTimes::default();
    let mut fault = controller.fault();

    loop {
        let start = loop {
            if let Some(start) = controller.scan_due(&mut pacer, time::now_ms()) {
                break start;
            }
            cortex_m::asm::wfi();
        };
        let began = cortex_m::peripheral::DWT::cycle_count();

        if start.overrun {
            report::overrun(controller.next_scan(), &start, pacer.period_ms());
        }
        // The background image test's share first, so that the path from
        // sampling the inputs to writing the outputs does not include it.
        controller.check_image_share();
        let (raw, changes) = edges::sample(&io);
        for (input, count) in changes.lost() {
            controller.report_lost_edge();
            report::lost_edge(controller.next_scan(), input, count);
        }

        controller.step_packed(start.time_ms, &raw);
        let record = controller.record();
        io.write(record.outputs);
        report::scan(&record, fault);
        fault = record.fault;

        stats.add(cortex_m::peripheral::DWT::cycle_count().wrapping_sub(began));
        watchdog.feed();
        if status.poll(time::now_ms()).is_some() {
            report::status(&controller, &mut stats);
        }
    }
}

/// On a host: the firmware only runs on the board.
#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "the board firmware runs on the STM32F411: cargo run -p firmware --release --target thumbv7em-none-eabihf (see docs/board.md)"
    );
    std::process::exit(2);
}
