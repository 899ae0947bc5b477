//! The executor's configuration of a project ([`ConfigPools`]):
//! fixed-size records plus shared pools addressed by spans, laid out in a
//! fixed order (the spans and the image CRC depend on it).

use super::nets::{NetGroups, NetLayout};
use crate::backend::table::{bits_for, write_bits};
use crate::error::Error;
use des::automaton::StateId;
use executor::program::{self as ex, Config, Index, Span};
use plc_project::{Action, Drive, Project, Trigger, Unexpected};
use std::collections::HashMap;
use std::collections::HashSet;

/// The executor's description of a project, in owned vectors: the typed
/// lay-out, which the emitter and host tools read, and its records as the
/// image holds them ([`ConfigPools::config`] reads those). After changing a
/// typed field, [`ConfigPools::refresh`] writes the records anew.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConfigPools {
    /// Project name.
    pub name: String,
    /// Nominal scan period.
    pub scan_period_ms: u32,
    /// Controllable events per scan (0: no limit).
    pub max_commands_per_scan: u16,
    /// Unexpected-event policy.
    pub unexpected: ex::UnexpectedPolicy,
    /// Reset input.
    pub reset: Option<Index>,
    /// Overrun limit in periods.
    pub overrun_limit: u16,
    /// Overruns are faults.
    pub overrun_fault: bool,
    /// Lost edges are faults.
    pub lost_edge_fault: bool,
    /// Bytes of the image the background test checks per scan.
    pub rom_test_bytes_per_scan: u16,
    /// Inputs.
    pub inputs: Vec<ex::InputSpec>,
    /// The debounced inputs, in order.
    pub debounced: Vec<Index>,
    /// Mask of the debounced inputs.
    pub debounce_mask: Span,
    /// Outputs.
    pub outputs: Vec<ex::OutputSpec>,
    /// Timers.
    pub timers: Vec<ex::TimerSpec>,
    /// Events.
    pub events: Vec<ex::EventSpec>,
    /// Supervisors.
    pub supervisors: Vec<ex::SupervisorSpec>,
    /// Pool of input masks, each [`ex::words`]`(inputs)` words; equal
    /// masks are stored once.
    pub input_masks: Vec<u32>,
    /// Pool of event lists: the events each input's edges and each timer's
    /// expiry can raise, each supervisor's alphabet in local order, the
    /// commands with a request input.
    pub event_lists: Vec<Index>,
    /// Pool of event sets, each [`ex::words`]`(events)` words: what each
    /// supervisor never blocks, its stored allowed sets, the commands
    /// without a request input.
    pub event_masks: Vec<u32>,
    /// The commands without a request input (span of `event_masks`).
    pub commands: Span,
    /// The commands with a request input (span of `event_lists`).
    pub requested: Span,
    /// Pool of actions.
    pub actions: Vec<ex::Action>,
    /// Pool of memberships.
    pub memberships: Vec<ex::Membership>,
    /// Pool of state-map entries.
    pub state_map: Vec<ex::StateMapEntry>,
    /// The guards of symbolic supervisors, in event order.
    pub guards: Vec<ex::GuardSpec>,
    /// Pool of the state bits guards read.
    pub state_bits: Vec<ex::StateBit>,
    /// Pool of guard nodes (node `bit`s index `state_bits`).
    pub guard_nodes: Vec<ex::GuardNode>,
    /// Pool of the packed set numbers of stored allowed sets.
    pub allowed_index: Vec<u32>,
    /// The layout of each net, in declaration order: its groups are the
    /// supervisors after the automata.
    pub nets: Vec<NetLayout>,
    /// The pools' records, as [`ConfigPools::config`] hands them out.
    records: Records,
}

/// The records of the pools of a [`ConfigPools`] (the image's words:
/// [`executor::image`]).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
struct Records {
    inputs: Vec<[u32; 2]>,
    debounced: Vec<u32>,
    outputs: Vec<[u32; 2]>,
    timers: Vec<[u32; 2]>,
    events: Vec<[u32; 7]>,
    supervisors: Vec<[u32; 6]>,
    event_lists: Vec<u32>,
    actions: Vec<u32>,
    memberships: Vec<u32>,
    state_map: Vec<[u32; 3]>,
    guards: Vec<[u32; 3]>,
    state_bits: Vec<[u32; 1]>,
    guard_nodes: Vec<[u32; 2]>,
}

/// Why a project cannot be laid out, before [`ConfigPools::from_project`]
/// names the project file in the [`Error`] (once, for all of them).
#[derive(Debug)]
enum Refusal {
    /// Too many of these for a 16-bit index.
    TooMany(&'static str),
    /// This supervisor has no initial state.
    NoInitialState(String),
}

/// A lay-out step's result.
type Result<T> = std::result::Result<T, Refusal>;

fn index(value: usize, what: &'static str) -> Result<Index> {
    Index::try_from(value).map_err(|_| Refusal::TooMany(what))
}

/// Appends `items` to `pool` and returns their span; an empty list is
/// always [`Span::EMPTY`], so every empty span has one form (the generated
/// code writes it that way, and the image CRC covers span starts).
fn push_span<T: Clone>(pool: &mut Vec<T>, items: &[T], what: &'static str) -> Result<Span> {
    if items.is_empty() {
        return Ok(Span::EMPTY);
    }
    let start = index(pool.len(), what)?;
    let len = index(items.len(), what)?;
    index(pool.len() + items.len(), what)?;
    pool.extend_from_slice(items);
    Ok(Span::new(start, len))
}

/// A pool of bit sets under construction (input masks, event sets): each
/// distinct set once, `words` words each.
struct MaskPool {
    /// Words per set.
    words: usize,
    pool: Vec<u32>,
    /// The number of each set in the pool.
    numbers: HashMap<Vec<u32>, usize>,
    /// What the sets and their words are, for errors (`"input masks"`,
    /// `"input words"`).
    names: (&'static str, &'static str),
}

impl MaskPool {
    fn new(names: (&'static str, &'static str), count: usize) -> MaskPool {
        MaskPool {
            words: ex::words(count),
            pool: Vec::new(),
            numbers: HashMap::new(),
            names,
        }
    }

    /// The span of the set of `members` (an empty list: [`Span::EMPTY`],
    /// which reads as zeros past any pool).
    fn span(&mut self, members: &[usize]) -> Result<Span> {
        if members.is_empty() {
            return Ok(Span::EMPTY);
        }
        let at = self.words * self.insert(self.mask(members));
        let (masks, words) = self.names;
        index(at + self.words, masks)?;
        Ok(Span::new(index(at, masks)?, index(self.words, words)?))
    }

    /// The set of `members` as words.
    fn mask<'m>(&self, members: impl IntoIterator<Item = &'m usize>) -> Vec<u32> {
        let mut mask = vec![0u32; self.words];
        for &i in members {
            mask[i / 32] |= 1 << (i % 32);
        }
        mask
    }

    /// The number of `mask` in the pool, appended if new.
    fn insert(&mut self, mask: Vec<u32>) -> usize {
        let next = self.numbers.len();
        *self.numbers.entry(mask.clone()).or_insert_with(|| {
            self.pool.extend_from_slice(&mask);
            next
        })
    }
}

impl ConfigPools {
    /// Lays out `project`.
    pub fn from_project(project: &Project) -> crate::Result<ConfigPools> {
        super::count_pass();
        // A pool beyond 16-bit indices has no one line to blame: name the
        // project file.
        Self::lay_out(project).map_err(|refusal| {
            let project = project.path.clone();
            match refusal {
                Refusal::TooMany(what) => Error::TooMany {
                    project,
                    what,
                    limit: usize::from(Index::MAX),
                },
                Refusal::NoInitialState(supervisor) => Error::NoInitialState {
                    project,
                    supervisor,
                },
            }
        })
    }

    /// The pools are filled in a fixed order (events, outputs, inputs,
    /// timers, the debounced inputs, supervisors, commands): spans and the
    /// image CRC depend on it, and so does which error a project with
    /// several is refused with.
    fn lay_out(project: &Project) -> Result<ConfigPools> {
        let nets: Vec<NetLayout> = project.nets.iter().map(NetLayout::of).collect();
        let mut layout = Layout::new(project, &nets);
        let shapes = supervisor_shapes(project, &nets)?;
        let members_of = memberships_by_event(project, &shapes)?;
        let events = layout.events(&members_of)?;
        let outputs = layout.outputs()?;
        let inputs = layout.inputs()?;
        let timers = layout.timers()?;
        let (debounced, debounce_mask) = layout.debounced()?;
        let shapes_len = shapes.len();
        let supervisors = layout.supervisors(shapes)?;
        let (commands, requested) = layout.commands()?;
        let guards = GuardPools::of(project)?;

        index(project.inputs.len(), "inputs")?;
        index(project.outputs.len(), "outputs")?;
        index(project.timers.len(), "timers")?;
        index(project.events.len(), "events")?;
        index(shapes_len, "supervisors")?;
        Ok(ConfigPools {
            name: project.name.clone(),
            scan_period_ms: project.scan_period_ms,
            max_commands_per_scan: project.max_commands_per_scan,
            unexpected: match project.unexpected {
                Unexpected::Fault => ex::UnexpectedPolicy::Fault,
                Unexpected::Ignore => ex::UnexpectedPolicy::Ignore,
            },
            reset: project.reset.map(|r| index(r, "inputs")).transpose()?,
            overrun_limit: project.overrun_limit,
            overrun_fault: project.overrun_fault,
            lost_edge_fault: project.lost_edge_fault,
            rom_test_bytes_per_scan: project.rom_test_bytes_per_scan,
            inputs,
            debounced,
            debounce_mask,
            outputs,
            timers,
            events,
            supervisors,
            input_masks: layout.input_masks.pool,
            event_lists: layout.event_lists,
            event_masks: layout.event_masks.pool,
            commands,
            requested,
            actions: layout.actions,
            memberships: layout.memberships,
            state_map: layout.state_map,
            guards: guards.guards,
            state_bits: guards.state_bits,
            guard_nodes: guards.nodes,
            allowed_index: layout.allowed_index,
            nets,
            records: Records::default(),
        }
        .refreshed())
    }

    /// Writes the records of the typed pools anew: after a change to them,
    /// before [`ConfigPools::config`].
    pub fn refresh(&mut self) {
        let words = |list: &[Index]| list.iter().map(|&i| u32::from(i)).collect();
        self.records = Records {
            inputs: ex::encode(&self.inputs),
            debounced: words(&self.debounced),
            outputs: ex::encode(&self.outputs),
            timers: ex::encode(&self.timers),
            events: ex::encode(&self.events),
            supervisors: ex::encode(&self.supervisors),
            event_lists: words(&self.event_lists),
            actions: self.actions.iter().map(ex::Action::to_word).collect(),
            memberships: self
                .memberships
                .iter()
                .map(ex::Membership::to_word)
                .collect(),
            state_map: ex::encode(&self.state_map),
            guards: ex::encode(&self.guards),
            state_bits: ex::encode(&self.state_bits),
            guard_nodes: ex::encode(&self.guard_nodes),
        };
    }

    fn refreshed(mut self) -> ConfigPools {
        self.refresh();
        self
    }

    /// The executor's borrowed view.
    pub fn config(&self) -> Config<'_> {
        let r = &self.records;
        Config {
            name: &self.name,
            scan_period_ms: self.scan_period_ms,
            max_commands_per_scan: self.max_commands_per_scan,
            unexpected: self.unexpected,
            reset: self.reset,
            overrun_limit: self.overrun_limit,
            overrun_fault: self.overrun_fault,
            lost_edge_fault: self.lost_edge_fault,
            rom_test_bytes_per_scan: self.rom_test_bytes_per_scan,
            inputs: &r.inputs,
            debounced: &r.debounced,
            debounce_mask: self.debounce_mask,
            outputs: &r.outputs,
            timers: &r.timers,
            events: &r.events,
            supervisors: &r.supervisors,
            input_masks: &self.input_masks,
            event_lists: &r.event_lists,
            event_masks: &self.event_masks,
            commands: self.commands,
            requested: self.requested,
            actions: &r.actions,
            memberships: &r.memberships,
            state_map: &r.state_map,
            guards: ex::Guards {
                events: &r.guards,
                bits: &r.state_bits,
                nodes: &r.guard_nodes,
            },
            allowed_index: &self.allowed_index,
        }
    }
}

/// The guards of every symbolic supervisor, with the state bits and nodes
/// they read, as the executor's pools. A guard that always holds (root 1)
/// is left out: the event is then never held back, as without a guard.
/// Only the state bits some kept guard reads are stored, each
/// supervisor's in its guard file's order, and its nodes' bit numbers are
/// renumbered to them.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct GuardPools {
    /// The kept guards, in event order.
    pub guards: Vec<ex::GuardSpec>,
    /// The state bits they read.
    pub state_bits: Vec<ex::StateBit>,
    /// Their decision nodes.
    pub nodes: Vec<ex::GuardNode>,
}

/// One guard as a symbolic supervisor states it: its event, its root and
/// its nodes `[bit, low, high]` over the supervisor's state bits.
pub type GuardTable<'g> = (usize, u32, &'g [[u32; 3]]);

impl GuardPools {
    fn of(project: &Project) -> Result<GuardPools> {
        let mut pools = GuardPools::default();
        for g in &project.guarded {
            let guards: Vec<GuardTable<'_>> = (g.guards.iter())
                .map(|guard| (guard.event, guard.root, guard.nodes.as_slice()))
                .collect();
            pools.push(&g.bits, &guards)?;
        }
        Ok(pools)
    }

    /// Adds the guards of one symbolic supervisor whose state bits are
    /// `bits` (supervisor, shift); guards stay in event order. `Err`
    /// names what would overflow a 16-bit index.
    pub fn add(
        &mut self,
        bits: &[(usize, u32)],
        guards: &[GuardTable<'_>],
    ) -> std::result::Result<(), &'static str> {
        self.push(bits, guards).map_err(|refusal| match refusal {
            Refusal::TooMany(what) => what,
            Refusal::NoInitialState(_) => "guards",
        })
    }

    /// [`GuardPools::add`], refusing as the rest of the lay-out does.
    fn push(&mut self, bits: &[(usize, u32)], guards: &[GuardTable<'_>]) -> Result<()> {
        let kept: Vec<_> = guards.iter().filter(|guard| guard.1 != 1).collect();
        let mut read = vec![false; bits.len()];
        for guard in &kept {
            for &[bit, _, _] in guard.2 {
                read[bit as usize] = true;
            }
        }
        let mut renumbered = vec![0; bits.len()];
        for (bit, &(component, shift)) in bits.iter().enumerate() {
            if !read[bit] {
                continue;
            }
            renumbered[bit] = index(self.state_bits.len(), "state bits")?;
            self.state_bits.push(ex::StateBit {
                component: index(component, "supervisors")?,
                shift: u8::try_from(shift).map_err(|_| Refusal::TooMany("state bits"))?,
            });
        }
        for &&(event, root, nodes) in &kept {
            let nodes = nodes
                .iter()
                .map(|&[bit, low, high]| {
                    Ok(ex::GuardNode {
                        bit: renumbered[bit as usize],
                        low: index(low as usize, "guard nodes")?,
                        high: index(high as usize, "guard nodes")?,
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            index(nodes.len() + 2, "guard nodes")?;
            let span = push_span(&mut self.nodes, &nodes, "guard nodes")?;
            self.guards.push(ex::GuardSpec {
                event: index(event, "events")?,
                root: index(root as usize, "guard nodes")?,
                nodes: span,
            });
        }
        self.guards.sort_by_key(|g| g.event);
        Ok(())
    }
}

/// `list` as executor indices.
fn to_indices(list: &[usize], what: &'static str) -> Result<Vec<Index>> {
    list.iter().map(|&i| index(i, what)).collect()
}

/// An executor supervisor before it is laid out.
struct SupervisorShape {
    states: u32,
    initial: u32,
    /// Its events (project indices) in local order.
    alphabet: Vec<usize>,
    /// The events it enables in each state (project indices), when its
    /// allowed sets are stored ([`ex::AllowedSets`]); `None` for a net
    /// group, whose sets are computed.
    enabled: Option<Vec<Vec<usize>>>,
}

/// Every executor supervisor of `project`: the automata, then the net
/// groups, whose local events are the transitions touching the group.
fn supervisor_shapes(project: &Project, nets: &[NetLayout]) -> Result<Vec<SupervisorShape>> {
    let mut shapes = Vec::new();
    for s in &project.supervisors {
        let initial = s.automaton.initial();
        let initial = initial.ok_or_else(|| Refusal::NoInitialState(s.name.clone()))?;
        let enabled = (0..s.automaton.num_states())
            .map(|x| {
                let x = StateId(x as u32);
                (s.local_events.iter())
                    .filter(|&&(_, id)| s.automaton.successor(x, id).is_some())
                    .map(|&(e, _)| e)
                    .collect()
            })
            .collect();
        shapes.push(SupervisorShape {
            states: s.automaton.num_states() as u32,
            initial: initial.0,
            alphabet: s.local_events.iter().map(|&(e, _)| e).collect(),
            enabled: Some(enabled),
        });
    }
    for (net, layout) in project.nets.iter().zip(nets) {
        let groups = NetGroups { net, layout };
        for g in 0..layout.groups() {
            let transitions = groups.group_transitions(g);
            shapes.push(SupervisorShape {
                states: 1 << layout.group_bits[g],
                initial: layout.pack(g, net.net.initial()),
                alphabet: transitions.iter().map(|&t| net.events[t]).collect(),
                enabled: None,
            });
        }
    }
    Ok(shapes)
}

/// Which supervisors have each event of `project`, with its local index
/// there.
fn memberships_by_event(
    project: &Project,
    shapes: &[SupervisorShape],
) -> Result<Vec<Vec<ex::Membership>>> {
    let mut members_of: Vec<Vec<ex::Membership>> = vec![Vec::new(); project.events.len()];
    for (j, shape) in shapes.iter().enumerate() {
        for (local, &global) in shape.alphabet.iter().enumerate() {
            members_of[global].push(ex::Membership {
                supervisor: index(j, "supervisors")?,
                local: index(local, "events")?,
            });
        }
    }
    Ok(members_of)
}

/// An event's action as the executor's.
fn action(a: &Action) -> Result<ex::Action> {
    Ok(match *a {
        Action::Set(o) => ex::Action::Set(index(o, "outputs")?),
        Action::Clear(o) => ex::Action::Clear(index(o, "outputs")?),
        Action::Start(t) => ex::Action::Start(index(t, "timers")?),
        Action::Reset(t) => ex::Action::Reset(index(t, "timers")?),
    })
}

/// A Moore output's state-map entries: each listed state of each listed
/// supervisor.
fn state_entries(entries: &[(usize, Vec<StateId>)]) -> Result<Vec<ex::StateMapEntry>> {
    let mut list = Vec::new();
    for (sup, states) in entries {
        for s in states {
            list.push(ex::StateMapEntry::in_state(
                index(*sup, "supervisors")?,
                s.0,
            ));
        }
    }
    Ok(list)
}

/// The pools of a project under construction, filled one record kind at
/// a time by [`ConfigPools::lay_out`].
struct Layout<'p> {
    project: &'p Project,
    /// Each net's layout.
    nets: &'p [NetLayout],
    input_masks: MaskPool,
    event_masks: MaskPool,
    event_lists: Vec<Index>,
    actions: Vec<ex::Action>,
    memberships: Vec<ex::Membership>,
    state_map: Vec<ex::StateMapEntry>,
    allowed_index: Vec<u32>,
}

impl<'p> Layout<'p> {
    /// Empty pools for `project`.
    fn new(project: &'p Project, nets: &'p [NetLayout]) -> Layout<'p> {
        Layout {
            project,
            nets,
            input_masks: MaskPool::new(("input masks", "input words"), project.inputs.len()),
            event_masks: MaskPool::new(("event masks", "event words"), project.events.len()),
            event_lists: Vec::new(),
            actions: Vec::new(),
            memberships: Vec::new(),
            state_map: Vec::new(),
            allowed_index: Vec::new(),
        }
    }

    /// The events: their triggers' and conditions' input masks, their
    /// actions and their memberships (`members_of`, by event).
    fn events(&mut self, members_of: &[Vec<ex::Membership>]) -> Result<Vec<ex::EventSpec>> {
        let mut events = Vec::with_capacity(self.project.events.len());
        for (e, ev) in self.project.events.iter().enumerate() {
            let masks = &mut self.input_masks;
            let trigger = match &ev.trigger {
                Trigger::Command => ex::Trigger::Command,
                Trigger::Rising(list) => ex::Trigger::Rising(masks.span(list)?),
                Trigger::Falling(list) => ex::Trigger::Falling(masks.span(list)?),
                Trigger::Expired(t) => ex::Trigger::Expired(index(*t, "timers")?),
            };
            let when = masks.span(&ev.when)?;
            let unless = masks.span(&ev.unless)?;
            let acts: Vec<ex::Action> = ev.actions.iter().map(action).collect::<Result<_>>()?;
            events.push(ex::EventSpec {
                trigger,
                when,
                unless,
                request: ev.request.map(|r| index(r, "inputs")).transpose()?,
                actions: push_span(&mut self.actions, &acts, "actions")?,
                members: push_span(&mut self.memberships, &members_of[e], "memberships")?,
            });
        }
        Ok(events)
    }

    /// The outputs, and the state-map entries of the Moore outputs.
    fn outputs(&mut self) -> Result<Vec<ex::OutputSpec>> {
        let mut outputs = Vec::with_capacity(self.project.outputs.len());
        for out in &self.project.outputs {
            let (initial, map) = match &out.drive {
                Drive::Actions { initial } => (*initial, Span::EMPTY),
                Drive::States(entries) => {
                    let list = state_entries(entries)?;
                    let map = push_span(&mut self.state_map, &list, "state-map entries")?;
                    (false, map)
                }
                Drive::Places(entries) => {
                    let list = self.place_entries(entries)?;
                    let map = push_span(&mut self.state_map, &list, "state-map entries")?;
                    (false, map)
                }
            };
            outputs.push(ex::OutputSpec {
                safe: out.safe,
                initial,
                state_map: map,
            });
        }
        Ok(outputs)
    }

    /// A Moore output of Petri nets' state-map entries: one per count a
    /// listed place can hold (at least 1, so a place map is never empty).
    fn place_entries(&self, entries: &[(usize, Vec<usize>)]) -> Result<Vec<ex::StateMapEntry>> {
        let mut list = Vec::new();
        for &(n, ref places) in entries {
            let net = &self.project.nets[n];
            // Net `n`'s groups follow the automata and the groups before it.
            let first = self.project.supervisors.len()
                + self.nets[..n].iter().map(NetLayout::groups).sum::<usize>();
            for &p in places {
                let field = self.nets[n].fields[p];
                let j = first + field.group;
                for count in 1..=net.bounds[p].max(1) {
                    let supervisor = index(j, "supervisors")?;
                    list.push(ex::StateMapEntry::marked(supervisor, field.mask(), count));
                }
            }
        }
        Ok(list)
    }

    /// The span of `event_lists` holding the events whose trigger `bound`
    /// accepts.
    fn raised_by(&mut self, bound: &dyn Fn(&Trigger) -> bool) -> Result<Span> {
        let events: Vec<Index> = (self.project.events.iter().enumerate())
            .filter(|(_, ev)| bound(&ev.trigger))
            .map(|(e, _)| index(e, "events"))
            .collect::<Result<_>>()?;
        push_span(&mut self.event_lists, &events, "event lists")
    }

    /// The inputs, with the events their edges can raise.
    fn inputs(&mut self) -> Result<Vec<ex::InputSpec>> {
        let mut inputs = Vec::with_capacity(self.project.inputs.len());
        for (i, input) in self.project.inputs.iter().enumerate() {
            let raises = self.raised_by(&|t| match t {
                Trigger::Rising(list) | Trigger::Falling(list) => list.contains(&i),
                Trigger::Command | Trigger::Expired(_) => false,
            })?;
            inputs.push(ex::InputSpec {
                debounce_scans: input.debounce_scans,
                raises,
            });
        }
        Ok(inputs)
    }

    /// The timers, with the events their expiry raises.
    fn timers(&mut self) -> Result<Vec<ex::TimerSpec>> {
        let mut timers = Vec::with_capacity(self.project.timers.len());
        for (t, timer) in self.project.timers.iter().enumerate() {
            let raises = self.raised_by(&|trigger| *trigger == Trigger::Expired(t))?;
            timers.push(ex::TimerSpec {
                preset_ms: timer.preset_ms,
                raises,
            });
        }
        Ok(timers)
    }

    /// The debounced inputs (`debounce_scans` of 2 or more) and their mask.
    fn debounced(&mut self) -> Result<(Vec<Index>, Span)> {
        let inputs = &self.project.inputs;
        let debounced: Vec<usize> = (0..inputs.len())
            .filter(|&i| inputs[i].debounce_scans >= 2)
            .collect();
        let mask = self.input_masks.span(&debounced)?;
        Ok((to_indices(&debounced, "inputs")?, mask))
    }

    /// The supervisors: alphabets in `event_lists`, what each never
    /// blocks and its stored allowed sets in `event_masks`, their index in
    /// `allowed_index`.
    fn supervisors(&mut self, shapes: Vec<SupervisorShape>) -> Result<Vec<ex::SupervisorSpec>> {
        let count = self.project.events.len();
        let mut supervisors = Vec::with_capacity(shapes.len());
        for shape in shapes {
            let outside: Vec<usize> = (0..count).filter(|e| !shape.alphabet.contains(e)).collect();
            let allowed = match &shape.enabled {
                Some(enabled) if count != 0 => self.allowed_sets(&outside, enabled)?,
                _ => ex::AllowedSets::COMPUTED,
            };
            let outside = self.event_masks.span(&outside)?;
            let alphabet = to_indices(&shape.alphabet, "events")?;
            // Consecutive and increasing (not so for a Petri-net group,
            // whose local order is its transitions'): the scan shifts an
            // enabled row into place rather than scattering its bits.
            let contiguous = alphabet.windows(2).all(|w| w[1] == w[0].wrapping_add(1));
            supervisors.push(ex::SupervisorSpec {
                states: shape.states,
                initial: shape.initial,
                alphabet: push_span(&mut self.event_lists, &alphabet, "event lists")?,
                outside,
                allowed,
                contiguous,
            });
        }
        Ok(supervisors)
    }

    /// A supervisor's allowed set in each state (`outside` and what it
    /// enables there), each distinct set once in `event_masks`, and the
    /// index of their numbers; [`ex::AllowedSets::COMPUTED`] when the index
    /// and the sets it adds would take more than `stored_sets_bytes`.
    fn allowed_sets(
        &mut self,
        outside: &[usize],
        enabled: &[Vec<usize>],
    ) -> Result<ex::AllowedSets> {
        let masks: Vec<Vec<u32>> = (enabled.iter())
            .map(|events| self.event_masks.mask(outside.iter().chain(events)))
            .collect();
        let new: HashSet<&Vec<u32>> = (masks.iter())
            .filter(|m| !self.event_masks.numbers.contains_key(*m))
            .collect();
        let sets = self.event_masks.numbers.len() + new.len();
        let bits = bits_for(sets.saturating_sub(1) as u64);
        let index_words = (masks.len() * usize::from(bits)).div_ceil(32);
        let bytes = 4 * (index_words + new.len() * self.event_masks.words);
        if bytes as u64 > u64::from(self.project.stored_sets_bytes) {
            return Ok(ex::AllowedSets::COMPUTED);
        }
        let mut packed = vec![0; index_words];
        for (x, mask) in masks.into_iter().enumerate() {
            let k = self.event_masks.insert(mask);
            write_bits(&mut packed, x, bits, k as u32);
        }
        // Set numbers stay within 16 bits, as every span of the pool.
        index(self.event_masks.pool.len(), self.event_masks.names.0)?;
        Ok(ex::AllowedSets {
            index: push_span(&mut self.allowed_index, &packed, "allowed index words")?,
            bits,
        })
    }

    /// The commands the controller may choose without a request (a span of
    /// `event_masks`) and those with a request input (of `event_lists`).
    fn commands(&mut self) -> Result<(Span, Span)> {
        let events = &self.project.events;
        let is_command = |e: &usize| events[*e].trigger == Trigger::Command;
        let commands: Vec<usize> = (0..events.len())
            .filter(|e| is_command(e) && events[*e].request.is_none())
            .collect();
        let commands = self.event_masks.span(&commands)?;
        let requested: Vec<usize> = (0..events.len())
            .filter(|e| is_command(e) && events[*e].request.is_some())
            .collect();
        let requested = to_indices(&requested, "events")?;
        let requested = push_span(&mut self.event_lists, &requested, "event lists")?;
        Ok((commands, requested))
    }
}
