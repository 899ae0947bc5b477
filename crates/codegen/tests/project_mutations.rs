//! Malformed projects never panic the loader, and every error points into
//! the right file.
//!
//! A property test takes the text of every project in `models/`
//! (`*.plc.toml`, read at test time) and applies random mutations: delete,
//! duplicate or swap lines, replace a token by another token of the file,
//! insert random bytes, truncate, change a number to a huge, negative or
//! non-integer value, rename one occurrence of a name (so that the other
//! occurrences no longer match it, or collide after sanitising). The result
//! is parsed with `project::from_str` as if it were the original file, so
//! model paths still resolve against `models/`. For thousands of cases from
//! a fixed seed it proves:
//!
//! - `from_str` returns (no panic), and so does generating table code from
//!   every project that still loads;
//! - every error located in the project names the project file and a line
//!   (and column) inside the text; an error located in a model file (a
//!   mutated path may name another file of `models/`, whose own errors
//!   point into it) names that existing file; an error without location
//!   still names the project file.
//!
//! Deterministic tests then pin the messages (and lines) of specific
//! damage to the seed projects themselves, which `tests/project.rs` (on
//! fixtures) does not load: undeclared events of a synthesised supervisor,
//! unknown inputs in bindings, sanitised-name collisions of a supervisor
//! or a timer with an event, an output driven twice, a controllable event
//! in no supervisor's alphabet.

use codegen::backend::Backend;
use codegen::emit::generate;
use des::Error;
use plc_project as project;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
use std::ops::Range;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// The seed projects, which must load unmutated.
const SEEDS: [&str; 4] = [
    "motivating.plc.toml",
    "press.plc.toml",
    "press7.plc.toml",
    "conveyor.plc.toml",
];

/// Mutated cases in total (spread over the projects by the strategy).
const CASES: u32 = 2_500;

/// The repository's `models/` directory.
fn models() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models")
}

/// Projects that are another one with a single key changed (the AGV
/// reduced and localized: `reduce = true`, `localize = true`), left out:
/// each load synthesises and reduces the 4,406-state supervisor four
/// times over, which would take minutes in a debug build for mutations
/// the AGV itself already gets.
const VARIANTS: [&str; 2] = ["agv_reduced.plc.toml", "agv_localized.plc.toml"];

/// Every project file in `models/` but the [`VARIANTS`], sorted, with its
/// text.
fn projects() -> Vec<(PathBuf, String)> {
    let mut list: Vec<(PathBuf, String)> = std::fs::read_dir(models())
        .expect("models/ exists")
        .map(|entry| entry.expect("readable directory").path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.ends_with(".plc.toml") && !VARIANTS.contains(&n))
        })
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("readable project");
            (p, text)
        })
        .collect();
    list.sort();
    list
}

/// The lexical classes mutations work on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// A bare word: key, number, `true`.
    Word,
    /// A basic string, quotes included.
    Str,
    /// Any other single character.
    Punct,
}

/// Byte spans of the tokens of `text` (comments skipped).
fn tokens(text: &str) -> Vec<(Range<usize>, Kind)> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        let start = i;
        if c.is_ascii_whitespace() {
            i += 1;
        } else if c == b'#' {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
        } else if c == b'"' {
            i += 1;
            while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
                i += if bytes[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(bytes.len());
            out.push((start..i, Kind::Str));
        } else if c.is_ascii_alphanumeric() || matches!(c, b'_' | b'-' | b'+') {
            while i < bytes.len()
                && (bytes[i].is_ascii_alphanumeric() || matches!(bytes[i], b'_' | b'-' | b'+'))
            {
                i += 1;
            }
            out.push((start..i, Kind::Word));
        } else {
            // One character (a whole UTF-8 sequence).
            i += 1;
            while i < bytes.len() && (bytes[i] & 0xc0) == 0x80 {
                i += 1;
            }
            out.push((start..i, Kind::Punct));
        }
    }
    out
}

/// Values a number is changed to: limits of every field's range and
/// beyond, negative, and things that are not integers at all.
const NUMBERS: &[&str] = &[
    "0",
    "-1",
    "1",
    "255",
    "256",
    "65535",
    "65536",
    "2147483647",
    "2147483648",
    "4294967296",
    "9223372036854775807",
    "-9223372036854775808",
    "99999999999999999999999",
    "1e400",
    "-0",
    "nan",
    "-inf",
    "1.5",
    "0x7fffffff",
    "1_000_000_000_000",
    "true",
    "\"10\"",
];

/// How one occurrence of a name is renamed.
const RENAMES: usize = 8;

fn rename(name: &str, style: usize, text: &str) -> String {
    match style % RENAMES {
        0 => format!("{name}_2"),
        // Sanitises to the same identifier as the original.
        1 => name.replace('_', "-").to_uppercase(),
        2 => String::new(),
        3 => "***".to_owned(),
        4 => format!("1{name}"),
        5 => format!("{name}é"),
        6 => name.repeat(200),
        // Another name of the file: a collision or a wrong reference.
        _ => {
            let words: Vec<&str> = tokens(text)
                .into_iter()
                .filter(|(_, k)| *k == Kind::Word)
                .map(|(r, _)| &text[r])
                .collect();
            words
                .get(name.len() % words.len().max(1))
                .map_or_else(|| "x".to_owned(), |w| (*w).to_owned())
        }
    }
}

/// One way to damage a project file. Indices are taken modulo whatever
/// they index when applied.
#[derive(Debug, Clone)]
enum Mutation {
    DeleteLine(usize),
    DuplicateLine(usize),
    SwapLines(usize, usize),
    ReplaceToken { at: usize, with: usize },
    InsertBytes { at: usize, bytes: Vec<u8> },
    Truncate(usize),
    Number { which: usize, value: usize },
    RenameOnce { which: usize, style: usize },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let byte = prop_oneof![
        any::<u8>(),
        prop::sample::select(b"\"[]{}=,.#\\\n\t\r 0_-".to_vec()),
    ];
    prop_oneof![
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        2 => (any::<usize>(), any::<usize>())
            .prop_map(|(at, with)| Mutation::ReplaceToken { at, with }),
        1 => (any::<usize>(), prop::collection::vec(byte, 1..8))
            .prop_map(|(at, bytes)| Mutation::InsertBytes { at, bytes }),
        1 => any::<usize>().prop_map(Mutation::Truncate),
        2 => (any::<usize>(), any::<usize>())
            .prop_map(|(which, value)| Mutation::Number { which, value }),
        3 => (any::<usize>(), any::<usize>())
            .prop_map(|(which, style)| Mutation::RenameOnce { which, style }),
    ]
}

fn splice(text: &str, range: Range<usize>, with: &str) -> String {
    format!("{}{with}{}", &text[..range.start], &text[range.end..])
}

/// `text` with `m` applied.
fn apply(text: &str, m: &Mutation) -> String {
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let toks = tokens(text);
    match m {
        _ if text.is_empty() => String::new(),
        Mutation::DeleteLine(l) => {
            let l = l % lines.len();
            lines
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != l)
                .map(|(_, s)| *s)
                .collect()
        }
        Mutation::DuplicateLine(l) => {
            let l = l % lines.len();
            let mut out: Vec<&str> = lines.clone();
            out.insert(l, lines[l]);
            out.concat()
        }
        Mutation::SwapLines(a, b) => {
            let mut out: Vec<String> = lines
                .iter()
                .map(|s| s.trim_end_matches('\n').into())
                .collect();
            out.swap(a % lines.len(), b % lines.len());
            out.join("\n") + if text.ends_with('\n') { "\n" } else { "" }
        }
        Mutation::ReplaceToken { at, with } => {
            if toks.is_empty() {
                return text.to_owned();
            }
            let (target, _) = &toks[at % toks.len()];
            let (source, _) = &toks[with % toks.len()];
            splice(text, target.clone(), &text[source.clone()])
        }
        Mutation::InsertBytes { at, bytes } => {
            let at = at % (text.len() + 1);
            let mut raw = text.as_bytes()[..at].to_vec();
            raw.extend_from_slice(bytes);
            raw.extend_from_slice(&text.as_bytes()[at..]);
            String::from_utf8_lossy(&raw).into_owned()
        }
        Mutation::Truncate(at) => {
            let mut at = at % text.len();
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            text[..at].to_owned()
        }
        Mutation::Number { which, value } => {
            let numbers: Vec<&Range<usize>> = toks
                .iter()
                .filter(|(r, k)| {
                    *k == Kind::Word && text[r.clone()].starts_with(|c: char| c.is_ascii_digit())
                })
                .map(|(r, _)| r)
                .collect();
            if numbers.is_empty() {
                return text.to_owned();
            }
            let target = numbers[which % numbers.len()].clone();
            splice(text, target, NUMBERS[value % NUMBERS.len()])
        }
        Mutation::RenameOnce { which, style } => {
            // Names: words and string contents that occur more than once.
            let name_of = |(r, k): &(Range<usize>, Kind)| -> Option<Range<usize>> {
                match k {
                    Kind::Word => Some(r.clone()),
                    Kind::Str if r.len() >= 2 => Some(r.start + 1..r.end - 1),
                    _ => None,
                }
            };
            let names: Vec<Range<usize>> = toks.iter().filter_map(name_of).collect();
            let repeated: Vec<Range<usize>> = names
                .iter()
                .filter(|r| {
                    !r.is_empty()
                        && names
                            .iter()
                            .filter(|o| text[(*o).clone()] == text[(*r).clone()])
                            .count()
                            > 1
                })
                .cloned()
                .collect();
            if repeated.is_empty() {
                return text.to_owned();
            }
            let target = repeated[which % repeated.len()].clone();
            let new = rename(&text[target.clone()], *style, text);
            splice(text, target, &new)
        }
    }
}

/// What a case's outcome says about the loader; `Err` describes a defect.
fn check_outcome(path: &Path, text: &str) -> Result<(), String> {
    let loaded = catch_unwind(AssertUnwindSafe(|| project::from_str(text, path)))
        .map_err(|_| "project::from_str panicked".to_owned())?;
    let err = match loaded {
        Ok(p) => {
            return catch_unwind(AssertUnwindSafe(|| {
                generate(&p, Backend::Table, "project_mutations")
            }))
            .map(|_| ())
            .map_err(|_| "emit::generate panicked on a project that loaded".to_owned());
        }
        Err(e) => e,
    };
    let shown = err.to_string();
    let file_name = path.file_name().unwrap().to_string_lossy();
    match err.located() {
        Some((location, _)) if location.file == path => {
            if !shown.contains(&*file_name) {
                return Err(format!("error does not name `{file_name}`: {shown}"));
            }
            // Lines as an editor counts them: a final newline opens one more.
            let lines: Vec<&str> = text.split('\n').collect();
            let line = location.line as usize;
            if line < 1 || line > lines.len() {
                return Err(format!("line {line} outside 1..={}: {shown}", lines.len()));
            }
            let width = lines[line - 1].chars().count() + 1;
            let column = location.column as usize;
            if column < 1 || column > width {
                return Err(format!(
                    "column {column} outside 1..={width} of line {line}: {shown}"
                ));
            }
            Ok(())
        }
        Some((location, _)) => {
            // Inside a model file the project names (they propagate
            // unchanged, pointing into that file).
            if !location.file.is_file() {
                return Err(format!("error located in no existing file: {shown}"));
            }
            if !shown.contains(&*location.file.to_string_lossy()) {
                return Err(format!("error does not name its file: {shown}"));
            }
            Ok(())
        }
        None if shown.contains(&*file_name) => Ok(()),
        None => Err(format!(
            "error names neither the project nor a line: {err:?}"
        )),
    }
}

#[test]
fn mutated_seed_projects_never_panic_and_errors_point_into_the_project() {
    let projects = projects();
    // The seed projects themselves load (others that may appear in
    // models/ are mutated all the same, but not required to load).
    for seed in SEEDS {
        let (path, text) = projects
            .iter()
            .find(|(p, _)| p.ends_with(seed))
            .unwrap_or_else(|| panic!("no models/{seed}"));
        project::from_str(text, path).unwrap_or_else(|e| panic!("{e}"));
    }

    let config = Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[0x5e; 32]);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let strategy = (0..projects.len(), prop::collection::vec(mutation(), 1..4));
    let result = runner.run(&strategy, |(which, mutations)| {
        let (path, original) = &projects[which];
        let text = mutations.iter().fold(original.clone(), |t, m| apply(&t, m));
        check_outcome(path, &text).map_err(|defect| {
            TestCaseError::fail(format!(
                "{}: {defect}\n--- mutated text ---\n{text}",
                path.display()
            ))
        })
    });
    if let Err(e) = result {
        panic!("{e}");
    }
}

/// The 1-based line of the first line of `text` containing `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("no `{needle}` in\n{text}"))
        + 1
}

/// The line of the unedited seed project `name` containing `needle`.
fn seed_line(name: &str, needle: &str) -> usize {
    line_of(
        &std::fs::read_to_string(models().join(name)).unwrap(),
        needle,
    )
}

/// A seed project, with `edit` applied to its text, loaded as itself.
fn load_edited(
    name: &str,
    edit: impl Fn(&str) -> String,
) -> (Result<project::Project, Error>, String) {
    let path = models().join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text, "the edit changes nothing");
    (project::from_str(&edited, &path), edited)
}

/// The error of the edited seed project, checked to be at the first line
/// containing `at` and to contain every fragment.
fn expect_error(name: &str, edit: impl Fn(&str) -> String, at: &str, fragments: &[&str]) {
    let (result, text) = load_edited(name, edit);
    let err = match result {
        Ok(_) => panic!("{name}: the edit should be an error\n{text}"),
        Err(e) => e,
    };
    let line = line_of(&text, at);
    let shown = err.to_string();
    let (location, _) = err
        .located()
        .unwrap_or_else(|| panic!("not located: {shown}"));
    assert_eq!(location.file, models().join(name), "{shown}");
    assert_eq!(location.line as usize, line, "{shown}");
    assert!(shown.contains(&format!("{name}:{line}:")), "{shown}");
    for f in fragments {
        assert!(shown.contains(f), "`{f}` not in: {shown}");
    }
}

#[test]
fn an_event_of_a_synthesised_supervisor_left_undeclared_names_its_model() {
    expect_error(
        "conveyor.plc.toml",
        |t| t.replace("gone = { expired = \"runon\" }\n", ""),
        "[[supervisor]]",
        &[
            "event `gone` of synthesised supervisor `conveyor`",
            "runon.toml",
            "is not declared in [events]",
        ],
    );
}

#[test]
fn a_binding_to_an_unknown_input_is_reported_where_it_is_written() {
    expect_error(
        "motivating.plc.toml",
        |t| t.replace("b = { rising = \"x_b\" }", "b = { rising = \"x_bb\" }"),
        "\"x_bb\"",
        &["unknown input `x_bb`: not declared in [inputs]"],
    );
}

#[test]
fn a_supervisor_name_that_sanitises_like_an_event_collides() {
    expect_error(
        "conveyor.plc.toml",
        |t| {
            t.replace(
                "name = \"conveyor\"\nsynthesize",
                "name = \"Re-Ls\"\nsynthesize",
            )
        },
        "\"Re-Ls\"",
        &[&format!(
            "supervisor `Re-Ls` and event `re_ls` (line {}) both become the identifier `RE_LS`",
            seed_line("conveyor.plc.toml", "re_ls =")
        )],
    );
}

#[test]
fn a_timer_name_that_sanitises_like_an_event_collides() {
    expect_error(
        "conveyor.plc.toml",
        |t| {
            t.replace(
                "gone = { expired = \"runon\" }",
                "RUNON = { expired = \"runon\" }",
            )
        },
        "RUNON =",
        &[&format!(
            "event `RUNON` and timer `runon` (line {}) both become the identifier `RUNON`",
            seed_line("conveyor.plc.toml", "runon =")
        )],
    );
}

#[test]
fn a_moore_output_driven_by_a_switch_too_is_driven_twice() {
    expect_error(
        "motivating.plc.toml",
        |t| {
            t.replace(
                "x_c_hi = {}",
                "x_c_hi = { states = { motivating = [\"3\"] } }",
            )
        },
        "c = { hi = \"x_c_hi\"",
        &["output `x_c_hi` has a state map", "(output driven twice)"],
    );
}

#[test]
fn a_controllable_event_of_no_supervisor_can_never_be_allowed() {
    expect_error(
        "motivating.plc.toml",
        |t| {
            t.replace(
                "d_off = { controllable = true, switch = { d = \"off\" } }",
                "d_off = { controllable = true, switch = { d = \"off\" } }\nd_pulse = { controllable = true, switch = { d = \"on\" } }",
            )
        },
        "d_pulse",
        &["controllable event `d_pulse` is in no supervisor's alphabet"],
    );
}
