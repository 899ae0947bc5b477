//! Rust source for a project: named constants, the executor's
//! configuration as statics, and the supervisors as bit-packed tables,
//! CMSSM logic functions or plain `match` statements.
//!
//! One module per part of the file: `config` writes the name modules and
//! the configuration statics (each pool entry decoded in doc comments), and
//! one module per backend writes the supervisors: `table`, [`logic`] and
//! `matches`.
//!
//! The text is parsed with `syn` and laid out with `prettyplease`, so it is
//! always syntactically valid and formatted the same way on every machine.
//! Explanations are doc comments (they survive formatting). Every name from
//! a model appears either sanitised into an identifier or as a string
//! literal escaped by `{:?}`, so no name can inject code.

mod config;
pub mod logic;
mod matches;
mod table;

use crate::backend::table::{EncodedTable, Layout};
use crate::backend::Backend;
use crate::error::{Error, Result};
use crate::lower::{ConfigPools, ImageCheck, Lowered, ScanSets, Supervisors};
use executor::program as ex;
use plc_project::ident::sanitize;
use plc_project::{Project, SupervisorSource};
use std::fmt::Write;

/// Size figures of one supervisor in the generated program.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct SupervisorStats {
    /// Supervisor name.
    pub name: String,
    /// States; for a group of a Petri net, the net's reachable markings.
    pub states: u32,
    /// Local events.
    pub events: u16,
    /// Table layout (table backend).
    pub layout: Option<Layout>,
    /// Table bytes (table backend).
    pub table_bytes: usize,
    /// Bytes of a naive `u16`-per-entry dense table; 0 for a net group
    /// (its counters have no state × event table to compare with).
    pub naive_bytes: usize,
    /// Cubes of the minimised functions (logic backend).
    pub cubes: usize,
    /// Literals of the minimised functions (logic backend).
    pub literals: usize,
    /// The minimisation effort and the supervisor's limit of it (logic
    /// backend; see `backend::logic`, "Effort bound").
    pub logic_effort: Option<(u64, u64)>,
}

/// The generated source and its figures.
#[derive(Debug, Clone)]
pub struct Generated {
    /// Formatted Rust source.
    pub code: String,
    /// Per-supervisor sizes.
    pub stats: Vec<SupervisorStats>,
    /// The image CRC recorded in the code.
    pub crc: u32,
    /// The image's size and the background test's figures.
    pub image: ImageCheck,
    /// The sizes of the enabled-event sets.
    pub sets: ScanSets,
}

/// A sanitised identifier (validation guarantees one exists).
fn ident(name: &str) -> String {
    sanitize(name).unwrap_or_else(|| "UNNAMED".to_owned())
}

/// Text on one line: control characters (line breaks among them) become
/// spaces, so it cannot end a comment.
fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            // Bidirectional overrides and isolates would make the comment
            // read differently from what it says (rustc denies them in
            // comments): written as escapes, visibly.
            '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' => {
                out.push_str(&c.escape_unicode().to_string());
            }
            c if c.is_control() || c == '\u{2028}' || c == '\u{2029}' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Text safe on one line of a doc comment and inside its Markdown code
/// spans: [`one_line`], and backticks become quotes.
fn doc_text(text: &str) -> String {
    one_line(text).replace('`', "'")
}

/// A name as a code span of a doc comment: `` `name` ``.
fn quoted(name: &str) -> String {
    format!("`{}`", doc_text(name))
}

/// `a`, `a or b`, `a, b or c` (`word` = "or" / "and").
fn listed(items: &[String], word: &str) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} {word} {last}", init.join(", ")),
    }
}

/// Pool positions as a doc comment reads them: `3` or `3–5` (`none` for an
/// empty span).
fn positions(s: ex::Span) -> String {
    match s.len {
        0 => "none".to_owned(),
        1 => s.start.to_string(),
        n => format!("{}–{}", s.start, u32::from(s.start) + u32::from(n) - 1),
    }
}

/// The text being assembled, with what names things. The parts of the
/// file are written by `impl Emitter` blocks in the submodules.
struct Emitter<'a> {
    project: &'a Project,
    pools: &'a ConfigPools,
    out: String,
}

impl<'a> Emitter<'a> {
    /// The executor's supervisors, named.
    fn supervisors(&self) -> Supervisors<'a> {
        Supervisors::new(self.project, &self.pools.nets)
    }

    /// Path of an input's index constant.
    fn input(&self, i: ex::Index) -> String {
        format!("input::{}", ident(&self.project.inputs[i as usize].name))
    }

    /// Path of an output's index constant.
    fn output(&self, o: ex::Index) -> String {
        format!("output::{}", ident(&self.project.outputs[o as usize].name))
    }

    /// Path of a timer's index constant.
    fn timer(&self, t: ex::Index) -> String {
        format!("timer::{}", ident(&self.project.timers[t as usize].name))
    }

    /// Path of a supervisor's index constant.
    fn supervisor(&self, s: ex::Index) -> String {
        format!(
            "supervisor::{}",
            ident(&self.supervisors().name(usize::from(s)))
        )
    }

    /// A span as a Rust expression (empty spans always as `Span::EMPTY`).
    fn span(&self, s: ex::Span) -> String {
        if s.is_empty() {
            "Span::EMPTY".to_owned()
        } else {
            format!("Span::new({}, {})", s.start, s.len)
        }
    }

    /// "Local events: 0 `a`, 1 `b`": what the local event indices of
    /// supervisor `j` (in its table, `match` or functions) stand for.
    fn local_events_line(&self, j: usize) -> String {
        let events: Vec<String> = self.project.supervisors[j]
            .local_events
            .iter()
            .enumerate()
            .map(|(i, &(g, _))| format!("{i} {}", quoted(&self.project.events[g].name)))
            .collect();
        format!("Local events: {}.", events.join(", "))
    }

    /// Where supervisor `j` came from, for its doc comment.
    fn source_line(&self, j: usize) -> String {
        match &self.project.supervisors[j].source {
            SupervisorSource::File(path) => {
                format!("from {}", quoted(&path.display().to_string()))
            }
            SupervisorSource::Synthesized {
                plants,
                specs,
                minimized,
                reduced,
                local,
            } => format!(
                "synthesised from {} plant and {} specification files{}{}{}",
                plants.len(),
                specs.len(),
                if *reduced { ", reduced" } else { "" },
                local.as_ref().map_or(String::new(), |e| format!(
                    ", localized: the local controller of {}",
                    quoted(e)
                )),
                if *minimized { ", minimised" } else { "" }
            ),
            SupervisorSource::Plant { reduced, file } => format!(
                "a plant component run beside reduced supervisor {}, from {}",
                quoted(reduced),
                quoted(&file.display().to_string())
            ),
            SupervisorSource::Component { guarded, file } => format!(
                "a component of symbolic supervisor {}, from {}",
                quoted(guarded),
                quoted(&file.display().to_string())
            ),
        }
    }
}

impl SupervisorStats {
    /// The figures of a supervisor encoded as `table`.
    pub fn of_table(name: &str, table: &EncodedTable) -> SupervisorStats {
        SupervisorStats {
            name: name.to_owned(),
            states: table.states,
            events: table.events,
            layout: Some(table.layout),
            table_bytes: table.bytes(),
            naive_bytes: table.naive_bytes(),
            cubes: 0,
            literals: 0,
            logic_effort: None,
        }
    }
}

/// Puts a blank line between consecutive items (prettyplease leaves none):
/// before a doc comment, an attribute or a function that follows the end
/// of an item (a line of code ending in `;` or `}`, not a comment) at the
/// same indentation.
fn separate_items(code: &str) -> String {
    let mut out = String::with_capacity(code.len() + code.len() / 16);
    let mut prev: Option<&str> = None;
    for line in code.lines() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        if let Some(p) = prev {
            let p_trimmed = p.trim_start();
            let starts_item = trimmed.starts_with("///")
                || trimmed.starts_with("#[")
                || trimmed.starts_with("fn ")
                || trimmed.starts_with("pub fn ");
            let ends_item = !p_trimmed.starts_with("//")
                && (p_trimmed.ends_with(';') || p_trimmed.ends_with('}'));
            if starts_item && ends_item && p.len() - p_trimmed.len() == indent {
                out.push('\n');
            }
        }
        out.push_str(line);
        out.push('\n');
        prev = Some(line);
    }
    out
}

/// The program text before layout, and its figures.
struct Unformatted {
    text: String,
    stats: Vec<SupervisorStats>,
    crc: u32,
    image: ImageCheck,
}

/// The doc comment of `IMAGE_CRC`: what the image is, and how fast the
/// background test covers it.
fn image_crc_doc(check: &ImageCheck, covers: &str) -> String {
    let text = format!(
        "CRC-32/MPEG-2 of the program image ({covers}, {} bytes), recorded at \
         generation. The controller checks the whole image at start-up, then in the \
         background, {} bytes per scan: a pass every {} scans, a flipped bit found \
         within {} scans ({} at {} ms a scan). See `executor::image`.",
        check.image_bytes,
        check.bytes_per_scan,
        check.pass_scans(),
        check.bound_scans(),
        duration(check.bound_ms()),
        check.scan_period_ms,
    );
    let mut doc = String::new();
    let mut line = String::from("///");
    for word in text.split(' ') {
        if line.len() + 1 + word.len() > 78 {
            doc.push_str(&line);
            doc.push('\n');
            line = String::from("///");
        }
        line.push(' ');
        line.push_str(word);
    }
    doc.push_str(&line);
    doc
}

/// `ms` as a reader reads it: milliseconds below 10 s, else seconds with
/// one decimal.
fn duration(ms: u64) -> String {
    if ms < 10_000 {
        format!("{ms} ms")
    } else {
        format!("{}.{} s", ms / 1000, ms % 1000 / 100)
    }
}

/// Writes the program of `project` lowered as `lowered`: the
/// configuration, the board and the supervisors in the backend's
/// representation, not yet laid out.
fn write_program(project: &Project, lowered: &Lowered) -> Unformatted {
    let pools = lowered.pools();
    let mut e = Emitter {
        project,
        pools,
        out: String::new(),
    };
    let uses = match lowered {
        Lowered::Table(_) => {
            "use executor::compiled::{Compiled, ProgramData};\nuse executor::table::{Rows, SupervisorTable};"
        }
        Lowered::Logic(_) | Lowered::Match(_) => "use executor::compiled::{Compiled, ProgramData};",
    };
    let _ = writeln!(
        e.out,
        "#[allow(unused_imports)]\nuse executor::program::{{indices, mask_word, mask_word_except, Action, AllowedSets, Config, EventSpec, GuardNode, GuardSpec, Guards, Index, InputSpec, Membership, OutputSpec, Span, StateBit, StateMapEntry, SupervisorSpec, TimerSpec, Trigger, UnexpectedPolicy}};\n#[allow(unused_imports)]\n{uses}"
    );
    e.names();
    e.config();
    e.out.push_str(&crate::board::board_module(project));
    let image = lowered.image_check();
    let stats = match lowered {
        Lowered::Table(tables) => {
            let doc = image_crc_doc(&image, "the configuration and the tables");
            e.tables(tables, &doc)
        }
        Lowered::Logic(logic) => {
            let doc = image_crc_doc(&image, "the configuration; the supervisors are code");
            e.logic(&logic.supervisors, logic.crc, &doc)
        }
        Lowered::Match(code) => {
            let doc = image_crc_doc(&image, "the configuration; the supervisors are code");
            e.matches(code.crc, &doc)
        }
    };
    Unformatted {
        text: e.out,
        stats,
        crc: executor::program::Program::recorded_crc(lowered),
        image,
    }
}

/// Parses `text` as a Rust file and lays it out: prettyplease, then a
/// blank line between items. Comments other than doc comments are lost
/// on the way, which is why the emitters write none.
fn format_rust(text: &str) -> Result<String> {
    let file = syn::parse_file(text).map_err(|source| Error::Unparsable { source })?;
    Ok(separate_items(&prettyplease::unparse(&file)))
}

/// Generates the Rust source of `project`. `regenerate` is the command
/// line the header tells users to run.
pub fn generate(project: &Project, backend: Backend, regenerate: &str) -> Result<Generated> {
    generate_with_progress(project, backend, regenerate, &())
}

/// [`generate`], telling `progress` what the logic backend is minimising.
pub fn generate_with_progress(
    project: &Project,
    backend: Backend,
    regenerate: &str,
    progress: &dyn des::ops::Progress,
) -> Result<Generated> {
    let lowered = Lowered::new(project, backend, progress)?;
    let program = write_program(project, &lowered);
    let body = format_rust(&program.text)?;
    let backend_name = backend.name();
    let header = format!(
        "// Generated by codegen {} from `{}` ({backend_name} backend). Do not edit.\n// Regenerate: {}\n// Include it in a module: `include!(concat!(env!(\"OUT_DIR\"), \"/<name>.rs\"));`\n\n",
        env!("CARGO_PKG_VERSION"),
        doc_text(&project.path.display().to_string()),
        doc_text(regenerate),
    );
    Ok(Generated {
        code: header + &body,
        stats: program.stats,
        crc: program.crc,
        image: program.image,
        sets: lowered.scan_sets(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;
    use std::path::Path;

    /// The seed projects of `models/`.
    const SEEDS: [&str; 5] = ["motivating", "press", "press7", "conveyor", "crane"];

    fn seed(name: &str) -> Project {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../models")
            .join(format!("{name}.plc.toml"));
        plc_project::load(&path).unwrap()
    }

    /// Layout keeps doc comments and drops every other comment, so the
    /// emitters write only doc comments: every explanation they write is
    /// in the file a user opens.
    #[test]
    fn every_comment_written_is_a_doc_comment_and_survives_layout() {
        let backends: &[Backend] = if crate::backend::logic::AVAILABLE {
            &Backend::ALL
        } else {
            &[Backend::Table, Backend::Match]
        };
        for name in SEEDS {
            let project = seed(name);
            for &backend in backends {
                let lowered = Lowered::new(&project, backend, &()).unwrap();
                let written = write_program(&project, &lowered).text;
                let laid_out = format_rust(&written).unwrap();
                let kept: HashSet<&str> = laid_out.lines().map(str::trim).collect();
                for line in written.lines().map(str::trim) {
                    if line.starts_with("///") {
                        assert!(kept.contains(line), "{name} {backend:?}: `{line}` lost");
                    } else {
                        assert!(
                            !line.contains("//"),
                            "{name} {backend:?}: plain comment in `{line}`"
                        );
                    }
                }
            }
        }
    }

    /// Code that does not parse is the emitters' fault, said as such.
    #[test]
    fn unparsable_code_is_an_internal_error() {
        let err = format_rust("pub fn (").unwrap_err();
        assert!(matches!(err, Error::Unparsable { .. }), "{err:?}");
        let message = err.to_string();
        assert!(
            message.starts_with("internal error: generated code does not parse (")
                && message.ends_with("); please report it with the project file"),
            "{message}"
        );
    }

    #[test]
    fn doc_text_stays_on_its_line_and_out_of_code_spans() {
        assert_eq!(doc_text("a\nb\r\u{2028}c`d"), "a b  c'd");
        assert_eq!(doc_text("x\u{202e}y\u{2066}"), "x\\u{202e}y\\u{2066}");
        assert_eq!(quoted("x`\n"), "`x' `");
        assert_eq!(one_line("`a`\tb"), "`a` b");
    }

    #[test]
    fn lists_and_positions_read_as_prose() {
        let items = |v: &[&str]| v.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>();
        assert_eq!(listed(&items(&[]), "or"), "");
        assert_eq!(listed(&items(&["a"]), "or"), "a");
        assert_eq!(listed(&items(&["a", "b"]), "and"), "a and b");
        assert_eq!(listed(&items(&["a", "b", "c"]), "or"), "a, b or c");
        assert_eq!(positions(ex::Span::EMPTY), "none");
        assert_eq!(positions(ex::Span::new(3, 1)), "3");
        assert_eq!(positions(ex::Span::new(3, 3)), "3–5");
    }

    #[test]
    fn a_doc_line_ending_like_code_is_not_followed_by_a_blank_line() {
        let code = "/// a;\n/// b}\nconst A: u8 = 0;\n/// c\nconst B: u8 = 1;\n";
        assert_eq!(
            separate_items(code),
            "/// a;\n/// b}\nconst A: u8 = 0;\n\n/// c\nconst B: u8 = 1;\n"
        );
    }
}
