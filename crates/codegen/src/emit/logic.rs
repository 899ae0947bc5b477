//! The logic backend's text: each supervisor's CMSSM as a Rust module of
//! plain functions ([`supervisor_module`]), the `Logic` program over them,
//! and the equations in mathematical notation for reports ([`equations`]).
//!
//! The synthesis and verification of the equations are in
//! [`crate::backend::logic`]; this module only writes them down. All the
//! explanations it writes are doc comments, so they survive layout.

use super::{doc_text, one_line, quoted, Emitter, SupervisorStats};
use crate::backend::logic::{self, Cover, Cube, LogicSupervisor};
use executor::program as ex;
use plc_project::ident::{snake_ident, supervisor_item};
use std::collections::HashSet;
use std::fmt::Write;

/// Transitions shown in a module's doc comment (the first states').
const DOC_ROWS: usize = 8;

/// What the module of one supervisor calls things.
#[derive(Debug, Clone, Copy)]
pub struct Names<'a> {
    /// The supervisor's name; the module and its functions are named
    /// after it.
    pub supervisor: &'a str,
    /// Where the supervisor came from, as Markdown for the module's doc
    /// comment (``from `file` ``), or empty. Line breaks become spaces.
    pub origin: &'a str,
    /// Local event names, in local order (a missing name prints as
    /// `e<i>`).
    pub events: &'a [&'a str],
    /// State names, in state order (a missing name prints as the index).
    pub states: &'a [&'a str],
}

impl Names<'_> {
    fn event(&self, i: usize) -> String {
        self.events
            .get(i)
            .map_or_else(|| format!("e{i}"), |s| (*s).to_owned())
    }

    fn state(&self, s: usize) -> String {
        self.states
            .get(s)
            .map_or_else(|| s.to_string(), |n| (*n).to_owned())
    }
}

/// `base`, or `base_2`, `base_3`, … whichever is not yet in `taken`; the
/// result is added to `taken`.
fn unique(base: String, taken: &mut HashSet<String>) -> String {
    let mut candidate = base.clone();
    let mut k = 2;
    while taken.contains(&candidate) {
        candidate = format!("{base}_{k}");
        k += 1;
    }
    taken.insert(candidate.clone());
    candidate
}

/// A code as a binary literal of `bits` digits.
fn code_literal(code: u32, bits: usize) -> String {
    format!("{code:#0width$b}", width = bits + 2)
}

/// `pub mod <name> { … }`: the CMSSM of one supervisor as plain Rust.
///
/// The module holds one constant per local event (`T1_AT13: u16 = 0`, the
/// `e` the functions take) and the functions `<name>_next(q, e) -> u32`
/// (`Ω`, its terms as a PLA over the code bits), `<name>_defined(q, e) ->
/// bool` (`φ`), `<name>_enabled(q, from, len) -> u32` (a row of φ, as the
/// executor's `Program::enabled`: φ's rows looked up by state code),
/// `<name>_move(q, e) -> u32` (Ω on an event `q` defines: per event, only
/// the terms 1 on some state code defining it, so that a move evaluates no
/// other event's terms; past [`MOVE_TERMS_MAX`] terms, by state code) and
/// `<name>_step(q, e) -> Option<u32>` (φ, read from its row once some φ has
/// more than [`MOVE_TERMS_MAX`] terms, and that Ω, as its
/// `Program::next_state`), where `q` is a state code. Its doc
/// comment gives the state codes, the reset code
/// and the transitions of the first states. Names are sanitised into
/// identifiers, or into one-line text in doc comments, so no name can
/// inject code; the functions use neither `std`, allocation nor `unsafe`.
pub fn supervisor_module(logic: &LogicSupervisor, names: &Names<'_>) -> String {
    module_with(logic, names, MOVE_TERMS_MAX)
}

/// The most product terms an event's arm of `_move` evaluates. An event
/// whose terms (those of ω that are 1 on some state code defining it) are
/// more is moved by a `match` on the state code instead, its arms the codes
/// the event leaves and the code each reaches, when those arms are fewer
/// than the terms: the compiler lays such a `match` out as a jump table or
/// a binary search, so a move costs a few comparisons instead of one per
/// term (the boiler's 1,272-state sequence evaluated up to 1,600 terms on
/// one move). φ is the same either way, so is every trace. The same bound
/// decides how `_step` asks φ: a supervisor with a φ of more than this many
/// terms reads it from its row by state code (`_enabled`), a lookup,
/// instead of evaluating the sum of products.
pub const MOVE_TERMS_MAX: usize = 32;

/// [`supervisor_module`], with the events of more than `lookup_above`
/// terms in `_move` moved by state code (0: every event that has terms,
/// even where the codes it leaves are not fewer; for tests).
fn module_with(logic: &LogicSupervisor, names: &Names<'_>, lookup_above: usize) -> String {
    let prefix = supervisor_item(names.supervisor);
    let l = usize::from(logic.bits());
    let m = logic.events();
    // Identifiers of the event wires, unique and clear of the fixed locals;
    // the event constants are the same in upper case. A wire holds a
    // lower-case letter (one of digits and `_` alone, `_1` from `1`, gets an
    // `e`: `e_1`), so the constants are unique too, differ from every wire
    // (a local of that name would shadow the constant) and from every
    // function.
    let mut taken: HashSet<String> = ["q", "e"].iter().map(|s| (*s).to_owned()).collect();
    for b in 0..l {
        taken.insert(format!("q{b}"));
        taken.insert(format!("w{b}"));
    }
    let wires: Vec<String> = (0..m)
        .map(|i| {
            let wire = snake_ident(&names.event(i));
            let wire = if wire.bytes().any(|b| b.is_ascii_lowercase()) {
                wire
            } else {
                format!("e{wire}")
            };
            unique(wire, &mut taken)
        })
        .collect();
    let constants: Vec<String> = wires.iter().map(|w| w.to_ascii_uppercase()).collect();

    let mut out = String::new();
    module_doc(&mut out, logic, names);
    // Names are lower-cased identifiers: unique, but free to hold `__`.
    let _ = writeln!(out, "#[allow(non_snake_case)]\npub mod {prefix} {{");
    for (i, constant) in constants.iter().enumerate() {
        let _ = writeln!(
            out,
            "/// Local event {i}: {}.\npub const {constant}: u16 = {i};",
            quoted(&names.event(i))
        );
    }

    let cube_expr = |c: &Cube| {
        let mut lits = Vec::new();
        for b in (0..l).rev() {
            if c.state_mask >> b & 1 == 1 {
                let neg = if c.state_value >> b & 1 == 1 { "" } else { "!" };
                lits.push(format!("{neg}q{b}"));
            }
        }
        for (i, wire) in wires.iter().enumerate() {
            if c.events_on >> i & 1 == 1 {
                lits.push(wire.clone());
            }
        }
        for (i, wire) in wires.iter().enumerate() {
            if c.events_off >> i & 1 == 1 {
                lits.push(format!("!{wire}"));
            }
        }
        lits
    };
    let sum_expr = |c: &Cover| {
        let terms: Vec<Vec<String>> = c.cubes.iter().map(cube_expr).collect();
        match terms.len() {
            0 => "false".to_owned(),
            1 if terms[0].is_empty() => "true".to_owned(),
            1 => terms[0].join(" & "),
            _ => terms
                .iter()
                .map(|t| {
                    if t.is_empty() {
                        "true".to_owned()
                    } else if t.len() == 1 {
                        t[0].clone()
                    } else {
                        format!("({})", t.join(" & "))
                    }
                })
                .collect::<Vec<_>>()
                .join(" | "),
        }
    };
    let state_bits_used = |covers: &[Cover]| {
        covers
            .iter()
            .flat_map(|c| c.cubes.iter())
            .fold(0u32, |acc, c| acc | c.state_mask)
    };
    let bit_lets = |out: &mut String, used: u32| {
        for b in (0..l).rev() {
            if used >> b & 1 == 1 {
                if b == 0 {
                    let _ = writeln!(out, "    let q0 = q & 1 != 0;");
                } else {
                    let _ = writeln!(out, "    let q{b} = (q >> {b}) & 1 != 0;");
                }
            }
        }
        if used == 0 {
            let _ = writeln!(out, "    let _ = q;");
        }
    };

    // Ω as a PLA over the code bits, each term setting the bits of every
    // ω_b it is in: the terms without a wire high are evaluated on every
    // move (a wire low as a mask of the events they exclude), those with
    // one only in the arm of that event (a term asking two wires high is
    // never 1 on one-hot inputs and is left out). A move evaluates the
    // common terms and its event's, not every term of every event.
    let _ = writeln!(
        out,
        "/// `{prefix}`: next state code of the CMSSM (Leduc–Wonham), minimised with Espresso.\n\
         ///\n\
         /// `q`: state code ({l} bits); `e`: local event index. An event the state does\n\
         /// not define, or an index of no event, leaves the code unchanged. The product\n\
         /// terms of ω, each setting the code bits whose ω holds it: those asking no\n\
         /// event wire high for every event they do not exclude, the others in the arm of\n\
         /// their event. The executor asks `_step`, hence `_move`, instead."
    );
    // The executor asks `_move`; this is the whole of Ω, for other callers.
    let _ = writeln!(
        out,
        "#[allow(dead_code)]\npub fn {prefix}_next(q: u32, e: u16) -> u32 {{"
    );
    // (mask, value, excluded events, bits) and, per event, (mask, value, bits).
    let mut common: Vec<(u32, u32, u128, u32)> = Vec::new();
    let mut specific: Vec<Vec<Term>> = vec![Vec::new(); m];
    for (b, w) in logic.next_covers().iter().enumerate() {
        for c in &w.cubes {
            let terms_of = |on: u128| -> Option<usize> {
                (on.count_ones() == 1).then(|| on.trailing_zeros() as usize)
            };
            if c.events_on == 0 {
                let key = (c.state_mask, c.state_value, c.events_off);
                match common.iter_mut().find(|t| (t.0, t.1, t.2) == key) {
                    Some(t) => t.3 |= 1 << b,
                    None => common.push((key.0, key.1, key.2, 1 << b)),
                }
            } else if let Some(i) = terms_of(c.events_on).filter(|&i| i < m) {
                if c.events_off >> i & 1 == 1 {
                    continue;
                }
                let terms = &mut specific[i];
                match terms
                    .iter_mut()
                    .find(|t| (t.0, t.1) == (c.state_mask, c.state_value))
                {
                    Some(t) => t.2 |= 1 << b,
                    None => terms.push((c.state_mask, c.state_value, 1 << b)),
                }
            }
        }
    }
    let uses_q = common.iter().any(|t| t.0 != 0) || specific.iter().flatten().any(|t| t.0 != 0);
    if common.is_empty() && specific.iter().all(Vec::is_empty) {
        // ω is 0 for every code and event.
        let _ = writeln!(out, "    let _ = (q, e);\n    0\n}}\n");
    } else {
        if !uses_q {
            let _ = writeln!(out, "    let _ = q;");
        }
        let wire_type = match m {
            0..=32 => "u32",
            33..=64 => "u64",
            _ => "u128",
        };
        if common.iter().any(|t| t.2 != 0) {
            let _ = writeln!(
                out,
                "    let wire: {wire_type} = if e < {m} {{ 1 << e }} else {{ 0 }};"
            );
        }
        let _ = writeln!(out, "    let mut w = 0;");
        for &(mask, value, excluded, bits) in &common {
            let mut tests = Vec::new();
            if mask != 0 {
                tests.push(format!("q & {mask:#x} == {value:#x}"));
            }
            if excluded != 0 {
                tests.push(format!("wire & {excluded:#x} == 0"));
            }
            if tests.is_empty() {
                let _ = writeln!(out, "    w |= {bits:#x};");
            } else {
                let _ = writeln!(
                    out,
                    "    if {} {{\n        w |= {bits:#x};\n    }}",
                    tests.join(" && ")
                );
            }
        }
        write_arms(
            &mut out,
            specific
                .iter()
                .zip(&constants)
                .map(|(t, c)| (c.as_str(), t.clone())),
        );
        let _ = writeln!(out, "    w\n}}\n");
    }

    // Φ
    let _ = writeln!(
        out,
        "/// `{prefix}`: whether local event `e` is defined in state code `q`: enabled\n\
         /// for a controllable event, expected for an uncontrollable one."
    );
    let _ = writeln!(out, "pub fn {prefix}_defined(q: u32, e: u16) -> bool {{");
    bit_lets(&mut out, state_bits_used(logic.defined_covers()));
    if m == 0 {
        let _ = writeln!(out, "    let _ = e;\n    false");
    } else {
        let _ = writeln!(out, "    match e {{");
        for (phi, constant) in logic.defined_covers().iter().zip(&constants) {
            let _ = writeln!(out, "        {constant} => {},", sum_expr(phi));
        }
        let _ = writeln!(out, "        _ => false,\n    }}");
    }
    let _ = writeln!(out, "}}\n");

    // Φ as a row, what the executor reads after every move: φ's rows by
    // state code, the codes of equal rows in one arm (a lookup the
    // compiler lays out as a table), so that a move costs one lookup
    // whatever the size of φ's terms.
    let _ = writeln!(
        out,
        "/// `{prefix}`: which of the local events `from..from + len` (`len` at most 32)\n\
         /// are defined in state code `q`: bit `k` for event `from + k` (one row of φ).\n\
         /// φ's rows by state code, the codes of equal rows in one arm; 0 for a code of\n\
         /// no state."
    );
    let _ = writeln!(
        out,
        "pub fn {prefix}_enabled(q: u32, from: u16, len: u8) -> u32 {{"
    );
    if m == 0 {
        let _ = writeln!(out, "    let _ = (q, from, len);\n    0");
    } else {
        let words = m.div_ceil(32);
        let mut rows: Vec<(Vec<u32>, Vec<u32>)> = Vec::new();
        for &code in logic.encoding().codes() {
            let mut row = vec![0u32; words];
            for i in 0..m {
                if logic.is_defined(code, i as u16) {
                    row[i / 32] |= 1 << (i % 32);
                }
            }
            match rows.iter_mut().find(|(r, _)| *r == row) {
                Some((_, codes)) => codes.push(code),
                None => rows.push((row, vec![code])),
            }
        }
        let _ = writeln!(out, "    let phi: [u32; {words}] = [");
        for w in 0..words {
            let _ = writeln!(out, "        match q {{");
            for (row, codes) in &rows {
                if row[w] == 0 {
                    continue;
                }
                let codes: Vec<String> = codes.iter().map(|c| format!("{c:#x}")).collect();
                let _ = writeln!(out, "            {} => {:#x},", codes.join(" | "), row[w]);
            }
            let _ = writeln!(out, "            _ => 0,\n        }},");
        }
        let _ = writeln!(out, "    ];");
        let _ = writeln!(
            out,
            "    let (word, shift) = (usize::from(from / 32), u32::from(from % 32));\n    \
             let low = phi.get(word).map_or(0, |w| w >> shift);\n    \
             let high = match shift {{\n        \
             0 => 0,\n        \
             _ => phi.get(word + 1).map_or(0, |w| w << (32 - shift)),\n    \
             }};\n    \
             match len {{\n        \
             0 => 0,\n        \
             32.. => low | high,\n        \
             _ => (low | high) & ((1 << len) - 1),\n    \
             }}"
        );
    }
    let _ = writeln!(out, "}}\n");

    // Ω on a move the state defines, what the executor asks: per event,
    // only the terms of ω that are 1 on some state code defining it (the
    // others are 0 on every such code, so the result is ω's).
    let mut doc = "/// the terms of ω that are 1 on some state code defining it.".to_owned();
    let codes = logic.encoding().codes();
    let mut moves: Vec<Vec<Term>> = (0..m)
        .map(|i| {
            let defining: Vec<u32> = codes
                .iter()
                .copied()
                .filter(|&c| logic.is_defined(c, i as u16))
                .collect();
            let mut terms: Vec<Term> = Vec::new();
            let candidates = common
                .iter()
                .filter(|t| t.2 >> i & 1 == 0)
                .map(|t| (t.0, t.1, t.3))
                .chain(specific[i].iter().copied());
            for (mask, value, bits) in candidates {
                if !defining.iter().any(|&c| c & mask == value) {
                    continue;
                }
                match terms.iter_mut().find(|t| (t.0, t.1) == (mask, value)) {
                    Some(t) => t.2 |= bits,
                    None => terms.push((mask, value, bits)),
                }
            }
            terms
        })
        .collect();
    // The events of too many terms, by state code: (event, arms of
    // (codes, target)), the codes the event leaves, grouped by target.
    let mut lookups: Vec<(usize, Lookup)> = Vec::new();
    for (i, terms) in moves.iter_mut().enumerate() {
        if terms.len() <= lookup_above {
            continue;
        }
        let mut arms: Lookup = Vec::new();
        let mut sorted: Vec<u32> = codes.to_vec();
        sorted.sort_unstable();
        for code in sorted {
            let Some(target) = logic.next_state(code, i as u16) else {
                continue;
            };
            if target == code {
                continue;
            }
            match arms.iter_mut().find(|(_, t)| *t == target) {
                Some((from, _)) => from.push(code),
                None => arms.push((vec![code], target)),
            }
        }
        let listed: usize = arms.iter().map(|(from, _)| from.len()).sum();
        if listed < terms.len() || lookup_above == 0 {
            terms.clear();
            lookups.push((i, arms));
        }
    }
    if !lookups.is_empty() {
        doc = format!(
            "/// the terms of ω that are 1 on some state code defining it; an event of more than\n\
             /// {lookup_above} such terms by state code instead, when the codes it leaves are fewer\n\
             /// (each arm: the codes it leaves for one code, that code; others keep theirs)."
        );
    }
    let _ = writeln!(
        out,
        "/// `{prefix}`: the code reached from `q` on local event `e` when `q` is the code of\n\
         /// a state that defines `e` (what `_step` asks; otherwise unspecified): per event,\n\
         {doc}"
    );
    let _ = writeln!(out, "pub fn {prefix}_move(q: u32, e: u16) -> u32 {{");
    let lookup_expr = |arms: &[(Vec<u32>, u32)]| {
        if arms.is_empty() {
            return "q".to_owned();
        }
        let mut text = "match q {\n".to_owned();
        for (from, target) in arms {
            let from: Vec<String> = from.iter().map(|c| format!("{c:#x}")).collect();
            let _ = writeln!(text, "            {} => {target:#x},", from.join(" | "));
        }
        text.push_str("            _ => q,\n        }");
        text
    };
    let pla = !moves.iter().all(Vec::is_empty);
    match lookups.as_slice() {
        [] => {}
        [(i, arms)] if pla => {
            let _ = writeln!(
                out,
                "    if e == {} {{\n        return {};\n    }}",
                constants[*i],
                lookup_expr(arms)
            );
        }
        [(i, arms)] => {
            let _ = writeln!(
                out,
                "    if e == {} {{\n        {}\n    }} else {{\n        0\n    }}\n}}\n",
                constants[*i],
                lookup_expr(arms)
            );
        }
        _ => {
            let _ = writeln!(out, "    match e {{");
            for (i, arms) in &lookups {
                let ret = if pla { "return " } else { "" };
                let _ = writeln!(
                    out,
                    "        {} => {ret}{},",
                    constants[*i],
                    lookup_expr(arms)
                );
            }
            if pla {
                let _ = writeln!(out, "        _ => {{}}\n    }}");
            } else {
                // The other events have no terms: ω is 0 there.
                let _ = writeln!(out, "        _ => 0,\n    }}\n}}\n");
            }
        }
    }
    if !lookups.is_empty() && !pla {
        // Every event moves by state code: the function is written.
    } else if !pla {
        let _ = writeln!(out, "    let _ = (q, e);\n    0\n}}\n");
    } else {
        if lookups.is_empty() && !moves.iter().flatten().any(|t| t.0 != 0) {
            let _ = writeln!(out, "    let _ = q;");
        }
        let _ = writeln!(out, "    let mut w = 0;");
        write_arms(
            &mut out,
            moves
                .iter()
                .zip(&constants)
                .map(|(t, c)| (c.as_str(), t.clone())),
        );
        let _ = writeln!(out, "    w\n}}\n");
    }

    // Both, as the executor wants them. φ as a sum of products while its
    // functions are small, as its row by state code once one has more
    // terms than a move may evaluate.
    let by_row = logic
        .defined_covers()
        .iter()
        .any(|phi| phi.cubes.len() > lookup_above);
    let (defined, how) = if by_row {
        (
            format!("{prefix}_enabled(q, e, 1) != 0"),
            format!(
                "\n/// φ read from its row by state code (`_enabled`): some φ has more than\n\
                 /// {lookup_above} terms."
            ),
        )
    } else {
        (format!("{prefix}_defined(q, e)"), String::new())
    };
    let _ = writeln!(
        out,
        "/// `{prefix}`: the code reached from `q` on local event `e`, `None` when the\n\
         /// event is not defined there.{how}"
    );
    let _ = writeln!(
        out,
        "pub fn {prefix}_step(q: u32, e: u16) -> Option<u32> {{\n    \
         if {defined} {{\n        \
         Some({prefix}_move(q, e))\n    \
         }} else {{\n        \
         None\n    \
         }}\n\
         }}\n}}"
    );
    out
}

/// The statements adding each event's terms to `w` in the body of a
/// function of `q` and `e`, from `(event constant, terms)` pairs: events
/// whose terms are alike share an arm, an arm of one term is a guard, and
/// a lone event an `if` (as clippy would have them).
fn write_arms<'a>(out: &mut String, events: impl Iterator<Item = (&'a str, Vec<Term>)>) {
    let mut arms: Vec<(Vec<&str>, Vec<Term>)> = Vec::new();
    for (constant, terms) in events {
        if terms.is_empty() {
            continue;
        }
        match arms.iter_mut().find(|(_, t)| *t == terms) {
            Some((names, _)) => names.push(constant),
            None => arms.push((vec![constant], terms)),
        }
    }
    match arms.as_slice() {
        [] => {
            let _ = writeln!(out, "    let _ = e;");
        }
        [(names, terms)] if names.len() == 1 => {
            let name = names[0];
            match terms.as_slice() {
                [(mask, value, bits)] if *mask != 0 => {
                    let _ = writeln!(
                        out,
                        "    if e == {name} && q & {mask:#x} == {value:#x} {{\n        w |= {bits:#x};\n    }}"
                    );
                }
                _ => {
                    let _ = writeln!(
                        out,
                        "    if e == {name} {{\n{}    }}",
                        pla_body(terms, "w", "        ")
                    );
                }
            }
        }
        _ => {
            let _ = writeln!(out, "    match e {{");
            for (names, terms) in &arms {
                let names = names.join(" | ");
                match terms.as_slice() {
                    [(mask, value, bits)] if *mask != 0 => {
                        let _ = writeln!(
                            out,
                            "        {names} if q & {mask:#x} == {value:#x} => w |= {bits:#x},"
                        );
                    }
                    [(0, _, bits)] => {
                        let _ = writeln!(out, "        {names} => w |= {bits:#x},");
                    }
                    _ => {
                        let _ = writeln!(
                            out,
                            "        {names} => {{\n{}        }}",
                            pla_body(terms, "w", "            ")
                        );
                    }
                }
            }
            let _ = writeln!(out, "        _ => {{}}\n    }}");
        }
    }
}

/// An event's moves by state code: `(codes, target)`, the codes it leaves
/// for `target`, in increasing order of their first code.
type Lookup = Vec<(Vec<u32>, u32)>;

/// A product term of a PLA over the code bits: `(mask, value, outputs)`,
/// 1 where `q & mask == value`, setting the bits `outputs`.
type Term = (u32, u32, u32);

/// The statements of a PLA over the code bits `q` adding to the variable
/// `var`, indented by `indent`: one `if` per term `(mask, value, bits)`
/// (a term without literals sets its bits outright).
fn pla_body(terms: &[Term], var: &str, indent: &str) -> String {
    let mut out = String::new();
    for &(mask, value, bits) in terms {
        if mask == 0 {
            let _ = writeln!(out, "{indent}{var} |= {bits:#x};");
        } else {
            let _ = writeln!(
                out,
                "{indent}if q & {mask:#x} == {value:#x} {{\n{indent}    {var} |= {bits:#x};\n{indent}}}"
            );
        }
    }
    out
}

/// The doc comment of a supervisor's module: what it is, its state codes
/// and reset code, and the transitions of the first states (read off the
/// equations, which verification proved equal to the automaton).
fn module_doc(out: &mut String, logic: &LogicSupervisor, names: &Names<'_>) {
    let l = usize::from(logic.bits());
    let origin = if names.origin.is_empty() {
        String::new()
    } else {
        format!(" ({})", one_line(names.origin))
    };
    let _ = writeln!(
        out,
        "/// Supervisor {}{origin} as a CMSSM (Leduc–Wonham), minimised with Espresso.\n///",
        quoted(names.supervisor)
    );
    let reset = logic.initial_code().map_or_else(String::new, |c| {
        format!(", reset code {}", code_literal(c, l))
    });
    let _ = writeln!(
        out,
        "/// State codes ({l} bits{reset}) and the transitions of the first states:"
    );
    let encoding = logic.encoding();
    for (s, &code) in encoding.codes().iter().enumerate().take(DOC_ROWS) {
        let moves: Vec<String> = (0..logic.events())
            .filter_map(|i| {
                let target = logic.next_state(code, i as u16)?;
                let t = encoding.state_of(target)?;
                Some(format!(
                    "{} → {}",
                    names.event(i),
                    names.state(t.0 as usize)
                ))
            })
            .collect();
        let moves = if moves.is_empty() {
            "(no transitions)".to_owned()
        } else {
            doc_text(&moves.join(", "))
        };
        let _ = writeln!(
            out,
            "/// - {} {}: {moves}",
            code_literal(code, l),
            quoted(&names.state(s))
        );
    }
    if encoding.len() > DOC_ROWS {
        let _ = writeln!(out, "/// - … {} more states", encoding.len() - DOC_ROWS);
    }
}

/// The equations of `logic` in mathematical notation, one per line
/// (`ω_b = …` then `φ_i = …`), with event names from `event_names` (local
/// order; missing names print as `e<i>`). For reports and logs.
pub fn equations(logic: &LogicSupervisor, event_names: &[&str]) -> String {
    let event = |i: usize| {
        event_names
            .get(i)
            .map_or_else(|| format!("e{i}"), |s| doc_text(s))
    };
    let cube = |c: &Cube| {
        let mut lits = Vec::new();
        for b in (0..logic.bits()).rev() {
            if c.state_mask >> b & 1 == 1 {
                let neg = if c.state_value >> b & 1 == 1 {
                    ""
                } else {
                    "¬"
                };
                lits.push(format!("{neg}q{b}"));
            }
        }
        for i in 0..logic.events() {
            if c.events_on >> i & 1 == 1 {
                lits.push(event(i));
            }
        }
        for i in 0..logic.events() {
            if c.events_off >> i & 1 == 1 {
                lits.push(format!("¬{}", event(i)));
            }
        }
        if lits.is_empty() {
            "1".to_owned()
        } else {
            lits.join(" ∧ ")
        }
    };
    let sum = |c: &Cover| {
        if c.cubes.is_empty() {
            return "0".to_owned();
        }
        let terms: Vec<String> = c.cubes.iter().map(cube).collect();
        if terms.len() == 1 {
            terms.into_iter().next().unwrap_or_default()
        } else {
            terms
                .iter()
                .map(|t| {
                    if t.contains(' ') {
                        format!("({t})")
                    } else {
                        t.clone()
                    }
                })
                .collect::<Vec<_>>()
                .join(" ∨ ")
        }
    };
    let mut out = String::new();
    for (b, w) in logic.next_covers().iter().enumerate().rev() {
        let _ = writeln!(out, "ω{b} = {}", sum(w));
    }
    for (i, phi) in logic.defined_covers().iter().enumerate() {
        let _ = writeln!(out, "φ{i} = {}  [{}]", sum(phi), event(i));
    }
    out
}

impl Emitter<'_> {
    /// `pub mod logic` with one [`supervisor_module`] per supervisor,
    /// `IMAGE_CRC` and the `Logic` program.
    pub(super) fn logic(
        &mut self,
        logic: &[LogicSupervisor],
        crc: u32,
        crc_doc: &str,
    ) -> Vec<SupervisorStats> {
        let mut stats = Vec::new();
        let mut arms = Vec::new();
        let mut enabled_arms = Vec::new();
        let _ = writeln!(
            self.out,
            "/// The supervisors as CMSSM next-state (`_next`) and enable (`_defined`) functions.\npub mod logic {{"
        );
        for (j, (sup, l)) in self.project.supervisors.iter().zip(logic).enumerate() {
            let fn_name = supervisor_item(&sup.name);
            let events: Vec<&str> = sup
                .local_events
                .iter()
                .map(|&(g, _)| self.project.events[g].name.as_str())
                .collect();
            let states: Vec<String> = sup
                .automaton
                .states()
                .map(|s| sup.automaton.state_name(s).into_owned())
                .collect();
            let states: Vec<&str> = states.iter().map(String::as_str).collect();
            let origin = self.source_line(j);
            let names = Names {
                supervisor: &sup.name,
                origin: &origin,
                events: &events,
                states: &states,
            };
            self.out.push_str(&supervisor_module(l, &names));
            self.out.push('\n');
            arms.push(format!(
                "{} => logic::{fn_name}::{fn_name}_step(state, local),",
                self.supervisor(j as ex::Index)
            ));
            enabled_arms.push(format!(
                "{} => logic::{fn_name}::{fn_name}_enabled(state, from, len),",
                self.supervisor(j as ex::Index)
            ));
            let sizes = l.sizes();
            stats.push(SupervisorStats {
                name: sup.name.clone(),
                states: sup.automaton.num_states() as u32,
                events: events.len() as u16,
                layout: None,
                table_bytes: 0,
                naive_bytes: 2 * sup.automaton.num_states() * events.len(),
                cubes: sizes.cubes,
                literals: sizes.literals,
                logic_effort: Some((l.effort(), logic::effort_limit(sup.max_logic_effort))),
            });
        }
        let _ = writeln!(self.out, "}}");
        let _ = writeln!(
            self.out,
            "{crc_doc}\n#[allow(dead_code)]\npub const IMAGE_CRC: u32 = {crc:#010x};\n/// The program's data: the configuration above, and the supervisors as\n/// minimised boolean functions (`executor::compiled`).\n#[allow(dead_code)]\npub struct Logic;\nimpl ProgramData for Logic {{\n    const CONFIG: Config<'static> = CONFIG;\n    const IMAGE_CRC: u32 = IMAGE_CRC;\n    fn next_state(supervisor: Index, state: u32, local: Index) -> Option<u32> {{\n        match supervisor {{ {} _ => None }}\n    }}\n    fn enabled(supervisor: Index, state: u32, from: Index, len: u8) -> u32 {{\n        match supervisor {{ {} _ => 0 }}\n    }}\n}}\n/// The program: run it with `executor::Controller::new(&PROGRAM, Memory::new())`.\n#[allow(dead_code)]\npub static PROGRAM: Compiled<Logic> = Compiled::new();",
            arms.join("\n"),
            enabled_arms.join("\n")
        );
        stats
    }
}

#[cfg(all(test, feature = "espresso"))]
mod tests {
    use super::*;
    use crate::backend::logic::Encoding;
    use des::automaton::Automaton;
    use des::testing::auto;
    use des::EventId;

    fn ids(a: &Automaton, names: &[&str]) -> Vec<EventId> {
        names.iter().map(|n| a.alphabet().id(n).unwrap()).collect()
    }

    /// sup_crane1 of Leduc–Wonham (see the backend's tests), binary
    /// encoded: idle (state 0) 0b00, train1 0b01, train2 0b10.
    fn crane() -> (LogicSupervisor, [&'static str; 6], [&'static str; 3]) {
        let events = ["t1_at13", "t2_at13", "f_ld1", "st_ld1", "run_t1", "run_t2"];
        let a = auto(
            "sup_crane1",
            &[
                ("t1_at13", false),
                ("t2_at13", false),
                ("f_ld1", false),
                ("st_ld1", true),
                ("run_t1", true),
                ("run_t2", true),
            ],
            &[
                ("0", "t1_at13", "1"),
                ("0", "t2_at13", "2"),
                ("1", "f_ld1", "0"),
                ("2", "f_ld1", "0"),
                ("1", "st_ld1", "1"),
                ("2", "st_ld1", "2"),
                ("0", "run_t1", "0"),
                ("2", "run_t1", "2"),
                ("0", "run_t2", "0"),
                ("1", "run_t2", "1"),
            ],
            &["0"],
        );
        let logic =
            LogicSupervisor::synthesize(&a, &ids(&a, &events), Encoding::binary(3)).unwrap();
        (logic, events, ["idle", "train1", "train2"])
    }

    #[test]
    fn every_explanation_is_a_doc_comment_and_survives_layout() {
        let (logic, events, states) = crane();
        let names = Names {
            supervisor: "sup_crane1",
            origin: "from `crane.toml`",
            events: &events,
            states: &states,
        };
        let written = supervisor_module(&logic, &names);
        let laid_out = crate::emit::format_rust(&written).unwrap();
        println!("{laid_out}");
        let kept: HashSet<&str> = laid_out.lines().map(str::trim).collect();
        for line in written.lines().map(str::trim) {
            if line.starts_with("///") {
                assert!(kept.contains(line), "`{line}` lost in layout");
            } else {
                assert!(
                    !line.contains("//"),
                    "plain comment `{line}` is dropped by layout"
                );
            }
        }
        // What the old `//` comments said: codes, reset code, event indices.
        for expected in [
            "/// Supervisor `sup_crane1` (from `crane.toml`) as a CMSSM (Leduc–Wonham), minimised with Espresso.",
            "/// State codes (2 bits, reset code 0b00) and the transitions of the first states:",
            "/// - 0b00 `idle`: t1_at13 → train1, t2_at13 → train2, run_t1 → idle, run_t2 → idle",
            "/// - 0b01 `train1`: f_ld1 → idle, st_ld1 → train1, run_t2 → train1",
            "/// - 0b10 `train2`: f_ld1 → idle, st_ld1 → train2, run_t1 → train2",
            "/// Local event 2: `f_ld1`.",
            "pub const F_LD1: u16 = 2;",
        ] {
            assert!(kept.contains(expected), "missing `{expected}` in\n{laid_out}");
        }
        // Ω's arms: one per event with terms of its own (events alike
        // sharing one), a term alone as a guard.
        assert!(
            laid_out
                .lines()
                .any(|l| l.contains(" if q & ") && l.contains("=> w |=")),
            "no Ω arm in\n{laid_out}"
        );
        // φ is matched on the named events, one arm per local event.
        let arms: Vec<&str> = laid_out
            .lines()
            .map(str::trim)
            .filter(|l| {
                l.contains(" => ") && !l.ends_with('{') && !l.contains("w |=") && *l != "_ => {}"
            })
            .take(7)
            .collect();
        assert_eq!(arms.last(), Some(&"_ => false,"), "{arms:?}");
        for (arm, event) in arms.iter().zip(events) {
            assert!(arm.starts_with(&event.to_ascii_uppercase()), "{arm}");
        }
    }

    /// Found by the names property (`tests/build_names.rs`): an event named
    /// `1` gave the wire `_1` and the constant `_1`, the same identifier,
    /// so `let _1 = e == _1;` did not compile. Ω no longer binds wires (its
    /// arms match the constants), but the constants stay distinct.
    #[test]
    fn events_without_letters_get_distinct_constants() {
        let a = auto(
            "digits",
            &[("1", true), ("e_1", false), ("007", false)],
            &[("0", "1", "1"), ("1", "e_1", "0"), ("1", "007", "0")],
            &[],
        );
        let events = ["1", "e_1", "007"];
        let logic =
            LogicSupervisor::synthesize(&a, &ids(&a, &events), Encoding::binary(2)).unwrap();
        let names = Names {
            supervisor: "digits",
            origin: "",
            events: &events,
            states: &["idle", "busy"],
        };
        let code = supervisor_module(&logic, &names);
        for line in [
            "pub const E_1: u16 = 0;",
            "pub const E_1_2: u16 = 1;",
            "pub const E_007: u16 = 2;",
        ] {
            assert!(code.contains(line), "{line}\n{code}");
        }
        syn::parse_file(&code).unwrap();
    }

    #[test]
    fn names_are_sanitised_and_cannot_inject_code() {
        let mut taken = HashSet::new();
        assert_eq!(unique("a".into(), &mut taken), "a");
        assert_eq!(unique("a".into(), &mut taken), "a_2");

        let a = auto(
            "evil",
            &[
                ("x\n}fn pwn(){", true),
                ("X }fn pwn(){", false),
                ("q", true),
                ("break", true),
            ],
            &[
                ("0", "x\n}fn pwn(){", "1"),
                ("1", "X }fn pwn(){", "0"),
                ("1", "q", "2"),
                ("2", "break", "0"),
            ],
            &[],
        );
        let events = ["x\n}fn pwn(){", "X }fn pwn(){", "q", "break"];
        let logic =
            LogicSupervisor::synthesize(&a, &ids(&a, &events), Encoding::binary(3)).unwrap();
        let names = Names {
            supervisor: "sup\n}evil",
            origin: "",
            events: &events,
            states: &["a\r\nb", "*/`", "ok"],
        };
        let code = supervisor_module(&logic, &names);
        let file = syn::parse_file(&code).unwrap();
        let [syn::Item::Mod(module)] = &file.items[..] else {
            panic!("one module expected:\n{code}");
        };
        assert_eq!(module.ident, "sup_sup__evil");
        let items: Vec<String> = module
            .content
            .as_ref()
            .unwrap()
            .1
            .iter()
            .map(|item| match item {
                syn::Item::Fn(f) => f.sig.ident.to_string(),
                syn::Item::Const(c) => c.ident.to_string(),
                _ => panic!("unexpected item"),
            })
            .collect();
        assert_eq!(
            items,
            [
                "X__FN_PWN___",
                "X__FN_PWN____2",
                "Q_2",
                "BREAK_",
                "sup_sup__evil_next",
                "sup_sup__evil_defined",
                "sup_sup__evil_enabled",
                "sup_sup__evil_move",
                "sup_sup__evil_step"
            ]
        );
        assert!(code.contains("pub const Q_2: u16 = 2;"), "{code}");
        assert!(code.contains("let mut w = 0;"), "{code}");
        // Names in doc comments stay on their line and out of code spans.
        assert!(
            code.contains("/// - 0b00 `a  b`: x }fn pwn(){ → */'\n"),
            "{code}"
        );
    }

    #[test]
    fn constant_functions_are_literals() {
        // One state, a self-loop and an event never defined: ω0 = 0 (no
        // term at all), φ of `a` = 1, φ of `b` = 0.
        let a = auto("one", &[("a", true), ("b", false)], &[("0", "a", "0")], &[]);
        let events = ["a", "b"];
        let logic =
            LogicSupervisor::synthesize(&a, &ids(&a, &events), Encoding::binary(1)).unwrap();
        let names = Names {
            supervisor: "one",
            origin: "",
            events: &events,
            states: &["0"],
        };
        let code = crate::emit::format_rust(&supervisor_module(&logic, &names)).unwrap();
        for expected in ["let _ = (q, e);", "A => true,", "B => false,"] {
            assert!(code.contains(expected), "missing `{expected}` in\n{code}");
        }
    }

    #[test]
    fn equations_read_as_the_paper_writes_them() {
        let (logic, events, _) = crane();
        let text = equations(&logic, &events);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2 + 6, "{text}");
        assert!(lines[0].starts_with("ω1 = "), "{text}");
        assert!(lines[1].starts_with("ω0 = "), "{text}");
        assert_eq!(lines[6], "φ4 = ¬q0  [run_t1]", "{text}");
        assert_eq!(lines[7], "φ5 = ¬q1  [run_t2]", "{text}");
    }

    /// Writes `src` to `dir/name.rs` and compiles it with rustc.
    fn rustc(dir: &std::path::Path, name: &str, src: &str, args: &[&str]) -> std::path::PathBuf {
        let path = dir.join(format!("{name}.rs"));
        std::fs::write(&path, src).unwrap();
        let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
        let out = std::process::Command::new(rustc)
            .args(["--edition", "2021", "-D", "warnings", "--crate-name", name])
            .args(args)
            .arg("-o")
            .arg(dir.join(name))
            .arg(&path)
            .output()
            .expect("rustc runs");
        assert!(
            out.status.success(),
            "rustc failed on\n{src}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        dir.join(name)
    }

    #[test]
    fn the_module_compiles_no_std_and_agrees_with_next_state() {
        // MACH1 plus a buffer: four states (one unused code), events with
        // awkward names.
        let a = auto(
            "Mach 1",
            &[
                ("start", true),
                ("finish", false),
                ("break", false),
                ("repair", true),
                ("e", true),
            ],
            &[
                ("0", "start", "1"),
                ("1", "finish", "0"),
                ("1", "break", "2"),
                ("2", "repair", "0"),
                ("0", "e", "3"),
                ("3", "e", "3"),
                ("3", "finish", "2"),
            ],
            &[],
        );
        let events = ["start", "finish", "break", "repair", "e"];
        let logic =
            LogicSupervisor::synthesize(&a, &ids(&a, &events), Encoding::binary(4)).unwrap();
        let names = Names {
            supervisor: a.name(),
            origin: "",
            events: &events,
            states: &["idle", "working", "down", "other"],
        };
        // As written, and with every event moved by state code.
        for lookup_above in [MOVE_TERMS_MAX, 0] {
            agrees(&logic, &names, &events, lookup_above);
        }
    }

    /// Compiles the module of `logic` with `lookup_above` no_std and as a
    /// program printing `_step`, `_next` and `_enabled` for every code and
    /// event; what it prints is what `logic` computes.
    fn agrees(logic: &LogicSupervisor, names: &Names<'_>, events: &[&str], lookup_above: usize) {
        let code = module_with(logic, names, lookup_above);
        println!("{code}");
        if lookup_above == 0 {
            assert!(code.contains("match q {"), "{code}");
        }
        let dir = tempfile::tempdir().unwrap();

        // As a no_std, unsafe-free library.
        let lib = format!("#![no_std]\n#![forbid(unsafe_code)]\n{code}");
        rustc(dir.path(), "emitted_lib", &lib, &["--crate-type", "lib"]);

        // As a program printing every (code, event) pair.
        let main = format!(
            "{code}\nfn main() {{\n    for q in 0..4u32 {{\n        for e in 0..6u16 {{\n            \
             println!(\"{{q}} {{e}} {{:?}} {{}}\", sup_mach_1::sup_mach_1_step(q, e), sup_mach_1::sup_mach_1_next(q, e));\n        \
             }}\n        \
             for (from, len) in [(0, 0), (0, 5), (0, 32), (1, 3), (3, 32), (5, 1), (40, 32)] {{\n            \
             println!(\"{{q}} row {{from}} {{len}} {{:#b}}\", sup_mach_1::sup_mach_1_enabled(q, from, len));\n        \
             }}\n    }}\n}}\n"
        );
        let exe = rustc(dir.path(), "emitted_main", &main, &[]);
        let out = std::process::Command::new(exe).output().unwrap();
        assert!(out.status.success());
        let printed = String::from_utf8(out.stdout).unwrap();
        let mut expected = String::new();
        for q in 0..4u32 {
            for e in 0..6u16 {
                let input = (usize::from(e) < events.len()).then_some(e);
                let _ = writeln!(
                    expected,
                    "{q} {e} {:?} {}",
                    logic.next_state(q, e),
                    logic.next_code(q, input)
                );
            }
            for (from, len) in [
                (0u16, 0u8),
                (0, 5),
                (0, 32),
                (1, 3),
                (3, 32),
                (5, 1),
                (40, 32),
            ] {
                let row = (0..u16::from(len))
                    .filter(|&k| {
                        let e = from + k;
                        usize::from(e) < events.len() && logic.is_defined(q, e)
                    })
                    .fold(0u32, |row, k| row | 1 << k);
                let _ = writeln!(expected, "{q} row {from} {len} {row:#b}");
            }
        }
        assert_eq!(printed, expected);
    }
}
