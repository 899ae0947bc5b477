//! Scalable benchmark families as libFAUDES `.gen` files.
//!
//! ```text
//! cargo run --release -p des --example families -- FAMILY N OUTDIR
//! ```
//!
//! writes the plant components `M*.gen`/`P*.gen`/`F*.gen` and the
//! specifications `B*.gen` of instance `N` into `OUTDIR` (created). The
//! families, each with its monolithic supcon size:
//!
//! - `tline N`: a transfer line of `N` machines in series with `N - 1`
//!   buffers of one slot. Machine `i` (plant `Mi`, Wonham's small-factory
//!   machine): `I -si-> W` (start, controllable), `W -fi-> I` (finish,
//!   uncontrollable), `W -bi-> D` (breakdown, uncontrollable), `D -ri-> I`
//!   (repair, controllable); every machine marked in `I`. Buffer `i`
//!   (specification `Bi`, `i < N`): `0 -fi-> 1 -s(i+1)-> 0`, marked in `0`.
//!   The supervisor has `3 · 4^(N-1)` states (tline9: 196,608; tline10:
//!   786,432).
//! - `ringb N`: `N` machines in a cycle with `N` buffers of one slot.
//!   Machine `i` (plant `Mi`) breaks down while working and is repaired
//!   back to work, keeping its part: `I -si-> W -fi-> I`, `W -bi-> D -ri->
//!   W` (`si`, `ri` controllable). Buffer `i` (specification `Bi`): `fi`
//!   fills it, `s(i mod N + 1)` empties it; the odd buffers start full
//!   (`⌈N/2⌉` parts circulate) and each is marked in its initial fill. As
//!   `ringb` of the `des-symbolic` families (and issue 23's "ring");
//!   ringb12 has 673,596
//!   supervisor states.
//! - `phil N`: `N` dining philosophers as in `/work/shared/bench/phil*`:
//!   philosopher `Pi` takes its left fork (`ei01`) and its right fork
//!   (`ei03`) in either order and puts both back (`ei05`); fork `Fi` is
//!   taken by `Pi`'s left and `P(i-1)`'s right. All plant, no
//!   specification; every event controllable. The supervisor has
//!   `3^N - 2` states.

use des::formats::{write_file, Component, Kind};
use des::{Automaton, AutomatonBuilder};
use std::path::Path;

/// An automaton from `(event, controllable)`, transitions
/// `(from, event, to)`, the initial state and the marked states.
fn automaton(
    name: &str,
    events: &[(String, bool)],
    transitions: &[(&str, String, &str)],
    initial: &str,
    marked: &[&str],
) -> Automaton {
    let mut b = AutomatonBuilder::new(name);
    for (e, c) in events {
        b.add_event(e, *c).expect("distinct controllability");
    }
    b.set_initial_by_name(initial).expect("one initial state");
    for m in marked {
        b.mark_by_name(m);
    }
    for (s, e, t) in transitions {
        b.add_transition_by_name(s, e, t, 0).expect("known event");
    }
    b.build().expect("deterministic")
}

/// Machine `i` with breakdowns (the small factory's machine).
fn machine(i: usize) -> Automaton {
    let (s, f, b, r) = (
        format!("s{i}"),
        format!("f{i}"),
        format!("b{i}"),
        format!("r{i}"),
    );
    automaton(
        &format!("M{i}"),
        &[
            (s.clone(), true),
            (f.clone(), false),
            (b.clone(), false),
            (r.clone(), true),
        ],
        &[("I", s, "W"), ("W", f, "I"), ("W", b, "D"), ("D", r, "I")],
        "I",
        &["I"],
    )
}

/// A buffer of one slot filled by `fill` (uncontrollable) and emptied by
/// `take` (controllable), starting in `initial` (`0` empty, `1` full) and
/// marked there.
fn buffer(i: usize, fill: String, take: String, initial: &str) -> Automaton {
    automaton(
        &format!("B{i}"),
        &[(fill.clone(), false), (take.clone(), true)],
        &[("0", fill, "1"), ("1", take, "0")],
        initial,
        &[initial],
    )
}

/// The transfer line of `n` machines.
fn tline(n: usize) -> (Vec<Automaton>, Vec<Automaton>) {
    let plants = (1..=n).map(machine).collect();
    let specs = (1..n)
        .map(|i| buffer(i, format!("f{i}"), format!("s{}", i + 1), "0"))
        .collect();
    (plants, specs)
}

/// Machine `i` that breaks down while working and is repaired back to
/// work, keeping its part: `I -si-> W -fi-> I`, `W -bi-> D -ri-> W`.
fn repairing_machine(i: usize) -> Automaton {
    let (s, f, b, r) = (
        format!("s{i}"),
        format!("f{i}"),
        format!("b{i}"),
        format!("r{i}"),
    );
    automaton(
        &format!("M{i}"),
        &[
            (s.clone(), true),
            (f.clone(), false),
            (b.clone(), false),
            (r.clone(), true),
        ],
        &[("I", s, "W"), ("W", f, "I"), ("W", b, "D"), ("D", r, "W")],
        "I",
        &["I"],
    )
}

/// The ring of `n` repairing machines: buffer `i` between `fi` and
/// `s(i mod n + 1)`, full at first for odd `i`.
fn ring(n: usize) -> (Vec<Automaton>, Vec<Automaton>) {
    let plants = (1..=n).map(repairing_machine).collect();
    let specs = (1..=n)
        .map(|i| {
            let initial = if i % 2 == 1 { "1" } else { "0" };
            buffer(i, format!("f{i}"), format!("s{}", i % n + 1), initial)
        })
        .collect();
    (plants, specs)
}

/// `n` dining philosophers and their forks.
fn phil(n: usize) -> Vec<Automaton> {
    let mut out = Vec::new();
    for i in 1..=n {
        let (l, r, d) = (format!("e{i}01"), format!("e{i}03"), format!("e{i}05"));
        out.push(automaton(
            &format!("P{i}"),
            &[(l.clone(), true), (r.clone(), true), (d.clone(), true)],
            &[
                ("n", l.clone(), "l"),
                ("n", r.clone(), "r"),
                ("l", r, "b"),
                ("r", l, "b"),
                ("b", d, "n"),
            ],
            "n",
            &["n"],
        ));
    }
    for i in 1..=n {
        // Fork i: philosopher i's left, philosopher i-1's right.
        let p = if i == 1 { n } else { i - 1 };
        let (l, dl, r, dr) = (
            format!("e{i}01"),
            format!("e{i}05"),
            format!("e{p}03"),
            format!("e{p}05"),
        );
        out.push(automaton(
            &format!("F{i}"),
            &[
                (l.clone(), true),
                (dl.clone(), true),
                (r.clone(), true),
                (dr.clone(), true),
            ],
            &[("a", l, "t"), ("a", r, "t"), ("t", dl, "a"), ("t", dr, "a")],
            "a",
            &["a"],
        ));
    }
    out
}

fn write(dir: &Path, kind: Kind, automata: Vec<Automaton>) -> Result<(), String> {
    for a in automata {
        let path = dir.join(format!("{}.gen", a.name()));
        write_file(&path, &[Component { kind, automaton: a }]).map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [family, n, dir] = args.as_slice() else {
        return Err("usage: families tline|ringb|phil N OUTDIR".into());
    };
    let n: usize = n
        .parse()
        .ok()
        .filter(|&n| n >= 2)
        .ok_or("N must be a number >= 2")?;
    let dir = Path::new(dir);
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let (plants, specs) = match family.as_str() {
        "tline" => tline(n),
        "ringb" => ring(n),
        "phil" => (phil(n), Vec::new()),
        other => return Err(format!("unknown family `{other}` (tline, ringb, phil)")),
    };
    write(dir, Kind::Plant, plants)?;
    write(dir, Kind::Spec, specs)
}
