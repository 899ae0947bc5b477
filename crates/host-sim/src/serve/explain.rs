//! Why a command may or may not run now: which supervisor disables it,
//! and in which state (an automaton without the event there, a guard that
//! does not hold, a net place short of tokens).

use codegen::lower::{NetLayout, Supervisors};
use des::automaton::StateId;

/// A supervisor that disables an event, and why.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Disabler {
    /// The supervisor (an automaton, a symbolic supervisor, a net).
    pub supervisor: String,
    /// Why, in its terms.
    pub why: String,
}

/// The longest guard text quoted in a reason.
const GUARD_TEXT: usize = 160;

/// Every supervisor that disables event `e` when the executor's
/// supervisors are in `states` (empty when the event is feasible).
pub fn disablers(
    supervisors: &Supervisors<'_>,
    nets: &[NetLayout],
    e: usize,
    states: &[u32],
) -> Vec<Disabler> {
    let project = supervisors.project();
    let name = &project.events[e].name;
    let mut out = Vec::new();
    for (j, sup) in project.supervisors.iter().enumerate() {
        let Some((_, id)) = sup.local(e) else {
            continue;
        };
        let x = states.get(j).copied().unwrap_or(u32::MAX);
        let a = &sup.automaton;
        if (x as usize) >= a.num_states() || a.successor(StateId(x), id).is_none() {
            out.push(Disabler {
                supervisor: sup.name.clone(),
                why: format!("no `{name}` in state `{}`", supervisors.state_name(j, x)),
            });
        }
    }
    for g in &project.guarded {
        if !g.allows(e, states) {
            let text = g
                .guards
                .iter()
                .find(|guard| guard.event == e)
                .map_or(String::new(), |guard| shorten(&guard.text));
            out.push(Disabler {
                supervisor: g.name.clone(),
                why: format!("guard of `{name}` is false: {text}"),
            });
        }
    }
    for (n, net) in project.nets.iter().enumerate() {
        let groups = states.get(supervisors.net_supervisors(n)).unwrap_or(&[]);
        if supervisors.net(n).event_enabled(e, groups) {
            continue;
        }
        let marking = nets[n].unpack(groups);
        let places = net.net.places();
        let control_from = places.len() - net.control_places;
        let short: Vec<String> = net
            .events
            .iter()
            .enumerate()
            .filter(|&(_, &ev)| ev == e)
            .flat_map(|(t, _)| net.net.transitions()[t].input.iter())
            .filter(|&&(p, w)| marking[p] < w)
            .map(|&(p, w)| {
                let kind = if p >= control_from {
                    "control place"
                } else {
                    "place"
                };
                format!("{kind} `{}` holds {} < {w}", places[p].id, marking[p])
            })
            .collect();
        out.push(Disabler {
            supervisor: net.name.clone(),
            why: if short.is_empty() {
                format!("no transition of `{name}` is enabled")
            } else {
                short.join(", ")
            },
        });
    }
    out
}

fn shorten(text: &str) -> String {
    if text.chars().count() <= GUARD_TEXT {
        text.to_owned()
    } else {
        let cut: String = text.chars().take(GUARD_TEXT).collect();
        format!("{cut}…")
    }
}
