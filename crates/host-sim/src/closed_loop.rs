//! One closed loop for every plant simulation: a [`Controller`] scans the
//! input image a [`Plant`] shows, the plant runs under the outputs until
//! the next scan, and a [`Record`] keeps what the run leaves. The boiler
//! ([`crate::boiler`]) and the batch cell ([`crate::cell`]) each bring
//! their plant, controller and record to the one runner, [`run`].
//!
//! One scan of [`run`]:
//!
//! 1. the actions due at the plant's time (`at <= now`) are applied, in
//!    order; a controller stall among them ([`Plant::stall_ms`]) hangs
//!    the controller right after this scan;
//! 2. the controller scans the input image the plant shows and reports
//!    its outputs ([`Plant::Report`]);
//! 3. the plant advances under those outputs until the controller's next
//!    scan, in steps of at most one period: one period, or as its schedule
//!    says after a stall (the late scan when the stall ends, then the grid
//!    in phase again);
//! 4. the record takes the scan: the plant's time, state and input image
//!    when scanned, the controller's report, and the plant as advanced.
//!
//! Scans run while the plant's time is before the end of the run (its
//! time at the start plus the duration).

/// A plant simulation the loop runs: its time, what is done to it from
/// outside the loop, the input image it shows and its true state, and how
/// it advances under the controller's outputs.
pub trait Plant {
    /// Something done to the plant at a given time: an operator's action,
    /// a disturbance, a fault.
    type Action;
    /// The plant's true state, as the record keeps it.
    type State;
    /// The input image the plant shows the controller.
    type Inputs;
    /// What one scan of the plant's controller reports: its output image,
    /// and whatever else the record keeps.
    type Report;

    /// Plant time, ms.
    fn time_ms(&self) -> u64;

    /// Applies `action` now.
    fn apply(&mut self, action: &Self::Action);

    /// How long `action` hangs the controller right after the scan it is
    /// due at (ms; no scans, outputs held). Default: it does not.
    fn stall_ms(action: &Self::Action) -> u64 {
        let _ = action;
        0
    }

    /// The true state now.
    fn state(&self) -> Self::State;

    /// The input image the controller reads now.
    fn inputs(&self) -> Self::Inputs;

    /// Advances the plant by `dt_ms` under the outputs of `report`.
    fn advance(&mut self, dt_ms: u64, report: &Self::Report);
}

/// What the loop scans against a plant `P`: a PLC project on the host
/// executor, or a hand-written controller.
pub trait Controller<P: Plant> {
    /// What can stop a run.
    type Error;

    /// The scan period, ms.
    fn scan_period_ms(&self) -> u64;

    /// One scan with the input image `inputs`.
    fn scan(&mut self, inputs: &P::Inputs) -> Result<P::Report, Self::Error>;

    /// The controller hangs for `ms` right after the scan it just ran,
    /// which delays its next scan ([`Controller::next_scan_in_ms`]).
    /// Default: a controller that does not hang.
    fn stall(&mut self, ms: u64) {
        let _ = ms;
    }

    /// Time from the scan just run to the next one, ms. Default: one
    /// period.
    fn next_scan_in_ms(&self) -> u64 {
        self.scan_period_ms()
    }
}

/// One scan of the loop, as the record is given it.
pub struct Scan<P: Plant> {
    /// Plant time when the controller scanned.
    pub time_ms: u64,
    /// The plant's true state then.
    pub state: P::State,
    /// The input image the controller read.
    pub inputs: P::Inputs,
    /// What the controller reported.
    pub report: P::Report,
}

/// What a run of plant `P` keeps, scan by scan.
pub trait Record<P: Plant> {
    /// Takes `scan`; `plant` has advanced to the controller's next scan.
    fn record(&mut self, scan: Scan<P>, plant: &P);
}

/// Runs `controller` against `plant` from the plant's current time for
/// `duration_ms` with `actions` (at plant times, in time order; those due
/// before the start are applied at once), every scan given to `record`.
pub fn run<P, C, R>(
    controller: &mut C,
    plant: &mut P,
    actions: &[(u64, P::Action)],
    duration_ms: u64,
    record: &mut R,
) -> Result<(), C::Error>
where
    P: Plant,
    C: Controller<P> + ?Sized,
    R: Record<P>,
{
    let period = controller.scan_period_ms().max(1);
    let end = plant.time_ms() + duration_ms;
    let mut next = 0;
    while plant.time_ms() < end {
        let mut stall = 0;
        while let Some((_, action)) = actions.get(next).filter(|(at, _)| *at <= plant.time_ms()) {
            stall += P::stall_ms(action);
            plant.apply(action);
            next += 1;
        }
        let time_ms = plant.time_ms();
        let state = plant.state();
        let inputs = plant.inputs();
        let report = controller.scan(&inputs)?;
        if stall > 0 {
            controller.stall(stall);
        }
        // In steps of at most a period, so a stall is simulated as finely.
        let until = plant.time_ms() + controller.next_scan_in_ms().max(1);
        while plant.time_ms() < until {
            plant.advance(period.min(until - plant.time_ms()), &report);
        }
        let scan = Scan {
            time_ms,
            state,
            inputs,
            report,
        };
        record.record(scan, plant);
    }
    Ok(())
}
