//! The IEC 61131-3 export (`iec_export`): identifiers, the I/O map and
//! its errors, and what the Structured Text says about a project. That
//! the exported text runs exactly as the executor does is shown by
//! `tests/st_lockstep.rs` (package `e2e`), which executes it.

use iec_export::pou::{PouKind, Section};
use iec_export::{self as iec, names, IoMap};
use plc_project::{self as project, Project};
use std::collections::HashSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

const SEEDS: [&str; 10] = [
    "models/motivating.plc.toml",
    "models/press.plc.toml",
    "models/press7.plc.toml",
    "models/conveyor.plc.toml",
    "models/crane.plc.toml",
    "models/agv.plc.toml",
    "models/boiler/boiler.plc.toml",
    "models/petri/mixers.plc.toml",
    "models/petri/cell/cell.plc.toml",
    "tests/fixtures/hostile/hostile.plc.toml",
];

fn load(rel: &str) -> Project {
    project::load(&root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// An IEC identifier: a letter or `_`, then letters, digits and single
/// underscores, not ending in `_`.
fn is_identifier(id: &str) -> bool {
    let b = id.as_bytes();
    !b.is_empty()
        && (b[0].is_ascii_alphabetic() || b[0] == b'_')
        && b.iter().all(|c| c.is_ascii_alphanumeric() || *c == b'_')
        && !id.contains("__")
        && !id.ends_with('_')
}

#[test]
fn every_declared_name_is_a_unique_unreserved_iec_identifier() {
    for rel in SEEDS {
        let project = load(rel);
        let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
        let pou_names: Vec<&str> = export.pous.iter().map(|p| p.name.as_str()).collect();
        for pou in &export.pous {
            let mut seen = HashSet::new();
            for name in pou_names.iter().copied().chain(
                pou.blocks
                    .iter()
                    .flat_map(|b| b.vars.iter().map(|v| v.name.as_str())),
            ) {
                assert!(is_identifier(name), "{rel}: `{name}`");
                assert!(!names::is_reserved(name), "{rel}: `{name}` is reserved");
                assert!(
                    seen.insert(name.to_ascii_uppercase()),
                    "{rel}: `{name}` twice in {}",
                    pou.name
                );
            }
        }
        // Inputs in, outputs out, with the project's names where those
        // are identifiers already.
        let fb = &export.pous[0];
        assert_eq!(fb.kind, PouKind::FunctionBlock);
        let inputs: Vec<&str> = fb.vars(Section::Input).map(|v| v.name.as_str()).collect();
        assert_eq!(inputs.len(), project.inputs.len() + 1, "{rel}");
        for (i, input) in project.inputs.iter().enumerate() {
            if is_identifier(&input.name) && !names::is_reserved(&input.name) {
                assert_eq!(export.names.inputs[i], input.name, "{rel}");
            }
            assert_eq!(inputs[i + 1], export.names.inputs[i]);
        }
        assert_eq!(export.pous[1].kind, PouKind::Program);
    }
}

/// A project whose names meet the block's own names, each other (by
/// case and by mapping), keywords and standard function blocks.
fn colliding() -> Project {
    let text = r#"
[plc]
name = "END_PROGRAM"

[inputs]
FAULT = {}
"now-ms" = {}
TON = {}
"x-1" = {}
ctrl = {}
EV_go = {}

[outputs]
"IF" = {}
"clock ms" = {}

[events]
go = { controllable = true, set = ["IF"] }
done = { rising = "FAULT" }
"#;
    let path = root().join("tests/fixtures/hostile/colliding.plc.toml");
    let text = format!("{text}\n[[supervisor]]\nname = \"machine\"\nfile = \"machine.toml\"\n");
    project::from_str(&text, &path).expect("a valid project")
}

#[test]
fn names_that_meet_get_suffixes_and_are_listed_in_the_header() {
    let project = colliding();
    let export =
        iec::export(&project, &IoMap::sequential(), "codegen st colliding").expect("exports");
    let n = &export.names;
    assert_eq!(
        n.inputs,
        ["FAULT_2", "now_ms_2", "TON_2", "x_1", "ctrl_2", "EV_go"]
    );
    assert_eq!(n.outputs, ["IF_2", "clock_ms_2"]);
    assert_eq!(n.events, ["EV_go_2", "EV_done"]);
    assert_eq!(export.pous[0].name, "END_PROGRAM_ctrl");
    let text = iec::st::print(&export);
    for (from, to) in &export.renamed {
        assert!(
            text.contains(&format!("'{from}' -> {to}")),
            "{from} -> {to}"
        );
    }
    assert_eq!(export.renamed.len(), 7, "{:?}", export.renamed);
}

#[test]
fn comments_cannot_be_closed_or_turned_around_by_a_name() {
    let text = r#"
[plc]
name = "*) x := 1; (* ]]> \u202e"

[inputs]
"a*)b" = {}

[outputs]
"(*c" = {}

[events]
go = { controllable = true, set = ["(*c"] }
done = { rising = "a*)b" }

[[supervisor]]
name = "m*)"
file = "machine.toml"
"#;
    let path = root().join("tests/fixtures/hostile/comments.plc.toml");
    let project = project::from_str(text, &path).expect("valid");
    let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
    let st = iec::st::print(&export);
    // Every comment opened on a line closes on it or, for the header,
    // at its end; no comment closes twice.
    let mut depth = 0i32;
    let bytes = st.as_bytes();
    let mut k = 0;
    while k + 1 < bytes.len() {
        match (bytes[k], bytes[k + 1]) {
            (b'(', b'*') => {
                assert_eq!(depth, 0, "nested comment at byte {k}");
                depth += 1;
                k += 2;
            }
            (b'*', b')') => {
                assert_eq!(depth, 1, "comment closed outside a comment at byte {k}");
                depth -= 1;
                k += 2;
            }
            _ => k += 1,
        }
    }
    assert_eq!(depth, 0);
    assert!(!st.contains("]]>"));
    assert!(!st.contains('\u{202e}'));
    assert!(st.contains("<U+202E>"));
}

fn io_error(map: &str) -> (u32, String) {
    let project = load("models/motivating.plc.toml");
    let io = IoMap::parse(map, Path::new("io.toml"))
        .and_then(|io| iec::export(&project, &io, "t").map(|_| io));
    let e = io.expect_err("refused");
    let (at, message) = e.located().expect("a located error");
    (at.line, message.to_owned())
}

const FULL: &str = r#"[inputs]
x_a = "%IX0.0"
x_b = "%IX0.1"
x_e = "%IX0.2"
x_f = "%IX0.3"
req_c_lo = "%IX1.0"
reset = "%I*"
[outputs]
x_c_hi = "%qx0.0"
x_c_lo = "%QX0.1"
x_d_on = "%QX4.7"
"#;

#[test]
fn an_io_map_places_every_signal_and_its_errors_name_the_line() {
    let project = load("models/motivating.plc.toml");
    let io = IoMap::parse(FULL, Path::new("io.toml")).expect("parses");
    let export = iec::export(&project, &io, "t").expect("exports");
    let st = iec::st::print(&export);
    for decl in [
        "x_a AT %IX0.0 : BOOL;",
        "req_c_lo AT %IX1.0 : BOOL;",
        "reset AT %I* : BOOL;",
        "x_c_hi AT %QX0.0 : BOOL;",
        "x_d_on AT %QX4.7 : BOOL;",
    ] {
        assert!(st.contains(decl), "{decl}");
    }

    let (line, m) = io_error(&FULL.replace("x_b = \"%IX0.1\"", "x_b = \"%IX0.9\""));
    assert_eq!(line, 3, "{m}");
    assert!(m.contains("%IX0.9") && m.contains("bit 0-7"), "{m}");
    let (line, m) = io_error(&FULL.replace("x_e = \"%IX0.2\"", "x_e = \"%QX0.2\""));
    assert_eq!(line, 4, "{m}");
    let (line, m) = io_error(&FULL.replace("x_f = \"%IX0.3\"", "x_f = \"%IX0.0\""));
    assert_eq!(line, 5, "{m}");
    assert!(m.contains("already given on line 2"), "{m}");
    let (line, m) = io_error(&FULL.replace("x_c_lo", "x_c_mid"));
    assert_eq!(line, 10, "{m}");
    assert!(m.contains("`x_c_mid` is not an output"), "{m}");
    let (line, m) = io_error(&FULL.replace("x_a = \"%IX0.0\"\n", ""));
    assert_eq!(line, 1, "{m}");
    assert!(m.contains("x_a") && m.contains("no address"), "{m}");
    let (line, m) = io_error(&format!("{FULL}[timers]\nt = \"%IX9.0\"\n"));
    assert_eq!(line, 12, "{m}");
    let (line, m) = io_error(&FULL.replace("\"%IX0.1\"", "1"));
    assert_eq!(line, 3, "{m}");
}

#[test]
fn default_addresses_count_bits_then_bytes() {
    let project = load("models/boiler/boiler.plc.toml");
    let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
    let program = &export.pous[1];
    let addresses: Vec<&str> = program
        .vars(Section::Local)
        .filter_map(|v| v.address.as_deref())
        .collect();
    let inputs = project.inputs.len();
    assert_eq!(addresses.len(), inputs + project.outputs.len());
    for (k, a) in addresses[..inputs].iter().enumerate() {
        assert_eq!(*a, format!("%IX{}.{}", k / 8, k % 8));
    }
    for (k, a) in addresses[inputs..].iter().enumerate() {
        assert_eq!(*a, format!("%QX{}.{}", k / 8, k % 8));
    }
}

/// The elements of constant array `name` of the controller, in order.
fn array_values(export: &iec::Export, name: &str) -> (Vec<(i64, i64)>, Vec<i64>) {
    use iec_export::pou::{Init, Type};
    let var = export.pous[0]
        .vars(Section::Constant)
        .find(|v| v.name == name)
        .unwrap_or_else(|| panic!("no array {name}"));
    let Type::Array { dims, .. } = &var.ty else {
        panic!("{name} is not an array")
    };
    let Some(Init::Rows(rows)) = &var.init else {
        panic!("{name} has no rows")
    };
    let values = rows
        .iter()
        .flat_map(|(_, row)| row.iter().map(|v| v.parse::<i64>().expect("a number")))
        .collect();
    (dims.clone(), values)
}

#[test]
fn the_transition_arrays_are_the_supervisors_transition_functions() {
    use des::StateId;
    let mut layouts = (0, 0);
    for rel in [
        "models/crane.plc.toml",
        "models/boiler/boiler.plc.toml",
        "models/agv.plc.toml",
    ] {
        let project = load(rel);
        let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
        for (j, sup) in project.supervisors.iter().enumerate() {
            let a = &sup.automaton;
            let n = a.num_states();
            let cols = sup.local_events.len();
            // The target of (state, column) as the export stores it.
            let target: Box<dyn Fn(usize, usize) -> i64> = match &export.names.sparse[j] {
                None => {
                    layouts.0 += 1;
                    let (dims, values) = array_values(&export, &export.names.tables[j]);
                    assert_eq!(dims, [(0, n as i64 - 1), (0, cols as i64 - 1)]);
                    assert_eq!(values.len(), n * cols);
                    Box::new(move |s, k| values[s * cols + k])
                }
                Some(t) => {
                    layouts.1 += 1;
                    assert!(iec::scan::sparse_layout(&project)[j]);
                    let (_, rows) = array_values(&export, &t.rows);
                    let (_, columns) = array_values(&export, &t.columns);
                    let (_, targets) = array_values(&export, &t.targets);
                    assert_eq!(rows.len(), n + 1);
                    assert_eq!(columns.len(), targets.len());
                    assert_eq!(rows[n] as usize + 1, columns.len(), "one −1 at the end");
                    assert_eq!(
                        (columns[rows[n] as usize], targets[rows[n] as usize]),
                        (-1, -1)
                    );
                    Box::new(move |s, k| {
                        let entries = rows[s] as usize..rows[s + 1] as usize;
                        let hits: Vec<i64> = entries
                            .filter(|&i| columns[i] == k as i64)
                            .map(|i| targets[i])
                            .collect();
                        assert!(hits.len() <= 1, "state {s} column {k} twice");
                        hits.first().copied().unwrap_or(-1)
                    })
                }
            };
            for s in 0..n {
                for (k, &(_, id)) in sup.local_events.iter().enumerate() {
                    let expected = a
                        .successor(StateId(s as u32), id)
                        .map_or(-1, |t| i64::from(t.0));
                    assert_eq!(target(s, k), expected, "{rel} {} {s} {k}", sup.name);
                }
            }
        }
    }
    assert!(layouts.0 > 0 && layouts.1 > 0, "both layouts: {layouts:?}");
}

/// The range of an integer type of the export, `None` for others.
fn range(ty: &iec_export::pou::Type) -> Option<(i64, i64)> {
    use iec_export::pou::Type;
    match ty {
        Type::Sint => Some((i8::MIN.into(), i8::MAX.into())),
        Type::Int => Some((i16::MIN.into(), i16::MAX.into())),
        Type::Dint => Some((i32::MIN.into(), i32::MAX.into())),
        Type::Udint => Some((0, u32::MAX.into())),
        Type::Array { elem, .. } => range(elem),
        Type::Bool | Type::Instance(_) => None,
    }
}

/// Every initial value and constant of `export` within its declared type
/// (a 2nd-edition compiler such as matiec converts nothing implicitly).
fn assert_values_fit(export: &iec::Export, what: &str) -> usize {
    use iec_export::pou::Init;
    let mut checked = 0;
    for pou in &export.pous {
        for var in pou.blocks.iter().flat_map(|b| &b.vars) {
            let (Some((lo, hi)), Some(init)) = (range(&var.ty), &var.init) else {
                continue;
            };
            let values: Vec<&String> = match init {
                Init::Value(v) => vec![v],
                Init::Rows(rows) => rows.iter().flat_map(|(_, r)| r).collect(),
            };
            for v in values {
                let n: i64 = v
                    .parse()
                    .unwrap_or_else(|_| panic!("{what}: {} = {v}", var.name));
                assert!(
                    (lo..=hi).contains(&n),
                    "{what}: {} : {} := {n} is outside its type",
                    var.name,
                    var.ty.iec()
                );
                checked += 1;
            }
        }
    }
    checked
}

#[test]
fn every_constant_fits_its_declared_type() {
    for rel in [
        "models/press.plc.toml",
        "models/agv.plc.toml",
        "models/boiler/boiler_mono.plc.toml",
        "models/petri/cell/cell.plc.toml",
        "tests/fixtures/iec_names/iec_names.plc.toml",
    ] {
        let project = load(rel);
        let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
        assert!(
            assert_values_fit(&export, rel) > 0,
            "{rel}: nothing checked"
        );
    }
    // 40,000 tokens: the marking array is DINT.
    let project = load("tests/fixtures/iec_names/iec_names.plc.toml");
    let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
    let marking = export.pous[0]
        .vars(Section::Output)
        .find(|v| v.name == export.names.nets[0])
        .expect("the marking");
    assert!(
        marking.ty.iec().ends_with("OF DINT"),
        "{}",
        marking.ty.iec()
    );
    // More inputs than an INT counts: their index constants are DINT.
    let mut text = String::from("[plc]\nname = \"wide\"\n\n[inputs]\n");
    for i in 0..32_770 {
        text.push_str(&format!("i{i} = {{}}\n"));
    }
    text.push_str(
        "\n[outputs]\nlamp = {}\n\n[events]\ngo = { controllable = true, set = [\"lamp\"] }\n\
         done = { rising = \"i32769\" }\n\n[[supervisor]]\nname = \"machine\"\nfile = \"machine.toml\"\n",
    );
    let path = root().join("tests/fixtures/hostile/wide.plc.toml");
    let project = project::from_str(&text, &path).expect("a valid project");
    let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
    let last = export.pous[0]
        .vars(Section::Constant)
        .find(|v| v.name == "IN_i32769")
        .expect("the last input's index");
    assert_eq!(last.ty.iec(), "DINT");
    assert!(assert_values_fit(&export, "32,770 inputs") > 32_770);
}

/// The conveyor module's symbolic supervisor: every guard that does not
/// always hold is a term of its command's feasibility test, as the state
/// comparison its text states, with its text in a comment; the whole file
/// stays under the 2,000 lines issue 24 sets, and nothing needs the chain
/// temporaries.
#[test]
fn the_modules_guards_are_state_comparisons_in_their_commands_tests() {
    let project = load("models/module.plc.toml");
    let export = iec::export(&project, &IoMap::sequential(), "t").expect("exports");
    let text = iec::st::print(&export);
    let lines = text.lines().count();
    assert!(lines <= 2_000, "{lines} lines");
    assert!(!text.contains("GN["), "no chain needed");
    let g = &project.guarded[0];
    let guarded: Vec<_> = g.guards.iter().filter(|eg| eg.root != 1).collect();
    assert_eq!(guarded.len(), 10);
    for eg in guarded {
        // `C = s`: component C's state variable equals s's number.
        let event = &project.events[eg.event].name;
        let (component, state) = eg.text.split_once(" = ").expect("C = s");
        let j = project
            .supervisors
            .iter()
            .position(|s| s.name == format!("module.{component}"))
            .expect("a component");
        let a = &project.supervisors[j].automaton;
        let s = a
            .states()
            .find(|&s| a.state_name(s) == state)
            .expect("a state");
        let comment = format!("(* guard of {event} (module): {} *)", eg.text);
        let at = text.find(&comment).unwrap_or_else(|| panic!("{comment}"));
        let head = text[at..].lines().nth(1).expect("the test");
        assert!(
            head.contains(&format!(
                "AND ({} = {}) THEN (* {event} *)",
                export.names.states[j], s.0
            )),
            "{head}"
        );
    }
}
