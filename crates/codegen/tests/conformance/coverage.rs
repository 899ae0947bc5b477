//! Coverage of the generators: what random runs exercise, counted from
//! reference traces, so that a generator change that silently stops
//! exercising a rule fails a test.

use crate::config;
use crate::projects::{ProjectSpec, WORD};
use crate::reference::{Record, Reference};
use crate::runs::RunSpec;
use plc_project::{Drive, Project, Trigger};
use proptest::prelude::*;
use std::fmt::Debug;

/// What happened in random runs, counted from reference traces, so that a
/// generator change that silently stops exercising a rule fails a test.
#[derive(Debug, Default)]
pub(crate) struct Coverage {
    pub(crate) scans: u64,
    pub(crate) scans_in_fault: u64,
    pub(crate) uncontrollable: u64,
    pub(crate) expiries: u64,
    pub(crate) conditioned: u64,
    pub(crate) local_logic: u64,
    pub(crate) commands: u64,
    pub(crate) requested: u64,
    pub(crate) several_commands: u64,
    pub(crate) shared: u64,
    pub(crate) faults: u64,
    pub(crate) resets: u64,
    pub(crate) ignored: u64,
    pub(crate) moore_high: u64,
    pub(crate) clock_wraps: u64,
    /// Events past the first word of an event set executed.
    pub(crate) high_events: u64,
    /// Commands past the first word executed.
    pub(crate) high_commands: u64,
    /// Commands executed on a request input past the first word.
    pub(crate) high_requests: u64,
    /// Edge events whose edge only inputs past the first word made.
    pub(crate) high_input_edges: u64,
    /// Supervisor moves on a local event past the first slice of its rows.
    pub(crate) high_local_moves: u64,
}

/// One scan as the coverage sees it: the reference's record and its
/// filtered input image F\[k\].
pub(crate) struct Observed {
    pub(crate) record: Record,
    pub(crate) filtered: Vec<bool>,
}

/// Runs `samples` through the reference, keeping F\[k\] of every scan.
pub(crate) fn observe(project: &Project, samples: &[(u32, Vec<bool>)]) -> Vec<Observed> {
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
pub(crate) struct EventMembership {
    /// Supervisors having the event.
    pub(crate) supervisors: usize,
    /// Some supervisor has it past the first slice of its rows.
    pub(crate) high_local: bool,
}

impl Coverage {
    /// Adds the counts of one run of `project`.
    pub(crate) fn add(&mut self, project: &Project, scans: &[Observed]) {
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

    pub(crate) fn add_scan(
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
    pub(crate) fn add_words(
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
    pub(crate) fn counters(&self) -> [(&'static str, u64); 14] {
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
    pub(crate) fn word_counters(&self) -> [(&'static str, u64); 5] {
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
pub(crate) fn moore_high(project: &Project, r: &Record) -> bool {
    project
        .outputs
        .iter()
        .zip(&r.outputs)
        .any(|(o, &level)| level && matches!(o.drive, Drive::States(_)))
}

/// The coverage of `runs` cases drawn from `strategy` (run through the
/// reference only).
pub(crate) fn coverage_of(
    strategy: impl Strategy<Value = (ProjectSpec, RunSpec)>,
    runs: u32,
) -> Coverage {
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
