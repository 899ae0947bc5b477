//! How the simulator makes an uncontrollable event happen: the input
//! changes that give its edge, at the scans they are due.
//!
//! A rising edge of an OR of inputs needs the OR at 0 first: when some of
//! its inputs are 1, they go to 0 and stay there long enough to pass the
//! debounce filter, then the first one goes to 1; a falling edge is the
//! mirror image. `when` and `unless` conditions are not forced: moving
//! them would be edges of their own. They are reported instead
//! ([`unmet_conditions`]), and the event is still given its edge.

use plc_project::{Project, Trigger};

/// One input change, due before scan `at_scan`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Change {
    /// The scan (number, from 0) that first reads the new level.
    pub at_scan: u64,
    /// The input.
    pub input: usize,
    /// Its new raw level.
    pub value: bool,
}

/// Scans a level must hold to pass input `i`'s debounce filter.
fn hold(project: &Project, i: usize) -> u64 {
    u64::from(project.inputs[i].debounce_scans.max(1))
}

/// The changes that give event `e` its edge from the raw image `raw`,
/// starting with scan `now`; an error for an event no input change makes
/// (a command, a timer's expiry).
pub fn plan(project: &Project, e: usize, raw: &[bool], now: u64) -> Result<Vec<Change>, String> {
    let event = &project.events[e];
    let (list, rising) = match &event.trigger {
        Trigger::Rising(list) => (list, true),
        Trigger::Falling(list) => (list, false),
        Trigger::Expired(t) => {
            return Err(format!(
                "`{}` happens when timer `{}` expires",
                event.name, project.timers[*t].name
            ))
        }
        Trigger::Command => {
            return Err(format!(
                "`{}` is a command: the controller chooses it",
                event.name
            ))
        }
    };
    let first = list[0];
    let hold = list.iter().map(|&i| hold(project, i)).max().unwrap_or(1);
    let change = |at_scan, input, value| Change {
        at_scan,
        input,
        value,
    };
    let any_high = list.iter().any(|&i| raw[i]);
    Ok(match (rising, any_high) {
        // The OR is at 0: one input up gives the edge.
        (true, false) => vec![change(now, first, true)],
        // The OR is at 1: all down first, then one up.
        (true, true) => {
            let mut changes: Vec<Change> = list
                .iter()
                .filter(|&&i| raw[i])
                .map(|&i| change(now, i, false))
                .collect();
            changes.push(change(now + hold, first, true));
            changes
        }
        // The OR is at 1: every input that is up goes down.
        (false, true) => list
            .iter()
            .filter(|&&i| raw[i])
            .map(|&i| change(now, i, false))
            .collect(),
        // The OR is at 0: one up first, then down again.
        (false, false) => vec![change(now, first, true), change(now + hold, first, false)],
    })
}

/// The most scans a planned event may take to show in the executor: its
/// plan's last change, then the debounce filter, and a margin of two.
pub fn patience(project: &Project, changes: &[Change], now: u64) -> u64 {
    let last = changes.iter().map(|c| c.at_scan).max().unwrap_or(now);
    let hold = changes
        .iter()
        .map(|c| hold(project, c.input))
        .max()
        .unwrap_or(1);
    last - now + hold + 2
}

/// The `when` inputs at 0 and `unless` inputs at 1 that keep event `e`
/// from occurring with the raw image `raw`, as `top_ls = 1, stop = 0`;
/// `None` when its conditions hold.
pub fn unmet_conditions(project: &Project, e: usize, raw: &[bool]) -> Option<String> {
    let event = &project.events[e];
    let unmet: Vec<String> = event
        .when
        .iter()
        .filter(|&&i| !raw[i])
        .map(|&i| format!("{} = 1", project.inputs[i].name))
        .chain(
            event
                .unless
                .iter()
                .filter(|&&i| raw[i])
                .map(|&i| format!("{} = 0", project.inputs[i].name)),
        )
        .collect();
    (!unmet.is_empty()).then(|| unmet.join(", "))
}

/// Whether an operator's button `input` goes back to 0 once its event is
/// seen: no event watches its falling edge, so releasing it is silent.
pub fn releases(project: &Project, input: usize) -> bool {
    !project
        .events
        .iter()
        .any(|e| matches!(&e.trigger, Trigger::Falling(list) if list.contains(&input)))
}
