//! Forward and backward reachability, event by event (chaining: states
//! found on one event are expanded on the next in the same sweep).

use crate::relation::Model;
use biodivine_lib_bdd::Bdd;

/// Which way to search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Successors.
    Forward,
    /// Predecessors.
    Backward,
}

/// The states reached from `start` in direction `dir` through states of
/// `within` only, on the events for which `use_event` holds. `start` is
/// intersected with `within` first.
pub fn search(
    model: &Model,
    start: &Bdd,
    within: &Bdd,
    dir: Direction,
    use_event: impl Fn(usize) -> bool,
) -> Bdd {
    // Chaining in variable order: an event's states, once found, feed the
    // events whose components lie next to its own in the same sweep.
    let layout = model.layout();
    let top = |e: usize| {
        layout.events[e]
            .participants
            .iter()
            .map(|&c| layout.components[c].offset)
            .min()
            .unwrap_or(usize::MAX)
    };
    let mut events: Vec<usize> = (0..model.relations.len())
        .filter(|&e| use_event(e))
        .collect();
    events.sort_by_key(|&e| top(e));
    let mut reached = start.and(within);
    // `within` minus `reached`, kept up to date: one conjunction per image.
    let mut open = within.and_not(&reached);
    let mut frontier = reached.clone();
    while !frontier.is_false() {
        let mut found = model.mk_false();
        for &e in &events {
            let step = match dir {
                Direction::Forward => model.post(&frontier, e),
                Direction::Backward => model.pre(&frontier, e),
            };
            let new = step.and(&open);
            if !new.is_false() {
                open = open.and_not(&new);
                reached = reached.or(&new);
                found = found.or(&new);
                frontier = frontier.or(&new);
            }
        }
        frontier = found;
    }
    reached
}

/// The states of plant ∥ specifications reachable from the initial state.
pub fn reachable(model: &Model) -> Bdd {
    search(
        model,
        model.initial(),
        &model.mk_true(),
        Direction::Forward,
        |_| true,
    )
}
