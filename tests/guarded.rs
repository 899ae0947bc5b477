//! Guards executed = the monolithic table executed (issue 24).
//!
//! For model instances small enough for both forms, two projects are
//! built from the same plant and specification files, with the same
//! events bound to the same inputs: one whose supervisor is synthesised
//! explicitly (`synthesize = { … }`, one automaton, `supcon`), one whose
//! supervisor is symbolic (`symbolic = true`: the components run as
//! supervisors and guards hold commands back). Both run in the executor
//! (table backend) on the same random input sequences; every scan must
//! execute the same events in the same order, find the same events
//! unexpected and fault alike. Policy `ignore` keeps most runs going past
//! events the closed loop cannot explain (plant behaviour the random
//! inputs invent), policy `fault` with a reset input covers fault mode.
//!
//! The instances: the `des_symbolic::families` at small sizes and random
//! modular instances (2–4 plants, 1–2 specifications over 6 events).
//! A third run of the symbolic project with its guards taken out shows
//! that the guards matter: its traces must differ from the others' on
//! some instances, or the comparison would prove nothing.

#[path = "common/symbolic.rs"]
mod symbolic;

use codegen::lower::TableImage;
use des::{Automaton, AutomatonBuilder};
use des_symbolic::families;
use executor::memory::HeapMemory;
use executor::{Controller, Fault, Program};
use plc_project::Project;
use symbolic::{project_text, write_models};

/// A small deterministic generator (xorshift64).
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n.max(1) as u64) as usize
    }

    fn one_in(&mut self, n: usize) -> bool {
        self.below(n) == 0
    }
}

/// Plant and specification components.
struct Instance {
    name: String,
    plants: Vec<Automaton>,
    specs: Vec<Automaton>,
}

/// A random modular instance over events `a0…a2` (controllable) and
/// `u0…u2` (uncontrollable): each automaton a random partial function
/// over a random part of them, every state marked with chance 1/2, the
/// initial state always.
fn random_instance(seed: u64) -> Instance {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let events: Vec<(String, bool)> = (0..3)
        .flat_map(|i| [(format!("a{i}"), true), (format!("u{i}"), false)])
        .collect();
    let automaton = |name: String, rng: &mut Rng, pool: &[usize]| {
        let mut alphabet: Vec<usize> = pool.iter().copied().filter(|_| rng.below(2) == 0).collect();
        if alphabet.is_empty() {
            alphabet.push(pool[rng.below(pool.len())]);
        }
        let states = 1 + rng.below(3);
        let mut b = AutomatonBuilder::new(&name);
        for &e in &alphabet {
            b.add_event(&events[e].0, events[e].1).unwrap();
        }
        for s in 0..states {
            b.add_state(&format!("q{s}"));
        }
        b.set_initial_by_name("q0").unwrap();
        b.mark_by_name("q0");
        for s in 0..states {
            if rng.one_in(2) {
                b.mark_by_name(&format!("q{s}"));
            }
            for &e in &alphabet {
                if rng.below(3) != 0 {
                    let t = rng.below(states);
                    b.add_transition_by_name(&format!("q{s}"), &events[e].0, &format!("q{t}"), 0)
                        .unwrap();
                }
            }
        }
        b.build().unwrap()
    };
    let all: Vec<usize> = (0..events.len()).collect();
    let plants: Vec<Automaton> = (0..2 + rng.below(3))
        .map(|i| automaton(format!("G{i}"), &mut rng, &all))
        .collect();
    let used: Vec<usize> = all
        .iter()
        .copied()
        .filter(|&e| {
            plants
                .iter()
                .any(|p| p.alphabet().id(&events[e].0).is_some())
        })
        .collect();
    let specs = (0..1 + rng.below(2))
        .map(|i| automaton(format!("E{i}"), &mut rng, &used))
        .collect();
    Instance {
        name: format!("random{seed}"),
        plants,
        specs,
    }
}

/// The families at sizes whose monolithic supervisor is small.
fn family_instances() -> Vec<Instance> {
    let sizes: [(&str, &[usize]); 5] = [
        ("ring", &[2, 3, 4]),
        ("ringb", &[2, 3]),
        ("tline", &[2, 3, 4]),
        ("phil", &[2, 3, 4]),
        ("module", &[2]),
    ];
    sizes
        .iter()
        .flat_map(|&(family, ns)| {
            ns.iter().map(move |&n| {
                let f = families::by_name(family, n).unwrap().unwrap();
                Instance {
                    name: f.name,
                    plants: f.plants,
                    specs: f.specs,
                }
            })
        })
        .collect()
}

/// One scan as compared: executed and unexpected events, the fault.
type Step = (Vec<u16>, Vec<u16>, Option<Fault>);

/// Runs `project` (table backend) on `inputs`, one image per scan.
fn run(project: &Project, inputs: &[Vec<bool>]) -> Vec<Step> {
    let image = TableImage::new(project).unwrap();
    let mut c = Controller::new(&image, HeapMemory::for_config(&image.config())).unwrap();
    assert_eq!(c.fault(), None, "the image passes the structure check");
    inputs
        .iter()
        .enumerate()
        .map(|(k, raw)| {
            let r = c.scan(10 * k as u32, raw);
            (r.executed.to_vec(), r.unexpected.to_vec(), r.fault)
        })
        .collect()
}

/// Random input images: each scan toggles one input with chance 1/2, the
/// reset input (input 0) now and then.
fn random_inputs(rng: &mut Rng, inputs: usize, scans: usize) -> Vec<Vec<bool>> {
    let mut image = vec![false; inputs];
    (0..scans)
        .map(|_| {
            if rng.one_in(2) {
                let i = rng.below(inputs);
                if i != 0 || rng.one_in(8) {
                    image[i] = !image[i];
                }
            }
            image.clone()
        })
        .collect()
}

#[test]
fn guards_executed_equal_the_monolithic_table_executed() {
    let mut rng = Rng(0x5EED);
    let instances = family_instances()
        .into_iter()
        .chain((0..500).map(random_instance));
    let (mut compared, mut refused, mut guards_mattered, mut scans, mut executed) =
        (0, 0, 0, 0usize, 0usize);
    for inst in instances {
        let dir = tempfile::tempdir().unwrap();
        let events = write_models(dir.path(), &inst.plants, &inst.specs);
        let policy = if rng.one_in(2) { "ignore" } else { "fault" };
        let commands = rng.below(3) as u16;
        let load = |symbolic: bool| {
            let text = project_text(&events, symbolic, policy, commands);
            plc_project::from_str(&text, &dir.path().join("x.plc.toml"))
        };
        let (monolithic, symbolic) = match (load(false), load(true)) {
            (Ok(m), Ok(s)) => (m, s),
            (Err(m), Err(s)) => {
                // The empty supervisor, refused alike.
                assert!(
                    m.to_string().contains("empty supervisor")
                        && s.to_string().contains("empty supervisor"),
                    "{}: {m} / {s}",
                    inst.name
                );
                refused += 1;
                continue;
            }
            (m, s) => panic!(
                "{}: one form builds, the other not: {:?} / {:?}",
                inst.name,
                m.err().map(|e| e.to_string()),
                s.err().map(|e| e.to_string())
            ),
        };
        let mut unguarded = symbolic.clone();
        unguarded.guarded.clear();
        let inputs = random_inputs(&mut rng, monolithic.inputs.len(), 300);
        let by_table = run(&monolithic, &inputs);
        let by_guards = run(&symbolic, &inputs);
        for (k, (t, g)) in by_table.iter().zip(&by_guards).enumerate() {
            assert_eq!(t, g, "{}: scan {k} (policy {policy})", inst.name);
        }
        if run(&unguarded, &inputs) != by_guards {
            guards_mattered += 1;
        }
        compared += 1;
        scans += inputs.len();
        executed += by_table.iter().map(|s| s.0.len()).sum::<usize>();
    }
    eprintln!(
        "{compared} instances compared over {scans} scans ({executed} events executed), {refused} refused alike as empty, guards mattered in {guards_mattered}"
    );
    assert!(compared >= 100, "{compared} instances compared");
    assert!(
        guards_mattered >= compared / 10,
        "guards held back a command in only {guards_mattered} of {compared} instances"
    );
    assert!(executed > scans / 4, "{executed} events in {scans} scans");
}
