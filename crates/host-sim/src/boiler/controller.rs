//! What the closed loop runs against the plant: a PLC project on the host
//! executor ([`Plc`]), or any hand-written [`BoilerController`] (a test's
//! reference or deliberately broken controller).

use super::signals::{Input, Inputs, IoMap, Output, Outputs};
use super::BoilerError;
use crate::lockstep::Lockstep;
use crate::sim::Sim;
use crate::trace::TraceRow;

/// A controller of the boiler, scanned once per period.
pub trait BoilerController {
    /// The scan period; the plant advances by it after every scan.
    fn scan_period_ms(&self) -> u32;

    /// `debounce_scans` of every boiler input as the controller filters it
    /// (by [`Input::index`]), so that checks judge the controller by the
    /// levels it saw; default: no filtering.
    fn debounce(&self) -> [u8; Input::ALL.len()] {
        [0; Input::ALL.len()]
    }

    /// One scan with the input image `inputs`.
    fn scan(&mut self, inputs: &Inputs) -> Result<ControllerScan, BoilerError>;

    /// The controller hangs for `ms` right after the scan it just ran (no
    /// scans, outputs held), which delays its next scan
    /// ([`BoilerController::next_scan_in_ms`]). Default: a controller that
    /// does not hang.
    fn stall(&mut self, ms: u64) {
        let _ = ms;
    }

    /// Time from the scan just run to the next one (ms); the plant runs
    /// that long under its outputs. Default: one period.
    fn next_scan_in_ms(&self) -> u64 {
        u64::from(self.scan_period_ms())
    }
}

/// What a controller did in one scan.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct ControllerScan {
    /// Time of the scan on the controller's clock.
    pub time_ms: u64,
    /// The output image written.
    pub outputs: Outputs,
    /// Executed events in order (empty for hand-written controllers).
    pub events: Vec<String>,
    /// `(supervisor, state)` after the scan (or any labels a hand-written
    /// controller reports).
    pub states: Vec<(String, String)>,
    /// Fault cause on a scan spent in fault mode.
    pub fault: Option<String>,
    /// The controller left fault mode in this scan (reset): it
    /// re-initialised and discarded the scan's edges.
    pub reinitialised: bool,
}

/// The executor running a project, single backend or both in lockstep.
enum Target<'a> {
    Sim(&'a mut Sim),
    Lockstep(&'a mut Lockstep),
}

/// A PLC project as a [`BoilerController`]: the boiler's signals are
/// looked up by name once, and each scan sets the seven boiler inputs and
/// runs one scan at the simulation's own clock. Other inputs of the
/// project keep the levels set on it before (request inputs, say).
pub struct Plc<'a> {
    target: Target<'a>,
    io: IoMap,
}

impl<'a> Plc<'a> {
    /// `sim` as a boiler controller, or the list of boiler signals its
    /// project lacks.
    pub fn new(sim: &'a mut Sim) -> Result<Plc<'a>, BoilerError> {
        let io = IoMap::new(sim.project())?;
        Ok(Plc {
            target: Target::Sim(sim),
            io,
        })
    }

    /// Both backends of a project in lockstep (every scan compared) as a
    /// boiler controller.
    pub fn lockstep(ls: &'a mut Lockstep) -> Result<Plc<'a>, BoilerError> {
        let io = IoMap::new(ls.project())?;
        Ok(Plc {
            target: Target::Lockstep(ls),
            io,
        })
    }

    /// Where the boiler's signals are in the project.
    pub fn io(&self) -> &IoMap {
        &self.io
    }

    /// The simulation (in lockstep, the table backend's).
    fn sim(&self) -> &Sim {
        match &self.target {
            Target::Sim(sim) => sim,
            Target::Lockstep(ls) => ls.sim(),
        }
    }

    fn scan_row(&mut self, inputs: &Inputs) -> Result<TraceRow, BoilerError> {
        Ok(match &mut self.target {
            Target::Sim(sim) => {
                for input in Input::ALL {
                    sim.set(input.name(), inputs.get(input))?;
                }
                sim.scan().clone()
            }
            Target::Lockstep(ls) => {
                for input in Input::ALL {
                    ls.set(input.name(), inputs.get(input))?;
                }
                ls.scan()?
            }
        })
    }
}

impl BoilerController for Plc<'_> {
    fn scan_period_ms(&self) -> u32 {
        self.sim().config().scan_period_ms
    }

    fn debounce(&self) -> [u8; Input::ALL.len()] {
        self.io.debounce(&self.sim().config())
    }

    fn scan(&mut self, inputs: &Inputs) -> Result<ControllerScan, BoilerError> {
        // A fault may start as the scan starts (an overrun after a stall)
        // and end in it (a reset edge), so the records do not tell: a
        // fault entered counts.
        let controller = self.sim().controller();
        let (faulted, faults) = (controller.fault().is_some(), controller.counters().faults);
        let row = self.scan_row(inputs)?;
        let faulted = faulted || self.sim().controller().counters().faults != faults;
        let mut outputs = Outputs::default();
        for output in Output::ALL {
            outputs.set(output, row.outputs[self.io.output(output)]);
        }
        Ok(ControllerScan {
            time_ms: row.time_ms,
            outputs,
            events: row.events,
            states: row.states,
            reinitialised: faulted && row.fault.is_none(),
            fault: row.fault,
        })
    }

    /// [`Sim::stall`]: the hang starts right after the last scan; the
    /// schedule then decides when the next scan starts.
    fn stall(&mut self, ms: u64) {
        match &mut self.target {
            Target::Sim(sim) => sim.stall(ms),
            Target::Lockstep(ls) => ls.stall(ms),
        }
    }

    fn next_scan_in_ms(&self) -> u64 {
        let sim = self.sim();
        sim.time_ms() - sim.last().map_or(0, |row| row.time_ms)
    }
}
