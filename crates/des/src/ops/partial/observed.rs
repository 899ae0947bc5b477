//! The supervisor a controller runs when it sees only the observable
//! events: the projection of the closed loop onto them, and the two
//! checks that make it safe to run.
//!
//! A PLC detects an event by an input edge or issues it as a command; an
//! unobservable event (a breakdown with no sensor, a silent internal step)
//! happens in the plant without the controller knowing. The controller can
//! then only run P(K): the deterministic projection of the closed loop K
//! onto the observable events, whose state is the set of closed-loop
//! states consistent with what it has seen ([`observed_supervisor`]). That
//! is right only when
//!
//! 1. the plant under P(K) does what K does: L(G) ∩ P⁻¹(P(K̄)) = K̄ and the
//!    same for the marked languages (K normal, which
//!    [`sup_con_normal`](super::sup_con_normal) gives), and
//! 2. every command P(K) allows in a state can be carried out from every
//!    closed-loop state that state stands for: a command that is
//!    possible in one of them only would be issued to a plant that may be
//!    in the other (a repair commanded to a machine that may not be
//!    broken).
//!
//! [`check_observed`] decides both, with a shortest string that breaks
//! them. Controllable events must be observable: a controller sees every
//! command it issues itself.

use crate::automaton::{Automaton, EventId, StateId};
use crate::error::{Error, Result};
use crate::ops::projection::project;
use crate::ops::reduce::closed_loop_difference;
use crate::ops::sync::ComposeOptions;
use rustc_hash::FxHashMap;

/// The observable events of `plant` by name; refused when a controllable
/// event is unobservable.
pub fn observable_events(plant: &Automaton) -> Result<Vec<String>> {
    let alphabet = plant.alphabet();
    if let Some((_, e)) = alphabet.unobservable().find(|(_, e)| e.controllable) {
        return Err(Error::Incompatible(format!(
            "event `{}` is controllable and unobservable: a controller sees every command it \
             issues, so a controllable event must be observable",
            e.name
        )));
    }
    Ok(alphabet
        .iter()
        .filter(|&(id, _)| alphabet.is_observable(id))
        .map(|(_, e)| e.name.clone())
        .collect())
}

/// The supervisor a controller that sees only `plant`'s observable events
/// runs for the closed loop `closed_loop` (a sublanguage of the plant over
/// its alphabet, such as supconnorm's result): its projection onto those
/// events, states named after the closed-loop states they stand for
/// (`{3,5}`), checked by [`check_observed`].
pub fn observed_supervisor(
    plant: &Automaton,
    closed_loop: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<Automaton> {
    let observable = observable_events(plant)?;
    let mut observed = project(closed_loop, &observable, options.max_states)?;
    observed.set_name(closed_loop.name());
    check_observed(plant, closed_loop, &observed, options)?;
    Ok(observed)
}

/// Checks that `observed`, a supervisor over `plant`'s observable events,
/// gives `plant` the closed and marked languages of `closed_loop`, and
/// that every controllable event it allows after an observed string is
/// possible in the closed loop after every string with that projection
/// (see the module docs); an error with a shortest string otherwise.
pub fn check_observed(
    plant: &Automaton,
    closed_loop: &Automaton,
    observed: &Automaton,
    options: ComposeOptions<'_>,
) -> Result<()> {
    let unseen = unobservable_names(plant);
    if let Some(d) = closed_loop_difference(plant, closed_loop, &[observed], options)? {
        let (with, without) = if d.in_first {
            (
                "the supervisor",
                "the controller that sees only the observable events",
            )
        } else {
            (
                "the controller that sees only the observable events",
                "the supervisor",
            )
        };
        return Err(Error::Incompatible(format!(
            "the plant `{}` does `{}` ({:?} language) with {with} and not with {without}: the \
             supervisor is not normal with respect to the events {unseen}, which the \
             controller cannot see (synthesise it with supconnorm)",
            plant.name(),
            d.string.join(" "),
            d.language,
        )));
    }
    if let Some((string, command)) = infeasible_command(closed_loop, observed) {
        return Err(Error::Incompatible(format!(
            "after `{}` the controller, which cannot see {unseen}, would command \
             `{command}`: the closed loop allows it after a string that looks the same, not \
             after this one (the plant may be unable to do it); a controller that sees \
             {unseen} could run this supervisor",
            string.join(" "),
        )));
    }
    Ok(())
}

/// Names each state of `observed` (a supervisor over some of `reference`'s
/// events) after the states of `reference` that the strings leading to it
/// may leave `reference` in: `{working.one,down.one}`, a state of
/// `reference` alone without braces. Used with `reference` the plant
/// composed with the specification, a projected supervisor's states say
/// what the controller knows. Two states that would get one name keep
/// them apart with `#1`, `#2`, … in state order. States no string
/// reaches in `reference` keep their index.
pub fn name_after(reference: &Automaton, observed: &mut Automaton) {
    let (Some(r0), Some(y0)) = (reference.initial(), observed.initial()) else {
        return;
    };
    let seen: Vec<Option<EventId>> = reference
        .alphabet()
        .iter()
        .map(|(_, e)| observed.alphabet().id(&e.name))
        .collect();
    let mut members: Vec<Vec<StateId>> = vec![Vec::new(); observed.num_states()];
    let mut visited: rustc_hash::FxHashSet<(StateId, StateId)> = Default::default();
    let mut stack = vec![(r0, y0)];
    visited.insert((r0, y0));
    while let Some((r, y)) = stack.pop() {
        members[y.index()].push(r);
        for t in reference.transitions(r) {
            let next_y = match seen[t.event.index()] {
                Some(e) => match observed.successor(y, e) {
                    Some(next) => next,
                    None => continue,
                },
                None => y,
            };
            if visited.insert((t.target, next_y)) {
                stack.push((t.target, next_y));
            }
        }
    }
    let mut names: Vec<String> = members
        .iter_mut()
        .enumerate()
        .map(|(y, rs)| {
            rs.sort_unstable();
            match rs.as_slice() {
                [] => y.to_string(),
                [one] => reference.state_name(*one).into_owned(),
                many => {
                    let inner: Vec<String> = many
                        .iter()
                        .map(|&r| reference.state_name(r).into_owned())
                        .collect();
                    format!("{{{}}}", inner.join(","))
                }
            }
        })
        .collect();
    let mut count: FxHashMap<String, u32> = FxHashMap::default();
    for n in &names {
        *count.entry(n.clone()).or_default() += 1;
    }
    let mut next: FxHashMap<String, u32> = FxHashMap::default();
    for n in &mut names {
        if count[n.as_str()] > 1 {
            let k = next.entry(n.clone()).or_default();
            *k += 1;
            n.push_str(&format!("#{k}"));
        }
    }
    observed.set_state_names(names);
}

/// `plant`'s unobservable events as a list for messages (`` `a`, `b` ``).
pub(crate) fn unobservable_names(plant: &Automaton) -> String {
    let names: Vec<String> = plant
        .alphabet()
        .unobservable()
        .map(|(_, e)| format!("`{}`", e.name))
        .collect();
    names.join(", ")
}

/// A shortest string of `closed_loop` after which `observed` allows a
/// controllable event that `closed_loop` does not, with that event.
fn infeasible_command(
    closed_loop: &Automaton,
    observed: &Automaton,
) -> Option<(Vec<String>, String)> {
    let (Some(x0), Some(y0)) = (closed_loop.initial(), observed.initial()) else {
        return None;
    };
    let k = closed_loop.alphabet();
    // Per event of the closed loop, its id in the observed supervisor.
    let seen: Vec<Option<EventId>> = k
        .iter()
        .map(|(_, e)| observed.alphabet().id(&e.name))
        .collect();
    let commands: Vec<(EventId, EventId)> = observed
        .alphabet()
        .iter()
        .filter(|(_, e)| e.controllable)
        .filter_map(|(id, e)| Some((id, k.id(&e.name)?)))
        .collect();
    let mut index: FxHashMap<(StateId, StateId), u32> = FxHashMap::default();
    let mut pairs = vec![(x0, y0)];
    let mut parent: Vec<(u32, EventId)> = vec![(u32::MAX, EventId(0))];
    index.insert((x0, y0), 0);
    let mut i = 0;
    while i < pairs.len() {
        let (x, y) = pairs[i];
        for &(oe, ke) in &commands {
            if observed.successor(y, oe).is_some() && closed_loop.successor(x, ke).is_none() {
                let mut string = Vec::new();
                let mut j = i;
                while parent[j].0 != u32::MAX {
                    string.push(k.name(parent[j].1).to_owned());
                    j = parent[j].0 as usize;
                }
                string.reverse();
                return Some((string, k.name(ke).to_owned()));
            }
        }
        for t in closed_loop.transitions(x) {
            let next_y = match seen[t.event.index()] {
                Some(oe) => match observed.successor(y, oe) {
                    Some(next) => next,
                    // Not a string of the projection: the language check
                    // reports it.
                    None => continue,
                },
                None => y,
            };
            if let std::collections::hash_map::Entry::Vacant(v) = index.entry((t.target, next_y)) {
                v.insert(pairs.len() as u32);
                pairs.push((t.target, next_y));
                parent.push((i as u32, t.event));
            }
        }
        i += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::partial::sup_con_normal;
    use crate::ops::sync::DEFAULT_MAX_STATES;
    use crate::testing::auto;

    fn options() -> ComposeOptions<'static> {
        ComposeOptions {
            max_states: DEFAULT_MAX_STATES,
            ..ComposeOptions::default()
        }
    }

    /// A machine (idle in `0`) that starts (`s`, controllable), finishes (`f`) or breaks
    /// down (`b`) and is repaired (`r`, controllable when `repair_cmd`).
    fn machine(repair_cmd: bool) -> Automaton {
        let mut m = auto(
            "M",
            &[("s", true), ("f", false), ("b", false), ("r", repair_cmd)],
            &[
                ("0", "s", "work"),
                ("work", "f", "0"),
                ("work", "b", "down"),
                ("down", "r", "0"),
            ],
            &["0"],
        );
        assert!(m.set_unobservable("b"));
        m
    }

    #[test]
    fn a_silent_breakdown_is_merged_into_the_working_state() {
        let m = machine(false);
        let observed = observed_supervisor(&m, &m, options()).unwrap();
        // {idle} -s-> {work,down} -f,r-> {idle}; `b` is gone.
        assert_eq!(observed.num_states(), 2);
        assert!(!observed.alphabet().contains("b"));
        assert_eq!(observed.num_transitions(), 3);
        let work = observed.successor(StateId(0), observed.alphabet().id("s").unwrap());
        assert_eq!(observed.state_name(work.unwrap()), "{work,down}");
    }

    #[test]
    fn a_command_possible_after_an_unseen_event_only_is_refused() {
        // The repair is commanded: after `s` the machine may be down (repair
        // it) or working (it cannot be repaired).
        let m = machine(true);
        let e = observed_supervisor(&m, &m, options())
            .unwrap_err()
            .to_string();
        assert!(e.contains("after `s`"), "{e}");
        assert!(e.contains("would command `r`"), "{e}");
        assert!(e.contains("`b`"), "{e}");
    }

    #[test]
    fn a_supervisor_that_is_not_normal_is_refused_with_the_string() {
        // Two machines; the spec forbids starting M2 while M1 is down, which
        // only a controller that sees `b` can enforce exactly.
        let m1 = machine(false);
        let m2 = auto(
            "M2",
            &[("s2", true), ("f2", false)],
            &[("0", "s2", "work"), ("work", "f2", "0")],
            &["0"],
        );
        let plant = crate::ops::sync(&[&m1, &m2]).unwrap();
        let spec = auto(
            "zone",
            &[("b", false), ("r", false), ("s2", true)],
            &[("0", "b", "m1down"), ("m1down", "r", "0"), ("0", "s2", "0")],
            &["0", "m1down"],
        );
        let full = crate::ops::supcon(&plant, &spec).unwrap();
        let e = observed_supervisor(&plant, &full, options())
            .unwrap_err()
            .to_string();
        assert!(e.contains("is not normal"), "{e}");
        assert!(e.contains("s b s2") || e.contains("s s2"), "{e}");

        // supconnorm's result runs: `s2` waits until M1 is idle again.
        let observable = observable_events(&plant).unwrap();
        let k = sup_con_normal(&plant, &spec, &["s", "s2"], &observable, 1000).unwrap();
        let observed = observed_supervisor(&plant, &k, options()).unwrap();
        let s = observed.alphabet().id("s").unwrap();
        let s2 = observed.alphabet().id("s2").unwrap();
        let init = observed.initial().unwrap();
        assert!(observed.successor(init, s2).is_some());
        let m1_started = observed.successor(init, s).unwrap();
        assert!(observed.successor(m1_started, s2).is_none());
    }

    #[test]
    fn a_controllable_unobservable_event_is_refused() {
        let mut m = machine(false);
        assert!(m.set_unobservable("s"));
        let e = observable_events(&m).unwrap_err().to_string();
        assert!(e.contains("`s` is controllable and unobservable"), "{e}");
    }
}
