//! Parametric model families: plants and specifications as component
//! automata, for benchmarks and cross-checks.
//!
//! Controllable events start something; uncontrollable ones finish or
//! release it. Every family returns a [`Family`] of plant and
//! specification components, never their product.

use crate::error::{Error, Result};
use des::{Automaton, AutomatonBuilder};

/// Plant and specification components of one instance.
#[derive(Debug, Clone)]
pub struct Family {
    /// Instance name, e.g. `ring13`.
    pub name: String,
    /// Plant components.
    pub plants: Vec<Automaton>,
    /// Specification components.
    pub specs: Vec<Automaton>,
}

/// One automaton from `(name, controllable)` events, `(source, event,
/// target)` transitions, the initial state and the marked states.
fn automaton(
    name: &str,
    events: &[(String, bool)],
    transitions: &[(&str, &str, &str)],
    initial: &str,
    marked: &[&str],
) -> Result<Automaton> {
    let mut b = AutomatonBuilder::new(name);
    for (e, c) in events {
        b.add_event(e, *c)?;
    }
    b.set_initial_by_name(initial)?;
    for &(s, e, t) in transitions {
        b.add_transition_by_name(s, e, t, 0)?;
    }
    for m in marked {
        b.mark_by_name(m);
    }
    Ok(b.build()?)
}

/// A machine `idle --start(c)--> working --finish(u)--> idle`, marked idle.
fn machine(name: &str, start: &str, finish: &str) -> Result<Automaton> {
    automaton(
        name,
        &[(start.to_owned(), true), (finish.to_owned(), false)],
        &[("idle", start, "working"), ("working", finish, "idle")],
        "idle",
        &["idle"],
    )
}

/// A one-slot buffer `empty --put--> full --take--> empty`: as a
/// specification it forbids underflow (`take` when empty) and overflow
/// (`put` when full). Marked when empty, or `full` at first when `full`.
fn buffer(name: &str, put: &str, take: &str, full: bool) -> Result<Automaton> {
    let initial = if full { "full" } else { "empty" };
    automaton(
        name,
        &[(put.to_owned(), false), (take.to_owned(), true)],
        &[("empty", put, "full"), ("full", take, "empty")],
        initial,
        &[initial],
    )
}

fn at_least(family: &'static str, n: usize, min: usize) -> Result<()> {
    if n < min {
        return Err(Error::FamilySize { family, min, n });
    }
    Ok(())
}

/// `ring n`: machines `M0..M(n-1)` in a cycle with one-slot buffers
/// `B0..B(n-1)`; machine `i` takes a part from `B(i-1)` when it starts
/// (`s_i`, controllable) and puts it into `Bi` when it finishes (`f_i`,
/// uncontrollable). Buffer `Bi` holds a part at first for even `i`, so
/// `⌈n/2⌉` parts circulate; a buffer is marked in its initial fill
/// (returning to the start is the task). Specifications: the buffers (no
/// underflow, no overflow). `n >= 2`.
pub fn ring(n: usize) -> Result<Family> {
    at_least("ring", n, 2)?;
    let mut plants = Vec::with_capacity(n);
    let mut specs = Vec::with_capacity(n);
    for i in 0..n {
        plants.push(machine(
            &format!("M{i}"),
            &format!("s_{i}"),
            &format!("f_{i}"),
        )?);
    }
    for i in 0..n {
        let next = (i + 1) % n;
        specs.push(buffer(
            &format!("B{i}"),
            &format!("f_{i}"),
            &format!("s_{next}"),
            i % 2 == 0,
        )?);
    }
    Ok(Family {
        name: format!("ring{n}"),
        plants,
        specs,
    })
}

/// `ringb n`: [`ring`] with machines that may break down while working
/// (`b_i`, uncontrollable) and are repaired (`r_i`, controllable) back to
/// work, keeping their part: `idle --s_i--> working --f_i--> idle`,
/// `working --b_i--> down --r_i--> working`. `n >= 2`.
pub fn ring_breakdowns(n: usize) -> Result<Family> {
    at_least("ringb", n, 2)?;
    let mut f = ring(n)?;
    for (i, m) in f.plants.iter_mut().enumerate() {
        let (s, fi, b, r) = (
            format!("s_{i}"),
            format!("f_{i}"),
            format!("b_{i}"),
            format!("r_{i}"),
        );
        *m = automaton(
            &format!("M{i}"),
            &[
                (s.clone(), true),
                (fi.clone(), false),
                (b.clone(), false),
                (r.clone(), true),
            ],
            &[
                ("idle", &s, "working"),
                ("working", &fi, "idle"),
                ("working", &b, "down"),
                ("down", &r, "working"),
            ],
            "idle",
            &["idle"],
        )?;
    }
    f.name = format!("ringb{n}");
    Ok(f)
}

/// `tline n`: a transfer line of `n` machines in series with one-slot
/// buffers `B1..B(n-1)` between neighbours. Machine 0 takes raw parts at
/// will; machine `i > 0` takes from `B(i)`; machine `n-1` hands its part
/// out. Each machine may fail while working (`b_i`, uncontrollable) and is
/// repaired (`r_i`, controllable) back to idle, losing the part.
/// Specifications: the buffers. `n >= 2`.
pub fn tline(n: usize) -> Result<Family> {
    at_least("tline", n, 2)?;
    let mut plants = Vec::with_capacity(n);
    let mut specs = Vec::with_capacity(n - 1);
    for i in 0..n {
        let (s, f, b, r) = (
            format!("s_{i}"),
            format!("f_{i}"),
            format!("b_{i}"),
            format!("r_{i}"),
        );
        plants.push(automaton(
            &format!("M{i}"),
            &[
                (s.clone(), true),
                (f.clone(), false),
                (b.clone(), false),
                (r.clone(), true),
            ],
            &[
                ("idle", &s, "working"),
                ("working", &f, "idle"),
                ("working", &b, "down"),
                ("down", &r, "idle"),
            ],
            "idle",
            &["idle"],
        )?);
    }
    for i in 1..n {
        specs.push(buffer(
            &format!("B{i}"),
            &format!("f_{}", i - 1),
            &format!("s_{i}"),
            false,
        )?);
    }
    Ok(Family {
        name: format!("tline{n}"),
        plants,
        specs,
    })
}

/// `phil n`: dining philosophers. Philosopher `i` (plant) thinks, takes
/// its left fork (`l_i`, controllable), its right fork (`r_i`,
/// controllable), eats and puts both down (`p_i`, uncontrollable). Fork
/// `j` (specification) lies between philosopher `j` (its left fork) and
/// philosopher `j-1` (its right fork) and is held by one at a time.
/// Marked: thinking, forks free. `n >= 2`.
pub fn phil(n: usize) -> Result<Family> {
    at_least("phil", n, 2)?;
    let mut plants = Vec::with_capacity(n);
    let mut specs = Vec::with_capacity(n);
    for i in 0..n {
        let (l, r, p) = (format!("l_{i}"), format!("r_{i}"), format!("p_{i}"));
        plants.push(automaton(
            &format!("P{i}"),
            &[(l.clone(), true), (r.clone(), true), (p.clone(), false)],
            &[
                ("thinking", &l, "left"),
                ("left", &r, "eating"),
                ("eating", &p, "thinking"),
            ],
            "thinking",
            &["thinking"],
        )?);
    }
    for j in 0..n {
        let before = (j + n - 1) % n;
        let (l, p) = (format!("l_{j}"), format!("p_{j}"));
        let (r, q) = (format!("r_{before}"), format!("p_{before}"));
        specs.push(automaton(
            &format!("F{j}"),
            &[
                (l.clone(), true),
                (p.clone(), false),
                (r.clone(), true),
                (q.clone(), false),
            ],
            &[
                ("free", &l, "left_user"),
                ("left_user", &p, "free"),
                ("free", &r, "right_user"),
                ("right_user", &q, "free"),
            ],
            "free",
            &["free"],
        )?);
    }
    Ok(Family {
        name: format!("phil{n}"),
        plants,
        specs,
    })
}

/// One automaton: `events` (name, controllable), `(source, event, target)`
/// transitions by state name, the initial state first among `states`, the
/// marked states.
fn automaton_with_states(
    name: &str,
    events: &[(&str, bool)],
    states: &[&str],
    transitions: &[(&str, &str, &str)],
    marked: &[&str],
) -> Result<Automaton> {
    let mut b = AutomatonBuilder::new(name);
    for &(e, c) in events {
        b.add_event(e, c)?;
    }
    for s in states {
        b.add_state(s);
    }
    b.set_initial_by_name(states[0])?;
    for &(s, e, t) in transitions {
        b.add_transition_by_name(s, e, t, 0)?;
    }
    for m in marked {
        b.mark_by_name(m);
    }
    Ok(b.build()?)
}

/// A Prenzel–Provost-class module (seed 004, docs/seeds.md): `n` conveyor
/// stations in a loop (the last hands over to the first), each one light sensor (an input: rising and falling
/// edges, uncontrollable) and one belt driven forward or backward (two
/// outputs: `fwd`, `rev`, and `stop`, controllable). With `n = 10`: 10
/// inputs, 20 outputs, 20 plant and 20 specification models, as the
/// paper's medium-sized module.
///
/// Our reading (the paper gives sizes, not the models): each station's
/// specification is the paper's Fig. 6b cycle (a part arrives, the belt
/// starts; it leaves, the belt stops; a part may be taken off before the
/// belt starts), where the belt may run backward on an empty station to
/// eject a sample once three parts have passed since the last one; each
/// handover specification keeps a belt from running forward while the
/// next station's sensor is covered.
///
/// `n >= 2` stations.
pub fn module(n: usize) -> Result<Family> {
    at_least("module", n, 2)?;
    let mut plants = Vec::with_capacity(2 * n);
    let mut specs = Vec::with_capacity(2 * n);
    let ev = |kind: &str, i: usize| format!("{kind}_{i}");
    for i in 0..n {
        let (re, fe) = (ev("RE_ls", i), ev("FE_ls", i));
        plants.push(automaton_with_states(
            &format!("LS{i}"),
            &[(&re, false), (&fe, false)],
            &["off", "on"],
            &[("off", &re, "on"), ("on", &fe, "off")],
            &["off"],
        )?);
        let (fwd, rev, stop) = (ev("fwd", i), ev("rev", i), ev("stop", i));
        plants.push(automaton_with_states(
            &format!("BELT{i}"),
            &[(&fwd, true), (&rev, true), (&stop, true)],
            &["stopped", "forward", "backward"],
            &[
                ("stopped", &fwd, "forward"),
                ("stopped", &rev, "backward"),
                ("forward", &stop, "stopped"),
                ("backward", &stop, "stopped"),
            ],
            &["stopped"],
        )?);
    }
    for i in 0..n {
        let (re, fe) = (ev("RE_ls", i), ev("FE_ls", i));
        let (fwd, rev, stop) = (ev("fwd", i), ev("rev", i), ev("stop", i));
        // idle → (part) waiting → (belt on) carrying → (part gone) leaving
        // → (belt off) idle; a part may arrive again while leaving, and be
        // taken off while waiting. The parts since the last sample count
        // up to 3 (`_k`); only then may the belt run backward to eject a
        // sample (clearing), which starts the count again.
        let name = |phase: &str, k: usize| format!("{phase}_{k}");
        let mut states: Vec<String> = Vec::new();
        for k in 0..4 {
            for phase in ["idle", "waiting", "carrying", "leaving"] {
                states.push(name(phase, k));
            }
        }
        states.push("clearing".to_owned());
        let mut moves: Vec<(String, String, String)> = Vec::new();
        for k in 0..4 {
            let at = |phase: &str| name(phase, k);
            moves.push((at("idle"), re.clone(), at("waiting")));
            moves.push((at("waiting"), fe.clone(), at("idle")));
            moves.push((at("waiting"), fwd.clone(), at("carrying")));
            moves.push((at("carrying"), fe.clone(), at("leaving")));
            moves.push((at("leaving"), re.clone(), at("carrying")));
            moves.push((at("leaving"), stop.clone(), name("idle", (k + 1).min(3))));
        }
        moves.push((name("idle", 3), rev.clone(), "clearing".to_owned()));
        moves.push(("clearing".to_owned(), stop.clone(), name("idle", 0)));
        moves.push(("clearing".to_owned(), re.clone(), "clearing".to_owned()));
        moves.push(("clearing".to_owned(), fe.clone(), "clearing".to_owned()));
        let state_refs: Vec<&str> = states.iter().map(String::as_str).collect();
        let move_refs: Vec<(&str, &str, &str)> = moves
            .iter()
            .map(|(s, e, t)| (s.as_str(), e.as_str(), t.as_str()))
            .collect();
        let idle: Vec<String> = (0..4).map(|k| name("idle", k)).collect();
        let idle: Vec<&str> = idle.iter().map(String::as_str).collect();
        specs.push(automaton_with_states(
            &format!("CYCLE{i}"),
            &[
                (&re, false),
                (&fe, false),
                (&fwd, true),
                (&rev, true),
                (&stop, true),
            ],
            &state_refs,
            &move_refs,
            &idle,
        )?);
        let next = (i + 1) % n;
        let (re_next, fe_next) = (ev("RE_ls", next), ev("FE_ls", next));
        specs.push(automaton_with_states(
            &format!("HANDOVER{i}"),
            &[(&re_next, false), (&fe_next, false), (&fwd, true)],
            &["free", "covered"],
            &[
                ("free", &fwd, "free"),
                ("free", &re_next, "covered"),
                ("covered", &fe_next, "free"),
            ],
            &["free"],
        )?);
    }
    Ok(Family {
        name: format!("module{n}"),
        plants,
        specs,
    })
}

/// The family named `name` (`ring`, `ringb`, `tline`, `phil`, `module`) of
/// size `n`.
pub fn by_name(name: &str, n: usize) -> Option<Result<Family>> {
    match name {
        "ring" => Some(ring(n)),
        "ringb" => Some(ring_breakdowns(n)),
        "tline" => Some(tline(n)),
        "phil" => Some(phil(n)),
        "module" => Some(module(n)),
        _ => None,
    }
}
