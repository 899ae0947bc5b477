//! Logic backend: a supervisor as a clocked Moore synchronous state
//! machine (CMSSM, after Leduc and Wonham), that is, as a handful of
//! minimised Boolean equations instead of a transition table.
//!
//! # Construction
//!
//! Each of the `n` states `x` gets a distinct `l`-bit code `λ(x)`
//! ([`Encoding`]; projects use the binary one, code = state index, so
//! codes and traces coincide with the [table backend](super::table)).
//! Each of the `m` local events gets an input wire `I_i`; during one scan
//! at most one wire is high, and all wires low means "nothing happened".
//!
//! The supervisor then becomes two families of Boolean functions:
//!
//! - **next state** `ω_b(Q, I)`, one per code bit `b`, over the `l` code
//!   bits and the `m` wires. At a state's code with all wires low, `ω_b`
//!   reproduces bit `b` of that code (no event, no move). With wire `i`
//!   high it gives bit `b` of the code of `δ(x, e_i)`; when `δ(x, e_i)` is
//!   undefined the code is again kept, so the machine simply ignores an
//!   event its state has no transition for.
//! - **defined** `φ_i(Q)`, one per local event, over the code bits alone:
//!   1 exactly in the states where `δ(x, e_i)` exists. For a controllable
//!   event this is its enable signal; for an uncontrollable one it says the
//!   event is expected, which lets the executor notice an event the
//!   supervisor does not allow before applying `ω`.
//!
//! Two kinds of points are left free (don't-care): codes that no state
//! uses, whatever the inputs, and inputs with two or more wires high.
//! Espresso uses this freedom to merge product terms.
//!
//! How the specification reaches Espresso. The care points of `ω` are
//! the `n·(m + 1)` pairs of a state with a single event or none. Espresso
//! gets an explicit OFF-set (exactly the care points where the function is
//! 0), an ON-set in compact form, and the unused codes as don't-care; the
//! multi-wire inputs are simply left out of the OFF-set, which lets the
//! expansion step grow terms over them without listing the `m(m-1)/2`
//! pairs of wires as don't-care cubes (which made Espresso's tautology
//! checks dominate its run time). The compact ON-set relies on that
//! freedom: a state whose bit `b` is 1 needs a single term "this code, and
//! none of the wires of the events that clear bit `b`", and a state whose
//! bit is 0 one term "this code and wire `i`" per event `i` that sets it.
//! Both are exact on every care point. Giving the OFF-set also spares
//! Espresso the complement of the ON-set, its most expensive set-up step.
//! `φ` is handled the same way over the code bits alone.
//!
//! By default every function is minimised on its own
//! ([`Minimisation::PerFunction`], fewest literals per equation);
//! [`Minimisation::Shared`] minimises each family as one multi-output PLA
//! instead (fewest distinct product terms). Beyond [`MAX_ROWS`] care
//! points or [`MAX_INPUTS`] inputs (`l + m`) synthesis refuses
//! ([`LogicError::TooLarge`]) and the table backend is the right choice.
//!
//! # Effort bound
//!
//! Espresso's run time is not bounded by the size of its input alone: its
//! expansion step compares every ON-set term with every OFF-set row, and
//! the later steps grow with the cover. Before any minimisation starts,
//! synthesis therefore counts the **effort**, the pairs of ON- and
//! OFF-set rows summed over the Espresso runs it is about to make
//! ([`effort`]), and refuses a supervisor above a limit
//! ([`DEFAULT_MAX_EFFORT`], raised per supervisor by the project key
//! `max_logic_effort`). The count depends on the automaton alone, never on
//! a clock, so the same project is accepted or refused on every machine.
//! Measured on random supervisors (2 to 100 events, 100 to 3,000 states,
//! a 2-core x86-64 CI machine), one unit cost 1 to 150 ns of Espresso time,
//! about 35 ns for supervisors of few events and many states, where the
//! cost per unit is highest; the default admits about 10 to 40 s.
//!
//! # Safety net
//!
//! The minimised covers are never trusted blindly: [`LogicSupervisor::synthesize`]
//! finishes with [`LogicSupervisor::verify`], which replays every state
//! against every local event and against the empty input and compares the
//! evaluated equations with the automaton. Any difference is a
//! [`LogicError::Mismatch`].
//!
//! # Output
//!
//! [`LogicSupervisor::next_state`] evaluates the covers directly (same
//! contract as the executor's `Program::next_state`);
//! [`crate::emit::logic`] writes the equations down as plain Rust
//! functions that need neither `std`, allocation nor `unsafe`, and in
//! mathematical notation.

use des::automaton::{Automaton, EventId, StateId};
use des::ops::Progress;
use std::collections::HashSet;
use std::fmt;

/// Whether this build can minimise: the logic backend needs Espresso
/// (cargo feature `espresso`), everything else works without it.
pub const AVAILABLE: bool = cfg!(feature = "espresso");

/// What a build without Espresso says when asked for the logic backend.
pub const UNAVAILABLE: &str =
    "the logic backend minimises its equations with Espresso, which this \
     build leaves out: rebuild with the `espresso` feature (`cargo run -p codegen-cli --features \
     espresso -- …`; host-sim and the firmware: `--features logic`). Espresso's Rust bindings \
     need libclang when they are built (Debian/Ubuntu: `apt-get install libclang-dev`); the \
     table backend needs nothing of the kind";

/// Largest specification of `ω` (care points = states × (local events +
/// 1)) synthesis accepts.
pub const MAX_ROWS: usize = 200_000;

/// Largest number of PLA inputs (code bits + local events) synthesis
/// accepts.
pub const MAX_INPUTS: usize = 128;

/// Default limit of the minimisation [`effort`] (pairs of ON- and OFF-set
/// rows over all Espresso runs) of one supervisor; see the module docs.
pub const DEFAULT_MAX_EFFORT: u64 = 250_000_000;

/// The effort limit of a supervisor whose project states `requested`
/// (`max_logic_effort`), or [`DEFAULT_MAX_EFFORT`].
pub fn effort_limit(requested: Option<u64>) -> u64 {
    requested.unwrap_or(DEFAULT_MAX_EFFORT)
}

/// How [`LogicSupervisor::synthesize_reporting`] minimises and how much
/// work it may take on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Settings {
    /// Per function or per family.
    pub minimisation: Minimisation,
    /// The largest [`effort`] accepted.
    pub max_effort: u64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            minimisation: Minimisation::default(),
            max_effort: DEFAULT_MAX_EFFORT,
        }
    }
}

/// How the functions of one family (`ω` or `φ`) are minimised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Minimisation {
    /// Each function on its own: fewest terms and literals per function,
    /// which is what a ladder rung or the emitted Rust evaluates.
    #[default]
    PerFunction,
    /// One multi-output PLA per family: fewest distinct product terms
    /// (terms may be shared between functions, at the price of longer
    /// individual functions).
    Shared,
}

/// Why the logic backend could not produce (trustworthy) equations.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LogicError {
    /// This build has no minimiser ([`AVAILABLE`] is false).
    #[error("{UNAVAILABLE}")]
    Unavailable,
    /// The automaton has no states.
    #[error("supervisor `{0}` has no states")]
    Empty(String),
    /// The state encoding is unusable (not injective, a code out of range,
    /// a width outside 1..=32, or the wrong number of codes).
    #[error("invalid state encoding: {0}")]
    Encoding(String),
    /// The PLA would be too large to minimise in reasonable time.
    #[error("too large for the logic backend: {0}")]
    TooLarge(String),
    /// Minimisation would take more than the effort limit (see the module
    /// docs); checked before it starts.
    #[error(
        "minimising its logic would take an effort of {effort} \
         (pairs of ON- and OFF-set rows Espresso compares), above the limit of {limit}; \
         use the table backend, or raise `max_logic_effort` for this supervisor in the project \
         (about 35 ns per unit on a 2-core x86-64 CI machine, up to 150 ns)"
    )]
    Effort {
        /// The supervisor (the automaton's name).
        supervisor: String,
        /// Its effort.
        effort: u64,
        /// The limit it exceeds.
        limit: u64,
    },
    /// Espresso reported an error.
    #[error("Espresso failed: {0}")]
    Minimiser(String),
    /// The minimised equations disagree with the automaton (a minimiser
    /// bug or a corrupted cover; never expected).
    #[error(
        "minimised logic disagrees with the automaton in state {state} on {}: expected {expected}, got {got}",
        input_label(.event)
    )]
    Mismatch {
        /// The state (automaton index).
        state: u32,
        /// The local event, `None` for the empty input.
        event: Option<u16>,
        /// What the automaton says.
        expected: Step,
        /// What the equations say.
        got: Step,
    },
}

fn input_label(event: &Option<u16>) -> String {
    match event {
        Some(i) => format!("local event {i}"),
        None => "the empty input".to_owned(),
    }
}

/// One step of the CMSSM as checked by [`LogicSupervisor::verify`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Step {
    /// The code after the step (`Ω`).
    pub next: u32,
    /// Whether the event is defined (`φ`); `None` for the empty input.
    pub defined: Option<bool>,
}

impl fmt::Display for Step {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "code {:#b}", self.next)?;
        match self.defined {
            Some(true) => write!(f, " (defined)"),
            Some(false) => write!(f, " (undefined)"),
            None => Ok(()),
        }
    }
}

/// An injective state encoding `λ: state → l-bit code`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Encoding {
    bits: u8,
    codes: Vec<u32>,
}

impl Encoding {
    /// The binary encoding of `n` states: state `i` gets code `i`, on the
    /// fewest bits that hold `n - 1` (at least 1). This is the encoding
    /// projects use; codes equal the table backend's state indices.
    ///
    /// # Panics
    ///
    /// If `n > 2^32` (codes are `u32`).
    pub fn binary(n: usize) -> Encoding {
        assert!(n as u64 <= 1 << 32, "at most 2^32 states");
        Encoding {
            bits: super::table::bits_for(n.saturating_sub(1) as u64),
            codes: (0..n as u64).map(|c| c as u32).collect(),
        }
    }

    /// An explicit encoding: `codes[i]` is the code of state `i`, on
    /// `bits` bits. Fails unless `1 ≤ bits ≤ 32`, every code fits in
    /// `bits` bits and no two states share a code.
    pub fn from_codes(bits: u8, codes: Vec<u32>) -> Result<Encoding, LogicError> {
        if !(1..=32).contains(&bits) {
            return Err(LogicError::Encoding(format!(
                "{bits} bits per code; need 1 to 32"
            )));
        }
        let limit = 1u64 << bits;
        let mut seen = HashSet::with_capacity(codes.len());
        for (state, &code) in codes.iter().enumerate() {
            if u64::from(code) >= limit {
                return Err(LogicError::Encoding(format!(
                    "state {state} has code {code:#b}, wider than {bits} bits"
                )));
            }
            if !seen.insert(code) {
                return Err(LogicError::Encoding(format!(
                    "code {code:#b} is used twice (again by state {state})"
                )));
            }
        }
        Ok(Encoding { bits, codes })
    }

    /// Bits per code, `l`.
    pub fn bits(&self) -> u8 {
        self.bits
    }

    /// Number of states encoded.
    pub fn len(&self) -> usize {
        self.codes.len()
    }

    /// `true` when no state is encoded.
    pub fn is_empty(&self) -> bool {
        self.codes.is_empty()
    }

    /// `λ(s)`.
    ///
    /// # Panics
    ///
    /// If `s` is not encoded.
    pub fn code(&self, s: StateId) -> u32 {
        self.codes[s.index()]
    }

    /// All codes, indexed by state.
    pub fn codes(&self) -> &[u32] {
        &self.codes
    }

    /// The state with code `code`, if any (a linear search).
    pub fn state_of(&self, code: u32) -> Option<StateId> {
        self.codes
            .iter()
            .position(|&c| c == code)
            .map(|s| StateId(s as u32))
    }

    /// The codes no state uses, as `(mask, value)` cubes: a code `c` is
    /// unused iff `c & mask == value` for one of them. At most
    /// `len · bits` cubes.
    fn unused_cubes(&self) -> Vec<(u32, u32)> {
        fn split(codes: &[u32], bit: i32, mask: u32, value: u32, out: &mut Vec<(u32, u32)>) {
            if codes.is_empty() {
                out.push((mask, value));
                return;
            }
            if bit < 0 {
                return;
            }
            let b = 1u32 << bit;
            // Sorted codes sharing the bits above `bit`: zeros come first.
            let ones = codes.partition_point(|&c| c & b == 0);
            split(&codes[..ones], bit - 1, mask | b, value, out);
            split(&codes[ones..], bit - 1, mask | b, value | b, out);
        }
        let mut sorted = self.codes.clone();
        sorted.sort_unstable();
        let mut out = Vec::new();
        split(&sorted, i32::from(self.bits) - 1, 0, 0, &mut out);
        out
    }
}

/// A product term over the code bits and the event wires.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Cube {
    /// Code bits that appear as literals.
    pub state_mask: u32,
    /// Their required values (bits outside `state_mask` are 0).
    pub state_value: u32,
    /// Event wires that must be 1.
    pub events_on: u128,
    /// Event wires that must be 0.
    pub events_off: u128,
}

impl Cube {
    /// Whether the term is 1 at `code` with the input `input` (`None`: all
    /// wires low; `Some(i)`: only wire `i` high; an `i` of 128 or more has
    /// no wire and counts as `None`).
    #[inline]
    pub fn matches(&self, code: u32, input: Option<u16>) -> bool {
        let wires = input.map_or(0, |i| 1u128.checked_shl(u32::from(i)).unwrap_or(0));
        code & self.state_mask == self.state_value
            && self.events_on & !wires == 0
            && self.events_off & wires == 0
    }

    /// Number of literals.
    pub fn literals(&self) -> u32 {
        self.state_mask.count_ones() + self.events_on.count_ones() + self.events_off.count_ones()
    }
}

/// A sum of products: the function is 1 where some cube is.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Cover {
    /// The product terms.
    pub cubes: Vec<Cube>,
}

impl Cover {
    /// The function's value at `code` with input `input` (see
    /// [`Cube::matches`]).
    #[inline]
    pub fn eval(&self, code: u32, input: Option<u16>) -> bool {
        self.cubes.iter().any(|c| c.matches(code, input))
    }

    /// Number of literals over all cubes.
    pub fn literals(&self) -> usize {
        self.cubes.iter().map(|c| c.literals() as usize).sum()
    }
}

/// Size of one minimised function.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct FunctionSize {
    /// Product terms.
    pub cubes: usize,
    /// Literals over all product terms.
    pub literals: usize,
}

/// Sizes of a [`LogicSupervisor`], for reports.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct LogicSizes {
    /// `ω_b`, by code bit.
    pub next: Vec<FunctionSize>,
    /// `φ_i`, by local event.
    pub defined: Vec<FunctionSize>,
    /// Product terms summed over all functions (a term shared by several
    /// outputs counts once per output).
    pub cubes: usize,
    /// Literals summed over all functions.
    pub literals: usize,
    /// Distinct product terms within each family (`ω`, `φ`), summed: the
    /// rows of the two PLAs if each family were laid out as one.
    pub distinct_cubes: usize,
}

/// A supervisor as minimised CMSSM equations; see the module docs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogicSupervisor {
    name: String,
    encoding: Encoding,
    initial: Option<u32>,
    /// `ω_b`, indexed by code bit `b`.
    next: Vec<Cover>,
    /// `φ_i`, indexed by local event `i`.
    defined: Vec<Cover>,
    /// The [`effort`] counted before minimising.
    effort: u64,
}

/// PLA input literal values, as Espresso's low-level API takes them.
const LIT_0: u8 = 0;
const LIT_1: u8 = 1;
const LIT_FREE: u8 = 2;

/// One family of functions as a PLA: rows of input literals (`LIT_*`)
/// with the outputs they assert (1) in their set.
#[derive(Default)]
#[cfg_attr(not(feature = "espresso"), allow(dead_code))]
struct Pla {
    inputs: usize,
    outputs: usize,
    /// Code bits are inputs `0..l`, event wires `l..`.
    l: usize,
    /// ON-set rows.
    on: Vec<(Vec<u8>, Vec<u8>)>,
    /// OFF-set rows (disjoint from the ON-set).
    off: Vec<(Vec<u8>, Vec<u8>)>,
    /// Don't-care rows (inputs only; free for every output).
    free: Vec<Vec<u8>>,
}

/// Appends `(inputs, output)` to `rows`, merging rows with equal inputs;
/// `index` maps inputs to row numbers. Insertion order is kept, so the
/// PLA (and Espresso's result) is reproducible.
fn add_row(
    rows: &mut Vec<(Vec<u8>, Vec<u8>)>,
    index: &mut std::collections::HashMap<Vec<u8>, usize>,
    outputs: usize,
    inputs: Vec<u8>,
    output: usize,
) {
    let k = *index.entry(inputs.clone()).or_insert_with(|| {
        rows.push((inputs, vec![0; outputs]));
        rows.len() - 1
    });
    rows[k].1[output] = 1;
}

impl Pla {
    /// The [`effort`] of minimising the PLA: ON- times OFF-set rows of
    /// each Espresso run [`Pla::minimise`] makes.
    fn effort(&self, how: Minimisation) -> u64 {
        let rows = |set: &[(Vec<u8>, Vec<u8>)], j: usize| {
            set.iter().filter(|(_, asserted)| asserted[j] == 1).count() as u64
        };
        match how {
            Minimisation::Shared => (self.on.len() as u64).saturating_mul(self.off.len() as u64),
            Minimisation::PerFunction => (0..self.outputs)
                .map(|j| rows(&self.on, j).saturating_mul(rows(&self.off, j)))
                .fold(0, u64::saturating_add),
        }
    }

    /// Minimises the PLA and returns one cover per output: all outputs in
    /// one Espresso run ([`Minimisation::Shared`]) or one run per output.
    /// `started(j)` is told before the run of output `j` (of the first
    /// output, for the single shared run).
    fn minimise(
        &self,
        how: Minimisation,
        started: &dyn Fn(usize),
    ) -> Result<Vec<Cover>, LogicError> {
        match how {
            Minimisation::Shared => {
                started(0);
                self.minimise_outputs(&(0..self.outputs).collect::<Vec<_>>())
            }
            Minimisation::PerFunction => {
                let mut covers = Vec::with_capacity(self.outputs);
                for j in 0..self.outputs {
                    started(j);
                    covers.extend(self.minimise_outputs(&[j])?);
                }
                Ok(covers)
            }
        }
    }

    /// Minimises the outputs `outputs` together; one cover each.
    #[cfg(not(feature = "espresso"))]
    fn minimise_outputs(&self, _outputs: &[usize]) -> Result<Vec<Cover>, LogicError> {
        Err(LogicError::Unavailable)
    }

    /// Minimises the outputs `outputs` together; one cover each.
    #[cfg(feature = "espresso")]
    fn minimise_outputs(&self, outputs: &[usize]) -> Result<Vec<Cover>, LogicError> {
        use espresso_logic::espresso::{Espresso, EspressoCover};
        let no = outputs.len();
        let ni = self.inputs;
        let mut covers = vec![Cover::default(); no];
        let select = |rows: &[(Vec<u8>, Vec<u8>)]| -> Vec<(Vec<u8>, Vec<u8>)> {
            rows.iter()
                .filter_map(|(inputs, asserted)| {
                    let out: Vec<u8> = outputs.iter().map(|&j| asserted[j]).collect();
                    out.contains(&1).then(|| (inputs.clone(), out))
                })
                .collect()
        };
        let on = select(&self.on);
        if on.is_empty() {
            // Every output is constant 0 on the care set.
            return Ok(covers);
        }
        let off = select(&self.off);
        let all = vec![1u8; no];
        let err =
            |e: espresso_logic::error::MinimizationError| LogicError::Minimiser(e.to_string());
        // The instance fixes the dimensions for the covers built below and
        // must outlive them.
        let esp = Espresso::try_new(ni, no, Some(&espresso_logic::EspressoConfig::default()))
            .map_err(err)?;
        let build = |rows: &[(Vec<u8>, Vec<u8>)]| {
            let refs: Vec<(&[u8], &[u8])> = rows
                .iter()
                .map(|(i, o)| (i.as_slice(), o.as_slice()))
                .collect();
            EspressoCover::from_cubes(&refs, ni, no)
        };
        let f = build(&on).map_err(err)?;
        let free: Vec<(Vec<u8>, Vec<u8>)> =
            self.free.iter().map(|i| (i.clone(), all.clone())).collect();
        let d = if free.is_empty() {
            None
        } else {
            Some(build(&free).map_err(err)?)
        };
        let r = if off.is_empty() {
            None // Espresso complements ON ∪ DC itself
        } else {
            Some(build(&off).map_err(err)?)
        };
        let (minimised, _, _) = esp.try_minimize(&f, d.as_ref(), r.as_ref()).map_err(err)?;
        for cube in minimised.to_cubes(ni, no, espresso_logic::CubeType::F) {
            let mut ours = Cube::default();
            for p in 0..ni {
                match (p < self.l, cube.inputs().value_at(p)) {
                    (_, None) => {}
                    (true, Some(v)) => {
                        ours.state_mask |= 1 << p;
                        ours.state_value |= u32::from(v) << p;
                    }
                    (false, Some(true)) => ours.events_on |= 1 << (p - self.l),
                    (false, Some(false)) => ours.events_off |= 1 << (p - self.l),
                }
            }
            for (j, cover) in covers.iter_mut().enumerate() {
                if cube.outputs().value_at(j) {
                    cover.cubes.push(ours);
                }
            }
        }
        Ok(covers)
    }
}

/// The [`effort`] of minimising the logic of `a` over `local` with
/// `encoding`: what [`LogicSupervisor::synthesize_reporting`] compares with
/// its limit, computed without minimising anything.
pub fn effort(
    a: &Automaton,
    local: &[EventId],
    encoding: &Encoding,
    how: Minimisation,
) -> Result<u64, LogicError> {
    let (next, defined) = plas(a, local, encoding)?;
    Ok(next.effort(how).saturating_add(defined.effort(how)))
}

/// The two PLAs to minimise, `ω` (next state) and `φ` (defined), after
/// the size checks.
fn plas(a: &Automaton, local: &[EventId], encoding: &Encoding) -> Result<(Pla, Pla), LogicError> {
    let n = a.num_states();
    if n == 0 {
        return Err(LogicError::Empty(a.name().to_owned()));
    }
    if encoding.len() != n {
        return Err(LogicError::Encoding(format!(
            "{} codes for {n} states",
            encoding.len()
        )));
    }
    let l = usize::from(encoding.bits());
    let m = local.len();
    let rows = n.saturating_mul(m + 1);
    if rows > MAX_ROWS || l + m > MAX_INPUTS {
        return Err(LogicError::TooLarge(format!(
            "supervisor `{}`: {n} states × {} inputs = {rows} care points \
             (limit {MAX_ROWS}), {l} code bits + {m} events = {} PLA inputs (limit {MAX_INPUTS}); \
             use the table backend",
            a.name(),
            m + 1,
            l + m,
        )));
    }
    let unused = encoding.unused_cubes();
    let unused_rows = |extra: usize| -> Vec<Vec<u8>> {
        unused
            .iter()
            .map(|&(mask, value)| {
                cube_row(mask, value, l)
                    .chain(std::iter::repeat_n(LIT_FREE, extra))
                    .collect()
            })
            .collect()
    };

    // Ω: inputs = code bits, then one wire per local event (see the
    // module docs for the shape of the ON- and OFF-set rows). With v =
    // bit b of λ(x), S = the events whose target has bit b ≠ v (an
    // undefined event keeps λ(x), so it is never in S):
    // - v = 1: ON "λ(x), no wire of S"; OFF "λ(x), only wire i", i ∈ S;
    // - v = 0: ON "λ(x), wire i", i ∈ S; OFF "λ(x), no wire" and
    //   "λ(x), only wire i", i ∉ S.
    let mut next = Pla {
        inputs: l + m,
        outputs: l,
        l,
        free: unused_rows(m),
        ..Pla::default()
    };
    let (mut on_index, mut off_index) = Default::default();
    for x in a.states() {
        let cx = encoding.code(x);
        let targets: Vec<u32> = local
            .iter()
            .map(|&e| a.successor(x, e).map_or(cx, |t| encoding.code(t)))
            .collect();
        for b in 0..l {
            let v = cx >> b & 1 == 1;
            let flips = |t: u32| (t >> b & 1 == 1) != v;
            // ON-set: compact terms (exact on one-hot and empty inputs).
            if v {
                let inputs = code_row(cx, l)
                    .chain(
                        targets
                            .iter()
                            .map(|&t| if flips(t) { LIT_0 } else { LIT_FREE }),
                    )
                    .collect();
                add_row(&mut next.on, &mut on_index, l, inputs, b);
            } else {
                for (i, _) in targets.iter().enumerate().filter(|(_, &t)| flips(t)) {
                    let inputs = code_row(cx, l)
                        .chain((0..m).map(|j| if j == i { LIT_1 } else { LIT_FREE }))
                        .collect();
                    add_row(&mut next.on, &mut on_index, l, inputs, b);
                }
            }
            // OFF-set: exactly the care points where ω_b is 0.
            let one_hot = |input: Option<usize>| -> Vec<u8> {
                code_row(cx, l)
                    .chain((0..m).map(|j| if Some(j) == input { LIT_1 } else { LIT_0 }))
                    .collect()
            };
            if !v {
                add_row(&mut next.off, &mut off_index, l, one_hot(None), b);
            }
            for (i, &t) in targets.iter().enumerate() {
                if t >> b & 1 == 0 {
                    add_row(&mut next.off, &mut off_index, l, one_hot(Some(i)), b);
                }
            }
        }
    }
    // Φ: inputs = code bits only; one row per state.
    let mut defined = Pla {
        inputs: l,
        outputs: m,
        l,
        free: unused_rows(0),
        ..Pla::default()
    };
    for x in a.states() {
        let row: Vec<bool> = local.iter().map(|&e| a.successor(x, e).is_some()).collect();
        let code: Vec<u8> = code_row(encoding.code(x), l).collect();
        for (rows, value) in [(&mut defined.on, true), (&mut defined.off, false)] {
            if row.contains(&value) {
                let outputs = row.iter().map(|&d| u8::from(d == value)).collect();
                rows.push((code.clone(), outputs));
            }
        }
    }
    Ok((next, defined))
}

/// The PLA input literals of a code: one per bit, `l` bits.
fn code_row(code: u32, l: usize) -> impl Iterator<Item = u8> {
    (0..l).map(move |b| if code >> b & 1 == 1 { LIT_1 } else { LIT_0 })
}

/// The PLA input literals of a `(mask, value)` code cube.
fn cube_row(mask: u32, value: u32, l: usize) -> impl Iterator<Item = u8> {
    (0..l).map(move |b| match (mask >> b & 1, value >> b & 1) {
        (0, _) => LIT_FREE,
        (_, 1) => LIT_1,
        _ => LIT_0,
    })
}

impl LogicSupervisor {
    /// Synthesises and minimises the CMSSM equations of `a` over the local
    /// alphabet `local` (local index `i` is event `local[i]` of `a`) with
    /// the state encoding `encoding`, then checks them exhaustively with
    /// [`LogicSupervisor::verify`]. Each function is minimised on its own
    /// ([`Minimisation::PerFunction`]).
    pub fn synthesize(
        a: &Automaton,
        local: &[EventId],
        encoding: Encoding,
    ) -> Result<LogicSupervisor, LogicError> {
        Self::synthesize_with(a, local, encoding, Minimisation::PerFunction)
    }

    /// [`LogicSupervisor::synthesize`] with a choice of [`Minimisation`].
    pub fn synthesize_with(
        a: &Automaton,
        local: &[EventId],
        encoding: Encoding,
        how: Minimisation,
    ) -> Result<LogicSupervisor, LogicError> {
        let settings = Settings {
            minimisation: how,
            max_effort: u64::MAX,
        };
        Self::synthesize_reporting(a, local, encoding, &settings, &())
    }

    /// [`LogicSupervisor::synthesize_with`] with an effort limit
    /// ([`Settings`]), telling `progress` which phase and which function it
    /// is working on: on large supervisors minimisation takes a while.
    /// Refuses ([`LogicError::Effort`]) before minimising anything when
    /// the [`effort`] exceeds `settings.max_effort`.
    pub fn synthesize_reporting(
        a: &Automaton,
        local: &[EventId],
        encoding: Encoding,
        settings: &Settings,
        progress: &dyn Progress,
    ) -> Result<LogicSupervisor, LogicError> {
        if !AVAILABLE {
            return Err(LogicError::Unavailable);
        }
        let how = settings.minimisation;
        let (next, defined) = plas(a, local, &encoding)?;
        let effort = next.effort(how).saturating_add(defined.effort(how));
        if effort > settings.max_effort {
            return Err(LogicError::Effort {
                supervisor: a.name().to_owned(),
                effort,
                limit: settings.max_effort,
            });
        }
        let n = a.num_states();
        let (l, m) = (next.l, local.len());
        let phase = |what: &str| {
            progress.report(
                &format!(
                    "supervisor `{}` ({n} states, effort {effort}): {what}",
                    a.name()
                ),
                0,
            );
        };
        let next = next.minimise(how, &|b| {
            phase(&format!(
                "minimising ω, the next-state logic (bit {} of {l})",
                b + 1
            ))
        })?;
        let defined = defined.minimise(how, &|i| {
            phase(&format!(
                "minimising φ, the enabling logic (event {} of {m})",
                i + 1
            ))
        })?;

        let supervisor = LogicSupervisor {
            name: a.name().to_owned(),
            initial: a.initial().map(|s| encoding.code(s)),
            encoding,
            next,
            defined,
            effort,
        };
        phase("verifying the logic against the automaton");
        supervisor.verify(a, local, &supervisor.encoding)?;
        Ok(supervisor)
    }

    /// Checks the equations against `a` on every state and every local
    /// event, and on the empty input: `Ω(λ(x), e_i)` must be `λ(δ(x, e_i))`
    /// (or `λ(x)` where undefined), `Ω(λ(x), 0)` must be `λ(x)`, and
    /// `φ_i(λ(x))` must say whether `δ(x, e_i)` is defined.
    pub fn verify(
        &self,
        a: &Automaton,
        local: &[EventId],
        encoding: &Encoding,
    ) -> Result<(), LogicError> {
        if encoding.len() != a.num_states()
            || encoding.bits() != self.bits()
            || local.len() != self.defined.len()
        {
            return Err(LogicError::Encoding(format!(
                "verifying {} codes of {} bits and {} events against an automaton of {} states, \
                 equations of {} bits and {} events",
                encoding.len(),
                encoding.bits(),
                local.len(),
                a.num_states(),
                self.bits(),
                self.defined.len()
            )));
        }
        for x in a.states() {
            let cx = encoding.code(x);
            let got = self.next_code(cx, None);
            if got != cx {
                return Err(LogicError::Mismatch {
                    state: x.0,
                    event: None,
                    expected: Step {
                        next: cx,
                        defined: None,
                    },
                    got: Step {
                        next: got,
                        defined: None,
                    },
                });
            }
            for (i, &e) in local.iter().enumerate() {
                let i = i as u16;
                let target = a.successor(x, e);
                let expected = Step {
                    next: target.map_or(cx, |t| encoding.code(t)),
                    defined: Some(target.is_some()),
                };
                let got = Step {
                    next: self.next_code(cx, Some(i)),
                    defined: Some(self.is_defined(cx, i)),
                };
                if got != expected {
                    return Err(LogicError::Mismatch {
                        state: x.0,
                        event: Some(i),
                        expected,
                        got,
                    });
                }
            }
        }
        Ok(())
    }

    /// The supervisor's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Bits per state code, `l`.
    pub fn bits(&self) -> u8 {
        self.encoding.bits()
    }

    /// Number of local events, `m`.
    pub fn events(&self) -> usize {
        self.defined.len()
    }

    /// The state encoding the equations were built for.
    pub fn encoding(&self) -> &Encoding {
        &self.encoding
    }

    /// The minimisation [`effort`] counted (and checked against the limit)
    /// before minimising.
    pub fn effort(&self) -> u64 {
        self.effort
    }

    /// The code of the initial state (`Q_Res`), if the automaton has one.
    pub fn initial_code(&self) -> Option<u32> {
        self.initial
    }

    /// `ω_b`, by code bit.
    pub fn next_covers(&self) -> &[Cover] {
        &self.next
    }

    /// `φ_i`, by local event.
    pub fn defined_covers(&self) -> &[Cover] {
        &self.defined
    }

    /// `Ω(code, input)`: every `ω_b` evaluated (`None`: no event). An
    /// undefined event leaves the code unchanged, as in the CMSSM.
    pub fn next_code(&self, code: u32, input: Option<u16>) -> u32 {
        self.next
            .iter()
            .enumerate()
            .filter(|(_, w)| w.eval(code, input))
            .fold(0, |acc, (b, _)| acc | 1 << b)
    }

    /// `φ_local(code)`: whether local event `local` is defined (enabled if
    /// controllable, expected if not); `false` for an index out of range.
    pub fn is_defined(&self, code: u32, local: u16) -> bool {
        self.defined
            .get(usize::from(local))
            .is_some_and(|phi| phi.eval(code, None))
    }

    /// δ in the executor's terms: `None` when `local` is undefined at
    /// `code`, else the code reached.
    pub fn next_state(&self, code: u32, local: u16) -> Option<u32> {
        self.is_defined(code, local)
            .then(|| self.next_code(code, Some(local)))
    }

    /// The local events defined at `code`, in order.
    pub fn defined_events(&self, code: u32) -> impl Iterator<Item = u16> + '_ {
        (0..self.defined.len() as u16).filter(move |&i| self.is_defined(code, i))
    }

    /// Cubes and literals per function and in total.
    pub fn sizes(&self) -> LogicSizes {
        let size = |c: &Cover| FunctionSize {
            cubes: c.cubes.len(),
            literals: c.literals(),
        };
        let next: Vec<FunctionSize> = self.next.iter().map(size).collect();
        let defined: Vec<FunctionSize> = self.defined.iter().map(size).collect();
        let distinct = |covers: &[Cover]| {
            covers
                .iter()
                .flat_map(|c| c.cubes.iter())
                .collect::<HashSet<_>>()
                .len()
        };
        LogicSizes {
            cubes: next.iter().chain(&defined).map(|s| s.cubes).sum(),
            literals: next.iter().chain(&defined).map(|s| s.literals).sum(),
            distinct_cubes: distinct(&self.next) + distinct(&self.defined),
            next,
            defined,
        }
    }
}

/// A build without Espresso refuses with [`LogicError::Unavailable`]
/// before any work, and says how to get the backend.
#[cfg(all(test, not(feature = "espresso")))]
mod without_espresso {
    use super::*;
    use des::testing::auto;

    #[test]
    fn the_logic_backend_says_what_to_build_with() {
        let a = auto("m", &[("go", true)], &[("0", "go", "0")], &["0"]);
        let local: Vec<EventId> = a.alphabet().ids().collect();
        let err = LogicSupervisor::synthesize(&a, &local, Encoding::binary(1)).unwrap_err();
        assert_eq!(err, LogicError::Unavailable);
        let message = err.to_string();
        assert!(message.contains("--features espresso"), "{message}");
        assert!(message.contains("libclang"), "{message}");
    }
}

#[cfg(all(test, feature = "espresso"))]
mod tests {
    use super::*;
    use des::automaton::AutomatonBuilder;
    use des::testing::auto;
    use proptest::prelude::*;

    fn ids(a: &Automaton, names: &[&str]) -> Vec<EventId> {
        names.iter().map(|n| a.alphabet().id(n).unwrap()).collect()
    }

    /// The local event order used for sup_crane1 below.
    const CRANE_EVENTS: [&str; 6] = ["t1_at13", "t2_at13", "f_ld1", "st_ld1", "run_t1", "run_t2"];

    /// sup_crane1 of Leduc–Wonham. The paper's figure is not in the text,
    /// so the automaton is read off its equations: sensor events t1_at13
    /// and t2_at13 lead from idle to "train 1 / train 2 at sensor 13",
    /// f_ld1 (loading finished) leads back to idle from both. The three
    /// controllable outputs are modelled by events of our naming: st_ld1
    /// (crane 1 starts loading; paper's φ0 = qa1 ∨ qa0, only with a train
    /// present), run_t1 and run_t2 (a train may move; φ1 = ¬qa0 holds
    /// train 1 while it is at the sensor, φ2 = ¬qa1 train 2). Where enabled
    /// they are self-loops: they do not change the crane's state.
    fn sup_crane1() -> Automaton {
        let mut b = AutomatonBuilder::new("sup_crane1");
        for e in ["t1_at13", "t2_at13", "f_ld1"] {
            b.add_event(e, false).unwrap();
        }
        for e in ["st_ld1", "run_t1", "run_t2"] {
            b.add_event(e, true).unwrap();
        }
        for s in ["idle", "train1", "train2"] {
            b.add_state(s);
        }
        b.set_initial_by_name("idle").unwrap();
        b.mark_by_name("idle");
        for (s, e, t) in [
            ("idle", "t1_at13", "train1"),
            ("idle", "t2_at13", "train2"),
            ("train1", "f_ld1", "idle"),
            ("train2", "f_ld1", "idle"),
            ("train1", "st_ld1", "train1"),
            ("train2", "st_ld1", "train2"),
            ("idle", "run_t1", "idle"),
            ("train2", "run_t1", "train2"),
            ("idle", "run_t2", "idle"),
            ("train1", "run_t2", "train1"),
        ] {
            b.add_transition_by_name(s, e, t, 0).unwrap();
        }
        b.build().unwrap()
    }

    fn crane_logic_with(how: Minimisation) -> (Automaton, Vec<EventId>, LogicSupervisor) {
        let a = sup_crane1();
        let local = ids(&a, &CRANE_EVENTS);
        // The paper's encoding: idle 00, train 1 at 13 01, train 2 at 13 10.
        let enc = Encoding::from_codes(2, vec![0b00, 0b01, 0b10]).unwrap();
        let logic = LogicSupervisor::synthesize_with(&a, &local, enc, how).unwrap();
        (a, local, logic)
    }

    fn crane_logic() -> (Automaton, Vec<EventId>, LogicSupervisor) {
        crane_logic_with(Minimisation::PerFunction)
    }

    #[test]
    fn sup_crane1_matches_the_paper_equations() {
        for how in [Minimisation::PerFunction, Minimisation::Shared] {
            let (_, _, logic) = crane_logic_with(how);
            println!(
                "sup_crane1, ours ({how:?}):\n{}",
                crate::emit::logic::equations(&logic, &CRANE_EVENTS)
            );
            println!("sizes: {:?}\n", logic.sizes());
            check_crane_against_paper(&logic);
        }
        // Per function, no equation is longer than the paper's: ω has 5
        // literals each there, φ1 = ¬qa0 and φ2 = ¬qa1 one, φ0 two.
        let sizes = crane_logic().2.sizes();
        assert!(sizes.next.iter().all(|s| s.literals <= 5), "{sizes:?}");
        let lits: Vec<usize> = sizes.defined[3..].iter().map(|s| s.literals).collect();
        assert_eq!(lits, [2, 1, 1]);
    }

    fn check_crane_against_paper(logic: &LogicSupervisor) {
        assert_eq!(logic.initial_code(), Some(0));
        // The paper's equations, on Qa = [qa1, qa0] and the wires.
        let w1 =
            |q1: bool, q0: bool, _t1: bool, t2: bool, f: bool| (!q1 && !q0 && t2) || (q1 && !f);
        let w0 =
            |q1: bool, q0: bool, t1: bool, _t2: bool, f: bool| (!q1 && !q0 && t1) || (q0 && !f);
        let phi2 = |q1: bool, _q0: bool| !q1;
        let phi1 = |_q1: bool, q0: bool| !q0;
        let phi0 = |q1: bool, q0: bool| q1 || q0;
        for code in [0b00u32, 0b01, 0b10] {
            let (q1, q0) = (code & 2 != 0, code & 1 != 0);
            for input in std::iter::once(None).chain((0..6u16).map(Some)) {
                let wire = |name: &str| input.is_some_and(|i| CRANE_EVENTS[usize::from(i)] == name);
                let (t1, t2, f) = (wire("t1_at13"), wire("t2_at13"), wire("f_ld1"));
                let paper =
                    (u32::from(w1(q1, q0, t1, t2, f)) << 1) | u32::from(w0(q1, q0, t1, t2, f));
                assert_eq!(
                    logic.next_code(code, input),
                    paper,
                    "code {code:02b} input {input:?}"
                );
            }
            // z0 ↔ st_ld1, z1 ↔ run_t1, z2 ↔ run_t2 (local 3, 4, 5).
            assert_eq!(logic.is_defined(code, 3), phi0(q1, q0), "φ0 at {code:02b}");
            assert_eq!(logic.is_defined(code, 4), phi1(q1, q0), "φ1 at {code:02b}");
            assert_eq!(logic.is_defined(code, 5), phi2(q1, q0), "φ2 at {code:02b}");
        }
        // The executor's view: δ and None.
        assert_eq!(logic.next_state(0b00, 0), Some(0b01));
        assert_eq!(logic.next_state(0b00, 1), Some(0b10));
        assert_eq!(logic.next_state(0b01, 2), Some(0b00));
        assert_eq!(logic.next_state(0b10, 2), Some(0b00));
        assert_eq!(logic.next_state(0b00, 2), None);
        assert_eq!(logic.next_state(0b01, 4), None);
        assert_eq!(logic.next_state(0b01, 6), None);
        assert_eq!(logic.defined_events(0b00).collect::<Vec<_>>(), [0, 1, 4, 5]);
    }

    #[test]
    fn a_corrupted_cover_fails_verification() {
        let (a, local, logic) = crane_logic();
        let enc = logic.encoding().clone();
        assert_eq!(logic.verify(&a, &local, &enc), Ok(()));

        // ω0 dropping a term.
        let mut bad = logic.clone();
        bad.next[0].cubes.pop();
        assert!(matches!(
            bad.verify(&a, &local, &enc),
            Err(LogicError::Mismatch { .. })
        ));

        // ω1 made constant 1: already wrong on the empty input at idle.
        let mut bad = logic.clone();
        bad.next[1].cubes.push(Cube::default());
        assert_eq!(
            bad.verify(&a, &local, &enc),
            Err(LogicError::Mismatch {
                state: 0,
                event: None,
                expected: Step {
                    next: 0b00,
                    defined: None
                },
                got: Step {
                    next: 0b10,
                    defined: None
                },
            })
        );

        // φ of f_ld1 emptied: f_ld1 no longer expected in train1.
        let mut bad = logic.clone();
        bad.defined[2].cubes.clear();
        let err = bad.verify(&a, &local, &enc).unwrap_err();
        assert_eq!(
            err,
            LogicError::Mismatch {
                state: 1,
                event: Some(2),
                expected: Step {
                    next: 0b00,
                    defined: Some(true)
                },
                got: Step {
                    next: 0b00,
                    defined: Some(false)
                },
            }
        );
        assert!(
            err.to_string().contains("state 1 on local event 2"),
            "{err}"
        );
    }

    #[test]
    fn binary_encoding_and_code_checks() {
        let e = Encoding::binary(3);
        assert_eq!((e.bits(), e.codes()), (2, &[0, 1, 2][..]));
        assert_eq!(Encoding::binary(1).bits(), 1);
        assert_eq!(Encoding::binary(4).bits(), 2);
        assert_eq!(Encoding::binary(5).bits(), 3);
        assert_eq!(e.unused_cubes(), [(0b11, 0b11)]);
        assert_eq!(e.state_of(2), Some(StateId(2)));
        assert!(Encoding::from_codes(2, vec![0, 3, 0]).is_err());
        assert!(Encoding::from_codes(2, vec![0, 4]).is_err());
        assert!(Encoding::from_codes(0, vec![]).is_err());
        assert!(Encoding::from_codes(33, vec![]).is_err());
        let sparse = Encoding::from_codes(3, vec![0b101, 0b010]).unwrap();
        let unused = sparse.unused_cubes();
        for c in 0..8u32 {
            let free = unused.iter().any(|&(m, v)| c & m == v);
            assert_eq!(free, !sparse.codes().contains(&c), "code {c:03b}");
        }
    }

    #[test]
    fn refuses_empty_mismatched_and_oversized_inputs() {
        let a = auto("one", &[("a", true)], &[("0", "a", "0")], &[]);
        let local = ids(&a, &["a"]);
        assert!(matches!(
            LogicSupervisor::synthesize(&a, &local, Encoding::binary(2)),
            Err(LogicError::Encoding(_))
        ));
        let empty = Automaton::empty("nothing", a.alphabet().clone());
        assert_eq!(
            LogicSupervisor::synthesize(&empty, &local, Encoding::binary(0)),
            Err(LogicError::Empty("nothing".into()))
        );
        // 200 wide events: too many PLA inputs.
        let events: Vec<(String, bool)> = (0..200).map(|i| (format!("e{i}"), true)).collect();
        let refs: Vec<(&str, bool)> = events.iter().map(|(n, c)| (n.as_str(), *c)).collect();
        let wide = auto("wide", &refs, &[("0", "e0", "0")], &[]);
        let local: Vec<EventId> = wide.alphabet().ids().collect();
        let err = LogicSupervisor::synthesize(&wide, &local, Encoding::binary(1)).unwrap_err();
        assert!(
            matches!(&err, LogicError::TooLarge(m) if m.contains("table backend")),
            "{err}"
        );
    }

    #[test]
    fn single_state_and_constant_functions() {
        // One state, a self-loop and an event never defined.
        let a = auto("one", &[("a", true), ("b", false)], &[("0", "a", "0")], &[]);
        let local = ids(&a, &["a", "b"]);
        let logic = LogicSupervisor::synthesize(&a, &local, Encoding::binary(1)).unwrap();
        assert_eq!(logic.next_state(0, 0), Some(0));
        assert_eq!(logic.next_state(0, 1), None);
        // ω0 is constant 0 (the only state keeps its code), φ of `a`
        // constant 1, φ of `b` constant 0.
        assert!(logic.next_covers()[0].cubes.is_empty());
        assert_eq!(logic.defined_covers()[0].cubes, [Cube::default()]);
        assert!(logic.defined_covers()[1].cubes.is_empty());
    }

    /// An automaton with states `s0..`, events `e0..` (even ones
    /// controllable) and `delta[s * m + e]` as transitions.
    fn random_automaton(n: usize, m: usize, delta: &[Option<u32>]) -> Automaton {
        crate::backend::table::tests::automaton(n, m, |s, e| delta[s * m + e].map(|t| t as usize)).0
    }

    fn random_case() -> impl Strategy<Value = (usize, usize, Vec<Option<u32>>)> {
        (1usize..=40, 1usize..=8).prop_flat_map(|(n, m)| {
            (
                Just(n),
                Just(m),
                proptest::collection::vec(proptest::option::weighted(0.5, 0..n as u32), n * m),
            )
        })
    }

    fn check_against(a: &Automaton, local: &[EventId], logic: &LogicSupervisor, enc: &Encoding) {
        for s in a.states() {
            for (i, &e) in local.iter().enumerate() {
                assert_eq!(
                    logic.next_state(enc.code(s), i as u16),
                    a.successor(s, e).map(|t| enc.code(t)),
                    "state {s} event {i}"
                );
            }
            assert_eq!(logic.next_state(enc.code(s), local.len() as u16), None);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn random_automata_binary_encoding((n, m, delta) in random_case(), shared in any::<bool>()) {
            let a = random_automaton(n, m, &delta);
            // Local order reversed, to exercise the mapping.
            let mut local: Vec<EventId> = a.alphabet().ids().collect();
            local.reverse();
            let enc = Encoding::binary(n);
            let how = if shared { Minimisation::Shared } else { Minimisation::PerFunction };
            let logic = LogicSupervisor::synthesize_with(&a, &local, enc.clone(), how).unwrap();
            check_against(&a, &local, &logic, &enc);
        }

        #[test]
        fn random_automata_scattered_encoding(
            (n, m, delta) in random_case(),
            seed in any::<u64>(),
        ) {
            let a = random_automaton(n, m, &delta);
            let local: Vec<EventId> = a.alphabet().ids().collect();
            // One spare bit, codes scattered by a bijection of 0..2^bits.
            let bits = crate::backend::table::bits_for(n as u64 - 1) + 1;
            let size = 1u64 << bits;
            let odd = (seed | 1) % size;
            let codes: Vec<u32> = (0..n as u64)
                .map(|s| ((s * odd + (seed >> 7)) % size) as u32)
                .collect();
            let enc = Encoding::from_codes(bits, codes).unwrap();
            let logic = LogicSupervisor::synthesize(&a, &local, enc.clone()).unwrap();
            check_against(&a, &local, &logic, &enc);
        }
    }

    /// Synthesis time for a random 50-state, 10-event supervisor; run with
    /// `cargo test -p codegen --release --lib backend::logic::tests::timing -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn timing() {
        let sizes: Vec<(usize, usize)> = std::env::var("LOGIC_TIMING")
            .ok()
            .map(|v| {
                v.split(',')
                    .filter_map(|p| p.split_once('x'))
                    .map(|(n, m)| (n.parse().unwrap(), m.parse().unwrap()))
                    .collect()
            })
            .unwrap_or_else(|| vec![(50, 10), (200, 20)]);
        // Structured: k independent two-state switches (set_i / clr_i), as
        // a product, binary encoded: 2^k states, 2k events.
        let switches: Vec<u32> = std::env::var("LOGIC_SWITCHES").map_or(vec![6, 8, 10], |v| {
            v.split(',').map(|k| k.parse().unwrap()).collect()
        });
        for k in switches {
            let (n, m) = (1usize << k, 2 * k as usize);
            let delta: Vec<Option<u32>> = (0..n * m)
                .map(|p| {
                    let (s, e) = ((p / m) as u32, (p % m) as u32);
                    let bit = 1 << (e / 2);
                    let set = e % 2 == 0;
                    (set == (s & bit == 0)).then_some(s ^ bit)
                })
                .collect();
            let a = random_automaton(n, m, &delta);
            let local: Vec<EventId> = a.alphabet().ids().collect();
            let start = std::time::Instant::now();
            let logic = LogicSupervisor::synthesize(&a, &local, Encoding::binary(n)).unwrap();
            let sizes = logic.sizes();
            println!(
                "{k} switches ({n} states × {m} events): {:?}, {} cubes, {} literals",
                start.elapsed(),
                sizes.cubes,
                sizes.literals
            );
        }
        for (n, m) in sizes {
            // A deterministic pseudo-random δ, about half defined.
            let mut x = 0x2545_f491_4f6c_dd1du64;
            let delta: Vec<Option<u32>> = (0..n * m)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    (x % 2 == 0).then_some((x >> 8) as u32 % n as u32)
                })
                .collect();
            let a = random_automaton(n, m, &delta);
            let local: Vec<EventId> = a.alphabet().ids().collect();
            for how in [Minimisation::PerFunction, Minimisation::Shared] {
                if how == Minimisation::Shared && n * m > 4000 {
                    continue; // slow on unstructured automata
                }
                let start = std::time::Instant::now();
                let logic =
                    LogicSupervisor::synthesize_with(&a, &local, Encoding::binary(n), how).unwrap();
                let sizes = logic.sizes();
                println!(
                    "{n} states × {m} events, {how:?}: {:?}, {} cubes ({} distinct), {} literals",
                    start.elapsed(),
                    sizes.cubes,
                    sizes.distinct_cubes,
                    sizes.literals
                );
            }
        }
    }
}
