//! The scan cycle (docs/semantics.md, "One scan").

use crate::inputs;
use crate::memory::{Memory, Ram};
use crate::pacing::{Pacer, ScanStart};
use crate::program::{Action, Config, Index, Program, Trigger, UnexpectedPolicy};
use crate::record::{Counters, Fault, ScanRecord};
use crate::rom_test::{ImageTest, RomTest};
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
    rom_test: RomTest,
}

impl<P: Program, M: Memory> Controller<P, M> {
    /// A controller in its initial state. The whole program image is
    /// checked first: a mismatch starts the controller in fault mode
    /// (`Corrupt`). From the first scan on, the image is checked again in
    /// the background, a share per scan.
    pub fn new(program: P, mut memory: M) -> Result<Self, SizeMismatch> {
        if !memory.fits(&program.config()) {
            return Err(SizeMismatch);
        }
        initialise(&program.config(), &mut memory.ram());
        let rom_test = RomTest::new(&program);
        let fault = (!rom_test.status().verified).then_some(Fault::Corrupt);
        let mut controller = Controller {
            program,
            memory,
            scan: 0,
            time_ms: 0,
            fault,
            executed_len: 0,
            unexpected_len: 0,
            counters: Counters::default(),
            rom_test,
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

    /// What the background image test has done.
    pub fn image_test(&self) -> ImageTest {
        self.rom_test.status()
    }

    /// Checks the whole program image now, as at start-up, apart from the
    /// background test (whose pass goes on where it was); a mismatch is a
    /// `Corrupt` fault.
    pub fn check_image(&mut self) -> bool {
        let intact = crate::image::crc(&self.program) == self.program.recorded_crc();
        self.rom_test.record(intact);
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
    /// (one value per input in declaration order) and returns its record.
    pub fn scan(&mut self, now_ms: u32, raw: &[bool]) -> ScanRecord<'_> {
        let first = self.scan == 0;
        let config = &self.program.config();
        let mut ram = self.memory.ram();
        inputs::sample(config, &mut ram, raw, first);
        self.executed_len = 0;
        self.unexpected_len = 0;

        // A state index out of range can only come from corruption; so can
        // a background image pass that ends on another CRC.
        let image_failed = self.rom_test.step(&self.program) == Some(false);
        let corrupt = image_failed
            || ram
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
            let reset = config.reset.is_some_and(|r| inputs::rising(&[r], &ram));
            // Only onto an image whose last complete check matched.
            if reset && self.rom_test.status().verified {
                initialise(config, &mut ram);
                self.fault = None;
                write_outputs(config, &mut ram);
            } else {
                write_safe_outputs(config, &mut ram);
            }
            return self.finish(now_ms);
        }

        // Step 3 and the triggers of step 4: which events occurred.
        for (e, spec) in config.events.iter().enumerate() {
            let fired = match spec.trigger {
                Trigger::Command => false,
                Trigger::Rising(list) => inputs::rising(list.of(config.input_lists), &ram),
                Trigger::Falling(list) => inputs::falling(list.of(config.input_lists), &ram),
                Trigger::Expired(t) => {
                    let t = t as usize;
                    ram.timer_running.get(t).copied().unwrap_or(false)
                        && due(ram.timer_deadline[t], now_ms)
                }
            };
            ram.occurred[e] = fired
                && inputs::all(spec.when.of(config.input_lists), ram.filtered)
                && !inputs::any(spec.unless.of(config.input_lists), ram.filtered);
            ram.done[e] = false;
        }
        for t in 0..config.timers.len() {
            if ram.timer_running[t] && due(ram.timer_deadline[t], now_ms) {
                ram.timer_running[t] = false;
            }
        }

        // Step 4: uncontrollable phase, in declaration order.
        let mut executed = 0usize;
        let mut unexpected = 0usize;
        for e in 0..config.events.len() {
            if !ram.occurred[e] {
                continue;
            }
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
                    && !ram.done[e]
                    && spec
                        .request
                        .is_none_or(|r| ram.filtered.get(r as usize).copied().unwrap_or(false))
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
    ram.done[e] = true;
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
