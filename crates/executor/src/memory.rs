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
    /// The lengths of its arrays (its parameters but `SEW`).
    const LENGTHS: Lengths = Lengths {
        input_words: IW,
        debounced: D,
        outputs: O,
        timers: T,
        supervisors: S,
        events: E,
        event_words: EW,
    };

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
        Lengths::of(config) == Self::LENGTHS && S * EW == SEW
    }
}

/// Memory with room for any program up to the sizes of its parameters
/// (those of [`StaticMemory`]), sized for one configuration at run time:
/// the memory of a program loaded in the field ([`crate::parse::load`]),
/// whose sizes the firmware does not know when it is built.
///
/// ```
/// use executor::memory::BoundedMemory;
///
/// /// Room for up to 64 inputs (2 words), 8 debounced, 16 outputs,
/// /// 8 timers, 4 supervisors and 64 events (2 words, 8 for the sets).
/// type Room = BoundedMemory<2, 8, 16, 8, 4, 64, 2, 8>;
/// let mut memory = Room::new();
/// // `memory.size_for(&loaded.config())` before `Controller::new`:
/// // `false` when the loaded program needs more room.
/// # let _ = &mut memory;
/// ```
#[derive(Debug, Clone)]
pub struct BoundedMemory<
    const IW: usize,
    const D: usize,
    const O: usize,
    const T: usize,
    const S: usize,
    const E: usize,
    const EW: usize,
    const SEW: usize,
> {
    arrays: StaticMemory<IW, D, O, T, S, E, EW, SEW>,
    len: Lengths,
}

/// The lengths of a memory's arrays that a configuration asks for: the
/// one place that works them out, for every kind of memory (the allowed
/// sets take `supervisors × event_words` words).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Lengths {
    input_words: usize,
    debounced: usize,
    outputs: usize,
    timers: usize,
    supervisors: usize,
    events: usize,
    event_words: usize,
}

impl Lengths {
    const ZERO: Lengths = Lengths {
        input_words: 0,
        debounced: 0,
        outputs: 0,
        timers: 0,
        supervisors: 0,
        events: 0,
        event_words: 0,
    };

    /// What `config` needs.
    fn of(config: &Config<'_>) -> Lengths {
        Lengths {
            input_words: words(config.inputs.len()),
            debounced: config.debounced.len(),
            outputs: config.outputs.len(),
            timers: config.timers.len(),
            supervisors: config.supervisors.len(),
            events: config.events.len(),
            event_words: words(config.events.len()),
        }
    }

    /// Words of the allowed sets: one set of `event_words` per supervisor.
    const fn allowed_words(&self) -> usize {
        self.supervisors * self.event_words
    }

    /// `true` when every length is at most `room`'s, and the allowed sets
    /// at most `allowed_words`.
    fn within(&self, room: &Lengths, allowed_words: usize) -> bool {
        self.input_words <= room.input_words
            && self.debounced <= room.debounced
            && self.outputs <= room.outputs
            && self.timers <= room.timers
            && self.supervisors <= room.supervisors
            && self.events <= room.events
            && self.event_words <= room.event_words
            && self.allowed_words() <= allowed_words
    }
}

/// The first `len` items of `array`, all of it when `len` is larger
/// (never: [`BoundedMemory::size_for`] keeps every length in its array).
fn first<T>(array: &mut [T], len: usize) -> &mut [T] {
    let len = len.min(array.len());
    &mut array[..len]
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
    > Default for BoundedMemory<IW, D, O, T, S, E, EW, SEW>
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
    > BoundedMemory<IW, D, O, T, S, E, EW, SEW>
{
    /// Zeroed memory sized for nothing yet (call [`Self::size_for`]).
    pub const fn new() -> Self {
        BoundedMemory {
            arrays: StaticMemory::new(),
            len: Lengths::ZERO,
        }
    }

    /// `true` when every array has room for what `config` needs.
    pub fn has_room(config: &Config<'_>) -> bool {
        Self::holds(&Lengths::of(config))
    }

    /// Sizes the memory for `config` and zeroes it; `false`, and the
    /// memory unchanged, when one of its arrays is too small.
    pub fn size_for(&mut self, config: &Config<'_>) -> bool {
        let len = Lengths::of(config);
        let room = Self::holds(&len);
        if room {
            self.arrays = StaticMemory::new();
            self.len = len;
        }
        room
    }

    fn holds(len: &Lengths) -> bool {
        len.within(&StaticMemory::<IW, D, O, T, S, E, EW, SEW>::LENGTHS, SEW)
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
    > sealed::Storage for BoundedMemory<IW, D, O, T, S, E, EW, SEW>
{
    fn ram(&mut self) -> Ram<'_> {
        let len = self.len;
        let a = &mut self.arrays;
        let (iw, ew) = (len.input_words, len.event_words);
        Ram {
            raw: first(&mut a.raw, iw),
            filtered: first(&mut a.filtered, iw),
            previous: first(&mut a.previous, iw),
            debounce: first(&mut a.debounce, len.debounced),
            timer_running: first(&mut a.timer_running, len.timers),
            timer_deadline: first(&mut a.timer_deadline, len.timers),
            latched: first(&mut a.latched, len.outputs),
            outputs: first(&mut a.outputs, len.outputs),
            states: first(&mut a.states, len.supervisors),
            occurred: first(&mut a.occurred, ew),
            done: first(&mut a.done, ew),
            allowed: first(&mut a.allowed, len.allowed_words()),
            feasible: first(&mut a.feasible, ew),
            executed: first(&mut a.executed, len.events),
            unexpected: first(&mut a.unexpected, len.events),
        }
    }

    fn states(&self) -> &[u32] {
        &self.arrays.states[..self.len.supervisors.min(S)]
    }

    fn outputs(&self) -> &[bool] {
        &self.arrays.outputs[..self.len.outputs.min(O)]
    }

    fn executed(&self) -> &[u16] {
        &self.arrays.executed[..self.len.events.min(E)]
    }

    fn unexpected(&self) -> &[u16] {
        &self.arrays.unexpected[..self.len.events.min(E)]
    }

    fn timers(&self) -> (&[bool], &[u32]) {
        let t = self.len.timers.min(T);
        (
            &self.arrays.timer_running[..t],
            &self.arrays.timer_deadline[..t],
        )
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
    > Memory for BoundedMemory<IW, D, O, T, S, E, EW, SEW>
{
    fn fits(&self, config: &Config<'_>) -> bool {
        self.len == Lengths::of(config)
    }
}

#[cfg(feature = "alloc")]
pub use heap::HeapMemory;

#[cfg(feature = "alloc")]
mod heap {
    use super::{sealed, Lengths, Memory, Ram};
    use crate::program::Config;
    use alloc::vec;
    use alloc::vec::Vec;

    /// Memory sized at run time from a [`Config`] (hosts only).
    #[derive(Debug, Clone, Default)]
    pub struct HeapMemory {
        len: Lengths,
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
            let len = Lengths::of(config);
            let (iw, ew) = (len.input_words, len.event_words);
            HeapMemory {
                len,
                raw: vec![0; iw],
                filtered: vec![0; iw],
                previous: vec![0; iw],
                debounce: vec![0; len.debounced],
                timer_running: vec![false; len.timers],
                timer_deadline: vec![0; len.timers],
                latched: vec![false; len.outputs],
                outputs: vec![false; len.outputs],
                states: vec![0; len.supervisors],
                occurred: vec![0; ew],
                done: vec![0; ew],
                allowed: vec![0; len.allowed_words()],
                feasible: vec![0; ew],
                executed: vec![0; len.events],
                unexpected: vec![0; len.events],
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
            self.len == Lengths::of(config)
        }
    }
}
