//! A picture of a run, for any project: inputs and outputs as digital
//! lanes, executed events as marks, each supervisor's state as labelled
//! segments, fault mode shaded with its cause, analog quantities on fixed
//! scales, over a time axis in seconds or milliseconds.
//!
//! The lanes are declared before the run (from the project, and for a
//! closed-loop run from its plant), so two runs of one project share one
//! layout. A [`Plot`] keeps only the changes of each signal, not its
//! scans, and [`Plot::to_svg`] draws each signal as one `<path>` of its
//! transitions: the file grows with what happened, not with how
//! long it took.

mod svg;
mod ticks;

use crate::trace::TraceRow;
use codegen::lower::Supervisors;

/// A digital lane: a signal's level at each change.
#[derive(Debug, Clone)]
struct Digital {
    /// The group it is drawn in (`inputs`, `outputs`, `plant`).
    group: &'static str,
    name: String,
    /// `(time, level)` at the first scan and at every change.
    changes: Vec<(u64, bool)>,
}

/// A supervisor's lane: its state at each change.
#[derive(Debug, Clone)]
struct States {
    name: String,
    changes: Vec<(u64, String)>,
}

/// An analog lane: one or more quantities on one fixed scale.
#[derive(Debug, Clone)]
struct Analog {
    name: String,
    unit: &'static str,
    /// The scale, `(bottom, top)`; widened (never narrowed) to hold
    /// every sample.
    range: (f64, f64),
    series: Vec<Series>,
}

/// One quantity of an analog lane.
#[derive(Debug, Clone)]
struct Series {
    name: String,
    colour: &'static str,
    samples: Vec<(u64, f64)>,
}

/// The picture of a run, recorded scan by scan.
#[derive(Debug, Clone)]
pub struct Plot {
    title: String,
    digital: Vec<Digital>,
    states: Vec<States>,
    analog: Vec<Analog>,
    /// `(time, executed events)` of every scan that executed any.
    events: Vec<(u64, Vec<String>)>,
    /// `(time, cause)` at the first scan and whenever fault mode or its
    /// cause changes (`None`: not in fault mode).
    faults: Vec<(u64, Option<String>)>,
    /// Time of the first and the last scan.
    span: Option<(u64, u64)>,
}

/// A digital lane of a [`Plot`] ([`Plot::digital`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DigitalLane(usize);

/// A supervisor's lane of a [`Plot`] ([`Plot::supervisor`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateLane(usize);

/// One quantity of an analog lane of a [`Plot`] ([`Plot::analog`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AnalogSeries {
    lane: usize,
    series: usize,
}

/// The lanes of a project ([`Plot::for_project`]).
#[derive(Debug, Clone)]
pub struct ProjectLanes {
    /// One per project input, in declaration order.
    pub inputs: Vec<DigitalLane>,
    /// One per project output, in declaration order.
    pub outputs: Vec<DigitalLane>,
    /// One per supervisor, in the lowered program's order.
    pub supervisors: Vec<StateLane>,
}

impl Plot {
    /// An empty picture titled `title`, with no lanes.
    pub fn new(title: &str) -> Plot {
        Plot {
            title: title.to_owned(),
            digital: Vec::new(),
            states: Vec::new(),
            analog: Vec::new(),
            events: Vec::new(),
            faults: Vec::new(),
            span: None,
        }
    }

    /// A picture with a lane for every input, output and supervisor of the
    /// project of `supervisors`.
    pub fn for_project(title: &str, supervisors: Supervisors<'_>) -> (Plot, ProjectLanes) {
        let project = supervisors.project();
        let mut plot = Plot::new(title);
        let lanes = ProjectLanes {
            inputs: project
                .inputs
                .iter()
                .map(|i| plot.digital("inputs", &i.name))
                .collect(),
            outputs: project
                .outputs
                .iter()
                .map(|o| plot.digital("outputs", &o.name))
                .collect(),
            supervisors: (0..supervisors.len())
                .map(|j| plot.supervisor(&supervisors.name(j)))
                .collect(),
        };
        (plot, lanes)
    }

    /// Declares a digital lane `name` in `group`.
    pub fn digital(&mut self, group: &'static str, name: &str) -> DigitalLane {
        self.digital.push(Digital {
            group,
            name: name.to_owned(),
            changes: Vec::new(),
        });
        DigitalLane(self.digital.len() - 1)
    }

    /// Declares the lane of supervisor `name`.
    pub fn supervisor(&mut self, name: &str) -> StateLane {
        self.states.push(States {
            name: name.to_owned(),
            changes: Vec::new(),
        });
        StateLane(self.states.len() - 1)
    }

    /// Declares an analog lane `name` on the scale `range` (in `unit`)
    /// holding `series` (`(name, SVG colour)` each); a sample outside the
    /// scale widens it to the next tick.
    pub fn analog(
        &mut self,
        name: &str,
        unit: &'static str,
        range: (f64, f64),
        series: &[(&str, &'static str)],
    ) -> Vec<AnalogSeries> {
        let lane = self.analog.len();
        self.analog.push(Analog {
            name: name.to_owned(),
            unit,
            range,
            series: series
                .iter()
                .map(|&(name, colour)| Series {
                    name: name.to_owned(),
                    colour,
                    samples: Vec::new(),
                })
                .collect(),
        });
        (0..series.len())
            .map(|series| AnalogSeries { lane, series })
            .collect()
    }

    /// Starts a scan at `time_ms`: the values set until the next call are
    /// this scan's.
    pub fn scan(&mut self, time_ms: u64) {
        self.span = Some(match self.span {
            None => (time_ms, time_ms),
            Some((start, _)) => (start, time_ms),
        });
    }

    fn now(&self) -> u64 {
        self.span.map_or(0, |(_, now)| now)
    }

    /// The level of `lane` in this scan.
    pub fn set_digital(&mut self, lane: DigitalLane, level: bool) {
        let now = self.now();
        let changes = &mut self.digital[lane.0].changes;
        if changes.last().map(|&(_, l)| l) != Some(level) {
            changes.push((now, level));
        }
    }

    /// The state of the supervisor of `lane` after this scan.
    pub fn set_state(&mut self, lane: StateLane, state: &str) {
        let now = self.now();
        let changes = &mut self.states[lane.0].changes;
        if changes.last().map(|(_, s)| s.as_str()) != Some(state) {
            changes.push((now, state.to_owned()));
        }
    }

    /// The value of `series` in this scan.
    pub fn set_analog(&mut self, series: AnalogSeries, value: f64) {
        let now = self.now();
        let lane = &mut self.analog[series.lane];
        if value.is_finite() {
            lane.range = ticks::widen(lane.range, value);
        }
        lane.series[series.series].samples.push((now, value));
    }

    /// The events this scan executed.
    pub fn events(&mut self, events: &[String]) {
        if !events.is_empty() {
            self.events.push((self.now(), events.to_vec()));
        }
    }

    /// The fault cause if this scan ended in fault mode.
    pub fn fault(&mut self, cause: Option<&str>) {
        let now = self.now();
        if self.faults.last().map(|(_, c)| c.as_deref()) != Some(cause) {
            self.faults.push((now, cause.map(str::to_owned)));
        }
    }

    /// Records one scan of a replay: its trace `row` and the raw `inputs`
    /// it read (`None`: not drawn for this scan), on the lanes of
    /// [`Plot::for_project`].
    pub fn trace_row(&mut self, lanes: &ProjectLanes, inputs: Option<&[bool]>, row: &TraceRow) {
        self.scan(row.time_ms);
        if let Some(inputs) = inputs {
            for (&lane, &level) in lanes.inputs.iter().zip(inputs) {
                self.set_digital(lane, level);
            }
        }
        for (&lane, &level) in lanes.outputs.iter().zip(&row.outputs) {
            self.set_digital(lane, level);
        }
        for (&lane, (_, state)) in lanes.supervisors.iter().zip(&row.states) {
            self.set_state(lane, state);
        }
        self.events(&row.events);
        self.fault(row.fault.as_deref());
    }

    /// The picture as SVG text.
    pub fn to_svg(&self) -> String {
        svg::render(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lane_keeps_changes_not_scans() {
        let mut plot = Plot::new("t");
        let lane = plot.digital("inputs", "a");
        let sup = plot.supervisor("s");
        for t in 0..100 {
            plot.scan(t * 10);
            plot.set_digital(lane, (40..60).contains(&t));
            plot.set_state(sup, if t < 50 { "idle" } else { "busy" });
            plot.fault(None);
        }
        assert_eq!(
            plot.digital[0].changes,
            [(0, false), (400, true), (600, false)]
        );
        assert_eq!(plot.states[0].changes.len(), 2);
        assert_eq!(plot.faults, [(0, None)]);
        assert_eq!(plot.span, Some((0, 990)));
    }

    #[test]
    fn an_analog_scale_widens_to_hold_its_samples_and_never_narrows() {
        let mut plot = Plot::new("t");
        let s = plot.analog("temperature", "°C", (0.0, 100.0), &[("flue", "red")]);
        plot.scan(0);
        plot.set_analog(s[0], 20.0);
        assert_eq!(plot.analog[0].range, (0.0, 100.0));
        plot.set_analog(s[0], 260.0);
        assert_eq!(plot.analog[0].range, (0.0, 260.0));
    }
}
