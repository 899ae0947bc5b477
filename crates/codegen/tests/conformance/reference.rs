//! The reference interpreter: a scan as `docs/semantics.md` states it,
//! one method a numbered rule of "One scan", over the [`Project`] model
//! (never the executor's `Config`), and the trace record all three
//! interpreters are compared on.

use des::automaton::{EventId, StateId};
use executor::{Fault, ScanRecord};
use plc_project::{Action, Drive, Net, Project, Trigger, Unexpected};
use std::collections::HashMap;
use std::fmt::Debug;

/// Why a scan is in fault mode, as comparable data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Cause {
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
pub(crate) struct Record {
    pub(crate) scan: u32,
    pub(crate) time_ms: u32,
    pub(crate) executed: Vec<usize>,
    pub(crate) unexpected: Vec<usize>,
    pub(crate) states: Vec<u32>,
    pub(crate) outputs: Vec<bool>,
    pub(crate) fault: Option<Cause>,
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

/// The reference interpreter: a straightforward reading of docs/semantics.md
/// over the [`Project`] model (see the module docs for the rule map).
pub(crate) struct Reference<'p> {
    pub(crate) project: &'p Project,
    /// δj per supervisor: (state, global event) → target.
    pub(crate) delta: Vec<HashMap<(u32, usize), u32>>,
    /// For each global event, the supervisors with it in their alphabet.
    pub(crate) members: Vec<Vec<usize>>,
    /// The marking of every Petri net, place by place.
    pub(crate) markings: Vec<Vec<u32>>,
    /// Initial state of every supervisor.
    pub(crate) initial: Vec<u32>,
    /// Number of the next scan.
    pub(crate) scan: u32,
    /// Filtered input image F\[k\].
    pub(crate) filtered: Vec<bool>,
    /// Consecutive scans the raw value has differed from the filtered one.
    pub(crate) differing: Vec<u8>,
    /// Deadline of every running timer.
    pub(crate) deadlines: Vec<Option<u32>>,
    /// Levels of the action-driven outputs.
    pub(crate) latched: Vec<bool>,
    /// The state vector.
    pub(crate) states: Vec<u32>,
    /// The fault cause while in fault mode.
    pub(crate) fault: Option<Cause>,
    /// Unexpected events dropped under policy `ignore`.
    pub(crate) ignored: u32,
}

impl<'p> Reference<'p> {
    pub(crate) fn new(project: &'p Project) -> Self {
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
    pub(crate) fn reinitialise(&mut self) {
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
    pub(crate) fn scan(&mut self, now: u32, raw: &[bool]) -> Record {
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
    pub(crate) fn sample(&mut self, raw: &[bool]) -> Vec<bool> {
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
    pub(crate) fn debounce(&mut self, i: usize, value: bool) {
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
    pub(crate) fn fault_mode(&mut self, previous: &[bool]) {
        if let Some(r) = self.project.reset {
            if self.filtered[r] && !previous[r] {
                self.reinitialise();
            }
        }
    }

    /// Rule 3: stops every timer whose deadline is reached (wrap-safe) and
    /// reports which expired.
    pub(crate) fn expire_timers(&mut self, now: u32) -> Vec<bool> {
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
    pub(crate) fn occurred(&self, previous: &[bool], expired: &[bool]) -> Vec<usize> {
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

    /// Feasibility: every supervisor having `e` has a transition on it,
    /// and every symbolic supervisor's guard of `e` holds.
    pub(crate) fn feasible(&self, e: usize) -> bool {
        self.members[e]
            .iter()
            .all(|&j| self.delta[j].contains_key(&(self.states[j], e)))
            && self
                .project
                .guarded
                .iter()
                .all(|g| g.allows(e, &self.states))
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
    pub(crate) fn execute(&mut self, e: usize, now: u32, record: &mut Record) {
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
    pub(crate) fn uncontrollable_phase(
        &mut self,
        now: u32,
        occurred: &[usize],
        record: &mut Record,
    ) {
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
    pub(crate) fn controllable_phase(&mut self, now: u32, record: &mut Record) {
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
    pub(crate) fn eligible(&self, e: usize) -> bool {
        let ev = &self.project.events[e];
        ev.controllable && ev.request.is_none_or(|r| self.filtered[r]) && self.feasible(e)
    }

    /// Rule 6 (and the safe image of rules 2 and 4).
    pub(crate) fn output_image(&self) -> Vec<bool> {
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
pub(crate) fn reached(deadline: u32, now: u32) -> bool {
    (now.wrapping_sub(deadline) as i32) >= 0
}

/// The initial state vector of `project`.
pub(crate) fn initial_states(project: &Project) -> Vec<u32> {
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
pub(crate) fn transition_of(net: &Net, e: usize) -> Option<usize> {
    net.events.iter().position(|&g| g == e)
}

/// A place's counter in the reference's own reading of the net layout.
struct Counter {
    group: usize,
    shift: u32,
    width: u32,
}

/// `net`'s counters laid out as docs/formats.md says ("[[net]]"): in place
/// order, each as wide as the place needs ([`Net::widths`]), a new group
/// whenever the next counter would take a group past 31 bits. Written here
/// again, not taken from lowering, so that the tests check its packing.
fn counters(net: &Net) -> Vec<Counter> {
    let mut counters: Vec<Counter> = Vec::new();
    let (mut group, mut used) = (0, 0);
    for width in net.widths() {
        if used > 0 && used + width > 31 {
            group += 1;
            used = 0;
        }
        counters.push(Counter {
            group,
            shift: used,
            width,
        });
        used += width;
    }
    counters
}

/// The number of groups (executor supervisors) of `net`.
pub(crate) fn groups_of(net: &Net) -> usize {
    counters(net).last().map_or(0, |c| c.group + 1)
}

/// `marking` as the states of `net`'s groups: each place's count at its
/// counter's shift (docs/formats.md, "[[net]]").
pub(crate) fn pack_marking(net: &Net, marking: &[u32]) -> Vec<u32> {
    let counters = counters(net);
    let mut groups = vec![0u32; groups_of(net)];
    for (p, c) in counters.iter().enumerate() {
        groups[c.group] |= marking[p] << c.shift;
    }
    groups
}

/// The marking of `net` from its groups' states.
pub(crate) fn unpack_marking(net: &Net, groups: &[u32]) -> Vec<u32> {
    counters(net)
        .iter()
        .map(|c| (groups[c.group] >> c.shift) & ((1 << c.width) - 1))
        .collect()
}
