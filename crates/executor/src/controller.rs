//! The scan cycle (docs/semantics.md, "One scan").

use crate::bits;
use crate::image::{CrcEngine, TableCrc};
use crate::inputs;
use crate::memory::{Memory, Ram};
use crate::pacing::{Pacer, ScanStart};
use crate::program::{
    Action, Config, EventSpec, Index, InputSpec, Program, SupervisorSpec, Trigger, UnexpectedPolicy,
};
use crate::record::{Counters, Fault, ScanRecord};
use crate::rom_test::{ImageTest, RomTest};
use crate::table::Layouts;
use crate::timers::{due, earliest};

/// The memory does not match the program's sizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SizeMismatch;

/// A running controller: a program, its memory, the scan counter and the
/// fault state; `C` computes the image CRC (in software by default, or a
/// board's CRC unit: [`Controller::new_proven_with_crc`]).
pub struct Controller<P: Program, M: Memory, C: CrcEngine = TableCrc> {
    program: P,
    /// Crate-visible so that tests can simulate a flipped RAM bit.
    pub(crate) memory: M,
    scan: u32,
    time_ms: u32,
    fault: Option<Fault>,
    executed_len: usize,
    unexpected_len: usize,
    counters: Counters,
    /// Some debounce counter is above 0.
    counting: bool,
    /// The last controllable phase found no command it could choose (not
    /// counting those it had executed), and no input or state has changed
    /// since: the next controllable phase would find none either.
    pub(crate) idle: bool,
    /// The output image no longer matches the states and latched levels.
    outputs_stale: bool,
    /// The earliest deadline of the running timers.
    next_due: Option<u32>,
    /// The supervisor whose state this scan checks for range.
    pub(crate) range_check: usize,
    /// The background image check.
    rom_test: RomTest,
    /// The image passed the structure check at construction
    /// ([`crate::validate`]); if not, no reset leaves fault mode.
    well_formed: bool,
    /// Computes the image CRC.
    crc: C,
}

impl<P: Program, M: Memory> Controller<P, M> {
    /// A controller in its initial state. The whole program image is
    /// checked first, its structure ([`crate::validate`]) and its CRC: a
    /// flaw or a mismatch starts the controller in fault mode (`Corrupt`),
    /// and after a flaw of structure nothing of the image is run and no
    /// reset leaves fault mode. From the first scan on, the CRC is checked
    /// again in the background, a share per scan.
    pub fn new(program: P, memory: M) -> Result<Self, SizeMismatch> {
        Self::start::<true>(program, memory, TableCrc)
    }

    /// [`Controller::new`] for a program whose image was proven when its
    /// CRC was recorded: a generated program (the generator runs
    /// [`crate::validate::validate_generated`] before it records the CRC)
    /// or words [`crate::parse::load`] accepted. Its structure is not
    /// checked again, so that check's code (3.7 KB of a Cortex-M4 board
    /// image) is not linked; the CRC is: nothing of the image runs before
    /// it matches the recorded one, and then the image is the one proven.
    /// A mismatch is a `Corrupt` fault, whose scans read the image only
    /// through bounds-checked accessors (sampling, the reset input, the
    /// safe output levels), as after a flaw of structure. For a program
    /// built any other way, use [`Controller::new`].
    pub fn new_proven(program: P, memory: M) -> Result<Self, SizeMismatch> {
        Self::start::<false>(program, memory, TableCrc)
    }
}

impl<P: Program, M: Memory, C: CrcEngine> Controller<P, M, C> {
    /// [`Controller::new`] whose image CRC, at start-up, in the background
    /// and in [`Controller::check_image`], `crc` computes: a board's CRC
    /// unit ([`crate::image::CrcEngine`]).
    pub fn new_with_crc(program: P, memory: M, crc: C) -> Result<Self, SizeMismatch> {
        Self::start::<true>(program, memory, crc)
    }

    /// [`Controller::new_proven`] whose image CRC `crc` computes, as
    /// [`Controller::new_with_crc`]. The controller holds the engine, so
    /// nothing else feeds it between two shares of a background pass;
    /// [`Controller::check_image`] does, on the same engine, and a unit
    /// that cannot load its register (an STM32F4's) then computes the rest
    /// of the pass under way in software: the same result, more slowly.
    pub fn new_proven_with_crc(program: P, memory: M, crc: C) -> Result<Self, SizeMismatch> {
        Self::start::<false>(program, memory, crc)
    }

    /// A controller in its initial state once its image is checked: its
    /// structure when `CHECK_STRUCTURE`, and its CRC.
    #[inline]
    fn start<const CHECK_STRUCTURE: bool>(
        program: P,
        mut memory: M,
        mut crc: C,
    ) -> Result<Self, SizeMismatch> {
        if !memory.fits(&program.config()) {
            return Err(SizeMismatch);
        }
        let well_formed = !CHECK_STRUCTURE || crate::validate::validate(&program).is_ok();
        let rom_test = RomTest::new(&program, &mut crc);
        let verified = rom_test.status().verified;
        // A proven image is run only once its CRC matched; a checked one
        // as soon as its structure is sound.
        if well_formed && (CHECK_STRUCTURE || verified) {
            initialise(&program, &program.config(), &mut memory);
        }
        let fault = (!well_formed || !verified).then_some(Fault::Corrupt);
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
            idle: false,
            outputs_stale: true,
            next_due: None,
            range_check: 0,
            rom_test,
            well_formed,
            crc,
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

    /// Timer `t`'s deadline (ms on the scan clock, wrapping) while it
    /// runs; `None` when it is stopped or there is no timer `t`. A timer
    /// whose deadline has passed expires at the next scan.
    pub fn timer_deadline(&self, t: usize) -> Option<u32> {
        let (running, deadline) = self.memory.timers();
        running
            .get(t)
            .copied()
            .filter(|&r| r)
            .and_then(|_| deadline.get(t).copied())
    }

    /// The record of the last scan (before the first scan: scan 0 with
    /// the initial state and an all-zero output image).
    pub fn record(&self) -> ScanRecord<'_> {
        ScanRecord {
            scan: self.scan.saturating_sub(1),
            time_ms: self.time_ms,
            executed: prefix(self.memory.executed(), self.executed_len),
            unexpected: prefix(self.memory.unexpected(), self.unexpected_len),
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
        let intact =
            crate::image::crc_with(&self.program, &mut self.crc) == self.program.recorded_crc();
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
    /// (one value per input in declaration order; missing inputs read as
    /// 0) and returns its record.
    pub fn scan(&mut self, now_ms: u32, raw: &[bool]) -> ScanRecord<'_> {
        self.check_image_share();
        let inputs = self.program.config().inputs.len();
        inputs::pack(raw, inputs, self.memory.ram().raw);
        self.run(now_ms);
        self.record()
    }

    /// [`Controller::scan`] with the raw input image packed 32 inputs to a
    /// word, input `i` at bit `i % 32` of word `i / 32`, as a board reads
    /// its ports (missing words read as 0, bits of no input are ignored).
    pub fn scan_packed(&mut self, now_ms: u32, raw: &[u32]) -> ScanRecord<'_> {
        self.check_image_share();
        self.step_packed(now_ms, raw);
        self.record()
    }

    /// The background image test's share of one scan
    /// (`rom_test_bytes_per_scan` bytes of the program image,
    /// docs/semantics.md, "Image check"): every scan starts with it.
    /// [`Controller::scan`] and [`Controller::scan_packed`] run it
    /// themselves; a board runs it before sampling its inputs, then
    /// [`Controller::step_packed`], so that the input-to-output path does
    /// not include it. A pass that ends on another CRC is a `Corrupt`
    /// fault, which the scan that follows handles (safe image). `Some`
    /// with the verdict when this share completed a pass.
    pub fn check_image_share(&mut self) -> Option<bool> {
        let verdict = self.rom_test.step(&self.program, &mut self.crc);
        if verdict == Some(false) {
            self.enter_fault(Fault::Corrupt);
        }
        verdict
    }

    /// The rest of a scan after its image share: sample `raw` (packed as
    /// in [`Controller::scan_packed`]), run the phases, write the output
    /// image, without building the record. Read the outputs
    /// ([`Controller::outputs`]) or the record ([`Controller::record`])
    /// after it when needed.
    pub fn step_packed(&mut self, now_ms: u32, raw: &[u32]) {
        let inputs = self.program.config().inputs.len();
        inputs::copy_packed(raw, inputs, self.memory.ram().raw);
        self.run(now_ms);
    }

    /// One scan of the raw image in memory.
    fn run(&mut self, now_ms: u32) {
        let first = self.scan == 0;
        let config = &self.program.config();
        let changed = inputs::sample(config, &mut self.memory.ram(), first, &mut self.counting);
        if self.executed_len != 0 {
            self.memory.ram().done.fill(0);
        }
        self.executed_len = 0;
        self.unexpected_len = 0;

        // A state index out of range can only come from corruption. Every
        // scan checks one supervisor in turn (all of them within S scans),
        // and `execute` checks those it is about to move.
        let j = self.range_check;
        let corrupt = match config.supervisors.get(j) {
            Some(spec) => self
                .memory
                .states()
                .get(j)
                .is_some_and(|&x| x >= SupervisorSpec::from_words(spec).states),
            None => false,
        };
        self.range_check = if j + 1 < config.supervisors.len() {
            j + 1
        } else {
            0
        };
        if corrupt && self.fault.is_none() {
            self.fault = Some(Fault::Corrupt);
            self.counters.faults = self.counters.faults.wrapping_add(1);
        }

        // Step 2: fault mode.
        if self.fault.is_some() {
            let reset = config
                .reset
                .is_some_and(|r| inputs::input_rose(usize::from(r), &self.memory.ram()));
            // Only onto a well-formed image whose last complete check
            // matched.
            if reset && self.well_formed && self.rom_test.status().verified {
                initialise(&self.program, config, &mut self.memory);
                self.fault = None;
                self.idle = false;
                self.next_due = None;
                write_outputs(config, &mut self.memory);
                self.outputs_stale = false;
            } else {
                write_safe_outputs(config, &mut self.memory);
                self.outputs_stale = true;
            }
            return self.finish(now_ms);
        }

        // Step 3 and the triggers of step 4: which events occurred. Only
        // the inputs that changed can raise an edge, only the events bound
        // to them are looked at, and the timers only when one is due.
        let timer_due = self.next_due.is_some_and(|d| due(d, now_ms));
        let ram = self.memory.ram();
        if changed || timer_due {
            ram.occurred.fill(0);
        }
        if changed {
            for k in 0..ram.filtered.len() {
                let mut changes = ram.filtered[k] ^ ram.previous[k];
                while changes != 0 {
                    let i = k * 32 + changes.trailing_zeros() as usize;
                    changes &= changes - 1;
                    let Some(input) = config.inputs.get(i) else {
                        continue;
                    };
                    let raises = InputSpec::from_words(input).raises;
                    for &e in raises.of(config.event_lists) {
                        let e = e as usize;
                        if edge_occurred(config, &ram, e) {
                            bits::insert(ram.occurred, e);
                        }
                    }
                }
            }
        }
        if timer_due {
            for (t, timer) in config.timer_specs().enumerate() {
                if ram.timer_running[t] && due(ram.timer_deadline[t], now_ms) {
                    ram.timer_running[t] = false;
                    for &e in timer.raises.of(config.event_lists) {
                        let e = e as usize;
                        if config.events.get(e).is_some_and(|spec| {
                            conditions_hold(config, &ram, &EventSpec::from_words(spec))
                        }) {
                            bits::insert(ram.occurred, e);
                        }
                    }
                }
            }
            self.next_due = earliest(ram.timer_running, ram.timer_deadline, now_ms);
        }

        // Step 4: uncontrollable phase, in declaration order. `execute`
        // takes the memory itself: handing it the arrays one by one would
        // cost every scan, quiet or not, the building of their views.
        let mut executed = 0usize;
        let mut unexpected = 0usize;
        let mut timers_changed = false;
        let event_words = if changed || timer_due {
            ram.occurred.len()
        } else {
            0
        };
        for k in 0..event_words {
            let mut pending = self.memory.ram().occurred[k];
            while pending != 0 {
                let e = k * 32 + pending.trailing_zeros() as usize;
                pending &= pending - 1;
                if bits::contains(self.memory.ram().feasible, e) {
                    let Some(timers) = execute(&self.program, config, &mut self.memory, e, now_ms)
                    else {
                        return self.fault_corrupt(executed, unexpected, now_ms);
                    };
                    timers_changed |= timers;
                    *slot(self.memory.ram().executed, executed) = e as Index;
                    executed += 1;
                    continue;
                }
                *slot(self.memory.ram().unexpected, unexpected) = e as Index;
                unexpected += 1;
                match config.unexpected {
                    UnexpectedPolicy::Ignore => {
                        self.counters.ignored = self.counters.ignored.wrapping_add(1);
                    }
                    UnexpectedPolicy::Fault => {
                        self.fault = Some(Fault::Unexpected { event: e as Index });
                        self.counters.faults = self.counters.faults.wrapping_add(1);
                        write_safe_outputs(config, &mut self.memory);
                        self.outputs_stale = true;
                        self.executed_len = executed;
                        self.unexpected_len = unexpected;
                        return self.finish(now_ms);
                    }
                }
            }
        }

        // Step 5: controllable phase, skipped when it would find nothing:
        // it found nothing last time, and neither the inputs (requests)
        // nor the states (enabled events) have changed since.
        if !(self.idle && !changed && executed == 0) {
            let limit = match config.max_commands_per_scan {
                0 => usize::MAX,
                n => n as usize,
            };
            let mut commands = 0usize;
            self.idle = false;
            let choosable = Commands::now(config, &self.memory.ram());
            while commands < limit {
                let Some(e) = next_command(config, &mut self.memory, &choosable) else {
                    self.idle = !any_command(config, &mut self.memory, &choosable);
                    break;
                };
                let Some(timers) = execute(&self.program, config, &mut self.memory, e, now_ms)
                else {
                    return self.fault_corrupt(executed, unexpected, now_ms);
                };
                timers_changed |= timers;
                *slot(self.memory.ram().executed, executed) = e as Index;
                executed += 1;
                commands += 1;
            }
        }
        if timers_changed {
            let ram = self.memory.ram();
            self.next_due = earliest(ram.timer_running, ram.timer_deadline, now_ms);
        }

        // Step 6: outputs, recomputed only when an event has moved a state
        // or a latched level.
        if executed != 0 || self.outputs_stale {
            write_outputs(config, &mut self.memory);
            self.outputs_stale = false;
        }
        self.executed_len = executed;
        self.unexpected_len = unexpected;
        self.finish(now_ms)
    }

    /// A supervisor's table refused a transition its cached enabled set
    /// allowed: the cache in RAM is corrupt. Fault mode from this scan on.
    fn fault_corrupt(&mut self, executed: usize, unexpected: usize, now_ms: u32) {
        self.enter_fault(Fault::Corrupt);
        write_safe_outputs(&self.program.config(), &mut self.memory);
        self.outputs_stale = true;
        self.executed_len = executed;
        self.unexpected_len = unexpected;
        self.finish(now_ms)
    }

    fn finish(&mut self, now_ms: u32) {
        self.time_ms = now_ms;
        self.scan = self.scan.wrapping_add(1);
    }
}

/// Entry `k` of an event list in RAM (executed or unexpected events),
/// which holds one entry per event: an event is executed or found
/// unexpected at most once a scan, so `k` is in range. Indexing would
/// link the formatting of its panic message (about 1.5 KB of the
/// target's flash); this panic's message is a constant.
#[inline(always)]
fn slot(list: &mut [Index], k: usize) -> &mut Index {
    match list.get_mut(k) {
        Some(entry) => entry,
        None => panic!("more events in a scan than the program has"),
    }
}

/// The first `len` entries of an event list in RAM (`len` counts entries
/// written this scan, so it is in range): slicing with a constant panic
/// message, as [`slot`] does.
#[inline(always)]
fn prefix(list: &[Index], len: usize) -> &[Index] {
    match list.get(..len) {
        Some(entries) => entries,
        None => panic!("more events in a scan than the program has"),
    }
}

/// Every supervisor initial, every timer stopped, action-driven outputs at
/// their initial level, and the enabled sets of the initial states.
fn initialise<P: Program, M: Memory>(program: &P, config: &Config<'_>, memory: &mut M) {
    let ram = &mut memory.ram();
    for (x, spec) in ram.states.iter_mut().zip(config.supervisor_specs()) {
        *x = spec.initial;
    }
    ram.timer_running.fill(false);
    for (level, spec) in ram.latched.iter_mut().zip(config.output_specs()) {
        *level = spec.initial;
    }
    for j in 0..config.supervisors.len() {
        let ew = ram.feasible.len();
        refresh_allowed(
            program,
            config,
            j,
            ram.states[j],
            allowed_of(ram.allowed, ew, j),
        );
    }
    refresh_feasible(ram);
}

/// Supervisor `j`'s `allowed` set for `state`: the events outside its
/// alphabet, and the local events its program enables there mapped to
/// their event numbers; copied when stored ([`crate::program::AllowedSets`]).
/// A move to a state with a stored set goes to [`update_set`] instead, so
/// the stored-set branch here serves [`initialise`]: moved there, it
/// changed the code LLVM makes of the scan (QEMU, 2026-11-28: the `match`
/// backend's breakdown p99 +11 %, the boiler's table p99 −2 %).
fn refresh_allowed<P: Program>(
    program: &P,
    config: &Config<'_>,
    j: usize,
    state: u32,
    allowed: &mut [u32],
) {
    let spec = &config.supervisor(j);
    if let Some(k) = config.stored_set(spec, state) {
        match stored_words(config, k, allowed.len()) {
            Some(set) => allowed.copy_from_slice(set),
            None => allowed.fill(0),
        }
        return;
    }
    let outside = spec.outside.of(config.event_masks);
    for (k, word) in allowed.iter_mut().enumerate() {
        *word = outside.get(k).copied().unwrap_or(0);
    }
    let alphabet = spec.alphabet.of(config.event_lists);
    // A Petri-net group tests its transitions straight into the set.
    if program.layouts().has(Layouts::NET)
        && program
            .table(j as Index)
            .is_some_and(|t| t.insert_enabled_net(state, alphabet, allowed))
    {
        return;
    }
    for (chunk, events) in alphabet.chunks(32).enumerate() {
        let from = (chunk * 32) as Index;
        let mut row = program.enabled(j as Index, state, from, events.len() as u8);
        // Consecutive event numbers: the row shifted into place.
        if spec.contiguous {
            let first = events.first().map_or(0, |&e| e as usize);
            let (k, shift) = (first / 32, first % 32);
            if let Some(word) = allowed.get_mut(k) {
                *word |= row << shift;
            }
            if shift != 0 {
                if let Some(word) = allowed.get_mut(k + 1) {
                    *word |= row >> (32 - shift);
                }
            }
            continue;
        }
        while row != 0 {
            let k = row.trailing_zeros() as usize;
            row &= row - 1;
            if let Some(&e) = events.get(k) {
                bits::insert(allowed, e as usize);
            }
        }
    }
}

/// The `w` words of stored event set `k` (`None` past the pool, which the
/// structure check rules out). Found from the set's width rather than
/// [`Config::event_set`]'s checked arithmetic: the same words, in fewer
/// instructions a move.
#[inline]
fn stored_words<'c>(config: &Config<'c>, k: usize, w: usize) -> Option<&'c [u32]> {
    config.event_masks.get(k * w..k * w + w)
}

/// `allowed` := stored event set `k` (all zeros, which blocks every
/// event, past the pool); `true` when that changed it. The new state's
/// set is compared with the words in RAM rather than with the old state's
/// set number, which would be one more packed read a move.
#[inline]
fn update_set(config: &Config<'_>, k: usize, allowed: &mut [u32]) -> bool {
    match stored_words(config, k, allowed.len()) {
        // Word by word: slice equality would call `memcmp`.
        Some(set) if set.iter().zip(allowed.iter()).all(|(a, b)| a == b) => false,
        Some(set) => {
            allowed.copy_from_slice(set);
            true
        }
        None => {
            allowed.fill(0);
            true
        }
    }
}

/// Supervisor `j`'s words of the `allowed` sets (empty past the last).
#[inline]
fn allowed_of(allowed: &mut [u32], event_words: usize, j: usize) -> &mut [u32] {
    allowed
        .get_mut(j * event_words..(j + 1) * event_words)
        .unwrap_or_default()
}

/// The events no supervisor blocks (feasible, unless a guard holds a
/// command back: [`next_command`]).
fn refresh_feasible(ram: &mut Ram<'_>) {
    // With two or three words the words are held in registers across the
    // rows (a row is a few loads and ANDs); otherwise word by word.
    let ew = ram.feasible.len();
    if ew == 2 || ew == 3 {
        return and_rows(ram.allowed, ram.feasible);
    }
    for (k, word) in ram.feasible.iter_mut().enumerate() {
        *word = ram
            .allowed
            .iter()
            .skip(k)
            .step_by(ew.max(1))
            .fold(u32::MAX, |w, a| w & a);
    }
}

/// `feasible` (two or three words) := the AND of the rows of `allowed`,
/// the words held in registers across the rows (a row is a few loads and
/// ANDs, whatever the supervisor count). Out of line: inlined, it would
/// cost a one-word program's scan more than it saves.
#[inline(never)]
fn and_rows(allowed: &[u32], feasible: &mut [u32]) {
    fn and<const N: usize>(allowed: &[u32], feasible: &mut [u32]) {
        let mut words = [u32::MAX; N];
        for row in allowed.chunks_exact(N) {
            for (word, &a) in words.iter_mut().zip(row) {
                *word &= a;
            }
        }
        for (out, word) in feasible.iter_mut().zip(words) {
            *out = word;
        }
    }
    if feasible.len() == 2 {
        and::<2>(allowed, feasible);
    } else {
        and::<3>(allowed, feasible);
    }
}

/// Word `k` of `candidates` (commands the supervisors allow) without the
/// guarded ones whose guard does not hold in `states` ([`crate::guards`]).
/// Guards hold only commands back, and only states move them, so they are
/// asked here, of the candidates, rather than kept with the feasible set.
#[inline]
fn unguarded(config: &Config<'_>, states: &[u32], k: usize, mut candidates: u32) -> u32 {
    let guards = &config.guards;
    for guard in guards.guards() {
        let e = usize::from(guard.event);
        let bit = 1u32 << (e % 32);
        if e / 32 == k && candidates & bit != 0 && !guards.holds(&guard, states) {
            candidates &= !bit;
        }
    }
    candidates
}

/// Event words whose commands the controllable phase works out once per
/// scan ([`Commands::now`]); a program with more events works out the
/// words past these at each choice.
pub(crate) const CACHED_COMMAND_WORDS: usize = 8;

/// The commands the controller may choose in this scan: those without a
/// request input, and those whose request input is 1. Requests are
/// inputs, fixed for the scan, so the set is worked out once, before the
/// first choice, not at every choice (the batch cell's 19 requested
/// commands were read again for each of up to 11 commands a scan).
pub(crate) struct Commands {
    words: [u32; CACHED_COMMAND_WORDS],
}

impl Commands {
    /// The commands that may be chosen now.
    #[inline]
    pub(crate) fn now(config: &Config<'_>, ram: &Ram<'_>) -> Commands {
        let mut words = [0u32; CACHED_COMMAND_WORDS];
        for (word, &mask) in words.iter_mut().zip(config.commands.of(config.event_masks)) {
            *word = mask;
        }
        for &e in config.requested.of(config.event_lists) {
            let e = e as usize;
            if let Some(word) = words.get_mut(e / 32) {
                if requested_now(config, ram, e) {
                    *word |= 1 << (e % 32);
                }
            }
        }
        Commands { words }
    }

    /// Word `k` of the commands that may be chosen now.
    #[inline]
    pub(crate) fn word(&self, config: &Config<'_>, ram: &Ram<'_>, k: usize) -> u32 {
        match self.words.get(k) {
            Some(&word) => word,
            None => commands_word(config, ram, k),
        }
    }
}

/// Command `e` has a request input, and it is 1.
#[inline]
fn requested_now(config: &Config<'_>, ram: &Ram<'_>, e: usize) -> bool {
    config
        .event(e)
        .request
        .is_some_and(|r| inputs::input_on(usize::from(r), ram))
}

/// Word `k` of the commands the controller may choose now, worked out
/// from the configuration (words past [`CACHED_COMMAND_WORDS`]). The
/// same set as [`Commands::now`], one word at a time (a test compares
/// them word by word): one function with a word range for both cost the
/// batch cell 450 instructions at its p99 and max (QEMU, 2026-11-28).
#[inline(never)]
pub(crate) fn commands_word(config: &Config<'_>, ram: &Ram<'_>, k: usize) -> u32 {
    let mut word = config
        .commands
        .of(config.event_masks)
        .get(k)
        .copied()
        .unwrap_or(0);
    for &e in config.requested.of(config.event_lists) {
        let e = e as usize;
        if e / 32 == k && requested_now(config, ram, e) {
            word |= 1 << (e % 32);
        }
    }
    word
}

/// The first command in declaration order that is feasible, may be
/// chosen now and has not run in this scan.
#[inline]
fn next_command<M: Memory>(
    config: &Config<'_>,
    memory: &mut M,
    commands: &Commands,
) -> Option<usize> {
    if !config.guards.events.is_empty() {
        return next_guarded_command(config, memory, commands);
    }
    let ram = &memory.ram();
    (0..ram.feasible.len()).find_map(|k| {
        let candidates = ram.feasible[k] & commands.word(config, ram, k) & !ram.done[k];
        (candidates != 0).then(|| k * 32 + candidates.trailing_zeros() as usize)
    })
}

/// [`next_command`] of a program with guards: the candidates' guards are
/// asked too. Out of line, so that a program without guards keeps its
/// scan's code as it was before guards.
#[inline(never)]
fn next_guarded_command<M: Memory>(
    config: &Config<'_>,
    memory: &mut M,
    commands: &Commands,
) -> Option<usize> {
    let ram = &memory.ram();
    (0..ram.feasible.len()).find_map(|k| {
        let mut candidates = ram.feasible[k] & commands.word(config, ram, k) & !ram.done[k];
        if candidates != 0 {
            candidates = unguarded(config, ram.states, k, candidates);
        }
        (candidates != 0).then(|| k * 32 + candidates.trailing_zeros() as usize)
    })
}

/// Some command is feasible and may be chosen now, executed in this scan
/// or not.
fn any_command<M: Memory>(config: &Config<'_>, memory: &mut M, commands: &Commands) -> bool {
    if !config.guards.events.is_empty() {
        return any_guarded_command(config, memory, commands);
    }
    let ram = &memory.ram();
    (0..ram.feasible.len()).any(|k| ram.feasible[k] & commands.word(config, ram, k) != 0)
}

/// [`any_command`] of a program with guards.
#[inline(never)]
fn any_guarded_command<M: Memory>(
    config: &Config<'_>,
    memory: &mut M,
    commands: &Commands,
) -> bool {
    let ram = &memory.ram();
    (0..ram.feasible.len()).any(|k| {
        let candidates = ram.feasible[k] & commands.word(config, ram, k);
        candidates != 0 && unguarded(config, ram.states, k, candidates) != 0
    })
}

/// An edge event whose binding changed: its edge happened and its
/// conditions hold in F\[k\].
#[inline]
fn edge_occurred(config: &Config<'_>, ram: &Ram<'_>, e: usize) -> bool {
    let Some(spec) = config.events.get(e) else {
        return false;
    };
    let spec = &EventSpec::from_words(spec);
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

/// Moves every supervisor having the (feasible) event, refreshes the
/// allowed sets of those that moved to a state with another set (and then
/// the feasible set) and applies the event's actions.
/// `Some(true)` when a timer was started or stopped; `None` when a
/// supervisor's state is out of range, its program refuses the event its
/// enabled set allowed (corrupt memory) or gives a state out of range (a
/// table word flipped since start-up).
fn execute<P: Program, M: Memory>(
    program: &P,
    config: &Config<'_>,
    memory: &mut M,
    e: usize,
    now: u32,
) -> Option<bool> {
    let ram = &mut memory.ram();
    let event = &config.event(e);
    let mut moved = false;
    for m in config.members_of(event.members) {
        let j = m.supervisor as usize;
        let sup = &config.supervisor(j);
        let state = *ram.states.get(j)?;
        if state >= sup.states {
            return None;
        }
        let next = program.next_state(m.supervisor, state, m.local)?;
        // Validated tables hold states in range; a word flipped since
        // is caught here before the state is stored.
        if next >= sup.states {
            return None;
        }
        if next != state {
            let ew = ram.feasible.len();
            let allowed = allowed_of(ram.allowed, ew, j);
            match config.stored_set(sup, next) {
                // Most moves keep the set: nothing to copy or AND.
                Some(new) => moved |= update_set(config, new, allowed),
                None => {
                    refresh_allowed(program, config, j, next, allowed);
                    moved = true;
                }
            }
            if let Some(x) = ram.states.get_mut(j) {
                *x = next;
            }
        }
    }
    if moved {
        refresh_feasible(ram);
    }
    let mut timers = false;
    for action in config.actions_of(event.actions) {
        match action {
            Action::Set(o) => ram.latched[o as usize] = true,
            Action::Clear(o) => ram.latched[o as usize] = false,
            Action::Start(t) => {
                let t = t as usize;
                ram.timer_running[t] = true;
                ram.timer_deadline[t] = now.wrapping_add(config.timer(t).preset_ms);
                timers = true;
            }
            Action::Reset(t) => {
                ram.timer_running[t as usize] = false;
                timers = true;
            }
        }
    }
    bits::insert(ram.done, e);
    Some(timers)
}

/// Action-driven levels, and for Moore outputs the OR over their state map.
fn write_outputs<M: Memory>(config: &Config<'_>, memory: &mut M) {
    let ram = memory.ram();
    for (o, spec) in config.output_specs().enumerate() {
        ram.outputs[o] = if spec.state_map.is_empty() {
            ram.latched[o]
        } else {
            config.state_map_of(spec.state_map).any(|entry| {
                ram.states
                    .get(entry.supervisor as usize)
                    .is_some_and(|&x| entry.holds(x))
            })
        };
    }
}

fn write_safe_outputs<M: Memory>(config: &Config<'_>, memory: &mut M) {
    let ram = memory.ram();
    for (level, spec) in ram.outputs.iter_mut().zip(config.output_specs()) {
        *level = spec.safe;
    }
}
