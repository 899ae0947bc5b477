//! Random input sequences: a run ([`RunSpec`]) is a start time and steps
//! of time and input flips, turned into timed input samples.

use crate::projects::{NARROW, WIDE};
use proptest::collection::vec;
use proptest::prelude::*;
use std::fmt::Debug;

/// The time between two scans.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Dt {
    /// The nominal scan period.
    Period,
    /// The period plus a few ms of jitter (never negative time).
    Jitter(i32),
    /// A late scan or a pause.
    Jump(u32),
}

/// A random run: start time, initial raw inputs, then for each scan the
/// time step before it and the inputs it flips (bit `i`: input `i`).
#[derive(Debug, Clone)]
pub(crate) struct RunSpec {
    pub(crate) start_ms: u32,
    pub(crate) initial: u128,
    pub(crate) steps: Vec<(Dt, u128)>,
}

impl RunSpec {
    /// (time, raw image) of every scan for `inputs` inputs and `period`.
    pub(crate) fn samples(&self, inputs: usize, period: u32) -> Vec<(u32, Vec<bool>)> {
        let image = |mask: u128| (0..inputs).map(|i| mask & (1 << i) != 0).collect();
        let mut now = self.start_ms;
        let mut mask = self.initial;
        let mut out = vec![(now, image(mask))];
        for &(dt, flips) in &self.steps {
            let step = match dt {
                Dt::Period => period,
                Dt::Jitter(j) => period.saturating_add_signed(j),
                Dt::Jump(ms) => ms,
            };
            now = now.wrapping_add(step);
            mask ^= flips;
            out.push((now, image(mask)));
        }
        out
    }
}

/// Which inputs of a narrow project flip before a scan: nothing in about
/// half the scans, usually one input otherwise (so each input mostly keeps
/// its value).
pub(crate) fn flips() -> impl Strategy<Value = u8> {
    prop_oneof![
        8 => Just(0u8),
        6 => (0..*NARROW.inputs.end()).prop_map(|i| 1u8 << i),
        1 => any::<u8>(),
    ]
}

/// The same for a wide project: the single input is any of the 70 a wide
/// project can have (a bit past its inputs flips nothing), the rare burst
/// flips about half of them.
pub(crate) fn wide_flips() -> impl Strategy<Value = u128> {
    prop_oneof![
        8 => Just(0u128),
        6 => (0..*WIDE.inputs.end()).prop_map(|i| 1u128 << i),
        1 => any::<u128>(),
    ]
}

pub(crate) fn dt() -> impl Strategy<Value = Dt> {
    prop_oneof![
        16 => Just(Dt::Period),
        3 => (-3i32..=3).prop_map(Dt::Jitter),
        1 => (0u32..=400).prop_map(Dt::Jump),
    ]
}

/// A run for a narrow project.
pub(crate) fn run() -> impl Strategy<Value = RunSpec> {
    run_with(
        any::<u8>().prop_map(u128::from),
        flips().prop_map(u128::from),
    )
}

/// A run for a wide project.
pub(crate) fn wide_run() -> impl Strategy<Value = RunSpec> {
    run_with(any::<u128>(), wide_flips())
}

/// 20–200 scans from the raw image `initial`, flipping `flips` before
/// each; one run in four starts just before the u32 clock wraps.
pub(crate) fn run_with(
    initial: impl Strategy<Value = u128>,
    flips: impl Strategy<Value = u128>,
) -> impl Strategy<Value = RunSpec> {
    let start = prop_oneof![3 => 0u32..1_000, 1 => (u32::MAX - 3_000)..=u32::MAX];
    (start, initial, vec((dt(), flips), 19..200)).prop_map(|(start_ms, initial, steps)| RunSpec {
        start_ms,
        initial,
        steps,
    })
}
