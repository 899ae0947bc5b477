//! From the raw project file and its loaded supervisors to a validated
//! [`Project`].
//!
//! Validation runs once [`super::sources`] has read (or synthesised) every
//! supervisor, and stops at the first error. Every error names the project
//! file and the line and column of the offending entry (a model file's own
//! syntax and model errors propagate unchanged: they point into that file).
//! Warnings do not stop validation; they are collected in
//! [`Project::warnings`].
//!
//! The rules live next to the code that enforces them:
//!
//! - [`names`]: names and generated identifiers (one namespace);
//! - [`numbers`]: the ranges of numeric fields; [`plc`]: the `[plc]` table;
//! - [`outputs`], [`switches`], [`state_maps`]: how outputs are driven;
//! - [`events`]: sources and conditions, events no supervisor knows;
//!   [`actions`]: what an event does, and in which order;
//! - [`supervisors`]: supervisors against the declared events; [`nets`]:
//!   Petri nets against them, and their counters; [`guarded`]: symbolic
//!   supervisors, their components and guards;
//! - [`nonconflict`]: `check_nonconflicting`, the supervisors proven not
//!   to block each other;
//! - [`board`]: the `[board]` pin map.
//!
//! # Order of passes
//!
//! Supervisor sources are loaded before any of this, so a missing model
//! file is reported before an error in the declarations. Sections are
//! then checked in the order their names are needed, each in file
//! order: inputs, `[plc]` (its `reset` input), outputs, timers, switches
//! (their outputs), events (inputs, timers, outputs, switches), supervisors
//! (events). Then what needs the supervisors: events in no supervisor's
//! alphabet, their nonconflict when asked, output drives (state maps name supervisor states), timers no
//! action starts; `[board]` last. The first error in this order is the
//! one reported, and warnings come in this order too.

use super::locate::ProjectFile;
use super::model::*;
use super::parse::{Entries, Name, RawInput, RawProject, RawTimer};
use super::sources::Sources;
use des::error::{Error, Result};
use std::collections::HashMap;
use std::ops::Range;

pub mod actions;
pub mod board;
pub mod events;
pub mod guarded;
pub mod names;
pub mod nets;
pub mod nonconflict;
pub mod numbers;
pub mod outputs;
pub mod plc;
pub mod state_maps;
pub mod supervisors;
pub mod switches;

pub use board::{DEFAULT_CHIP, MAX_BOARD_SCAN_PERIOD_MS};

/// Validates `raw`, the parsed text of `file`, whose supervisors `sources`
/// has loaded.
pub(crate) fn validate(raw: RawProject, sources: Sources, file: &ProjectFile) -> Result<Project> {
    let mut v = Validator {
        file,
        warnings: Vec::new(),
        namespace: HashMap::new(),
        groups: Vec::new(),
        claimed: HashMap::new(),
    };
    v.project(raw, sources)
}

/// The declarations of one section in file order, found by name.
struct Declared<T> {
    /// What one declaration is (`input`), for errors.
    kind: &'static str,
    /// Where they are declared (`inputs` for `[inputs]`), for errors.
    section: &'static str,
    items: Vec<T>,
    index: HashMap<String, usize>,
    /// The span of each name.
    spans: Vec<Range<usize>>,
}

impl<T> Declared<T> {
    fn new(kind: &'static str, section: &'static str) -> Self {
        Declared {
            kind,
            section,
            items: Vec::new(),
            index: HashMap::new(),
            spans: Vec::new(),
        }
    }

    /// Adds the next declaration (its name is already claimed).
    fn push(&mut self, name: &str, span: Range<usize>, item: T) {
        self.index.insert(name.to_owned(), self.items.len());
        self.spans.push(span);
        self.items.push(item);
    }
}

struct Validator<'a> {
    file: &'a ProjectFile<'a>,
    warnings: Vec<Warning>,
    /// Every identifier claimed so far (see [`names`]).
    namespace: HashMap<String, names::Claim>,
    /// The group names each net claimed so far reserves (see [`names`]).
    groups: Vec<names::Claim>,
    /// Names claimed so far, by kind.
    claimed: HashMap<&'static str, usize>,
}

impl Validator<'_> {
    fn line(&self, span: &Range<usize>) -> u32 {
        self.file.line(span)
    }

    fn error(&self, span: &Range<usize>, message: impl Into<String>) -> Error {
        self.file.error(span, message)
    }

    fn warn(&mut self, span: &Range<usize>, message: impl Into<String>) {
        let line = self.line(span);
        self.warnings.push(Warning {
            line,
            message: message.into(),
        });
    }

    /// The index of the declaration `name` refers to.
    fn resolve<T>(&self, declared: &Declared<T>, name: &Name) -> Result<usize> {
        declared.index.get(name.get_ref()).copied().ok_or_else(|| {
            self.error(
                &name.span(),
                format!(
                    "unknown {} `{}`: not declared in [{}]",
                    declared.kind,
                    name.get_ref(),
                    declared.section
                ),
            )
        })
    }

    /// The passes, in the order of the module docs.
    fn project(&mut self, raw: RawProject, sources: Sources) -> Result<Project> {
        let inputs = self.inputs(&raw.inputs)?;
        let plc = self.plc(raw.plc.get_ref(), &inputs)?;
        let mut output_uses = self.declare_outputs(&raw.outputs)?;
        let timers = self.timers(&raw.timers)?;
        let switches = self.switches(&raw.switches, &mut output_uses)?;
        let env = events::Env {
            inputs: &inputs,
            timers: &timers,
            switches: &switches,
        };
        let events = self.events(&raw.events, &env, &mut output_uses)?;
        let (supervisors, guarded) =
            self.supervisors(&raw.supervisor, sources.supervisors, &events)?;
        let nets = self.nets(&raw.net, sources.nets, &events)?;
        self.events_no_supervisor_knows(&events, &supervisors.items, &nets.items)?;
        self.nonconflicting(
            raw.plc.get_ref().check_nonconflicting.as_ref(),
            &supervisors.items,
            &nets.items,
            &guarded,
        )?;
        let outputs = self.outputs(&raw.outputs, &output_uses.items, &supervisors, &nets)?;
        self.timers_nothing_starts(&timers, &events.items);
        let board = self.board(
            raw.board.as_ref(),
            raw.plc.get_ref().scan_period_ms.as_ref(),
            &inputs.items,
            &outputs,
        )?;

        Ok(Project {
            path: self.file.path().to_path_buf(),
            name: raw.plc.into_inner().name.into_inner(),
            scan_period_ms: plc.scan_period_ms,
            max_commands_per_scan: plc.max_commands_per_scan,
            unexpected: plc.unexpected,
            reset: plc.reset,
            overrun_limit: plc.overrun_limit,
            overrun_fault: plc.overrun_fault,
            lost_edge_fault: plc.lost_edge_fault,
            rom_test_bytes_per_scan: plc.rom_test_bytes_per_scan,
            stored_sets_bytes: plc.stored_sets_bytes,
            inputs: inputs.items,
            outputs,
            timers: timers.items,
            switches: switches.items,
            events: events.items,
            supervisors: supervisors.items,
            nets: nets.items,
            guarded,
            board,
            warnings: std::mem::take(&mut self.warnings),
            files: sources.files,
        })
    }

    fn inputs(&mut self, raw: &Entries<RawInput>) -> Result<Declared<Input>> {
        let mut inputs = Declared::new("input", "inputs");
        for (name, decl) in &raw.0 {
            self.claim("input", name.get_ref(), &name.span())?;
            let debounce = self.number_or(
                decl.get_ref().debounce_scans.as_ref(),
                &numbers::DEBOUNCE_SCANS,
                0,
            )?;
            let input = Input {
                name: name.get_ref().clone(),
                debounce_scans: debounce as u8,
                line: self.line(&name.span()),
            };
            inputs.push(name.get_ref(), name.span(), input);
        }
        Ok(inputs)
    }

    fn timers(&mut self, raw: &Entries<RawTimer>) -> Result<Declared<Timer>> {
        let mut timers = Declared::new("timer", "timers");
        for (name, decl) in &raw.0 {
            self.claim("timer", name.get_ref(), &name.span())?;
            let preset = self.number(&decl.get_ref().preset_ms, &numbers::PRESET_MS)?;
            let timer = Timer {
                name: name.get_ref().clone(),
                preset_ms: preset as u32,
                line: self.line(&name.span()),
            };
            timers.push(name.get_ref(), name.span(), timer);
        }
        Ok(timers)
    }
}

/// What the unit tests of every pass load projects with.
#[cfg(test)]
mod testing {
    use super::super::{from_str, Project};
    use std::path::Path;

    /// The `[plc]` table every test project starts with.
    pub(super) const HEAD: &str = "[plc]\nname = \"local\"\n";

    /// Validates `text` as `dir/p.plc.toml`.
    pub(super) fn load(text: &str) -> des::Result<Project> {
        from_str(text, Path::new("dir/p.plc.toml"))
    }
}

#[cfg(test)]
mod tests {
    //! Rules that need no model file; the rest are in `tests/project.rs`.

    use super::super::{Action, Trigger};
    use super::testing::{load, HEAD};
    use std::fmt::Write;
    use std::path::Path;

    #[test]
    fn a_project_without_supervisors_is_local_logic() {
        let p = load(&format!(
            "{HEAD}[inputs]\nls = {{}}\n[outputs]\nlamp = {{}}\n[events]\non = {{ rising = \"ls\", set = \"lamp\" }}\noff = {{ falling = \"ls\", clear = \"lamp\" }}\n"
        ))
        .unwrap();
        assert!(p.supervisors.is_empty());
        assert_eq!(p.events[0].trigger, Trigger::Rising(vec![0]));
        assert_eq!(p.events[0].actions, [Action::Set(0)]);
        assert_eq!(p.events[1].actions, [Action::Clear(0)]);
        assert_eq!(p.files, [Path::new("dir/p.plc.toml")]);
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    }

    /// Validation is linear in the number of declarations: 20,000 inputs,
    /// 20,000 events and 20,000 outputs (every one located, and every
    /// output and event warned about) validate in a fraction of a second in
    /// a debug build. Locating each span by scanning the text from its
    /// start, as validation once did, made this test take minutes.
    #[test]
    fn a_project_with_twenty_thousand_of_each_declaration_is_validated_in_one_pass() {
        const N: usize = 20_000;
        let mut text = format!("{HEAD}[inputs]\n");
        for i in 0..N {
            writeln!(text, "in{i} = {{}}").unwrap();
        }
        text.push_str("[outputs]\n");
        for i in 0..N {
            writeln!(text, "out{i} = {{}}").unwrap();
        }
        text.push_str("[events]\n");
        for i in 0..N {
            writeln!(text, "ev{i} = {{ rising = \"in{i}\" }}").unwrap();
        }
        let p = load(&text).unwrap();

        let first_input = 4;
        let first_output = first_input + N as u32 + 1;
        let first_event = first_output + N as u32 + 1;
        assert_eq!(p.inputs.len(), N);
        assert_eq!(p.inputs[N - 1].line, first_input + N as u32 - 1);
        assert_eq!(p.outputs[N - 1].line, first_output + N as u32 - 1);
        assert_eq!(p.events[N - 1].line, first_event + N as u32 - 1);
        assert_eq!(p.events[N - 1].trigger, Trigger::Rising(vec![N - 1]));
        // Each event moves nothing and does nothing; then each output is
        // driven by nothing.
        assert_eq!(p.warnings.len(), 2 * N);
        assert_eq!(p.warnings[N - 1].line, first_event + N as u32 - 1);
        assert!(p.warnings[N - 1].message.contains("`ev19999`"));
        assert_eq!(p.warnings[2 * N - 1].line, first_output + N as u32 - 1);
        assert!(p.warnings[2 * N - 1].message.contains("`out19999`"));
    }
}
