//! The names property, at build time: seeded random projects whose names
//! are drawn to break generated code (keywords, `Self`, suffix collisions
//! such as `fn` / `fn_`, `count` / `names` in any case, leading digits,
//! non-ASCII letters, bidirectional overrides, zero-width and control
//! characters, quotes, comment markers, line breaks), generated with every
//! backend. `generated.rs` compiles each under `#[deny(warnings)]` and
//! checks that every name comes through as written.
//!
//! Two sides of the property:
//! - a project whose names give distinct identifiers, none of them
//!   reserved, validates and generates on every backend (a failure fails
//!   the build with the project's `file:line` message);
//! - the same project with one name replaced by a reserved one (`count`,
//!   `Names`, …) or by the twin of another (`a-b` next to `a_b`) is refused
//!   at the line of that name.
//!
//! `E2E_NAMES_SEED` and `E2E_NAMES_CASES` (defaults 1 and 16) choose the
//! cases; a longer campaign sets them (the test prints nothing new, it only
//! compiles more).

use codegen::backend::Backend;
use codegen::build::Build;
use plc_project::ident::sanitize;
use std::fmt::Write as _;
use std::path::Path;

/// Pieces of names: Rust keywords and generated identifiers, names that
/// meet after sanitising or lower-casing, and text no identifier can hold.
const PIECES: &[&str] = &[
    "fn",
    "fn_",
    "Self",
    "self",
    "self_",
    "type",
    "TYPE_",
    "match",
    "crate",
    "super",
    "mod",
    "loop",
    "async",
    "await",
    "dyn",
    "static",
    "const",
    "impl",
    "true",
    "false",
    "Some",
    "None",
    "Ok",
    "Err",
    "u32",
    "bool",
    "str",
    "core",
    "std",
    "PROGRAM",
    "CONFIG",
    "IMAGE_CRC",
    "Memory",
    "states",
    "input",
    "output",
    "event",
    "timer",
    "supervisor",
    "sup_x",
    "count_",
    "names_",
    "x",
    "x_",
    "x__",
    "_x",
    "a1",
    "1",
    "2nd",
    "007",
    "ünïcode",
    "日本",
    "go\u{2066}",
    "\u{202e}",
    "zw\u{200b}",
    "a b",
    "a-b",
    "a.b",
    "a\"b",
    "a\\b",
    "a'b",
    "{x}",
    "*/",
    "/*",
    "//",
    "\t",
    "\n",
    "\r",
    "😀",
    "#[x]",
    "r#",
    "\u{0}",
    "\u{7f}",
    "é",
];

/// Names generated code reserves next to the names of each kind.
const RESERVED: &[&str] = &["count", "Count", "NAMES", "names"];

/// xorshift64*: a few lines, no dependency, the same names everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// One to three pieces.
    fn name(&mut self) -> String {
        (0..1 + self.below(3))
            .map(|_| PIECES[self.below(PIECES.len())])
            .collect()
    }
}

/// One random project: its names by kind, declaration order.
struct Case {
    project: String,
    inputs: Vec<String>,
    outputs: Vec<String>,
    timers: Vec<String>,
    /// Command (sets every output, starts the timer), sensor (rising input 0),
    /// and with a timer its expiry.
    events: Vec<String>,
    supervisors: Vec<String>,
    states: [String; 2],
}

impl Case {
    fn draw(rng: &mut Rng) -> Case {
        let mut taken = std::collections::HashSet::new();
        let mut fresh = |rng: &mut Rng| loop {
            let name = rng.name();
            if let Some(ident) = sanitize(&name) {
                if ident != "COUNT" && ident != "NAMES" && taken.insert(ident) {
                    return name;
                }
            }
        };
        let inputs = (0..1 + rng.below(3)).map(|_| fresh(rng)).collect();
        let outputs = (0..1 + rng.below(2)).map(|_| fresh(rng)).collect();
        let timers: Vec<String> = (0..rng.below(2)).map(|_| fresh(rng)).collect();
        let events = (0..2 + timers.len()).map(|_| fresh(rng)).collect();
        let supervisors = (0..1 + rng.below(3)).map(|_| fresh(rng)).collect();
        let first = rng.name();
        let second = loop {
            let s = rng.name();
            if s != first {
                break s;
            }
        };
        Case {
            project: rng.name(),
            inputs,
            outputs,
            timers,
            events,
            supervisors,
            states: [first, second],
        }
    }

    /// The model every supervisor runs: idle → busy on the command, back
    /// on the sensor (or the timer).
    fn model(&self) -> String {
        let [idle, busy] = &self.states;
        let (idle, busy) = (q(idle), q(busy));
        let (command, sensor) = (q(&self.events[0]), q(&self.events[1]));
        let uncontrollable: Vec<String> = self.events[1..].iter().map(|e| q(e)).collect();
        let mut m = format!(
            "name = \"machine\"\ninitial = {idle}\ncontrollable = [{command}]\n\
             uncontrollable = [{}]\ntransitions = [[{idle}, {command}, {busy}], [{busy}, {sensor}, {idle}]",
            uncontrollable.join(", "),
        );
        if let Some(expiry) = self.events.get(2) {
            let _ = write!(m, ", [{busy}, {}, {idle}]", q(expiry));
        }
        m.push_str("]\n");
        m
    }

    /// The project file; `line_of` is told the line of each name.
    fn project(&self) -> String {
        let mut p = format!("[plc]\nname = {}\n\n[inputs]\n", q(&self.project));
        for i in &self.inputs {
            let _ = writeln!(p, "{} = {{}}", q(i));
        }
        p.push_str("\n[outputs]\n");
        for o in &self.outputs {
            let _ = writeln!(p, "{} = {{}}", q(o));
        }
        p.push_str("\n[timers]\n");
        for t in &self.timers {
            let _ = writeln!(p, "{} = {{ preset_ms = 100 }}", q(t));
        }
        p.push_str("\n[events]\n");
        let start = match self.timers.first() {
            Some(t) => format!(", start = [{}]", q(t)),
            None => String::new(),
        };
        let outputs: Vec<String> = self.outputs.iter().map(|o| q(o)).collect();
        let _ = writeln!(
            p,
            "{} = {{ controllable = true, set = [{}]{start} }}",
            q(&self.events[0]),
            outputs.join(", ")
        );
        let _ = writeln!(
            p,
            "{} = {{ rising = {} }}",
            q(&self.events[1]),
            q(&self.inputs[0])
        );
        if let (Some(e), Some(t)) = (self.events.get(2), self.timers.first()) {
            let _ = writeln!(p, "{} = {{ expired = {} }}", q(e), q(t));
        }
        for s in &self.supervisors {
            let _ = write!(
                p,
                "\n[[supervisor]]\nname = {}\nfile = \"machine.toml\"\n",
                q(s)
            );
        }
        p
    }
}

/// A one-line TOML basic string (keys cannot be multi-line strings).
fn q(text: &str) -> String {
    des::formats::toml::basic_string(text)
}

/// Writes `text` to `path` unless it already holds it: a rewritten file
/// would look changed to cargo and rerun the build script every time.
fn write_if_changed(path: &Path, text: &str) {
    if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
        std::fs::write(path, text).unwrap();
    }
}

/// A Rust string literal for `text`.
fn lit(text: &str) -> String {
    format!("{text:?}")
}

fn list(names: &[String]) -> String {
    format!(
        "&[{}]",
        names.iter().map(|n| lit(n)).collect::<Vec<_>>().join(", ")
    )
}

/// Writes the cases, generates them with every backend, checks the
/// refusals, and writes `names_cases.rs` for `generated.rs`.
pub fn generate(out_dir: &Path) {
    println!("cargo:rerun-if-env-changed=E2E_NAMES_SEED");
    println!("cargo:rerun-if-env-changed=E2E_NAMES_CASES");
    let env = |key: &str, default: u64| {
        std::env::var(key)
            .ok()
            .map(|v| {
                v.parse()
                    .unwrap_or_else(|_| panic!("{key} must be a number"))
            })
            .unwrap_or(default)
    };
    let seed = env("E2E_NAMES_SEED", 1);
    let cases = env("E2E_NAMES_CASES", 16) as usize;
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut modules = String::from("generated!(\n");
    let mut checks = String::from(
        "/// The random name cases of `build_names.rs`, one per case and backend.\n\
         fn name_cases() -> Vec<NameCase> {\n    vec![\n",
    );
    for k in 0..cases {
        let case = Case::draw(&mut rng);
        let dir = out_dir.join(format!("names_{k}"));
        std::fs::create_dir_all(&dir).unwrap();
        write_if_changed(&dir.join("machine.toml"), &case.model());
        let project = case.project();
        let path = dir.join("names.plc.toml");
        write_if_changed(&path, &project);
        for backend in Backend::ALL {
            let module = format!("names_{k}_{}", backend.name());
            Build::new(&path)
                .backend(backend)
                .file_name(&module)
                .generate_or_exit();
            let _ = writeln!(modules, "    {module},");
            let states = sanitize(&case.supervisors[0]).unwrap();
            let _ = writeln!(
                checks,
                "        NameCase {{ case: {k}, backend: {:?}, program: &{module}::PROGRAM, \
                 names: [&{module}::input::NAMES, &{module}::output::NAMES, &{module}::timer::NAMES, \
                 &{module}::event::NAMES, &{module}::supervisor::NAMES, &{module}::states::{states}], \
                 expected: [{}, {}, {}, {}, {}, {}] }},",
                backend.name(),
                list(&case.inputs),
                list(&case.outputs),
                list(&case.timers),
                list(&case.events),
                list(&case.supervisors),
                list(&case.states),
            );
        }
        refusals(&case, &project, &dir, &mut rng);
    }
    modules.push_str(");\n");
    checks.push_str("    ]\n}\n");
    write_if_changed(&out_dir.join("names_cases.rs"), &(modules + &checks));
}

/// The other side of the property: `project` with one more input, named
/// with a reserved name or with the twin of a declared name (the same
/// identifier, other text: `a-b` for `a_b`), is refused at the line of
/// whichever of the two comes later (the second claim of the identifier).
fn refusals(case: &Case, project: &str, dir: &Path, rng: &mut Rng) {
    let declared: Vec<&String> = case
        .inputs
        .iter()
        .chain(&case.outputs)
        .chain(&case.timers)
        .chain(&case.events)
        .chain(&case.supervisors)
        .collect();
    let other = declared[rng.below(declared.len())];
    let twin: String = other
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    let lines: Vec<&str> = project.lines().collect();
    let sections = lines.iter().position(|l| *l == "[inputs]").unwrap();
    let line_of = |name: &str| {
        let quoted = q(name);
        sections
            + lines[sections..]
                .iter()
                .position(|l| l.starts_with(&quoted) || *l == format!("name = {quoted}"))
                .unwrap_or_else(|| panic!("`{name}` is not declared in\n{project}"))
    };
    let added = line_of(case.inputs.last().unwrap()) + 1;
    for (name, first) in [
        (RESERVED[rng.below(RESERVED.len())].to_owned(), None),
        (twin, Some(line_of(other))),
    ] {
        let mut mutated: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        mutated.insert(added, format!("{} = {{}}", q(&name)));
        // The twin's claim fails wherever it comes second.
        let expected = match first {
            Some(line) if line >= added => line + 1,
            _ => added,
        };
        let path = dir.join("refused.plc.toml");
        let text = mutated.join("\n") + "\n";
        let err = match plc_project::from_str(&text, &path) {
            Ok(_) => panic!("an input named `{name}` was accepted:\n{text}"),
            Err(e) => e.to_string(),
        };
        let at = format!("refused.plc.toml:{}:", expected + 1);
        assert!(
            err.contains(&at),
            "an input named `{name}`: expected an error at {at}, got {err}\n{text}"
        );
    }
}
