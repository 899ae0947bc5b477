//! The batch process cell of Mušič, Matko et al. (SEEDS D, section 4 of
//! the seed paper), as rebuilt in `models/petri/cell/` (its README states
//! every interpretation): the paper's three claims about the recipe net
//! and its supervisor, and the figures of the nets and automata.

use des::ops;
use des::petri::admissible::make_admissible;
use des::petri::compare::against_supcon;
use des::petri::constraints::{self, Constraint};
use des::petri::reach::{reachability, reachability_with, Marked, Reachability};
use des::petri::synth::{synthesize, Supervised};
use des::petri::{read_file, PetriNet};
use std::path::{Path, PathBuf};

fn model(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models/petri/cell")
        .join(file)
}

fn cell() -> PetriNet {
    read_file(&model("cell.toml")).unwrap()
}

fn constraints_of(net: &PetriNet, file: &str) -> Vec<Constraint> {
    constraints::read_file(&model(file), net).unwrap()
}

fn closed_loop(plant: &PetriNet, file: &str) -> (Supervised, Reachability) {
    let s = synthesize(plant, &constraints_of(plant, file)).unwrap();
    let r = reachability(&s.net, 100_000).unwrap();
    (s, r)
}

/// The transition indices of `ids`.
fn transitions(net: &PetriNet, ids: &[&str]) -> Vec<usize> {
    ids.iter()
        .map(|id| net.transition(id).unwrap_or_else(|| panic!("no `{id}`")))
        .collect()
}

fn ids(net: &PetriNet, sequence: &[usize]) -> Vec<String> {
    sequence
        .iter()
        .map(|&t| net.transitions()[t].id.clone())
        .collect()
}

/// The marking after firing `sequence` from the initial one; panics if a
/// transition is not enabled on the way.
fn fire_all(net: &PetriNet, sequence: &[usize]) -> Vec<u32> {
    sequence.iter().fold(net.initial().clone(), |m, &t| {
        net.fire(&m, t)
            .unwrap_or_else(|| panic!("`{}` not enabled", net.transitions()[t].id))
    })
}

/// The places that ever hold more than one token.
fn unsafe_places(net: &PetriNet, r: &Reachability) -> Vec<String> {
    net.places()
        .iter()
        .zip(&r.bounds)
        .filter(|&(_, &b)| b > 1)
        .map(|(p, _)| p.id.clone())
        .collect()
}

/// `L` of the constraints as a dense matrix over the net's places.
fn matrix(net: &PetriNet, cs: &[Constraint]) -> Vec<Vec<i64>> {
    cs.iter()
        .map(|c| {
            let mut row = vec![0; net.places().len()];
            for &(p, w) in &c.weights {
                row[p] = w;
            }
            row
        })
        .collect()
}

#[test]
fn the_recipe_net_has_the_papers_dimensions_and_uncontrollable_transitions() {
    let plant = cell();
    let d = plant.incidence();
    // "the incidence matrix D_p is of dimension 42 × 28"
    assert_eq!((d.len(), d[0].len()), (42, 28));
    // "the matrix L is of dimension 5 × 42"
    let l = matrix(&plant, &constraints_of(&plant, "cell.constraints.toml"));
    assert_eq!((l.len(), l[0].len()), (5, 42));
    let uncontrollable: Vec<&str> = plant
        .transitions()
        .iter()
        .filter(|t| !t.controllable)
        .map(|t| t.id.as_str())
        .collect();
    assert_eq!(uncontrollable, ["t_ra2", "t_ra3", "t_rb2", "t_rb3"]);
    assert_eq!(plant.marking_name(plant.initial()), "ra13+rb13");
    // The merges of section 4.1: a product of one unit is the other
    // unit's input. Substance A of mixer a is what reactor a fills first,
    // substance B of mixer b what it fills second.
    let consumers = |place: &str| -> Vec<String> {
        let p = plant.place(place).unwrap();
        let t: Vec<usize> = (0..28).filter(|&t| d[p][t] < 0).collect();
        ids(&plant, &t)
    };
    assert_eq!(consumers("ma10"), ["t_ra1"]);
    assert_eq!(consumers("mb11"), ["t_ra2"]);
    assert_eq!(consumers("mb10"), ["t_rb1"]);
    assert_eq!(consumers("ma11"), ["t_rb2"]);
    // One discharge valve per mixing tank, whichever reactor it fills.
    assert_eq!(consumers("ra4"), ["t_ra2", "t_rb3"]);
    assert_eq!(consumers("rb4"), ["t_ra3", "t_rb2"]);
}

#[test]
fn the_pnml_file_is_the_same_net() {
    assert_eq!(read_file(&model("cell.pnml")).unwrap(), cell());
}

#[test]
fn without_a_supervisor_the_mixer_filling_valve_is_booked_twice() {
    let plant = cell();
    let r = reachability(&plant, 100_000).unwrap();
    assert_eq!(r.markings.len(), 1117);
    assert_eq!(r.automaton.num_transitions(), 3390);
    assert!(!r.is_safe());
    assert_eq!(
        unsafe_places(&plant, &r),
        ["ma5", "ma6", "ma7", "ma8", "ma9", "mb5", "mb6", "mb7", "mb8", "mb9", "ra4", "rb4"]
    );
    // Section 4.2: "places p_ma1 and p_ma2 are marked. If the transitions
    // t_ma1 and t_ma2 fire, the place p_ma5 … contains two tokens": the
    // first such marking is reached by starting both batches (t_ra8 marks
    // p_ma1, t_rb8 p_ma2) and firing t_ma1 and t_ma2.
    let ma5 = plant.place("ma5").unwrap();
    let k = (0..r.markings.len())
        .find(|&k| r.markings[k][ma5] == 2)
        .expect("p_ma5 holds two tokens");
    assert_eq!(
        plant.marking_name(&r.markings[k]),
        "ma3+ma4+2·ma5+ma6+ma7+mb1+mb2"
    );
    assert_eq!(
        ids(&plant, &r.firing_sequence(k)),
        ["t_ra8", "t_ma1", "t_rb8", "t_ma2"]
    );
    let before = fire_all(&plant, &transitions(&plant, &["t_ra8", "t_rb8"]));
    assert_eq!(plant.marking_name(&before), "ma1+ma2+mb1+mb2");
    // The recipe net itself neither deadlocks nor loses a transition: its
    // flaw is the double booking, not blocking.
    assert!(r.dead.is_empty());
    assert_eq!(r.live(28), [true; 28]);
}

#[test]
fn with_heating_and_resource_allocation_alone_the_cell_deadlocks() {
    let plant = cell();
    let (s, r) = closed_loop(&plant, "cell.resources.toml");
    assert_eq!(r.markings.len(), 295);
    assert_eq!(r.automaton.num_transitions(), 686);
    assert!(r.is_safe(), "(7) and (8) alone keep every place safe");
    let dead: Vec<String> = r
        .dead
        .iter()
        .map(|&k| s.net.marking_name(&r.markings[k]))
        .collect();
    // "In the case when two batches are started simultaneously, both
    // mixers may start preparing the same substance, e.g., substance B.
    // When this is ready, reactors keep waiting to substance A but this
    // is never ready because both mixers are booked." Also with A: each
    // reactor fills (or waits to fill) A and waits for B from the mixer
    // the other one holds.
    assert_eq!(
        dead,
        [
            "ma1+ma11+mb1+mb11+c1",
            "ma2+mb2+mb10+ra3+ra4",
            "ma2+ma10+mb2+rb3+rb4",
        ]
    );
    let both_b = r.dead[0];
    assert_eq!(
        ids(&s.net, &r.firing_sequence(both_b)),
        ["t_ra8", "t_mb2", "t_mb4", "t_mb6", "t_rb8", "t_ma2", "t_ma4", "t_ma6"]
    );
    // The paper's order, both batches started first, ends there too.
    let paper = transitions(
        &s.net,
        &[
            "t_ra8", "t_rb8", "t_ma2", "t_mb2", "t_ma4", "t_mb4", "t_ma6", "t_mb6",
        ],
    );
    assert_eq!(fire_all(&s.net, &paper), r.markings[both_b]);
    assert!(
        r.live(28).iter().all(|&live| !live),
        "every transition can die"
    );
}

#[test]
fn with_all_five_constraints_the_cell_is_safe_deadlock_free_and_live() {
    let plant = cell();
    let cs = constraints_of(&plant, "cell.constraints.toml");
    let (s, r) = closed_loop(&plant, "cell.constraints.toml");
    let control: Vec<&str> = s.control.iter().map(|c| c.id.as_str()).collect();
    assert_eq!(control, ["c1", "c2", "c3", "c4", "c5"]);
    assert!(s.control.iter().all(|c| c.initial == 1));
    assert_eq!(r.markings.len(), 265);
    assert_eq!(r.automaton.num_transitions(), 626);
    // "The analysis of the resulting net shows that all places are safe
    // and that the net is deadlock-free."
    assert_eq!(r.bounds.len(), 47);
    assert!(r.is_safe(), "bounds {:?}", r.bounds);
    assert!(r.dead.is_empty());
    assert_eq!(r.live(28), [true; 28]);
    // Each control place keeps its invariant L·m_p + m_c = b.
    for m in &r.markings {
        for (k, c) in cs.iter().enumerate() {
            assert_eq!(
                c.weighted(&m[..42]) + i128::from(m[42 + k]),
                i128::from(c.bound)
            );
        }
    }
    // The control places' arcs (D_c = −L·D_p): each start of a booking
    // takes the token, its end gives it back (c1 at "setpoint reached",
    // the others at the uncontrollable "mixing tank empty").
    let arcs: Vec<String> = s
        .control
        .iter()
        .map(|c| {
            let with = |sign: i64| {
                let t: Vec<usize> = (0..28)
                    .filter(|&t| c.incidence[t].signum() == sign)
                    .collect();
                ids(&plant, &t).join(" ")
            };
            format!("{} takes, {} gives", with(-1), with(1))
        })
        .collect();
    assert_eq!(
        arcs,
        [
            "t_ra1 t_rb1 takes, t_ra4 t_rb4 gives",
            "t_ma1 t_ma2 takes, t_ra2 t_rb3 gives",
            "t_mb1 t_mb2 takes, t_ra3 t_rb2 gives",
            "t_ma1 t_mb1 takes, t_ra2 t_rb2 gives",
            "t_ma2 t_mb2 takes, t_ra3 t_rb3 gives",
        ]
    );
}

#[test]
fn the_heating_constraint_as_first_written_is_refused_and_its_transform_is_not_the_papers() {
    let plant = cell();
    let original = constraints_of(&plant, "cell.heating.toml");
    let err = synthesize(&plant, &original).unwrap_err().to_string();
    assert!(
        err.contains("uncontrollable transition(s) `t_ra3`, `t_rb3` from firing"),
        "{err}"
    );
    let modified = constraints_of(&plant, "cell.constraints.toml")[0].clone();
    let modified_loop = synthesize(&plant, std::slice::from_ref(&modified)).unwrap();

    // The greedy transformation counts, for each uncontrollable transition
    // that raises L·m, the first of its input places in place order: t_ra3
    // gets ra6, t_rb3 gets ra4 (mixing tank a's discharge valve, before
    // rb6), then t_ra2 gets mb11 and t_rb2 gets ma11. The paper counts the
    // filling places ra3, ra6, rb3, rb6 instead.
    let transformed = make_admissible(&plant, &original[0]).unwrap();
    let counted: Vec<&str> = transformed
        .weights
        .iter()
        .map(|&(p, w)| {
            assert_eq!(w, 1);
            plant.places()[p].id.as_str()
        })
        .collect();
    assert_eq!(counted, ["ma11", "mb11", "ra4", "ra6", "ra9", "rb9"]);
    assert_eq!(transformed.bound, 1);
    let transformed_loop = synthesize(&plant, std::slice::from_ref(&transformed)).unwrap();

    // Both keep (6); neither is supcon of (6) (1108 states), nor does one
    // allow all the other does: the paper's form lets a reactor's B
    // preparation finish before it fills A, the transformed one lets both
    // reactors fill with A at once.
    let graph = |s: &Supervised| reachability(&s.net, 100_000).unwrap();
    let (m, t) = (graph(&modified_loop), graph(&transformed_loop));
    for r in [&m, &t] {
        assert!(r
            .markings
            .iter()
            .all(|k| original[0].weighted(&k[..42]) <= 1));
    }
    assert_eq!((m.markings.len(), t.markings.len()), (1068, 728));
    assert!(m.dead.is_empty());
    assert_eq!(t.dead.len(), 2, "the transformed form alone can deadlock");
    let both = ops::meet(&[&t.automaton, &m.automaton]).unwrap();
    let only = |a: &Reachability| {
        let d = ops::language_difference(&a.automaton, &both).expect("a string only it allows");
        assert!(d.in_first);
        d.string.join(" ")
    };
    // Reactor a starts filling A with its B already prepared (mb11 and
    // ra4 both counted by the transformed form) …
    assert_eq!(only(&m), "t_ra8 t_ma1 t_ma3 t_ma5 t_mb2 t_mb4 t_mb6 t_ra1");
    // … and both reactors fill A at once (ra3 and rb3 both counted by
    // the paper's).
    assert_eq!(
        only(&t),
        "t_ra8 t_ma1 t_ma3 t_ma5 t_ra1 t_rb8 t_mb1 t_mb3 t_mb5 t_rb1"
    );
    for s in [&modified_loop, &transformed_loop] {
        let cmp = against_supcon(&plant, &original, s, 100_000)
            .unwrap()
            .unwrap();
        assert_eq!(cmp.supcon_states, 1108);
        assert!(!cmp.difference.unwrap().in_first, "never beyond supcon");
    }
}

#[test]
fn marking_every_sensor_event_uncontrollable_keeps_the_five_constraints_admissible() {
    // Level switches, the temperature sensor, the reaction timer and the
    // "empty" events are sensor readings: only starting a preparation, a
    // filling or a batch is a command.
    const COMMANDS: [&str; 8] = [
        "t_ma1", "t_ma2", "t_mb1", "t_mb2", "t_ra1", "t_ra8", "t_rb1", "t_rb8",
    ];
    let text = std::fs::read_to_string(model("cell.toml")).unwrap();
    let mut sensors = 0;
    let text: String = text
        .lines()
        .map(|line| {
            let command = COMMANDS
                .iter()
                .any(|id| line.contains(&format!("id = \"{id}\"")));
            if line.contains("id = \"t_") && !command && line.contains("controllable = true") {
                sensors += 1;
                line.replace("controllable = true", "controllable = false")
            } else {
                line.to_owned()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_eq!(
        sensors, 16,
        "28 transitions: 8 commands, 4 already uncontrollable"
    );
    let strict =
        des::petri::read_str(&text, des::petri::NetFormat::Toml, Path::new("s.toml")).unwrap();
    assert_eq!(
        strict
            .transitions()
            .iter()
            .filter(|t| !t.controllable)
            .count(),
        20
    );
    let cs = constraints_of(&strict, "cell.constraints.toml");
    let s = synthesize(&strict, &cs).unwrap();
    let (paper, _) = closed_loop(&cell(), "cell.constraints.toml");
    for (c, p) in s.control.iter().zip(&paper.control) {
        assert_eq!(c.incidence, p.incidence);
        for (t, &w) in c.incidence.iter().enumerate() {
            if !strict.transitions()[t].controllable {
                assert!(w >= 0, "{} takes from {}", strict.transitions()[t].id, c.id);
            }
        }
    }
    let cmp = against_supcon(&strict, &cs, &s, 100_000).unwrap().unwrap();
    assert_eq!(cmp.difference, None);
    assert_eq!(cmp.supcon_states, 265);
}

#[test]
fn the_invariant_supervisor_is_supcons_language_and_the_papers_deadlock_prevention_is_not_the_least_restrictive(
) {
    let plant = cell();
    let five = constraints_of(&plant, "cell.constraints.toml");
    let (s, r) = closed_loop(&plant, "cell.constraints.toml");
    let cmp = against_supcon(&plant, &five, &s, 100_000).unwrap().unwrap();
    assert_eq!(cmp.difference, None);
    assert_eq!((cmp.controlled_states, cmp.supcon_states), (265, 265));

    // supcon with the completed batches (the initial marking) marked, so
    // that it also removes blocking: against the five constraints it is
    // the controlled net again, markings and all.
    let plant_graph = reachability(&plant, 100_000).unwrap().automaton;
    let nonblocking = |cs: &[Constraint]| {
        let legal = |m: &[u32]| cs.iter().all(|c| c.weighted(m) <= i128::from(c.bound));
        let spec = reachability_with(&plant, 100_000, Marked::Initial, &legal)
            .unwrap()
            .automaton;
        ops::supcon(&plant_graph, &spec).unwrap()
    };
    let sup = nonblocking(&five);
    assert_eq!(sup.num_states(), 265);
    assert_eq!(ops::language_difference(&r.automaton, &sup), None);

    // Against heating, (7) and (8) alone, supcon avoids the deadlocks
    // with 6 states more: it lets mixer a prepare B for reactor b while
    // reactor a still takes B from mixer b, which the batch-B constraint
    // forbids.
    let sup = nonblocking(&constraints_of(&plant, "cell.resources.toml"));
    assert_eq!((sup.num_states(), sup.num_transitions()), (271, 638));
    let d = ops::language_difference(&r.automaton, &sup).expect("supcon allows more");
    assert!(!d.in_first);
    assert_eq!(
        d.string,
        [
            "t_ra8", "t_ma1", "t_ma3", "t_ma5", "t_mb2", "t_mb4", "t_mb6", "t_ra1", "t_ra2",
            "t_rb8", "t_ma2"
        ]
    );
    let both = ops::meet(&[&r.automaton, &sup]).unwrap();
    assert_eq!(
        ops::language_difference(&both, &r.automaton),
        None,
        "the five constraints allow nothing supcon does not"
    );
}
