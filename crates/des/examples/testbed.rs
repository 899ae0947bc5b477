//! The manufacturing testbed of Leduc and Wonham (docs/seeds.md B) as
//! automata: the plant components and the 29 modular supervisors of
//! `models/testbed/` (its README states the layout and every
//! interpretation that is ours).
//!
//! ```text
//! cargo run -p des --example testbed -- models/testbed
//! ```
//!
//! writes `plant/*.toml` and `sup/*.toml` under the directory given;
//! `crates/des/tests/testbed.rs` checks that the committed files are what
//! this program writes.

#![forbid(unsafe_code)]
// `crates/des/tests/testbed.rs` includes this file for `files()` alone.
#![allow(dead_code)]

use des::formats::{self, Component, Format, Kind};
use des::{Automaton, AutomatonBuilder};
use std::collections::{BTreeMap, HashMap, VecDeque};
use std::path::Path;

/// Sensors, numbered 1 … 26 along the direction of travel.
const SENSORS: usize = 26;
/// Trains 1 and 2 and the sensor each stands at in the beginning.
const TRAINS: [(usize, usize); 2] = [(1, 1), (2, 16)];

/// A work unit: its crane, the sensors around its siding and its two
/// switches.
#[derive(Clone, Copy)]
struct Unit {
    crane: usize,
    /// Approach: the last sensor before the diverging switch.
    a: usize,
    /// Bypass: the main line's sensor beside the siding.
    b: usize,
    /// The crane's sensor, first on the siding.
    c: usize,
    /// The siding's exit sensor, before the merging switch.
    x: usize,
    /// The first sensor after the merging switch.
    e: usize,
    /// The diverging switch (after `a`).
    div: usize,
    /// The merging switch (before `e`).
    merge: usize,
}

/// The units in the order a train meets them after sensor 1.
const UNITS: [Unit; 3] = [
    Unit {
        crane: 2,
        a: 4,
        b: 5,
        c: 6,
        x: 7,
        e: 8,
        div: 3,
        merge: 4,
    },
    Unit {
        crane: 1,
        a: 11,
        b: 12,
        c: 13,
        x: 14,
        e: 15,
        div: 1,
        merge: 2,
    },
    Unit {
        crane: 3,
        a: 19,
        b: 20,
        c: 21,
        x: 22,
        e: 23,
        div: 5,
        merge: 6,
    },
];

/// Routes: for each train, the cranes it visits (the units whose siding
/// it takes); at the other units it takes the bypass.
const ROUTES: [(usize, [usize; 2]); 2] = [(1, [1, 2]), (2, [1, 3])];

/// The collision-protection sections: runs of consecutive sensors.
const SECTIONS: [&[usize]; 14] = [
    &[4],
    &[5],
    &[6, 7],
    &[8, 9, 10],
    &[11],
    &[12],
    &[13, 14],
    &[15, 16],
    &[17, 18],
    &[19],
    &[20],
    &[21, 22],
    &[23, 24, 25],
    &[26, 1, 2, 3],
];

/// Switch position: straight (`s`, the bypass) or diverging (`d`, the
/// siding).
const POSITIONS: [char; 2] = ['s', 'd'];

/// The sensors a train at `k` can reach next, each with the switch
/// position it needs (only the diverging switches decide: a train runs
/// through a merging switch set either way, see the README).
fn successors(k: usize) -> Vec<(usize, Option<(usize, char)>)> {
    for u in UNITS {
        if k == u.a {
            return vec![(u.b, Some((u.div, 's'))), (u.c, Some((u.div, 'd')))];
        }
        if k == u.b {
            return vec![(u.e, None)];
        }
    }
    vec![(k % SENSORS + 1, None)]
}

fn run(i: usize) -> String {
    format!("run_t{i}")
}
fn at(i: usize, k: usize) -> String {
    format!("t{i}_at{k}")
}
fn sw(w: usize, p: char) -> String {
    format!("sw{w}_{p}")
}
fn req(i: usize, w: usize, p: char) -> String {
    format!("t{i}_req_sw{w}_{p}")
}

/// An automaton from named transitions; `events` with controllability.
struct Spec {
    name: String,
    events: Vec<(String, bool)>,
    initial: String,
    marked: Vec<String>,
    transitions: Vec<(String, String, String)>,
}

impl Spec {
    fn new(name: &str, initial: &str) -> Spec {
        Spec {
            name: name.to_owned(),
            events: Vec::new(),
            initial: initial.to_owned(),
            marked: vec![initial.to_owned()],
            transitions: Vec::new(),
        }
    }
    fn event(&mut self, e: &str, controllable: bool) {
        if !self.events.iter().any(|(n, _)| n == e) {
            self.events.push((e.to_owned(), controllable));
        }
    }
    /// Marks every state named so far: a safety specification asks
    /// nothing of where the system stops.
    fn mark_all(&mut self) {
        for (s, _, t) in &self.transitions {
            for x in [s, t] {
                if !self.marked.contains(x) {
                    self.marked.push(x.clone());
                }
            }
        }
    }
    fn t(&mut self, s: &str, e: &str, t: &str) {
        self.transitions
            .push((s.to_owned(), e.to_owned(), t.to_owned()));
    }
    fn build(&self) -> Automaton {
        let mut b = AutomatonBuilder::new(self.name.as_str());
        for (e, c) in &self.events {
            b.add_event(e, *c).expect("one controllability per event");
        }
        b.set_initial_by_name(&self.initial).expect("a state name");
        for (s, e, t) in &self.transitions {
            b.add_transition_by_name(s, e, t, 0)
                .expect("declared events");
        }
        for m in &self.marked {
            b.mark_by_name(m);
        }
        b.build().expect("deterministic by construction")
    }
}

/// Basic model of train `i`, merged with the sensors' dependency on it:
/// stopped until `run_ti`, then moving until the next sensor reports it
/// (the train's embedded controller stops it there).
fn train(i: usize) -> Automaton {
    let mut a = Spec::new(&format!("train{i}"), "stopped");
    a.event(&run(i), true);
    a.t("stopped", &run(i), "moving");
    for k in 1..=SENSORS {
        a.event(&at(i, k), false);
        a.t("moving", &at(i, k), "stopped");
    }
    a.build()
}

/// A crane: `st_ldu` starts loading, `f_ldu` reports it finished.
fn crane(u: usize) -> Automaton {
    let mut a = Spec::new(&format!("crane{u}"), "idle");
    a.event(&format!("st_ld{u}"), true);
    a.event(&format!("f_ld{u}"), false);
    a.t("idle", &format!("st_ld{u}"), "loading");
    a.t("loading", &format!("f_ld{u}"), "idle");
    a.build()
}

/// Sensor ordering for train `i`: the sensors it can reach next from the
/// one it last passed, by their place on the track.
fn order(i: usize, start: usize) -> Automaton {
    let mut a = Spec::new(&format!("order_t{i}"), &format!("at{start}"));
    for k in 1..=SENSORS {
        a.event(&at(i, k), false);
    }
    for k in 1..=SENSORS {
        for (m, _) in successors(k) {
            a.t(&format!("at{k}"), &at(i, m), &format!("at{m}"));
        }
    }
    a.build()
}

/// A switch: `swW_s` and `swW_d` set it (setting it where it is does
/// nothing).
fn switch(w: usize) -> Automaton {
    let mut a = Spec::new(&format!("switch{w}"), "s");
    for p in POSITIONS {
        a.event(&sw(w, p), true);
    }
    for from in POSITIONS {
        for p in POSITIONS {
            a.t(&from.to_string(), &sw(w, p), &p.to_string());
        }
    }
    a.marked = vec!["s".into(), "d".into()];
    a.build()
}

/// The sensors' dependency on diverging switch `w` of unit `u` (the
/// paper's Fig. 4 for switch 6): a train reaches the bypass sensor only
/// with the switch straight, the crane's sensor only with it diverging.
fn switch_dependency(u: Unit) -> Automaton {
    let w = u.div;
    let mut a = Spec::new(&format!("sensors_sw{w}"), "s");
    for p in POSITIONS {
        a.event(&sw(w, p), true);
    }
    for (i, _) in TRAINS {
        a.event(&at(i, u.b), false);
        a.event(&at(i, u.c), false);
        a.t("s", &at(i, u.b), "s");
        a.t("d", &at(i, u.c), "d");
    }
    for from in POSITIONS {
        for p in POSITIONS {
            a.t(&from.to_string(), &sw(w, p), &p.to_string());
        }
    }
    a.marked = vec!["s".into(), "d".into()];
    a.build()
}

/// The request handler of switch `w`: a switch moves only when a router
/// asked for that position, one request at a time.
fn handler(w: usize) -> Automaton {
    let mut a = Spec::new(&format!("handler_sw{w}"), "idle");
    for p in POSITIONS {
        a.event(&sw(w, p), true);
    }
    for (i, _) in TRAINS {
        for p in POSITIONS {
            a.event(&req(i, w, p), true);
            a.t("idle", &req(i, w, p), &format!("want_{p}"));
        }
    }
    for p in POSITIONS {
        a.t(&format!("want_{p}"), &sw(w, p), "idle");
    }
    a.build()
}

/// Builds a supervisor by exploring its reachable states from `initial`:
/// `step(state, event)` is the successor, `None` where the event is
/// disabled (or, for an uncontrollable event, not in the alphabet's
/// reach); state names come from `name`.
fn explore<S: Clone + Eq + std::hash::Hash>(
    sup: &str,
    events: &[(String, bool)],
    initial: S,
    name: impl Fn(&S) -> String,
    step: impl Fn(&S, &str) -> Option<S>,
) -> Automaton {
    let mut spec = Spec::new(sup, &name(&initial));
    for (e, c) in events {
        spec.event(e, *c);
    }
    let events = spec.events.clone();
    let mut seen: HashMap<S, ()> = HashMap::new();
    seen.insert(initial.clone(), ());
    let mut queue = VecDeque::from([initial]);
    while let Some(s) = queue.pop_front() {
        for (e, _) in &events {
            if let Some(t) = step(&s, e) {
                spec.t(&name(&s), e, &name(&t));
                if seen.insert(t.clone(), ()).is_none() {
                    queue.push_back(t);
                }
            }
        }
    }
    spec.mark_all();
    spec.build()
}

/// Crane `u`'s controller (the paper's Fig. 5 for crane 1): a train that
/// reaches the crane's sensor is held there (its `run` disabled), loaded
/// (`st_ld` enabled only then) and released when loading finishes. Ours:
/// the other train's arrival is self-looped while one is held.
fn sup_crane(u: Unit) -> Automaton {
    let n = u.crane;
    let mut a = Spec::new(&format!("sup_crane{n}"), "idle");
    a.event(&format!("st_ld{n}"), true);
    for (i, _) in TRAINS {
        a.event(&run(i), true);
    }
    for (i, _) in TRAINS {
        a.event(&at(i, u.c), false);
    }
    a.event(&format!("f_ld{n}"), false);
    for (i, _) in TRAINS {
        let held = format!("train{i}");
        a.t("idle", &at(i, u.c), &held);
        a.t(&held, &format!("f_ld{n}"), "idle");
        a.t(&held, &format!("st_ld{n}"), &held);
        a.t("idle", &run(i), "idle");
        for (j, _) in TRAINS {
            if j != i {
                a.t(&held, &run(j), &held);
                a.t(&held, &at(j, u.c), &held);
            }
        }
    }
    a.mark_all();
    a.build()
}

/// Where a collision-protection controller sees one train.
#[derive(Clone, PartialEq, Eq, Hash)]
enum Place {
    /// Neither in the section nor at a sensor it is entered from.
    Away,
    /// Stopped at a sensor the section is entered from.
    At(usize),
    /// Departed into the section, not yet at its first sensor.
    Entering,
    /// In the section, at (or past) this sensor.
    In(usize),
}

impl Place {
    fn occupies(&self) -> bool {
        matches!(self, Place::Entering | Place::In(_))
    }
    fn name(&self) -> String {
        match self {
            Place::Away => "away".into(),
            Place::At(k) => format!("at{k}"),
            Place::Entering => "entering".into(),
            Place::In(k) => format!("in{k}"),
        }
    }
}

/// The collision protection of one section (the paper's Fig. 6): a train
/// may depart into it only while the other train is not in it.
fn sup_section(section: &[usize]) -> Automaton {
    let first = section[0];
    let last = *section.last().expect("a section has sensors");
    let name = format!("sup_section_{first}_{last}");
    // Sensors the section is entered from, and the switch position each
    // needs to lead into it.
    let entries: Vec<(usize, Option<(usize, char)>)> = (1..=SENSORS)
        .filter(|k| !section.contains(k))
        .flat_map(|k| {
            successors(k)
                .into_iter()
                .filter(|(m, _)| *m == first)
                .map(move |(_, cond)| (k, cond))
        })
        .collect();
    let switches: Vec<usize> = entries
        .iter()
        .filter_map(|(_, c)| c.map(|(w, _)| w))
        .collect();
    let mut events: Vec<(String, bool)> = Vec::new();
    for (i, _) in TRAINS {
        events.push((run(i), true));
    }
    for &w in &switches {
        for p in POSITIONS {
            events.push((sw(w, p), true));
        }
    }
    for (i, _) in TRAINS {
        for &(k, _) in &entries {
            events.push((at(i, k), false));
        }
        for &k in section {
            events.push((at(i, k), false));
        }
    }
    // State: each train's place, then the switches' positions.
    type State = (Vec<Place>, Vec<char>);
    let place_of = |k: usize| {
        if section.contains(&k) {
            Place::In(k)
        } else if entries.iter().any(|&(e, _)| e == k) {
            Place::At(k)
        } else {
            Place::Away
        }
    };
    let initial: State = (
        TRAINS.iter().map(|&(_, k)| place_of(k)).collect(),
        switches.iter().map(|_| 's').collect(),
    );
    let state_name = |(places, sws): &State| {
        let mut parts: Vec<String> = places
            .iter()
            .zip(TRAINS)
            .map(|(p, (i, _))| format!("t{i}:{}", p.name()))
            .collect();
        parts.extend(sws.iter().zip(&switches).map(|(p, w)| format!("sw{w}:{p}")));
        parts.join(",")
    };
    let step = |(places, sws): &State, e: &str| -> Option<State> {
        let mut places = places.clone();
        let mut sws = sws.clone();
        for (x, &w) in switches.iter().enumerate() {
            for p in POSITIONS {
                if e == sw(w, p) {
                    sws[x] = p;
                    return Some((places, sws));
                }
            }
        }
        for (t, (i, _)) in TRAINS.iter().enumerate() {
            if e == run(*i) {
                places[t] = match &places[t] {
                    Place::At(k) => {
                        let cond = entries.iter().find(|(e, _)| e == k).expect("an entry").1;
                        let into = cond.is_none_or(|(w, p)| {
                            let x = switches.iter().position(|&s| s == w).expect("tracked");
                            sws[x] == p
                        });
                        if !into {
                            Place::Away
                        } else if places.iter().any(Place::occupies) {
                            return None;
                        } else {
                            Place::Entering
                        }
                    }
                    Place::In(k) if *k == last => Place::Away,
                    other => other.clone(),
                };
                return Some((places, sws));
            }
            for k in 1..=SENSORS {
                if e == at(*i, k) {
                    places[t] = place_of(k);
                    return Some((places, sws));
                }
            }
        }
        unreachable!("every event of the alphabet is handled")
    };
    explore(&name, &events, initial, state_name, step)
}

/// Where a switch lock sees one train.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Lock {
    Away,
    At,
    Traversing,
}

/// Switch `w` stays set while a train traverses it: from a train's
/// departure at a sensor before the switch until it reaches one after.
fn sup_switch(w: usize) -> Automaton {
    let (before, after): (Vec<usize>, Vec<usize>) = {
        let u = UNITS
            .iter()
            .find(|u| u.div == w || u.merge == w)
            .expect("a unit's switch");
        if u.div == w {
            (vec![u.a], vec![u.b, u.c])
        } else {
            (vec![u.b, u.x], vec![u.e])
        }
    };
    let mut events: Vec<(String, bool)> = Vec::new();
    for p in POSITIONS {
        events.push((sw(w, p), true));
    }
    for (i, _) in TRAINS {
        events.push((run(i), true));
    }
    for (i, _) in TRAINS {
        for &k in before.iter().chain(&after) {
            events.push((at(i, k), false));
        }
    }
    let initial: Vec<Lock> = TRAINS
        .iter()
        .map(|&(_, k)| {
            if before.contains(&k) {
                Lock::At
            } else {
                Lock::Away
            }
        })
        .collect();
    let name = |s: &Vec<Lock>| {
        s.iter()
            .zip(TRAINS)
            .map(|(l, (i, _))| {
                let l = match l {
                    Lock::Away => "away",
                    Lock::At => "before",
                    Lock::Traversing => "on",
                };
                format!("t{i}:{l}")
            })
            .collect::<Vec<_>>()
            .join(",")
    };
    let step = |s: &Vec<Lock>, e: &str| -> Option<Vec<Lock>> {
        let mut s = s.clone();
        if POSITIONS.iter().any(|&p| e == sw(w, p)) {
            return (!s.contains(&Lock::Traversing)).then_some(s);
        }
        for (t, (i, _)) in TRAINS.iter().enumerate() {
            if e == run(*i) {
                if s[t] == Lock::At {
                    s[t] = Lock::Traversing;
                }
                return Some(s);
            }
            if before.iter().any(|&k| e == at(*i, k)) {
                s[t] = Lock::At;
                return Some(s);
            }
            if after.iter().any(|&k| e == at(*i, k)) {
                s[t] = Lock::Away;
                return Some(s);
            }
        }
        unreachable!("every event of the alphabet is handled")
    };
    explore(&format!("sup_switch{w}"), &events, initial, name, step)
}

/// Where a router sees its train, and what it did about the switch.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Phase {
    /// The switch is to be requested.
    Need,
    /// Requested, not yet set.
    Asked,
    /// Set as needed: the train may go.
    Set,
}

/// The router of train `i` at unit `u`: before the train leaves the
/// approach sensor it requests the diverging switch for its route, and
/// before it leaves the bypass or siding exit sensor it requests the
/// merging switch for the branch it is on; it holds the train (disables
/// `run`) until it has seen the switch set.
fn sup_route(i: usize, u: Unit) -> Automaton {
    let siding = ROUTES
        .iter()
        .find(|(t, _)| *t == i)
        .is_some_and(|(_, cranes)| cranes.contains(&u.crane));
    // The sensors the router acts at, the switch and position each needs.
    let needs: [(usize, usize, char); 3] = [
        (u.a, u.div, if siding { 'd' } else { 's' }),
        (u.b, u.merge, 's'),
        (u.x, u.merge, 'd'),
    ];
    let mut events: Vec<(String, bool)> = vec![(run(i), true)];
    for w in [u.div, u.merge] {
        for p in POSITIONS {
            events.push((req(i, w, p), true));
        }
    }
    for w in [u.div, u.merge] {
        for p in POSITIONS {
            events.push((sw(w, p), true));
        }
    }
    for (k, _, _) in needs {
        events.push((at(i, k), false));
    }
    // None: elsewhere; Some((index into needs, phase)).
    type State = Option<(usize, Phase)>;
    let start = TRAINS.iter().find(|(t, _)| *t == i).expect("a train").1;
    let initial: State = needs
        .iter()
        .position(|&(k, _, _)| k == start)
        .map(|n| (n, Phase::Need));
    let name = |s: &State| match s {
        None => "free".to_owned(),
        Some((n, phase)) => {
            let (k, w, p) = needs[*n];
            let phase = match phase {
                Phase::Need => "need",
                Phase::Asked => "asked",
                Phase::Set => "set",
            };
            format!("at{k}:sw{w}_{p}:{phase}")
        }
    };
    let step = |s: &State, e: &str| -> Option<State> {
        for (n, &(k, _, _)) in needs.iter().enumerate() {
            if e == at(i, k) {
                return Some(Some((n, Phase::Need)));
            }
        }
        if e == run(i) {
            return match s {
                None => Some(None),
                Some((_, Phase::Set)) => Some(None),
                Some(_) => None,
            };
        }
        for w in [u.div, u.merge] {
            for p in POSITIONS {
                if e == req(i, w, p) {
                    return match s {
                        Some((n, Phase::Need)) if needs[*n].1 == w && needs[*n].2 == p => {
                            Some(Some((*n, Phase::Asked)))
                        }
                        _ => None,
                    };
                }
                if e == sw(w, p) {
                    return Some(match s {
                        Some((n, phase)) if needs[*n].1 == w => {
                            if needs[*n].2 == p {
                                Some((*n, Phase::Set))
                            } else if *phase == Phase::Asked {
                                Some((*n, Phase::Asked))
                            } else {
                                Some((*n, Phase::Need))
                            }
                        }
                        other => *other,
                    });
                }
            }
        }
        unreachable!("every event of the alphabet is handled")
    };
    explore(
        &format!("sup_route_t{i}_crane{}", u.crane),
        &events,
        initial,
        name,
        step,
    )
}

/// Every file of `models/testbed/`, relative to it, with its text.
pub fn files() -> BTreeMap<String, String> {
    let mut plant: Vec<Automaton> = Vec::new();
    for (i, _) in TRAINS {
        plant.push(train(i));
    }
    for n in 1..=3 {
        plant.push(crane(n));
    }
    for (i, start) in TRAINS {
        plant.push(order(i, start));
    }
    for u in UNITS {
        plant.push(switch_dependency(u));
    }
    for w in 1..=6 {
        plant.push(switch(w));
    }
    for w in 1..=6 {
        plant.push(handler(w));
    }
    let mut sups: Vec<Automaton> = Vec::new();
    for (i, _) in TRAINS {
        for u in UNITS {
            sups.push(sup_route(i, u));
        }
    }
    let mut by_crane = UNITS;
    by_crane.sort_by_key(|u| u.crane);
    for u in by_crane {
        sups.push(sup_crane(u));
    }
    for w in 1..=6 {
        sups.push(sup_switch(w));
    }
    for s in SECTIONS {
        sups.push(sup_section(s));
    }
    let mut out = BTreeMap::new();
    let header = "# Generated by `cargo run -p des --example testbed -- models/testbed`\n\
                  # (crates/des/examples/testbed.rs); models/testbed/README.md explains it.\n";
    for (dir, kind, automata) in [
        ("plant", Kind::Plant, &plant),
        ("sup", Kind::Supervisor, &sups),
    ] {
        for a in automata {
            let text = formats::write_string(
                Format::Toml,
                &[Component {
                    kind,
                    automaton: a.clone(),
                }],
            )
            .expect("TOML holds any automaton");
            out.insert(
                format!("{dir}/{}.toml", a.name()),
                format!("{header}{text}"),
            );
        }
    }
    out
}

fn main() {
    let Some(dir) = std::env::args().nth(1) else {
        eprintln!("usage: cargo run -p des --example testbed -- DIR");
        std::process::exit(2);
    };
    let dir = Path::new(&dir);
    for (name, text) in files() {
        let path = dir.join(&name);
        let written = path
            .parent()
            .map_or(Ok(()), std::fs::create_dir_all)
            .and_then(|()| std::fs::write(&path, text));
        if let Err(e) = written {
            eprintln!("error: {}: {e}", path.display());
            std::process::exit(2);
        }
    }
}
