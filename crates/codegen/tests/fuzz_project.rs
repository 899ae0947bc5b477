//! The body of the `fuzz_project` target (`crates/codegen/fuzz`) on the
//! stable toolchain: the seed projects, then the seeds with a declared name
//! renamed everywhere to a name that is hard on generated code (keywords,
//! generated names, unicode, bidirectional overrides, control characters).

#[path = "../fuzz/src/lib.rs"]
mod fuzz_project;

use fuzz_project::{check_project, model_root, SEED_PROJECTS};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn root() -> &'static Path {
    static ROOT: OnceLock<PathBuf> = OnceLock::new();
    ROOT.get_or_init(|| {
        let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-project-models");
        model_root(&repo(), &root).unwrap();
        root
    })
}

/// Seeds whose generated code takes seconds to lay out and check in a
/// debug build (the fuzz target, optimised, takes them all).
const SLOW: [&str; 2] = ["models/agv.plc.toml", "models/boiler/boiler_mono.plc.toml"];

/// The seed projects but the [`SLOW`] ones, by name, with their text.
fn seeds() -> &'static [(&'static str, String)] {
    static SEEDS: OnceLock<Vec<(&str, String)>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        SEED_PROJECTS
            .into_iter()
            .filter(|p| !SLOW.contains(p))
            .map(|p| (p, std::fs::read_to_string(repo().join(p)).unwrap()))
            .collect()
    })
}

#[test]
fn every_seed_project_validates_in_the_fuzzing_directory_and_passes_the_checks() {
    assert_eq!(seeds().len(), SEED_PROJECTS.len() - SLOW.len());
    for (name, text) in seeds() {
        let path = root().join("fuzz.plc.toml");
        if let Err(e) = plc_project::from_str(text, &path) {
            panic!("{name}: {e}");
        }
        check_project(text, root());
    }
}

/// The names `text` declares for its own signals (inputs, outputs,
/// timers): a rename of one of them everywhere keeps a project valid
/// unless the new name is refused, where a rename of an event would not
/// match the supervisors' alphabets.
fn signal_names(text: &str) -> Vec<String> {
    let table: toml::Table = text.parse().unwrap();
    ["inputs", "outputs", "timers"]
        .iter()
        .filter_map(|kind| table.get(*kind).and_then(toml::Value::as_table))
        .flat_map(|signals| signals.keys().cloned())
        .collect()
}

/// `text` with every whole word `from` (outside comments) replaced by the
/// name `to`: inside a string as its escaped content, elsewhere (a key) as
/// a quoted key.
fn rename(text: &str, from: &str, to: &str) -> String {
    let mut escaped = String::new();
    for c in to.chars() {
        match c {
            '"' | '\\' => escaped.extend(['\\', c]),
            c if c.is_control() => escaped.push_str(&format!("\\u{:04X}", u32::from(c))),
            c => escaped.push(c),
        }
    }
    let quoted = format!("\"{escaped}\"");
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let (mut in_string, mut rest) = (false, line);
        while let Some(c) = rest.chars().next() {
            let word_len = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            if word_len > 0 {
                let word = &rest[..word_len];
                if word == from {
                    out.push_str(if in_string { &escaped } else { &quoted });
                } else {
                    out.push_str(word);
                }
                rest = &rest[word_len..];
                continue;
            }
            if c == '#' && !in_string {
                out.push_str(rest);
                break;
            }
            let mut len = c.len_utf8();
            if in_string && c == '\\' {
                // An escape: the character after it does not end the string.
                len += rest[len..].chars().next().map_or(0, char::len_utf8);
            } else if c == '"' {
                in_string = !in_string;
            }
            out.push_str(&rest[..len]);
            rest = &rest[len..];
        }
    }
    out
}

/// Names that generated code must survive.
fn hard_name() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "count",
            "COUNT",
            "names",
            "Names",
            "fn",
            "fn_",
            "Self",
            "self",
            "self_",
            "type",
            "TYPE_",
            "mod",
            "crate",
            "super",
            "Index",
            "CONFIG",
            "PROGRAM",
            "IMAGE_CRC",
            "tables",
            "board",
            "input",
            "event",
            "states",
            "matches",
            "sup_x",
            "_",
            "__",
            "0",
            "1st",
            "a-b",
            "a_b",
            "é",
            "a b",
            "a\u{202e}b",
            "a\u{2066}",
            "a\nb",
            "a\"b",
            "a`b",
            "a\\b",
            "a//b",
            "*/",
            "",
        ])
        .prop_map(str::to_owned),
        "\\PC{1,6}",
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The checks of the fuzz target hold for every seed with up to three
    /// of its signals renamed.
    #[test]
    fn renamed_seed_projects_pass_the_checks(
        seed in any::<prop::sample::Index>(),
        renames in proptest::collection::vec((any::<prop::sample::Index>(), hard_name()), 1..4),
    ) {
        let mut text = seed.get(seeds()).1.clone();
        let names = signal_names(&text);
        for (name, to) in renames {
            text = rename(&text, name.get(&names).as_str(), &to);
        }
        check_project(&text, root());
    }
}

#[test]
fn a_rename_reaches_keys_and_strings_but_not_comments() {
    let text = "[inputs]\nauto_pb = {} # auto_pb\n[events]\nauto = { rising = \"auto_pb\" }\n";
    assert_eq!(
        rename(text, "auto_pb", "a\"b"),
        "[inputs]\n\"a\\\"b\" = {} # auto_pb\n[events]\nauto = { rising = \"a\\\"b\" }\n"
    );
    assert_eq!(signal_names(text), ["auto_pb"]);
}
