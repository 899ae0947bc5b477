//! Programs compiled into the firmware: a generated file states its data
//! by implementing [`ProgramData`] (constants, and for supervisors written
//! as code their transition function), and [`Compiled`] runs it as a
//! [`Program`]. No generated file repeats an `impl Program`.
//!
//! Everything is a constant or a function of the data type, so the
//! compiler sees through it as it would through hand-written code: a
//! [`Compiled`] is zero-sized, and its methods are the table decoder (or
//! the generated functions) with the tables inlined.
//!
//! ```
//! use executor::compiled::{Compiled, ProgramData};
//! use executor::program::{Config, Guards, Index, Program, Span, UnexpectedPolicy};
//!
//! /// A program of one supervisor written as code: `0 --e--> 1`.
//! struct Toggle;
//! impl ProgramData for Toggle {
//!     const CONFIG: Config<'static> = Config {
//!         name: "toggle",
//!         scan_period_ms: 10,
//!         max_commands_per_scan: 0,
//!         unexpected: UnexpectedPolicy::Fault,
//!         reset: None,
//!         overrun_limit: 0,
//!         overrun_fault: false,
//!         lost_edge_fault: false,
//!         rom_test_bytes_per_scan: 64,
//!         inputs: &[],
//!         debounced: &[],
//!         debounce_mask: Span::EMPTY,
//!         outputs: &[],
//!         timers: &[],
//!         events: &[],
//!         supervisors: &[],
//!         input_masks: &[],
//!         event_lists: &[],
//!         event_masks: &[],
//!         commands: Span::EMPTY,
//!         requested: Span::EMPTY,
//!         actions: &[],
//!         memberships: &[],
//!         state_map: &[],
//!         guards: Guards::NONE,
//!         allowed_index: &[],
//!     };
//!     const IMAGE_CRC: u32 = 0;
//!     fn next_state(_supervisor: Index, state: u32, local: Index) -> Option<u32> {
//!         ((state, local) == (0, 0)).then_some(1)
//!     }
//! }
//! static PROGRAM: Compiled<Toggle> = Compiled::new();
//! assert_eq!(PROGRAM.next_state(0, 0, 0), Some(1));
//! assert_eq!(PROGRAM.enabled(0, 0, 0, 2), 0b01, "e defined in 0, local 1 not");
//! assert!(PROGRAM.table(0).is_none(), "code, not a table in the image");
//! assert_eq!(PROGRAM.recorded_crc(), 0);
//! ```

use crate::program::{enabled_by_steps, Config, Index, Layouts, Program, SupervisorTable};
use core::marker::PhantomData;

/// What a generated program file defines.
pub trait ProgramData {
    /// The configuration.
    const CONFIG: Config<'static>;
    /// The image CRC recorded at generation ([`crate::image`]).
    const IMAGE_CRC: u32;
    /// One table per supervisor, part of the image (the table backend);
    /// empty when the supervisors are code.
    const TABLES: &'static [SupervisorTable<'static>] = &[];
    /// The layouts of [`ProgramData::TABLES`], worked out at build time:
    /// the decoders of the others are left out of the program's code.
    const LAYOUTS: Layouts = Layouts::of(Self::TABLES);

    /// δ of supervisor `supervisor` ([`Program::next_state`]). The default
    /// reads [`ProgramData::TABLES`]; a program whose supervisors are code
    /// (the logic and `match` backends) calls its functions here.
    #[inline]
    fn next_state(supervisor: Index, state: u32, local: Index) -> Option<u32> {
        Self::TABLES
            .get(usize::from(supervisor))?
            .next_state_in(Self::LAYOUTS, state, local)
    }

    /// Which of the local events `from..from + len` (`len ≤ 32`) are
    /// defined in `state` ([`Program::enabled`]). The default reads a
    /// table's row of defined-bits, or asks [`ProgramData::next_state`] for
    /// each event; the logic backend evaluates its φ functions once.
    #[inline]
    fn enabled(supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        match Self::TABLES.get(usize::from(supervisor)) {
            Some(t) => t.enabled_in(Self::LAYOUTS, state, from, len),
            None => enabled_by_steps(len, |k| {
                Self::next_state(supervisor, state, from.wrapping_add(k)).is_some()
            }),
        }
    }
}

/// The [`Program`] of the data `D`: `static PROGRAM: Compiled<D> =
/// Compiled::new();` in a generated file.
pub struct Compiled<D>(PhantomData<D>);

impl<D> Compiled<D> {
    /// The program (zero-sized).
    pub const fn new() -> Compiled<D> {
        Compiled(PhantomData)
    }
}

impl<D> Default for Compiled<D> {
    fn default() -> Compiled<D> {
        Compiled::new()
    }
}

impl<D: ProgramData> Program for Compiled<D> {
    fn config(&self) -> Config<'_> {
        D::CONFIG
    }

    #[inline]
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        D::next_state(supervisor, state, local)
    }

    /// [`ProgramData::enabled`].
    #[inline]
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        D::enabled(supervisor, state, from, len)
    }

    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>> {
        D::TABLES.get(usize::from(supervisor)).copied()
    }

    #[inline]
    fn layouts(&self) -> Layouts {
        D::LAYOUTS
    }

    fn recorded_crc(&self) -> u32 {
        D::IMAGE_CRC
    }
}
