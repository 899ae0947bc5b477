//! Rust source for a project: named constants, the executor's
//! configuration as statics, and the supervisors as bit-packed tables or
//! CMSSM logic functions.
//!
//! The text is parsed with `syn` and laid out with `prettyplease`, so it is
//! always syntactically valid and formatted the same way on every machine.
//! Explanations are doc comments (they survive formatting). Every name from
//! a model appears either sanitised into an identifier or as a string
//! literal escaped by `{:?}`, so no name can inject code.

use crate::backend::logic::LogicSupervisor;
use crate::backend::table::{EncodedTable, Layout};
use crate::error::{Error, Result};
use crate::image::{ConfigPools, LogicImage, TableImage};
use crate::project::ident::{sanitize, snake_ident};
use crate::project::{Project, SupervisorSource};
use executor::program as ex;
use std::fmt::Write;

/// How supervisors are represented in the generated program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// Bit-packed transition tables (the default).
    #[default]
    Table,
    /// CMSSM next-state and output functions (Espresso-minimised).
    Logic,
    /// Baseline for measurements: one plain `match` on (state, event) per
    /// supervisor, what a hand-written state machine does.
    Match,
}

impl Backend {
    /// Every backend.
    pub const ALL: [Backend; 3] = [Backend::Table, Backend::Logic, Backend::Match];

    /// The name used on command lines and in file headers.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Table => "table",
            Backend::Logic => "logic",
            Backend::Match => "match",
        }
    }
}

impl std::str::FromStr for Backend {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Backend, String> {
        Backend::ALL
            .into_iter()
            .find(|b| b.name() == s)
            .ok_or_else(|| format!("unknown backend `{s}` (expected table, logic or match)"))
    }
}

/// Size figures of one supervisor in the generated program.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct SupervisorStats {
    /// Supervisor name.
    pub name: String,
    /// States.
    pub states: u32,
    /// Local events.
    pub events: u16,
    /// Table layout (table backend).
    pub layout: Option<Layout>,
    /// Table bytes (table backend).
    pub table_bytes: usize,
    /// Bytes of a naive `u16`-per-entry dense table.
    pub naive_bytes: usize,
    /// Cubes of the minimised functions (logic backend).
    pub cubes: usize,
    /// Literals of the minimised functions (logic backend).
    pub literals: usize,
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
}

/// A sanitised identifier (validation guarantees one exists).
fn ident(name: &str) -> String {
    sanitize(name).unwrap_or_else(|| "UNNAMED".to_owned())
}

fn words(list: &[u32]) -> String {
    list.iter()
        .map(|w| format!("{w:#010x}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// One line of text safe inside a doc comment.
fn doc_line(text: &str) -> String {
    text.replace(['\n', '\r'], " ")
}

struct Emitter<'a> {
    project: &'a Project,
    pools: &'a ConfigPools,
    out: String,
}

impl Emitter<'_> {
    fn input(&self, i: ex::Index) -> String {
        format!("input::{}", ident(&self.project.inputs[i as usize].name))
    }

    fn output(&self, o: ex::Index) -> String {
        format!("output::{}", ident(&self.project.outputs[o as usize].name))
    }

    fn timer(&self, t: ex::Index) -> String {
        format!("timer::{}", ident(&self.project.timers[t as usize].name))
    }

    fn supervisor(&self, s: ex::Index) -> String {
        format!(
            "supervisor::{}",
            ident(&self.project.supervisors[s as usize].name)
        )
    }

    fn span(&self, s: ex::Span) -> String {
        if s.is_empty() {
            "Span::EMPTY".to_owned()
        } else {
            format!("Span::new({}, {})", s.start, s.len)
        }
    }

    fn names(&mut self, module: &str, doc: &str, names: &[&str]) {
        // Names are for reference: a crate uses some of them, never all.
        let _ = writeln!(
            self.out,
            "/// {doc}\n#[allow(dead_code)]\npub mod {module} {{"
        );
        if !names.is_empty() {
            let _ = writeln!(self.out, "    use super::Index;");
        }
        for (i, n) in names.iter().enumerate() {
            let _ = writeln!(self.out, "    /// `{}`", doc_line(n).replace('`', "'"));
            let _ = writeln!(self.out, "    pub const {}: Index = {i};", ident(n));
        }
        let _ = writeln!(
            self.out,
            "    /// How many there are.\n    pub const COUNT: usize = {};\n    /// Names in declaration order.\n    pub static NAMES: [&str; {}] = [{}];\n}}",
            names.len(),
            names.len(),
            names.iter().map(|n| format!("{n:?}")).collect::<Vec<_>>().join(", ")
        );
    }

    fn constants(&mut self) {
        let p = self.project;
        let inputs: Vec<&str> = p.inputs.iter().map(|x| x.name.as_str()).collect();
        let outputs: Vec<&str> = p.outputs.iter().map(|x| x.name.as_str()).collect();
        let timers: Vec<&str> = p.timers.iter().map(|x| x.name.as_str()).collect();
        let events: Vec<&str> = p.events.iter().map(|x| x.name.as_str()).collect();
        let sups: Vec<&str> = p.supervisors.iter().map(|x| x.name.as_str()).collect();
        self.names("input", "Inputs, in declaration order.", &inputs);
        self.names("output", "Outputs, in declaration order.", &outputs);
        self.names("timer", "Timers, in declaration order.", &timers);
        self.names("event", "Events, in declaration (priority) order.", &events);
        self.names("supervisor", "Supervisors, in declaration order.", &sups);
        let _ = writeln!(
            self.out,
            "/// State names of each supervisor, by state index.\n#[allow(dead_code)]\npub mod states {{"
        );
        for s in &p.supervisors {
            let names: Vec<String> = s
                .automaton
                .states()
                .map(|x| format!("{:?}", s.automaton.state_name(x)))
                .collect();
            let _ = writeln!(
                self.out,
                "    /// Supervisor `{}`.\n    pub static {}: [&str; {}] = [{}];",
                doc_line(&s.name).replace('`', "'"),
                ident(&s.name),
                names.len(),
                names.join(", ")
            );
        }
        let _ = writeln!(self.out, "}}");
    }

    fn pools(&mut self) {
        let pools = self.pools;
        let p = self.project;
        let list = |items: Vec<String>| items.join(", ");

        let inputs = list(
            pools
                .inputs
                .iter()
                .map(|i| format!("InputSpec {{ debounce_scans: {} }}", i.debounce_scans))
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Input filtering, by input.\nconst INPUTS: [InputSpec; {}] = [{inputs}];",
            pools.inputs.len()
        );

        let mut doc = String::new();
        for (o, out) in p.outputs.iter().enumerate() {
            let how = match &out.drive {
                crate::project::Drive::Actions { initial } => {
                    format!("actions, initial {}", u8::from(*initial))
                }
                crate::project::Drive::States(_) => "state map".to_owned(),
            };
            let _ = writeln!(
                doc,
                "/// - {o} `{}`: {how}, safe {}",
                doc_line(&out.name).replace('`', "'"),
                u8::from(out.safe)
            );
        }
        let outputs = list(
            pools
                .outputs
                .iter()
                .map(|o| {
                    format!(
                        "OutputSpec {{ safe: {}, initial: {}, state_map: {} }}",
                        o.safe,
                        o.initial,
                        self.span(o.state_map)
                    )
                })
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Outputs:\n{doc}const OUTPUTS: [OutputSpec; {}] = [{outputs}];",
            pools.outputs.len()
        );

        let timers = list(
            pools
                .timers
                .iter()
                .map(|t| format!("TimerSpec {{ preset_ms: {} }}", t.preset_ms))
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Timer presets.\nconst TIMERS: [TimerSpec; {}] = [{timers}];",
            pools.timers.len()
        );

        let mut doc = String::new();
        for (e, ev) in p.events.iter().enumerate() {
            let kind = if ev.controllable {
                "controllable"
            } else {
                "uncontrollable"
            };
            let _ = writeln!(
                doc,
                "/// - {e} `{}` ({kind})",
                doc_line(&ev.name).replace('`', "'")
            );
        }
        let events = list(
            pools
                .events
                .iter()
                .map(|e| {
                    let trigger = match e.trigger {
                        ex::Trigger::Command => "Trigger::Command".to_owned(),
                        ex::Trigger::Rising(s) => format!("Trigger::Rising({})", self.span(s)),
                        ex::Trigger::Falling(s) => format!("Trigger::Falling({})", self.span(s)),
                        ex::Trigger::Expired(t) => format!("Trigger::Expired({})", self.timer(t)),
                    };
                    let request = e
                        .request
                        .map_or("None".to_owned(), |r| format!("Some({})", self.input(r)));
                    format!(
                        "EventSpec {{ trigger: {trigger}, when: {}, unless: {}, request: {request}, actions: {}, members: {} }}",
                        self.span(e.when),
                        self.span(e.unless),
                        self.span(e.actions),
                        self.span(e.members)
                    )
                })
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Events in priority order:\n{doc}const EVENTS: [EventSpec; {}] = [{events}];",
            pools.events.len()
        );

        let sups = list(
            pools
                .supervisors
                .iter()
                .map(|s| {
                    format!(
                        "SupervisorSpec {{ states: {}, initial: {} }}",
                        s.states, s.initial
                    )
                })
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Supervisor sizes and initial states.\nconst SUPERVISORS: [SupervisorSpec; {}] = [{sups}];",
            pools.supervisors.len()
        );

        let lists = list(pools.input_lists.iter().map(|&i| self.input(i)).collect());
        let _ = writeln!(
            self.out,
            "/// Input lists of edge bindings and `when`/`unless` conditions.\nconst INPUT_LISTS: [Index; {}] = [{lists}];",
            pools.input_lists.len()
        );
        let actions = list(
            pools
                .actions
                .iter()
                .map(|a| match *a {
                    ex::Action::Set(o) => format!("Action::Set({})", self.output(o)),
                    ex::Action::Clear(o) => format!("Action::Clear({})", self.output(o)),
                    ex::Action::Start(t) => format!("Action::Start({})", self.timer(t)),
                    ex::Action::Reset(t) => format!("Action::Reset({})", self.timer(t)),
                })
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Event actions.\nconst ACTIONS: [Action; {}] = [{actions}];",
            pools.actions.len()
        );
        let members = list(
            pools
                .memberships
                .iter()
                .map(|m| {
                    format!(
                        "Membership {{ supervisor: {}, local: {} }}",
                        self.supervisor(m.supervisor),
                        m.local
                    )
                })
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Which supervisors have each event, and its local index there.\nconst MEMBERSHIPS: [Membership; {}] = [{members}];",
            pools.memberships.len()
        );
        let map = list(
            pools
                .state_map
                .iter()
                .map(|m| {
                    format!(
                        "StateMapEntry {{ supervisor: {}, state: {} }}",
                        self.supervisor(m.supervisor),
                        m.state
                    )
                })
                .collect(),
        );
        let _ = writeln!(
            self.out,
            "/// Moore outputs: (supervisor, state) pairs.\nconst STATE_MAP: [StateMapEntry; {}] = [{map}];",
            pools.state_map.len()
        );

        let policy = match pools.unexpected {
            ex::UnexpectedPolicy::Fault => "Fault",
            ex::UnexpectedPolicy::Ignore => "Ignore",
        };
        let reset = pools
            .reset
            .map_or("None".to_owned(), |r| format!("Some({})", self.input(r)));
        let _ = writeln!(
            self.out,
            "/// The executor's description of the project.\npub const CONFIG: Config<'static> = Config {{ name: {:?}, scan_period_ms: {}, max_commands_per_scan: {}, unexpected: UnexpectedPolicy::{policy}, reset: {reset}, overrun_limit: {}, overrun_fault: {}, lost_edge_fault: {}, inputs: &INPUTS, outputs: &OUTPUTS, timers: &TIMERS, events: &EVENTS, supervisors: &SUPERVISORS, input_lists: &INPUT_LISTS, actions: &ACTIONS, memberships: &MEMBERSHIPS, state_map: &STATE_MAP }};",
            pools.name,
            pools.scan_period_ms,
            pools.max_commands_per_scan,
            pools.overrun_limit,
            pools.overrun_fault,
            pools.lost_edge_fault,
        );
        let _ = writeln!(
            self.out,
            "/// Controller memory sized for this project.\npub type Memory = executor::memory::StaticMemory<{}, {}, {}, {}, {}>;",
            pools.inputs.len(),
            pools.outputs.len(),
            pools.timers.len(),
            pools.supervisors.len(),
            pools.events.len()
        );
    }

    /// Doc lines showing the first rows of a supervisor's transitions.
    fn decoded_rows(&self, j: usize, rows: usize) -> String {
        let sup = &self.project.supervisors[j];
        let a = &sup.automaton;
        let mut doc = String::new();
        for s in a.states().take(rows) {
            let moves: Vec<String> = sup
                .local_events
                .iter()
                .filter_map(|&(g, id)| {
                    a.successor(s, id)
                        .map(|t| format!("{} → {}", self.project.events[g].name, a.state_name(t)))
                })
                .collect();
            let _ = writeln!(
                doc,
                "/// - state {} `{}`: {}",
                s.0,
                doc_line(&a.state_name(s)).replace('`', "'"),
                if moves.is_empty() {
                    "(no transitions)".to_owned()
                } else {
                    doc_line(&moves.join(", ")).replace('`', "'")
                }
            );
        }
        if a.num_states() > rows {
            let _ = writeln!(doc, "/// - … {} more states", a.num_states() - rows);
        }
        doc
    }

    fn source_line(&self, j: usize) -> String {
        match &self.project.supervisors[j].source {
            SupervisorSource::File(path) => format!(
                "from `{}`",
                doc_line(&path.display().to_string()).replace('`', "'")
            ),
            SupervisorSource::Synthesized {
                plants,
                specs,
                minimized,
            } => format!(
                "synthesised from {} plant and {} specification files{}",
                plants.len(),
                specs.len(),
                if *minimized { ", minimised" } else { "" }
            ),
        }
    }

    fn tables(&mut self, image: &TableImage) -> Vec<SupervisorStats> {
        let mut stats = Vec::new();
        let mut views = Vec::new();
        for (j, (sup, table)) in self
            .project
            .supervisors
            .iter()
            .zip(&image.tables)
            .enumerate()
        {
            let id = ident(&sup.name);
            let rows = self.decoded_rows(j, 8);
            let layout = match table.layout {
                Layout::Dense => "dense",
                Layout::Sparse => "sparse",
            };
            let _ = writeln!(
                self.out,
                "/// Supervisor `{}` ({}): {} states in {} bits, {} local events, {layout} layout, {} bytes.\n/// Transitions of the first states:\n{rows}const {id}_DEFINED: [u32; {}] = [{}];\n/// Packed targets of `{}`.\nconst {id}_TARGETS: [u32; {}] = [{}];",
                doc_line(&sup.name).replace('`', "'"),
                self.source_line(j),
                table.states,
                table.state_bits,
                table.events,
                table.bytes(),
                table.defined.len(),
                words(&table.defined),
                doc_line(&sup.name).replace('`', "'"),
                table.targets.len(),
                words(&table.targets),
            );
            let rows = match table.layout {
                Layout::Dense => "Rows::Dense".to_owned(),
                Layout::Sparse => {
                    let _ = writeln!(
                        self.out,
                        "/// Row starts of `{}`.\nconst {id}_ROW_STARTS: [u32; {}] = [{}];",
                        doc_line(&sup.name).replace('`', "'"),
                        table.row_starts.len(),
                        words(&table.row_starts)
                    );
                    format!(
                        "Rows::Sparse {{ row_starts: &{id}_ROW_STARTS, start_bits: {} }}",
                        table.start_bits
                    )
                }
            };
            views.push(format!(
                "SupervisorTable {{ events: {}, state_bits: {}, defined: &{id}_DEFINED, targets: &{id}_TARGETS, rows: {rows} }}",
                table.events, table.state_bits
            ));
            stats.push(SupervisorStats::of_table(&sup.name, table));
        }
        let _ = writeln!(
            self.out,
            "/// One table per supervisor.\nconst TABLES: [SupervisorTable<'static>; {}] = [{}];\n/// CRC-32 of the program image (configuration and tables), checked at start.\npub const IMAGE_CRC: u32 = {:#010x};\n/// The program: the configuration and the tables above, as constants the\n/// compiler can see through (a zero-sized type rather than a `static` holding them).\npub struct Tables;\nimpl Program for Tables {{\n    fn config(&self) -> Config<'_> {{ CONFIG }}\n    #[inline]\n    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {{\n        TABLES.get(supervisor as usize)?.next_state(state, local)\n    }}\n    fn image_intact(&self) -> bool {{ executor::table::image_crc(&CONFIG, &TABLES) == IMAGE_CRC }}\n}}\n/// The program: run it with `executor::Controller::new(&PROGRAM, Memory::new())`.\npub static PROGRAM: Tables = Tables;",
            views.len(),
            views.join(", "),
            image.crc
        );
        stats
    }

    /// The baseline: each supervisor as one `match` on (state, local event).
    fn matches(&mut self, crc: u32) -> Vec<SupervisorStats> {
        let mut stats = Vec::new();
        let mut arms = Vec::new();
        let _ = writeln!(
            self.out,
            "/// The supervisors as plain `match` statements on (state, local event): the\n/// baseline a hand-written state machine would be.\npub mod matches {{"
        );
        for (j, sup) in self.project.supervisors.iter().enumerate() {
            let a = &sup.automaton;
            let fn_name = snake_ident(&sup.name);
            let mut cases = String::new();
            for s in a.states() {
                for (local, &(_, id)) in sup.local_events.iter().enumerate() {
                    if let Some(t) = a.successor(s, id) {
                        let _ = write!(cases, "({}, {local}) => Some({}),", s.0, t.0);
                    }
                }
            }
            let _ = writeln!(
                self.out,
                "/// Supervisor `{}` ({}).\npub fn {fn_name}(state: u32, event: u16) -> Option<u32> {{ match (state, event) {{ {cases} _ => None }} }}",
                doc_line(&sup.name).replace('`', "'"),
                self.source_line(j),
            );
            arms.push(format!(
                "{} => matches::{fn_name}(state, local),",
                self.supervisor(j as ex::Index)
            ));
            stats.push(SupervisorStats {
                name: sup.name.clone(),
                states: a.num_states() as u32,
                events: sup.local_events.len() as u16,
                layout: None,
                table_bytes: 0,
                naive_bytes: 2 * a.num_states() * sup.local_events.len(),
                cubes: 0,
                literals: 0,
            });
        }
        let _ = writeln!(self.out, "}}");
        let _ = writeln!(
            self.out,
            "/// CRC-32 of the configuration (the supervisors are code), checked at start.\npub const IMAGE_CRC: u32 = {crc:#010x};\n/// The program: supervisors as `match` statements.\npub struct Match;\nimpl Program for Match {{\n    fn config(&self) -> Config<'_> {{ CONFIG }}\n    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {{\n        match supervisor {{ {} _ => None }}\n    }}\n    fn image_intact(&self) -> bool {{ executor::table::config_crc(&CONFIG) == IMAGE_CRC }}\n}}\n/// The program: run it with `executor::Controller::new(&PROGRAM, Memory::new())`.\npub static PROGRAM: Match = Match;",
            arms.join("\n")
        );
        stats
    }

    fn logic(&mut self, logic: &[LogicSupervisor], crc: u32) -> Vec<SupervisorStats> {
        let mut stats = Vec::new();
        let mut arms = Vec::new();
        let _ = writeln!(
            self.out,
            "/// The supervisors as CMSSM next-state (`_next`) and enable (`_defined`) functions.\npub mod logic {{"
        );
        for (j, (sup, l)) in self.project.supervisors.iter().zip(logic).enumerate() {
            let fn_name = snake_ident(&sup.name);
            let events: Vec<&str> = sup
                .local_events
                .iter()
                .map(|&(g, _)| self.project.events[g].name.as_str())
                .collect();
            let states: Vec<String> = sup
                .automaton
                .states()
                .map(|s| sup.automaton.state_name(s).into_owned())
                .collect();
            let state_refs: Vec<&str> = states.iter().map(String::as_str).collect();
            let rows = self.decoded_rows(j, 8);
            let _ = writeln!(
                self.out,
                "/// Supervisor `{}` ({}) as a CMSSM. Transitions of the first states:\n{rows}pub mod {fn_name} {{\n{}\n}}",
                doc_line(&sup.name).replace('`', "'"),
                self.source_line(j),
                l.emit_rust(&fn_name, &events, &state_refs)
            );
            arms.push(format!(
                "{} => logic::{fn_name}::{fn_name}_step(state, local),",
                self.supervisor(j as ex::Index)
            ));
            let sizes = l.sizes();
            let (cubes, literals) = (sizes.cubes, sizes.literals);
            stats.push(SupervisorStats {
                name: sup.name.clone(),
                states: sup.automaton.num_states() as u32,
                events: events.len() as u16,
                layout: None,
                table_bytes: 0,
                naive_bytes: 2 * sup.automaton.num_states() * events.len(),
                cubes,
                literals,
            });
        }
        let _ = writeln!(self.out, "}}");
        let _ = writeln!(
            self.out,
            "/// CRC-32 of the configuration (the supervisors are code), checked at start.\npub const IMAGE_CRC: u32 = {crc:#010x};\n/// The program: supervisors as minimised boolean functions.\npub struct Logic;\nimpl Program for Logic {{\n    fn config(&self) -> Config<'_> {{ CONFIG }}\n    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {{\n        match supervisor {{ {} _ => None }}\n    }}\n    fn image_intact(&self) -> bool {{ executor::table::config_crc(&CONFIG) == IMAGE_CRC }}\n}}\n/// The program: run it with `executor::Controller::new(&PROGRAM, Memory::new())`.\npub static PROGRAM: Logic = Logic;",
            arms.join("\n")
        );
        stats
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
        }
    }
}

/// Puts a blank line between consecutive items (prettyplease leaves none):
/// before a doc comment or attribute that follows the end of an item at the
/// same indentation.
fn separate_items(code: &str) -> String {
    let mut out = String::with_capacity(code.len() + code.len() / 16);
    let mut prev: Option<&str> = None;
    for line in code.lines() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        if let Some(p) = prev {
            let p_trimmed = p.trim_start();
            let starts_item = trimmed.starts_with("///") || trimmed.starts_with("#[");
            let ends_item = p_trimmed.ends_with(';') || p_trimmed.ends_with('}');
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
    progress: &dyn crate::ops::Progress,
) -> Result<Generated> {
    let pools = ConfigPools::from_project(project)?;
    let mut e = Emitter {
        project,
        pools: &pools,
        out: String::new(),
    };
    let uses = match backend {
        Backend::Table => {
            "use executor::program::Program;\nuse executor::table::{Rows, SupervisorTable};"
        }
        Backend::Logic | Backend::Match => "use executor::program::Program;",
    };
    let _ = writeln!(
        e.out,
        "#[allow(unused_imports)]\nuse executor::program::{{Action, Config, EventSpec, Index, InputSpec, Membership, OutputSpec, Span, StateMapEntry, SupervisorSpec, TimerSpec, Trigger, UnexpectedPolicy}};\n#[allow(unused_imports)]\n{uses}"
    );
    e.constants();
    e.pools();
    e.out.push_str(&crate::board::board_module(project));
    let (stats, crc) = match backend {
        Backend::Table => {
            let image = TableImage::new(project)?;
            (e.tables(&image), image.crc)
        }
        Backend::Logic => {
            let image = LogicImage::with_progress(project, progress)?;
            (e.logic(&image.supervisors, image.crc), image.crc)
        }
        Backend::Match => {
            let crc = executor::table::config_crc(&pools.config());
            (e.matches(crc), crc)
        }
    };
    let file = syn::parse_file(&e.out).map_err(|err| {
        Error::Incompatible(format!(
            "internal error: generated code does not parse ({err}); please report it with the project file"
        ))
    })?;
    let body = separate_items(&prettyplease::unparse(&file));
    let backend_name = backend.name();
    let header = format!(
        "// Generated by codegen {} from `{}` ({backend_name} backend). Do not edit.\n// Regenerate: {}\n// Include it in a module: `include!(concat!(env!(\"OUT_DIR\"), \"/<name>.rs\"));`\n\n",
        env!("CARGO_PKG_VERSION"),
        doc_line(&project.path.display().to_string()),
        doc_line(regenerate),
    );
    Ok(Generated {
        code: header + &body,
        stats,
        crc,
    })
}
