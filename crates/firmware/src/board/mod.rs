//! Board support for the STM32F411 (Nucleo-F411RE): everything between
//! the pins and the executor's input and output images. No control logic:
//! the scan loop in `main.rs` hands every sample to the executor.
//!
//! - [`clocks`]: 100 MHz from the ST-LINK's 8 MHz clock or the HSI;
//! - [`pins`]: GPIO from the generated pin map (`program::board`);
//! - [`edges`]: EXTI change counting for lost-edge detection;
//! - [`time`]: the SysTick millisecond clock;
//! - [`watchdog`]: the IWDG and the reset cause.

pub mod clocks;
pub mod edges;
pub mod pins;
pub mod time;
pub mod watchdog;
