//! Export to industrial PLCs: a project as IEC 61131-3 Structured Text
//! ([`st`]) and PLCopen XML ([`plcopen`]).
//!
//! [`export`] builds two POUs: the controller function block
//! ([`scan::controller`], the whole scan of docs/semantics.md: debounce,
//! edges, timers on a millisecond clock input, the uncontrollable then
//! the controllable phase, actions, state maps, fault mode and reset,
//! supervisors as constant transition arrays, the guards of symbolic
//! supervisors as Boolean expressions, [`guards`]) and a program that calls
//! it once per task cycle with the inputs and outputs at `%I`/`%Q`
//! addresses ([`program`]). Names go through [`names`]. What the PLC
//! must provide (the task cycle, the image check) is in the README,
//! "Industrial PLCs".
//!
//! The scan written here in ST is the third of three on purpose (the
//! executor runs it, the conformance tests' reference interpreter
//! restates it): a change to docs/semantics.md moves all three
//! (docs/architecture.md, "Changing the scan").

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod guards;
pub mod ladder;
pub mod names;
pub mod plcopen;
pub mod pou;
pub mod program;
pub mod scan;
pub mod st;

use des::Result;
use names::Namer;
use plc_project::Project;
use pou::Pou;
pub use program::IoMap;

/// The identifiers of one export.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Names {
    /// The controller function block.
    pub controller: String,
    /// The program calling it.
    pub program: String,
    /// The configuration, its resource, its cyclic task and the program's
    /// instance in it (PLCopen XML's `instances`; ST with
    /// `--configuration`).
    pub configuration: [String; 4],
    /// Each input's variable (controller input, program variable).
    pub inputs: Vec<String>,
    /// Each output's variable.
    pub outputs: Vec<String>,
    /// Each input's index constant (`IN_…`).
    pub input_index: Vec<String>,
    /// Each output's index constant (`Q_…`), used by action-driven ones.
    pub output_index: Vec<String>,
    /// Each timer's index constant (`TM_…`).
    pub timers: Vec<String>,
    /// Each event's number constant (`EV_…`).
    pub events: Vec<String>,
    /// Each automaton supervisor's state variable (`S_…`).
    pub states: Vec<String>,
    /// Each automaton supervisor's transition array (`D_…`), when it is
    /// laid out dense.
    pub tables: Vec<String>,
    /// Each automaton supervisor's sparse table, when it is laid out
    /// sparse ([`scan::sparse_layout`]).
    pub sparse: Vec<Option<SparseNames>>,
    /// Each net's marking array (`M_…`).
    pub nets: Vec<String>,
}

/// The identifiers of a supervisor whose transitions are exported as a
/// sparse table: the transitions of state `s` are entries
/// `rows[s] .. rows[s + 1] - 1` of `columns` (local event) and `targets`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SparseNames {
    /// Row starts, one per state and a final one (`DR_…`).
    pub rows: String,
    /// The local event of each transition, then −1 (`DE_…`).
    pub columns: String,
    /// The target state of each transition, then −1 (`DT_…`).
    pub targets: String,
    /// The target the last lookup found, −1 for none (`NX_…`).
    pub next: String,
}

/// A project ready to print.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Export {
    /// The controller function block, then the program.
    pub pous: Vec<Pou>,
    /// The identifiers chosen.
    pub names: Names,
    /// Free-text names that changed on the way to identifiers: (name,
    /// identifier), in the order met.
    pub renamed: Vec<(String, String)>,
    /// The command that regenerates the file (for its header).
    pub regenerate: String,
    /// The project's name.
    pub project: String,
    /// The scan period: the interval of the PLC task running the program.
    pub scan_period_ms: u32,
}

impl Export {
    /// Bytes of the constant arrays (the supervisors' transition arrays
    /// and the debounce presets), at the element sizes declared.
    pub fn array_bytes(&self) -> usize {
        self.pous
            .iter()
            .flat_map(|p| p.vars(pou::Section::Constant))
            .filter(|v| matches!(v.ty, pou::Type::Array { .. }))
            .map(|v| v.ty.bytes())
            .sum()
    }
}

/// Instance and clock names of the program, reserved in the controller's
/// namespace so that no signal can take them.
const PROGRAM_IDS: [&str; 2] = ["ctrl", "clock_ms"];

/// `project` as a controller function block and a program wiring it to
/// the addresses of `io`; `regenerate` is the command named in the
/// header.
pub fn export(project: &Project, io: &IoMap, regenerate: &str) -> Result<Export> {
    let mut pous = Namer::new();
    let controller = pous.name("", &format!("{}_ctrl", project.name));
    let program = pous.name("", &format!("{}_main", project.name));
    let configuration = [
        pous.name("", &format!("{}_config", project.name)),
        pous.name("", &format!("{}_resource", project.name)),
        pous.name("", "scan_task"),
        pous.name("", "main"),
    ];
    // The LD rendering's POU (`plcopen --ladder`) joins the same project:
    // no POU or variable may take its name.
    let ladder = pous.name("", &ladder::pou_name(project));
    let mut namer = Namer::new();
    namer.reserve(&controller);
    namer.reserve(&program);
    namer.reserve(&ladder);
    let mut names = scan::names(project, &mut namer, &PROGRAM_IDS);
    names.controller = controller;
    names.program = program;
    names.configuration = configuration;
    let addresses = io.addresses(project)?;
    let fb = scan::controller(project, &names);
    let main = program::program(project, &names, &addresses, &PROGRAM_IDS);
    Ok(Export {
        pous: vec![fb, main],
        names,
        renamed: namer.changed,
        regenerate: regenerate.to_owned(),
        project: project.name.clone(),
        scan_period_ms: project.scan_period_ms,
    })
}

/// Free text made safe inside an ST comment and an XML CDATA section:
/// no comment delimiters, no `]]>`, line breaks and control characters as
/// spaces, no U+FFFE or U+FFFF (characters XML 1.0 does not allow
/// anywhere), bidirectional overrides and isolates (which could make a
/// reader see other code than the PLC compiles) written as `<U+202E>`.
pub fn comment_text(text: &str) -> String {
    let mut flat = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() || c == '\u{FFFE}' || c == '\u{FFFF}' {
            flat.push(' ');
        } else if matches!(c, '\u{061c}' | '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
        {
            flat.push_str(&format!("<U+{:04X}>", c as u32));
        } else {
            flat.push(c);
        }
    }
    flat.replace("(*", "( *")
        .replace("*)", "* )")
        .replace("]]>", "] ]>")
}
