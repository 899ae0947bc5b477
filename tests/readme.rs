//! The README's `codegen` examples are what the command prints.
//!
//! Every ```` ```console ```` block of the section "The `codegen` command"
//! is run: each `$ codegen …` line (continued by a trailing `\`) in one
//! scratch directory where `models/` is the repository's, its standard
//! output compared line by line with the lines under it. Times (`(0.1 ms`)
//! are compared as `(… ms`; a last line `…` stands for more output. The
//! README keeps real-looking output; this test keeps it true.

use e2e::{codegen, repo};
use std::path::Path;

/// One `$ codegen …` line of the README and the output shown under it.
#[derive(Debug, Clone)]
struct Example {
    args: Vec<String>,
    expected: Vec<String>,
    /// The shown output ends with `…`: it is a prefix.
    truncated: bool,
}

/// The section of the README about the `codegen` command.
fn section(readme: &str) -> &str {
    let start = readme
        .find("## The `codegen` command")
        .expect("README has the section \"The `codegen` command\"");
    let rest = &readme[start..];
    let end = rest[3..].find("\n## ").map_or(rest.len(), |i| i + 3);
    &rest[..end]
}

/// The examples of the console blocks of `text`.
fn examples(text: &str) -> Vec<Example> {
    let mut examples = Vec::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        if line.trim() != "```console" {
            continue;
        }
        let mut current: Option<Example> = None;
        let mut continued = false;
        for line in lines.by_ref() {
            if line.trim() == "```" {
                break;
            }
            if let Some(command) = line.strip_prefix("$ ").filter(|_| !continued) {
                examples.extend(current.take());
                current = Some(Example {
                    args: Vec::new(),
                    expected: Vec::new(),
                    truncated: false,
                });
                continued = push_words(current.as_mut().unwrap(), command);
            } else if continued {
                continued = push_words(current.as_mut().unwrap(), line);
            } else {
                let example = current
                    .as_mut()
                    .unwrap_or_else(|| panic!("output before any command: {line:?}"));
                assert!(!example.truncated, "output after `…`: {line:?}");
                if line == "…" {
                    example.truncated = true;
                } else {
                    example.expected.push(line.to_owned());
                }
            }
        }
        examples.extend(current.take());
    }
    examples
}

/// Adds the words of one command line; `true` when it continues.
fn push_words(example: &mut Example, line: &str) -> bool {
    let (line, continues) = match line.trim_end().strip_suffix('\\') {
        Some(rest) => (rest, true),
        None => (line, false),
    };
    for word in line.split_whitespace() {
        assert!(
            !word.contains(['*', '?', '|', '>', '<', '"', '\'', '$', '`']),
            "README commands run without a shell: spell out `{word}`"
        );
        example.args.push(word.to_owned());
    }
    continues
}

/// `line` with every time `(12.3 ms` written `(… ms`.
fn normalise(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut rest = line;
    while let Some(open) = rest.find('(') {
        out.push_str(&rest[..=open]);
        rest = &rest[open + 1..];
        let digits = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(rest.len());
        let unit = rest[digits..].strip_prefix(" ms");
        if digits > 0 && unit.is_some_and(|u| !u.starts_with(char::is_alphanumeric)) {
            out.push('…');
            rest = &rest[digits..];
        }
    }
    out.push_str(rest);
    out
}

/// Why `stdout` is not what `example` shows, if it is not.
fn mismatch(example: &Example, stdout: &str) -> Option<String> {
    let actual: Vec<String> = stdout.lines().map(normalise).collect();
    let expected: Vec<String> = example.expected.iter().map(|l| normalise(l)).collect();
    let compared = if example.truncated {
        actual.get(..expected.len()).unwrap_or(&actual)
    } else {
        &actual
    };
    (compared != expected.as_slice()).then(|| {
        format!(
            "$ {}\nREADME shows:\n{}{}\ncodegen prints:\n{stdout}",
            example.args.join(" "),
            example.expected.join("\n"),
            if example.truncated { "\n…" } else { "" },
        )
    })
}

/// Runs `example` in `dir`; its mismatch, if any.
fn run(example: &Example, dir: &Path) -> Option<String> {
    let (program, args) = example.args.split_first().expect("a command");
    assert_eq!(program, "codegen", "README examples run `codegen …`");
    let out = codegen()
        .args(args)
        .current_dir(dir)
        .output()
        .expect("codegen starts");
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !stderr.is_empty() {
        return Some(format!(
            "$ {}\nprints on stderr:\n{stderr}",
            example.args.join(" ")
        ));
    }
    mismatch(example, &String::from_utf8_lossy(&out.stdout))
}

/// A scratch directory whose `models/` is the repository's.
fn scratch() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(repo().join("models"), dir.path().join("models")).unwrap();
    dir
}

fn readme() -> String {
    std::fs::read_to_string(repo().join("README.md")).unwrap()
}

#[test]
fn the_readme_examples_are_what_codegen_prints() {
    let readme = readme();
    let examples = examples(section(&readme));
    assert!(examples.len() >= 3, "{examples:?}");
    let dir = scratch();
    let failures: Vec<String> = examples.iter().filter_map(|e| run(e, dir.path())).collect();
    assert!(
        failures.is_empty(),
        "the README's `codegen` examples disagree with the command:\n\n{}",
        failures.join("\n\n")
    );
}

#[test]
fn a_changed_figure_fails_and_a_changed_time_does_not() {
    let readme = readme();
    let synth = examples(section(&readme))
        .into_iter()
        .find(|e| e.args.get(1).map(String::as_str) == Some("synth"))
        .expect("a synth example");
    let dir = scratch();
    assert_eq!(run(&synth, dir.path()), None);

    let mut other_time = synth.clone();
    for line in &mut other_time.expected {
        *line = line.replace(" ms", "0 ms");
    }
    assert_eq!(run(&other_time, dir.path()), None);

    let mut other_size = synth.clone();
    let line = other_size
        .expected
        .iter_mut()
        .find(|l| l.starts_with("supervisor:"))
        .expect("a supervisor line");
    *line = line.replace("12 states", "13 states");
    let failure = run(&other_size, dir.path()).expect("a different size is caught");
    assert!(failure.contains("13 states"), "{failure}");

    let mut missing_line = synth;
    missing_line.expected.pop();
    assert!(run(&missing_line, dir.path()).is_some());
}

#[test]
fn times_are_normalised_and_nothing_else() {
    assert_eq!(
        normalise("plant:      9 states (0.1 ms)"),
        "plant:      9 states (… ms)"
    );
    assert_eq!(
        normalise("wrote sup.gen (12 ms total)"),
        "wrote sup.gen (… ms total)"
    );
    assert_eq!(
        normalise("(MACH1 1, MACH2 0) (3 msgs)"),
        "(MACH1 1, MACH2 0) (3 msgs)"
    );
}
