//! The name modules (`input`, `output`, …, `states`) and the executor's
//! configuration as statics (`INPUTS` … `STATE_MAP`, `CONFIG`, `Memory`).
//!
//! The configuration is indices and spans into shared pools; its doc
//! comments decode them (which inputs an event is bound to, what it does,
//! which supervisors have it; which event owns which pool positions), so a
//! reader never counts offsets. The decoding reads the pools themselves,
//! not the project, so the comments describe exactly the data below them.

use super::{ident, listed, positions, quoted, Emitter};
use crate::lower::ConfigPools;

/// The members of a bit set, in order.
fn mask_members(mask: &[u32]) -> Vec<ex::Index> {
    let mut members = Vec::new();
    for (k, &w) in mask.iter().enumerate() {
        for b in 0..32 {
            if w >> b & 1 == 1 {
                members.push((k * 32 + b) as ex::Index);
            }
        }
    }
    members
}

/// A doc comment: `title` and, if there are any, the list items `doc`.
fn titled(title: &str, doc: &str) -> String {
    if doc.is_empty() {
        format!("/// {title}.\n")
    } else {
        format!("/// {title}:\n{doc}")
    }
}
use executor::program as ex;
use plc_project::Origin;
use std::fmt::Write;

impl Emitter<'_> {
    /// `pub mod <module>` with one index constant per name, `COUNT` and
    /// `NAMES`.
    fn name_module(&mut self, module: &str, doc: &str, names: &[&str]) {
        // Names are for reference: a crate uses some of them, never all.
        let _ = writeln!(
            self.out,
            "/// {doc}\n#[allow(dead_code)]\npub mod {module} {{"
        );
        if !names.is_empty() {
            let _ = writeln!(self.out, "    use super::Index;");
        }
        for (i, n) in names.iter().enumerate() {
            let _ = writeln!(self.out, "    /// {}", quoted(n));
            let _ = writeln!(self.out, "    pub const {}: Index = {i};", ident(n));
        }
        let _ = writeln!(
            self.out,
            "    /// How many there are.\n    pub const COUNT: usize = {};\n    /// Names in declaration order.\n    pub static NAMES: [&str; {}] = [{}];\n}}",
            names.len(),
            names.len(),
            names.iter().map(|n| format!("{n:?}")).collect::<Vec<_>>().join(", ")
        );
    }

    /// The name modules of inputs, outputs, timers, events and
    /// supervisors, and the state names of every supervisor.
    pub(super) fn names(&mut self) {
        let p = self.project;
        let inputs: Vec<&str> = p.inputs.iter().map(|x| x.name.as_str()).collect();
        let outputs: Vec<&str> = p.outputs.iter().map(|x| x.name.as_str()).collect();
        let timers: Vec<&str> = p.timers.iter().map(|x| x.name.as_str()).collect();
        let events: Vec<&str> = p.events.iter().map(|x| x.name.as_str()).collect();
        let supervisors = self.supervisors();
        let sup_names: Vec<String> = (0..supervisors.len())
            .map(|j| supervisors.name(j))
            .collect();
        let sups: Vec<&str> = sup_names.iter().map(String::as_str).collect();
        self.name_module("input", "Inputs, in declaration order.", &inputs);
        self.name_module("output", "Outputs, in declaration order.", &outputs);
        self.name_module("timer", "Timers, in declaration order.", &timers);
        self.name_module("event", "Events, in declaration (priority) order.", &events);
        self.name_module("supervisor", "Supervisors, in declaration order.", &sups);
        let _ = writeln!(
            self.out,
            "/// State names of each supervisor, by state index.\n#[allow(dead_code)]\npub mod states {{"
        );
        for s in &p.supervisors {
            let names: Vec<String> = s
                .automaton
                .states()
                .map(|x| format!("{:?}", s.automaton.state_name(x)))
                .collect();
            let _ = writeln!(
                self.out,
                "    /// Supervisor {}.\n    pub static {}: [&str; {}] = [{}];",
                quoted(&s.name),
                ident(&s.name),
                names.len(),
                names.join(", ")
            );
        }
        let _ = writeln!(self.out, "}}");
        if !p.nets.is_empty() {
            self.place_names();
        }
    }

    /// The `places` module: for each group of each net, the places it
    /// holds and each one's counter mask in the group's packed marking.
    fn place_names(&mut self) {
        let p = self.project;
        let _ = writeln!(
            self.out,
            "/// Places of each Petri-net group: ids in place order, and the mask of
/// each one's counter in the group's state (its packed marking).
#[allow(dead_code)]
pub mod places {{"
        );
        let supervisors = self.supervisors();
        for n in 0..p.nets.len() {
            let net = supervisors.net(n);
            for g in 0..net.groups() {
                let name = net.group_name(g);
                let places: Vec<usize> = net.layout.group_places(g).collect();
                let ids: Vec<String> = places
                    .iter()
                    .map(|&q| format!("{:?}", net.net.net.places()[q].id))
                    .collect();
                let masks: Vec<String> = places
                    .iter()
                    .map(|&q| format!("{:#x}", net.layout.fields[q].mask()))
                    .collect();
                let _ = writeln!(
                    self.out,
                    "    /// Places of {} (supervisor {}).
    pub static {}: [&str; {}] = [{}];
    /// Counter masks of {}, in the order of its places.
    pub static {}_MASKS: [u32; {}] = [{}];",
                    quoted(&name),
                    supervisors.group_supervisor(n, g),
                    ident(&name),
                    ids.len(),
                    ids.join(", "),
                    quoted(&name),
                    ident(&name),
                    masks.len(),
                    masks.join(", ")
                );
            }
        }
        let _ = writeln!(self.out, "}}");
    }

    fn input_name(&self, i: ex::Index) -> String {
        quoted(&self.project.inputs[usize::from(i)].name)
    }

    fn output_name(&self, o: ex::Index) -> String {
        quoted(&self.project.outputs[usize::from(o)].name)
    }

    fn timer_name(&self, t: ex::Index) -> String {
        quoted(&self.project.timers[usize::from(t)].name)
    }

    fn event_name(&self, e: usize) -> String {
        quoted(&self.project.events[e].name)
    }

    fn supervisor_name(&self, s: ex::Index) -> String {
        quoted(&self.supervisors().name(usize::from(s)))
    }

    fn state_name(&self, s: ex::Index, state: u32) -> String {
        quoted(&self.supervisors().state_name(usize::from(s), state))
    }

    /// The input names of a mask (a span of the input masks).
    fn inputs_in(&self, s: ex::Span) -> Vec<String> {
        mask_members(s.of(&self.pools.input_masks))
            .into_iter()
            .map(|i| self.input_name(i))
            .collect()
    }

    /// The event names of a span of the event-list pool.
    fn raised_in(&self, s: ex::Span) -> Vec<String> {
        s.of(&self.pools.event_lists)
            .iter()
            .map(|&e| self.event_name(usize::from(e)))
            .collect()
    }

    /// A mask word as Rust: `mask_word(k, &[input::A, input::B])`, or `0`.
    fn mask_word_expr(&self, k: usize, word: u32) -> String {
        if word == 0 {
            return "0".to_owned();
        }
        let names: Vec<String> = (0..32)
            .filter(|b| word >> b & 1 == 1)
            .map(|b| self.input((k * 32 + b) as ex::Index))
            .collect();
        format!("mask_word({k}, &[{}])", names.join(", "))
    }

    /// An event-set word as Rust: `mask_word(k, &[event::A, event::B])`,
    /// `mask_word_except(k, event::COUNT, &[event::C])` when that names
    /// fewer events, or `0`.
    fn event_word_expr(&self, k: usize, word: u32) -> String {
        if word == 0 {
            return "0".to_owned();
        }
        let events = &self.project.events;
        let in_word = (events.len() - k * 32).min(32);
        let names = |member: bool| -> Vec<String> {
            (0..in_word)
                .filter(|b| (word >> b & 1 == 1) == member)
                .map(|b| format!("event::{}", ident(&events[k * 32 + b].name)))
                .collect()
        };
        let (members, others) = (names(true), names(false));
        // A set that holds most of the word's events is written by what it
        // leaves out.
        if others.len() < members.len() {
            format!(
                "mask_word_except({k}, event::COUNT, &[{}])",
                others.join(", ")
            )
        } else {
            format!("mask_word({k}, &[{}])", members.join(", "))
        }
    }

    /// The events whose actions include `wanted`.
    fn events_doing(&self, wanted: ex::Action) -> Vec<String> {
        let pools = self.pools;
        (0..pools.events.len())
            .filter(|&e| pools.events[e].actions.of(&pools.actions).contains(&wanted))
            .map(|e| self.event_name(e))
            .collect()
    }

    /// "`sup` is in `a` or `b`, or `other` is in `c`": the states of a
    /// state-map span, grouped by supervisor in pool order.
    fn state_map_text(&self, s: ex::Span) -> String {
        let mut groups: Vec<(ex::Index, Vec<String>)> = Vec::new();
        for entry in s.of(&self.pools.state_map) {
            let name = self.state_name(entry.supervisor, entry.state);
            match groups.last_mut() {
                Some((sup, states)) if *sup == entry.supervisor => states.push(name),
                _ => groups.push((entry.supervisor, vec![name])),
            }
        }
        let clauses: Vec<String> = groups
            .iter()
            .map(|(sup, states)| {
                format!(
                    "{} is in {}",
                    self.supervisor_name(*sup),
                    listed(states, "or")
                )
            })
            .collect();
        clauses.join(", or ")
    }

    /// One event decoded: its kind, binding and conditions, actions and
    /// supervisors (with its local index in each).
    fn event_text(&self, e: usize) -> String {
        let pools = self.pools;
        let spec = &pools.events[e];
        let ev = &self.project.events[e];
        let kind = match (ev.controllable, ev.origin) {
            (true, _) => "controllable",
            (false, Origin::Operator) => "uncontrollable, operator",
            (false, _) => "uncontrollable, plant",
        };
        let edge = |what: &str, s: ex::Span| {
            let inputs = self.inputs_in(s);
            if inputs.len() == 1 {
                format!("{what} edge of {}", inputs[0])
            } else {
                format!("{what} edge of ({})", listed(&inputs, "or"))
            }
        };
        let mut binding = match spec.trigger {
            ex::Trigger::Command => "commanded".to_owned(),
            ex::Trigger::Rising(s) => edge("rising", s),
            ex::Trigger::Falling(s) => edge("falling", s),
            ex::Trigger::Expired(t) => format!("expiry of {}", self.timer_name(t)),
        };
        if !spec.when.is_empty() {
            let _ = write!(
                binding,
                " when {}",
                listed(&self.inputs_in(spec.when), "and")
            );
        }
        if !spec.unless.is_empty() {
            let _ = write!(
                binding,
                " unless {}",
                listed(&self.inputs_in(spec.unless), "or")
            );
        }
        if let Some(r) = spec.request {
            let _ = write!(binding, ", only while {} is 1", self.input_name(r));
        }
        let mut parts = vec![binding];
        let actions: Vec<String> = spec
            .actions
            .of(&pools.actions)
            .iter()
            .map(|a| match *a {
                ex::Action::Set(o) => format!("sets {}", self.output_name(o)),
                ex::Action::Clear(o) => format!("clears {}", self.output_name(o)),
                ex::Action::Start(t) => format!("starts {}", self.timer_name(t)),
                ex::Action::Reset(t) => format!("resets {}", self.timer_name(t)),
            })
            .collect();
        if !actions.is_empty() {
            parts.push(actions.join(", "));
        }
        let members: Vec<String> = spec
            .members
            .of(&pools.memberships)
            .iter()
            .map(|m| format!("{} (local {})", self.supervisor_name(m.supervisor), m.local))
            .collect();
        parts.push(if members.is_empty() {
            "in no supervisor".to_owned()
        } else {
            format!("in {}", members.join(", "))
        });
        format!("{} ({kind}): {}", self.event_name(e), parts.join("; "))
    }

    /// Doc lines naming the owners of each non-empty span, in pool order
    /// (a span several owners share on one line).
    fn owners(&self, mut spans: Vec<(ex::Span, String)>) -> String {
        spans.retain(|(s, _)| !s.is_empty());
        spans.sort_by_key(|(s, _)| (s.start, s.len));
        let mut lines: Vec<(ex::Span, Vec<String>)> = Vec::new();
        for (s, owner) in spans {
            match lines.last_mut() {
                Some((last, owners)) if *last == s => owners.push(owner),
                _ => lines.push((s, vec![owner])),
            }
        }
        let mut doc = String::new();
        for (s, owners) in lines {
            let _ = writeln!(doc, "/// - {}: {}", positions(s), owners.join(", "));
        }
        doc
    }

    /// `const <name>: [<ty>; N] = [<items>];` under the doc comment
    /// `titled(title, doc)`: one pool of the configuration.
    ///
    /// A pool of typed items is stored as their words (the image: the
    /// executor's `Config`), written as the typed values converted by a
    /// `const fn`: `Ty::records(&[..])`, `Ty::words(&[..])` for a kind of
    /// one word, `indices(&[..])` for indices.
    fn pool(&mut self, name: &str, ty: &str, title: &str, doc: &str, items: &[String]) {
        let n = items.len();
        let items = items.join(", ");
        let (ty, value) = match ty {
            "u32" => (format!("[u32; {n}]"), format!("[{items}]")),
            "Index" => (format!("[u32; {n}]"), format!("indices(&[{items}])")),
            "Action" | "Membership" => (format!("[u32; {n}]"), format!("{ty}::words(&[{items}])")),
            _ => {
                let k = record_words(ty);
                (
                    format!("[[u32; {k}]; {n}]"),
                    format!("{ty}::records(&[{items}])"),
                )
            }
        };
        let _ = writeln!(
            self.out,
            "{}const {name}: {ty} = {value};",
            titled(title, doc)
        );
    }

    /// The configuration statics, `CONFIG` and `Memory`, in the order the
    /// generated file has always had.
    pub(super) fn config(&mut self) {
        self.input_specs();
        self.output_specs();
        self.timer_specs();
        self.event_specs();
        self.supervisor_specs();
        self.input_masks();
        self.event_lists();
        self.event_masks();
        self.actions();
        self.memberships();
        self.state_map();
        self.guards();
        self.allowed_index();
        self.config_and_memory();
    }

    /// `ALLOWED_INDEX`: for each supervisor that stores its allowed sets,
    /// the number of its set in `EVENT_MASKS` in each state (nothing when
    /// none does; `CONFIG` then has an empty pool).
    fn allowed_index(&mut self) {
        let pools = self.pools;
        if pools.allowed_index.is_empty() {
            return;
        }
        let mut doc = String::new();
        for (j, sup) in pools.supervisors.iter().enumerate() {
            if !sup.allowed.is_stored() {
                continue;
            }
            let index = j as ex::Index;
            let sets = stored_sets(pools, j);
            let by_state: Vec<String> = (sets.iter().enumerate().take(STATES_LISTED))
                .map(|(x, k)| format!("{} {k}", self.state_name(index, x as u32)))
                .collect();
            let more = if sets.len() > STATES_LISTED {
                ", …"
            } else {
                ""
            };
            let _ = writeln!(
                doc,
                "/// - {}: {} ({}-bit set numbers by state: {}{more})",
                positions(sup.allowed.index),
                self.supervisor_name(index),
                sup.allowed.bits,
                by_state.join(", ")
            );
        }
        let words: Vec<String> = (pools.allowed_index.iter())
            .map(|w| format!("{w:#010x}"))
            .collect();
        self.pool(
            "ALLOWED_INDEX",
            "u32",
            "The stored allowed sets: in each state, the number `k` of the supervisor's allowed set, words `k·EVENT_WORDS ..` of `EVENT_MASKS`, packed; by position",
            &doc,
            &words,
        );
    }

    /// `GUARDS`, `STATE_BITS` and `GUARD_NODES`: the symbolic
    /// supervisors' guards (nothing when the project has none; `CONFIG`
    /// then says `Guards::NONE`).
    fn guards(&mut self) {
        let pools = self.pools;
        if pools.guards.is_empty() && pools.state_bits.is_empty() {
            return;
        }
        let texts: Vec<(usize, &str)> = self
            .project
            .guarded
            .iter()
            .flat_map(|g| g.guards.iter().map(|x| (x.event, x.text.as_str())))
            .collect();
        let mut doc = String::new();
        let mut guards = Vec::with_capacity(pools.guards.len());
        for (k, g) in pools.guards.iter().enumerate() {
            let e = usize::from(g.event);
            let text = texts
                .iter()
                .find(|(event, _)| *event == e)
                .map_or("", |(_, t)| t);
            let _ = writeln!(
                doc,
                "/// - {k}: {} may occur while {}",
                self.event_name(e),
                abbreviated(text, 160)
            );
            guards.push(format!(
                "GuardSpec {{ event: event::{}, root: {}, nodes: {} }}",
                ident(&self.project.events[e].name),
                g.root,
                self.span(g.nodes)
            ));
        }
        self.pool(
            "GUARDS",
            "GuardSpec",
            "The guarded commands: each may occur only while its guard (a decision diagram over `STATE_BITS`, its `nodes` in `GUARD_NODES`, `root` 0 false, 1 true, k ≥ 2 node k − 2 of its span) holds, by position",
            &doc,
            &guards,
        );
        let bits: Vec<String> = pools
            .state_bits
            .iter()
            .map(|b| {
                format!(
                    "StateBit {{ component: {}, shift: {} }}",
                    self.supervisor(b.component),
                    b.shift
                )
            })
            .collect();
        self.pool(
            "STATE_BITS",
            "StateBit",
            "The state bits the guards read: a component's state, shifted right by `shift`, bit 0",
            "",
            &bits,
        );
        let nodes: Vec<String> = pools
            .guard_nodes
            .iter()
            .map(|n| {
                format!(
                    "GuardNode {{ bit: {}, low: {}, high: {} }}",
                    n.bit, n.low, n.high
                )
            })
            .collect();
        self.pool(
            "GUARD_NODES",
            "GuardNode",
            "Decision nodes of the guards: read `STATE_BITS[bit]`, go on at `high` when it is 1, at `low` when 0 (children first)",
            "",
            &nodes,
        );
    }

    /// `INPUT_WORDS`, `INPUTS` (filtering and the events each input's
    /// edges can raise) and `DEBOUNCED`.
    fn input_specs(&mut self) {
        let pools = self.pools;
        let mut doc = String::new();
        for (i, input) in pools.inputs.iter().enumerate() {
            let mut about = match input.debounce_scans {
                0 | 1 => "unfiltered".to_owned(),
                d => format!("debounced over {d} scans"),
            };
            let raised = self.raised_in(input.raises);
            if !raised.is_empty() {
                let _ = write!(about, "; its edges can raise {}", listed(&raised, "and"));
            }
            let name = quoted(&self.project.inputs[i].name);
            let _ = writeln!(doc, "/// - {i} {name}: {about}");
        }
        let inputs: Vec<String> = pools
            .inputs
            .iter()
            .map(|i| {
                format!(
                    "InputSpec {{ debounce_scans: {}, raises: {} }}",
                    i.debounce_scans,
                    self.span(i.raises)
                )
            })
            .collect();
        let _ = writeln!(
            self.out,
            "/// Words of the input image and of every input mask (32 inputs per word).\n#[allow(dead_code)]\npub const INPUT_WORDS: usize = executor::program::words(input::COUNT);"
        );
        self.pool(
            "INPUTS",
            "InputSpec",
            "Input filtering and the events each input's edges can raise, by input",
            &doc,
            &inputs,
        );
        let debounced: Vec<String> = pools.debounced.iter().map(|&i| self.input(i)).collect();
        self.pool(
            "DEBOUNCED",
            "Index",
            "The debounced inputs; filter counter `k` belongs to the `k`-th",
            "",
            &debounced,
        );
    }

    /// `OUTPUTS`: safe levels, initial levels and state maps.
    fn output_specs(&mut self) {
        let pools = self.pools;
        let mut doc = String::new();
        for (o, out) in pools.outputs.iter().enumerate() {
            let index = o as ex::Index;
            let drive = if out.state_map.is_empty() {
                let mut how = format!("latched, initially {}", u8::from(out.initial));
                let set = self.events_doing(ex::Action::Set(index));
                let clear = self.events_doing(ex::Action::Clear(index));
                if !set.is_empty() {
                    let _ = write!(how, "; set by {}", listed(&set, "and"));
                }
                if !clear.is_empty() {
                    let _ = write!(how, "; cleared by {}", listed(&clear, "and"));
                }
                how
            } else {
                format!("1 while {}", self.state_map_text(out.state_map))
            };
            let name = self.output_name(index);
            let safe = u8::from(out.safe);
            let _ = writeln!(doc, "/// - {o} {name} (safe {safe}): {drive}");
        }
        let outputs: Vec<String> = pools
            .outputs
            .iter()
            .map(|o| {
                format!(
                    "OutputSpec {{ safe: {}, initial: {}, state_map: {} }}",
                    o.safe,
                    o.initial,
                    self.span(o.state_map)
                )
            })
            .collect();
        self.pool(
            "OUTPUTS",
            "OutputSpec",
            "Outputs, by output (level in fault mode, and how each is driven)",
            &doc,
            &outputs,
        );
    }

    /// `TIMERS`: presets and the events each expiry raises.
    fn timer_specs(&mut self) {
        let pools = self.pools;
        let mut doc = String::new();
        for (t, timer) in pools.timers.iter().enumerate() {
            let index = t as ex::Index;
            let mut about = format!("{} ms", timer.preset_ms);
            let started = self.events_doing(ex::Action::Start(index));
            let reset = self.events_doing(ex::Action::Reset(index));
            let expiry: Vec<String> = (0..pools.events.len())
                .filter(|&e| pools.events[e].trigger == ex::Trigger::Expired(index))
                .map(|e| self.event_name(e))
                .collect();
            if !started.is_empty() {
                let _ = write!(about, ", started by {}", listed(&started, "and"));
            }
            if !reset.is_empty() {
                let _ = write!(about, ", reset by {}", listed(&reset, "and"));
            }
            if !expiry.is_empty() {
                let _ = write!(about, ", expiry raises {}", listed(&expiry, "and"));
            }
            let _ = writeln!(doc, "/// - {t} {}: {about}", self.timer_name(index));
        }
        let timers: Vec<String> = pools
            .timers
            .iter()
            .map(|t| {
                format!(
                    "TimerSpec {{ preset_ms: {}, raises: {} }}",
                    t.preset_ms,
                    self.span(t.raises)
                )
            })
            .collect();
        self.pool(
            "TIMERS",
            "TimerSpec",
            "Timer presets, by timer",
            &doc,
            &timers,
        );
    }

    /// `EVENTS`: triggers, conditions, requests, actions and memberships.
    fn event_specs(&mut self) {
        let pools = self.pools;
        let mut doc = String::new();
        for e in 0..pools.events.len() {
            let _ = writeln!(doc, "/// - {e} {}", self.event_text(e));
        }
        let events: Vec<String> = pools
            .events
            .iter()
            .map(|e| {
                let trigger = match e.trigger {
                    ex::Trigger::Command => "Trigger::Command".to_owned(),
                    ex::Trigger::Rising(s) => format!("Trigger::Rising({})", self.span(s)),
                    ex::Trigger::Falling(s) => format!("Trigger::Falling({})", self.span(s)),
                    ex::Trigger::Expired(t) => format!("Trigger::Expired({})", self.timer(t)),
                };
                let request = e
                    .request
                    .map_or("None".to_owned(), |r| format!("Some({})", self.input(r)));
                format!(
                    "EventSpec {{ trigger: {trigger}, when: {}, unless: {}, request: {request}, actions: {}, members: {} }}",
                    self.span(e.when),
                    self.span(e.unless),
                    self.span(e.actions),
                    self.span(e.members)
                )
            })
            .collect();
        self.pool(
            "EVENTS",
            "EventSpec",
            "Events in priority order (trigger and conditions; actions; supervisors, with the event's local index)",
            &doc,
            &events,
        );
    }

    /// `SUPERVISORS`: sizes, initial states, alphabets and the events
    /// outside them.
    fn supervisor_specs(&mut self) {
        let pools = self.pools;
        let mut doc = String::new();
        for (j, s) in pools.supervisors.iter().enumerate() {
            let index = j as ex::Index;
            let _ = writeln!(
                doc,
                "/// - {j} {}: {} states, initial {}",
                self.supervisor_name(index),
                s.states,
                self.state_name(index, s.initial)
            );
        }
        let sups: Vec<String> = pools
            .supervisors
            .iter()
            .map(|s| {
                let allowed = if s.allowed.is_stored() {
                    format!(
                        "AllowedSets {{ index: {}, bits: {} }}",
                        self.span(s.allowed.index),
                        s.allowed.bits
                    )
                } else {
                    "AllowedSets::COMPUTED".to_owned()
                };
                format!(
                    "SupervisorSpec {{ states: {}, initial: {}, alphabet: {}, outside: {}, allowed: {allowed}, contiguous: {} }}",
                    s.states,
                    s.initial,
                    self.span(s.alphabet),
                    self.span(s.outside),
                    s.contiguous
                )
            })
            .collect();
        self.pool(
            "SUPERVISORS",
            "SupervisorSpec",
            "Supervisor sizes, initial states, alphabets (`EVENT_LISTS`, in local order), the events outside them (`EVENT_MASKS`) and their allowed sets (stored: `ALLOWED_INDEX`), and whether an alphabet is consecutive event numbers (`contiguous`), by supervisor",
            &doc,
            &sups,
        );
    }

    /// `INPUT_MASKS`: edge bindings, `when`/`unless` conditions and the
    /// debounced inputs, each word named by its inputs.
    fn input_masks(&mut self) {
        let pools = self.pools;
        let mut spans = vec![(pools.debounce_mask, "the debounced inputs".to_owned())];
        for (e, spec) in pools.events.iter().enumerate() {
            let name = self.event_name(e);
            if let ex::Trigger::Rising(s) | ex::Trigger::Falling(s) = spec.trigger {
                spans.push((s, format!("edge of {name}")));
            }
            spans.push((spec.when, format!("`when` of {name}")));
            spans.push((spec.unless, format!("`unless` of {name}")));
        }
        let doc = self.owners(spans);
        let iw = ex::words(pools.inputs.len()).max(1);
        let masks: Vec<String> = pools
            .input_masks
            .iter()
            .enumerate()
            .map(|(at, &w)| self.mask_word_expr(at % iw, w))
            .collect();
        self.pool(
            "INPUT_MASKS",
            "u32",
            "Input masks of edge bindings, `when`/`unless` conditions and the debounced inputs, `INPUT_WORDS` words each, by position",
            &doc,
            &masks,
        );
    }

    /// `EVENT_LISTS`: what inputs' edges and timers' expiries raise, the
    /// alphabets, the commands with a request input.
    fn event_lists(&mut self) {
        let pools = self.pools;
        let mut spans = Vec::new();
        for (i, input) in pools.inputs.iter().enumerate() {
            let name = self.input_name(i as ex::Index);
            spans.push((input.raises, format!("edges of {name}")));
        }
        for (t, timer) in pools.timers.iter().enumerate() {
            let name = self.timer_name(t as ex::Index);
            spans.push((timer.raises, format!("expiry of {name}")));
        }
        for (j, sup) in pools.supervisors.iter().enumerate() {
            let name = self.supervisor_name(j as ex::Index);
            spans.push((sup.alphabet, format!("alphabet of {name}")));
        }
        let requested = "the commands with a request input".to_owned();
        spans.push((pools.requested, requested));
        let doc = self.owners(spans);
        let events = &self.project.events;
        let lists: Vec<String> = pools
            .event_lists
            .iter()
            .map(|&e| format!("event::{}", ident(&events[usize::from(e)].name)))
            .collect();
        self.pool(
            "EVENT_LISTS",
            "Index",
            "Event lists: what an input's edges or a timer's expiry can raise, each supervisor's alphabet, the commands with a request input, by position",
            &doc,
            &lists,
        );
    }

    /// `EVENT_MASKS`: what each supervisor never blocks, the commands
    /// without a request input.
    fn event_masks(&mut self) {
        let pools = self.pools;
        let mut spans = Vec::new();
        for (j, sup) in pools.supervisors.iter().enumerate() {
            let name = self.supervisor_name(j as ex::Index);
            spans.push((sup.outside, format!("outside the alphabet of {name}")));
        }
        let commands = "the commands without a request input".to_owned();
        spans.push((pools.commands, commands));
        let ew = ex::words(pools.events.len()).max(1);
        for j in 0..pools.supervisors.len() {
            let name = self.supervisor_name(j as ex::Index);
            let mut sets = stored_sets(pools, j);
            sets.sort_unstable();
            sets.dedup();
            for k in sets {
                let at = ex::Span::new((k * ew) as ex::Index, ew as ex::Index);
                spans.push((at, format!("allowed by {name}")));
            }
        }
        let doc = self.owners(spans);
        let masks: Vec<String> = pools
            .event_masks
            .iter()
            .enumerate()
            .map(|(at, &w)| self.event_word_expr(at % ew, w))
            .collect();
        self.pool(
            "EVENT_MASKS",
            "u32",
            "Event sets, `EVENT_WORDS` words each: what each supervisor never blocks, the commands without a request input, the allowed sets a supervisor stores (`ALLOWED_INDEX`), by position",
            &doc,
            &masks,
        );
    }

    /// `ACTIONS`, each event's run named by the event.
    fn actions(&mut self) {
        let pools = self.pools;
        let spans = (0..pools.events.len())
            .map(|e| (pools.events[e].actions, self.event_name(e)))
            .collect();
        let doc = self.owners(spans);
        let actions: Vec<String> = pools
            .actions
            .iter()
            .map(|a| match *a {
                ex::Action::Set(o) => format!("Action::Set({})", self.output(o)),
                ex::Action::Clear(o) => format!("Action::Clear({})", self.output(o)),
                ex::Action::Start(t) => format!("Action::Start({})", self.timer(t)),
                ex::Action::Reset(t) => format!("Action::Reset({})", self.timer(t)),
            })
            .collect();
        self.pool(
            "ACTIONS",
            "Action",
            "Event actions, by position",
            &doc,
            &actions,
        );
    }

    /// `MEMBERSHIPS`: which supervisors have each event, and its local
    /// index there.
    fn memberships(&mut self) {
        let pools = self.pools;
        let spans = (0..pools.events.len())
            .map(|e| (pools.events[e].members, self.event_name(e)))
            .collect();
        let doc = self.owners(spans);
        let members: Vec<String> = pools
            .memberships
            .iter()
            .map(|m| {
                let supervisor = self.supervisor(m.supervisor);
                format!(
                    "Membership {{ supervisor: {supervisor}, local: {} }}",
                    m.local
                )
            })
            .collect();
        self.pool(
            "MEMBERSHIPS",
            "Membership",
            "Which supervisors have each event, and its local index there, by position",
            &doc,
            &members,
        );
    }

    /// `STATE_MAP`: the Moore outputs' supervisor states and place counts.
    fn state_map(&mut self) {
        let pools = self.pools;
        let spans = (0..pools.outputs.len())
            .map(|o| (pools.outputs[o].state_map, self.output_name(o as ex::Index)))
            .collect();
        let doc = self.owners(spans);
        let map: Vec<String> = pools
            .state_map
            .iter()
            .map(|m| {
                let supervisor = self.supervisor(m.supervisor);
                if m.mask == u32::MAX {
                    format!("StateMapEntry::in_state({supervisor}, {})", m.state)
                } else {
                    let count = m.state >> m.mask.trailing_zeros().min(31);
                    format!(
                        "StateMapEntry::marked({supervisor}, {:#x}, {count})",
                        m.mask
                    )
                }
            })
            .collect();
        let title = if self.project.nets.is_empty() {
            "Moore outputs: (supervisor, state) pairs, by position"
        } else {
            "Moore outputs: a supervisor's state, or a count of tokens in a net's place (its counter's mask), by position"
        };
        self.pool("STATE_MAP", "StateMapEntry", title, &doc, &map);
    }

    /// `CONFIG`, `CONFIG_CRC`, `EVENT_WORDS` and `Memory`.
    fn config_and_memory(&mut self) {
        let pools = self.pools;
        let policy = match pools.unexpected {
            ex::UnexpectedPolicy::Fault => "Fault",
            ex::UnexpectedPolicy::Ignore => "Ignore",
        };
        let reset = pools
            .reset
            .map_or("None".to_owned(), |r| format!("Some({})", self.input(r)));
        let guards = if pools.guards.is_empty() && pools.state_bits.is_empty() {
            "Guards::NONE"
        } else {
            "Guards { events: &GUARDS, bits: &STATE_BITS, nodes: &GUARD_NODES }"
        };
        let allowed_index = if pools.allowed_index.is_empty() {
            "&[]"
        } else {
            "&ALLOWED_INDEX"
        };
        let _ = writeln!(
            self.out,
            "/// The executor's description of the project.\n#[allow(dead_code)]\npub const CONFIG: Config<'static> = Config {{ name: {:?}, scan_period_ms: {}, max_commands_per_scan: {}, unexpected: UnexpectedPolicy::{policy}, reset: {reset}, overrun_limit: {}, overrun_fault: {}, lost_edge_fault: {}, rom_test_bytes_per_scan: {}, inputs: &INPUTS, debounced: &DEBOUNCED, debounce_mask: {}, outputs: &OUTPUTS, timers: &TIMERS, events: &EVENTS, supervisors: &SUPERVISORS, input_masks: &INPUT_MASKS, event_lists: &EVENT_LISTS, event_masks: &EVENT_MASKS, commands: {}, requested: {}, actions: &ACTIONS, memberships: &MEMBERSHIPS, state_map: &STATE_MAP, guards: {guards}, allowed_index: {allowed_index} }};",
            pools.name,
            pools.scan_period_ms,
            pools.max_commands_per_scan,
            pools.overrun_limit,
            pools.overrun_fault,
            pools.lost_edge_fault,
            pools.rom_test_bytes_per_scan,
            self.span(pools.debounce_mask),
            self.span(pools.commands),
            self.span(pools.requested),
        );
        let _ = writeln!(
            self.out,
            "/// CRC of the configuration alone (the program image without tables): how recorded\n/// scenarios name the project they belong to.\n#[allow(dead_code)]\npub const CONFIG_CRC: u32 = {:#010x};",
            executor::image::config_crc(&pools.config())
        );
        let _ = writeln!(
            self.out,
            "/// Words of an event set (32 events per word).\n#[allow(dead_code)]\npub const EVENT_WORDS: usize = executor::program::words(event::COUNT);\n/// Controller memory sized for this project: the input image in `INPUT_WORDS` words, a filter counter per debounced input, the outputs, timers, supervisor states and events, event sets in `EVENT_WORDS` words, and one event set per supervisor.\n#[allow(dead_code)]\npub type Memory = executor::memory::StaticMemory<INPUT_WORDS, {{ DEBOUNCED.len() }}, {{ output::COUNT }}, {{ timer::COUNT }}, {{ supervisor::COUNT }}, {{ event::COUNT }}, EVENT_WORDS, {{ supervisor::COUNT * EVENT_WORDS }}>;"
        );
    }
}

/// `text` cut to at most `limit` characters, with `…` when cut.
fn abbreviated(text: &str, limit: usize) -> String {
    match text.char_indices().nth(limit) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_owned(),
    }
}

/// States whose set numbers the doc of `ALLOWED_INDEX` lists, per
/// supervisor.
const STATES_LISTED: usize = 8;

/// Supervisor `j`'s stored set number in each state (empty when its sets
/// are computed).
fn stored_sets(pools: &ConfigPools, j: usize) -> Vec<usize> {
    let (config, sup) = (pools.config(), &pools.supervisors[j]);
    (0..sup.states)
        .map_while(|x| config.stored_set(sup, x))
        .collect()
}

/// Words of a record of the executor's type `ty`.
fn record_words(ty: &str) -> usize {
    match ty {
        "InputSpec" | "OutputSpec" | "TimerSpec" | "GuardNode" => 2,
        "EventSpec" => 7,
        "SupervisorSpec" => 6,
        "StateMapEntry" | "GuardSpec" => 3,
        "StateBit" => 1,
        _ => unreachable!("no record type {ty}"),
    }
}

#[cfg(test)]
mod tests {
    use crate::backend::Backend;
    use crate::emit::generate;
    use plc_project as project;
    use std::path::Path;

    /// The doc comment lines of the generated table program of `text`
    /// (a project file in `models/`, so that its model paths resolve).
    fn docs(text: &str) -> Vec<String> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models/decode_test.plc.toml");
        let project = project::from_str(text, &path).unwrap();
        let code = generate(&project, Backend::Table, "test").unwrap().code;
        code.lines()
            .map(str::trim)
            .filter(|l| l.starts_with("///"))
            .map(str::to_owned)
            .collect()
    }

    fn has(docs: &[String], line: &str) {
        assert!(
            docs.iter().any(|d| d == line),
            "missing `{line}` in\n{}",
            docs.join("\n")
        );
    }

    /// Every pool-indexed field decoded by name: bindings over several
    /// inputs, `when`/`unless`, requests, actions of every kind, several
    /// supervisors, state maps and the owners of pool positions.
    #[test]
    fn the_configuration_is_decoded_by_name() {
        let docs = docs(
            r#"
[plc]
name = "decode"
reset = "rst"

[inputs]
a = { debounce_scans = 3 }
b = {}
c = {}
d = {}
go = {}
rst = {}

[outputs]
lamp = { states = { sup_crane1 = ["train1", "train2"], sup_section = ["t1_in"] } }
valve = { initial = true, safe = true }

[timers]
t = { preset_ms = 500 }

[events]
t1_at13 = { rising = "a", when = ["b", "c"], unless = ["go"], origin = "operator" }
t2_at13 = { falling = ["a", "b"], reset = ["t"] }
f_ld1 = { expired = "t" }
t1_at14 = { rising = "c" }
t2_at14 = { rising = "b" }
st_ld1 = { controllable = true, request = "go", set = ["valve"], start = ["t"] }
run_t1 = { controllable = true, clear = ["valve"] }
run_t2 = { controllable = true }
spare = { rising = "d" }

[[supervisor]]
name = "sup_crane1"
file = "crane/sup_crane1.toml"

[[supervisor]]
name = "sup_section"
file = "crane/sup_section.toml"
"#,
        );
        for line in [
            // INPUTS, OUTPUTS, TIMERS
            "/// - 0 `a`: debounced over 3 scans; its edges can raise `t1_at13` and `t2_at13`",
            "/// - 1 `b`: unfiltered; its edges can raise `t2_at13` and `t2_at14`",
            "/// - 4 `go`: unfiltered",
            "/// - 0 `lamp` (safe 0): 1 while `sup_crane1` is in `train1` or `train2`, or `sup_section` is in `t1_in`",
            "/// - 1 `valve` (safe 1): latched, initially 1; set by `st_ld1`; cleared by `run_t1`",
            "/// - 0 `t`: 500 ms, started by `st_ld1`, reset by `t2_at13`, expiry raises `f_ld1`",
            // EVENTS
            "/// - 0 `t1_at13` (uncontrollable, operator): rising edge of `a` when `b` and `c` unless `go`; in `sup_crane1` (local 0)",
            "/// - 1 `t2_at13` (uncontrollable, plant): falling edge of (`a` or `b`); resets `t`; in `sup_crane1` (local 1)",
            "/// - 2 `f_ld1` (uncontrollable, plant): expiry of `t`; in `sup_crane1` (local 2)",
            "/// - 5 `st_ld1` (controllable): commanded, only while `go` is 1; sets `valve`, starts `t`; in `sup_crane1` (local 3)",
            "/// - 6 `run_t1` (controllable): commanded; clears `valve`; in `sup_crane1` (local 4), `sup_section` (local 2)",
            "/// - 8 `spare` (uncontrollable, plant): rising edge of `d`; in no supervisor",
            // SUPERVISORS
            "/// - 0 `sup_crane1`: 3 states, initial `idle`",
            // INPUT_MASKS: one word each, equal masks stored once
            "/// - 0: the debounced inputs, edge of `t1_at13`",
            "/// - 1: `when` of `t1_at13`",
            "/// - 2: `unless` of `t1_at13`",
            "/// - 3: edge of `t2_at13`",
            "/// - 6: edge of `spare`",
            // RAISED
            "/// - 0–1: edges of `a`",
            "/// - 2–3: edges of `b`",
            "/// - 6: expiry of `t`",
            // ACTIONS
            "/// - 0: `t2_at13`",
            "/// - 1–2: `st_ld1`",
            "/// - 3: `run_t1`",
            // MEMBERSHIPS
            "/// - 6–7: `run_t1`",
            "/// - 8–9: `run_t2`",
            // STATE_MAP
            "/// - 0–2: `lamp`",
        ] {
            has(&docs, line);
        }
    }
}
