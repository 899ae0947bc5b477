//! Petri-net arithmetic at the edges of its types: arc weights and
//! tokens near `u32::MAX` and 2^31, constraint weights and bounds near
//! `i64::MIN`/`i64::MAX`, 2^62, 2^32 and `i32`'s limits. Whatever the
//! input, synthesis, `--transform`, the invariants and the exploration
//! either give a correct result (checked here exactly, in `i128` or
//! modulo primes whose product exceeds every sum) or refuse it; never a
//! wrapped value, never a panic.

use des::petri::admissible::make_admissible;
use des::petri::constraints;
use des::petri::invariants::{place_invariants, transition_invariants, value};
use des::petri::reach::{explore, Beyond, Limits, Marked, Region};
use des::petri::synth::synthesize;
use des::petri::{read_str, NetFormat, PetriNet};
use proptest::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

const U32_EDGES: [u32; 9] = [
    1,
    2,
    3,
    (1 << 31) - 1,
    1 << 31,
    (1 << 31) + 1,
    u32::MAX - 1,
    u32::MAX,
    65_536,
];

const I64_EDGES: [i64; 16] = [
    1,
    -1,
    2,
    -2,
    i32::MAX as i64,
    i32::MIN as i64,
    u32::MAX as i64,
    -(u32::MAX as i64),
    1 << 32,
    1 << 62,
    -(1 << 62),
    (1 << 62) + 1,
    i64::MAX,
    i64::MAX - 1,
    i64::MIN,
    i64::MIN + 1,
];

fn u32_near_limits() -> impl Strategy<Value = u32> {
    prop_oneof![
        prop::sample::select(&U32_EDGES[..]),
        1u32..5,
        any::<u32>().prop_map(|v| v.max(1)),
    ]
}

fn tokens_near_limits() -> impl Strategy<Value = u32> {
    prop_oneof![Just(0u32), u32_near_limits()]
}

fn i64_near_limits() -> impl Strategy<Value = i64> {
    prop_oneof![prop::sample::select(&I64_EDGES[..]), -3i64..4, any::<i64>(),]
}

/// Arcs of one side of a transition: (place, weight).
type Arcs = Vec<(usize, u32)>;

/// A net of 2–4 places and 1–3 transitions, each with up to two input
/// and two output arcs (distinct places per side), weights near limits.
#[derive(Debug, Clone)]
struct Edgy {
    tokens: Vec<u32>,
    /// (controllable, inputs, outputs): (place, weight).
    transitions: Vec<(bool, Arcs, Arcs)>,
    /// (place, weight) and the bound.
    constraint: (Vec<(usize, i64)>, i64),
}

impl Edgy {
    fn net_text(&self) -> String {
        let mut t = String::from("name = \"edgy\"\nplaces = [\n");
        for (p, k) in self.tokens.iter().enumerate() {
            let _ = writeln!(t, "  {{ id = \"p{p}\", tokens = {k} }},");
        }
        t.push_str("]\ntransitions = [\n");
        for (i, (c, input, output)) in self.transitions.iter().enumerate() {
            let arcs = |arcs: &[(usize, u32)]| {
                arcs.iter()
                    .map(|(p, w)| format!("p{p} = {w}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let _ = writeln!(
                t,
                "  {{ id = \"t{i}\", controllable = {c}, input = {{ {} }}, output = {{ {} }} }},",
                arcs(input),
                arcs(output)
            );
        }
        t.push_str("]\n");
        t
    }

    fn constraint_text(&self) -> String {
        let (weights, bound) = &self.constraint;
        let list: Vec<String> = weights.iter().map(|(p, w)| format!("p{p} = {w}")).collect();
        format!(
            "[[constraint]]\nname = \"edge\"\nweights = {{ {} }}\nbound = {bound}\n",
            list.join(", ")
        )
    }

    fn net(&self) -> PetriNet {
        read_str(&self.net_text(), NetFormat::Toml, Path::new("edgy.toml")).unwrap()
    }
}

fn arcs(places: usize) -> impl Strategy<Value = Vec<(usize, u32)>> {
    prop::collection::btree_map(0..places, u32_near_limits(), 0..3)
        .prop_map(|m| m.into_iter().collect())
}

fn edgy() -> impl Strategy<Value = Edgy> {
    (2usize..5).prop_flat_map(|places| {
        let transition = (prop::bool::weighted(0.7), arcs(places), arcs(places));
        (
            prop::collection::vec(tokens_near_limits(), places),
            prop::collection::vec(transition, 1..4),
            prop::collection::btree_map(0..places, i64_near_limits(), 1..3),
            i64_near_limits(),
        )
            .prop_map(|(tokens, transitions, weights, bound)| Edgy {
                tokens,
                transitions,
                constraint: (weights.into_iter().collect(), bound),
            })
    })
}

/// `Σ y_i · a_i = 0` exactly: checked modulo four primes near 2^61, whose
/// product (above 2^243) exceeds the largest possible |sum| (at most five
/// terms, each below 2^128 · 2^63), so zero modulo all four is zero (the
/// Chinese remainder theorem).
fn sums_to_zero(terms: &[(u128, i64)]) -> bool {
    const PRIMES: [u128; 4] = [
        2_305_843_009_213_693_951,
        2_305_843_009_213_693_921,
        2_305_843_009_213_693_907,
        2_305_843_009_213_693_669,
    ];
    PRIMES.iter().all(|&q| {
        let sum = terms.iter().fold(0u128, |acc, &(y, a)| {
            let a_mod = if a < 0 {
                q - (u128::from(a.unsigned_abs()) % q)
            } else {
                u128::from(a.unsigned_abs()) % q
            };
            (acc + (y % q) * a_mod % q) % q
        });
        sum == 0
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Synthesis is exact or refused: `D_c = −L·D_p` and
    /// `m_c0 = b − L·m_p0`, recomputed here in `i128`, and the control
    /// place's arcs are that row.
    #[test]
    fn control_places_are_exact_or_refused(e in edgy()) {
        let net = e.net();
        let text = e.constraint_text();
        let Ok(cs) = constraints::read(&text, Path::new("c.toml"), &net) else {
            // Only a constraint of zero weights is refused when read.
            prop_assert!(e.constraint.0.iter().all(|&(_, w)| w == 0), "{text}");
            return Ok(());
        };
        let d = net.incidence();
        let l = &cs[0].weights;
        let exact_row: Vec<i128> = (0..net.transitions().len())
            .map(|t| -l.iter().map(|&(p, w)| i128::from(w) * i128::from(d[p][t])).sum::<i128>())
            .collect();
        let exact_initial = i128::from(cs[0].bound)
            - l.iter().map(|&(p, w)| i128::from(w) * i128::from(net.initial()[p])).sum::<i128>();
        match synthesize(&net, &cs) {
            Ok(s) => {
                let c = &s.control[0];
                let row: Vec<i128> = c.incidence.iter().map(|&v| i128::from(v)).collect();
                prop_assert_eq!(&row, &exact_row, "{}{}", e.net_text(), text);
                prop_assert_eq!(i128::from(c.initial), exact_initial);
                let place = net.places().len();
                prop_assert_eq!(s.net.initial()[place], c.initial);
                prop_assert_eq!(s.net.change(0).len(), place + 1);
                for t in 0..net.transitions().len() {
                    prop_assert_eq!(i128::from(s.net.change(t)[place]), exact_row[t]);
                    prop_assert_eq!(&s.net.change(t)[..place], &d.iter().map(|r| r[t]).collect::<Vec<_>>()[..]);
                }
            }
            Err(err) => {
                let msg = err.to_string();
                prop_assert!(msg.starts_with("c.toml:1:1: "), "{msg}");
                let refused_for_cause = exact_initial < 0
                    || exact_initial > i128::from(u32::MAX)
                    || exact_row.iter().any(|&w| w.unsigned_abs() > u128::from(u32::MAX))
                    || net.transitions().iter().zip(&exact_row).any(|(t, &w)| !t.controllable && w < 0);
                prop_assert!(refused_for_cause, "refused without cause: {msg}\n{}{}", e.net_text(), text);
            }
        }
    }

    /// `--transform`'s constraint implies the original (`R1 ≥ 0`), keeps
    /// `i64` weights, no uncontrollable transition raises it, and the
    /// initial marking satisfies it; or it is refused.
    #[test]
    fn an_admissible_form_is_exact_or_refused(e in edgy()) {
        let net = e.net();
        let Ok(cs) = constraints::read(&e.constraint_text(), Path::new("c.toml"), &net) else {
            return Ok(());
        };
        let Ok(a) = make_admissible(&net, &cs[0]) else { return Ok(()) };
        let places = net.places().len();
        let mut original = vec![0i128; places];
        for &(p, w) in &cs[0].weights {
            original[p] = i128::from(w);
        }
        let mut now = vec![0i128; places];
        for &(p, w) in &a.weights {
            now[p] = i128::from(w);
        }
        for p in 0..places {
            prop_assert!(now[p] >= original[p], "R1 ≥ 0 at p{}", p);
        }
        for (t, tr) in net.transitions().iter().enumerate() {
            let raised: i128 = (0..places).map(|p| now[p] * i128::from(net.change(t)[p])).sum();
            prop_assert!(tr.controllable || raised <= 0);
        }
        let at_start: i128 = (0..places).map(|p| now[p] * i128::from(net.initial()[p])).sum();
        prop_assert!(at_start <= i128::from(a.bound));
    }

    /// Invariants are semiflows exactly (`yᵀ·D = 0`, `D·x = 0`), their
    /// values exact or `None`; or the computation is refused.
    #[test]
    fn invariants_are_exact_or_refused(e in edgy()) {
        let net = e.net();
        let d = net.incidence();
        if let Ok(ys) = place_invariants(&net) {
            for y in &ys {
                for t in 0..net.transitions().len() {
                    let column = net.change(t);
                    let terms: Vec<(u128, i64)> = y.iter().map(|&(p, w)| (w, column[p])).collect();
                    prop_assert!(sums_to_zero(&terms), "{:?} on t{}\n{}", y, t, e.net_text());
                }
                if let Some(v) = value(y, net.initial()) {
                    let terms: Vec<(u128, i64)> = y
                        .iter()
                        .map(|&(p, w)| (w, i64::from(net.initial()[p])))
                        .chain([(v, -1)])
                        .collect();
                    prop_assert!(sums_to_zero(&terms));
                }
            }
        }
        if let Ok(xs) = transition_invariants(&net) {
            for x in &xs {
                for row in &d {
                    let terms: Vec<(u128, i64)> = x.iter().map(|&(t, w)| (w, row[t])).collect();
                    prop_assert!(sums_to_zero(&terms));
                }
            }
        }
    }

    /// Exploring a net with token counts near `u32::MAX` stops cleanly:
    /// every marking found is the initial one or a firing of one found.
    #[test]
    fn exploration_at_the_token_limit_is_exact_or_stops(e in edgy()) {
        let net = e.net();
        let Ok(Ok(r)) = explore(&net, Limits::states(64), Marked::Initial, Region::All, Beyond::Drop) else {
            return Ok(());
        };
        prop_assert_eq!(&r.markings[0], net.initial());
        for (k, m) in r.markings.iter().enumerate().skip(1) {
            let sequence = r.firing_sequence(k);
            let mut at = net.initial().clone();
            for t in sequence {
                at = net.fire(&at, t).expect("a firing sequence of the graph fires");
            }
            prop_assert_eq!(&at, m);
        }
    }
}
