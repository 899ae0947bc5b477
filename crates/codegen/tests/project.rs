//! PLC project files: a realistic project loads with every field in place,
//! supervisors are read from any format or synthesised, every validation
//! rule rejects its violation at the right line, and no mangled project
//! file makes the loader panic.

use des::formats;
use des::ops;
use des::{Error, StateId};
use plc_project::{
    self as project, Action, Drive, Origin, Project, SupervisorSource, Trigger, Unexpected,
};
use proptest::prelude::*;

mod common;
use common::{assert_errors_at_marked_lines, dir, fixture, load_err, load_ok, load_text};

fn states(p: &Project, sup: usize, names: &[&str]) -> Vec<StateId> {
    let a = &p.supervisors[sup].automaton;
    names.iter().map(|n| a.state_by_name(n).unwrap()).collect()
}

#[test]
fn the_stamping_press_loads_with_every_field_in_place() {
    let path = fixture("press.plc.toml");
    let p = project::load(&path).unwrap();
    assert_eq!(p.path, path);
    assert_eq!(p.name, "stamping-press");
    assert_eq!(p.scan_period_ms, 10);
    assert_eq!(p.max_commands_per_scan, 1);
    assert_eq!(p.unexpected, Unexpected::Fault);
    assert_eq!(p.reset, p.input("reset_pb"));
    assert_eq!(
        (p.overrun_limit, p.overrun_fault, p.lost_edge_fault),
        (1, false, false)
    );

    let inputs: Vec<(&str, u8, u32)> = p
        .inputs
        .iter()
        .map(|i| (i.name.as_str(), i.debounce_scans, i.line))
        .collect();
    assert_eq!(
        inputs,
        [
            ("auto_pb", 0, 12),
            ("stop_pb", 0, 13),
            ("reset_pb", 0, 14),
            ("part", 3, 15),
            ("top_ls", 0, 16),
            ("bottom_ls", 0, 17)
        ]
    );

    // Moore outputs: the lesson's output table.
    let table = [
        ("auto_lamp", vec!["2", "3", "4", "6"]),
        ("part_hold", vec!["3", "4"]),
        ("up_sol", vec!["4"]),
        ("down_sol", vec!["3"]),
    ];
    assert_eq!(p.outputs.len(), table.len());
    for (o, (name, listed)) in p.outputs.iter().zip(&table) {
        assert_eq!(o.name, *name);
        assert!(!o.safe);
        assert_eq!(o.drive, Drive::States(vec![(0, states(&p, 0, listed))]));
    }
    assert_eq!(p.outputs[0].line, 20);
    assert!(p.timers.is_empty() && p.switches.is_empty());

    // Events in declaration order, each bound to its edge.
    let i = |n: &str| p.input(n).unwrap();
    let names: Vec<&str> = p.events.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "auto",
            "stop",
            "reset",
            "part_in",
            "part_out",
            "at_bottom",
            "at_top"
        ]
    );
    let auto = &p.events[0];
    assert!(!auto.controllable);
    assert_eq!(auto.origin, Origin::Operator);
    assert_eq!(auto.trigger, Trigger::Rising(vec![i("auto_pb")]));
    assert_eq!(auto.when, [i("top_ls")]);
    assert!(auto.unless.is_empty() && auto.actions.is_empty() && auto.request.is_none());
    assert_eq!(auto.line, 26);
    let part_out = &p.events[p.event("part_out").unwrap()];
    assert_eq!(part_out.origin, Origin::Plant);
    assert_eq!(part_out.trigger, Trigger::Falling(vec![i("part")]));

    // The supervisor: six states, named by the automaton, every event local.
    assert_eq!(p.supervisors.len(), 1);
    let s = &p.supervisors[0];
    assert_eq!(s.name, "press");
    assert_eq!(s.line, 34);
    assert_eq!(s.automaton.num_states(), 6);
    assert_eq!(s.automaton.initial(), s.automaton.state_by_name("1"));
    assert_eq!(
        s.source,
        SupervisorSource::File(dir().join("press/press.toml"))
    );
    let globals: Vec<usize> = s.local_events.iter().map(|&(g, _)| g).collect();
    assert_eq!(globals, (0..7).collect::<Vec<_>>());
    for &(g, id) in &s.local_events {
        assert_eq!(s.automaton.alphabet().name(id), p.events[g].name);
    }
    assert_eq!(p.files, [path, dir().join("press/press.toml")]);
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

#[test]
fn the_small_factory_is_synthesised_into_the_12_state_supervisor() {
    let path = fixture("factory.plc.toml");
    let p = project::load(&path).unwrap();
    assert_eq!(p.name, "small-factory");
    assert_eq!(p.scan_period_ms, 20);
    assert_eq!(p.max_commands_per_scan, 0);
    assert_eq!(p.unexpected, Unexpected::Ignore);
    assert_eq!(p.reset, None);
    let s = &p.supervisors[0];
    assert_eq!(s.name, "factory");
    assert_eq!(
        (s.automaton.num_states(), s.automaton.num_transitions()),
        (12, 24)
    );
    let plants = vec![
        dir().join("factory/plant/MACH1.gen"),
        dir().join("factory/plant/MACH2.gen"),
    ];
    // Glob matches come in alphabetical order.
    let specs = vec![
        dir().join("factory/spec/BRSPEC.gen"),
        dir().join("factory/spec/BUFSPEC.gen"),
    ];
    assert_eq!(
        s.source,
        SupervisorSource::Synthesized {
            plants: plants.clone(),
            specs: specs.clone(),
            minimized: false,
            reduced: false,
            local: None
        }
    );
    let mut files = vec![path];
    files.extend(plants);
    files.extend(specs);
    assert_eq!(p.files, files);
    // Local events in the project's order, which is not the automaton's.
    let order: Vec<&str> = s
        .local_events
        .iter()
        .map(|&(g, _)| p.events[g].name.as_str())
        .collect();
    assert_eq!(
        order,
        ["e10", "e12", "e20", "e22", "e11", "e13", "e21", "e23"]
    );
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

#[test]
fn a_synthesis_beyond_its_max_states_is_refused_at_its_line() {
    // The small factory's plant composes to 9 states.
    let base = std::fs::read_to_string(fixture("factory.plc.toml")).unwrap();
    let text = base.replace("*SPEC.gen\"] }", "*SPEC.gen\"], max_states = 5 }");
    assert_ne!(text, base);
    let err = load_err(&text);
    // The composition's limit, with how a project raises it (no
    // command-line flag: that is the CLI's to name).
    assert!(
        err.ends_with(
            "cannot synthesise the supervisor: composition `MACH1||MACH2` exceeds the limit of 5 \
             states (raise it with `max_states` in `synthesize`)"
        ),
        "{err}"
    );
    let line = base.lines().position(|l| l.contains("synthesize")).unwrap() + 1;
    assert!(err.contains(&format!("t.plc.toml:{line}:")), "{err}");
    let zero = base.replace("*SPEC.gen\"] }", "*SPEC.gen\"], max_states = 0 }");
    assert!(load_err(&zero).contains("max_states must be a positive number"));
    let enough = base.replace("*SPEC.gen\"] }", "*SPEC.gen\"], max_states = 100 }");
    assert_eq!(load_ok(&enough).supervisors[0].automaton.num_states(), 12);
}

#[test]
fn a_supervisor_beyond_its_logic_effort_is_refused_at_its_line_before_minimising() {
    use codegen::backend::logic::{self, Encoding, Minimisation, DEFAULT_MAX_EFFORT};
    use codegen::lower::{LogicImage, TableImage};
    let base = std::fs::read_to_string(fixture("factory.plc.toml")).unwrap();
    let project = load_ok(&base);
    let s = &project.supervisors[0];
    assert_eq!(s.max_logic_effort, None, "the project states no limit");
    assert_eq!(logic::effort_limit(s.max_logic_effort), DEFAULT_MAX_EFFORT);
    let local: Vec<_> = s.local_events.iter().map(|&(_, id)| id).collect();
    let encoding = Encoding::binary(s.automaton.num_states());
    let effort = logic::effort(&s.automaton, &local, &encoding, Minimisation::PerFunction).unwrap();
    assert!(
        effort > 1,
        "the 12-state supervisor has work to do: {effort}"
    );

    let limited = |limit: u64| {
        let text = base.replace(
            "name = \"factory\"",
            &format!("name = \"factory\"\nmax_logic_effort = {limit}"),
        );
        assert_ne!(text, base);
        load_ok(&text)
    };
    let phases = std::cell::RefCell::new(Vec::<String>::new());
    struct Phases<'a>(&'a std::cell::RefCell<Vec<String>>);
    impl ops::Progress for Phases<'_> {
        fn report(&self, phase: &str, _done: usize) {
            self.0.borrow_mut().push(phase.to_owned());
        }
    }
    let err = LogicImage::with_progress(&limited(effort - 1), &Phases(&phases)).unwrap_err();
    assert_eq!(phases.borrow().len(), 0, "nothing minimised: {phases:?}");
    let line = base.lines().position(|l| l == "[[supervisor]]").unwrap() + 1;
    assert!(
        matches!(
            &err,
            codegen::Error::Logic {
                location,
                supervisor,
                source: logic::LogicError::Effort { effort: e, limit, .. },
            } if location.line == line as u32 && supervisor == &s.name && *e == effort && *limit == effort - 1
        ),
        "{err:?}"
    );
    let err = err.to_string();
    assert!(err.contains(&format!("t.plc.toml:{line}:")), "{err}");
    assert!(
        err.contains(&format!("effort of {effort}"))
            && err.contains(&format!("limit of {}", effort - 1)),
        "{err}"
    );
    assert!(
        err.contains("max_logic_effort") && err.contains("table backend"),
        "{err}"
    );
    // The limit concerns the logic backend only, and is inclusive.
    TableImage::new(&limited(1)).unwrap();
    LogicImage::new(&limited(effort)).unwrap();
    let zero = base.replace(
        "name = \"factory\"",
        "name = \"factory\"\nmax_logic_effort = 0",
    );
    assert!(load_err(&zero).contains("max_logic_effort must be a positive number"));
}

#[test]
fn more_names_of_a_kind_than_16_bit_indices_hold_are_refused_at_the_first_too_many() {
    let mut text = String::from("[plc]\nname = \"wide\"\n[inputs]\n");
    for i in 0..=u16::MAX as usize {
        text.push_str(&format!("i{i} = {{}}\n"));
    }
    let err = load_err(&text);
    // Header lines 1-3, input k on line 4 + k: the 65,536th (k = 65535).
    assert!(
        err.contains("t.plc.toml:65539:1: more than 65535 inputs"),
        "{err}"
    );
}

#[test]
fn minimize_runs_minstate_on_the_synthesised_supervisor() {
    let text = std::fs::read_to_string(fixture("factory.plc.toml"))
        .unwrap()
        .replace("*SPEC.gen\"] }", "*SPEC.gen\"], minimize = true }");
    let p = load_ok(&text);
    let read = |f: &str| formats::read_automaton(&fixture(f)).unwrap();
    let plant = ops::sync(&[
        &read("factory/plant/MACH1.gen"),
        &read("factory/plant/MACH2.gen"),
    ])
    .unwrap();
    let spec = ops::sync(&[
        &read("factory/spec/BRSPEC.gen"),
        &read("factory/spec/BUFSPEC.gen"),
    ])
    .unwrap();
    let expected = ops::minstate(&ops::supcon(&plant, &spec).unwrap());
    let s = &p.supervisors[0];
    assert_eq!(s.automaton.num_states(), expected.num_states());
    assert!(ops::language_equal(&s.automaton, &expected));
    assert!(matches!(
        s.source,
        SupervisorSource::Synthesized {
            minimized: true,
            reduced: false,
            ..
        }
    ));
}

#[test]
fn a_wmod_component_is_selected_by_name() {
    let p = project::load(&fixture("cell.plc.toml")).unwrap();
    let s = &p.supervisors[0];
    assert_eq!(s.name, "once");
    assert_eq!(s.automaton.num_states(), 3);
    assert_eq!(
        p.outputs[1].drive,
        Drive::States(vec![(0, states(&p, 0, &["fresh"]))])
    );
    assert_eq!(p.files[1], dir().join("cell/cell.wmod"));

    // Any kind can be named, even the plant.
    let text = std::fs::read_to_string(fixture("cell.plc.toml"))
        .unwrap()
        .replace("component = \"once\"", "component = \"machine\"")
        .replace("once = [\"fresh\"]", "machine = [\"idle\"]");
    assert_eq!(load_ok(&text).supervisors[0].name, "machine");
}

#[test]
fn a_wmod_with_several_supervisors_needs_a_component() {
    let text = std::fs::read_to_string(fixture("cell.plc.toml"))
        .unwrap()
        .replace("component = \"once\"\n", "");
    let msg = load_err(&text);
    assert!(msg.contains("t.plc.toml:18:8:"), "{msg}");
    assert!(msg.contains("several components"), "{msg}");
    assert!(
        msg.contains("`once` (supervisor), `always` (supervisor)"),
        "{msg}"
    );
    let text = text.replace(
        "\"cell/cell.wmod\"",
        "\"cell/cell.wmod\"\ncomponent = \"twice\"",
    );
    let msg = load_err(&text);
    assert!(msg.contains("t.plc.toml:19:13:"), "{msg}");
    assert!(msg.contains("has no component `twice`"), "{msg}");
}

#[test]
fn a_wmod_with_one_spec_and_a_plant_runs_the_spec() {
    let p = load_ok(
        r#"
[plc]
name = "x"
[events]
go = { controllable = true }
[[supervisor]]
file = "cell/plant_and_spec.wmod"
"#,
    );
    assert_eq!(p.supervisors[0].name, "twice");
    assert_eq!(p.supervisors[0].automaton.num_states(), 3);
}

#[test]
fn a_file_with_only_a_plant_runs_it_when_named() {
    let p = load_ok(
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nfile = \"mini/plant.toml\"\ncomponent = \"machine\"\n",
    );
    assert_eq!(p.supervisors[0].name, "machine");
}

/// Each case: a project with the offending line marked `# <-`, and what
/// the error must say. The error must name the project file and that line.
const ERRORS: &[(&str, &str)] = &[
    // Identifiers the generated code reserves in every kind's module.
    (
        "[plc]\nname = \"x\"\n[inputs]\nCount = {} # <-\n",
        "input name `Count` becomes the identifier `COUNT`, which generated code reserves",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\nnames = {} # <-\n",
        "output name `names` becomes the identifier `NAMES`",
    ),
    // Shape.
    (
        "[plc]\nname = \"x\"\n[eventz] # <-\n",
        "unknown field `eventz`",
    ),
    (
        "[plc]\nname = \"x\"\nscan_periode_ms = 5 # <-\n",
        "unknown field `scan_periode_ms`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", when = [\"i\"], raising = 1 } # <-\n",
        "unknown field `raising`",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\no = { initial = 1 } # <-\n",
        "invalid type: integer `1`, expected a boolean",
    ),
    (
        "[plc]\nname = \"x\"\n[timers]\nt = {} # <-\n",
        "missing field `preset_ms`",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nfile = \"mini/mini.toml\"\ncomponents = \"x\" # <-\n",
        "unknown field `components`",
    ),
    // Numbers.
    (
        "[plc]\nname = \"x\"\nscan_period_ms = 0 # <-\n",
        "scan_period_ms must be between 1 and 2147483647, found 0",
    ),
    (
        "[plc]\nname = \"x\"\nmax_commands_per_scan = 70000 # <-\n",
        "max_commands_per_scan must be between 0 and 65535",
    ),
    (
        "[plc]\nname = \"x\"\noverrun_limit = -1 # <-\n",
        "overrun_limit must be between 0 and 65535",
    ),
    (
        "[plc]\nname = \"x\"\nrom_test_bytes_per_scan = 0 # <-\n",
        "rom_test_bytes_per_scan must be between 4 and 65532, found 0",
    ),
    (
        "[plc]\nname = \"x\"\nrom_test_bytes_per_scan = 65536 # <-\n",
        "rom_test_bytes_per_scan must be between 4 and 65532, found 65536",
    ),
    (
        "[plc]\nname = \"x\"\nrom_test_bytes_per_scan = 66 # <-\n",
        "rom_test_bytes_per_scan must be a multiple of 4 (the image is checked in 32-bit words), found 66",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = { debounce_scans = 256 } # <-\n",
        "debounce_scans must be between 0 and 255, found 256",
    ),
    (
        "[plc]\nname = \"x\"\n[timers]\nt = { preset_ms = 0 } # <-\n",
        "preset_ms must be between 1 and 2147483647, found 0",
    ),
    (
        "[plc]\nname = \"x\"\n[timers]\nt = { preset_ms = 2_147_483_648 } # <-\n",
        "preset_ms must be between 1 and 2147483647",
    ),
    (
        "[plc]\nname = \"x\"\nunexpected = \"crash\" # <-\n",
        "unexpected must be \"fault\" or \"ignore\", found \"crash\"",
    ),
    // References.
    (
        "[plc]\nname = \"x\"\nreset = \"reset_pb\" # <-\n",
        "unknown input `reset_pb`: not declared in [inputs]",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ne = { rising = [\"a\"] } # <-\n",
        "unknown input `a`",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ne = { falling = \"a\" } # <-\n",
        "unknown input `a`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", when = [\"j\"] } # <-\n",
        "unknown input `j`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\",\n  unless = [\"j\"] } # <-\n",
        "unknown input `j`",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ne = { expired = \"t\" } # <-\n",
        "unknown timer `t`: not declared in [timers]",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ngo = { controllable = true, request = \"r\" } # <-\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "unknown input `r`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", set = [\"lamp\"] } # <-\n",
        "unknown output `lamp`: not declared in [outputs]",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", clear = \"lamp\" } # <-\n",
        "unknown output `lamp`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", start = [\"t\"] } # <-\n",
        "unknown timer `t`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", reset = [\"t\"] } # <-\n",
        "unknown timer `t`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", switch = { valve = \"hi\" } } # <-\n",
        "unknown switch `valve`: not declared in [switches]",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\nv_hi = {}\n[switches]\nvalve = { hi = \"v_hi\" }\n[events]\ne = { rising = \"i\", switch = { valve = \"lo\" } } # <-\n",
        "switch `valve` has no position `lo` (positions: hi, off)",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\n[switches]\nvalve = { hi = \"v_hi\" } # <-\n",
        "unknown output `v_hi`",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\nlamp = { states = { mini = [\"idle\"], other = [\"x\"] } } # <-\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[inputs]\ni = {}\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "unknown supervisor `other`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\nlamp = { states = { mini = [\n  \"idle\",\n  \"bsy\", # <-\n] } }\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "supervisor `mini` has no state `bsy`",
    ),
    // Names.
    (
        "[plc]\nname = \"x\"\n[inputs]\n\"***\" = {} # <-\n",
        "input name `***` is not a valid identifier",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\n\"\" = { rising = \"i\" } # <-\n",
        "event name `` is not a valid identifier",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\nvalve-1 = {}\nvalve_1 = {} # <-\n",
        "input `valve_1` and input `valve-1` (line 4) both become the identifier `VALVE_1`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\nValve = {}\n[outputs]\nVALVE = {} # <-\n",
        "output `VALVE` and input `Valve` (line 4) both become the identifier `VALVE`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\npart = {}\n[events]\npart = { rising = \"part\" } # <-\n",
        "`part` names both the input at line 4 and this event",
    ),
    (
        "[plc]\nname = \"x\"\n[timers]\nmini = { preset_ms = 5 }\n[events]\ngo = { controllable = true }\n[inputs]\ni = {}\n[[supervisor]] # <-\nfile = \"mini/mini.toml\"\n",
        "`mini` names both the timer at line 4 and this supervisor",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nname = \"m\"\nfile = \"mini/mini.toml\"\n[[supervisor]]\nname = \"m\" # <-\nfile = \"mini/mini.toml\"\n",
        "supervisor name `m` is already used at line 9; supervisor names must be unique",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\na = {}\n[switches]\nv = { \"off\" = \"a\" } # <-\n",
        "`off` is implicit (it lowers every position) and may not be declared",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\na = {}\nb = {}\n[switches]\nv = { hi = \"a\", Hi = \"b\" } # <-\n",
        "positions `hi` and `Hi` of switch `v` both become the identifier `HI`",
    ),
    (
        "[plc]\nname = \"x\"\n[switches]\nv = {} # <-\n",
        "switch `v` needs at least one position",
    ),
    // Outputs driven twice.
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\nlamp = { states = { mini = [\"busy\"] } }\n[events]\ngo = { controllable = true,\n  set = [\"lamp\"] } # <-\ndone = { rising = \"i\" }\n",
        "output driven twice",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\nlamp = { states = { mini = [\"busy\"] } }\n[switches]\nv = { on = \"lamp\" } # <-\n",
        "output driven twice",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\na = {}\n[switches]\nv = { on = \"a\" }\nw = { on = \"a\" } # <-\n",
        "output `a` is already position `on` of switch `v` (line 6)",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\na = {}\n[switches]\nv = { on = \"a\", up = \"a\" } # <-\n",
        "output `a` is already position `on` of this switch",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\na = {}\n[switches]\nv = { on = \"a\" }\n[events]\ne = { rising = \"i\", clear = [\"a\"] } # <-\n",
        "output `a` is position `on` of switch `v`: drive it with `switch = { v = \"on\" }`, not with `clear`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\na = {}\n[events]\ne = { rising = \"i\", clear = [\"a\"], set = [\"a\"] } # <-\n",
        "event `e` both sets and clears output `a`",
    ),
    (
        "[plc]\nname = \"x\"\n[outputs]\nlamp = { initial = true, states = { mini = [\"busy\"] } } # <-\n",
        "output `lamp` has a state map (a Moore output): it takes no `initial`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\nlamp = { states = {} } # <-\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "a state map must name at least one state",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\nlamp = { states = { mini = [] } } # <-\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "lists no state of supervisor `mini`",
    ),
    // Events.
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true, rising = \"i\" } # <-\n",
        "controllable event `go` cannot have `rising`",
    ),
    (
        "[plc]\nname = \"x\"\n[timers]\nt = { preset_ms = 5 }\n[events]\ngo = { controllable = true, expired = \"t\" } # <-\n",
        "controllable event `go` cannot have `expired`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true,\n  unless = [\"i\"] } # <-\n",
        "controllable event `go` cannot have `unless`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true, when = [\"i\"] } # <-\n",
        "controllable event `go` cannot have `when`",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ngo = { controllable = true, origin = \"operator\" } # <-\n",
        "controllable event `go` cannot have `origin`",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ne = { set = [] } # <-\n",
        "uncontrollable event `e` needs a source: exactly one of `rising`, `falling` or `expired`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\",\n  falling = \"i\" } # <-\n",
        "uncontrollable event `e` has both `rising` and `falling`: it needs exactly one source",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[timers]\nt = { preset_ms = 9 }\n[events]\ne = { falling = \"i\",\n  expired = \"t\" } # <-\n",
        "has both `falling` and `expired`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", request = \"i\" } # <-\n",
        "uncontrollable event `e` cannot have `request`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", origin = \"user\" } # <-\n",
        "origin must be \"operator\" or \"plant\", found \"user\"",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ne = { rising = [] } # <-\n",
        "`rising` of event `e` names no input",
    ),
    // Events against supervisors.
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { rising = \"i\" } # <-\ndone = { rising = \"i\" }\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "event `go` is uncontrollable here but controllable in supervisor `mini` (`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { controllable = true } # <-\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "event `done` is controllable here but uncontrollable in supervisor `mini`",
    ),
    (
        "[plc]\nname = \"x\"\n[events]\ngo = { controllable = true }\n[[supervisor]] # <-\nfile = \"mini/mini.toml\"\n",
        "event `done` of supervisor `mini` (",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\nextra = { controllable = true } # <-\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
        "controllable event `extra` is in no supervisor's alphabet (controllable event in no alphabet)",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne10 = { rising = \"i\" }\ne11 = { rising = \"i\" } # <-\ne12 = { rising = \"i\" }\ne13 = { controllable = true }\n[[supervisor]]\nname = \"m1\"\nsynthesize = { plants = [\"factory/plant/MACH1.gen\"] }\n",
        "event `e11` is uncontrollable here but controllable in `MACH1` (`",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne10 = { rising = \"i\" }\ne11 = { controllable = true }\ne12 = { rising = \"i\" }\n[[supervisor]] # <-\nname = \"m1\"\nsynthesize = { plants = [\"factory/plant/MACH1.gen\"] }\n",
        "event `e13` of synthesised supervisor `m1` (from `MACH1` in `",
    ),
    // Supervisor sources.
    (
        "[plc]\nname = \"x\"\n[[supervisor]] # <-\nname = \"s\"\n",
        "a supervisor needs `file = \"…\"`, `synthesize",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nfile = \"mini/mini.toml\"\nsynthesize = { plants = [\"mini/mini.toml\"] } # <-\n",
        "either `file` or `synthesize`, not both",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nsynthesize = { plants = [\"mini/mini.toml\"] }\ncomponent = \"a\" # <-\n",
        "a synthesised supervisor has none",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nfile = \"mini/missing.toml\" # <-\n",
        "cannot read model file",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nfile = \"mini/mini.txt\" # <-\n",
        "unknown model format (expected .toml, .gen, .ads or .wmod)",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]] # <-\nfile = \"mini/empty.toml\"\n",
        "supervisor `nothing` (",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nsynthesize = { plants = \"mini/mini.toml\", specs = [\"mini/spec_never.toml\"] } # <-\n",
        "synthesis gave the empty supervisor: the specification cannot be enforced",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nsynthesize = { plants = [\n  \"mini/*.toml\",\n  \"mini/*.nothing\", # <-\n] }\n",
        "`mini/*.nothing` matches no file",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nsynthesize = { plants = [] } # <-\n",
        "synthesis needs at least one plant",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nfile = \"mini/plant.toml\" # <-\n",
        "holds no supervisor, spec or unspecified component (components: `machine` (plant)); name the one to run with `component",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nsynthesize = { plants = [\"mini/spec_never.toml\"] } # <-\n",
        "holds no component usable as a plant (kinds: plant, unspecified)",
    ),
    (
        "[plc]\nname = \"x\"\n[[supervisor]]\nsynthesize = { plants = [\"mini/mini.toml\"], specs = [\"factory/spec/BUFSPEC.gen\"] } # <-\n",
        "cannot synthesise the supervisor: event `e10`",
    ),
    // Partial observation: the executor sees only what it detects.
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]] # <-\nfile = \"mini/hidden.toml\"\n",
        "mini/hidden.toml`) is unobservable: the executor sees only the events it detects",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\nj = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\nstep = { rising = \"j\" } # <-\n[[supervisor]]\nname = \"s\"\nsynthesize = { plants = [\"mini/silent_step.toml\"] }\n",
        "event `step` is unobservable in `silent_step` (`",
    ),
    // Synthesis runs the projected supervisor, unless it would command
    // what the plant may not be able to do.
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\n[[supervisor]]\nname = \"s\"\nsynthesize = { plants = [\"mini/hidden_plant.toml\"] } # <-\n",
        "cannot synthesise the supervisor: after `go` the controller, which cannot see `done`, would command `go`: the closed loop allows it after a string that looks the same, not after this one",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nname = \"s\"\nsynthesize = { plants = [\"mini/hidden_go.toml\"] } # <-\n",
        "cannot synthesise the supervisor: event `go` is controllable and unobservable",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nname = \"s\"\nsynthesize = { plants = [\"mini/silent_step.toml\"], reduce = true } # <-\n",
        "supervisor reduction assumes a supervisor that sees every event, and the plant's events `step` are unobservable",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nname = \"s\"\nsynthesize = { plants = [\"mini/silent_step.toml\"], localize = true } # <-\n",
        "localization assumes a supervisor that sees every event",
    ),
    (
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nname = \"s\"\nsynthesize = { plants = [\"mini/silent_step.toml\"], symbolic = true } # <-\n",
        "symbolic synthesis assumes a supervisor that sees every event, and the events `step` are unobservable",
    ),
];

#[test]
fn every_rule_rejects_its_violation_at_the_offending_line() {
    assert_errors_at_marked_lines(
        ERRORS
            .iter()
            .map(|&(text, expected)| (text.to_owned(), expected)),
    );
}

#[test]
fn errors_carry_the_column_too() {
    let msg = load_err("[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ne = { rising = \"i\", set = [\"lamp\"] }\n");
    assert!(
        msg.contains("t.plc.toml:6:28: unknown output `lamp`"),
        "{msg}"
    );
    match load_text("[plc]\nname = \"x\"\nscan_period_ms = 0\n") {
        Err(Error::Model { location, .. }) => {
            assert_eq!((location.line, location.column), (3, 18));
            assert_eq!(location.file, fixture("t.plc.toml"));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn errors_inside_model_files_point_into_the_model_file() {
    let msg = load_err("[plc]\nname = \"x\"\n[[supervisor]]\nfile = \"bad_transition.toml\"\n");
    assert!(msg.contains("bad_transition.toml:"), "{msg}");
    assert!(!msg.contains("t.plc.toml"), "{msg}");
}

#[test]
fn uncontrollable_events_in_no_alphabet_warn_only_without_actions() {
    let p = load_ok(
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[outputs]\nlamp = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\nsensor = { rising = \"i\", set = [\"lamp\"] }\nidle = { falling = \"i\" }\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
    );
    assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    assert_eq!(p.warnings[0].line, 11);
    assert!(p.warnings[0].message.contains("`idle`"));
    assert!(p.warnings[0]
        .message
        .contains("moves nothing and does nothing"));
}

#[test]
fn a_timer_observed_but_never_started_is_a_warning() {
    let p = load_ok(
        "[plc]\nname = \"x\"\n[timers]\nlost = { preset_ms = 100 }\nrunon = { preset_ms = 1000 }\nfree = { preset_ms = 5 }\n[inputs]\ni = {}\n[events]\nlost_end = { expired = \"lost\" }\nrun = { rising = \"i\", start = [\"runon\", \"free\"] }\nrun_end = { expired = \"runon\" }\n",
    );
    let timer: Vec<_> = p
        .warnings
        .iter()
        .filter(|w| w.message.contains("never started"))
        .collect();
    // `runon` is started, `free` is started and unobserved (fine).
    assert_eq!(timer.len(), 1, "{:?}", p.warnings);
    assert_eq!(timer[0].line, 4);
    assert!(timer[0].message.contains("`lost_end` (line 10)"));
}

#[test]
fn unstated_controllability_is_not_checked() {
    // `unstated.gen` names no controllable event: the project decides.
    let p = load_ok(
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nfile = \"mini/unstated.gen\"\n",
    );
    assert!(p.events[0].controllable);
    assert!(!p.supervisors[0]
        .automaton
        .alphabet()
        .controllability_stated());
}

#[test]
fn declaration_order_is_priority_order_and_local_events_follow_it() {
    let p = load_ok(
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\nzzz = { rising = \"i\" }\ndone = { rising = \"i\" }\naaa = { falling = \"i\" }\ngo = { controllable = true }\n[[supervisor]]\nfile = \"mini/mini.toml\"\n",
    );
    let names: Vec<&str> = p.events.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["zzz", "done", "aaa", "go"]);
    let s = &p.supervisors[0];
    let local: Vec<(usize, &str)> = s
        .local_events
        .iter()
        .map(|&(g, id)| (g, s.automaton.alphabet().name(id)))
        .collect();
    assert_eq!(local, [(1, "done"), (3, "go")]);
}

#[test]
fn actions_clear_then_set_then_reset_then_start() {
    let p = load_ok(
        r#"[plc]
name = "x"
[inputs]
i = {}
[outputs]
a = {}
b = { initial = true, safe = true }
hi = {}
lo = {}
mid = {}
[timers]
t1 = { preset_ms = 10 }
t2 = { preset_ms = 20 }
[switches]
valve = { hi = "hi", mid = "mid", lo = "lo" }
[events]
e = { rising = "i", start = ["t1"], reset = ["t2"], set = ["a"], switch = { valve = "mid" }, clear = ["b"] }
off = { falling = "i", switch = { valve = "off" } }
"#,
    );
    let o = |n: &str| p.output(n).unwrap();
    assert_eq!(
        p.events[0].actions,
        [
            Action::Clear(o("b")),
            Action::Clear(o("hi")),
            Action::Clear(o("lo")),
            Action::Set(o("a")),
            Action::Set(o("mid")),
            Action::Reset(1),
            Action::Start(0),
        ]
    );
    assert_eq!(
        p.events[1].actions,
        [
            Action::Clear(o("hi")),
            Action::Clear(o("mid")),
            Action::Clear(o("lo"))
        ]
    );
    assert_eq!(
        p.switches[0].positions,
        [
            ("hi".to_owned(), o("hi")),
            ("mid".to_owned(), o("mid")),
            ("lo".to_owned(), o("lo"))
        ]
    );
    assert_eq!(p.outputs[1].drive, Drive::Actions { initial: true });
    assert!(p.outputs[1].safe);
    assert_eq!(p.outputs[0].drive, Drive::Actions { initial: false });
}

#[test]
fn the_format_example_of_formats_md_loads() {
    let p = load_ok(
        r#"
[plc]
name = "stamping-press"
scan_period_ms = 10
max_commands_per_scan = 1
unexpected = "fault"
reset = "reset_pb"
overrun_limit = 3
overrun_fault = true
lost_edge_fault = true
rom_test_bytes_per_scan = 128

[inputs]
auto_pb  = {}
part     = { debounce_scans = 3 }
reset_pb = {}
x_pb     = {}

[outputs]
down_sol = { safe = false }
main_valve_hi = {}
main_valve_lo = {}
y = { initial = false }
auto_lamp = { states = { press = ["2", "3", "4", "6"] } }

[timers]
purge = { preset_ms = 10_000 }

[switches]
main_valve = { hi = "main_valve_hi", lo = "main_valve_lo" }

[events]
auto      = { rising = "auto_pb", when = ["reset_pb"], unless = ["x_pb"] }
part_in   = { rising = ["part", "x_pb"] }
purge_end = { expired = "purge" }
go_down   = { controllable = true, set = ["down_sol"] }
valve_hi  = { controllable = true, switch = { main_valve = "hi" } }
valve_off = { controllable = true, switch = { main_valve = "off" } }
purge_go  = { controllable = true, start = ["purge"] }
manual_x  = { controllable = true, request = "x_pb", set = ["y"] }

[[supervisor]]
name = "press"
file = "formats_example/press.toml"
"#,
    );
    assert_eq!(
        (p.overrun_limit, p.overrun_fault, p.lost_edge_fault),
        (3, true, true)
    );
    assert_eq!(p.rom_test_bytes_per_scan, 128);
    let e = &p.events[p.event("manual_x").unwrap()];
    assert_eq!(e.request, p.input("x_pb"));
    assert_eq!(e.origin, Origin::Controller);
    assert_eq!(e.trigger, Trigger::Command);
    assert_eq!(
        p.events[1].trigger,
        Trigger::Rising(vec![p.input("part").unwrap(), p.input("x_pb").unwrap()])
    );
    assert_eq!(p.events[2].trigger, Trigger::Expired(0));
    assert_eq!(p.timers[0].preset_ms, 10_000);
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

/// One way to damage a file.
#[derive(Debug, Clone)]
enum Edit {
    Flip(usize, u8),
    Delete(usize, usize),
    DuplicateLine(usize),
    Truncate(usize),
}

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    let edit = prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Edit::Flip(p, b)),
        (any::<usize>(), 1usize..20).prop_map(|(p, n)| Edit::Delete(p, n)),
        any::<usize>().prop_map(Edit::DuplicateLine),
        any::<usize>().prop_map(Edit::Truncate),
    ];
    proptest::collection::vec(edit, 1..6)
}

fn mutate(text: &str, edits: &[Edit]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for edit in edits {
        if bytes.is_empty() {
            break;
        }
        let n = bytes.len();
        match *edit {
            Edit::Flip(p, b) => bytes[p % n] = b,
            Edit::Delete(p, len) => {
                let p = p % n;
                bytes.drain(p..(p + len).min(n));
            }
            Edit::DuplicateLine(l) => {
                let text = String::from_utf8_lossy(&bytes).into_owned();
                let lines: Vec<&str> = text.split_inclusive('\n').collect();
                let l = l % lines.len();
                let mut out = String::new();
                for (i, line) in lines.iter().enumerate() {
                    out.push_str(line);
                    if i == l {
                        out.push_str(line);
                    }
                }
                bytes = out.into_bytes();
            }
            Edit::Truncate(p) => bytes.truncate(p % n),
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn mutated_projects_never_panic(which in 0usize..3, edits in edits()) {
        let name = ["press.plc.toml", "factory.plc.toml", "cell.plc.toml"][which];
        let text = std::fs::read_to_string(fixture(name)).unwrap();
        let text = mutate(&text, &edits);
        let _ = project::from_str(&text, &fixture(name));
    }
}

/// The mixers' project with its net as another editor writes it: the same
/// PNML without our tool-specific elements, and `entry` added to the
/// `[[net]]` entry; the directory, the project's path and its text.
fn foreign_mixers(entry: &str) -> (tempfile::TempDir, std::path::PathBuf, String) {
    let models = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/petri");
    let dir = tempfile::tempdir().unwrap();
    let pnml = std::fs::read_to_string(models.join("mixers.pnml")).unwrap();
    let mut foreign = String::new();
    for line in pnml.lines() {
        if !line.contains("<toolspecific tool=\"codegen\"") {
            foreign.push_str(line);
            foreign.push('\n');
        }
    }
    assert!(!foreign.contains("controllable"));
    std::fs::write(dir.path().join("foreign.pnml"), foreign).unwrap();
    std::fs::copy(
        models.join("mixers.constraints.toml"),
        dir.path().join("mixers.constraints.toml"),
    )
    .unwrap();
    let text = std::fs::read_to_string(models.join("mixers.plc.toml"))
        .unwrap()
        .replace(
            "file = \"mixers.toml\"\n",
            &format!("file = \"foreign.pnml\"\n{entry}"),
        );
    let path = dir.path().join("mixers.plc.toml");
    std::fs::write(&path, &text).unwrap();
    (dir, path, text)
}

#[test]
fn a_net_from_another_editor_needs_its_controllability_in_the_net_entry() {
    let line =
        |text: &str, needle: &str| text.lines().position(|l| l.contains(needle)).unwrap() + 1;
    let (_dir, path, text) = foreign_mixers("");
    let err = project::load(&path).unwrap_err().to_string();
    let net_line = line(&text, "[[net]]");
    assert!(
        err.contains("none of the net's 8 transitions says whether it is controllable")
            && err.ends_with(&format!(
                "add `uncontrollable = [\"T1\", …]` (the others are controllable; [] for none) or `control = \"FILE\"` to the [[net]] at {}:{net_line}:1",
                path.display()
            )),
        "{err}"
    );

    // Every transition controllable, as the project's events say.
    let (_dir, path, _) = foreign_mixers("uncontrollable = []\n");
    let p = project::load(&path).unwrap();
    assert_eq!(p.nets.len(), 1);

    // A name that is no transition, at its line.
    let (_dir, path, text) = foreign_mixers("uncontrollable = [\n  \"t9\",\n]\n");
    let err = project::load(&path).unwrap_err().to_string();
    assert!(
        err.starts_with(&format!(
            "{}:{}:3: `uncontrollable` in",
            path.display(),
            line(&text, "\"t9\"")
        )) && err.contains("names `t9`, which is no transition of"),
        "{err}"
    );

    // A transition stated uncontrollable meets the project's events,
    // which say controllable: validation refuses it at the event.
    let (_dir, path, text) = foreign_mixers("uncontrollable = \"t2\"\n");
    let err = project::load(&path).unwrap_err().to_string();
    assert!(
        err.starts_with(&format!("{}:{}:", path.display(), line(&text, "t2 = {"))),
        "{err}"
    );

    // A control file, and never both ways.
    let (dir, path, _) = foreign_mixers("control = \"mixers.control.toml\"\n");
    std::fs::write(
        dir.path().join("mixers.control.toml"),
        "uncontrollable = []\n",
    )
    .unwrap();
    project::load(&path).unwrap();
    let (dir, path, text) = foreign_mixers("control = \"c.toml\"\nunobservable = []\n");
    std::fs::write(dir.path().join("c.toml"), "uncontrollable = []\n").unwrap();
    let err = project::load(&path).unwrap_err().to_string();
    assert!(
        err.starts_with(&format!(
            "{}:{}:",
            path.display(),
            line(&text, "unobservable = []")
        )) && err.contains("not both ways"),
        "{err}"
    );
}

#[test]
fn a_local_controller_named_like_a_plant_component_takes_a_suffix() {
    let p = load_ok(
        "[plc]\nname = \"x\"\n[inputs]\ni = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"i\" }\n[[supervisor]]\nname = \"s\"\nsynthesize = { plants = [\"mini/go.toml\"], specs = [\"mini/go_once.toml\"], localize = true }\n",
    );
    let names: Vec<&str> = p.supervisors.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["s.go", "s.go.local"]);
}
