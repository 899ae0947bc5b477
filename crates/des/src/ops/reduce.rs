//! Supervisor reduction: a smaller supervisor with the same closed-loop
//! behaviour (Su and Wonham, "Supervisor reduction for discrete-event
//! systems", 2004).
//!
//! A supervisor S of a plant G is judged only by what it does in the
//! closed loop G‖S. For each state x of S that the closed loop reaches:
//!
//! - E(x): the events S lets occur at x in the closed loop (its
//!   transitions from x that some closed-loop string takes);
//! - D(x): the events of S's alphabet that G could do at x in the closed
//!   loop but S does not (S disables them there);
//! - T(x): some closed-loop string reaching x is marked by G;
//! - M(x): x is marked in S.
//!
//! Two states are *control consistent* when neither enables what the
//! other disables (E(x) ∩ D(x') = ∅ = E(x') ∩ D(x)) and, when G may mark
//! strings reaching both (T(x) = T(x') = 1), they mark alike
//! (M(x) = M(x')). A partition of S's states into classes of pairwise
//! consistent states, closed under transitions (the states of a class
//! reach, on any event, states of one class), is a supervisor of its own
//! whose states are the classes: it enables at a class what its states
//! enable, and gives G‖R the closed and marked languages of G‖S.
//!
//! Finding the smallest such partition is NP-hard; [`reduce`] is the
//! usual greedy search: states in order, each one's class tries to absorb
//! each later state's class, with every pair of successor classes the
//! merge forces merged too, all or nothing, and never a class settled
//! earlier. The result depends on the order, so the search runs in four
//! orders (breadth and depth first through the closed loop, by state
//! number, backwards) and keeps the smallest. A class is marked when it holds a state x with T(x) = 1 and
//! M(x) = 1 (where T = 0 the plant marks nothing, so its marking is moot).
//!
//! The closed loop is computed once (a composition, bounded by
//! `max_states`); the merging works on per-class bit sets, so a check is a
//! few word operations. Transitions of S the closed loop never takes are
//! not kept: the plant cannot make them happen.

use super::{compose, language_difference, ComposeOptions, Composition, LanguageDifference};
use crate::automaton::{Automaton, AutomatonBuilder, EventId, StateId};
use crate::error::{Error, Result};
use rustc_hash::FxHashMap;
use std::collections::VecDeque;

/// What [`reduce`] found.
#[derive(Debug, Clone)]
pub struct Reduction {
    /// The reduced supervisor (its states named after their classes' first
    /// states).
    pub automaton: Automaton,
    /// The class (state of the reduced supervisor) of each state of the
    /// original; `None` for states the closed loop never reaches.
    pub class_of: Vec<Option<StateId>>,
    /// States of the closed loop G‖S.
    pub closed_loop_states: usize,
}

/// "No state": an absent successor.
const NONE: u32 = u32::MAX;

/// The control data of one class: what its states enable and disable,
/// whether a plant-marked string reaches a marked or an unmarked one, and
/// a successor state per event.
#[derive(Debug, Clone)]
struct Class {
    enabled: Vec<u64>,
    disabled: Vec<u64>,
    marks: bool,
    unmarks: bool,
    /// A state of the class's successor class per event, or `NONE`.
    next: Vec<u32>,
}

impl Class {
    fn consistent(&self, other: &Class) -> bool {
        let clash = |a: &[u64], b: &[u64]| a.iter().zip(b).any(|(x, y)| x & y != 0);
        !clash(&self.enabled, &other.disabled)
            && !clash(&other.enabled, &self.disabled)
            && !((self.marks || other.marks) && (self.unmarks || other.unmarks))
    }

    fn absorb(&mut self, other: &Class) {
        for (a, b) in self.enabled.iter_mut().zip(&other.enabled) {
            *a |= b;
        }
        for (a, b) in self.disabled.iter_mut().zip(&other.disabled) {
            *a |= b;
        }
        self.marks |= other.marks;
        self.unmarks |= other.unmarks;
        for (a, &b) in self.next.iter_mut().zip(&other.next) {
            if *a == NONE {
                *a = b;
            }
        }
    }
}

/// The closed loop's view of S: reached states in order, the transitions
/// the closed loop takes, and each state's control data.
struct ControlData {
    /// Reached states of S, in the order reduction visits them.
    order: Vec<u32>,
    /// Per state of S: its position in `order`, or `NONE`.
    position: Vec<u32>,
    /// Per reached state (by position): the closed-loop transitions
    /// `(event, target position)`.
    moves: Vec<Vec<(EventId, u32)>>,
    /// Per reached state (by position): its class data.
    data: Vec<Class>,
    closed_loop_states: usize,
}

fn set(bits: &mut [u64], e: EventId) {
    bits[e.index() / 64] |= 1 << (e.index() % 64);
}

/// Explores G‖S from the initial pair, breadth first.
fn control_data(plant: &Automaton, sup: &Automaton, max_states: usize) -> Result<ControlData> {
    let words = sup.alphabet().len().div_ceil(64).max(1);
    let n = sup.num_states();
    let events = sup.alphabet().len();
    // The plant's id of each of S's events (`None`: G does not restrict it).
    let in_plant: Vec<Option<EventId>> = sup
        .alphabet()
        .iter()
        .map(|(_, e)| plant.alphabet().id(&e.name))
        .collect();
    // Plant events S does not know move G alone.
    let plant_only: Vec<EventId> = plant
        .alphabet()
        .iter()
        .filter(|(_, e)| !sup.alphabet().contains(&e.name))
        .map(|(id, _)| id)
        .collect();
    let empty = Class {
        enabled: vec![0; words],
        disabled: vec![0; words],
        marks: false,
        unmarks: false,
        next: vec![NONE; events],
    };
    let mut position = vec![NONE; n];
    let mut order: Vec<u32> = Vec::new();
    let mut moves: Vec<Vec<(EventId, u32)>> = Vec::new();
    let mut data: Vec<Class> = Vec::new();
    let (Some(g0), Some(s0)) = (plant.initial(), sup.initial()) else {
        return Ok(ControlData {
            order,
            position,
            moves,
            data,
            closed_loop_states: 0,
        });
    };
    let mut seen: FxHashMap<(u32, u32), ()> = FxHashMap::default();
    let mut queue = VecDeque::new();
    seen.insert((g0.0, s0.0), ());
    queue.push_back((g0, s0));
    let visit = |s: StateId,
                 position: &mut Vec<u32>,
                 order: &mut Vec<u32>,
                 moves: &mut Vec<Vec<(EventId, u32)>>,
                 data: &mut Vec<Class>| {
        if position[s.index()] == NONE {
            position[s.index()] = order.len() as u32;
            order.push(s.0);
            moves.push(Vec::new());
            data.push(empty.clone());
        }
        position[s.index()] as usize
    };
    visit(s0, &mut position, &mut order, &mut moves, &mut data);
    while let Some((g, s)) = queue.pop_front() {
        let x = visit(s, &mut position, &mut order, &mut moves, &mut data);
        if plant.is_marked(g) {
            if sup.is_marked(s) {
                data[x].marks = true;
            } else {
                data[x].unmarks = true;
            }
        }
        let mut successors: Vec<(StateId, StateId)> = Vec::new();
        for (e, plant_event) in in_plant.iter().enumerate() {
            let e = EventId(e as u32);
            let g_next = match plant_event {
                Some(pe) => match plant.successor(g, *pe) {
                    Some(next) => next,
                    None => continue,
                },
                None => g,
            };
            match sup.successor(s, e) {
                Some(s_next) => {
                    set(&mut data[x].enabled, e);
                    let y = visit(s_next, &mut position, &mut order, &mut moves, &mut data);
                    if !moves[x].iter().any(|&(m, _)| m == e) {
                        moves[x].push((e, y as u32));
                    }
                    successors.push((g_next, s_next));
                }
                None => set(&mut data[x].disabled, e),
            }
        }
        for &pe in &plant_only {
            if let Some(next) = plant.successor(g, pe) {
                successors.push((next, s));
            }
        }
        for pair in successors {
            if seen.insert((pair.0 .0, pair.1 .0), ()).is_none() {
                if seen.len() > max_states {
                    return Err(Error::StateLimit {
                        max_states,
                        message: format!(
                            "the closed loop of supervisor `{}` and its plant has more than {max_states} states",
                            sup.name()
                        ),
                    });
                }
                queue.push_back(pair);
            }
        }
    }
    for (x, m) in moves.iter().enumerate() {
        for &(e, y) in m {
            data[x].next[e.index()] = y;
        }
    }
    Ok(ControlData {
        order,
        position,
        moves,
        data,
        closed_loop_states: seen.len(),
    })
}

/// The partition being built: committed classes (a state's root is the
/// first state of its class, in visiting order) and their data.
struct Partition {
    root: Vec<u32>,
    members: Vec<Vec<u32>>,
    data: Vec<Class>,
}

impl Partition {
    fn root(&self, x: u32) -> u32 {
        self.root[x as usize]
    }
}

/// Tentative merges of committed classes, kept apart until all succeed.
#[derive(Default)]
struct Tentative {
    parent: FxHashMap<u32, u32>,
    data: FxHashMap<u32, Class>,
}

impl Tentative {
    fn find(&self, mut c: u32) -> u32 {
        while let Some(&p) = self.parent.get(&c) {
            c = p;
        }
        c
    }

    fn data<'a>(&'a self, partition: &'a Partition, c: u32) -> &'a Class {
        self.data
            .get(&c)
            .unwrap_or_else(|| &partition.data[c as usize])
    }
}

/// Tries to merge the classes of `x` and `y` with every merge that forces,
/// none of them touching a class whose root is before `settled`.
fn try_merge(partition: &Partition, x: u32, y: u32, settled: u32) -> Option<Tentative> {
    let mut tent = Tentative::default();
    let mut work = vec![(x, y)];
    while let Some((x, y)) = work.pop() {
        let a = tent.find(partition.root(x));
        let b = tent.find(partition.root(y));
        if a == b {
            continue;
        }
        if a < settled || b < settled {
            return None;
        }
        let (da, db) = (tent.data(partition, a), tent.data(partition, b));
        if !da.consistent(db) {
            return None;
        }
        for (&na, &nb) in da.next.iter().zip(&db.next) {
            if na != NONE && nb != NONE {
                work.push((na, nb));
            }
        }
        let mut merged = da.clone();
        merged.absorb(db);
        let (keep, gone) = (a.min(b), a.max(b));
        tent.parent.insert(gone, keep);
        tent.data.remove(&gone);
        tent.data.insert(keep, merged);
    }
    Some(tent)
}

fn commit(partition: &mut Partition, tent: Tentative) {
    let Tentative { parent, data } = tent;
    let find = |mut c: u32| {
        while let Some(&p) = parent.get(&c) {
            c = p;
        }
        c
    };
    for (&gone, _) in parent.iter() {
        let keep = find(gone);
        let moved = std::mem::take(&mut partition.members[gone as usize]);
        for &m in &moved {
            partition.root[m as usize] = keep;
        }
        partition.members[keep as usize].extend(moved);
    }
    for (c, d) in data {
        partition.data[c as usize] = d;
    }
}

/// Reduces supervisor `sup` of `plant` (see the module docs). The closed
/// loop G‖S may have at most `max_states` states.
pub fn reduce(plant: &Automaton, sup: &Automaton, max_states: usize) -> Result<Reduction> {
    let cd = control_data(plant, sup, max_states)?;
    let mut best: Option<Reduction> = None;
    for order in Order::ALL {
        let cd = cd.reordered(order);
        let partition = cover(&cd, cd.data.clone());
        let candidate = build(sup, &cd, &partition)?;
        let size = |r: &Reduction| (r.automaton.num_states(), r.automaton.num_transitions());
        if best.as_ref().is_none_or(|b| size(&candidate) < size(b)) {
            best = Some(candidate);
        }
    }
    Ok(best.expect("at least one order"))
}

/// The orders the greedy search visits states in ([`reduce`] keeps the
/// smallest result): the search is order-sensitive, and no one order wins
/// everywhere (on 1,000 random problems each of these gives some
/// smallest result the others miss).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Order {
    /// Breadth first through the closed loop.
    BreadthFirst,
    /// By the supervisor's state numbers.
    Numbered,
    /// Depth first through the closed loop.
    DepthFirst,
    /// Breadth first, the initial state first and the rest backwards.
    Backwards,
}

impl Order {
    const ALL: [Order; 4] = [
        Order::BreadthFirst,
        Order::Numbered,
        Order::DepthFirst,
        Order::Backwards,
    ];
}

impl ControlData {
    /// The same data with states visited in `order` (the initial state
    /// stays first).
    fn reordered(&self, order: Order) -> ControlData {
        let n = self.order.len();
        // `perm[new] = old`.
        let perm: Vec<u32> = match order {
            Order::BreadthFirst => (0..n as u32).collect(),
            Order::Numbered => {
                let mut p: Vec<u32> = (0..n as u32).collect();
                p[1..].sort_by_key(|&x| self.order[x as usize]);
                p
            }
            Order::Backwards => {
                let mut p: Vec<u32> = (0..n as u32).collect();
                p[1..].reverse();
                p
            }
            Order::DepthFirst => {
                let mut p = Vec::with_capacity(n);
                let mut seen = vec![false; n];
                let mut stack = if n > 0 { vec![0u32] } else { Vec::new() };
                while let Some(x) = stack.pop() {
                    if std::mem::replace(&mut seen[x as usize], true) {
                        continue;
                    }
                    p.push(x);
                    for &(_, y) in self.moves[x as usize].iter().rev() {
                        if !seen[y as usize] {
                            stack.push(y);
                        }
                    }
                }
                p
            }
        };
        let mut new_of = vec![NONE; n];
        for (new, &old) in perm.iter().enumerate() {
            new_of[old as usize] = new as u32;
        }
        let renumber = |x: u32| if x == NONE { NONE } else { new_of[x as usize] };
        ControlData {
            order: perm.iter().map(|&o| self.order[o as usize]).collect(),
            position: self.position.iter().map(|&p| renumber(p)).collect(),
            moves: perm
                .iter()
                .map(|&o| {
                    self.moves[o as usize]
                        .iter()
                        .map(|&(e, y)| (e, renumber(y)))
                        .collect()
                })
                .collect(),
            data: perm
                .iter()
                .map(|&o| {
                    let mut c = self.data[o as usize].clone();
                    c.next.iter_mut().for_each(|x| *x = renumber(*x));
                    c
                })
                .collect(),
            closed_loop_states: self.closed_loop_states,
        }
    }
}

/// The greedy search for a control cover, with `data` as the states'
/// control data.
fn cover(cd: &ControlData, data: Vec<Class>) -> Partition {
    let n = cd.order.len();
    let mut partition = Partition {
        root: (0..n as u32).collect(),
        members: (0..n as u32).map(|x| vec![x]).collect(),
        data,
    };
    for i in 0..n as u32 {
        if partition.root(i) != i {
            continue;
        }
        for j in i + 1..n as u32 {
            if partition.root(j) != j || partition.root(i) == partition.root(j) {
                continue;
            }
            if let Some(tent) = try_merge(&partition, i, j, i) {
                commit(&mut partition, tent);
            }
        }
    }
    partition
}

/// One local controller per controllable event (Cai and Wonham,
/// "Supervisor localization", 2010): what [`localize`] found.
#[derive(Debug, Clone)]
pub struct Localization {
    /// Per controllable event of the supervisor (alphabet order): the
    /// event and its local controller. A controller's alphabet is its
    /// event and the events that move it; the others, self-loops
    /// everywhere, are left out.
    pub controllers: Vec<(String, Automaton)>,
    /// States of the closed loop G‖S.
    pub closed_loop_states: usize,
}

/// Localizes supervisor `sup` of `plant`: for each controllable event σ a
/// control cover that keeps apart only the states that disagree on σ
/// (and on marking), as [`reduce`] does for all events; then the events
/// whose transitions are all self-loops leave its alphabet (where such an
/// event is missing the supervisor disabled it, which is another local
/// controller's business, or the plant cannot do it), and `minstate`
/// merges what that made equal. Run beside the plant (each component as
/// its own automaton), the local controllers give the closed and marked
/// languages of G‖S ([`check_localized`]).
pub fn localize(plant: &Automaton, sup: &Automaton, max_states: usize) -> Result<Localization> {
    let cd = control_data(plant, sup, max_states)?;
    let mut controllers = Vec::new();
    for (sigma, event) in sup.alphabet().iter() {
        if !event.controllable {
            continue;
        }
        let only = |bits: &[u64]| {
            let mut out = vec![0; bits.len()];
            out[sigma.index() / 64] = bits[sigma.index() / 64] & (1 << (sigma.index() % 64));
            out
        };
        let data = cd
            .data
            .iter()
            .map(|c| Class {
                enabled: only(&c.enabled),
                disabled: only(&c.disabled),
                ..c.clone()
            })
            .collect();
        let partition = cover(&cd, data);
        let full = build(sup, &cd, &partition)?.automaton;
        let mut local = super::minstate(&without_self_loop_events(&full, sigma)?);
        local.set_name(format!("{}.{}", sup.name(), event.name));
        controllers.push((event.name.clone(), local));
    }
    Ok(Localization {
        controllers,
        closed_loop_states: cd.closed_loop_states,
    })
}

/// `a` without the events, other than `keep`, whose every transition is a
/// self-loop.
fn without_self_loop_events(a: &Automaton, keep: EventId) -> Result<Automaton> {
    let mut moves = vec![false; a.alphabet().len()];
    moves[keep.index()] = true;
    for (s, e, t) in a.iter_transitions() {
        if s != t {
            moves[e.index()] = true;
        }
    }
    let mut b = AutomatonBuilder::new(a.name());
    b.set_controllability_stated(a.alphabet().controllability_stated());
    let mut ids = vec![None; a.alphabet().len()];
    for (e, event) in a.alphabet().iter() {
        if moves[e.index()] {
            ids[e.index()] = Some(
                b.add_event_like(event)
                    .map_err(|e| Error::Incompatible(e.to_string()))?,
            );
        }
    }
    let states: Vec<StateId> = a
        .states()
        .map(|s| {
            if a.has_state_names() {
                b.add_state(&a.state_name(s))
            } else {
                b.add_anonymous_state()
            }
        })
        .collect();
    if let Some(init) = a.initial() {
        b.set_initial(states[init.index()])
            .map_err(|e| Error::Incompatible(e.to_string()))?;
    }
    for s in a.marked_states() {
        b.mark(states[s.index()]);
    }
    for (s, e, t) in a.iter_transitions() {
        if let Some(id) = ids[e.index()] {
            b.add_transition(states[s.index()], id, states[t.index()], 0);
        }
    }
    b.build().map_err(|e| Error::Incompatible(e.to_string()))
}

/// Checks that the local controllers of `localization`, composed with
/// `plant`, give the closed and marked languages of `plant` ‖ `original`.
pub fn check_localized(
    plant: &Automaton,
    original: &Automaton,
    localization: &Localization,
    options: ComposeOptions<'_>,
) -> Result<()> {
    let controllers: Vec<&Automaton> = localization.controllers.iter().map(|(_, a)| a).collect();
    same_closed_loop(
        plant,
        original,
        &controllers,
        ("localization", "with the local controllers"),
        options,
    )
}

/// Checks that `replacement` (composed) gives `plant` the closed and
/// marked languages `original` gives it; `what` names the operation and
/// the replacement in the error, which has a shortest distinguishing
/// string.
fn same_closed_loop(
    plant: &Automaton,
    original: &Automaton,
    replacement: &[&Automaton],
    what: (&str, &str),
    options: ComposeOptions<'_>,
) -> Result<()> {
    match closed_loop_difference(plant, original, replacement, options)? {
        None => Ok(()),
        Some(d) => Err(Error::Incompatible(format!(
            "supervisor {} changed the closed loop of `{}` ({:?} language, string `{}` only {}): a bug, please report it",
            what.0,
            original.name(),
            d.language,
            d.string.join(" "),
            if d.in_first { "with the original" } else { what.1 }
        ))),
    }
}

/// A shortest string that tells `plant` ‖ `original` from `plant` ‖ the
/// `replacement` automata (closed or marked language; `in_first` when
/// only `original` lets the plant do it), `None` when they are equal.
pub(crate) fn closed_loop_difference(
    plant: &Automaton,
    original: &Automaton,
    replacement: &[&Automaton],
    options: ComposeOptions<'_>,
) -> Result<Option<LanguageDifference>> {
    let options = ComposeOptions {
        name_states: false,
        ..options
    };
    let lhs = compose(&[plant, original], Composition::Sync, options)?.automaton;
    let mut parts: Vec<&Automaton> = vec![plant];
    parts.extend_from_slice(replacement);
    let rhs = compose(&parts, Composition::Sync, options)?.automaton;
    Ok(language_difference(&lhs, &rhs))
}

/// The reduced supervisor: one state per class, in root order.
fn build(sup: &Automaton, cd: &ControlData, partition: &Partition) -> Result<Reduction> {
    let mut b = AutomatonBuilder::new(sup.name());
    for (_, e) in sup.alphabet().iter() {
        b.add_event_like(e)
            .map_err(|e| Error::Incompatible(e.to_string()))?;
    }
    b.set_controllability_stated(sup.alphabet().controllability_stated());
    let n = cd.order.len();
    let roots: Vec<u32> = (0..n as u32).filter(|&x| partition.root(x) == x).collect();
    let mut state_of_root: FxHashMap<u32, StateId> = FxHashMap::default();
    let named = sup.has_state_names();
    for &r in &roots {
        let s = if named {
            b.add_state(&sup.state_name(StateId(cd.order[r as usize])))
        } else {
            b.add_anonymous_state()
        };
        state_of_root.insert(r, s);
    }
    let class = |x: u32| state_of_root[&partition.root(x)];
    if n > 0 {
        b.set_initial(class(0))
            .map_err(|e| Error::Incompatible(e.to_string()))?;
    }
    for &r in &roots {
        if partition.data[r as usize].marks {
            b.mark(class(r));
        }
    }
    let mut added: FxHashMap<(StateId, EventId), StateId> = FxHashMap::default();
    for x in 0..n as u32 {
        for &(e, y) in &cd.moves[x as usize] {
            let (from, to) = (class(x), class(y));
            match added.insert((from, e), to) {
                Some(other) if other != to => {
                    return Err(Error::Incompatible(format!(
                        "supervisor reduction: classes are not closed under `{}` (a bug)",
                        sup.alphabet().name(e)
                    )))
                }
                Some(_) => {}
                None => b.add_transition(from, e, to, 0),
            }
        }
    }
    let automaton = b.build().map_err(|e| Error::Incompatible(e.to_string()))?;
    let class_of = (0..sup.num_states())
        .map(|s| {
            let x = cd.position[s];
            (x != NONE).then(|| class(x))
        })
        .collect();
    Ok(Reduction {
        automaton,
        class_of,
        closed_loop_states: cd.closed_loop_states,
    })
}

/// Checks that `reduced` gives `plant` the closed and marked languages
/// `original` gives it (both closed loops composed within `options`'
/// state limit); an error with a shortest distinguishing string
/// otherwise.
pub fn check_closed_loop(
    plant: &Automaton,
    original: &Automaton,
    reduced: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<()> {
    same_closed_loop(
        plant,
        original,
        &[reduced],
        ("reduction", "with the reduced supervisor"),
        options,
    )
}
