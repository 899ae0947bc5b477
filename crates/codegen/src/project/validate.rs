//! From the raw project file to a validated [`Project`].
//!
//! Validation stops at the first error. Every error names the project file
//! and the line and column of the offending entry (a model file's own
//! syntax and model errors propagate unchanged: they point into that file).
//! Warnings do not stop validation; they are collected in
//! [`Project::warnings`].
//!
//! # Names and generated identifiers
//!
//! Inputs, outputs, timers, switches, events and supervisors share **one
//! namespace**: every name is sanitised with [`sanitize`], and no two
//! names of any of these kinds may give the same identifier (`valve-1` and
//! `valve_1` collide, and so do an input `part` and an event `part`). This
//! is stricter than the Rust emitter needs (it puts each kind in its own
//! module) but keeps every backend free to use one flat namespace (ST
//! globals, DOT nodes, trace columns), where an input and an event of the
//! same name would clash. A name without an ASCII letter or digit (`""`,
//! `"***"`) is not a valid identifier. Switch positions are checked within
//! their switch (valid identifier, no collision, and none may sanitise to
//! `OFF`, the implicit position). State names and the project name are not
//! identifiers (the emitter writes them as escaped string literals).
//!
//! # Outputs
//!
//! An output is driven by actions (`set`, `clear`, switch positions) or by
//! a state map, never both. An output belongs to at most one switch, and an
//! output of a switch is driven only through that switch (never by `set` or
//! `clear`), so the switch always knows its position. An output driven by
//! nothing is a warning.
//!
//! # Actions
//!
//! The actions of an event are applied in this order:
//! 1. clears: the `clear` list, then the outputs lowered by the `switch`
//!    entries (other positions, or every position for `off`), in the order
//!    of the entries;
//! 2. sets: the `set` list, then the outputs raised by the `switch`
//!    entries;
//! 3. timer resets (`reset` list);
//! 4. timer starts (`start` list), so `reset` and `start` of one timer
//!    restart it.
//!
//! Validation guarantees that no event raises and lowers the same output,
//! so the order of clears and sets never changes the result; it is fixed
//! for reproducible tables.
//!
//! # Events and supervisors
//!
//! - A controllable event has no source (`rising`, `falling`, `expired`),
//!   no level conditions and no `origin`; only it may have a `request`.
//!   An uncontrollable event has exactly one source; `origin` defaults to
//!   `plant`.
//! - Controllability must agree with every automaton that has the event
//!   and states controllability (for a synthesised supervisor: every plant
//!   and specification file it was synthesised from).
//! - Every event of a supervisor's alphabet must be declared. A
//!   controllable event in no alphabet is an error (nothing could ever
//!   allow it); an uncontrollable one is always feasible and only warned
//!   about when it has no actions either.
//! - Several events may share a source (the same input edge or timer
//!   expiry) with different `when`/`unless` conditions.
//! - A timer whose expiry an event observes but that no action starts is a
//!   warning (the event can never occur). An input in both `when` and
//!   `unless` of one event is a warning too.
//!
//! # Supervisor sources
//!
//! `file` names any supported automaton file, relative to the project
//! file's directory. Without `component`, the file must hold exactly one
//! component of kind supervisor, spec or unspecified; `component` selects
//! one by automaton name (any kind). `synthesize` expands its glob
//! patterns relative to the project directory (matches in alphabetical
//! order, duplicates dropped; a pattern without `*`, `?` or `[` is a plain
//! path); every pattern must match at least one file. From a file under
//! `plants` every plant and unspecified component is taken, from a file
//! under `specs` every spec, supervisor and unspecified component. The
//! supervisor is `supcon(sync(plants), sync(specs))` (no specs: the plant's
//! nonblocking controllable part), then `minstate` if `minimize = true`.
//! A missing or unreadable model file, or one of unknown format, is
//! reported at the line of the project that names it.
//!
//! # Numbers
//!
//! `scan_period_ms` and `preset_ms` lie in `1..2^31` (time differences
//! must stay wrap-safe on a 32-bit millisecond clock);
//! `max_commands_per_scan` and `overrun_limit` in `0..=65535`;
//! `debounce_scans` in `0..=255`.
//!
//! # Board
//!
//! The optional `[board]` section maps signals to pins of the MCU the
//! board firmware runs on:
//!
//! ```toml
//! [board]
//! chip = "STM32F411RETx"            # optional, this is the default
//! inputs = { auto_pb = { pin = "PC13", pull = "up", active_low = true }, part = "PA1" }
//! outputs = { down_sol = { pin = "PB0" }, auto_lamp = "PA5" }
//! ```
//!
//! (`[board.inputs]` / `[board.outputs]` tables work as well). A bare
//! string is the pin with every option at its default: `pull = "none"`,
//! `active_low = false`. Outputs are push-pull and take no `pull`.
//!
//! - `chip` must be an STM32F411 (the firmware's HAL); its package letter
//!   (`R`: 64 pins, `C`: 48 pins) limits the pins that exist.
//! - Every key names a declared input (under `inputs`) or output (under
//!   `outputs`); a pin is `P<port><n>`, ports A–E and H, pins 0–15 (port H:
//!   PH0 and PH1), case-insensitive. PA13/PA14 (SWD, which flashes the board
//!   and carries the log) and PH0 (the HSE clock input) are refused.
//! - No pin carries two signals; `pull` is `up`, `down` or `none`.
//! - `scan_period_ms` is at most [`MAX_BOARD_SCAN_PERIOD_MS`] (the
//!   watchdog waits 4 periods and at most 32.7 s).
//! - Warnings: an input without a pin (the firmware reads 0), an output
//!   without a pin (computed, not driven), Nucleo-F411RE pins that are
//!   wired to something else by default (PA2/PA3, PC14/PC15, PC13 as an
//!   output), and an input whose EXTI line is taken.
//!
//! **Edge latching** ([`EdgeLatch`]): the firmware counts the changes of an
//! input between two samples with an interrupt on both edges of EXTI line
//! *n* (the pin number); more than one change is a lost edge (docs/semantics.md,
//! `LostEdge`). A line listens to one port, so the first input in
//! declaration order with pin number *n* owns it and a later one on
//! another port is not latched (a warning). Debounced inputs
//! (`debounce_scans > 1`) are not latched either: their filter drops short
//! pulses on purpose, so a pulse between samples is not an error there.

use super::ident::sanitize;
use super::model::*;
use super::parse::{names, Entries, Name, Names, RawEvent, RawProject, RawSupervisor};
use crate::automaton::{Alphabet, Automaton, EventId, StateId};
use crate::error::{line_column, Error, Location, Result};
use crate::formats::{self, Component, Kind};
use crate::ops;
use std::collections::{HashMap, HashSet};
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

mod board;

pub use board::{DEFAULT_CHIP, MAX_BOARD_SCAN_PERIOD_MS};

/// Exclusive upper bound of `scan_period_ms` and `preset_ms`.
const TIME_LIMIT: i64 = 1 << 31;

/// Validates `raw`, the parsed `text` of the project file at `path`.
pub(crate) fn validate(raw: RawProject, text: &str, path: &Path) -> Result<Project> {
    let mut v = Validator {
        text,
        path,
        dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
        warnings: Vec::new(),
        files: vec![path.to_path_buf()],
        namespace: HashMap::new(),
    };
    v.project(raw)
}

/// A name declared in the shared namespace.
struct Claim {
    kind: &'static str,
    name: String,
    line: u32,
}

/// An automaton a supervisor was read or synthesised from.
struct ModelOrigin {
    file: PathBuf,
    name: String,
    alphabet: Alphabet,
}

/// What validation knows of an output before the supervisors are loaded.
struct OutputUse {
    /// Span of the output's `states` table, if it has one.
    state_map: Option<Range<usize>>,
    /// The switch (index) and position that drive it.
    switch: Option<(usize, String)>,
    /// Some event sets or clears it.
    acted_on: bool,
}

struct Validator<'a> {
    text: &'a str,
    path: &'a Path,
    dir: PathBuf,
    warnings: Vec<Warning>,
    files: Vec<PathBuf>,
    namespace: HashMap<String, Claim>,
}

fn kind_list(kinds: &[Kind]) -> String {
    kinds
        .iter()
        .map(Kind::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

impl Validator<'_> {
    fn location(&self, span: &Range<usize>) -> Location {
        Location::at_offset(self.path, self.text, span.start)
    }

    fn line(&self, span: &Range<usize>) -> u32 {
        line_column(self.text, span.start).0
    }

    fn error(&self, span: &Range<usize>, message: impl Into<String>) -> Error {
        Error::model(self.location(span), message)
    }

    fn warn(&mut self, span: &Range<usize>, message: impl Into<String>) {
        let line = self.line(span);
        self.warnings.push(Warning {
            line,
            message: message.into(),
        });
    }

    /// Records a model file for `rerun-if-changed` (once).
    fn depend_on(&mut self, file: &Path) {
        if !self.files.iter().any(|f| f == file) {
            self.files.push(file.to_path_buf());
        }
    }

    /// Enters `name` into the shared namespace (see the module docs).
    fn claim(&mut self, kind: &'static str, name: &str, span: &Range<usize>) -> Result<()> {
        let Some(ident) = sanitize(name) else {
            return Err(self.error(
                span,
                format!(
                    "{kind} name `{name}` is not a valid identifier: it needs at least one ASCII letter or digit"
                ),
            ));
        };
        if let Some(c) = self.namespace.get(&ident) {
            let message = if c.name == name && c.kind == kind {
                format!(
                    "{kind} name `{name}` is already used at line {}; {kind} names must be unique",
                    c.line
                )
            } else if c.name == name {
                format!(
                    "`{name}` names both the {} at line {} and this {kind}; inputs, outputs, timers, switches, events and supervisors share one namespace",
                    c.kind, c.line
                )
            } else {
                format!(
                    "{kind} `{name}` and {} `{}` (line {}) both become the identifier `{ident}` in generated code; rename one",
                    c.kind, c.name, c.line
                )
            };
            return Err(self.error(span, message));
        }
        let line = self.line(span);
        self.namespace.insert(
            ident,
            Claim {
                kind,
                name: name.to_owned(),
                line,
            },
        );
        Ok(())
    }

    /// An integer field in `range`, or `default` when absent.
    fn number(
        &self,
        field: &Option<Spanned<i64>>,
        default: i64,
        range: std::ops::RangeInclusive<i64>,
        what: &str,
    ) -> Result<i64> {
        match field {
            None => Ok(default),
            Some(v) if range.contains(v.get_ref()) => Ok(*v.get_ref()),
            Some(v) => Err(self.error(
                &v.span(),
                format!(
                    "{what} must be between {} and {}, found {}",
                    range.start(),
                    range.end(),
                    v.get_ref()
                ),
            )),
        }
    }

    fn resolve(
        &self,
        index: &HashMap<String, usize>,
        kind: &str,
        section: &str,
        name: &Name,
    ) -> Result<usize> {
        index.get(name.get_ref()).copied().ok_or_else(|| {
            self.error(
                &name.span(),
                format!(
                    "unknown {kind} `{}`: not declared in [{section}]",
                    name.get_ref()
                ),
            )
        })
    }

    fn project(&mut self, raw: RawProject) -> Result<Project> {
        let RawProject {
            plc,
            inputs: raw_inputs,
            outputs: raw_outputs,
            timers: raw_timers,
            switches: raw_switches,
            events: raw_events,
            supervisor: raw_supervisors,
            board: raw_board,
        } = raw;
        let plc = plc.into_inner();

        // Inputs.
        let mut inputs = Vec::new();
        let mut input_index = HashMap::new();
        for (name, decl) in &raw_inputs.0 {
            self.claim("input", name.get_ref(), &name.span())?;
            let debounce =
                self.number(&decl.get_ref().debounce_scans, 0, 0..=255, "debounce_scans")?;
            input_index.insert(name.get_ref().clone(), inputs.len());
            inputs.push(Input {
                name: name.get_ref().clone(),
                debounce_scans: debounce as u8,
                line: self.line(&name.span()),
            });
        }

        // [plc].
        let scan_period_ms = self.number(
            &plc.scan_period_ms,
            10,
            1..=TIME_LIMIT - 1,
            "scan_period_ms",
        )? as u32;
        let max_commands_per_scan = self.number(
            &plc.max_commands_per_scan,
            1,
            0..=i64::from(u16::MAX),
            "max_commands_per_scan",
        )? as u16;
        let overrun_limit = self.number(
            &plc.overrun_limit,
            1,
            0..=i64::from(u16::MAX),
            "overrun_limit",
        )? as u16;
        let unexpected = match &plc.unexpected {
            None => Unexpected::Fault,
            Some(u) => match u.get_ref().as_str() {
                "fault" => Unexpected::Fault,
                "ignore" => Unexpected::Ignore,
                other => {
                    return Err(self.error(
                        &u.span(),
                        format!("unexpected must be \"fault\" or \"ignore\", found {other:?}"),
                    ))
                }
            },
        };
        let reset = match &plc.reset {
            None => None,
            Some(r) => Some(self.resolve(&input_index, "input", "inputs", r)?),
        };

        // Outputs (their drive is settled once the supervisors are known).
        let mut output_index = HashMap::new();
        let mut output_uses = Vec::new();
        for (i, (name, decl)) in raw_outputs.0.iter().enumerate() {
            self.claim("output", name.get_ref(), &name.span())?;
            output_index.insert(name.get_ref().clone(), i);
            let decl = decl.get_ref();
            if let (Some(_), Some(initial)) = (&decl.states, &decl.initial) {
                return Err(self.error(
                    &initial.span(),
                    format!(
                        "output `{}` has a state map (a Moore output): it takes no `initial`, its level follows the supervisor states",
                        name.get_ref()
                    ),
                ));
            }
            output_uses.push(OutputUse {
                state_map: decl.states.as_ref().map(Spanned::span),
                switch: None,
                acted_on: false,
            });
        }

        // Timers.
        let mut timers = Vec::new();
        let mut timer_index = HashMap::new();
        for (name, decl) in &raw_timers.0 {
            self.claim("timer", name.get_ref(), &name.span())?;
            let preset = self.number(
                &Some(decl.get_ref().preset_ms.clone()),
                0,
                1..=TIME_LIMIT - 1,
                "preset_ms",
            )?;
            timer_index.insert(name.get_ref().clone(), timers.len());
            timers.push(Timer {
                name: name.get_ref().clone(),
                preset_ms: preset as u32,
                line: self.line(&name.span()),
            });
        }

        // Switches.
        let mut switches = Vec::new();
        let mut switch_index = HashMap::new();
        for (name, decl) in &raw_switches.0 {
            self.claim("switch", name.get_ref(), &name.span())?;
            let switch = self.switch(&switches, name, decl, &output_index, &mut output_uses)?;
            switch_index.insert(name.get_ref().clone(), switches.len());
            switches.push(switch);
        }

        // Events.
        let mut events = Vec::new();
        let mut event_index = HashMap::new();
        let mut started = HashSet::new();
        let mut expiry_events: Vec<Vec<usize>> = vec![Vec::new(); timers.len()];
        let mut event_spans = Vec::new();
        for (name, decl) in &raw_events.0 {
            self.claim("event", name.get_ref(), &name.span())?;
            let env = Env {
                inputs: &input_index,
                outputs: &output_index,
                timers: &timer_index,
                switches: &switch_index,
                switch_list: &switches,
            };
            let event = self.event(name, decl.get_ref(), &env, &mut output_uses)?;
            for action in &event.actions {
                if let Action::Start(t) = action {
                    started.insert(*t);
                }
            }
            if let Trigger::Expired(t) = event.trigger {
                expiry_events[t].push(events.len());
            }
            event_index.insert(name.get_ref().clone(), events.len());
            event_spans.push(name.span());
            events.push(event);
        }

        // Supervisors.
        let mut supervisors = Vec::new();
        let mut supervisor_index = HashMap::new();
        let mut in_alphabet = vec![false; events.len()];
        for raw_sup in &raw_supervisors {
            let sup = self.supervisor(raw_sup, &events, &event_index, &event_spans)?;
            for &(g, _) in &sup.local_events {
                in_alphabet[g] = true;
            }
            supervisor_index.insert(sup.name.clone(), supervisors.len());
            supervisors.push(sup);
        }

        // Events no supervisor knows.
        for (e, event) in events.iter().enumerate() {
            if in_alphabet[e] {
                continue;
            }
            if event.controllable {
                return Err(self.error(
                    &event_spans[e],
                    format!(
                        "controllable event `{}` is in no supervisor's alphabet (controllable event in no alphabet): no supervisor could ever allow it",
                        event.name
                    ),
                ));
            }
            if event.actions.is_empty() {
                self.warn(
                    &event_spans[e],
                    format!(
                        "uncontrollable event `{}` is in no supervisor's alphabet and has no actions: it executes, moves nothing and does nothing",
                        event.name
                    ),
                );
            }
        }

        // Outputs, now that state maps can be resolved.
        let mut outputs = Vec::new();
        for ((name, decl), usage) in raw_outputs.0.iter().zip(&output_uses) {
            let decl_ref = decl.get_ref();
            let drive = match &decl_ref.states {
                Some(map) => {
                    Drive::States(self.state_map(name, map, &supervisors, &supervisor_index)?)
                }
                None => {
                    if usage.switch.is_none() && !usage.acted_on {
                        self.warn(
                            &name.span(),
                            format!(
                                "output `{}` is driven by nothing (no action, switch or state map): it stays at its initial level",
                                name.get_ref()
                            ),
                        );
                    }
                    Drive::Actions {
                        initial: decl_ref.initial.as_ref().is_some_and(|i| *i.get_ref()),
                    }
                }
            };
            outputs.push(Output {
                name: name.get_ref().clone(),
                safe: decl_ref.safe,
                drive,
                line: self.line(&name.span()),
            });
        }

        // Timers nothing starts.
        for (t, observers) in expiry_events.iter().enumerate() {
            if let Some(&e) = observers.first() {
                if !started.contains(&t) {
                    let span = raw_timers.0[t].0.span();
                    self.warn(
                        &span,
                        format!(
                            "timer `{}` is never started by any action, so event `{}` (line {}) can never occur",
                            timers[t].name, events[e].name, events[e].line
                        ),
                    );
                }
            }
        }

        let board = self.board(
            raw_board.as_ref(),
            plc.scan_period_ms.as_ref(),
            &inputs,
            &outputs,
        )?;

        Ok(Project {
            path: self.path.to_path_buf(),
            name: plc.name.into_inner(),
            scan_period_ms,
            max_commands_per_scan,
            unexpected,
            reset,
            overrun_limit,
            overrun_fault: plc.overrun_fault,
            lost_edge_fault: plc.lost_edge_fault,
            inputs,
            outputs,
            timers,
            switches,
            events,
            supervisors,
            board,
            warnings: std::mem::take(&mut self.warnings),
            files: std::mem::take(&mut self.files),
        })
    }

    fn switch(
        &mut self,
        done: &[Switch],
        name: &Name,
        decl: &Spanned<Entries<String>>,
        output_index: &HashMap<String, usize>,
        output_uses: &mut [OutputUse],
    ) -> Result<Switch> {
        let sw = name.get_ref();
        if decl.get_ref().0.is_empty() {
            return Err(self.error(
                &decl.span(),
                format!("switch `{sw}` needs at least one position (`off` is implicit)"),
            ));
        }
        let mut positions = Vec::new();
        let mut seen: HashMap<String, String> = HashMap::new();
        for (pos, out) in &decl.get_ref().0 {
            let ident = sanitize(pos.get_ref()).ok_or_else(|| {
                self.error(
                    &pos.span(),
                    format!(
                        "position name `{}` of switch `{sw}` is not a valid identifier: it needs at least one ASCII letter or digit",
                        pos.get_ref()
                    ),
                )
            })?;
            if ident == "OFF" {
                return Err(self.error(
                    &pos.span(),
                    format!(
                        "switch `{sw}` declares position `{}`: `off` is implicit (it lowers every position) and may not be declared",
                        pos.get_ref()
                    ),
                ));
            }
            if let Some(other) = seen.insert(ident.clone(), pos.get_ref().clone()) {
                return Err(self.error(
                    &pos.span(),
                    format!(
                        "positions `{other}` and `{}` of switch `{sw}` both become the identifier `{ident}`; rename one",
                        pos.get_ref()
                    ),
                ));
            }
            let out_name = Spanned::new(out.span(), out.get_ref().clone());
            let o = self.resolve(output_index, "output", "outputs", &out_name)?;
            let usage = &mut output_uses[o];
            if usage.state_map.is_some() {
                return Err(self.error(
                    &out.span(),
                    format!(
                        "output `{}` has a state map: an output is driven by actions or by a state map, not both (output driven twice)",
                        out.get_ref()
                    ),
                ));
            }
            if let Some((other, other_pos)) = &usage.switch {
                let whose = match done.get(*other) {
                    Some(sw) => format!("switch `{}` (line {})", sw.name, sw.line),
                    None => "this switch".to_owned(),
                };
                return Err(self.error(
                    &out.span(),
                    format!(
                        "output `{}` is already position `{other_pos}` of {whose}: an output belongs to at most one switch position",
                        out.get_ref()
                    ),
                ));
            }
            usage.switch = Some((done.len(), pos.get_ref().clone()));
            positions.push((pos.get_ref().clone(), o));
        }
        Ok(Switch {
            name: sw.clone(),
            positions,
            line: self.line(&name.span()),
        })
    }

    fn event(
        &mut self,
        name: &Name,
        decl: &RawEvent,
        env: &Env<'_>,
        output_uses: &mut [OutputUse],
    ) -> Result<Event> {
        let ev = name.get_ref();
        let controllable = decl.controllable.as_ref().is_some_and(|c| *c.get_ref());
        let inputs_of = |this: &Self, field: &Option<Spanned<Names>>| -> Result<Vec<usize>> {
            names(field.as_ref())
                .iter()
                .map(|n| this.resolve(env.inputs, "input", "inputs", n))
                .collect()
        };

        let (trigger, origin) = if controllable {
            let forbidden: [(&str, Option<Range<usize>>); 6] = [
                ("rising", decl.rising.as_ref().map(Spanned::span)),
                ("falling", decl.falling.as_ref().map(Spanned::span)),
                ("expired", decl.expired.as_ref().map(Spanned::span)),
                ("when", decl.when.as_ref().map(Spanned::span)),
                ("unless", decl.unless.as_ref().map(Spanned::span)),
                ("origin", decl.origin.as_ref().map(Spanned::span)),
            ];
            if let Some((field, Some(span))) = forbidden.iter().find(|(_, s)| s.is_some()) {
                let why = if *field == "origin" {
                    "the origin of a controllable event is the controller"
                } else {
                    "the controller chooses controllable events; only uncontrollable events are bound to inputs, timers and level conditions"
                };
                return Err(self.error(
                    span,
                    format!("controllable event `{ev}` cannot have `{field}`: {why}"),
                ));
            }
            (Trigger::Command, Origin::Controller)
        } else {
            if let Some(r) = &decl.request {
                return Err(self.error(
                    &r.span(),
                    format!(
                        "uncontrollable event `{ev}` cannot have `request`: request inputs (manual mode) are only for controllable events"
                    ),
                ));
            }
            let sources: Vec<(&str, Range<usize>)> = [
                ("rising", decl.rising.as_ref().map(Spanned::span)),
                ("falling", decl.falling.as_ref().map(Spanned::span)),
                ("expired", decl.expired.as_ref().map(Spanned::span)),
            ]
            .into_iter()
            .filter_map(|(f, s)| s.map(|s| (f, s)))
            .collect();
            match sources.as_slice() {
                [] => {
                    return Err(self.error(
                        &name.span(),
                        format!(
                            "uncontrollable event `{ev}` needs a source: exactly one of `rising`, `falling` or `expired` (or `controllable = true`)"
                        ),
                    ))
                }
                [(first, _), (second, span), ..] => {
                    return Err(self.error(
                        span,
                        format!(
                            "uncontrollable event `{ev}` has both `{first}` and `{second}`: it needs exactly one source"
                        ),
                    ))
                }
                [_] => {}
            }
            let trigger = if let Some(r) = &decl.rising {
                let list = inputs_of(self, &decl.rising)?;
                if list.is_empty() {
                    return Err(self.error(
                        &r.span(),
                        format!("`rising` of event `{ev}` names no input"),
                    ));
                }
                Trigger::Rising(list)
            } else if let Some(f) = &decl.falling {
                let list = inputs_of(self, &decl.falling)?;
                if list.is_empty() {
                    return Err(self.error(
                        &f.span(),
                        format!("`falling` of event `{ev}` names no input"),
                    ));
                }
                Trigger::Falling(list)
            } else {
                let t = decl.expired.as_ref().expect("one source");
                Trigger::Expired(self.resolve(env.timers, "timer", "timers", t)?)
            };
            let origin = match &decl.origin {
                None => Origin::Plant,
                Some(o) => match o.get_ref().as_str() {
                    "plant" => Origin::Plant,
                    "operator" => Origin::Operator,
                    other => {
                        return Err(self.error(
                            &o.span(),
                            format!("origin must be \"operator\" or \"plant\", found {other:?}"),
                        ))
                    }
                },
            };
            (trigger, origin)
        };

        let when = inputs_of(self, &decl.when)?;
        let unless = inputs_of(self, &decl.unless)?;
        for input in names(decl.unless.as_ref()) {
            if when.contains(&self.resolve(env.inputs, "input", "inputs", &input)?) {
                self.warn(
                    &input.span(),
                    format!(
                        "input `{}` is in both `when` and `unless` of event `{ev}`: the event can never occur",
                        input.get_ref()
                    ),
                );
            }
        }
        let request = match &decl.request {
            None => None,
            Some(r) => Some(self.resolve(env.inputs, "input", "inputs", r)?),
        };

        // Actions on outputs.
        let mut clears = Vec::new();
        let mut sets = Vec::new();
        for (field, list) in [("clear", &decl.clear), ("set", &decl.set)] {
            for out in names(list.as_ref()) {
                let o = self.resolve(env.outputs, "output", "outputs", &out)?;
                let usage = &mut output_uses[o];
                if usage.state_map.is_some() {
                    return Err(self.error(
                        &out.span(),
                        format!(
                            "output `{}` has a state map: an output is driven by actions or by a state map, not both (output driven twice)",
                            out.get_ref()
                        ),
                    ));
                }
                if let Some((s, pos)) = &usage.switch {
                    let sw = &env.switch_list[*s].name;
                    return Err(self.error(
                        &out.span(),
                        format!(
                            "output `{}` is position `{pos}` of switch `{sw}`: drive it with `switch = {{ {sw} = \"{pos}\" }}`, not with `{field}`",
                            out.get_ref()
                        ),
                    ));
                }
                usage.acted_on = true;
                if field == "set" && clears.contains(&o) {
                    return Err(self.error(
                        &out.span(),
                        format!(
                            "event `{ev}` both sets and clears output `{}`",
                            out.get_ref()
                        ),
                    ));
                }
                let list = if field == "clear" {
                    &mut clears
                } else {
                    &mut sets
                };
                if !list.contains(&o) {
                    list.push(o);
                }
            }
        }
        if let Some(entries) = &decl.switch {
            for (sw_name, pos) in &entries.get_ref().0 {
                let s = self.resolve(env.switches, "switch", "switches", sw_name)?;
                let switch = &env.switch_list[s];
                let position = pos.get_ref();
                if position == "off" {
                    clears.extend(switch.positions.iter().map(|&(_, o)| o));
                    continue;
                }
                let Some(&(_, chosen)) = switch.positions.iter().find(|(p, _)| p == position)
                else {
                    let known: Vec<&str> = switch
                        .positions
                        .iter()
                        .map(|(p, _)| p.as_str())
                        .chain(["off"])
                        .collect();
                    return Err(self.error(
                        &pos.span(),
                        format!(
                            "switch `{}` has no position `{position}` (positions: {})",
                            switch.name,
                            known.join(", ")
                        ),
                    ));
                };
                clears.extend(
                    switch
                        .positions
                        .iter()
                        .filter(|&&(_, o)| o != chosen)
                        .map(|&(_, o)| o),
                );
                sets.push(chosen);
            }
        }

        let mut actions: Vec<Action> = clears.into_iter().map(Action::Clear).collect();
        actions.extend(sets.into_iter().map(Action::Set));
        for t in names(decl.reset.as_ref()) {
            actions.push(Action::Reset(
                self.resolve(env.timers, "timer", "timers", &t)?,
            ));
        }
        for t in names(decl.start.as_ref()) {
            actions.push(Action::Start(
                self.resolve(env.timers, "timer", "timers", &t)?,
            ));
        }

        Ok(Event {
            name: ev.clone(),
            controllable,
            origin,
            trigger,
            when,
            unless,
            request,
            actions,
            line: self.line(&name.span()),
        })
    }

    /// Reads a model file named at `span`; I/O and format errors are
    /// reported at that line, errors inside the file propagate unchanged.
    fn read_model(&mut self, file: &Path, span: &Range<usize>) -> Result<Vec<Component>> {
        self.depend_on(file);
        formats::read_file(file).map_err(|e| match e {
            Error::Io { path, source } => self.error(
                span,
                format!("cannot read model file `{}`: {source}", path.display()),
            ),
            Error::UnknownFormat { path } => self.error(
                span,
                format!(
                    "`{}`: unknown model format (expected .toml, .gen, .ads or .wmod)",
                    path.display()
                ),
            ),
            other => other,
        })
    }

    /// The files `patterns` (relative to the project directory) match.
    fn expand(&mut self, patterns: &[Name]) -> Result<Vec<(PathBuf, Range<usize>)>> {
        let mut files: Vec<(PathBuf, Range<usize>)> = Vec::new();
        for pattern in patterns {
            let p = pattern.get_ref();
            let span = pattern.span();
            if !p.contains(['*', '?', '[']) {
                let file = self.dir.join(p);
                if !files.iter().any(|(f, _)| *f == file) {
                    files.push((file, span));
                }
                continue;
            }
            let full = if Path::new(p).is_absolute() || self.dir.as_os_str().is_empty() {
                p.clone()
            } else {
                let dir = self.dir.to_str().ok_or_else(|| {
                    self.error(
                        &span,
                        format!(
                            "cannot expand `{p}`: the project directory `{}` is not valid UTF-8",
                            self.dir.display()
                        ),
                    )
                })?;
                format!("{}/{p}", glob::Pattern::escape(dir))
            };
            let matches = glob::glob(&full)
                .map_err(|e| self.error(&span, format!("invalid file pattern `{p}`: {}", e.msg)))?;
            let mut any = false;
            for m in matches {
                let file = m.map_err(|e| {
                    self.error(
                        &span,
                        format!("cannot expand `{p}`: {}: {}", e.path().display(), e.error()),
                    )
                })?;
                if !file.is_file() {
                    continue;
                }
                any = true;
                if !files.iter().any(|(f, _)| *f == file) {
                    files.push((file, span.clone()));
                }
            }
            if !any {
                return Err(self.error(
                    &span,
                    format!(
                        "`{p}` matches no file (patterns are relative to `{}`)",
                        if self.dir.as_os_str().is_empty() {
                            ".".to_owned()
                        } else {
                            self.dir.display().to_string()
                        }
                    ),
                ));
            }
        }
        Ok(files)
    }

    /// The components of `patterns`' files whose kind is in `kinds`.
    fn synthesis_inputs(
        &mut self,
        patterns: &[Name],
        kinds: &[Kind],
        role: &str,
        origins: &mut Vec<ModelOrigin>,
    ) -> Result<(Vec<PathBuf>, Vec<Automaton>)> {
        let mut paths = Vec::new();
        let mut automata = Vec::new();
        for (file, span) in self.expand(patterns)? {
            let before = automata.len();
            for c in self.read_model(&file, &span)? {
                if kinds.contains(&c.kind) {
                    origins.push(ModelOrigin {
                        file: file.clone(),
                        name: c.automaton.name().to_owned(),
                        alphabet: c.automaton.alphabet().clone(),
                    });
                    automata.push(c.automaton);
                }
            }
            if automata.len() == before {
                return Err(self.error(
                    &span,
                    format!(
                        "`{}` holds no component usable as a {role} (kinds: {})",
                        file.display(),
                        kind_list(kinds)
                    ),
                ));
            }
            paths.push(file);
        }
        Ok((paths, automata))
    }

    /// The automaton `sup` names, where it came from, and the automata of
    /// its source files.
    fn load(
        &mut self,
        sup: &Spanned<RawSupervisor>,
    ) -> Result<(Automaton, SupervisorSource, Vec<ModelOrigin>)> {
        let header = sup.span();
        let raw = sup.get_ref();
        let mut origins = Vec::new();
        match (&raw.file, &raw.synthesize) {
            (Some(_), Some(s)) => Err(self.error(
                &s.span(),
                "a supervisor has either `file` or `synthesize`, not both",
            )),
            (None, None) => Err(self.error(
                &header,
                "a supervisor needs `file = \"…\"` or `synthesize = { plants = […], specs = […] }`",
            )),
            (Some(file), None) => {
                let path = self.dir.join(file.get_ref());
                let components = self.read_model(&path, &file.span())?;
                let automaton =
                    self.select(components, raw.component.as_ref(), &path, &file.span())?;
                origins.push(ModelOrigin {
                    file: path.clone(),
                    name: automaton.name().to_owned(),
                    alphabet: automaton.alphabet().clone(),
                });
                Ok((automaton, SupervisorSource::File(path), origins))
            }
            (None, Some(synth)) => {
                if let Some(c) = &raw.component {
                    return Err(self.error(
                        &c.span(),
                        "`component` selects from a `file`; a synthesised supervisor has none",
                    ));
                }
                let s = synth.get_ref();
                let plant_patterns = names(Some(&s.plants));
                if plant_patterns.is_empty() {
                    return Err(self.error(&s.plants.span(), "synthesis needs at least one plant"));
                }
                let (plants, plant_automata) = self.synthesis_inputs(
                    &plant_patterns,
                    &[Kind::Plant, Kind::Unspecified],
                    "plant",
                    &mut origins,
                )?;
                let (specs, spec_automata) = self.synthesis_inputs(
                    &names(s.specs.as_ref()),
                    &[Kind::Spec, Kind::Supervisor, Kind::Unspecified],
                    "specification",
                    &mut origins,
                )?;
                let fail = |this: &Self, e: Error| match e {
                    Error::Incompatible(message) => this.error(
                        &synth.span(),
                        format!("cannot synthesise the supervisor: {message}"),
                    ),
                    other => other,
                };
                let options = ops::SynthesisOptions {
                    minstate: s.minimize,
                    ..ops::SynthesisOptions::default()
                };
                let result = ops::synthesize(&plant_automata, &spec_automata, options)
                    .map_err(|e| fail(self, e))?
                    .supervisor;
                if result.is_empty() {
                    return Err(self.error(
                        &synth.span(),
                        "synthesis gave the empty supervisor: the specification cannot be enforced",
                    ));
                }
                Ok((
                    result,
                    SupervisorSource::Synthesized {
                        plants,
                        specs,
                        minimized: s.minimize,
                    },
                    origins,
                ))
            }
        }
    }

    /// Picks the supervisor among a file's components.
    fn select(
        &self,
        mut components: Vec<Component>,
        wanted: Option<&Name>,
        path: &Path,
        file_span: &Range<usize>,
    ) -> Result<Automaton> {
        let listing = |components: &[Component]| {
            components
                .iter()
                .map(|c| format!("`{}` ({})", c.automaton.name(), c.kind))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if let Some(name) = wanted {
            return match components
                .iter()
                .position(|c| c.automaton.name() == name.get_ref())
            {
                Some(i) => Ok(components.swap_remove(i).automaton),
                None => Err(self.error(
                    &name.span(),
                    format!(
                        "`{}` has no component `{}` (components: {})",
                        path.display(),
                        name.get_ref(),
                        listing(&components)
                    ),
                )),
            };
        }
        let candidates: Vec<usize> = components
            .iter()
            .enumerate()
            .filter(|(_, c)| matches!(c.kind, Kind::Supervisor | Kind::Spec | Kind::Unspecified))
            .map(|(i, _)| i)
            .collect();
        match candidates.as_slice() {
            [i] => Ok(components.swap_remove(*i).automaton),
            [] => Err(self.error(
                file_span,
                format!(
                    "`{}` holds no supervisor, spec or unspecified component (components: {}); name the one to run with `component = \"…\"`",
                    path.display(),
                    listing(&components)
                ),
            )),
            _ => Err(self.error(
                file_span,
                format!(
                    "`{}` holds several components that could be the supervisor ({}); name one with `component = \"…\"`",
                    path.display(),
                    listing(&components)
                ),
            )),
        }
    }

    fn supervisor(
        &mut self,
        sup: &Spanned<RawSupervisor>,
        events: &[Event],
        event_index: &HashMap<String, usize>,
        event_spans: &[Range<usize>],
    ) -> Result<Supervisor> {
        let header = sup.span();
        let raw = sup.get_ref();
        let (automaton, source, origins) = self.load(sup)?;
        let (name, name_span) = match &raw.name {
            Some(n) => (n.get_ref().clone(), n.span()),
            None => (automaton.name().to_owned(), header.clone()),
        };
        self.claim("supervisor", &name, &name_span)?;
        let described = match &source {
            SupervisorSource::File(p) => format!("supervisor `{name}` (`{}`)", p.display()),
            SupervisorSource::Synthesized { .. } => format!("synthesised supervisor `{name}`"),
        };
        if automaton.is_empty() {
            return Err(self.error(&header, format!("{described} has no states")));
        }
        if automaton.initial().is_none() {
            return Err(self.error(&header, format!("{described} has no initial state")));
        }

        let alphabet = automaton.alphabet();
        let mut local_events: Vec<(usize, EventId)> = Vec::with_capacity(alphabet.len());
        for (id, e) in alphabet.iter() {
            let Some(&g) = event_index.get(&e.name) else {
                let whose = match source {
                    SupervisorSource::File(_) => None,
                    SupervisorSource::Synthesized { .. } => {
                        origins.iter().find(|o| o.alphabet.contains(&e.name))
                    }
                }
                .map(|o| format!(" (from `{}` in `{}`)", o.name, o.file.display()))
                .unwrap_or_default();
                return Err(self.error(
                    &header,
                    format!(
                        "event `{}` of {described}{whose} is not declared in [events]",
                        e.name
                    ),
                ));
            };
            local_events.push((g, id));
        }
        local_events.sort_by_key(|&(g, _)| g);

        // Controllability against every source that states it.
        for &(g, _) in &local_events {
            let event = &events[g];
            for o in origins
                .iter()
                .filter(|o| o.alphabet.controllability_stated())
            {
                let Some(id) = o.alphabet.id(&event.name) else {
                    continue;
                };
                let theirs = o.alphabet.is_controllable(id);
                if theirs != event.controllable {
                    let word = |c: bool| if c { "controllable" } else { "uncontrollable" };
                    let model = match source {
                        SupervisorSource::File(_) => described.clone(),
                        SupervisorSource::Synthesized { .. } => format!(
                            "`{}` (`{}`), a model of {described}",
                            o.name,
                            o.file.display()
                        ),
                    };
                    return Err(self.error(
                        &event_spans[g],
                        format!(
                            "event `{}` is {} here but {} in {model}",
                            event.name,
                            word(event.controllable),
                            word(theirs),
                        ),
                    ));
                }
            }
        }

        Ok(Supervisor {
            name,
            automaton,
            local_events,
            source,
            line: self.line(&header),
        })
    }

    fn state_map(
        &self,
        output: &Name,
        map: &Spanned<Entries<Names>>,
        supervisors: &[Supervisor],
        supervisor_index: &HashMap<String, usize>,
    ) -> Result<Vec<(usize, Vec<StateId>)>> {
        let out = output.get_ref();
        if map.get_ref().0.is_empty() {
            return Err(self.error(
                &map.span(),
                format!("the state map of output `{out}` names no state; a state map must name at least one state"),
            ));
        }
        let mut entries = Vec::new();
        for (sup_name, states) in &map.get_ref().0 {
            let j = self.resolve(supervisor_index, "supervisor", "[supervisor]", sup_name)?;
            let sup = &supervisors[j];
            let list = names(Some(states));
            if list.is_empty() {
                return Err(self.error(
                    &states.span(),
                    format!(
                        "the state map of output `{out}` lists no state of supervisor `{}`; a state map must name at least one state",
                        sup.name
                    ),
                ));
            }
            let mut ids: Vec<StateId> = Vec::with_capacity(list.len());
            for state in &list {
                let id = sup
                    .automaton
                    .state_by_name(state.get_ref())
                    .ok_or_else(|| {
                        self.error(
                            &state.span(),
                            format!(
                                "supervisor `{}` has no state `{}`",
                                sup.name,
                                state.get_ref()
                            ),
                        )
                    })?;
                if !ids.contains(&id) {
                    ids.push(id);
                }
            }
            entries.push((j, ids));
        }
        Ok(entries)
    }
}

/// The name indices an event's declaration is resolved against.
struct Env<'a> {
    inputs: &'a HashMap<String, usize>,
    outputs: &'a HashMap<String, usize>,
    timers: &'a HashMap<String, usize>,
    switches: &'a HashMap<String, usize>,
    switch_list: &'a [Switch],
}

#[cfg(test)]
mod tests {
    //! Rules that need no model file; the rest are in `tests/project.rs`.

    use super::super::{from_str, Action, Drive, Project, Trigger};
    use std::path::Path;

    fn load(text: &str) -> crate::Result<Project> {
        from_str(text, Path::new("dir/p.plc.toml"))
    }

    const HEAD: &str = "[plc]\nname = \"local\"\n";

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

    #[test]
    fn defaults_fill_what_the_file_leaves_out() {
        let p = load(&format!("{HEAD}[inputs]\ni = {{}}\n[outputs]\no = {{}}\n")).unwrap();
        assert_eq!(p.scan_period_ms, 10);
        assert_eq!(p.max_commands_per_scan, 1);
        assert_eq!(p.unexpected, super::Unexpected::Fault);
        assert_eq!(p.reset, None);
        assert_eq!(p.overrun_limit, 1);
        assert!(!p.overrun_fault && !p.lost_edge_fault);
        assert_eq!(p.inputs[0].debounce_scans, 0);
        assert!(!p.outputs[0].safe);
        assert_eq!(p.outputs[0].drive, Drive::Actions { initial: false });
    }

    #[test]
    fn switches_share_the_namespace() {
        let err = load(&format!(
            "{HEAD}[outputs]\nvalve = {{}}\n[switches]\nVALVE = {{ on = \"valve\" }}\n"
        ))
        .unwrap_err()
        .to_string();
        assert!(
            err.starts_with("dir/p.plc.toml:6:1: switch `VALVE` and output `valve` (line 4)"),
            "{err}"
        );
    }

    #[test]
    fn an_output_driven_by_nothing_is_a_warning() {
        let p = load(&format!(
            "{HEAD}\n[outputs]\nspare = {{ initial = true }}\n"
        ))
        .unwrap();
        assert_eq!(p.warnings.len(), 1);
        assert_eq!(p.warnings[0].line, 5);
        assert!(p.warnings[0].message.contains("driven by nothing"));
        assert_eq!(p.outputs[0].drive, Drive::Actions { initial: true });
    }

    #[test]
    fn an_input_both_required_and_forbidden_is_a_warning() {
        let p = load(&format!(
            "{HEAD}[inputs]\na = {{}}\nb = {{}}\n[outputs]\no = {{}}\n[events]\ne = {{ rising = \"a\", when = [\"b\"],\n  unless = [\"b\"], set = [\"o\"] }}\n"
        ))
        .unwrap();
        assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
        assert_eq!(p.warnings[0].line, 10);
        assert!(p.warnings[0].message.contains("can never occur"));
    }

    #[test]
    fn several_events_may_share_a_source() {
        let p = load(&format!(
            "{HEAD}[inputs]\nx = {{}}\nmode = {{}}\n[outputs]\no = {{}}\n[timers]\nt = {{ preset_ms = 5 }}\n[events]\nstart = {{ rising = \"x\", start = [\"t\"] }}\nlate = {{ expired = \"t\", when = [\"mode\"], set = \"o\" }}\nearly = {{ expired = \"t\", unless = [\"mode\"], clear = \"o\" }}\n"
        ))
        .unwrap();
        assert_eq!(p.events[1].trigger, Trigger::Expired(0));
        assert_eq!(p.events[2].trigger, Trigger::Expired(0));
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    }

    #[test]
    fn duplicate_actions_collapse() {
        let p = load(&format!(
            "{HEAD}[inputs]\nx = {{}}\n[outputs]\no = {{}}\n[events]\ne = {{ rising = \"x\", set = [\"o\", \"o\"] }}\n"
        ))
        .unwrap();
        assert_eq!(p.events[0].actions, [Action::Set(0)]);
    }
}
