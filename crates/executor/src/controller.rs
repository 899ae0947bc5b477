//! The scan cycle (docs/semantics.md, "One scan").

use crate::bits;
use crate::inputs;
use crate::memory::{Memory, Ram};
use crate::pacing::{Pacer, ScanStart};
use crate::program::{Action, Config, EventSpec, Index, Program, Trigger, UnexpectedPolicy};
use crate::record::{Counters, Fault, ScanRecord};
use crate::timers::due;

/// The memory does not match the program's sizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SizeMismatch;

/// A running controller: a program, its memory, the scan counter and the
/// fault state.
pub struct Controller<P: Program, M: Memory> {
    program: P,
    memory: M,
    scan: u32,
    time_ms: u32,
    fault: Option<Fault>,
    executed_len: usize,
    unexpected_len: usize,
    counters: Counters,
    /// Some debounce counter is above 0.
    counting: bool,
}

impl<P: Program, M: Memory> Controller<P, M> {
    /// A controller in its initial state. The program image is checked
    /// first: a mismatch starts the controller in fault mode (`Corrupt`).
    pub fn new(program: P, mut memory: M) -> Result<Self, SizeMismatch> {
        if !memory.fits(&program.config()) {
            return Err(SizeMismatch);
        }
        initialise(&program.config(), &mut memory.ram());
        let fault = (!program.image_intact()).then_some(Fault::Corrupt);
        let mut controller = Controller {
            program,
            memory,
            scan: 0,
            time_ms: 0,
            fault,
            executed_len: 0,
            unexpected_len: 0,
            counters: Counters::default(),
            counting: false,
        };
        if fault.is_some() {
            controller.counters.faults += 1;
        }
        Ok(controller)
    }

    /// The program.
    pub fn program(&self) -> &P {
        &self.program
    }

    /// The current fault, if in fault mode.
    pub fn fault(&self) -> Option<Fault> {
        self.fault
    }

    /// Counters of ignored events, overruns, skipped periods, lost edges
    /// and faults.
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// The number of the next scan.
    pub fn next_scan(&self) -> u32 {
        self.scan
    }

    /// The supervisor states.
    pub fn states(&self) -> &[u32] {
        self.memory.states()
    }

    /// The output image of the last scan.
    pub fn outputs(&self) -> &[bool] {
        self.memory.outputs()
    }

    /// The record of the last scan (before the first scan: scan 0 with
    /// the initial state and an all-zero output image).
    pub fn record(&self) -> ScanRecord<'_> {
        ScanRecord {
            scan: self.scan.saturating_sub(1),
            time_ms: self.time_ms,
            executed: &self.memory.executed()[..self.executed_len],
            unexpected: &self.memory.unexpected()[..self.unexpected_len],
            states: self.memory.states(),
            outputs: self.memory.outputs(),
            fault: self.fault,
        }
    }

    /// Polls the scan schedule `pacer` (built from this program's
    /// [`Config`]: [`Pacer::for_config`]) at `now_ms`. When a scan is due,
    /// counts the periods it skipped and, when it starts more than
    /// `overrun_limit` periods late, reports an overrun
    /// ([`Controller::report_overrun`]), then returns its start: the caller
    /// samples the inputs and runs [`Controller::scan`] at
    /// `start.time_ms`. `None` before the deadline.
    pub fn scan_due(&mut self, pacer: &mut Pacer, now_ms: u32) -> Option<ScanStart> {
        let start = pacer.poll(now_ms)?;
        self.counters.skipped_periods = self.counters.skipped_periods.wrapping_add(start.skipped);
        if start.overrun {
            self.report_overrun();
        }
        Some(start)
    }

    /// A scan started too late: counted, and a fault from the next scan
    /// on when the project says so. [`Controller::scan_due`] judges and
    /// reports overruns; this is for callers that pace scans otherwise.
    pub fn report_overrun(&mut self) {
        self.counters.overruns = self.counters.overruns.wrapping_add(1);
        if self.program.config().overrun_fault {
            self.enter_fault(Fault::Overrun);
        }
    }

    /// An input changed more than once between two samples: counted, and a
    /// fault when the project says so.
    pub fn report_lost_edge(&mut self) {
        self.counters.lost_edges = self.counters.lost_edges.wrapping_add(1);
        if self.program.config().lost_edge_fault {
            self.enter_fault(Fault::LostEdge);
        }
    }

    /// Checks the program image now; a mismatch is a `Corrupt` fault.
    pub fn check_image(&mut self) -> bool {
        let intact = self.program.image_intact();
        if !intact {
            self.enter_fault(Fault::Corrupt);
        }
        intact
    }

    fn enter_fault(&mut self, fault: Fault) {
        if self.fault.is_none() {
            self.fault = Some(fault);
            self.counters.faults = self.counters.faults.wrapping_add(1);
        }
    }

    /// Runs one scan at time `now_ms` with the raw input image `raw`
    /// (one value per input in declaration order; missing inputs read as
    /// 0) and returns its record.
    pub fn scan(&mut self, now_ms: u32, raw: &[bool]) -> ScanRecord<'_> {
        let inputs = self.program.config().inputs.len();
        inputs::pack(raw, inputs, self.memory.ram().raw);
        self.run(now_ms)
    }

    /// [`Controller::scan`] with the raw input image packed 32 inputs to a
    /// word, input `i` at bit `i % 32` of word `i / 32`, as a board reads
    /// its ports (missing words read as 0, bits of no input are ignored).
    pub fn scan_packed(&mut self, now_ms: u32, raw: &[u32]) -> ScanRecord<'_> {
        let inputs = self.program.config().inputs.len();
        inputs::copy_packed(raw, inputs, self.memory.ram().raw);
        self.run(now_ms)
    }

    /// One scan of the raw image in memory.
    fn run(&mut self, now_ms: u32) -> ScanRecord<'_> {
        let first = self.scan == 0;
        let config = &self.program.config();
        let mut ram = self.memory.ram();
        let changed = inputs::sample(config, &mut ram, first, &mut self.counting);
        self.executed_len = 0;
        self.unexpected_len = 0;

        // A state index out of range can only come from corruption.
        let corrupt = ram
            .states
            .iter()
            .zip(config.supervisors)
            .any(|(&x, spec)| x >= spec.states);
        if corrupt && self.fault.is_none() {
            self.fault = Some(Fault::Corrupt);
            self.counters.faults = self.counters.faults.wrapping_add(1);
        }

        // Step 2: fault mode.
        if self.fault.is_some() {
            let reset = config
                .reset
                .is_some_and(|r| inputs::input_rose(usize::from(r), &ram));
            if reset && self.program.image_intact() {
                initialise(config, &mut ram);
                self.fault = None;
                write_outputs(config, &mut ram);
            } else {
                write_safe_outputs(config, &mut ram);
            }
            return self.finish(now_ms);
        }

        // Step 3 and the triggers of step 4: which events occurred. Only
        // the inputs that changed can raise an edge, and only the events
        // bound to them are looked at.
        ram.occurred.fill(0);
        ram.done.fill(0);
        if changed {
            for k in 0..ram.filtered.len() {
                let mut changes = ram.filtered[k] ^ ram.previous[k];
                while changes != 0 {
                    let i = k * 32 + changes.trailing_zeros() as usize;
                    changes &= changes - 1;
                    let Some(input) = config.inputs.get(i) else {
                        continue;
                    };
                    for &e in input.raises.of(config.raised) {
                        if edge_occurred(config, &ram, usize::from(e)) {
                            bits::insert(ram.occurred, usize::from(e));
                        }
                    }
                }
            }
        }
        for (t, timer) in config.timers.iter().enumerate() {
            if ram.timer_running[t] && due(ram.timer_deadline[t], now_ms) {
                ram.timer_running[t] = false;
                for &e in timer.raises.of(config.raised) {
                    let e = usize::from(e);
                    if config.events.get(e).is_some_and(|spec| conditions_hold(config, &ram, spec)) {
                        bits::insert(ram.occurred, e);
                    }
                }
            }
        }

        // Step 4: uncontrollable phase, in declaration order.
        let mut executed = 0usize;
        let mut unexpected = 0usize;
        for k in 0..ram.occurred.len() {
            let mut pending = ram.occurred[k];
            while pending != 0 {
                let e = k * 32 + pending.trailing_zeros() as usize;
                pending &= pending - 1;
                if feasible(&self.program, config, &ram, e) {
                    execute(&self.program, config, &mut ram, e, now_ms);
                    ram.executed[executed] = e as Index;
                    executed += 1;
                    continue;
                }
                ram.unexpected[unexpected] = e as Index;
                unexpected += 1;
                match config.unexpected {
                    UnexpectedPolicy::Ignore => {
                        self.counters.ignored = self.counters.ignored.wrapping_add(1);
                    }
                    UnexpectedPolicy::Fault => {
                        self.fault = Some(Fault::Unexpected { event: e as Index });
                        self.counters.faults = self.counters.faults.wrapping_add(1);
                        write_safe_outputs(config, &mut ram);
                        self.executed_len = executed;
                        self.unexpected_len = unexpected;
                        return self.finish(now_ms);
                    }
                }
            }
        }

        // Step 5: controllable phase.
        let limit = match config.max_commands_per_scan {
            0 => usize::MAX,
            n => n as usize,
        };
        let mut commands = 0usize;
        while commands < limit {
            let choice = (0..config.events.len()).find(|&e| {
                let spec = &config.events[e];
                spec.is_controllable()
                    && !bits::contains(ram.done, e)
                    && spec
                        .request
                        .is_none_or(|r| inputs::input_on(usize::from(r), &ram))
                    && feasible(&self.program, config, &ram, e)
            });
            let Some(e) = choice else { break };
            execute(&self.program, config, &mut ram, e, now_ms);
            ram.executed[executed] = e as Index;
            executed += 1;
            commands += 1;
        }

        // Step 6: outputs.
        write_outputs(config, &mut ram);
        self.executed_len = executed;
        self.unexpected_len = unexpected;
        self.finish(now_ms)
    }

    fn finish(&mut self, now_ms: u32) -> ScanRecord<'_> {
        self.time_ms = now_ms;
        self.scan = self.scan.wrapping_add(1);
        self.record()
    }
}

/// Every supervisor initial, every timer stopped, action-driven outputs at
/// their initial level.
fn initialise(config: &Config<'_>, ram: &mut Ram<'_>) {
    for (x, spec) in ram.states.iter_mut().zip(config.supervisors) {
        *x = spec.initial;
    }
    ram.timer_running.fill(false);
    for (level, spec) in ram.latched.iter_mut().zip(config.outputs) {
        *level = spec.initial;
    }
}

/// An edge event whose binding changed: its edge happened and its
/// conditions hold in F\[k\].
#[inline]
fn edge_occurred(config: &Config<'_>, ram: &Ram<'_>, e: usize) -> bool {
    let Some(spec) = config.events.get(e) else {
        return false;
    };
    let edge = match spec.trigger {
        Trigger::Rising(mask) => inputs::rising(mask.of(config.input_masks), ram),
        Trigger::Falling(mask) => inputs::falling(mask.of(config.input_masks), ram),
        Trigger::Command | Trigger::Expired(_) => false,
    };
    edge && conditions_hold(config, ram, spec)
}

/// `when` (all 1) and `unless` (all 0) of an event in F\[k\].
#[inline]
fn conditions_hold(config: &Config<'_>, ram: &Ram<'_>, spec: &EventSpec) -> bool {
    inputs::all(spec.when.of(config.input_masks), ram.filtered)
        && !inputs::any(spec.unless.of(config.input_masks), ram.filtered)
}

/// An event is feasible when every supervisor having it can take it.
#[inline]
fn feasible<P: Program>(program: &P, config: &Config<'_>, ram: &Ram<'_>, e: usize) -> bool {
    config.events[e]
        .members
        .of(config.memberships)
        .iter()
        .all(|m| {
            program
                .next_state(m.supervisor, ram.states[m.supervisor as usize], m.local)
                .is_some()
        })
}

/// Moves every supervisor having the (feasible) event and applies its
/// actions.
fn execute<P: Program>(program: &P, config: &Config<'_>, ram: &mut Ram<'_>, e: usize, now: u32) {
    let spec = &config.events[e];
    for m in spec.members.of(config.memberships) {
        let j = m.supervisor as usize;
        if let Some(next) = program.next_state(m.supervisor, ram.states[j], m.local) {
            ram.states[j] = next;
        }
    }
    for action in spec.actions.of(config.actions) {
        match *action {
            Action::Set(o) => ram.latched[o as usize] = true,
            Action::Clear(o) => ram.latched[o as usize] = false,
            Action::Start(t) => {
                let t = t as usize;
                ram.timer_running[t] = true;
                ram.timer_deadline[t] = now.wrapping_add(config.timers[t].preset_ms);
            }
            Action::Reset(t) => ram.timer_running[t as usize] = false,
        }
    }
    bits::insert(ram.done, e);
}

/// Action-driven levels, and for Moore outputs the OR over their state map.
fn write_outputs(config: &Config<'_>, ram: &mut Ram<'_>) {
    for (o, spec) in config.outputs.iter().enumerate() {
        ram.outputs[o] = if spec.state_map.is_empty() {
            ram.latched[o]
        } else {
            spec.state_map.of(config.state_map).iter().any(|entry| {
                ram.states
                    .get(entry.supervisor as usize)
                    .is_some_and(|&x| x == entry.state)
            })
        };
    }
}

fn write_safe_outputs(config: &Config<'_>, ram: &mut Ram<'_>) {
    for (level, spec) in ram.outputs.iter_mut().zip(config.outputs) {
        *level = spec.safe;
    }
}
