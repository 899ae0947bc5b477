//! The four automaton file formats: every benchmark model reads, every
//! format round-trips, conversions between formats preserve the automaton,
//! errors point at the right line, and no input makes a reader panic.

use des::formats::{self, ads, gen, read_str, wmod, Component, Format, Kind};
use des::{Automaton, AutomatonBuilder, Error, StateId};
use proptest::prelude::*;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/formats")
        .join(name)
}

fn fixture_text(name: &str) -> String {
    std::fs::read_to_string(fixture(name)).unwrap()
}

/// The benchmark models (`models/bench`).
fn bench_root() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/bench");
    assert!(
        root.is_dir(),
        "benchmark models not found at {}",
        root.display()
    );
    root
}

fn bench_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for set in std::fs::read_dir(bench_root()).unwrap() {
        let set = set.unwrap().path();
        if !set.is_dir() {
            continue;
        }
        for f in std::fs::read_dir(&set).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == "gen") {
                files.push(f);
            }
        }
    }
    files.sort();
    assert!(
        files.len() >= 60,
        "expected the benchmark sets, found {files:?}"
    );
    files
}

fn bench(set: &str, name: &str) -> Automaton {
    formats::read_automaton(&bench_root().join(set).join(format!("{name}.gen"))).unwrap()
}

/// A readable, order-independent description: name, events with
/// controllability, states by name, initial, marked and transitions by
/// names. Two automata with equal descriptions are the same automaton up
/// to the numbering of events and states.
#[derive(Debug, PartialEq, Eq)]
struct Described {
    name: String,
    /// Controllable, observable.
    events: BTreeMap<String, (bool, bool)>,
    states: BTreeSet<String>,
    initial: Option<String>,
    marked: BTreeSet<String>,
    transitions: BTreeSet<(String, String, String)>,
}

fn describe(a: &Automaton) -> Described {
    let st = |s: StateId| a.state_name(s).into_owned();
    let states: BTreeSet<String> = a.states().map(st).collect();
    assert_eq!(states.len(), a.num_states(), "state names are unique");
    Described {
        name: a.name().to_owned(),
        events: a
            .alphabet()
            .iter()
            .map(|(_, e)| (e.name.clone(), (e.controllable, e.observable)))
            .collect(),
        states,
        initial: a.initial().map(st),
        marked: a.marked_states().map(st).collect(),
        transitions: a
            .iter_transitions()
            .map(|(s, e, t)| (st(s), a.alphabet().name(e).to_owned(), st(t)))
            .collect(),
    }
}

fn assert_same(a: &Automaton, b: &Automaton, context: &str) {
    assert_eq!(describe(a), describe(b), "{context}");
    assert_eq!(a.num_transitions(), b.num_transitions(), "{context}");
}

fn one(format: Format, text: &str) -> Automaton {
    let mut cs = read_str(text, format, Path::new("roundtrip")).unwrap_or_else(|e| {
        panic!("{format:?} reading its own output failed: {e}\n{text}");
    });
    assert_eq!(cs.len(), 1);
    cs.remove(0).automaton
}

fn through(format: Format, a: &Automaton) -> Automaton {
    let text = formats::write_string(format, &[Component::unspecified(a.clone())]).unwrap();
    one(format, &text)
}

fn location(e: &Error) -> (u32, u32) {
    match e {
        Error::Syntax { location, .. } | Error::Model { location, .. } => {
            (location.line, location.column)
        }
        other => panic!("expected a located error, got {other:?}"),
    }
}

// ---------------------------------------------------------------------
// Benchmark models

#[test]
fn smallfactory_mach1_reads_with_its_controllability() {
    let m = bench("smallfactory", "MACH1");
    assert_eq!(m.name(), "MACH1");
    assert_eq!((m.num_states(), m.num_transitions()), (3, 4));
    let ab = m.alphabet();
    assert!(ab.is_controllable(ab.id("e11").unwrap()));
    assert!(ab.is_controllable(ab.id("e13").unwrap()));
    assert!(!ab.is_controllable(ab.id("e10").unwrap()));
    assert!(!ab.is_controllable(ab.id("e12").unwrap()));
    assert_eq!(m.initial(), Some(StateId(0)));
    assert_eq!(m.marked_states().collect::<Vec<_>>(), [StateId(0)]);
}

#[test]
fn phil5_p1_has_named_states() {
    let p = bench("phil5", "P1");
    let names: Vec<_> = p.states().map(|s| p.state_name(s).into_owned()).collect();
    assert_eq!(names, ["b", "l", "n", "r"]);
    assert_eq!(p.num_transitions(), 5);
    assert_eq!(p.state_name(p.initial().unwrap()), "n");
    assert_eq!(p.alphabet().controllable_count(), 3);
}

#[test]
fn every_benchmark_model_reads_and_round_trips_through_every_format() {
    let mut total = (0, 0);
    for f in bench_files() {
        let a = formats::read_automaton(&f).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            a.num_states() > 0 && a.initial().is_some(),
            "{}",
            f.display()
        );
        total.0 += a.num_states();
        total.1 += a.num_transitions();
        let ctx = f.display().to_string();
        // .gen and .wmod keep even the numbering. Only .gen can say
        // "controllability not stated" (a plain generator, as the
        // specification files are); the other formats always state it, so
        // such a file comes back stated with its events uncontrollable.
        assert_eq!(through(Format::Gen, &a), a, "{ctx}: gen");
        let mut stated = a.clone();
        stated.set_controllability_stated(true);
        assert_eq!(through(Format::Wmod, &a), stated, "{ctx}: wmod");
        assert_same(&through(Format::Toml, &a), &a, &format!("{ctx}: toml"));
        assert_same(&through(Format::Ads, &a), &a, &format!("{ctx}: ads"));
    }
    assert!(total.1 > 100, "{total:?}");
}

#[test]
fn conversion_gen_wmod_toml_ads_gen_preserves_the_automaton() {
    for (set, name) in [
        ("smallfactory", "MACH1"),
        ("phil5", "P1"),
        ("transferline", "TU"),
        ("agv", "Z1SPEC"),
    ] {
        let a = bench(set, name);
        let w = through(Format::Wmod, &a);
        let t = through(Format::Toml, &w);
        let d = through(Format::Ads, &t);
        let g = through(Format::Gen, &d);
        assert_same(&g, &a, &format!("{set}/{name}"));
    }
}

// ---------------------------------------------------------------------
// Fixtures written by other tools

#[test]
fn a_file_written_by_libfaudes_reads_identically_in_both_flavours() {
    let plain = formats::read_automaton(&fixture("faudes_mixed.gen")).unwrap();
    let xml = formats::read_automaton(&fixture("faudes_mixed_xml.gen")).unwrap();
    assert_eq!(plain, xml);
    assert_eq!(plain.name(), "my gen");
    // 44 indexed states minus 2 deleted, plus idle and busy.
    assert_eq!((plain.num_states(), plain.num_transitions()), (44, 4));
    assert_eq!(plain.state_name(plain.initial().unwrap()), "idle");
    let marked: Vec<_> = plain
        .marked_states()
        .map(|s| plain.state_name(s).into_owned())
        .collect();
    assert_eq!(marked, ["3", "busy"]);
    assert_eq!(plain.state_by_name("5"), None, "deleted state 5 is gone");
    let b = plain.alphabet().id("b").unwrap();
    let four = plain.state_by_name("4").unwrap();
    assert_eq!(plain.successor(four, b), plain.state_by_name("44"));
    assert!(plain
        .alphabet()
        .is_controllable(plain.alphabet().id("c").unwrap()));
    assert_eq!(through(Format::Gen, &plain), plain);
}

#[test]
fn an_unnamed_libfaudes_file_with_ranges_is_renumbered_densely() {
    let a = formats::read_automaton(&fixture("faudes_unnamed.gen")).unwrap();
    assert!(!a.has_state_names());
    assert_eq!((a.num_states(), a.num_transitions()), (29, 29));
    assert_eq!(a.initial(), Some(StateId(0)));
    // libFAUDES state 13 follows 11 (12 was deleted): dense index 11.
    let done = a.alphabet().id("done").unwrap();
    assert_eq!(a.successor(StateId(10), done), Some(StateId(11)));
    assert_eq!(through(Format::Gen, &a), a);
}

#[test]
fn a_file_written_by_tct_reads_with_numeric_event_names() {
    let a = formats::read_automaton(&fixture("tct_mach1.ads")).unwrap();
    let m = bench("smallfactory", "MACH1");
    assert_eq!((a.num_states(), a.num_transitions()), (3, 4));
    // Same automaton as the benchmark's MACH1, with events `11` for `e11`.
    for (s, e, t) in m.iter_transitions() {
        let label = &m.alphabet().name(e)[1..];
        let e2 = a.alphabet().id(label).unwrap();
        assert_eq!(a.successor(s, e2), Some(t));
        assert_eq!(
            a.alphabet().is_controllable(e2),
            m.alphabet().is_controllable(e)
        );
    }
}

#[test]
fn a_waters_module_reads_all_components_with_kinds() {
    let cs = formats::read_file(&fixture("smallfactory.wmod")).unwrap();
    let kinds: Vec<_> = cs.iter().map(|c| (c.automaton.name(), c.kind)).collect();
    assert_eq!(
        kinds,
        [
            ("MACH1", Kind::Plant),
            ("BUFSPEC", Kind::Spec),
            ("NEVER_E20_FIRST", Kind::Property)
        ]
    );
    let mach1 = &cs[0].automaton;
    assert_eq!((mach1.num_states(), mach1.num_transitions()), (3, 4));
    assert_eq!(mach1.marked_states().count(), 1);
    let buf = &cs[1].automaton;
    assert_eq!(buf.marked_states().count(), 1);
    let prop = &cs[2].automaton;
    assert_eq!(
        prop.alphabet().len(),
        3,
        "blocked e20 belongs to the alphabet"
    );
    assert_eq!(prop.marked_states().count(), 1, "no :accepting: all marked");
    let text = wmod::write(&cs);
    assert_eq!(wmod::read(&text, Path::new("again.wmod")).unwrap(), cs);

    let toml = formats::read_file(&fixture("mach1.toml")).unwrap();
    assert_eq!(toml[0].kind, Kind::Plant);
    let t = &toml[0].automaton;
    assert_eq!((t.num_states(), t.num_transitions()), (3, 4));
}

// ---------------------------------------------------------------------
// Errors

#[test]
fn errors_name_the_file_line_and_column() {
    let path = fixture("bad_transition.toml");
    let e = formats::read_file(&path).unwrap_err();
    assert_eq!(location(&e), (9, 15));
    let shown = e.to_string();
    assert!(
        shown.starts_with(&format!("{}:9:15: ", path.display())),
        "{shown}"
    );
    assert!(shown.contains("`finsh`"), "{shown}");
}

#[test]
fn error_lines_are_exact_in_every_format() {
    let p = Path::new("x");
    let cases: &[(Format, &str, (u32, u32), &str)] = &[
        // Malformed tokens.
        (
            Format::Gen,
            "<Generator>\n<Alphabet>\n  a +C\n</Alphabet>\n</Generator>",
            (3, 5),
            "unterminated attribute",
        ),
        (
            Format::Gen,
            "<Generator>\n<Alphabet> a </Alphabet>\n<States> x </States\n",
            (3, 12),
            "unterminated tag",
        ),
        (
            Format::Toml,
            "name = \"x\"\ninitial = 'a\n",
            (2, 13),
            "",
        ),
        (
            Format::Ads,
            "X\nState size (State set will be (0,1....,size-1)):\n2\n\nTransitions:\n0 1 1\n1 1x 0\n",
            (7, 3),
            "transition label",
        ),
        // Unknown events.
        (
            Format::Gen,
            "<Generator>\n<Alphabet> a </Alphabet>\n<States> x </States>\n<TransRel>\nx a x\n  x b x\n</TransRel>\n</Generator>",
            (6, 5),
            "event `b`",
        ),
        (
            Format::Toml,
            "name = \"x\"\ninitial = \"s\"\ncontrollable = [\"a\"]\ntransitions = [\n  [\"s\", \"a\", \"s\"],\n  [\"s\", \"b\", \"s\"],\n]\n",
            (6, 9),
            "event `b`",
        ),
        // Nondeterminism.
        (
            Format::Gen,
            "<Generator>\n<Alphabet> a </Alphabet>\n<States> x y </States>\n<TransRel>\nx a x\nx a y\n</TransRel>\n</Generator>",
            (6, 1),
            "line 5",
        ),
        (
            Format::Toml,
            "name = \"x\"\ninitial = \"s\"\ncontrollable = [\"a\"]\ntransitions = [\n  [\"s\", \"a\", \"s\"],\n  [\"s\", \"a\", \"t\"],\n]\n",
            (6, 3),
            "line 5",
        ),
        (
            Format::Ads,
            "X\nState size (State set will be (0,1....,size-1)):\n2\n\nTransitions:\n0 1 1\n0 1 0\n",
            (7, 1),
            "line 6",
        ),
        // Undeclared states when the states are listed.
        (
            Format::Toml,
            "name = \"x\"\ninitial = \"s\"\ncontrollable = [\"a\"]\nstates = [\"s\"]\ntransitions = [\n  [\"s\", \"a\", \"t\"],\n]\n",
            (6, 14),
            "`t` is not declared",
        ),
        (
            Format::Gen,
            "<Generator>\n<Alphabet> a </Alphabet>\n<States> x </States>\n<MarkedStates>\n z\n</MarkedStates>\n</Generator>",
            (5, 2),
            "`z` is not declared",
        ),
        // Two initial states.
        (
            Format::Gen,
            "<Generator>\n<States> x y </States>\n<InitStates> x\ny </InitStates>\n</Generator>",
            (4, 1),
            "two initial states",
        ),
        (
            Format::Wmod,
            "<Module xmlns=\"http://waters.sourceforge.net/xsd/module\" Name=\"m\">\n<ComponentList>\n<SimpleComponent Kind=\"PLANT\" Name=\"p\"><Graph><NodeList>\n<SimpleNode Name=\"a\" Initial=\"true\"/>\n<SimpleNode Name=\"b\" Initial=\"true\"/>\n</NodeList></Graph></SimpleComponent>\n</ComponentList>\n</Module>",
            (5, 1),
            "two initial states",
        ),
        // Bad XML.
        (
            Format::Wmod,
            "<Module xmlns=\"http://waters.sourceforge.net/xsd/module\">\n<EventDeclList>\n</EventDecList>\n</Module>",
            (3, 1),
            "malformed XML",
        ),
        (
            Format::Gen,
            "<?xml version=\"1.0\"?>\n<Generator name=\"g\">\n<StateSet>\n<State id=\"1\">\n</StateSet>\n</Generator>",
            (5, 1),
            "malformed XML",
        ),
    ];
    for (format, text, at, needle) in cases {
        let e = read_str(text, *format, p).expect_err(text);
        assert_eq!(location(&e), *at, "{format:?}: {e}\n{text}");
        assert!(e.to_string().contains(needle), "{format:?}: {e}");
    }
}

// ---------------------------------------------------------------------
// Round trips of generated automata

/// Names that exercise quoting and escaping, plus plain ones.
fn name() -> impl Strategy<Value = String> {
    prop_oneof![
        "[a-z][a-z0-9_]{0,6}",
        "[0-9]{1,3}",
        "e[0-9]{1,3}",
        "[ -~]{0,8}",
        "[a-zé#&<>\" ]{1,6}",
    ]
}

#[derive(Debug, Clone)]
struct Spec {
    name: String,
    events: Vec<(String, bool)>,
    states: Option<Vec<String>>,
    n: usize,
    initial: Option<usize>,
    marked: Vec<usize>,
    transitions: Vec<(usize, usize, usize)>,
}

fn spec() -> impl Strategy<Value = Spec> {
    (
        name(),
        prop::collection::vec((name(), any::<bool>()), 0..6),
        0usize..7,
        any::<bool>(),
        prop::collection::vec(name(), 7),
    )
        .prop_flat_map(|(name, events, n, named, state_names)| {
            let ne = events.len();
            (
                Just(name),
                Just(events),
                Just(n),
                Just(named),
                Just(state_names),
                if n == 0 {
                    Just(None).boxed()
                } else {
                    prop::option::of(0..n).boxed()
                },
                prop::collection::vec(0..n.max(1), 0..=n),
                prop::collection::vec((0..n.max(1), 0..ne.max(1), 0..n.max(1)), 0..12),
            )
        })
        .prop_map(
            |(name, events, n, named, state_names, initial, marked, transitions)| {
                // Unique names (the model requires it).
                let mut seen = BTreeSet::new();
                let events: Vec<_> = events
                    .into_iter()
                    .filter(|(e, _)| seen.insert(e.clone()))
                    .collect();
                let mut seen = BTreeSet::new();
                let states = named.then(|| {
                    state_names
                        .into_iter()
                        .enumerate()
                        .map(|(i, s)| {
                            if seen.insert(s.clone()) {
                                s
                            } else {
                                format!("{s}~{i}")
                            }
                        })
                        .take(n)
                        .collect()
                });
                let transitions = if events.is_empty() || n == 0 {
                    Vec::new()
                } else {
                    let ne = events.len();
                    transitions
                        .into_iter()
                        .map(|(s, e, t)| (s, e % ne, t))
                        .collect()
                };
                Spec {
                    name,
                    events,
                    states,
                    n,
                    initial,
                    marked: if n == 0 { Vec::new() } else { marked },
                    transitions,
                }
            },
        )
}

fn build(spec: &Spec) -> Automaton {
    let mut b = AutomatonBuilder::new(spec.name.clone());
    let events: Vec<_> = spec
        .events
        .iter()
        .map(|(e, c)| b.add_event(e, *c).unwrap())
        .collect();
    let states: Vec<_> = (0..spec.n)
        .map(|i| match &spec.states {
            Some(names) => b.add_state(&names[i]),
            None => b.add_anonymous_state(),
        })
        .collect();
    if let Some(i) = spec.initial {
        b.set_initial(states[i]).unwrap();
    }
    for &m in &spec.marked {
        b.mark(states[m]);
    }
    // Keep the first transition per (source, event): deterministic.
    let mut taken = BTreeSet::new();
    for &(s, e, t) in &spec.transitions {
        if taken.insert((s, e)) {
            b.add_transition(states[s], events[e], states[t], 0);
        }
    }
    let mut a = b.build().unwrap();
    // Names equal to indices read back as unnamed (see formats::gen).
    let plain = a.states().all(|s| a.state_name(s) == s.0.to_string());
    if plain {
        a.clear_state_names();
    }
    a
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn generated_automata_round_trip(spec in spec()) {
        let a = build(&spec);
        // .gen keeps everything, numbering included.
        prop_assert_eq!(&through(Format::Gen, &a), &a);
        // TOML lists controllable events first.
        let t = formats::toml::read(
            &formats::toml::write(&Component { kind: Kind::Spec, automaton: a.clone() }),
            Path::new("t"),
        ).unwrap();
        prop_assert_eq!(t.kind, Kind::Spec);
        prop_assert_eq!(describe(&t.automaton), describe(&a));
        // .wmod cannot carry most control characters; the names here have none.
        prop_assert_eq!(&through(Format::Wmod, &a), &a);
        // ADS moves the initial state to 0; names (or, unnamed, the
        // numbering when the initial state already is 0) survive.
        let d = through(Format::Ads, &a);
        if a.initial().is_some() {
            if a.has_state_names() || a.initial() == Some(StateId(0)) {
                prop_assert_eq!(describe(&d), describe(&a));
            } else {
                prop_assert_eq!(d.num_states(), a.num_states());
                prop_assert_eq!(d.num_transitions(), a.num_transitions());
            }
        } else {
            prop_assert!(d.is_empty(), "no initial state: the empty language");
        }
        prop_assert!(d.alphabet().same_events(a.alphabet()));
        prop_assert_eq!(d.name(), a.name());
    }

    #[test]
    fn unobservable_events_round_trip_where_a_format_can_say_so(spec in spec(), every in 1usize..4) {
        let mut b = AutomatonBuilder::new("h");
        for (k, (e, c)) in spec.events.iter().enumerate() {
            let id = b.add_event(e, *c).unwrap();
            if k % every == 0 {
                b.set_unobservable(id);
            }
        }
        let h = b.build().unwrap();
        for format in [Format::Gen, Format::Toml, Format::Wmod] {
            prop_assert_eq!(describe(&through(format, &h)), describe(&h), "{:?}", format);
        }
        let a = build(&spec);
        let hidden = a.alphabet().unobservable().count();
        prop_assert_eq!(hidden, 0);
        if !spec.events.is_empty() {
            let refused = formats::write_string(Format::Ads, &[Component::unspecified(h)]);
            prop_assert!(refused.is_err());
        }
    }
}

// ---------------------------------------------------------------------
// Readers never panic

fn all_formats() -> [Format; 4] {
    [Format::Toml, Format::Gen, Format::Ads, Format::Wmod]
}

fn seed_texts() -> Vec<(Format, String)> {
    vec![
        (Format::Gen, fixture_text("faudes_mixed.gen")),
        (Format::Gen, fixture_text("faudes_mixed_xml.gen")),
        (Format::Gen, fixture_text("faudes_unnamed.gen")),
        (Format::Toml, fixture_text("mach1.toml")),
        (Format::Ads, fixture_text("tct_mach1.ads")),
        (Format::Ads, ads::write(&bench("phil5", "P1"))),
        (Format::Wmod, fixture_text("smallfactory.wmod")),
        (Format::Gen, gen::write(&bench("smallfactory", "MACH1"))),
    ]
}

/// Bits of every format's syntax, so random sequences reach deep.
fn vocabulary() -> impl Strategy<Value = String> {
    const WORDS: &[&str] = &[
        "<Generator>",
        "</Generator>",
        "<Alphabet>",
        "</Alphabet>",
        "<States>",
        "</States>",
        "<TransRel>",
        "</TransRel>",
        "<InitStates>",
        "</InitStates>",
        "<MarkedStates/>",
        "<Consecutive>",
        "</Consecutive>",
        "+C+",
        "\"",
        "#",
        "%",
        "{",
        "}",
        "a",
        "x#2",
        "0",
        "1",
        "4294967296",
        "99999999999999999999",
        " ",
        "\n",
        "State size:",
        "Marker states:",
        "Vocal states:",
        "Transitions:",
        "*",
        "# event 1 = \"x\"",
        "# state 0 = \"s\"",
        "=",
        "[",
        "]",
        "name = \"n\"",
        "transitions = [",
        "<?xml version=\"1.0\"?>",
        "<Module>",
        "<SimpleComponent Kind=\"PLANT\" Name=\"p\">",
        "<Graph>",
        "<NodeList>",
        "<SimpleNode Name=\"a\" Initial=\"true\"/>",
        "&amp;",
        "&#0;",
        "&#x110000;",
        "<",
    ];
    prop::collection::vec(prop::sample::select(WORDS), 0..60).prop_map(|w| w.concat())
}

#[derive(Debug, Clone)]
enum Edit {
    Flip(usize, u8),
    Delete(usize, usize),
    Insert(usize, Vec<u8>),
}

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    prop::collection::vec(
        prop_oneof![
            (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Flip(i, b)),
            (any::<usize>(), 0usize..20).prop_map(|(i, n)| Edit::Delete(i, n)),
            (any::<usize>(), prop::collection::vec(any::<u8>(), 1..6))
                .prop_map(|(i, v)| Edit::Insert(i, v)),
        ],
        1..8,
    )
}

fn mutate(text: &str, edits: &[Edit]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for e in edits {
        let len = bytes.len().max(1);
        match e {
            Edit::Flip(i, b) => {
                if !bytes.is_empty() {
                    let i = i % len;
                    bytes[i] ^= b | 1;
                }
            }
            Edit::Delete(i, n) => {
                if !bytes.is_empty() {
                    let i = i % len;
                    let end = (i + n).min(bytes.len());
                    bytes.drain(i..end);
                }
            }
            Edit::Insert(i, v) => {
                let i = i % (bytes.len() + 1);
                bytes.splice(i..i, v.iter().copied());
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn arbitrary_text_never_panics(text in ".{0,300}", words in vocabulary()) {
        for f in all_formats() {
            let _ = read_str(&text, f, Path::new("p"));
            let _ = read_str(&words, f, Path::new("p"));
        }
    }

    #[test]
    fn mutated_valid_files_never_panic(which in 0usize..8, edits in edits()) {
        let seeds = seed_texts();
        let (format, text) = &seeds[which % seeds.len()];
        let text = mutate(text, &edits);
        let _ = read_str(&text, *format, Path::new("p"));
        // Any reader on any format's text: still no panic.
        for f in all_formats() {
            let _ = read_str(&text, f, Path::new("p"));
        }
    }
}

// ---------------------------------------------------------------------
// Names libFAUDES would misread, and kinds

/// Names that libFAUDES's tokenizer reads as numbers (`0.0`, `2.0` as
/// reals, `0x1F` as a hexadecimal index, `inf`), as an attribute (`+1`) or
/// as an index (`12`): composite state names from `sync` look like the
/// first two.
const NUMBER_LIKE: [&str; 10] = [
    "0.0", "2.0", "1.5", ".5", "5.", "0x1F", "inf", "-inf", "+1", "12",
];

fn number_like_names() -> Automaton {
    let mut b = AutomatonBuilder::new("numbers");
    let e = b.add_event("2.0", true).unwrap();
    let states: Vec<StateId> = NUMBER_LIKE.iter().map(|n| b.add_state(n)).collect();
    b.set_initial(states[0]).unwrap();
    b.mark(states[1]);
    for pair in states.windows(2) {
        b.add_transition(pair[0], e, pair[1], 0);
    }
    b.build().unwrap()
}

#[test]
fn gen_quotes_every_name_libfaudes_would_read_as_a_number() {
    let a = number_like_names();
    let text = gen::write(&a);
    for name in NUMBER_LIKE {
        assert!(
            text.contains(&format!("\n\"{name}\"\n")),
            "{name} unquoted:\n{text}"
        );
    }
    assert!(text.contains("\n\"2.0\" +C+\n"), "{text}");
    assert_eq!(gen::read(&text, Path::new("n.gen")).unwrap(), a);
    // Names that start with a letter or `_` stay bare; sync's composite
    // names of such states too.
    let mut b = AutomatonBuilder::new("plain");
    let go = b.add_event("go", true).unwrap();
    let s = b.add_state("idle.busy");
    let t = b.add_state("_x-1");
    b.set_initial(s).unwrap();
    b.add_transition(s, go, t, 0);
    let text = gen::write(&b.build().unwrap());
    assert!(text.contains("\nidle.busy go _x-1\n"), "{text}");
}

fn supervisor(kind: Kind) -> Component {
    Component {
        kind,
        automaton: bench("smallfactory", "MACH1"),
    }
}

#[test]
fn every_format_keeps_the_kind_of_a_component() {
    for kind in [Kind::Plant, Kind::Spec, Kind::Supervisor, Kind::Property] {
        for format in all_formats() {
            let c = supervisor(kind);
            let text = formats::write_string(format, std::slice::from_ref(&c)).unwrap();
            let back = read_str(&text, format, Path::new("k")).unwrap();
            let context = format!("{kind} through {format:?}:\n{text}");
            assert_eq!(back.len(), 1, "{context}");
            assert_eq!(back[0].kind, kind, "{context}");
            assert_same(&back[0].automaton, &c.automaton, &context);
        }
    }
    // Unstated stays unstated (and a .gen looks as before).
    let c = supervisor(Kind::Unspecified);
    let text = formats::write_string(Format::Gen, std::slice::from_ref(&c)).unwrap();
    assert!(
        text.starts_with("<Generator name=\"MACH1\" ftype=\"System\">\n"),
        "{text}"
    );
    assert_eq!(
        read_str(&text, Format::Gen, Path::new("k")).unwrap()[0].kind,
        Kind::Unspecified
    );
    let text = formats::write_string(Format::Gen, &[supervisor(Kind::Supervisor)]).unwrap();
    assert!(
        text.starts_with("<Generator name=\"MACH1\" ftype=\"System\" kind=\"supervisor\">\n"),
        "{text}"
    );
    let text = formats::write_string(Format::Ads, &[supervisor(Kind::Spec)]).unwrap();
    assert!(text.contains("\n# kind = \"spec\"\n"), "{text}");
}

#[test]
fn an_unknown_kind_is_an_error_at_its_line() {
    let gen_text = "% a comment\n<Generator name=\"m\" kind=\"plantt\">\n<Alphabet> a </Alphabet>\n</Generator>\n";
    let e = read_str(gen_text, Format::Gen, Path::new("m.gen")).unwrap_err();
    assert_eq!(location(&e).0, 2, "{e}");
    assert!(e.to_string().contains("unknown kind `plantt`"), "{e}");
    let ads_text =
        ads::write(&bench("smallfactory", "MACH1")).replacen('\n', "\n# kind = \"boss\"\n", 1);
    let e = read_str(&ads_text, Format::Ads, Path::new("m.ads")).unwrap_err();
    assert_eq!(location(&e).0, 2, "{e}");
    assert!(e.to_string().contains("unknown kind \"boss\""), "{e}");
}

// ---------------------------------------------------------------------
// Compatibility and speed (need the outside world or release mode)

/// libFAUDES (Python package `faudes`) reads what we write. Skipped when
/// the package is not installed.
#[test]
fn libfaudes_reads_our_gen_files() {
    let probe = std::process::Command::new("python3")
        .args(["-c", "import faudes"])
        .output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: python3 with the faudes package is not available");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut cases = vec![
        bench("phil5", "P1"),
        bench("smallfactory", "MACH1"),
        formats::read_automaton(&fixture("faudes_mixed.gen")).unwrap(),
        formats::read_automaton(&fixture("faudes_unnamed.gen")).unwrap(),
    ];
    // Names that need quotes or escapes (libFAUDES refuses names with
    // spaces, `"`, `#` or non-ASCII characters, quoted or not).
    let mut b = AutomatonBuilder::new("odd names & co");
    let go = b.add_event("+go+", true).unwrap();
    let x = b.add_event("x<y>&z", false).unwrap();
    let s = b.add_state("50%{a}");
    let t = b.add_state("7");
    b.set_initial(s).unwrap();
    b.mark(t);
    b.add_transition(s, go, t, 0);
    b.add_transition(t, x, s, 0);
    cases.push(b.build().unwrap());
    cases.push(number_like_names());
    let mut script = String::from("import faudes\n");
    for (i, a) in cases.iter().enumerate() {
        let path = dir.path().join(format!("case{i}.gen"));
        std::fs::write(&path, gen::write(a)).unwrap();
        script.push_str(&format!(
            "g = faudes.System({:?})\nprint(g.Size(), g.TransRelSize(), g.InitStatesSize(), g.MarkedStatesSize(), g.Alphabet().Size(), g.ControllableEvents().Size(), g.Name(), '|'.join(sorted(g.StateName(s) for s in g.States())))\n",
            path.to_str().unwrap()
        ));
    }
    let out = std::process::Command::new("python3")
        .args(["-c", &script])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The package prints warnings about optional graphics modules.
    let lines: Vec<&str> = stdout
        .lines()
        .filter(|l| !l.starts_with("WARNING"))
        .collect();
    assert_eq!(lines.len(), cases.len(), "{stdout}");
    for (a, line) in cases.iter().zip(lines) {
        let mut names: Vec<String> = a
            .states()
            .map(|s| {
                if a.has_state_names() {
                    a.state_name(s).into_owned()
                } else {
                    String::new()
                }
            })
            .collect();
        names.sort();
        let expected = format!(
            "{} {} {} {} {} {} {} {}",
            a.num_states(),
            a.num_transitions(),
            usize::from(a.initial().is_some()),
            a.marked_states().count(),
            a.alphabet().len(),
            a.alphabet().controllable_count(),
            a.name(),
            names.join("|")
        );
        assert_eq!(line, expected);
    }
}

/// A `.gen` file with a million transitions reads in well under a second
/// (release mode: `cargo test --release -p des --test formats -- --ignored`).
#[test]
#[ignore = "timing; run in release mode"]
fn a_million_transitions_read_fast() {
    let n: u32 = 200_000;
    let mut text = String::from("<Generator name=\"big\">\n<Alphabet>\n");
    for e in 0..5 {
        text.push_str(&format!("ev{e} {}\n", if e % 2 == 1 { "+C+" } else { "" }));
    }
    text.push_str(&format!(
        "</Alphabet>\n<States>\n<Consecutive>\n1 {n}\n</Consecutive>\n</States>\n<TransRel>\n"
    ));
    for s in 1..=n {
        for e in 0..5u32 {
            let t = (s.wrapping_mul(7) + e * 13) % n + 1;
            text.push_str(&format!("{s} ev{e} {t}\n"));
        }
    }
    text.push_str("</TransRel>\n<InitStates>\n1\n</InitStates>\n<MarkedStates>\n1\n</MarkedStates>\n</Generator>\n");
    let start = std::time::Instant::now();
    let a = gen::read(&text, Path::new("big.gen")).unwrap();
    let read = start.elapsed();
    assert_eq!(a.num_transitions(), 1_000_000);
    let start = std::time::Instant::now();
    let written = gen::write(&a);
    let write = start.elapsed();
    eprintln!(
        "read {} MB in {read:?}, wrote {} MB in {write:?}",
        text.len() >> 20,
        written.len() >> 20
    );
    assert!(read.as_secs_f64() < 1.0, "{read:?}");
}

/// A flat entity amplification (no nesting, which the XML parser catches
/// on its own): 1,000 references to a 1,000-byte entity, a file of about
/// 10 KB that would expand to 1 MB, and proportionally more for larger
/// files. Refused at the declaration, before any expansion.
#[test]
fn xml_entity_declarations_are_refused_at_their_line() {
    let entity = "a".repeat(1000);
    let refs = "&e;".repeat(1000);
    for (format, text) in [
        (
            Format::Wmod,
            format!(
                "<?xml version=\"1.0\"?>\n<!DOCTYPE Module [\n<!ENTITY e \"{entity}\">\n]>\n<Module Name=\"{refs}\"/>\n"
            ),
        ),
        (
            Format::Gen,
            format!(
                "<?xml version=\"1.0\"?>\n<!DOCTYPE Generator [\n<!ENTITY e \"{entity}\">\n]>\n<Generator name=\"{refs}\"/>\n"
            ),
        ),
    ] {
        let err = read_str(&text, format, Path::new("amplified")).unwrap_err();
        assert_eq!(location(&err).0, 3, "{err}");
        assert!(err.to_string().contains("entity declarations"), "{err}");
    }
}

#[cfg(unix)]
#[test]
fn devices_fifos_and_directories_are_not_model_files() {
    let dir = tempfile::tempdir().unwrap();
    let zero = dir.path().join("zero.gen");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let fifo = dir.path().join("pipe.toml");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    let folder = dir.path().join("folder.wmod");
    std::fs::create_dir(&folder).unwrap();
    let mut paths = vec![zero, folder];
    if made.is_ok_and(|s| s.success()) {
        paths.push(fifo);
    }
    for path in paths {
        let err = formats::read_file(&path).unwrap_err().to_string();
        assert!(
            err.contains("not a regular file"),
            "{}: {err}",
            path.display()
        );
    }
}

/// A `.gen` file is written in pieces; the pieces make exactly the text
/// `write_string` gives, names composed on demand included (here a
/// composition whose text is several pieces long).
#[test]
fn a_streamed_gen_file_is_the_written_string() {
    let machine = |i: usize| {
        let mut b = des::AutomatonBuilder::new(format!("M{i}"));
        let (s, f, k) = (format!("s{i}"), format!("f{i}"), format!("b{i}"));
        b.add_event(&s, true).unwrap();
        b.add_event(&f, false).unwrap();
        b.add_event(&k, false).unwrap();
        b.set_initial_by_name("idle").unwrap();
        b.mark_by_name("idle");
        b.add_transition_by_name("idle", &s, "busy", 0).unwrap();
        b.add_transition_by_name("busy", &f, "idle", 0).unwrap();
        b.add_transition_by_name("busy", &k, "down#3", 0).unwrap();
        b.add_transition_by_name("down#3", &s, "idle", 0).unwrap();
        b.build().unwrap()
    };
    let parts: Vec<_> = (0..9).map(machine).collect();
    let refs: Vec<_> = parts.iter().collect();
    let product = des::ops::sync(&refs).unwrap();
    let component = des::formats::Component {
        kind: des::formats::Kind::Supervisor,
        automaton: product,
    };
    let text =
        des::formats::write_string(des::formats::Format::Gen, std::slice::from_ref(&component))
            .unwrap();
    assert!(text.len() > 3 << 20, "several pieces: {}", text.len());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.gen");
    des::formats::write_file(&path, std::slice::from_ref(&component)).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
}
