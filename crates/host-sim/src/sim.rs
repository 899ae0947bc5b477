//! Running a project on the host: a virtual clock, the executor, and the
//! trace.
//!
//! The clock follows the executor's scan schedule ([`executor::pacing`]),
//! as the firmware's loop does: scans start on the grid of
//! `scan_period_ms` from time 0, and scans take no time. A stall
//! ([`Sim::stall`]) holds the controller right after its last scan; the
//! next scan starts when the stall ends if a deadline has passed by then
//! (else at the deadline), the periods it missed are skipped, and the grid
//! resumes in phase.

use crate::trace::TraceRow;
use codegen::backend::Backend;
use codegen::lower::{Lowered, NetLayout, Supervisors};
use executor::memory::HeapMemory;
use executor::pacing::{Pacer, ScanStart};
use executor::program::Program;
use executor::Controller;
use plc_project::{self as project, Project};
use std::path::Path;

/// A problem setting up or driving a simulation.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// The project or a model file is invalid.
    #[error(transparent)]
    Model(#[from] des::Error),
    /// The project cannot be lowered for the backend (a net on a backend
    /// other than tables, the logic backend not in this build, …).
    #[error(transparent)]
    Lowering(#[from] codegen::Error),
    /// A name that is not in the project.
    #[error("`{0}` is not {1} of the project")]
    Unknown(String, &'static str),
    /// The two backends produced different rows for the same scan.
    #[error("backends diverge at scan {}:\n  table: {table:?}\n  logic: {logic:?}", table.scan)]
    Diverged {
        /// The table backend's row.
        table: Box<TraceRow>,
        /// The logic backend's row.
        logic: Box<TraceRow>,
    },
    /// The input image does not have one value per input.
    #[error("expected {expected} input values, got {got}")]
    InputCount {
        /// Inputs of the project.
        expected: usize,
        /// Values given.
        got: usize,
    },
}

/// A controller on a virtual clock, with its trace.
pub struct Sim {
    project: Project,
    /// The layout of each net in the program (a copy of the lowered
    /// one's, so that a scan's record and the names can be read together).
    nets: Vec<NetLayout>,
    controller: Controller<Lowered, HeapMemory>,
    inputs: Vec<bool>,
    /// The controller's clock: when its last scan, or the stall after it,
    /// ended.
    clock_ms: u64,
    /// Stalled since the last scan.
    stalled_ms: u64,
    pacer: Pacer,
    last_start: Option<ScanStart>,
    trace: Vec<TraceRow>,
    /// Keep every row in `trace` (else only the last one).
    retain_trace: bool,
}

impl Sim {
    /// Loads the project at `path` and starts a controller for it.
    pub fn load(path: &Path, backend: Backend) -> Result<Sim, SimError> {
        Sim::new(project::load(path)?, backend)
    }

    /// A controller for `project` at time 0 with every input 0.
    pub fn new(project: Project, backend: Backend) -> Result<Sim, SimError> {
        let program = Lowered::new(&project, backend, &())?;
        let memory = HeapMemory::for_config(&program.config());
        // Validation keeps `scan_period_ms` in 1..2^31, as the pacer needs.
        let pacer = Pacer::for_config(&program.config(), 0);
        let controller = Controller::new(program, memory)
            .expect("memory is sized from the program's own configuration");
        Ok(Sim {
            inputs: vec![false; project.inputs.len()],
            nets: controller.program().pools().nets.clone(),
            project,
            controller,
            clock_ms: 0,
            stalled_ms: 0,
            pacer,
            last_start: None,
            trace: Vec::new(),
            retain_trace: true,
        })
    }

    /// Whether the trace keeps every scan (the default) or only the last
    /// one, so that a long run streamed elsewhere holds constant memory.
    pub fn retain_trace(&mut self, keep: bool) -> &mut Self {
        self.retain_trace = keep;
        self
    }

    /// The project.
    pub fn project(&self) -> &Project {
        &self.project
    }

    /// The executor's supervisors of the program, named (the automata,
    /// then the Petri nets' groups).
    pub fn supervisors(&self) -> Supervisors<'_> {
        Supervisors::new(&self.project, &self.nets)
    }

    /// The layout of each Petri net in the program.
    pub fn nets(&self) -> &[NetLayout] {
        &self.nets
    }

    /// The lowered configuration the controller runs: timing and limits
    /// as the executor reads them (the project says what they were
    /// declared as; after lowering, this is what holds).
    pub fn config(&self) -> executor::program::Config<'_> {
        self.controller.program().config()
    }

    /// The controller (fault state, counters).
    pub fn controller(&self) -> &Controller<Lowered, HeapMemory> {
        &self.controller
    }

    /// The controller, mutably (to report overruns or lost edges).
    pub fn controller_mut(&mut self) -> &mut Controller<Lowered, HeapMemory> {
        &mut self.controller
    }

    /// The virtual time of the next scan: its deadline, or the end of a
    /// stall that passed it.
    pub fn time_ms(&self) -> u64 {
        // The clock's low 32 bits are the controller's millisecond clock.
        self.clock_ms + u64::from(self.pacer.due_in(self.clock_ms as u32))
    }

    /// How the last scan of [`Sim::scan`] started on the schedule (how
    /// late, periods skipped, overrun); `None` before the first.
    pub fn last_start(&self) -> Option<ScanStart> {
        self.last_start
    }

    /// Sets the raw value of input `name` for the following scans.
    pub fn set(&mut self, name: &str, value: bool) -> Result<&mut Self, SimError> {
        let i = self
            .project
            .input(name)
            .ok_or_else(|| SimError::Unknown(name.to_owned(), "an input"))?;
        self.inputs[i] = value;
        Ok(self)
    }

    /// The raw value of input `name`.
    pub fn input(&self, name: &str) -> Result<bool, SimError> {
        let i = self
            .project
            .input(name)
            .ok_or_else(|| SimError::Unknown(name.to_owned(), "an input"))?;
        Ok(self.inputs[i])
    }

    /// Runs the next scan when the schedule says it is due
    /// ([`Sim::time_ms`]) with the current inputs. A scan that starts more
    /// than `overrun_limit` periods after its deadline is an overrun,
    /// reported to the controller first (SEMANTICS, faults: counted, and a
    /// fault from this scan on when the project sets `overrun_fault`).
    pub fn scan(&mut self) -> &TraceRow {
        let time = self.time_ms();
        let start = self
            .controller
            .scan_due(&mut self.pacer, time as u32)
            .expect("a scan is due at its own time");
        self.clock_ms = time;
        self.stalled_ms = 0;
        self.last_start = Some(start);
        let inputs = self.inputs.clone();
        self.scan_with(time, &inputs)
            .expect("the input image has one value per input")
    }

    /// The controller hangs for `ms` right after its last scan (before the
    /// first scan: from time 0), as a scan that overruns into a hang on
    /// the board: no scan runs until the hang ends. The next scan then
    /// starts at once if a deadline passed meanwhile (how late it is, and
    /// whether that is an overrun, is judged by the schedule when it
    /// starts), else at its deadline; the grid keeps its phase. Stalls add
    /// up until the next scan.
    ///
    /// # Panics
    ///
    /// When the stalls since the last scan add up to 2^31 ms (24.8 days:
    /// the horizon of the controller's wrapping millisecond clock; the
    /// board's watchdog resets long before).
    pub fn stall(&mut self, ms: u64) {
        let stalled = self.stalled_ms.saturating_add(ms);
        assert!(
            stalled < 1 << 31,
            "a stall must be shorter than 2^31 ms, got {stalled} ms"
        );
        self.stalled_ms = stalled;
        self.clock_ms += ms;
    }

    /// Runs one scan at `time_ms` with the raw image `raw`, outside the
    /// schedule (replays of recorded inputs give their own times); the
    /// virtual clock does not move.
    pub fn scan_with(&mut self, time_ms: u64, raw: &[bool]) -> Result<&TraceRow, SimError> {
        if raw.len() != self.project.inputs.len() {
            return Err(SimError::InputCount {
                expected: self.project.inputs.len(),
                got: raw.len(),
            });
        }
        let record = self.controller.scan(time_ms as u32, raw);
        let supervisors = Supervisors::new(&self.project, &self.nets);
        let row = TraceRow::from_record(&record, time_ms, supervisors);
        if !self.retain_trace {
            self.trace.clear();
        }
        self.trace.push(row);
        Ok(self.trace.last().expect("just pushed"))
    }

    /// Runs `scans` scans.
    pub fn run(&mut self, scans: usize) -> &[TraceRow] {
        let start = self.trace.len();
        for _ in 0..scans {
            self.scan();
        }
        &self.trace[start..]
    }

    /// Runs scans until the virtual clock has advanced by at least `ms`.
    pub fn run_for(&mut self, ms: u64) -> &[TraceRow] {
        let start = self.trace.len();
        let until = self.time_ms() + ms;
        while self.time_ms() < until {
            self.scan();
        }
        &self.trace[start..]
    }

    /// The last scan's row, if any.
    pub fn last(&self) -> Option<&TraceRow> {
        self.trace.last()
    }

    /// The whole trace so far.
    pub fn trace(&self) -> &[TraceRow] {
        &self.trace
    }

    /// The current state (name) of supervisor `name`.
    pub fn state(&self, name: &str) -> Result<String, SimError> {
        let supervisors = self.supervisors();
        let j = supervisors
            .find(name)
            .ok_or_else(|| SimError::Unknown(name.to_owned(), "a supervisor"))?;
        Ok(supervisors.state_name(j, self.controller.states()[j]))
    }

    /// The current level of output `name`.
    pub fn output(&self, name: &str) -> Result<bool, SimError> {
        let o = self
            .project
            .output(name)
            .ok_or_else(|| SimError::Unknown(name.to_owned(), "an output"))?;
        Ok(self.controller.outputs()[o])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_project_the_backend_cannot_lower_is_generations_refusal() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/petri/mixers.plc.toml");
        let err = Sim::load(&path, Backend::Match)
            .err()
            .expect("nets run on the table backend only");
        assert!(
            matches!(
                err,
                SimError::Lowering(codegen::Error::TableOnly {
                    backend: Backend::Match,
                    ..
                })
            ),
            "{err:?}"
        );
        assert!(
            err.to_string()
                .contains("Petri nets run on the table backend only, not the match backend"),
            "{err}"
        );
    }
}
