//! Place-invariant synthesis on random nets: whenever it accepts a
//! constraint `L·m ≤ b`, the controlled net keeps the invariant
//! `L·m_p + m_c = b` in every reachable marking, and it is exactly as
//! permissive as the constraint: its reachable plant markings are those
//! the plant reaches along firing sequences that never leave `L·m ≤ b`
//! (admissibility means no uncontrollable transition ever raises `L·m`,
//! so none needs to be blocked), which is also supcon's language on the
//! reachability graph with the constraint as specification. Refusals are
//! checked against the definition too.

use des::petri::compare;
use des::petri::constraints::{self, Constraint};
use des::petri::synth::synthesize;
use des::petri::{reach, read_str, Marking, NetFormat, PetriNet};
use proptest::prelude::*;
use std::collections::{HashSet, VecDeque};
use std::fmt::Write as _;
use std::path::Path;

/// A conservative net (each transition moves as many tokens as it
/// takes, so the net is bounded): `places` places with random tokens,
/// transitions with one or two input and as many output places.
#[derive(Debug, Clone)]
struct RandomNet {
    tokens: Vec<u32>,
    /// (controllable, inputs, outputs) by place index.
    transitions: Vec<(bool, Vec<usize>, Vec<usize>)>,
}

impl RandomNet {
    fn text(&self) -> String {
        let mut t = String::from("name = \"random\"\nplaces = [\n");
        for (p, k) in self.tokens.iter().enumerate() {
            let _ = writeln!(t, "  {{ id = \"p{p}\", tokens = {k} }},");
        }
        t.push_str("]\ntransitions = [\n");
        for (i, (controllable, input, output)) in self.transitions.iter().enumerate() {
            let arcs = |places: &[usize]| {
                // A place listed twice is one arc of weight 2.
                let mut weights: Vec<(usize, u32)> = Vec::new();
                for &p in places {
                    match weights.iter_mut().find(|(q, _)| *q == p) {
                        Some((_, w)) => *w += 1,
                        None => weights.push((p, 1)),
                    }
                }
                weights
                    .iter()
                    .map(|(p, w)| format!("p{p} = {w}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let _ = writeln!(
                t,
                "  {{ id = \"t{i}\", controllable = {controllable}, input = {{ {} }}, output = {{ {} }} }},",
                arcs(input),
                arcs(output)
            );
        }
        t.push_str("]\n");
        t
    }

    fn net(&self) -> PetriNet {
        read_str(&self.text(), NetFormat::Toml, Path::new("random.toml")).unwrap()
    }
}

fn random_net() -> impl Strategy<Value = RandomNet> {
    (3usize..7).prop_flat_map(|places| {
        let transition = (prop::bool::weighted(0.75), 1usize..3).prop_flat_map(move |(c, n)| {
            (
                Just(c),
                prop::collection::vec(0..places, n),
                prop::collection::vec(0..places, n),
            )
        });
        (
            prop::collection::vec(0u32..3, places),
            prop::collection::vec(transition, 2..6),
        )
            .prop_map(|(tokens, transitions)| RandomNet {
                tokens,
                transitions,
            })
    })
}

/// A constraint over one or two places with weights 1 or 2, and a bound
/// 0 or 1 above the initial value (or 1 below it, to test refusals).
fn random_constraint(net: &PetriNet, seed: (usize, usize, i64, i64, i64)) -> String {
    let places = net.places().len();
    let (a, b, wa, wb, slack) = seed;
    let (a, b) = (a % places, b % places);
    let mut text = format!("[[constraint]]\nname = \"k\"\nweights = {{ p{a} = {wa}");
    if b != a {
        let _ = write!(text, ", p{b} = {wb}");
    }
    let weights: Vec<(usize, i64)> = if b != a {
        vec![(a, wa), (b, wb)]
    } else {
        vec![(a, wa)]
    };
    let initial: i64 = weights
        .iter()
        .map(|&(p, w)| w * i64::from(net.initial()[p]))
        .sum();
    let _ = write!(text, " }}\nbound = {}\n", initial + slack);
    text
}

/// The plant markings reachable along firing sequences that stay within
/// `c`.
fn within(net: &PetriNet, c: &Constraint) -> HashSet<Marking> {
    let mut seen = HashSet::new();
    let mut queue = VecDeque::new();
    if c.weighted(net.initial()) <= i128::from(c.bound) {
        seen.insert(net.initial().clone());
        queue.push_back(net.initial().clone());
    }
    while let Some(m) = queue.pop_front() {
        for t in 0..net.transitions().len() {
            if let Some(next) = net.fire(&m, t) {
                if c.weighted(&next) <= i128::from(c.bound) && seen.insert(next.clone()) {
                    queue.push_back(next);
                }
            }
        }
    }
    seen
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    #[test]
    fn an_accepted_constraint_holds_as_an_invariant_and_is_enforced_exactly(
        random in random_net(),
        seed in (0usize..7, 0usize..7, 1i64..3, 1i64..3, -1i64..2),
    ) {
        let net = random.net();
        let text = random_constraint(&net, seed);
        let cs = constraints::read(&text, Path::new("c.toml"), &net).unwrap();
        let c = &cs[0];
        let d = net.incidence();
        let row: Vec<i64> = (0..net.transitions().len())
            .map(|t| -c.weights.iter().map(|&(p, w)| w * d[p][t]).sum::<i64>())
            .collect();
        let violated = c.weighted(net.initial()) > i128::from(c.bound);
        let inadmissible = net
            .transitions()
            .iter()
            .zip(&row)
            .any(|(t, &w)| !t.controllable && w < 0);
        match synthesize(&net, &cs) {
            Err(e) => {
                // Refused exactly when the definition says so.
                prop_assert!(violated || inadmissible, "refused without cause: {e}\n{}{text}", random.text());
            }
            Ok(s) => {
                prop_assert!(!violated && !inadmissible, "accepted:\n{}{text}", random.text());
                prop_assert_eq!(&s.control[0].incidence, &row);
                let plant_places = net.places().len();
                let r = reach::reachability(&s.net, 100_000).unwrap();
                let mut reached = HashSet::new();
                for m in &r.markings {
                    let (plant, control) = m.split_at(plant_places);
                    prop_assert_eq!(
                        c.weighted(plant) + i128::from(control[0]),
                        i128::from(c.bound),
                        "invariant broken in {}", s.net.marking_name(m)
                    );
                    reached.insert(plant.to_vec());
                }
                prop_assert_eq!(reached, within(&net, c), "not exactly the constraint:\n{}{}", random.text(), text);
                // And it is supcon's language on the reachability graph.
                let cmp = compare::against_supcon(&net, &cs, &s, 100_000).unwrap().unwrap();
                prop_assert!(cmp.difference.is_none(), "differs from supcon: {:?}\n{}{}", cmp.difference, random.text(), text);
                prop_assert_eq!(cmp.controlled_states, cmp.supcon_states);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Every minimal P-semiflow found is one (`yᵀ·D = 0`, `y ≥ 0`), keeps
    /// `y·m` over every reachable marking, and no other's support lies
    /// within its own; likewise every T-semiflow solves `D·x = 0`.
    #[test]
    fn semiflows_are_invariants_and_minimal(random in random_net()) {
        use des::petri::invariants::{place_invariants, transition_invariants};
        let net = random.net();
        let d = net.incidence();
        let ps = place_invariants(&net).unwrap();
        let r = reach::reachability(&net, 100_000).unwrap();
        for y in &ps {
            for (t, _) in net.transitions().iter().enumerate() {
                let sum: i128 = y.iter().map(|&(p, w)| w as i128 * i128::from(d[p][t])).sum();
                prop_assert_eq!(sum, 0, "{:?} on t{}\n{}", y, t, random.text());
            }
            let value = |m: &[u32]| -> u128 { y.iter().map(|&(p, w)| w * u128::from(m[p])).sum() };
            for m in &r.markings {
                prop_assert_eq!(value(m), value(net.initial()));
            }
        }
        for (i, a) in ps.iter().enumerate() {
            for (k, b) in ps.iter().enumerate() {
                let within = b.iter().all(|&(p, _)| a.iter().any(|&(q, _)| q == p));
                prop_assert!(i == k || !within, "{:?} within {:?}", b, a);
            }
        }
        // A conservative net keeps its token count: the all-ones vector is
        // an invariant, so some semiflow exists.
        prop_assert!(!ps.is_empty());
        for x in transition_invariants(&net).unwrap() {
            for row in &d {
                let sum: i128 = x.iter().map(|&(t, w)| w as i128 * i128::from(row[t])).sum();
                prop_assert_eq!(sum, 0);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// An inadmissible constraint made admissible is enforced safely: the
    /// controlled net never breaks the original constraint, and it allows
    /// nothing supcon (the supremal controllable behaviour within the
    /// original constraint) forbids; it may allow less.
    #[test]
    fn an_admissible_form_is_safe_and_never_beyond_supcon(
        random in random_net(),
        seed in (0usize..7, 0usize..7, 1i64..3, 1i64..3, 0i64..2),
    ) {
        use des::petri::admissible::make_admissible;
        let net = random.net();
        let text = random_constraint(&net, seed);
        let cs = constraints::read(&text, Path::new("c.toml"), &net).unwrap();
        let Ok(admissible) = make_admissible(&net, &cs[0]) else {
            return Ok(());
        };
        let s = synthesize(&net, std::slice::from_ref(&admissible)).unwrap();
        let r = reach::reachability(&s.net, 100_000).unwrap();
        let plant_places = net.places().len();
        for m in &r.markings {
            prop_assert!(cs[0].weighted(&m[..plant_places]) <= i128::from(cs[0].bound));
        }
        let cmp = compare::against_supcon(&net, &cs, &s, 100_000).unwrap().unwrap();
        if let Some(d) = cmp.difference {
            prop_assert!(!d.in_first, "beyond supcon: {:?}\n{}{}", d.string, random.text(), text);
        }
    }
}
