//! Conformance of the generated programs with the scan-cycle semantics.
//!
//! # What is tested
//!
//! For random valid projects and random input sequences, three
//! interpreters run side by side, scan by scan:
//!
//! - the **table backend** ([`TableImage`]) in the executor's [`Controller`],
//! - the **logic backend** ([`LogicImage`], minimised CMSSM covers) in the
//!   same controller,
//! - a **reference interpreter** ([`Reference`]) kept here, in test code.
//!
//! Every scan record must agree field by field (scan number, time,
//! executed events in order, unexpected events, state vector, output
//! image, fault cause), and so must the count of ignored events at the
//! end. Independently of all three interpreters, every scan is also checked
//! for **control equivalence** against the source automata
//! ([`check_control`]): replaying the executed events from the pre-scan
//! state vector with [`codegen::Automaton::successor`] must find every event defined
//! in every supervisor that has it (so no executed controllable event was
//! disabled) and must land on the recorded state vector (no supervisor
//! moves except along a defined transition, or back to its initial state in
//! a reset scan).
//!
//! # How the reference follows docs/semantics.md
//!
//! The reference is written from `docs/semantics.md` alone,
//! with plain `Vec`s and one hash map of transitions per supervisor, and
//! works on the [`Project`] model directly (never on the executor's
//! `Config`). One method per numbered rule of "One scan":
//!
//! 1. [`Reference::sample`]: debounce (`d > 1` consecutive differing scans,
//!    this one included), edges between F\[k-1\] and F\[k\]; scan 0 has no
//!    edges.
//! 2. [`Reference::fault_mode`]: in fault mode only a rising edge of the
//!    `reset` input does anything (re-initialise, fault cause cleared in
//!    that very record); otherwise the safe image.
//! 3. [`Reference::expire_timers`]: wrap-safe `deadline <= t`; expiry stops
//!    the timer; `start` sets `deadline = t + preset`.
//! 4. [`Reference::uncontrollable_phase`]: occurred events (edges of the OR
//!    of the bound inputs, expiries, with `when`/`unless` on F\[k\]) in
//!    declaration order; feasible ones execute (events in no alphabet are
//!    always feasible); an unexpected one faults (its actions never apply,
//!    events before it stay executed) or is counted and traced under
//!    `ignore`.
//! 5. [`Reference::controllable_phase`]: up to `max_commands_per_scan`
//!    times (0: no limit) the first controllable event in declaration order
//!    that is feasible, not yet executed in this scan, and whose `request`
//!    input is 1 in F\[k\].
//! 6. [`Reference::output_image`]: latched action-driven levels, Moore
//!    outputs as the OR over their state map, the safe image in fault mode.
//! 7. [`Record`]: the trace record.
//!
//! Where docs/semantics.md is silent the reference makes one choice, stated
//! here: the filtered value of a debounced input at scan 0 is its raw
//! sample (the filter has no history yet; F\[-1\] = F\[0\] then makes scan 0
//! edge-free, as rule 1 requires).
//!
//! The reference itself is pinned by two hand-computed traces
//! ([`reference_follows_a_hand_computed_trace`],
//! [`reference_runs_commands_of_modular_supervisors`]) and by a time-shift
//! test across the u32 wrap-around
//! ([`reference_trace_is_invariant_under_clock_wrap`]); the control check
//! by [`control_check_rejects_what_the_supervisors_forbid`].
//!
//! # Random projects and runs
//!
//! A narrow project ([`NARROW`]) has 2–5 inputs (debounce 0–3, usually
//! one of them the `reset` input), 0–3 timers (presets a multiple of the
//! scan period or any 1–80 ms), 1–5 outputs (action-driven or Moore), 2–8
//! events (about 40 % controllable, some with a request input; the others
//! bound to the rising or falling edge of the OR of 1–3 inputs or to a
//! timer expiry, some with `when`/`unless`), 0–3 actions per event, 1–4
//! deterministic supervisors with random partial transition functions over
//! random, overlapping alphabets, `max_commands_per_scan` 0–3 and either
//! unexpected-event policy. [`ProjectSpec`] is plain data whose references
//! are [`proptest::sample::Index`]es, resolved modulo the current counts
//! by [`ProjectSpec::build`], so any shrunk value still builds a valid
//! project (the rules of `project::validate`: controllability agrees with
//! the automata, every controllable event is in some alphabet, an output
//! is driven by actions or a state map, never both, no event sets and
//! clears one output, actions are ordered clears, sets, resets, starts,
//! only controllable events have a request input).
//!
//! A run ([`RunSpec`]) is 20–200 scans, one period apart with occasional
//! jitter or jumps, starting near 0 or (one run in four) just before the
//! u32 clock wraps; before each scan usually nothing or one input flips.
//! [`random_runs_exercise_every_rule`] checks that these generators really
//! execute every kind of event, enter and leave fault mode, ignore events
//! and wrap the clock.
//!
//! # Wide projects
//!
//! The executor keeps input images and event sets as 32-bit words and
//! reads a supervisor's enabled events in rows of up to 32 local events;
//! a narrow project fits in one word everywhere. A wide project ([`WIDE`])
//! is built the same way but has 33–70 inputs and 33–70 events, so inputs
//! and events 31, 32 and 33 always exist and every set spans two or three
//! words. Each of its supervisors (1–8 states, about 80 % of the (state,
//! event) pairs defined) has a few picked events, many (usually more than
//! 32, read in two or three slices) or every event; before each scan of
//! its run any of the 70 inputs a wide project can have may flip.
//! [`wide_runs_cross_every_word_boundary`] checks that events, commands
//! and request inputs past the first word are executed and used, that
//! inputs past the first word alone make edges, that supervisors move on
//! local events past the first slice of their rows, and that these runs
//! still reach every rule.
//!
//! 8,500 cases have narrow projects with supervisors of 1–12 states and
//! 1,500 with 13–50 states (CMSSM synthesis, which runs on every case,
//! dominates their run time); 200 cases have wide projects (each costs
//! about as much as fifteen narrow ones, mostly the logic backend
//! evaluating its covers for every local event when a state changes).

use codegen::automaton::{EventId, StateId};
use codegen::image::{LogicImage, TableImage};
use codegen::project::{
    Action, Drive, Event, Input, Net, NetSource, Origin, Output, Project, Supervisor,
    SupervisorSource, Timer, Trigger, Unexpected,
};
use codegen::AutomatonBuilder;
use executor::memory::HeapMemory;
use executor::{Controller, Fault, Program, ScanRecord};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::Index as Pick;
use proptest::test_runner::{RngAlgorithm, TestCaseError};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt::Debug;
use std::ops::RangeInclusive;
use std::path::PathBuf;

// ---------------------------------------------------------------------------
// Trace records
// ---------------------------------------------------------------------------

/// Why a scan is in fault mode, as comparable data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Cause {
    /// An unexpected uncontrollable event (global index).
    Unexpected(usize),
    /// Any other executor fault (the reference never produces one).
    Other(Fault),
}

impl From<Fault> for Cause {
    fn from(fault: Fault) -> Cause {
        match fault {
            Fault::Unexpected { event } => Cause::Unexpected(usize::from(event)),
            other => Cause::Other(other),
        }
    }
}

/// One scan's trace record (docs/semantics.md, step 7), owned.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Record {
    scan: u32,
    time_ms: u32,
    executed: Vec<usize>,
    unexpected: Vec<usize>,
    states: Vec<u32>,
    outputs: Vec<bool>,
    fault: Option<Cause>,
}

impl From<ScanRecord<'_>> for Record {
    fn from(r: ScanRecord<'_>) -> Record {
        Record {
            scan: r.scan,
            time_ms: r.time_ms,
            executed: r.executed.iter().map(|&e| usize::from(e)).collect(),
            unexpected: r.unexpected.iter().map(|&e| usize::from(e)).collect(),
            states: r.states.to_vec(),
            outputs: r.outputs.to_vec(),
            fault: r.fault.map(Cause::from),
        }
    }
}

// ---------------------------------------------------------------------------
// Reference interpreter
// ---------------------------------------------------------------------------

/// The reference interpreter: a straightforward reading of docs/semantics.md
/// over the [`Project`] model (see the module docs for the rule map).
struct Reference<'p> {
    project: &'p Project,
    /// δj per supervisor: (state, global event) → target.
    delta: Vec<HashMap<(u32, usize), u32>>,
    /// For each global event, the supervisors with it in their alphabet.
    members: Vec<Vec<usize>>,
    /// The marking of every Petri net, place by place.
    markings: Vec<Vec<u32>>,
    /// Initial state of every supervisor.
    initial: Vec<u32>,
    /// Number of the next scan.
    scan: u32,
    /// Filtered input image F\[k\].
    filtered: Vec<bool>,
    /// Consecutive scans the raw value has differed from the filtered one.
    differing: Vec<u8>,
    /// Deadline of every running timer.
    deadlines: Vec<Option<u32>>,
    /// Levels of the action-driven outputs.
    latched: Vec<bool>,
    /// The state vector.
    states: Vec<u32>,
    /// The fault cause while in fault mode.
    fault: Option<Cause>,
    /// Unexpected events dropped under policy `ignore`.
    ignored: u32,
}

impl<'p> Reference<'p> {
    fn new(project: &'p Project) -> Self {
        let delta = project
            .supervisors
            .iter()
            .map(|sup| {
                let global: HashMap<EventId, usize> =
                    sup.local_events.iter().map(|&(g, id)| (id, g)).collect();
                sup.automaton
                    .iter_transitions()
                    .map(|(s, e, t)| ((s.0, global[&e]), t.0))
                    .collect()
            })
            .collect();
        let mut members = vec![Vec::new(); project.events.len()];
        for (j, sup) in project.supervisors.iter().enumerate() {
            for &(g, _) in &sup.local_events {
                members[g].push(j);
            }
        }
        let mut reference = Reference {
            project,
            delta,
            members,
            markings: Vec::new(),
            // The automata's; the nets' markings are kept apart.
            initial: initial_states(project)[..project.supervisors.len()].to_vec(),
            scan: 0,
            filtered: vec![false; project.inputs.len()],
            differing: vec![0; project.inputs.len()],
            deadlines: Vec::new(),
            latched: Vec::new(),
            states: Vec::new(),
            fault: None,
            ignored: 0,
        };
        reference.reinitialise();
        reference
    }

    /// Supervisors to their initial states, timers stopped, action-driven
    /// outputs to their initial levels, no fault (rule 2).
    fn reinitialise(&mut self) {
        self.states = self.initial.clone();
        self.markings = self
            .project
            .nets
            .iter()
            .map(|n| n.net.initial().clone())
            .collect();
        self.deadlines = vec![None; self.project.timers.len()];
        self.latched = self
            .project
            .outputs
            .iter()
            .map(|o| matches!(o.drive, Drive::Actions { initial: true }))
            .collect();
        self.fault = None;
    }

    /// One scan at time `now` with the raw input image `raw`.
    fn scan(&mut self, now: u32, raw: &[bool]) -> Record {
        let previous = self.sample(raw);
        let mut record = Record {
            scan: self.scan,
            time_ms: now,
            executed: Vec::new(),
            unexpected: Vec::new(),
            states: Vec::new(),
            outputs: Vec::new(),
            fault: None,
        };
        if self.fault.is_some() {
            self.fault_mode(&previous);
        } else {
            let expired = self.expire_timers(now);
            let occurred = self.occurred(&previous, &expired);
            self.uncontrollable_phase(now, &occurred, &mut record);
            if self.fault.is_none() {
                self.controllable_phase(now, &mut record);
            }
        }
        record.states = self.states.clone();
        for (net, marking) in self.project.nets.iter().zip(&self.markings) {
            record.states.extend(pack_marking(net, marking));
        }
        record.outputs = self.output_image();
        record.fault = self.fault;
        self.scan += 1;
        record
    }

    /// Rule 1: samples and debounces `raw` into F\[k\]; returns F\[k-1\].
    fn sample(&mut self, raw: &[bool]) -> Vec<bool> {
        if self.scan == 0 {
            // The filter has no history: F[0] is the raw sample and
            // F[-1] = F[0], so scan 0 has no edges.
            self.filtered = raw.to_vec();
            return self.filtered.clone();
        }
        let previous = self.filtered.clone();
        for (i, &value) in raw.iter().enumerate() {
            self.debounce(i, value);
        }
        previous
    }

    /// Rule 1: the filtered value follows `value` once it has differed for
    /// `d` consecutive scans (`d` ≤ 1: at once).
    fn debounce(&mut self, i: usize, value: bool) {
        if value == self.filtered[i] {
            self.differing[i] = 0;
            return;
        }
        self.differing[i] += 1;
        if self.differing[i] >= self.project.inputs[i].debounce_scans {
            self.filtered[i] = value;
            self.differing[i] = 0;
        }
    }

    /// Rule 2: a rising edge of `reset` re-initialises; otherwise nothing
    /// changes (the safe image is written by [`Reference::output_image`]).
    fn fault_mode(&mut self, previous: &[bool]) {
        if let Some(r) = self.project.reset {
            if self.filtered[r] && !previous[r] {
                self.reinitialise();
            }
        }
    }

    /// Rule 3: stops every timer whose deadline is reached (wrap-safe) and
    /// reports which expired.
    fn expire_timers(&mut self, now: u32) -> Vec<bool> {
        self.deadlines
            .iter_mut()
            .map(|deadline| match *deadline {
                Some(d) if reached(d, now) => {
                    *deadline = None;
                    true
                }
                _ => false,
            })
            .collect()
    }

    /// Rule 4: the uncontrollable events that occur in this scan, in
    /// declaration order.
    fn occurred(&self, previous: &[bool], expired: &[bool]) -> Vec<usize> {
        let now = &self.filtered;
        let any = |list: &[usize], image: &[bool]| list.iter().any(|&i| image[i]);
        (0..self.project.events.len())
            .filter(|&e| {
                let ev = &self.project.events[e];
                let source = match &ev.trigger {
                    Trigger::Command => false,
                    Trigger::Rising(list) => any(list, now) && !any(list, previous),
                    Trigger::Falling(list) => !any(list, now) && any(list, previous),
                    Trigger::Expired(t) => expired[*t],
                };
                source && ev.when.iter().all(|&i| now[i]) && ev.unless.iter().all(|&i| !now[i])
            })
            .collect()
    }

    /// Feasibility: every supervisor having `e` has a transition on it.
    fn feasible(&self, e: usize) -> bool {
        self.members[e]
            .iter()
            .all(|&j| self.delta[j].contains_key(&(self.states[j], e)))
            && self
                .project
                .nets
                .iter()
                .zip(&self.markings)
                .all(|(net, m)| {
                    transition_of(net, e).is_none_or(|t| {
                        net.net.transitions()[t]
                            .input
                            .iter()
                            .all(|&(p, w)| m[p] >= w)
                    })
                })
    }

    /// Executes a feasible event: members move, actions apply.
    fn execute(&mut self, e: usize, now: u32, record: &mut Record) {
        for &j in &self.members[e] {
            self.states[j] = self.delta[j][&(self.states[j], e)];
        }
        for (net, m) in self.project.nets.iter().zip(&mut self.markings) {
            if let Some(t) = transition_of(net, e) {
                let tr = &net.net.transitions()[t];
                for &(p, w) in &tr.input {
                    m[p] -= w;
                }
                for &(p, w) in &tr.output {
                    m[p] += w;
                }
            }
        }
        for action in &self.project.events[e].actions {
            match *action {
                Action::Set(o) => self.latched[o] = true,
                Action::Clear(o) => self.latched[o] = false,
                Action::Start(t) => {
                    let preset = self.project.timers[t].preset_ms;
                    self.deadlines[t] = Some(now.wrapping_add(preset));
                }
                Action::Reset(t) => self.deadlines[t] = None,
            }
        }
        record.executed.push(e);
    }

    /// Rule 4: occurred events in declaration order, each once.
    fn uncontrollable_phase(&mut self, now: u32, occurred: &[usize], record: &mut Record) {
        for &e in occurred {
            if self.feasible(e) {
                self.execute(e, now, record);
                continue;
            }
            record.unexpected.push(e);
            match self.project.unexpected {
                Unexpected::Fault => {
                    self.fault = Some(Cause::Unexpected(e));
                    return;
                }
                Unexpected::Ignore => self.ignored += 1,
            }
        }
    }

    /// Rule 5: commands, first eligible in declaration order each time.
    fn controllable_phase(&mut self, now: u32, record: &mut Record) {
        let limit = match self.project.max_commands_per_scan {
            0 => usize::MAX,
            n => usize::from(n),
        };
        let mut done = vec![false; self.project.events.len()];
        for _ in 0..limit {
            let Some(e) = (0..done.len()).find(|&e| !done[e] && self.eligible(e)) else {
                break;
            };
            done[e] = true;
            self.execute(e, now, record);
        }
    }

    /// Rule 5: a controllable, feasible event whose request input (if
    /// any) is 1.
    fn eligible(&self, e: usize) -> bool {
        let ev = &self.project.events[e];
        ev.controllable && ev.request.is_none_or(|r| self.filtered[r]) && self.feasible(e)
    }

    /// Rule 6 (and the safe image of rules 2 and 4).
    fn output_image(&self) -> Vec<bool> {
        self.project
            .outputs
            .iter()
            .enumerate()
            .map(|(o, out)| match (&self.fault, &out.drive) {
                (Some(_), _) => out.safe,
                (None, Drive::Actions { .. }) => self.latched[o],
                (None, Drive::States(map)) => map
                    .iter()
                    .any(|(j, listed)| listed.contains(&StateId(self.states[*j]))),
                (None, Drive::Places(map)) => map
                    .iter()
                    .any(|(n, places)| places.iter().any(|&p| self.markings[*n][p] > 0)),
            })
            .collect()
    }
}

/// Wrap-safe `deadline <= now` on the u32 millisecond clock (rule 1:
/// "all time comparisons are wrap-safe"; presets stay below 2^31).
fn reached(deadline: u32, now: u32) -> bool {
    (now.wrapping_sub(deadline) as i32) >= 0
}

/// The initial state vector of `project`.
fn initial_states(project: &Project) -> Vec<u32> {
    let mut states: Vec<u32> = project
        .supervisors
        .iter()
        .map(|s| s.automaton.initial().expect("initial state").0)
        .collect();
    for net in &project.nets {
        states.extend(pack_marking(net, net.net.initial()));
    }
    states
}

/// The transition of `net` that is event `e`, if any.
fn transition_of(net: &Net, e: usize) -> Option<usize> {
    net.events.iter().position(|&g| g == e)
}

/// `marking` as the states of `net`'s groups: each place's count at its
/// counter's shift (docs/formats.md, "[[net]]").
fn pack_marking(net: &Net, marking: &[u32]) -> Vec<u32> {
    let mut groups = vec![0u32; net.groups()];
    for (p, field) in net.fields.iter().enumerate() {
        groups[field.group] |= marking[p] << field.shift;
    }
    groups
}

/// The marking of `net` from its groups' states.
fn unpack_marking(net: &Net, groups: &[u32]) -> Vec<u32> {
    net.fields
        .iter()
        .map(|f| (groups[f.group] >> f.shift) & ((1 << f.width) - 1))
        .collect()
}

// ---------------------------------------------------------------------------
// Comparison and control equivalence
// ---------------------------------------------------------------------------

/// Fails with scan, field and the three values unless they agree.
fn agree<T: PartialEq + Debug>(
    scan: usize,
    field: &str,
    reference: &T,
    table: &T,
    logic: &T,
) -> Result<(), TestCaseError> {
    if reference == table && reference == logic {
        return Ok(());
    }
    Err(TestCaseError::fail(format!(
        "scan {scan}, field `{field}`: reference = {reference:?}, table = {table:?}, logic = {logic:?}"
    )))
}

/// Compares one scan record of the three interpreters, field by field.
fn compare(scan: usize, r: &Record, t: &Record, l: &Record) -> Result<(), TestCaseError> {
    agree(scan, "scan", &r.scan, &t.scan, &l.scan)?;
    agree(scan, "time_ms", &r.time_ms, &t.time_ms, &l.time_ms)?;
    agree(scan, "executed", &r.executed, &t.executed, &l.executed)?;
    agree(
        scan,
        "unexpected",
        &r.unexpected,
        &t.unexpected,
        &l.unexpected,
    )?;
    agree(scan, "states", &r.states, &t.states, &l.states)?;
    agree(scan, "outputs", &r.outputs, &t.outputs, &l.outputs)?;
    agree(scan, "fault", &r.fault, &t.fault, &l.fault)
}

/// Control equivalence of one scan, against the source automata only:
/// replayed in order from the pre-scan state vector `before`, every
/// executed event must be defined, in the state vector it was executed in,
/// by every supervisor having it (Leduc–Wonham: only allowed commands are
/// issued), and the replay must end on the recorded state vector (no
/// supervisor moves otherwise).
fn check_control(
    project: &Project,
    scan: usize,
    before: &[u32],
    was_faulted: bool,
    record: &Record,
) -> Result<(), TestCaseError> {
    let outcome = if was_faulted {
        check_fault_scan(project, before, record)
    } else {
        replay(project, before, &record.executed).and_then(|x| {
            if x == record.states {
                Ok(())
            } else {
                Err(format!(
                    "states {:?} do not follow from {before:?} by the executed events {:?} (expected {x:?})",
                    record.states, record.executed
                ))
            }
        })
    };
    outcome.map_err(|why| TestCaseError::fail(format!("scan {scan}: {why}")))
}

/// A scan that starts in fault mode executes nothing and either keeps the
/// state vector or resets it.
fn check_fault_scan(project: &Project, before: &[u32], record: &Record) -> Result<(), String> {
    if !record.executed.is_empty() {
        return Err(format!("executed {:?} in fault mode", record.executed));
    }
    if record.states != before && record.states != initial_states(project) {
        return Err(format!(
            "states {before:?} -> {:?} in fault mode (neither kept nor reset)",
            record.states
        ));
    }
    Ok(())
}

/// The state vector after `executed` from `before`, moving along
/// [`codegen::Automaton::successor`]; an error names the first event some
/// supervisor having it does not allow.
fn replay(project: &Project, before: &[u32], executed: &[usize]) -> Result<Vec<u32>, String> {
    let mut x = before.to_vec();
    for &e in executed {
        for (j, sup) in project.supervisors.iter().enumerate() {
            let Some(&(_, id)) = sup.local_events.iter().find(|&&(g, _)| g == e) else {
                continue;
            };
            let next = sup.automaton.successor(StateId(x[j]), id).ok_or_else(|| {
                let kind = if project.events[e].controllable {
                    "controllable"
                } else {
                    "uncontrollable"
                };
                format!(
                    "executed {kind} event {e} is undefined in supervisor {j} at state {}",
                    x[j]
                )
            })?;
            x[j] = next.0;
        }
        let mut first = project.supervisors.len();
        for net in &project.nets {
            let groups = first..first + net.groups();
            first = groups.end;
            let Some(t) = transition_of(net, e) else {
                continue;
            };
            let marking = unpack_marking(net, &x[groups.clone()]);
            let next = net.net.fire(&marking, t).ok_or_else(|| {
                format!(
                    "executed event {e} is transition {t} of net `{}`, not enabled in {marking:?}",
                    net.name
                )
            })?;
            x.splice(groups, pack_marking(net, &next));
        }
    }
    Ok(x)
}

/// Runs `samples` (time, raw input image) through the reference and both
/// backends, comparing every scan and checking control equivalence.
fn check_run(project: &Project, samples: &[(u32, Vec<bool>)]) -> Result<(), TestCaseError> {
    let table = TableImage::new(project).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let mut by_table = Controller::new(&table, HeapMemory::for_config(&table.config()))
        .map_err(|e| TestCaseError::fail(format!("table controller: {e:?}")))?;
    // Petri nets run on the table backend only: then its twin stands in
    // for the logic backend.
    let logic = if project.nets.is_empty() {
        Some(LogicImage::new(project).map_err(|e| TestCaseError::fail(e.to_string()))?)
    } else {
        None
    };
    let twin = TableImage::new(project).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let mut by_logic: Controller<&dyn Program, _> = match &logic {
        Some(logic) => Controller::new(
            logic as &dyn Program,
            HeapMemory::for_config(&logic.config()),
        ),
        None => Controller::new(
            &twin as &dyn Program,
            HeapMemory::for_config(&twin.config()),
        ),
    }
    .map_err(|e| TestCaseError::fail(format!("logic controller: {e:?}")))?;
    let mut reference = Reference::new(project);
    let mut before = initial_states(project);
    let mut was_faulted = false;
    for (k, (now, raw)) in samples.iter().enumerate() {
        let r = reference.scan(*now, raw);
        let t = Record::from(by_table.scan(*now, raw));
        let l = Record::from(by_logic.scan(*now, raw));
        compare(k, &r, &t, &l)?;
        // The three records are equal now: checking one checks all.
        check_control(project, k, &before, was_faulted, &t)?;
        before = t.states;
        was_faulted = t.fault.is_some();
    }
    let last = samples.len();
    agree(
        last,
        "counters.ignored (after the last scan)",
        &reference.ignored,
        &by_table.counters().ignored,
        &by_logic.counters().ignored,
    )
}

// ---------------------------------------------------------------------------
// Random projects
// ---------------------------------------------------------------------------

/// Members per word of the executor's input images and event sets.
const WORD: usize = 32;

/// How many inputs and events the projects of a family have.
struct Shape {
    /// Inputs; the largest count is also the bits of an input flip mask.
    inputs: RangeInclusive<usize>,
    /// Events; the largest count is also the transition slots per state.
    events: RangeInclusive<usize>,
}

/// The first two families: every input image and event set fits in one
/// word.
const NARROW: Shape = Shape {
    inputs: 2..=5,
    events: 2..=8,
};

/// The wide family: input images and event sets of two or three words, so
/// that inputs and events 31, 32 and 33 always exist.
const WIDE: Shape = Shape {
    inputs: 33..=70,
    events: 33..=70,
};

// A wide flip mask is a u128.
const _: () = assert!(*WIDE.inputs.end() <= 128);

/// A timer preset: a multiple of the scan period or any small value.
#[derive(Debug, Clone, Copy)]
enum PresetSpec {
    Periods(u32),
    Millis(u32),
}

/// How an output is driven.
#[derive(Debug, Clone)]
enum DriveSpec {
    Actions {
        initial: bool,
    },
    /// (supervisor, states) entries of a state map.
    States(Vec<(Pick, Vec<Pick>)>),
}

/// An output: safe level and drive.
#[derive(Debug, Clone)]
struct OutputSpec {
    safe: bool,
    drive: DriveSpec,
}

/// The source of an uncontrollable event.
#[derive(Debug, Clone)]
enum TriggerSpec {
    Rising(Vec<Pick>),
    Falling(Vec<Pick>),
    /// A timer; the input is the fallback source when there are no timers.
    Expired(Pick, Pick),
}

/// An action; outputs are picked among the action-driven ones, and
/// timer actions are dropped when there are no timers.
#[derive(Debug, Clone, Copy)]
enum ActionSpec {
    Set(Pick),
    Clear(Pick),
    Start(Pick),
    Reset(Pick),
}

/// An event; a controllable one ignores `trigger`, `when` and `unless`,
/// an uncontrollable one ignores `request`.
#[derive(Debug, Clone)]
struct EventSpec {
    controllable: bool,
    operator: bool,
    trigger: TriggerSpec,
    when: Vec<Pick>,
    unless: Vec<Pick>,
    request: Option<Pick>,
    actions: Vec<ActionSpec>,
}

/// The events a supervisor has, before more are added so that every
/// controllable event is in some alphabet.
#[derive(Debug, Clone)]
enum AlphabetSpec {
    /// The picked events.
    Picked(Vec<Pick>),
    /// Every event of the project.
    Every,
}

/// A supervisor: alphabet, initial state and transition rows.
#[derive(Debug, Clone)]
struct SupervisorSpec {
    alphabet: AlphabetSpec,
    initial: Pick,
    /// One row per state: the target on the i-th event of the (sorted)
    /// alphabet, if defined.
    rows: Vec<Vec<Option<Pick>>>,
}

/// A random project before it is built (see the module docs).
#[derive(Debug, Clone)]
struct ProjectSpec {
    scan_period_ms: u32,
    max_commands_per_scan: u16,
    unexpected: Unexpected,
    reset: Option<Pick>,
    /// The background image test's share per scan: a few words, so that
    /// passes complete (and compare) many times in a run.
    rom_test_bytes_per_scan: u16,
    debounce: Vec<u8>,
    timers: Vec<PresetSpec>,
    outputs: Vec<OutputSpec>,
    events: Vec<EventSpec>,
    supervisors: Vec<SupervisorSpec>,
}

/// `picks` resolved into `0..len`, duplicates dropped, order kept.
fn resolve(picks: &[Pick], len: usize) -> Vec<usize> {
    let mut out = Vec::new();
    for p in picks {
        let i = p.index(len);
        if !out.contains(&i) {
            out.push(i);
        }
    }
    out
}

impl ProjectSpec {
    /// The project this spec describes; valid by construction.
    fn build(&self) -> Project {
        let inputs = self.build_inputs();
        let timers = self.build_timers();
        let outputs = self.build_outputs();
        let action_driven: Vec<usize> = (0..outputs.len())
            .filter(|&o| matches!(outputs[o].drive, Drive::Actions { .. }))
            .collect();
        let sizes = Sizes {
            inputs: inputs.len(),
            timers: timers.len(),
            action_driven: &action_driven,
        };
        let events: Vec<Event> = self
            .events
            .iter()
            .enumerate()
            .map(|(e, spec)| build_event(e, spec, &sizes))
            .collect();
        let supervisors = self.build_supervisors(&events);
        Project {
            path: PathBuf::from("random.plc.toml"),
            name: "random".to_owned(),
            scan_period_ms: self.scan_period_ms,
            max_commands_per_scan: self.max_commands_per_scan,
            unexpected: self.unexpected,
            reset: self.reset.map(|r| r.index(inputs.len())),
            overrun_limit: 1,
            overrun_fault: false,
            lost_edge_fault: false,
            rom_test_bytes_per_scan: self.rom_test_bytes_per_scan,
            inputs,
            outputs,
            timers,
            switches: Vec::new(),
            events,
            supervisors,
            nets: Vec::new(),
            board: None,
            warnings: Vec::new(),
            files: Vec::new(),
        }
    }

    fn build_inputs(&self) -> Vec<Input> {
        self.debounce
            .iter()
            .enumerate()
            .map(|(i, &d)| Input {
                name: format!("i{i}"),
                debounce_scans: d,
                line: 0,
            })
            .collect()
    }

    fn build_timers(&self) -> Vec<Timer> {
        self.timers
            .iter()
            .enumerate()
            .map(|(t, p)| Timer {
                name: format!("t{t}"),
                preset_ms: match *p {
                    PresetSpec::Periods(n) => n * self.scan_period_ms,
                    PresetSpec::Millis(ms) => ms,
                },
                line: 0,
            })
            .collect()
    }

    fn build_outputs(&self) -> Vec<Output> {
        let states: Vec<usize> = self.supervisors.iter().map(|s| s.rows.len()).collect();
        self.outputs
            .iter()
            .enumerate()
            .map(|(o, spec)| build_output(o, spec, &states))
            .collect()
    }

    /// The alphabets (sorted global event indices): the picked events, and
    /// every controllable event nobody picked goes to supervisor `e mod n`.
    fn alphabets(&self, events: &[Event]) -> Vec<Vec<usize>> {
        let mut sets: Vec<BTreeSet<usize>> = self
            .supervisors
            .iter()
            .map(|s| match &s.alphabet {
                AlphabetSpec::Picked(picked) => resolve(picked, events.len()).into_iter().collect(),
                AlphabetSpec::Every => (0..events.len()).collect(),
            })
            .collect();
        for (e, ev) in events.iter().enumerate() {
            if ev.controllable && !sets.iter().any(|s| s.contains(&e)) {
                let n = sets.len();
                sets[e % n].insert(e);
            }
        }
        sets.into_iter().map(|s| s.into_iter().collect()).collect()
    }

    fn build_supervisors(&self, events: &[Event]) -> Vec<Supervisor> {
        self.alphabets(events)
            .iter()
            .zip(&self.supervisors)
            .enumerate()
            .map(|(j, (alphabet, spec))| build_supervisor(j, spec, alphabet, events))
            .collect()
    }
}

/// Counts an event's references are resolved against.
struct Sizes<'a> {
    inputs: usize,
    timers: usize,
    action_driven: &'a [usize],
}

fn build_output(o: usize, spec: &OutputSpec, states: &[usize]) -> Output {
    let drive = match &spec.drive {
        DriveSpec::Actions { initial } => Drive::Actions { initial: *initial },
        DriveSpec::States(entries) => {
            // One entry per supervisor, as a TOML table gives them.
            let mut map: BTreeMap<usize, Vec<StateId>> = BTreeMap::new();
            for (sup, listed) in entries {
                let j = sup.index(states.len());
                let list = map.entry(j).or_default();
                for s in resolve(listed, states[j]) {
                    let s = StateId(s as u32);
                    if !list.contains(&s) {
                        list.push(s);
                    }
                }
            }
            Drive::States(map.into_iter().collect())
        }
    };
    Output {
        name: format!("o{o}"),
        safe: spec.safe,
        drive,
        line: 0,
    }
}

fn build_trigger(spec: &TriggerSpec, sizes: &Sizes<'_>) -> Trigger {
    match spec {
        TriggerSpec::Rising(list) => Trigger::Rising(resolve(list, sizes.inputs)),
        TriggerSpec::Falling(list) => Trigger::Falling(resolve(list, sizes.inputs)),
        TriggerSpec::Expired(_, input) if sizes.timers == 0 => {
            Trigger::Rising(vec![input.index(sizes.inputs)])
        }
        TriggerSpec::Expired(timer, _) => Trigger::Expired(timer.index(sizes.timers)),
    }
}

/// Actions in the validated order: clears, sets (never of a cleared
/// output), timer resets, timer starts; duplicates dropped.
fn build_actions(specs: &[ActionSpec], sizes: &Sizes<'_>) -> Vec<Action> {
    let (mut clears, mut sets, mut resets, mut starts) = (vec![], vec![], vec![], vec![]);
    let outputs = sizes.action_driven;
    for spec in specs {
        let (list, item) = match *spec {
            ActionSpec::Clear(p) if !outputs.is_empty() => {
                (&mut clears, outputs[p.index(outputs.len())])
            }
            ActionSpec::Set(p) if !outputs.is_empty() => {
                (&mut sets, outputs[p.index(outputs.len())])
            }
            ActionSpec::Reset(p) if sizes.timers > 0 => (&mut resets, p.index(sizes.timers)),
            ActionSpec::Start(p) if sizes.timers > 0 => (&mut starts, p.index(sizes.timers)),
            _ => continue,
        };
        if !list.contains(&item) {
            list.push(item);
        }
    }
    sets.retain(|o| !clears.contains(o));
    let mut actions: Vec<Action> = clears.into_iter().map(Action::Clear).collect();
    actions.extend(sets.into_iter().map(Action::Set));
    actions.extend(resets.into_iter().map(Action::Reset));
    actions.extend(starts.into_iter().map(Action::Start));
    actions
}

fn build_event(e: usize, spec: &EventSpec, sizes: &Sizes<'_>) -> Event {
    let actions = build_actions(&spec.actions, sizes);
    let name = format!("e{e}");
    if spec.controllable {
        return Event {
            name,
            controllable: true,
            origin: Origin::Controller,
            trigger: Trigger::Command,
            when: Vec::new(),
            unless: Vec::new(),
            request: spec.request.map(|r| r.index(sizes.inputs)),
            actions,
            line: 0,
        };
    }
    Event {
        name,
        controllable: false,
        origin: if spec.operator {
            Origin::Operator
        } else {
            Origin::Plant
        },
        trigger: build_trigger(&spec.trigger, sizes),
        when: resolve(&spec.when, sizes.inputs),
        unless: resolve(&spec.unless, sizes.inputs),
        request: None,
        actions,
        line: 0,
    }
}

fn build_supervisor(
    j: usize,
    spec: &SupervisorSpec,
    alphabet: &[usize],
    events: &[Event],
) -> Supervisor {
    let mut b = AutomatonBuilder::new(format!("s{j}"));
    let ids: Vec<EventId> = alphabet
        .iter()
        .map(|&e| {
            b.add_event(&events[e].name, events[e].controllable)
                .expect("fresh event")
        })
        .collect();
    let states: Vec<StateId> = spec.rows.iter().map(|_| b.add_anonymous_state()).collect();
    b.set_initial(states[spec.initial.index(states.len())])
        .expect("one initial state");
    for (s, row) in spec.rows.iter().enumerate() {
        for (slot, &id) in ids.iter().enumerate() {
            if let Some(target) = row[slot] {
                b.add_transition(states[s], id, states[target.index(states.len())], 0);
            }
        }
    }
    Supervisor {
        name: format!("s{j}"),
        automaton: b.build().expect("deterministic by construction"),
        local_events: alphabet.iter().copied().zip(ids).collect(),
        source: SupervisorSource::File(PathBuf::from(format!("s{j}.toml"))),
        line: 0,
        max_logic_effort: codegen::backend::logic::DEFAULT_MAX_EFFORT,
    }
}

fn picks(len: RangeInclusive<usize>) -> impl Strategy<Value = Vec<Pick>> {
    vec(any::<Pick>(), len)
}

fn preset() -> impl Strategy<Value = PresetSpec> {
    prop_oneof![
        (1u32..=6).prop_map(PresetSpec::Periods),
        (1u32..=80).prop_map(PresetSpec::Millis),
    ]
}

fn output() -> impl Strategy<Value = OutputSpec> {
    let drive = prop_oneof![
        2 => any::<bool>().prop_map(|initial| DriveSpec::Actions { initial }),
        1 => vec((any::<Pick>(), picks(1..=3)), 1..=2).prop_map(DriveSpec::States),
    ];
    (any::<bool>(), drive).prop_map(|(safe, drive)| OutputSpec { safe, drive })
}

fn trigger() -> impl Strategy<Value = TriggerSpec> {
    prop_oneof![
        2 => picks(1..=3).prop_map(TriggerSpec::Rising),
        2 => picks(1..=3).prop_map(TriggerSpec::Falling),
        1 => (any::<Pick>(), any::<Pick>()).prop_map(|(t, i)| TriggerSpec::Expired(t, i)),
    ]
}

/// A `when`/`unless` list: mostly empty.
fn conditions() -> impl Strategy<Value = Vec<Pick>> {
    prop_oneof![3 => Just(Vec::new()), 1 => picks(1..=2)]
}

fn action() -> impl Strategy<Value = ActionSpec> {
    prop_oneof![
        any::<Pick>().prop_map(ActionSpec::Set),
        any::<Pick>().prop_map(ActionSpec::Clear),
        any::<Pick>().prop_map(ActionSpec::Start),
        any::<Pick>().prop_map(ActionSpec::Reset),
    ]
}

fn event() -> impl Strategy<Value = EventSpec> {
    (
        proptest::bool::weighted(0.4),
        any::<bool>(),
        trigger(),
        conditions(),
        conditions(),
        proptest::option::weighted(0.3, any::<Pick>()),
        vec(action(), 0..=3),
    )
        .prop_map(
            |(controllable, operator, trigger, when, unless, request, actions)| EventSpec {
                controllable,
                operator,
                trigger,
                when,
                unless,
                request,
                actions,
            },
        )
}

/// A supervisor of the narrow families: 1–5 picked events, a number of
/// states drawn from `states`, and about 60 % of the (state, event) pairs
/// with a transition.
fn supervisor(states: RangeInclusive<usize>) -> impl Strategy<Value = SupervisorSpec> {
    let alphabet = picks(1..=5).prop_map(AlphabetSpec::Picked);
    supervisor_over(&NARROW, alphabet, 0.6, states)
}

/// A supervisor of the wide family: a few events, many (usually more than
/// 32 distinct, so its rows are read in several slices) or every event.
/// About 80 % of the (state, event) pairs have a transition: a wide
/// project has many shared events, and sparser supervisors would leave
/// most runs in fault mode. 1–8 states: the narrow families cover larger
/// supervisors, and with 1–12 a wide case took about three times as long.
fn wide_supervisor() -> impl Strategy<Value = SupervisorSpec> {
    let alphabet = prop_oneof![
        2 => picks(1..=8).prop_map(AlphabetSpec::Picked),
        2 => picks(40..=90).prop_map(AlphabetSpec::Picked),
        1 => Just(AlphabetSpec::Every),
    ];
    supervisor_over(&WIDE, alphabet, 0.8, 1..=8)
}

/// A supervisor of a `shape` project over `alphabet`, with a transition
/// on each (state, event) pair with probability `defined`.
fn supervisor_over(
    shape: &Shape,
    alphabet: impl Strategy<Value = AlphabetSpec>,
    defined: f64,
    states: RangeInclusive<usize>,
) -> impl Strategy<Value = SupervisorSpec> {
    let row = vec(
        proptest::option::weighted(defined, any::<Pick>()),
        *shape.events.end(),
    );
    (alphabet, any::<Pick>(), vec(row, states)).prop_map(|(alphabet, initial, rows)| {
        SupervisorSpec {
            alphabet,
            initial,
            rows,
        }
    })
}

/// Random `shape` projects with 1–4 supervisors drawn from `supervisor`.
fn project(
    shape: &Shape,
    supervisor: impl Strategy<Value = SupervisorSpec>,
) -> impl Strategy<Value = ProjectSpec> {
    (
        1u32..=20,
        0u16..=3,
        prop_oneof![Just(Unexpected::Fault), Just(Unexpected::Ignore)],
        proptest::option::weighted(0.85, any::<Pick>()),
        (1u16..=16).prop_map(|words| 4 * words),
        vec(0u8..=3, shape.inputs.clone()),
        vec(preset(), 0..=3),
        vec(output(), 1..=5),
        vec(event(), shape.events.clone()),
        vec(supervisor, 1..=4),
    )
        .prop_map(
            |(
                period,
                max,
                unexpected,
                reset,
                rom_test_bytes_per_scan,
                debounce,
                timers,
                outputs,
                events,
                supervisors,
            )| {
                ProjectSpec {
                    scan_period_ms: period,
                    max_commands_per_scan: max,
                    unexpected,
                    reset,
                    rom_test_bytes_per_scan,
                    debounce,
                    timers,
                    outputs,
                    events,
                    supervisors,
                }
            },
        )
}

// ---------------------------------------------------------------------------
// Random input sequences
// ---------------------------------------------------------------------------

/// The time between two scans.
#[derive(Debug, Clone, Copy)]
enum Dt {
    /// The nominal scan period.
    Period,
    /// The period plus a few ms of jitter (never negative time).
    Jitter(i32),
    /// A late scan or a pause.
    Jump(u32),
}

/// A random run: start time, initial raw inputs, then for each scan the
/// time step before it and the inputs it flips (bit `i`: input `i`).
#[derive(Debug, Clone)]
struct RunSpec {
    start_ms: u32,
    initial: u128,
    steps: Vec<(Dt, u128)>,
}

impl RunSpec {
    /// (time, raw image) of every scan for `inputs` inputs and `period`.
    fn samples(&self, inputs: usize, period: u32) -> Vec<(u32, Vec<bool>)> {
        let image = |mask: u128| (0..inputs).map(|i| mask & (1 << i) != 0).collect();
        let mut now = self.start_ms;
        let mut mask = self.initial;
        let mut out = vec![(now, image(mask))];
        for &(dt, flips) in &self.steps {
            let step = match dt {
                Dt::Period => period,
                Dt::Jitter(j) => period.saturating_add_signed(j),
                Dt::Jump(ms) => ms,
            };
            now = now.wrapping_add(step);
            mask ^= flips;
            out.push((now, image(mask)));
        }
        out
    }
}

/// Which inputs of a narrow project flip before a scan: nothing in about
/// half the scans, usually one input otherwise (so each input mostly keeps
/// its value).
fn flips() -> impl Strategy<Value = u8> {
    prop_oneof![
        8 => Just(0u8),
        6 => (0..*NARROW.inputs.end()).prop_map(|i| 1u8 << i),
        1 => any::<u8>(),
    ]
}

/// The same for a wide project: the single input is any of the 70 a wide
/// project can have (a bit past its inputs flips nothing), the rare burst
/// flips about half of them.
fn wide_flips() -> impl Strategy<Value = u128> {
    prop_oneof![
        8 => Just(0u128),
        6 => (0..*WIDE.inputs.end()).prop_map(|i| 1u128 << i),
        1 => any::<u128>(),
    ]
}

fn dt() -> impl Strategy<Value = Dt> {
    prop_oneof![
        16 => Just(Dt::Period),
        3 => (-3i32..=3).prop_map(Dt::Jitter),
        1 => (0u32..=400).prop_map(Dt::Jump),
    ]
}

/// A run for a narrow project.
fn run() -> impl Strategy<Value = RunSpec> {
    run_with(
        any::<u8>().prop_map(u128::from),
        flips().prop_map(u128::from),
    )
}

/// A run for a wide project.
fn wide_run() -> impl Strategy<Value = RunSpec> {
    run_with(any::<u128>(), wide_flips())
}

/// 20–200 scans from the raw image `initial`, flipping `flips` before
/// each; one run in four starts just before the u32 clock wraps.
fn run_with(
    initial: impl Strategy<Value = u128>,
    flips: impl Strategy<Value = u128>,
) -> impl Strategy<Value = RunSpec> {
    let start = prop_oneof![3 => 0u32..1_000, 1 => (u32::MAX - 3_000)..=u32::MAX];
    (start, initial, vec((dt(), flips), 19..200)).prop_map(|(start_ms, initial, steps)| RunSpec {
        start_ms,
        initial,
        steps,
    })
}

/// `cases` cases with the XorShift generator: in a debug build the default
/// ChaCha generator (unoptimised SIMD) took most of the run time.
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_algorithm: RngAlgorithm::XorShift,
        ..ProptestConfig::default()
    }
}

/// Builds and runs one random case; a failure also lists the project as
/// built, which is easier to read than the spec.
fn check_case(spec: &ProjectSpec, run: &RunSpec) -> Result<(), TestCaseError> {
    let project = spec.build();
    let samples = run.samples(project.inputs.len(), project.scan_period_ms);
    check_run(&project, &samples).map_err(|e| match e {
        TestCaseError::Fail(why) => TestCaseError::fail(format!("{why}\n{}", describe(&project))),
        other => other,
    })
}

/// A compact listing of `project` (events, inputs, … by index).
fn describe(project: &Project) -> String {
    use std::fmt::Write as _;
    let mut out = format!(
        "project: period {} ms, max_commands_per_scan {}, unexpected {:?}, reset {:?}\n",
        project.scan_period_ms, project.max_commands_per_scan, project.unexpected, project.reset
    );
    for (i, input) in project.inputs.iter().enumerate() {
        let _ = writeln!(out, "  input {i}: debounce {}", input.debounce_scans);
    }
    for (o, output) in project.outputs.iter().enumerate() {
        let _ = writeln!(
            out,
            "  output {o}: safe {}, {:?}",
            output.safe, output.drive
        );
    }
    for (t, timer) in project.timers.iter().enumerate() {
        let _ = writeln!(out, "  timer {t}: {} ms", timer.preset_ms);
    }
    for (e, ev) in project.events.iter().enumerate() {
        let _ = writeln!(
            out,
            "  event {e}: {:?}, when {:?}, unless {:?}, request {:?}, actions {:?}",
            ev.trigger, ev.when, ev.unless, ev.request, ev.actions
        );
    }
    for (j, sup) in project.supervisors.iter().enumerate() {
        let global: HashMap<EventId, usize> =
            sup.local_events.iter().map(|&(g, id)| (id, g)).collect();
        let transitions: Vec<String> = sup
            .automaton
            .iter_transitions()
            .map(|(s, e, t)| format!("{s} -{}-> {t}", global[&e]))
            .collect();
        let _ = writeln!(
            out,
            "  supervisor {j}: {} states, initial {}, events {:?}, transitions {}",
            sup.automaton.num_states(),
            sup.automaton.initial().expect("initial state"),
            sup.local_events.iter().map(|&(g, _)| g).collect::<Vec<_>>(),
            transitions.join(", ")
        );
    }
    out
}

proptest! {
    #![proptest_config(config(8_500))]

    /// Small supervisors (1–12 states): most of the cases.
    #[test]
    fn backends_match_reference_on_small_supervisors(
        spec in project(&NARROW, supervisor(1..=12)),
        run in run(),
    ) {
        check_case(&spec, &run)?;
    }
}

/// Adds one or two random Petri nets to `project`, from `seed`: 2–6
/// places holding 0–2 tokens each, the transitions a random subset of the
/// events (each with its event's controllability), every transition
/// taking one or two arcs of weight 1–2 and giving back as many tokens
/// (so every net is bounded; weights of 2 make counters of two or more
/// bits), and one new output per net driven by a place map of one or two
/// places. The counters are laid out as `[[net]]` lays them out, from the
/// bounds of the reachability graph.
fn add_random_nets(project: &mut Project, seed: u64) {
    use codegen::des::petri::{reach, NetBuilder};
    use codegen::Location;
    let mut state = seed | 1;
    let mut next = move |n: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n as u64) as usize
    };
    let at = || Location::new("random.net.toml", 1, 1);
    for k in 0..1 + next(2) {
        let places = 2 + next(5);
        let mut b = NetBuilder::new(format!("n{k}"));
        for p in 0..places {
            b.add_place(&format!("p{p}"), None, next(3) as u32, at())
                .expect("place");
        }
        let mut events = Vec::new();
        for (e, ev) in project.events.iter().enumerate() {
            if next(2) == 0 {
                continue;
            }
            b.add_transition(&ev.name, None, ev.controllable, true, at())
                .expect("transition");
            // As many tokens out as in, spread over one or two places
            // each way (one arc per place: weights add up).
            let tokens = 1 + next(2) as u32;
            let arcs = |next: &mut dyn FnMut(usize) -> usize| {
                let mut weights = vec![0u32; places];
                for _ in 0..tokens {
                    weights[next(places)] += 1;
                }
                weights
            };
            let input = arcs(&mut next);
            let output = arcs(&mut next);
            for p in 0..places {
                if input[p] > 0 {
                    b.add_arc(&format!("p{p}"), &ev.name, input[p], at())
                        .expect("input arc");
                }
                if output[p] > 0 {
                    b.add_arc(&ev.name, &format!("p{p}"), output[p], at())
                        .expect("output arc");
                }
            }
            events.push(e);
        }
        let net = b.build();
        let bounds = reach::reachability(&net, 100_000).expect("bounded").bounds;
        let (fields, group_bits) = Net::pack_fields(&net, &bounds).expect("counters fit");
        let n = project.nets.len();
        let mapped: Vec<usize> = (0..1 + next(2)).map(|_| next(places)).collect();
        project.outputs.push(Output {
            name: format!("net{n}_out"),
            safe: next(2) == 0,
            drive: Drive::Places(vec![(n, mapped)]),
            line: 0,
        });
        project.nets.push(Net {
            name: format!("n{k}"),
            events,
            fields,
            bounds,
            group_bits,
            markings: 0,
            control_places: 0,
            source: NetSource::File("random.net.toml".into()),
            line: 0,
            net,
        });
    }
}

proptest! {
    #![proptest_config(config(1_500))]

    /// Petri nets beside the automata: the table backend's net layout
    /// against the reference's markings.
    #[test]
    fn table_backend_matches_reference_on_petri_nets(
        spec in project(&NARROW, supervisor(1..=12)),
        run in run(),
        seed in any::<u64>(),
    ) {
        let mut project = spec.build();
        add_random_nets(&mut project, seed);
        let samples = run.samples(project.inputs.len(), project.scan_period_ms);
        check_run(&project, &samples).map_err(|e| match e {
            TestCaseError::Fail(why) => TestCaseError::fail(format!("{why}\n{}\nnets: {:#?}", describe(&project), project.nets)),
            other => other,
        })?;
    }
}

proptest! {
    #![proptest_config(config(1_500))]

    /// Supervisors of up to 50 states.
    #[test]
    fn backends_match_reference_on_large_supervisors(
        spec in project(&NARROW, supervisor(13..=50)),
        run in run(),
    ) {
        check_case(&spec, &run)?;
    }
}

proptest! {
    #![proptest_config(config(200))]

    /// Input images and event sets of two or three words, supervisors with
    /// more than 32 local events.
    #[test]
    fn backends_match_reference_on_wide_projects(
        spec in project(&WIDE, wide_supervisor()),
        run in wide_run(),
    ) {
        check_case(&spec, &run)?;
    }
}

// ---------------------------------------------------------------------------
// Coverage of the generators
// ---------------------------------------------------------------------------

/// What happened in random runs, counted from reference traces, so that a
/// generator change that silently stops exercising a rule fails a test.
#[derive(Debug, Default)]
struct Coverage {
    scans: u64,
    scans_in_fault: u64,
    uncontrollable: u64,
    expiries: u64,
    conditioned: u64,
    local_logic: u64,
    commands: u64,
    requested: u64,
    several_commands: u64,
    shared: u64,
    faults: u64,
    resets: u64,
    ignored: u64,
    moore_high: u64,
    clock_wraps: u64,
    /// Events past the first word of an event set executed.
    high_events: u64,
    /// Commands past the first word executed.
    high_commands: u64,
    /// Commands executed on a request input past the first word.
    high_requests: u64,
    /// Edge events whose edge only inputs past the first word made.
    high_input_edges: u64,
    /// Supervisor moves on a local event past the first slice of its rows.
    high_local_moves: u64,
}

/// One scan as the coverage sees it: the reference's record and its
/// filtered input image F\[k\].
struct Observed {
    record: Record,
    filtered: Vec<bool>,
}

/// Runs `samples` through the reference, keeping F\[k\] of every scan.
fn observe(project: &Project, samples: &[(u32, Vec<bool>)]) -> Vec<Observed> {
    let mut reference = Reference::new(project);
    samples
        .iter()
        .map(|(now, raw)| Observed {
            record: reference.scan(*now, raw),
            filtered: reference.filtered.clone(),
        })
        .collect()
}

/// What `project`'s supervisors make of each event.
struct EventMembership {
    /// Supervisors having the event.
    supervisors: usize,
    /// Some supervisor has it past the first slice of its rows.
    high_local: bool,
}

impl Coverage {
    /// Adds the counts of one run of `project`.
    fn add(&mut self, project: &Project, scans: &[Observed]) {
        let mut members: Vec<EventMembership> = (0..project.events.len())
            .map(|_| EventMembership {
                supervisors: 0,
                high_local: false,
            })
            .collect();
        for sup in &project.supervisors {
            for (local, &(g, _)) in sup.local_events.iter().enumerate() {
                members[g].supervisors += 1;
                members[g].high_local |= local >= WORD;
            }
        }
        for (k, now) in scans.iter().enumerate() {
            let previous = k.checked_sub(1).map(|p| &scans[p]);
            self.add_scan(project, &members, previous.map(|p| &p.record), &now.record);
            let before = previous.unwrap_or(now);
            self.add_words(project, &members, &before.filtered, now);
        }
    }

    fn add_scan(
        &mut self,
        project: &Project,
        members: &[EventMembership],
        previous: Option<&Record>,
        r: &Record,
    ) {
        let count = |n: usize| n as u64;
        let events = || r.executed.iter().map(|&e| (e, &project.events[e]));
        let was_faulted = previous.is_some_and(|p| p.fault.is_some());
        self.scans += 1;
        self.scans_in_fault += u64::from(r.fault.is_some());
        self.uncontrollable += count(
            events()
                .filter(|&(e, ev)| !ev.controllable && members[e].supervisors > 0)
                .count(),
        );
        self.expiries += count(
            events()
                .filter(|(_, ev)| matches!(ev.trigger, Trigger::Expired(_)))
                .count(),
        );
        self.conditioned += count(
            events()
                .filter(|(_, ev)| !ev.when.is_empty() || !ev.unless.is_empty())
                .count(),
        );
        self.local_logic += count(
            events()
                .filter(|&(e, ev)| !ev.controllable && members[e].supervisors == 0)
                .count(),
        );
        let commands = events().filter(|(_, ev)| ev.controllable).count();
        self.commands += count(commands);
        self.several_commands += u64::from(commands > 1);
        self.requested += count(events().filter(|(_, ev)| ev.request.is_some()).count());
        self.shared += count(
            events()
                .filter(|&(e, _)| members[e].supervisors > 1)
                .count(),
        );
        self.faults += u64::from(r.fault.is_some() && !was_faulted);
        self.resets += u64::from(was_faulted && r.fault.is_none());
        self.ignored += u64::from(r.fault.is_none() && !r.unexpected.is_empty());
        self.moore_high += u64::from(r.fault.is_none() && moore_high(project, r));
        self.clock_wraps += u64::from(previous.is_some_and(|p| r.time_ms < p.time_ms));
    }

    /// The counts past the first word of a set: scan `now`, whose
    /// filtered image before was `before`.
    fn add_words(
        &mut self,
        project: &Project,
        members: &[EventMembership],
        before: &[bool],
        now: &Observed,
    ) {
        let r = &now.record;
        let count = |n: usize| n as u64;
        let high = || r.executed.iter().filter(|&&e| e >= WORD);
        self.high_events += count(high().count());
        let commands = || high().filter(|&&e| project.events[e].controllable);
        self.high_commands += count(commands().count());
        self.high_requests += count(
            r.executed
                .iter()
                .filter(|&&e| project.events[e].request.is_some_and(|i| i >= WORD))
                .count(),
        );
        self.high_local_moves += count(
            r.executed
                .iter()
                .filter(|&&e| members[e].high_local)
                .count(),
        );
        // A changed input of an event's binding made its edge (the edge of
        // an OR rises only from all 0 and falls only to all 0).
        let edge_from_high_inputs = |e: usize| match &project.events[e].trigger {
            Trigger::Rising(list) | Trigger::Falling(list) => {
                let mut changed = list.iter().filter(|&&i| before[i] != now.filtered[i]);
                changed.clone().next().is_some() && changed.all(|&i| i >= WORD)
            }
            _ => false,
        };
        self.high_input_edges += count(
            r.executed
                .iter()
                .chain(&r.unexpected)
                .filter(|&&e| edge_from_high_inputs(e))
                .count(),
        );
    }

    /// The counters, named.
    fn counters(&self) -> [(&'static str, u64); 14] {
        [
            (
                "uncontrollable events moving supervisors",
                self.uncontrollable,
            ),
            ("timer expiries executed", self.expiries),
            ("events with when/unless executed", self.conditioned),
            ("events in no alphabet executed", self.local_logic),
            ("commands executed", self.commands),
            ("requested commands executed", self.requested),
            ("scans with several commands", self.several_commands),
            ("shared events executed", self.shared),
            ("faults entered", self.faults),
            ("resets", self.resets),
            ("scans with ignored events", self.ignored),
            ("scans with a Moore output high", self.moore_high),
            ("clock wrap-arounds", self.clock_wraps),
            ("scans in fault mode", self.scans_in_fault),
        ]
    }

    /// The counters past the first word of an input image, an event set or
    /// a supervisor's rows, named.
    fn word_counters(&self) -> [(&'static str, u64); 5] {
        [
            ("events >= 32 executed", self.high_events),
            ("commands >= 32 executed", self.high_commands),
            ("commands requested by an input >= 32", self.high_requests),
            ("edges made by inputs >= 32 alone", self.high_input_edges),
            (
                "supervisor moves on a local event >= 32",
                self.high_local_moves,
            ),
        ]
    }
}

/// `true` when some state-mapped output is 1 in `r`.
fn moore_high(project: &Project, r: &Record) -> bool {
    project
        .outputs
        .iter()
        .zip(&r.outputs)
        .any(|(o, &level)| level && matches!(o.drive, Drive::States(_)))
}

/// The coverage of `runs` cases drawn from `strategy` (run through the
/// reference only).
fn coverage_of(strategy: impl Strategy<Value = (ProjectSpec, RunSpec)>, runs: u32) -> Coverage {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;

    let mut runner = TestRunner::new(config(runs));
    let mut coverage = Coverage::default();
    for _ in 0..runs {
        let (spec, run) = strategy.new_tree(&mut runner).unwrap().current();
        let project = spec.build();
        let samples = run.samples(project.inputs.len(), project.scan_period_ms);
        coverage.add(&project, &observe(&project, &samples));
    }
    coverage
}

/// The random cases reach every rule: events of every kind execute,
/// faults are entered and left, events are ignored, the clock wraps; and
/// most scans are not spent in fault mode.
#[test]
fn random_runs_exercise_every_rule() {
    let coverage = coverage_of((project(&NARROW, supervisor(1..=12)), run()), 300);
    println!("{} scans: {:#?}", coverage.scans, coverage.counters());
    for (what, n) in coverage.counters() {
        assert!(n > 0, "no {what} in 300 random runs: {coverage:#?}");
    }
    assert!(
        coverage.scans_in_fault * 2 < coverage.scans,
        "most scans are spent in fault mode: {coverage:#?}"
    );
}

/// The wide cases cross every word boundary the executor has: events and
/// commands past the first word of an event set execute, a request input
/// and edges past the first word of the input image count, supervisors
/// move on local events past the first 32-event slice of their rows; and
/// they still reach every rule without spending most scans in fault mode.
#[test]
fn wide_runs_cross_every_word_boundary() {
    let coverage = coverage_of((project(&WIDE, wide_supervisor()), wide_run()), 100);
    println!(
        "{} scans: {:#?} {:#?}",
        coverage.scans,
        coverage.word_counters(),
        coverage.counters()
    );
    for (what, n) in coverage
        .word_counters()
        .into_iter()
        .chain(coverage.counters())
    {
        assert!(n > 0, "no {what} in 100 wide runs: {coverage:#?}");
    }
    assert!(
        coverage.scans_in_fault * 2 < coverage.scans,
        "most scans are spent in fault mode: {coverage:#?}"
    );
}

// ---------------------------------------------------------------------------
// The reference against hand-computed traces
// ---------------------------------------------------------------------------

fn input(name: &str, debounce_scans: u8) -> Input {
    Input {
        name: name.to_owned(),
        debounce_scans,
        line: 0,
    }
}

fn output_named(name: &str, safe: bool, drive: Drive) -> Output {
    Output {
        name: name.to_owned(),
        safe,
        drive,
        line: 0,
    }
}

/// An event; `trigger` `Command` makes it controllable.
fn event_named(name: &str, trigger: Trigger, actions: Vec<Action>) -> Event {
    let controllable = trigger == Trigger::Command;
    Event {
        name: name.to_owned(),
        controllable,
        origin: if controllable {
            Origin::Controller
        } else {
            Origin::Plant
        },
        trigger,
        when: Vec::new(),
        unless: Vec::new(),
        request: None,
        actions,
        line: 0,
    }
}

/// A supervisor over `alphabet` (global event indices, ascending) with
/// states `0..n`, initial state 0 and transitions (source, global event,
/// target).
fn supervisor_named(
    name: &str,
    events: &[Event],
    alphabet: &[usize],
    n: u32,
    transitions: &[(u32, usize, u32)],
) -> Supervisor {
    let mut b = AutomatonBuilder::new(name);
    let ids: Vec<EventId> = alphabet
        .iter()
        .map(|&e| {
            b.add_event(&events[e].name, events[e].controllable)
                .unwrap()
        })
        .collect();
    for _ in 0..n {
        b.add_anonymous_state();
    }
    b.set_initial(StateId(0)).unwrap();
    for &(s, e, t) in transitions {
        let slot = alphabet.iter().position(|&g| g == e).unwrap();
        b.add_transition(StateId(s), ids[slot], StateId(t), 0);
    }
    Supervisor {
        name: name.to_owned(),
        automaton: b.build().unwrap(),
        local_events: alphabet.iter().copied().zip(ids).collect(),
        source: SupervisorSource::File(PathBuf::from(format!("{name}.toml"))),
        line: 0,
        max_logic_effort: codegen::backend::logic::DEFAULT_MAX_EFFORT,
    }
}

fn hand_project(
    inputs: Vec<Input>,
    outputs: Vec<Output>,
    timers: Vec<Timer>,
    events: Vec<Event>,
) -> Project {
    Project {
        path: PathBuf::from("hand.plc.toml"),
        name: "hand".to_owned(),
        scan_period_ms: 10,
        max_commands_per_scan: 1,
        unexpected: Unexpected::Fault,
        reset: None,
        overrun_limit: 1,
        overrun_fault: false,
        lost_edge_fault: false,
        rom_test_bytes_per_scan: 64,
        inputs,
        outputs,
        timers,
        switches: Vec::new(),
        events,
        supervisors: Vec::new(),
        nets: Vec::new(),
        board: None,
        warnings: Vec::new(),
        files: Vec::new(),
    }
}

/// A press station. Inputs `btn` (debounce 2) and `rst` (reset); output
/// `lamp` (actions) and `moving` (state map, safe 1); timer `t` (50 ms).
/// Events: `press` (rising btn, sets lamp), `release` (falling btn, in no
/// alphabet, clears lamp), `tick` (t expired, clears lamp), `run`
/// (controllable, starts t). Supervisor S: idle -press-> armed -run->
/// running -tick-> idle.
fn press_station() -> Project {
    let events = vec![
        event_named("press", Trigger::Rising(vec![0]), vec![Action::Set(0)]),
        event_named("release", Trigger::Falling(vec![0]), vec![Action::Clear(0)]),
        event_named("tick", Trigger::Expired(0), vec![Action::Clear(0)]),
        event_named("run", Trigger::Command, vec![Action::Start(0)]),
    ];
    let s = supervisor_named(
        "S",
        &events,
        &[0, 2, 3],
        3,
        &[(0, 0, 1), (1, 3, 2), (2, 2, 0)],
    );
    let mut p = hand_project(
        vec![input("btn", 2), input("rst", 0)],
        vec![
            output_named("lamp", false, Drive::Actions { initial: false }),
            output_named("moving", true, Drive::States(vec![(0, vec![StateId(2)])])),
        ],
        vec![Timer {
            name: "t".to_owned(),
            preset_ms: 50,
            line: 0,
        }],
        events,
    );
    p.supervisors = vec![s];
    p.reset = Some(1);
    p
}

/// (btn, rst) raw inputs of the press-station run, one pair per scan.
const PRESS_INPUTS: [(bool, bool); 20] = [
    (false, false), // 0
    (true, false),  // 1: btn differs once
    (true, false),  // 2: twice -> F=1, press, run
    (false, false), // 3
    (false, false), // 4: F=0, release
    (true, false),  // 5
    (true, false),  // 6: press while running -> fault
    (true, false),  // 7: t due (70 ms) but faulted
    (true, true),   // 8: reset rises -> re-initialised
    (true, true),   // 9
    (false, false), // 10
    (false, false), // 11: release
    (true, false),  // 12
    (true, false),  // 13: press, run (deadline 180)
    (true, false),  // 14
    (false, false), // 15: glitch ...
    (true, false),  // 16: ... filtered out
    (true, false),  // 17
    (true, false),  // 18: 180 ms, tick
    (true, false),  // 19
];

/// The press-station samples with scan k at `start + 10 k` ms.
fn press_samples(start: u32) -> Vec<(u32, Vec<bool>)> {
    PRESS_INPUTS
        .iter()
        .zip(0u32..)
        .map(|(&(btn, rst), k)| (start.wrapping_add(10 * k), vec![btn, rst]))
        .collect()
}

fn run_reference(project: &Project, samples: &[(u32, Vec<bool>)]) -> Vec<Record> {
    let mut reference = Reference::new(project);
    samples
        .iter()
        .map(|(now, raw)| reference.scan(*now, raw))
        .collect()
}

/// (executed, unexpected, state, outputs, fault) as hand-computed.
type Expected = (
    &'static [usize],
    &'static [usize],
    u32,
    [bool; 2],
    Option<Cause>,
);

const PRESS: usize = 0;
const RELEASE: usize = 1;
const TICK: usize = 2;
const RUN: usize = 3;
const FAULTED: Option<Cause> = Some(Cause::Unexpected(PRESS));

const PRESS_TRACE: [Expected; 20] = [
    (&[], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[PRESS, RUN], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[RELEASE], &[], 2, [false, true], None),
    (&[], &[], 2, [false, true], None),
    (&[], &[PRESS], 2, [false, true], FAULTED),
    (&[], &[], 2, [false, true], FAULTED),
    (&[], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[RELEASE], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
    (&[PRESS, RUN], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[], &[], 2, [true, true], None),
    (&[TICK], &[], 0, [false, false], None),
    (&[], &[], 0, [false, false], None),
];

/// Debounce, edges, an event in no alphabet, a timer, an unexpected event
/// faulting (safe image, timer expiry ignored in fault mode), reset
/// recovery (timer stopped) and a suppressed glitch.
#[test]
fn reference_follows_a_hand_computed_trace() {
    let project = press_station();
    let samples = press_samples(0);
    let trace = run_reference(&project, &samples);
    for (k, (got, want)) in trace.iter().zip(&PRESS_TRACE).enumerate() {
        let (executed, unexpected, state, outputs, fault) = *want;
        let want = Record {
            scan: k as u32,
            time_ms: 10 * k as u32,
            executed: executed.to_vec(),
            unexpected: unexpected.to_vec(),
            states: vec![state],
            outputs: outputs.to_vec(),
            fault,
        };
        assert_eq!(*got, want, "scan {k}");
    }
    check_run(&project, &samples).unwrap();
}

/// Shifting the clock so that the second timer runs across the u32
/// wrap-around (started at 2^32 - 21 ms, due at 29 ms) changes nothing but
/// the times.
#[test]
fn reference_trace_is_invariant_under_clock_wrap() {
    let project = press_station();
    let start = u32::MAX - 149;
    let shifted = press_samples(start);
    assert!(shifted[13].0 > shifted[18].0, "the run must cross the wrap");
    let plain = run_reference(&project, &press_samples(0));
    let wrapped = run_reference(&project, &shifted);
    for (k, (p, w)) in plain.iter().zip(&wrapped).enumerate() {
        let w = Record {
            time_ms: w.time_ms.wrapping_sub(start),
            ..w.clone()
        };
        assert_eq!(*p, w, "scan {k}");
    }
    check_run(&project, &shifted).unwrap();
}

/// Two supervisors sharing a controllable event with a request input, no
/// command limit, and an unexpected event under policy `ignore`.
///
/// Events: `u` (rising x), `a`, `go` (request `req`), `b`; outputs `lamp`
/// (set by `a`, cleared by `go`) and `b_done` (B in state 2).
/// A: 0 -a-> 1 -go-> 0. B: 0 -go-> 1 -b-> 2 -u-> 0.
#[test]
fn reference_runs_commands_of_modular_supervisors() {
    let events = vec![
        event_named("u", Trigger::Rising(vec![1]), vec![]),
        event_named("a", Trigger::Command, vec![Action::Set(0)]),
        Event {
            request: Some(0),
            ..event_named("go", Trigger::Command, vec![Action::Clear(0)])
        },
        event_named("b", Trigger::Command, vec![]),
    ];
    let a = supervisor_named("A", &events, &[1, 2], 2, &[(0, 1, 1), (1, 2, 0)]);
    let b = supervisor_named(
        "B",
        &events,
        &[0, 2, 3],
        3,
        &[(0, 2, 1), (1, 3, 2), (2, 0, 0)],
    );
    let mut project = hand_project(
        vec![input("req", 0), input("x", 0)],
        vec![
            output_named("lamp", false, Drive::Actions { initial: false }),
            output_named("b_done", false, Drive::States(vec![(1, vec![StateId(2)])])),
        ],
        Vec::new(),
        events,
    );
    project.supervisors = vec![a, b];
    project.max_commands_per_scan = 0;
    project.unexpected = Unexpected::Ignore;

    // (req, x) -> (executed, unexpected, states, outputs)
    type Step = (
        (bool, bool),
        &'static [usize],
        &'static [usize],
        [u32; 2],
        [bool; 2],
    );
    const STEPS: [Step; 6] = [
        ((false, false), &[1], &[], [1, 0], [true, false]),
        ((true, false), &[2, 1, 3], &[], [1, 2], [true, true]),
        ((false, true), &[0], &[], [1, 0], [true, false]),
        ((false, false), &[], &[], [1, 0], [true, false]),
        ((false, true), &[], &[0], [1, 0], [true, false]),
        ((true, true), &[2, 1, 3], &[], [1, 2], [true, true]),
    ];
    let samples: Vec<(u32, Vec<bool>)> = STEPS
        .iter()
        .zip(0u32..)
        .map(|(&((req, x), ..), k)| (10 * k, vec![req, x]))
        .collect();
    let mut reference = Reference::new(&project);
    for (k, (now, raw)) in samples.iter().enumerate() {
        let (_, executed, unexpected, states, outputs) = STEPS[k];
        let got = reference.scan(*now, raw);
        assert_eq!(got.executed, executed, "scan {k}: executed");
        assert_eq!(got.unexpected, unexpected, "scan {k}: unexpected");
        assert_eq!(got.states, states, "scan {k}: states");
        assert_eq!(got.outputs, outputs, "scan {k}: outputs");
        assert_eq!(got.fault, None, "scan {k}: fault");
    }
    assert_eq!(reference.ignored, 1);
    check_run(&project, &samples).unwrap();
}

/// The control-equivalence check rejects a command the supervisor does
/// not allow, a move along no transition, and a move in fault mode.
#[test]
fn control_check_rejects_what_the_supervisors_forbid() {
    let project = press_station();
    let record = |executed: &[usize], state: u32| Record {
        scan: 1,
        time_ms: 10,
        executed: executed.to_vec(),
        unexpected: Vec::new(),
        states: vec![state],
        outputs: vec![false, false],
        fault: None,
    };
    let check = |before: u32, faulted: bool, r: &Record| {
        check_control(&project, 1, &[before], faulted, r).is_ok()
    };
    assert!(check(0, false, &record(&[PRESS, RUN], 2)));
    assert!(
        !check(0, false, &record(&[RUN], 2)),
        "run is disabled in idle"
    );
    assert!(
        !check(0, false, &record(&[PRESS], 2)),
        "press leads to armed"
    );
    assert!(check(2, true, &record(&[], 0)), "a reset scan");
    assert!(!check(2, true, &record(&[], 1)), "no move in fault mode");
    assert!(
        !check(2, true, &record(&[TICK], 0)),
        "nothing runs in fault mode"
    );
}
