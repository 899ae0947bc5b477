//! The symbolic supervisor against `des`'s explicit supcon: same number of
//! states and the same closed and marked languages, on the families and
//! on random modular instances.
//!
//! The closed loop is walked explicitly: plant ∥ specifications, where a
//! controllable event fires only if its guard BDD holds in the current
//! component states. That automaton must be language-equal to
//! `supcon(sync(plants), sync(specs))`.

use des::ops::{self, ComposeOptions, Composition};
use des::{Automaton, AutomatonBuilder, StateId};
use des_symbolic::{families, synthesize, BigUint, Error, Synthesis};
use proptest::prelude::*;
use std::collections::{HashMap, VecDeque};

/// `supcon(sync(plants), sync(specs))` (the plant itself as the
/// specification when there is none).
fn explicit(plants: &[Automaton], specs: &[Automaton]) -> Automaton {
    let compose = |parts: &[Automaton]| -> Automaton {
        let refs: Vec<&Automaton> = parts.iter().collect();
        ops::compose(&refs, Composition::Sync, options())
            .unwrap()
            .automaton
    };
    let plant = compose(plants);
    let spec = if specs.is_empty() {
        plant.clone()
    } else {
        compose(specs)
    };
    ops::supcon_with(&plant, &spec, options()).unwrap()
}

/// No state names, and room for the ignored large instances.
fn options() -> ComposeOptions<'static> {
    ComposeOptions {
        name_states: false,
        max_states: 50_000_000,
        ..ComposeOptions::default()
    }
}

/// The reachable states of plant ∥ specifications, explicitly.
fn explicit_reachable(plants: &[Automaton], specs: &[Automaton]) -> usize {
    let all: Vec<&Automaton> = plants.iter().chain(specs).collect();
    ops::sync(&all).unwrap().num_states()
}

/// Plant ∥ specifications under the symbolic guards, walked explicitly.
fn closed_loop(plants: &[Automaton], specs: &[Automaton], s: &Synthesis) -> Automaton {
    let all: Vec<&Automaton> = plants.iter().chain(specs).collect();
    let mut b = AutomatonBuilder::new("closed loop");
    let events = &s.model.layout().events;
    for e in events {
        b.add_event(&e.name, e.controllable).unwrap();
    }
    if s.is_empty() {
        return b.build().unwrap();
    }
    let initial: Vec<StateId> = all.iter().map(|a| a.initial().unwrap()).collect();
    let name = |t: &[StateId]| {
        t.iter()
            .map(|s| s.0.to_string())
            .collect::<Vec<_>>()
            .join(".")
    };
    let mut seen: HashMap<Vec<StateId>, ()> = HashMap::new();
    let mut queue = VecDeque::from([initial.clone()]);
    seen.insert(initial.clone(), ());
    b.set_initial_by_name(&name(&initial)).unwrap();
    while let Some(t) = queue.pop_front() {
        let here = name(&t);
        b.add_state(&here);
        if all.iter().zip(&t).all(|(a, s)| a.is_marked(*s)) {
            b.mark_by_name(&here);
        }
        'events: for e in events {
            let mut next = t.clone();
            for &c in &e.participants {
                let a = all[c];
                let id = a.alphabet().id(&e.name).unwrap();
                match a.successor(t[c], id) {
                    Some(n) => next[c] = n,
                    None => continue 'events,
                }
            }
            if !s.allows(&e.name, &t).unwrap() {
                continue;
            }
            b.add_transition_by_name(&here, &e.name, &name(&next), 0)
                .unwrap();
            if seen.insert(next.clone(), ()).is_none() {
                queue.push_back(next);
            }
        }
    }
    b.build().unwrap()
}

/// Checks the symbolic result of `plants` ∥ `specs` against des.
fn check(plants: &[Automaton], specs: &[Automaton]) -> Result<(), String> {
    let s = synthesize(plants, specs).map_err(|e| e.to_string())?;
    let sup = explicit(plants, specs);
    let reach = explicit_reachable(plants, specs);
    if s.reachable_states() != BigUint::from(reach) {
        return Err(format!(
            "reachable: symbolic {} explicit {reach}",
            s.reachable_states()
        ));
    }
    if s.supervisor_states() != BigUint::from(sup.num_states()) {
        return Err(format!(
            "supervisor: symbolic {} explicit {}",
            s.supervisor_states(),
            sup.num_states()
        ));
    }
    let cl = closed_loop(plants, specs, &s);
    if cl.num_states() != sup.num_states() {
        return Err(format!(
            "closed loop {} states, supcon {}",
            cl.num_states(),
            sup.num_states()
        ));
    }
    if let Some(d) = ops::language_difference(&cl, &sup) {
        return Err(format!("languages differ: {d:?}"));
    }
    Ok(())
}

#[test]
fn rings_match_supcon() {
    for n in 2..=6 {
        let f = families::ring(n).unwrap();
        check(&f.plants, &f.specs).unwrap_or_else(|e| panic!("{}: {e}", f.name));
    }
}

#[test]
fn rings_with_breakdowns_match_supcon() {
    for n in 2..=5 {
        let f = families::ring_breakdowns(n).unwrap();
        check(&f.plants, &f.specs).unwrap_or_else(|e| panic!("{}: {e}", f.name));
    }
}

#[test]
fn transfer_lines_match_supcon() {
    for n in 2..=4 {
        let f = families::tline(n).unwrap();
        check(&f.plants, &f.specs).unwrap_or_else(|e| panic!("{}: {e}", f.name));
    }
}

#[test]
fn philosophers_match_supcon() {
    for n in 3..=5 {
        let f = families::phil(n).unwrap();
        check(&f.plants, &f.specs).unwrap_or_else(|e| panic!("{}: {e}", f.name));
    }
}

/// The earlier monolithic measurements: ring12 673,596 states, ring13
/// 3,752,892 (the family with breakdowns), explicitly and symbolically.
/// Slow in debug builds: `cargo test --release -p des-symbolic -- --ignored`.
#[test]
#[ignore]
fn ring_with_breakdowns_12_is_the_measured_family() {
    let f = families::ring_breakdowns(12).unwrap();
    let s = synthesize(&f.plants, &f.specs).unwrap();
    assert_eq!(s.supervisor_states(), BigUint::from(673_596u32));
    assert_eq!(explicit(&f.plants, &f.specs).num_states(), 673_596);
    let f = families::ring_breakdowns(13).unwrap();
    let s = synthesize(&f.plants, &f.specs).unwrap();
    assert_eq!(s.supervisor_states(), BigUint::from(3_752_892u32));
}

fn auto(
    name: &str,
    events: &[(&str, bool)],
    trans: &[(&str, &str, &str)],
    marked: &[&str],
) -> Automaton {
    des::testing::auto(name, events, trans, marked)
}

#[test]
fn empty_supervisor() {
    // The plant can do `u` (uncontrollable) at once; the specification
    // never allows it.
    let plant = auto("p", &[("u", false)], &[("0", "u", "1")], &["0", "1"]);
    let spec = auto("e", &[("u", false)], &[], &["0"]);
    let (plants, specs) = ([plant], [spec]);
    let s = synthesize(&plants, &specs).unwrap();
    assert!(s.is_empty());
    assert_eq!(s.supervisor_states(), BigUint::from(0u32));
    assert_eq!(explicit(&plants, &specs).num_states(), 0);
    check(&plants, &specs).unwrap();
}

#[test]
fn blocking_plant_without_marked_states_is_empty() {
    let plant = auto("p", &[("a", true)], &[("0", "a", "1")], &[]);
    let plants = [plant];
    let s = synthesize(&plants, &[]).unwrap();
    assert!(s.is_empty());
    check(&plants, &[]).unwrap();
}

#[test]
fn bad_input_is_an_error() {
    let p = auto("p", &[("a", true)], &[("0", "a", "0")], &["0"]);
    let q = auto("q", &[("a", false)], &[("0", "a", "0")], &["0"]);
    let e = auto("e", &[("b", true)], &[("0", "b", "0")], &["0"]);
    assert!(matches!(
        synthesize(&[p.clone(), q], &[]),
        Err(Error::Controllability { .. })
    ));
    assert!(matches!(
        synthesize(std::slice::from_ref(&p), &[e]),
        Err(Error::SpecEvent { .. })
    ));
    assert!(matches!(synthesize(&[], &[]), Err(Error::NoPlant)));
    assert!(matches!(families::ring(1), Err(Error::FamilySize { .. })));
    let s = synthesize(&[p], &[]).unwrap();
    assert!(matches!(
        s.allows("a", &[StateId(0), StateId(0)]),
        Err(Error::StateTuple(_))
    ));
    assert!(matches!(
        s.allows("a", &[StateId(5)]),
        Err(Error::StateTuple(_))
    ));
    assert!(matches!(
        s.allows("zz", &[StateId(0)]),
        Err(Error::UnknownEvent(_))
    ));
    assert!(s.allows("a", &[StateId(0)]).unwrap());
}

/// A small deterministic generator of random modular instances.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        // xorshift64*
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn chance(&mut self, percent: u64) -> bool {
        self.below(100) < percent
    }
}

/// Six events; `e0`, `e2`, `e4` controllable.
const EVENTS: [(&str, bool); 6] = [
    ("e0", true),
    ("e1", false),
    ("e2", true),
    ("e3", false),
    ("e4", true),
    ("e5", false),
];

fn random_automaton(rng: &mut Rng, name: &str, states: u64, alphabet: &[usize]) -> Automaton {
    let mut b = AutomatonBuilder::new(name);
    for &e in alphabet {
        b.add_event(EVENTS[e].0, EVENTS[e].1).unwrap();
    }
    b.set_initial_by_name("0").unwrap();
    for s in 0..states {
        b.add_state(&s.to_string());
    }
    for s in 0..states {
        for &e in alphabet {
            if rng.chance(55) {
                let t = rng.below(states);
                b.add_transition_by_name(&s.to_string(), EVENTS[e].0, &t.to_string(), 0)
                    .unwrap();
            }
        }
        if s == 0 && rng.chance(70) || rng.chance(40) {
            b.mark_by_name(&s.to_string());
        }
    }
    b.build().unwrap()
}

/// 2–4 plants of 2–4 states over random subsets of the six events, 1–2
/// specifications of 1–3 states over subsets of the plants' events.
fn random_instance(seed: u64) -> (Vec<Automaton>, Vec<Automaton>) {
    let mut rng = Rng(seed | 1);
    let mut plants = Vec::new();
    let mut used = [false; 6];
    for i in 0..2 + rng.below(3) {
        let mut alphabet: Vec<usize> = (0..6).filter(|_| rng.chance(45)).collect();
        if alphabet.is_empty() {
            alphabet.push(rng.below(6) as usize);
        }
        for &e in &alphabet {
            used[e] = true;
        }
        let states = 2 + rng.below(3);
        plants.push(random_automaton(
            &mut rng,
            &format!("G{i}"),
            states,
            &alphabet,
        ));
    }
    let pool: Vec<usize> = (0..6).filter(|&e| used[e]).collect();
    let mut specs = Vec::new();
    for i in 0..1 + rng.below(2) {
        let mut alphabet: Vec<usize> = pool.iter().copied().filter(|_| rng.chance(60)).collect();
        if alphabet.is_empty() {
            alphabet.push(pool[rng.below(pool.len() as u64) as usize]);
        }
        let states = 1 + rng.below(3);
        specs.push(random_automaton(
            &mut rng,
            &format!("E{i}"),
            states,
            &alphabet,
        ));
    }
    (plants, specs)
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn random_modular_instances_match_supcon(seed in any::<u64>()) {
        let (plants, specs) = random_instance(seed);
        if let Err(e) = check(&plants, &specs) {
            prop_assert!(false, "seed {seed}: {e}");
        }
    }
}

/// The random instances are not all trivial: some supervisors are empty,
/// some are the whole reachable set, some cut states.
#[test]
fn random_instances_cover_the_cases() {
    let (mut empty, mut whole, mut cut) = (0, 0, 0);
    for seed in 0..300 {
        let (plants, specs) = random_instance(seed * 7919 + 13);
        let s = synthesize(&plants, &specs).unwrap();
        if s.is_empty() {
            empty += 1;
        } else if s.supervisor_states() == s.reachable_states() {
            whole += 1;
        } else {
            cut += 1;
        }
    }
    assert!(
        empty > 10 && whole > 10 && cut > 10,
        "{empty} {whole} {cut}"
    );
}

/// The symbolic nonblocking verdict of plants ∥ specifications (all run
/// as they are) against `des`'s explicit one: same verdict, and when
/// blocking, a counterexample of the same (shortest) length that leads,
/// run on the explicit product, into a blocking state.
fn check_nonblocking(plants: &[Automaton], specs: &[Automaton]) -> Result<bool, String> {
    use des_symbolic::verify::nonblocking;
    let model = des_symbolic::Model::new(plants, specs).map_err(|e| e.to_string())?;
    let verdict = nonblocking(&model);
    let all: Vec<&Automaton> = plants.iter().chain(specs).collect();
    let explicit = ops::verify::check_nonconflicting(&all).map_err(|e| e.to_string())?;
    let product = ops::sync(&all).map_err(|e| e.to_string())?;
    if verdict.reachable != BigUint::from(product.num_states()) {
        return Err(format!(
            "reachable {} symbolically, {} explicitly",
            verdict.reachable,
            product.num_states()
        ));
    }
    match (&verdict.counterexample, &explicit) {
        (None, None) => Ok(true),
        (Some(c), Some(w)) => {
            if c.events.len() != w.path.len() {
                return Err(format!("strings {:?} and {:?}", c.events, w.path));
            }
            // Run the string on the product: it must end where no marked
            // state can be reached.
            let mut s = product.initial().ok_or("no initial state")?;
            for e in &c.events {
                let id = product.alphabet().id(e).ok_or("unknown event")?;
                s = product.successor(s, id).ok_or(format!("{e} not enabled"))?;
            }
            let coreachable = ops::reach::coreachable(&product);
            if coreachable.contains(s.index()) {
                return Err(format!("{:?} ends in a state that can finish", c.events));
            }
            Ok(false)
        }
        _ => Err(format!(
            "symbolic {:?}, explicit {:?}",
            verdict.counterexample, explicit
        )),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn random_closed_loops_block_as_the_explicit_check_says(seed in any::<u64>()) {
        let (plants, specs) = random_instance(seed);
        if let Err(e) = check_nonblocking(&plants, &specs) {
            prop_assert!(false, "seed {seed}: {e}");
        }
    }
}

/// Both verdicts occur among the random closed loops.
#[test]
fn random_closed_loops_cover_both_verdicts() {
    let (mut nonblocking, mut blocking) = (0, 0);
    for seed in 0..300 {
        let (plants, specs) = random_instance(seed * 104_729 + 7);
        match check_nonblocking(&plants, &specs) {
            Ok(true) => nonblocking += 1,
            Ok(false) => blocking += 1,
            Err(e) => panic!("seed {seed}: {e}"),
        }
    }
    assert!(
        nonblocking > 10 && blocking > 10,
        "{nonblocking} {blocking}"
    );
}
