//! Safety invariants of the boiler, checked scan by scan on any record of
//! inputs and outputs: a closed-loop [`Run`](super::Run), or a replay trace
//! of a project ([`Checker::for_project`], [`check_replay`]).
//!
//! # Reading of a trace
//!
//! Scan `k` has the input image `I[k]` the controller read and the output
//! image `O[k]` it wrote. The checker filters the inputs as the controller
//! does (`debounce_scans`, docs/semantics.md: a level is taken after it has
//! differed for that many scans) into `F[k]`; scan 0 has no input edges
//! (`F[-1] = F[0]`) and `O[-1]` is all off. An output *opens* in scan `k`
//! when it is 1 in `O[k]` and 0 in `O[k-1]`. The fuel valves are
//! `pilot_valve`, `main_valve_lo` and `main_valve_hi`.
//!
//! The selector is **switched on** in scan `k` when one of its contacts
//! (`sel_high`, `sel_low`) rises in `F[k]` while it does not demand heat;
//! it then **demands heat** until it is off (both contacts 0) again. A
//! selector already on when the controller starts (scan 0, where there are
//! no edges) or when it re-initialises (the scan that leaves fault mode,
//! reported with [`Checker::reinitialised`], which also ends the start
//! request) does not demand heat until a contact rises: the controller has
//! seen no edge of it (docs/semantics.md, "One scan", steps 1 and 2; the
//! re-initialising scan discards its own edges, a contact rising in it
//! included).
//!
//! A **start request** begins in scan `k` when the selector is switched on,
//! or when `reset` rises in `F[k]` while the selector demands heat, the
//! burner locked out (a shutdown below not yet reset, or `alarm` on in
//! `O[k-1]`) and every fuel valve closed in `O[k-1]` (a restart after a
//! lockout purges again). It ends when the selector is off.
//!
//! A **shutdown** is triggered in scan `k` by a rising edge of `bath_hot`
//! or `flue_hot` in `F` while the selector demands heat, or by a falling
//! edge of `main_flame` while a main valve was open in `O[k-1]`. The burner
//! is then **locked out** until a rising edge of `reset`.
//!
//! # The rules ([`Rule`])
//!
//! 1. [`Rule::IgnitionIntoFlame`]: `ignition` never opens in a scan where
//!    `pilot_flame` is 1.
//! 2. [`Rule::IgnitionWithoutPilotGas`]: `ignition` is 1 only while
//!    `pilot_valve` is 1 (same scan).
//! 3. [`Rule::FuelBeforePurge`]: a fuel valve opens only during a start
//!    request at least `purge_ms` after it began; with
//!    `purge_needs_blower`, also only after the blower has been on
//!    continuously for `purge_ms` within the request. The thesis's
//!    pre-purge is a timer in the pilot stage and starts the blower only in
//!    the main-flame stage (damper, then blower, then main valve), so the
//!    blower is not required by default.
//! 4. [`Rule::MainWithoutPermit`]: a main valve position is 1 only while a
//!    damper position is 1, the blower is 1, and `pilot_flame` has been 1 in
//!    `F` in some scan of the current start request.
//! 5. [`Rule::BothPositions`]: `main_valve_lo` and `main_valve_hi` are never
//!    both 1, nor `damper_lo` and `damper_hi`.
//! 6. [`Rule::FuelNotShut`] and [`Rule::NoAlarm`]: after a shutdown trigger
//!    in scan `k`, every fuel valve is closed in some scan `k..=k+N` and
//!    `alarm` is 1 in some scan `k..=k+N` (`N = shutdown_scans`, default 2:
//!    the trigger scan and two more). A trace that ends before `k+N` is not
//!    judged.
//! 7. [`Rule::RestartWithoutReset`]: no fuel valve opens while locked out.
//! 8. [`Rule::OutputsOnWhileOff`]: once the selector has been off in `F`
//!    for `off_scans` scans (default 5: from scan `s` where it went off,
//!    scans `s+5` on), every output except `alarm` is 0.
//! 9. [`Rule::TooManyTrials`]: `ignition` opens at most `max_trials`
//!    (default 2) times per start request.
//!
//! Level rules (2, 4, 5, 8) are reported once per episode, at its first
//! scan; edge rules at every offending edge.

use super::error::BoilerError;
use super::signals::{Input, Inputs, IoMap, Output, Outputs};
use crate::inputs::InputRow;
use crate::trace::TraceRow;
use executor::program::Config;
use plc_project::Project;
use std::fmt;

/// The constants of the rules.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Invariants {
    /// Pre-purge before any fuel valve opens (default 10 s).
    pub purge_ms: u64,
    /// The blower must run through the pre-purge (default `false`, see the
    /// module documentation).
    pub purge_needs_blower: bool,
    /// Scans after a shutdown trigger within which the fuel is off and the
    /// alarm on (default 2).
    pub shutdown_scans: u64,
    /// Scans after the selector goes off within which every output but the
    /// alarm is off (default 5).
    pub off_scans: u64,
    /// Ignition trials per start request (default 2).
    pub max_trials: u32,
}

impl Default for Invariants {
    fn default() -> Self {
        Invariants {
            purge_ms: 10_000,
            purge_needs_blower: false,
            shutdown_scans: 2,
            off_scans: 5,
            max_trials: 2,
        }
    }
}

/// A safety rule (see the module documentation for the exact reading).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Rule {
    /// The spark was switched on into a detected pilot flame.
    IgnitionIntoFlame,
    /// The spark was on without pilot gas.
    IgnitionWithoutPilotGas,
    /// A fuel valve opened before a full pre-purge of the start request.
    FuelBeforePurge,
    /// A main valve was open without air or without a pilot flame.
    MainWithoutPermit,
    /// Both positions of the main valve or of the damper were on.
    BothPositions,
    /// Fuel still open too long after a shutdown trigger.
    FuelNotShut,
    /// No alarm soon after a shutdown trigger.
    NoAlarm,
    /// A fuel valve opened after a shutdown before any reset.
    RestartWithoutReset,
    /// Outputs still on too long after the selector went off.
    OutputsOnWhileOff,
    /// More ignition trials than allowed in one start request.
    TooManyTrials,
}

impl Rule {
    /// A short kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            Rule::IgnitionIntoFlame => "ignition-into-flame",
            Rule::IgnitionWithoutPilotGas => "ignition-without-pilot-gas",
            Rule::FuelBeforePurge => "fuel-before-purge",
            Rule::MainWithoutPermit => "main-without-permit",
            Rule::BothPositions => "both-positions",
            Rule::FuelNotShut => "fuel-not-shut",
            Rule::NoAlarm => "no-alarm",
            Rule::RestartWithoutReset => "restart-without-reset",
            Rule::OutputsOnWhileOff => "outputs-on-while-off",
            Rule::TooManyTrials => "too-many-trials",
        }
    }
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One broken rule.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Violation {
    /// Scan number in the checked record (from 0).
    pub scan: u64,
    /// Time of that scan.
    pub time_ms: u64,
    /// The rule.
    pub rule: Rule,
    /// What happened, with names and numbers.
    pub message: String,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "scan {} at {} ms [{}]: {}",
            self.scan, self.time_ms, self.rule, self.message
        )
    }
}

/// The level rules reported once per episode.
#[derive(Debug, Clone, Copy)]
enum Episode {
    IgnitionWithoutGas,
    MainWithoutPermit,
    MainBoth,
    DamperBoth,
}

/// The controller's input filter, replayed (docs/semantics.md, "One scan", step 1).
#[derive(Debug, Clone)]
struct Filter {
    debounce: [u8; Input::ALL.len()],
    differing: [u8; Input::ALL.len()],
    filtered: Inputs,
}

impl Filter {
    fn sample(&mut self, raw: &Inputs, first: bool) -> Inputs {
        for input in Input::ALL {
            let i = input.index();
            let value = raw.get(input);
            if first || self.debounce[i] <= 1 || value == self.filtered.get(input) {
                self.filtered.set(input, value);
                self.differing[i] = 0;
            } else {
                self.differing[i] = self.differing[i].saturating_add(1);
                if self.differing[i] >= self.debounce[i] {
                    self.filtered.set(input, value);
                    self.differing[i] = 0;
                }
            }
        }
        self.filtered
    }
}

/// The current start request.
#[derive(Debug, Clone, Copy)]
struct Request {
    scan: u64,
    time_ms: u64,
    pilot_seen: bool,
    trials: u32,
}

/// A shutdown trigger waiting for fuel off and alarm on.
#[derive(Debug, Clone)]
struct Shutdown {
    cause: &'static str,
    scan: u64,
    fuel_closed: bool,
    alarm_on: bool,
}

/// The checker: feed it one scan at a time with [`Checker::observe`].
#[derive(Debug, Clone)]
pub struct Checker {
    rules: Invariants,
    filter: Filter,
    scan: u64,
    prev_inputs: Inputs,
    prev_outputs: Outputs,
    demand: bool,
    reinitialising: bool,
    request: Option<Request>,
    blower_since_ms: Option<u64>,
    lockout: Option<(u64, &'static str)>,
    pending: Vec<Shutdown>,
    off_since: Option<u64>,
    off_reported: bool,
    episodes: [bool; 4],
    violations: Vec<Violation>,
}

impl Checker {
    /// A checker for a controller that does not filter its inputs.
    pub fn new(rules: Invariants) -> Checker {
        Checker::with_debounce(rules, [0; Input::ALL.len()])
    }

    /// A checker for a controller that debounces input `i` over
    /// `debounce[i.index()]` scans.
    pub fn with_debounce(rules: Invariants, debounce: [u8; Input::ALL.len()]) -> Checker {
        Checker {
            rules,
            filter: Filter {
                debounce,
                differing: [0; Input::ALL.len()],
                filtered: Inputs::default(),
            },
            scan: 0,
            prev_inputs: Inputs::default(),
            prev_outputs: Outputs::default(),
            demand: false,
            reinitialising: false,
            request: None,
            blower_since_ms: None,
            lockout: None,
            pending: Vec::new(),
            off_since: None,
            off_reported: false,
            episodes: [false; 4],
            violations: Vec::new(),
        }
    }

    /// A checker for raw rows of `project` lowered as `config` (its
    /// boiler signals found by name, its debouncing replayed as `config`
    /// has it).
    pub fn for_project(
        project: &Project,
        config: &Config<'_>,
        rules: Invariants,
    ) -> Result<ProjectChecker, BoilerError> {
        let io = IoMap::new(project)?;
        let checker = Checker::with_debounce(rules, io.debounce(config));
        Ok(ProjectChecker { io, checker })
    }

    /// The violations found so far.
    pub fn violations(&self) -> &[Violation] {
        &self.violations
    }

    /// The controller re-initialises in the next observed scan (it leaves
    /// fault mode on `reset`): the start request ends, and a selector
    /// already on no longer demands heat until one of its contacts rises.
    pub fn reinitialised(&mut self) {
        self.demand = false;
        self.reinitialising = true;
        self.request = None;
    }

    /// The violations of the whole record.
    pub fn finish(self) -> Vec<Violation> {
        self.violations
    }

    /// Checks one scan: the inputs the controller read at `time_ms` and
    /// the outputs it wrote.
    pub fn observe(&mut self, time_ms: u64, inputs: &Inputs, outputs: &Outputs) {
        let first = self.scan == 0;
        let now = self.filter.sample(inputs, first);
        let before = if first { now } else { self.prev_inputs };
        let scan = Scan {
            k: self.scan,
            time_ms,
            now,
            before,
            out: *outputs,
            out_before: self.prev_outputs,
        };
        self.track_request(&scan);
        self.track_shutdowns(&scan);
        self.check_ignition(&scan);
        self.check_fuel_openings(&scan);
        self.check_main_permit(&scan);
        self.check_positions(&scan);
        self.check_shutdowns(&scan);
        self.check_off(&scan);
        self.prev_inputs = now;
        self.prev_outputs = *outputs;
        self.scan += 1;
    }

    fn report(&mut self, s: &Scan, rule: Rule, message: String) {
        self.violations.push(Violation {
            scan: s.k,
            time_ms: s.time_ms,
            rule,
            message,
        });
    }

    /// Reports `message` when `holds` starts an episode of `episode`.
    fn episode(
        &mut self,
        s: &Scan,
        episode: Episode,
        holds: bool,
        rule: Rule,
        message: impl FnOnce() -> String,
    ) {
        let was = std::mem::replace(&mut self.episodes[episode as usize], holds);
        if holds && !was {
            self.report(s, rule, message());
        }
    }

    fn track_request(&mut self, s: &Scan) {
        let reset = s.rose(Input::Reset);
        let locked = self.lockout.is_some() || s.out_before.alarm;
        if reset {
            self.lockout = None;
        }
        // The scan that re-initialises discards its edges (docs/semantics.md, step 2).
        let contact_rose = !std::mem::take(&mut self.reinitialising)
            && (s.rose(Input::SelHigh) || s.rose(Input::SelLow));
        let switched_on = s.now.selector_on() && !self.demand && contact_rose;
        self.demand = s.now.selector_on() && (self.demand || switched_on);
        if !s.now.selector_on() {
            self.request = None;
        } else if switched_on || (reset && locked && self.demand && !s.out_before.fuel_open()) {
            self.request = Some(Request {
                scan: s.k,
                time_ms: s.time_ms,
                pilot_seen: false,
                trials: 0,
            });
            self.blower_since_ms = s.out_before.blower.then_some(s.time_ms);
        }
        if let Some(r) = &mut self.request {
            r.pilot_seen |= s.now.pilot_flame;
            if s.opened(Output::Ignition) {
                r.trials += 1;
            }
        }
        self.blower_since_ms = if s.out.blower {
            Some(self.blower_since_ms.unwrap_or(s.time_ms))
        } else {
            None
        };
    }

    fn track_shutdowns(&mut self, s: &Scan) {
        let mut causes = Vec::new();
        if self.demand && s.rose(Input::BathHot) {
            causes.push("bath_hot rose");
        }
        if self.demand && s.rose(Input::FlueHot) {
            causes.push("flue_hot rose");
        }
        if s.fell(Input::MainFlame) && s.out_before.main_open() {
            causes.push("main_flame dropped with a main valve open");
        }
        for cause in causes {
            self.lockout = Some((s.k, cause));
            self.pending.push(Shutdown {
                cause,
                scan: s.k,
                fuel_closed: false,
                alarm_on: false,
            });
        }
    }

    fn check_ignition(&mut self, s: &Scan) {
        if s.opened(Output::Ignition) && s.now.pilot_flame {
            self.report(
                s,
                Rule::IgnitionIntoFlame,
                "ignition switched on while pilot_flame is 1".into(),
            );
        }
        self.episode(
            s,
            Episode::IgnitionWithoutGas,
            s.out.ignition && !s.out.pilot_valve,
            Rule::IgnitionWithoutPilotGas,
            || "ignition is on with pilot_valve closed".into(),
        );
        if s.opened(Output::Ignition) {
            if let Some(r) = self.request.filter(|r| r.trials > self.rules.max_trials) {
                let message = format!(
                    "ignition trial {} since the start request at scan {} (at most {})",
                    r.trials, r.scan, self.rules.max_trials
                );
                self.report(s, Rule::TooManyTrials, message);
            }
        }
    }

    fn check_fuel_openings(&mut self, s: &Scan) {
        for valve in Output::FUEL.into_iter().filter(|&v| s.opened(v)) {
            let name = valve.name();
            if let Some((at, cause)) = self.lockout {
                let message = format!(
                    "{name} opened after the shutdown at scan {at} ({cause}) without a reset"
                );
                self.report(s, Rule::RestartWithoutReset, message);
            }
            let purge = self.rules.purge_ms;
            let Some(r) = self.request else {
                let why = if s.now.selector_on() {
                    "the selector was on when the controller (re)started, not switched on since"
                } else {
                    "the selector is off"
                };
                let message = format!("{name} opened without a start request ({why})");
                self.report(s, Rule::FuelBeforePurge, message);
                continue;
            };
            let elapsed = s.time_ms.saturating_sub(r.time_ms);
            if elapsed < purge {
                let message = format!(
                    "{name} opened {elapsed} ms after the start request at scan {}; the pre-purge is {purge} ms",
                    r.scan
                );
                self.report(s, Rule::FuelBeforePurge, message);
            } else if self.rules.purge_needs_blower {
                let air = self
                    .blower_since_ms
                    .map_or(0, |t| s.time_ms.saturating_sub(t));
                if air < purge {
                    let message = format!(
                        "{name} opened after {air} ms of blower since the start request at scan {}; the pre-purge is {purge} ms with the blower on",
                        r.scan
                    );
                    self.report(s, Rule::FuelBeforePurge, message);
                }
            }
        }
    }

    fn check_main_permit(&mut self, s: &Scan) {
        let o = &s.out;
        let pilot_seen = self.request.is_some_and(|r| r.pilot_seen);
        let permitted = o.damper_open() && o.blower && pilot_seen;
        self.episode(
            s,
            Episode::MainWithoutPermit,
            o.main_open() && !permitted,
            Rule::MainWithoutPermit,
            || {
                let mut missing = Vec::new();
                if !o.damper_open() {
                    missing.push("no damper position");
                }
                if !o.blower {
                    missing.push("blower off");
                }
                if !pilot_seen {
                    missing.push("no pilot flame since the start request");
                }
                format!("a main valve is open with {}", missing.join(", "))
            },
        );
    }

    fn check_positions(&mut self, s: &Scan) {
        let o = s.out;
        self.episode(
            s,
            Episode::MainBoth,
            o.main_valve_lo && o.main_valve_hi,
            Rule::BothPositions,
            || "main_valve_lo and main_valve_hi are both on".into(),
        );
        self.episode(
            s,
            Episode::DamperBoth,
            o.damper_lo && o.damper_hi,
            Rule::BothPositions,
            || "damper_lo and damper_hi are both on".into(),
        );
    }

    fn check_shutdowns(&mut self, s: &Scan) {
        let deadline = self.rules.shutdown_scans;
        let mut late = Vec::new();
        self.pending.retain_mut(|d| {
            d.fuel_closed |= !s.out.fuel_open();
            d.alarm_on |= s.out.alarm;
            let settled = d.fuel_closed && d.alarm_on;
            if s.k >= d.scan + deadline {
                late.push(d.clone());
                return false;
            }
            !settled
        });
        for d in late {
            if !d.fuel_closed {
                let open: Vec<&str> = Output::FUEL
                    .into_iter()
                    .filter(|&v| s.out.get(v))
                    .map(Output::name)
                    .collect();
                let message = format!(
                    "{} at scan {}, and {} still open {deadline} scans later",
                    d.cause,
                    d.scan,
                    open.join(", ")
                );
                self.report(s, Rule::FuelNotShut, message);
            }
            if !d.alarm_on {
                let message = format!(
                    "{} at scan {}, and no alarm within {deadline} scans",
                    d.cause, d.scan
                );
                self.report(s, Rule::NoAlarm, message);
            }
        }
    }

    fn check_off(&mut self, s: &Scan) {
        if s.now.selector_on() {
            self.off_since = None;
            self.off_reported = false;
            return;
        }
        let since = *self.off_since.get_or_insert(s.k);
        if self.off_reported || s.k < since + self.rules.off_scans {
            return;
        }
        let on: Vec<&str> = Output::ALL
            .into_iter()
            .filter(|&o| o != Output::Alarm && s.out.get(o))
            .map(Output::name)
            .collect();
        if !on.is_empty() {
            let message = format!(
                "selector off since scan {since}, and {} still on {} scans later",
                on.join(", "),
                s.k - since
            );
            self.report(s, Rule::OutputsOnWhileOff, message);
            self.off_reported = true;
        }
    }
}

/// One scan as the rules see it.
struct Scan {
    k: u64,
    time_ms: u64,
    /// `F[k]`.
    now: Inputs,
    /// `F[k-1]`.
    before: Inputs,
    /// `O[k]`.
    out: Outputs,
    /// `O[k-1]`.
    out_before: Outputs,
}

impl Scan {
    fn rose(&self, input: Input) -> bool {
        self.now.get(input) && !self.before.get(input)
    }

    fn fell(&self, input: Input) -> bool {
        !self.now.get(input) && self.before.get(input)
    }

    fn opened(&self, output: Output) -> bool {
        self.out.get(output) && !self.out_before.get(output)
    }
}

/// A [`Checker`] fed with raw images of a project.
#[derive(Debug, Clone)]
pub struct ProjectChecker {
    io: IoMap,
    checker: Checker,
}

impl ProjectChecker {
    /// Checks one scan: the project's raw input image at `time_ms` and its
    /// output image.
    pub fn observe(
        &mut self,
        time_ms: u64,
        inputs: &[bool],
        outputs: &[bool],
    ) -> Result<(), BoilerError> {
        let inputs = self.io.inputs_of(inputs)?;
        let outputs = self.io.outputs_of(outputs)?;
        self.checker.observe(time_ms, &inputs, &outputs);
        Ok(())
    }

    /// See [`Checker::reinitialised`].
    pub fn reinitialised(&mut self) {
        self.checker.reinitialised();
    }

    /// The violations found so far.
    pub fn violations(&self) -> &[Violation] {
        self.checker.violations()
    }

    /// The violations of the whole record.
    pub fn finish(self) -> Vec<Violation> {
        self.checker.finish()
    }
}

/// The violations in rows of `(time_ms, raw inputs, raw outputs)` of
/// `project` lowered as `config`, a controller that never leaves fault
/// mode in them (rows with fault causes: [`check_replay`]).
pub fn check_rows<'r>(
    project: &Project,
    config: &Config<'_>,
    rules: Invariants,
    rows: impl IntoIterator<Item = (u64, &'r [bool], &'r [bool])>,
) -> Result<Vec<Violation>, BoilerError> {
    let mut checker = Checker::for_project(project, config, rules)?;
    for (time_ms, inputs, outputs) in rows {
        checker.observe(time_ms, inputs, outputs)?;
    }
    Ok(checker.finish())
}

/// The violations in a replay of `project` lowered as `config`: the
/// input rows and the trace they produced, scan by scan.
pub fn check_replay(
    project: &Project,
    config: &Config<'_>,
    rules: Invariants,
    inputs: &[InputRow],
    trace: &[TraceRow],
) -> Result<Vec<Violation>, BoilerError> {
    if inputs.len() != trace.len() {
        return Err(BoilerError::RowCount {
            inputs: inputs.len(),
            trace: trace.len(),
        });
    }
    let mut checker = Checker::for_project(project, config, rules)?;
    let mut faulted = false;
    for (i, t) in inputs.iter().zip(trace) {
        if faulted && t.fault.is_none() {
            checker.reinitialised();
        }
        faulted = t.fault.is_some();
        checker.observe(t.time_ms, &i.values, &t.outputs)?;
    }
    Ok(checker.finish())
}
