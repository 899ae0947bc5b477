//! The controller's RAM: sizes in the types, nothing allocated behind the
//! user's back.
//!
//! [`StaticMemory`] holds fixed-size arrays whose lengths are const
//! generics (the code generator emits them from the project); with the
//! `alloc` feature, [`HeapMemory`] sizes itself from a [`Config`] at run
//! time for hosts. Both hand the controller a [`Ram`] of slices.

use crate::program::Config;

/// Mutable views of every per-controller array.
pub struct Ram<'a> {
    /// Debounced input values, this scan (F\[k\]).
    pub filtered: &'a mut [bool],
    /// Debounced input values, previous scan (F\[k-1\]).
    pub previous: &'a mut [bool],
    /// Consecutive scans each raw input has differed from its filtered value.
    pub debounce: &'a mut [u8],
    /// Per timer: running.
    pub timer_running: &'a mut [bool],
    /// Per timer: deadline (ms, wrapping).
    pub timer_deadline: &'a mut [u32],
    /// Levels of action-driven outputs.
    pub latched: &'a mut [bool],
    /// The output image written by the last scan.
    pub outputs: &'a mut [bool],
    /// The state of each supervisor.
    pub states: &'a mut [u32],
    /// Per event: occurred (edge or expiry) in this scan.
    pub occurred: &'a mut [bool],
    /// Per event: executed in this scan.
    pub done: &'a mut [bool],
    /// Events executed in this scan, in order (capacity: all events).
    pub executed: &'a mut [u16],
    /// Unexpected events of this scan, in order (capacity: all events).
    pub unexpected: &'a mut [u16],
}

/// Storage a [`crate::Controller`] can run in.
pub trait Memory {
    /// All arrays at once, mutably.
    fn ram(&mut self) -> Ram<'_>;

    /// The supervisor states.
    fn states(&self) -> &[u32];

    /// The last output image.
    fn outputs(&self) -> &[bool];

    /// The last scan's executed events (first `executed_len` are valid).
    fn executed(&self) -> &[u16];

    /// The last scan's unexpected events.
    fn unexpected(&self) -> &[u16];

    /// `true` when every array is large enough for `config`.
    fn fits(&self, config: &Config<'_>) -> bool;
}

/// Fixed-size memory: `I` inputs, `O` outputs, `T` timers, `S` supervisors,
/// `E` events.
///
/// ```
/// use executor::memory::{Memory, StaticMemory};
/// let mem: StaticMemory<2, 1, 0, 1, 3> = StaticMemory::new();
/// assert_eq!(mem.states().len(), 1);
/// ```
#[derive(Debug, Clone)]
pub struct StaticMemory<
    const I: usize,
    const O: usize,
    const T: usize,
    const S: usize,
    const E: usize,
> {
    filtered: [bool; I],
    previous: [bool; I],
    debounce: [u8; I],
    timer_running: [bool; T],
    timer_deadline: [u32; T],
    latched: [bool; O],
    outputs: [bool; O],
    states: [u32; S],
    occurred: [bool; E],
    done: [bool; E],
    executed: [u16; E],
    unexpected: [u16; E],
}

impl<const I: usize, const O: usize, const T: usize, const S: usize, const E: usize> Default
    for StaticMemory<I, O, T, S, E>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<const I: usize, const O: usize, const T: usize, const S: usize, const E: usize>
    StaticMemory<I, O, T, S, E>
{
    /// Zeroed memory (the controller initialises it).
    pub const fn new() -> Self {
        StaticMemory {
            filtered: [false; I],
            previous: [false; I],
            debounce: [0; I],
            timer_running: [false; T],
            timer_deadline: [0; T],
            latched: [false; O],
            outputs: [false; O],
            states: [0; S],
            occurred: [false; E],
            done: [false; E],
            executed: [0; E],
            unexpected: [0; E],
        }
    }
}

impl<const I: usize, const O: usize, const T: usize, const S: usize, const E: usize> Memory
    for StaticMemory<I, O, T, S, E>
{
    fn ram(&mut self) -> Ram<'_> {
        Ram {
            filtered: &mut self.filtered,
            previous: &mut self.previous,
            debounce: &mut self.debounce,
            timer_running: &mut self.timer_running,
            timer_deadline: &mut self.timer_deadline,
            latched: &mut self.latched,
            outputs: &mut self.outputs,
            states: &mut self.states,
            occurred: &mut self.occurred,
            done: &mut self.done,
            executed: &mut self.executed,
            unexpected: &mut self.unexpected,
        }
    }

    fn states(&self) -> &[u32] {
        &self.states
    }

    fn outputs(&self) -> &[bool] {
        &self.outputs
    }

    fn executed(&self) -> &[u16] {
        &self.executed
    }

    fn unexpected(&self) -> &[u16] {
        &self.unexpected
    }

    fn fits(&self, config: &Config<'_>) -> bool {
        config.inputs.len() == I
            && config.outputs.len() == O
            && config.timers.len() == T
            && config.supervisors.len() == S
            && config.events.len() == E
    }
}

#[cfg(feature = "alloc")]
pub use heap::HeapMemory;

#[cfg(feature = "alloc")]
mod heap {
    use super::{Memory, Ram};
    use crate::program::Config;
    use alloc::vec;
    use alloc::vec::Vec;

    /// Memory sized at run time from a [`Config`] (hosts only).
    #[derive(Debug, Clone, Default)]
    pub struct HeapMemory {
        filtered: Vec<bool>,
        previous: Vec<bool>,
        debounce: Vec<u8>,
        timer_running: Vec<bool>,
        timer_deadline: Vec<u32>,
        latched: Vec<bool>,
        outputs: Vec<bool>,
        states: Vec<u32>,
        occurred: Vec<bool>,
        done: Vec<bool>,
        executed: Vec<u16>,
        unexpected: Vec<u16>,
    }

    impl HeapMemory {
        /// Memory for `config`.
        pub fn for_config(config: &Config<'_>) -> Self {
            let (i, o, t) = (
                config.inputs.len(),
                config.outputs.len(),
                config.timers.len(),
            );
            let (s, e) = (config.supervisors.len(), config.events.len());
            HeapMemory {
                filtered: vec![false; i],
                previous: vec![false; i],
                debounce: vec![0; i],
                timer_running: vec![false; t],
                timer_deadline: vec![0; t],
                latched: vec![false; o],
                outputs: vec![false; o],
                states: vec![0; s],
                occurred: vec![false; e],
                done: vec![false; e],
                executed: vec![0; e],
                unexpected: vec![0; e],
            }
        }
    }

    impl Memory for HeapMemory {
        fn ram(&mut self) -> Ram<'_> {
            Ram {
                filtered: &mut self.filtered,
                previous: &mut self.previous,
                debounce: &mut self.debounce,
                timer_running: &mut self.timer_running,
                timer_deadline: &mut self.timer_deadline,
                latched: &mut self.latched,
                outputs: &mut self.outputs,
                states: &mut self.states,
                occurred: &mut self.occurred,
                done: &mut self.done,
                executed: &mut self.executed,
                unexpected: &mut self.unexpected,
            }
        }

        fn states(&self) -> &[u32] {
            &self.states
        }

        fn outputs(&self) -> &[bool] {
            &self.outputs
        }

        fn executed(&self) -> &[u16] {
            &self.executed
        }

        fn unexpected(&self) -> &[u16] {
            &self.unexpected
        }

        fn fits(&self, config: &Config<'_>) -> bool {
            config.inputs.len() == self.filtered.len()
                && config.outputs.len() == self.outputs.len()
                && config.timers.len() == self.timer_running.len()
                && config.supervisors.len() == self.states.len()
                && config.events.len() == self.occurred.len()
        }
    }
}
