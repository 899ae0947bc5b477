//! Guard-form benchmark (QEMU mps2-an386, Cortex-M4): every guard of
//! every collection evaluated on every state vector twice, by the
//! executor's node-table walk (`Guards::holds`) and by a sum of products
//! over the bits the guard reads, with the instructions of each call.
//!
//! The data (`PLC_GUARD_BENCH`, written by `cargo xtask guard-bench`)
//! holds per collection the executor's pools (`GuardSpec`, `StateBit`,
//! `GuardNode`, as codegen lowers them), the cubes Espresso minimised and
//! the state vectors. The sum of products gathers the bits a guard reads
//! into one word, a shift and a mask per run of consecutive bits of one
//! component, then tests the cubes as `word & mask == value`, first hit
//! wins (a guard reading more than 32 bits packs two words); a guard whose OFF-set has the smaller cover holds when no cube
//! matches. Both calls are out of line and timed with SysTick under
//! `-icount shift=9` (12.8 ticks per instruction), less the cost of
//! reading the counter. One line per collection:
//!
//! `collection=NAME guards=G as_nodes=K vectors=V reachable=R evals=E bdd_median=…
//! bdd_max=… sop_median=… sop_max=… bdd_bytes=… sop_bytes=… nodes=N
//! bits=B gathers=A cubes=C disagreements=D`
//!
//! (`bytes`: the data of each form; the code of the two evaluators is
//! measured from the ELF; `as_nodes`: guards without a sum of products,
//! which the second form evaluates as node tables), then
//! `collections=K disagreements=D call=C`, where C is what a timed call
//! that reads no guard costs (part of every figure above). Exit code 0
//! only when the two forms agree on every evaluation.

#![no_std]
#![no_main]

use core::hint::black_box;
use core::mem::{size_of, size_of_val};
use cortex_m::peripheral::SYST;
use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln};
use executor::program::{GuardNode, GuardSpec, Guards, Span, StateBit};
use firmware::icount::{elapsed, exit, finish, instructions, start};
use panic_semihosting as _;

/// A run of state bits copied into the packed word:
/// `word |= ((states[component] >> shift) & mask) << dest`.
#[derive(Clone, Copy)]
struct Gather {
    /// `2^width − 1` for a run of `width` bits.
    mask: u32,
    component: u16,
    shift: u8,
    dest: u8,
}

/// A cube: the packed word matches when `word & mask == value`.
#[derive(Clone, Copy)]
struct Cube {
    mask: u32,
    value: u32,
}

/// One guard as a sum of products.
#[derive(Clone, Copy)]
struct SopGuard {
    /// Its runs (span of [`SopGuards::gathers`]).
    gathers: Span,
    /// Its cubes (span of [`SopGuards::cubes`]).
    cubes: Span,
    /// The cubes cover the OFF-set: the guard holds when none matches.
    complement: bool,
    /// The guard reads more than 32 bits: the packed word is two words
    /// (runs with `dest` ≥ 32 go to the second) and each cube two
    /// entries, the first word's then the second's.
    wide: bool,
    /// No sum of products (too large to build): the guard stays a node
    /// table, as a switch between the forms would keep it.
    nodes: bool,
}

/// The guards of a collection as sums of products, in the order of
/// [`Guards::events`].
struct SopGuards {
    guards: &'static [SopGuard],
    gathers: &'static [Gather],
    cubes: &'static [Cube],
}

/// A guard collection and the state vectors to evaluate it on.
struct Collection {
    name: &'static str,
    /// Entries per state vector.
    components: usize,
    /// Vectors from a walk of the closed loop (the rest are random).
    reachable: usize,
    guards: Guards<'static>,
    sop: SopGuards,
    /// The vectors, `components` entries each.
    states: &'static [u32],
}

include!(concat!(env!("OUT_DIR"), "/guard_bench.rs"));

/// Most evaluations timed per collection and form.
const MAX_EVALS: usize = 16_384;

/// The executor's walk, as the scan asks it.
#[inline(never)]
fn bdd_holds(guards: &Guards<'_>, guard: &GuardSpec, states: &[u32]) -> bool {
    guards.holds(guard, states)
}

/// The sum of products: gather, then the first matching cube.
#[inline(never)]
fn sop_holds(sop: &SopGuards, guard: &SopGuard, states: &[u32]) -> bool {
    let gathers = guard.gathers.of(sop.gathers);
    let cubes = guard.cubes.of(sop.cubes);
    let hit = if guard.wide {
        let mut word = [0u32; 2];
        for g in gathers {
            let Some(&state) = states.get(usize::from(g.component)) else {
                return false;
            };
            word[usize::from(g.dest >= 32)] |= ((state >> g.shift) & g.mask) << (g.dest & 31);
        }
        cubes
            .chunks_exact(2)
            .any(|c| word[0] & c[0].mask == c[0].value && word[1] & c[1].mask == c[1].value)
    } else {
        let mut word = 0u32;
        for g in gathers {
            let Some(&state) = states.get(usize::from(g.component)) else {
                return false;
            };
            word |= ((state >> g.shift) & g.mask) << g.dest;
        }
        cubes.iter().any(|c| word & c.mask == c.value)
    };
    hit != guard.complement
}

/// A call with the evaluators' arguments that evaluates nothing: what a
/// timed call costs before any guard is read.
#[inline(never)]
fn no_guard(guards: &Guards<'_>, guard: &GuardSpec, states: &[u32]) -> bool {
    guards.events.len() == usize::from(guard.root) && states.is_empty()
}

/// Median and largest of `samples` (sorted in place).
fn median_max(samples: &mut [u16]) -> (u16, u16) {
    samples.sort_unstable();
    let median = samples
        .get(samples.len().saturating_sub(1) / 2)
        .copied()
        .unwrap_or(0);
    (median, samples.last().copied().unwrap_or(0))
}

#[entry]
fn main() -> ! {
    let Some(mut core) = cortex_m::Peripherals::take() else {
        hprintln!("error: core peripherals taken twice");
        exit(debug::EXIT_FAILURE)
    };
    let overhead = start(&mut core.SYST);
    let cost = |before, after| {
        let i = instructions(elapsed(before, after).saturating_sub(overhead));
        u16::try_from(i).unwrap_or(u16::MAX)
    };

    let call = {
        let c = &COLLECTIONS[0];
        let spec = &GuardSpec::from_words(&c.guards.events[0]);
        let t0 = SYST::get_current();
        let _ = no_guard(black_box(&c.guards), black_box(spec), black_box(c.states));
        cost(t0, SYST::get_current())
    };

    let mut bdd = [0u16; MAX_EVALS];
    let mut sop = [0u16; MAX_EVALS];
    let mut total_disagreements = 0u32;
    for c in &COLLECTIONS {
        let vectors = c.states.len() / c.components.max(1);
        let mut evals = 0usize;
        let mut disagreements = 0u32;
        for v in 0..vectors {
            let states = &c.states[v * c.components..(v + 1) * c.components];
            for (spec, sg) in c.guards.events.iter().zip(c.sop.guards) {
                let spec = &GuardSpec::from_words(spec);
                let t0 = SYST::get_current();
                let a = bdd_holds(black_box(&c.guards), black_box(spec), black_box(states));
                let t1 = SYST::get_current();
                let b = if sg.nodes {
                    bdd_holds(black_box(&c.guards), black_box(spec), black_box(states))
                } else {
                    sop_holds(black_box(&c.sop), black_box(sg), black_box(states))
                };
                let t2 = SYST::get_current();
                if a != b {
                    if disagreements < 5 {
                        hprintln!(
                            "disagreement: {} vector {} event {}: nodes {}, cubes {}",
                            c.name,
                            v,
                            spec.event,
                            a,
                            b
                        );
                    }
                    disagreements += 1;
                }
                if evals < MAX_EVALS {
                    bdd[evals] = cost(t0, t1);
                    sop[evals] = cost(t1, t2);
                }
                evals += 1;
            }
        }
        let timed = evals.min(MAX_EVALS);
        let (bdd_median, bdd_max) = median_max(&mut bdd[..timed]);
        let (sop_median, sop_max) = median_max(&mut sop[..timed]);
        let g = &c.guards;
        let bdd_bytes = size_of_val(g.events) + size_of_val(g.bits) + size_of_val(g.nodes);
        let s = &c.sop;
        // Guards kept as node tables keep their nodes and state bits.
        let as_nodes = s.guards.iter().filter(|g| g.nodes).count();
        let kept_nodes: usize = (g.events.iter().zip(s.guards))
            .filter(|(_, sg)| sg.nodes)
            .map(|(spec, _)| {
                // As stored: a guard's record and its nodes' records.
                size_of_val(spec)
                    + usize::from(GuardSpec::from_words(spec).nodes.len) * size_of::<[u32; 2]>()
            })
            .sum();
        let kept_bits = if as_nodes > 0 { size_of_val(g.bits) } else { 0 };
        let sop_bytes = size_of_val(s.guards)
            + size_of_val(s.gathers)
            + size_of_val(s.cubes)
            + kept_nodes
            + kept_bits;
        hprintln!(
            "collection={} guards={} as_nodes={} vectors={} reachable={} evals={} bdd_median={} bdd_max={} sop_median={} sop_max={} bdd_bytes={} sop_bytes={} nodes={} bits={} gathers={} cubes={} disagreements={}",
            c.name,
            g.events.len(),
            as_nodes,
            vectors,
            c.reachable,
            evals,
            bdd_median,
            bdd_max,
            sop_median,
            sop_max,
            bdd_bytes,
            sop_bytes,
            g.nodes.len(),
            g.bits.len(),
            s.gathers.len(),
            s.cubes.len(),
            disagreements
        );
        total_disagreements += disagreements;
    }
    hprintln!(
        "collections={} disagreements={} call={}",
        COLLECTIONS.len(),
        total_disagreements,
        call
    );
    finish(total_disagreements == 0)
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    hprintln!("HardFault at pc={:#010x}", frame.pc());
    exit(debug::EXIT_FAILURE)
}
