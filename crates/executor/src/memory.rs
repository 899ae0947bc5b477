//! The controller's RAM: sizes in the types, nothing allocated behind the
//! user's back.
//!
//! [`StaticMemory`] holds fixed-size arrays whose lengths are const
//! generics (the code generator emits them from the project as the
//! `Memory` type); with the `alloc` feature, `HeapMemory` sizes itself
//! from a [`Config`] at run time for hosts.
//!
//! Memory is opaque outside this crate. [`Memory`] is sealed: only the
//! types here implement it, so every array has the size its constructor
//! gave it, and [`crate::Controller::new`] refuses memory whose sizes do
//! not match the program's configuration. Nothing outside the crate can
//! read or write the arrays; the controller's state is visible only
//! through [`crate::Controller`]'s accessors and its scan records.

use crate::program::{words, Config};

pub(crate) use sealed::Ram;

/// What only this crate may see. `pub` items in a private module: the
/// types can appear in the sealed trait's signatures, yet no one outside
/// can name them.
pub(crate) mod sealed {
    /// Mutable views of every per-controller array, for the scan cycle.
    /// Input images and event sets are bit sets in `u32` words (bit
    /// `i % 32` of word `i / 32`).
    pub struct Ram<'a> {
        /// The raw input image of this scan.
        pub(crate) raw: &'a mut [u32],
        /// Debounced input values, this scan (F\[k\]).
        pub(crate) filtered: &'a mut [u32],
        /// Debounced input values, previous scan (F\[k-1\]).
        pub(crate) previous: &'a mut [u32],
        /// Per debounced input (`Config::debounced`): consecutive scans its
        /// raw value has differed from its filtered value.
        pub(crate) debounce: &'a mut [u8],
        /// Per timer: running.
        pub(crate) timer_running: &'a mut [bool],
        /// Per timer: deadline (ms, wrapping).
        pub(crate) timer_deadline: &'a mut [u32],
        /// Levels of action-driven outputs.
        pub(crate) latched: &'a mut [bool],
        /// The output image written by the last scan.
        pub(crate) outputs: &'a mut [bool],
        /// The state of each supervisor.
        pub(crate) states: &'a mut [u32],
        /// Events that occurred (edge or expiry) in this scan.
        pub(crate) occurred: &'a mut [u32],
        /// Events executed in this scan.
        pub(crate) done: &'a mut [u32],
        /// Per supervisor, an event set: the events it does not block in
        /// its current state (its enabled events and every event outside
        /// its alphabet), supervisor `j` in words `j·EW..(j+1)·EW`.
        pub(crate) allowed: &'a mut [u32],
        /// The AND of every supervisor's `allowed`: the feasible events.
        pub(crate) feasible: &'a mut [u32],
        /// Events executed in this scan, in order (capacity: all events).
        pub(crate) executed: &'a mut [u16],
        /// Unexpected events of this scan, in order (capacity: all events).
        pub(crate) unexpected: &'a mut [u16],
    }

    /// The arrays behind a [`super::Memory`]; crate-private, so no one
    /// outside can implement `Memory` or reach the arrays.
    pub trait Storage {
        /// All arrays at once, mutably.
        fn ram(&mut self) -> Ram<'_>;
        /// The supervisor states.
        fn states(&self) -> &[u32];
        /// The last output image.
        fn outputs(&self) -> &[bool];
        /// The last scan's executed events (the controller knows how many
        /// are valid).
        fn executed(&self) -> &[u16];
        /// The last scan's unexpected events.
        fn unexpected(&self) -> &[u16];
        /// Per timer: running, and its deadline (ms, wrapping).
        fn timers(&self) -> (&[bool], &[u32]);
    }
}

/// Storage a [`crate::Controller`] can run in: [`StaticMemory`], or
/// `HeapMemory` with the `alloc` feature.
///
/// Sealed, so that memory always has the sizes it was built with; a type
/// outside this crate cannot implement it:
///
/// ```compile_fail,E0277
/// use executor::memory::Memory;
/// use executor::program::Config;
///
/// struct Mine;
/// impl Memory for Mine {
///     fn fits(&self, _: &Config<'_>) -> bool { true }
/// }
/// ```
///
/// and the arrays inside are out of reach (the controller alone reads and
/// writes them):
///
/// ```compile_fail,E0599
/// use executor::memory::StaticMemory;
///
/// let mut memory: StaticMemory<1, 0, 1, 0, 1, 2, 1, 1> = StaticMemory::new();
/// let _ = memory.ram();
/// ```
pub trait Memory: sealed::Storage {
    /// `true` when every array has exactly the size `config` needs.
    fn fits(&self, config: &Config<'_>) -> bool;
}

/// Fixed-size memory: `IW` input words (32 inputs per `u32`), `D`
/// debounced inputs, `O` outputs, `T` timers, `S` supervisors, `E` events,
/// `EW` event words (32 events per `u32`) and `SEW` = `S·EW` words of the
/// supervisors' event sets.
///
/// ```
/// use executor::memory::StaticMemory;
///
/// /// A project with 2 inputs (1 word, none debounced), 1 output, no
/// /// timer, 1 supervisor and 3 events (1 word), as `codegen gen`
/// /// declares its memory.
/// pub type Memory = StaticMemory<1, 0, 1, 0, 1, 3, 1, 1>;
///
/// // `new` is `const`, so the memory can be a `static` or built at compile time.
/// const FRESH: Memory = Memory::new();
/// # let _ = FRESH;
/// ```
#[derive(Debug, Clone)]
pub struct StaticMemory<
    const IW: usize,
    const D: usize,
    const O: usize,
    const T: usize,
    const S: usize,
    const E: usize,
    const EW: usize,
    const SEW: usize,
> {
    raw: [u32; IW],
    filtered: [u32; IW],
    previous: [u32; IW],
    debounce: [u8; D],
    timer_running: [bool; T],
    timer_deadline: [u32; T],
    latched: [bool; O],
    outputs: [bool; O],
    states: [u32; S],
    occurred: [u32; EW],
    done: [u32; EW],
    allowed: [u32; SEW],
    feasible: [u32; EW],
    executed: [u16; E],
    unexpected: [u16; E],
}

impl<
        const IW: usize,
        const D: usize,
        const O: usize,
        const T: usize,
        const S: usize,
        const E: usize,
        const EW: usize,
        const SEW: usize,
    > Default for StaticMemory<IW, D, O, T, S, E, EW, SEW>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<
        const IW: usize,
        const D: usize,
        const O: usize,
        const T: usize,
        const S: usize,
        const E: usize,
        const EW: usize,
        const SEW: usize,
    > StaticMemory<IW, D, O, T, S, E, EW, SEW>
{
    /// Zeroed memory (the controller initialises it).
    pub const fn new() -> Self {
        StaticMemory {
            raw: [0; IW],
            filtered: [0; IW],
            previous: [0; IW],
            debounce: [0; D],
            timer_running: [false; T],
            timer_deadline: [0; T],
            latched: [false; O],
            outputs: [false; O],
            states: [0; S],
            occurred: [0; EW],
            done: [0; EW],
            allowed: [0; SEW],
            feasible: [0; EW],
            executed: [0; E],
            unexpected: [0; E],
        }
    }
}

impl<
        const IW: usize,
        const D: usize,
        const O: usize,
        const T: usize,
        const S: usize,
        const E: usize,
        const EW: usize,
        const SEW: usize,
    > sealed::Storage for StaticMemory<IW, D, O, T, S, E, EW, SEW>
{
    fn ram(&mut self) -> Ram<'_> {
        Ram {
            raw: &mut self.raw,
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
            allowed: &mut self.allowed,
            feasible: &mut self.feasible,
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

    fn timers(&self) -> (&[bool], &[u32]) {
        (&self.timer_running, &self.timer_deadline)
    }
}

impl<
        const IW: usize,
        const D: usize,
        const O: usize,
        const T: usize,
        const S: usize,
        const E: usize,
        const EW: usize,
        const SEW: usize,
    > Memory for StaticMemory<IW, D, O, T, S, E, EW, SEW>
{
    fn fits(&self, config: &Config<'_>) -> bool {
        words(config.inputs.len()) == IW
            && config.debounced.len() == D
            && config.outputs.len() == O
            && config.timers.len() == T
            && config.supervisors.len() == S
            && config.events.len() == E
            && words(config.events.len()) == EW
            && config.supervisors.len() * EW == SEW
    }
}

#[cfg(feature = "alloc")]
pub use heap::HeapMemory;

#[cfg(feature = "alloc")]
mod heap {
    use super::{sealed, Memory, Ram};
    use crate::program::{words, Config};
    use alloc::vec;
    use alloc::vec::Vec;

    /// Memory sized at run time from a [`Config`] (hosts only).
    #[derive(Debug, Clone, Default)]
    pub struct HeapMemory {
        raw: Vec<u32>,
        filtered: Vec<u32>,
        previous: Vec<u32>,
        debounce: Vec<u8>,
        timer_running: Vec<bool>,
        timer_deadline: Vec<u32>,
        latched: Vec<bool>,
        outputs: Vec<bool>,
        states: Vec<u32>,
        occurred: Vec<u32>,
        done: Vec<u32>,
        allowed: Vec<u32>,
        feasible: Vec<u32>,
        executed: Vec<u16>,
        unexpected: Vec<u16>,
    }

    impl HeapMemory {
        /// Memory for `config`.
        pub fn for_config(config: &Config<'_>) -> Self {
            let iw = words(config.inputs.len());
            let (o, t) = (config.outputs.len(), config.timers.len());
            let (s, e) = (config.supervisors.len(), config.events.len());
            let ew = words(e);
            HeapMemory {
                raw: vec![0; iw],
                filtered: vec![0; iw],
                previous: vec![0; iw],
                debounce: vec![0; config.debounced.len()],
                timer_running: vec![false; t],
                timer_deadline: vec![0; t],
                latched: vec![false; o],
                outputs: vec![false; o],
                states: vec![0; s],
                occurred: vec![0; ew],
                done: vec![0; ew],
                allowed: vec![0; s * ew],
                feasible: vec![0; ew],
                executed: vec![0; e],
                unexpected: vec![0; e],
            }
        }
    }

    impl sealed::Storage for HeapMemory {
        fn ram(&mut self) -> Ram<'_> {
            Ram {
                raw: &mut self.raw,
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
                allowed: &mut self.allowed,
                feasible: &mut self.feasible,
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

        fn timers(&self) -> (&[bool], &[u32]) {
            (&self.timer_running, &self.timer_deadline)
        }
    }

    impl Memory for HeapMemory {
        fn fits(&self, config: &Config<'_>) -> bool {
            words(config.inputs.len()) == self.filtered.len()
                && config.debounced.len() == self.debounce.len()
                && config.outputs.len() == self.outputs.len()
                && config.timers.len() == self.timer_running.len()
                && config.supervisors.len() == self.states.len()
                && config.events.len() == self.executed.len()
                && words(config.events.len()) == self.occurred.len()
                && config.supervisors.len() * self.occurred.len() == self.allowed.len()
        }
    }
}
