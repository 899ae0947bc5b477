//! Comparing the three interpreters scan by scan, and control equivalence
//! of every scan against the source automata.

use crate::reference::{
    groups_of, initial_states, pack_marking, transition_of, unpack_marking, Record, Reference,
};
use codegen::lower::{LogicImage, TableImage};
use des::automaton::StateId;
use executor::memory::HeapMemory;
use executor::{Controller, Program};
use plc_project::Project;
use proptest::test_runner::TestCaseError;
use std::fmt::Debug;

/// Fails with scan, field and the three values unless they agree.
pub(crate) fn agree<T: PartialEq + Debug>(
    scan: usize,
    field: &str,
    reference: &T,
    table: &T,
    logic: &T,
) -> Result<(), TestCaseError> {
    if reference == table && reference == logic {
        return Ok(());
    }
    Err(TestCaseError::fail(format!(
        "scan {scan}, field `{field}`: reference = {reference:?}, table = {table:?}, logic = {logic:?}"
    )))
}

/// Compares one scan record of the three interpreters, field by field.
pub(crate) fn compare(
    scan: usize,
    r: &Record,
    t: &Record,
    l: &Record,
) -> Result<(), TestCaseError> {
    agree(scan, "scan", &r.scan, &t.scan, &l.scan)?;
    agree(scan, "time_ms", &r.time_ms, &t.time_ms, &l.time_ms)?;
    agree(scan, "executed", &r.executed, &t.executed, &l.executed)?;
    agree(
        scan,
        "unexpected",
        &r.unexpected,
        &t.unexpected,
        &l.unexpected,
    )?;
    agree(scan, "states", &r.states, &t.states, &l.states)?;
    agree(scan, "outputs", &r.outputs, &t.outputs, &l.outputs)?;
    agree(scan, "fault", &r.fault, &t.fault, &l.fault)
}

/// Control equivalence of one scan, against the source automata only:
/// replayed in order from the pre-scan state vector `before`, every
/// executed event must be defined, in the state vector it was executed in,
/// by every supervisor having it (Leduc–Wonham: only allowed commands are
/// issued), and the replay must end on the recorded state vector (no
/// supervisor moves otherwise).
pub(crate) fn check_control(
    project: &Project,
    scan: usize,
    before: &[u32],
    was_faulted: bool,
    record: &Record,
) -> Result<(), TestCaseError> {
    let outcome = if was_faulted {
        check_fault_scan(project, before, record)
    } else {
        replay(project, before, &record.executed).and_then(|x| {
            if x == record.states {
                Ok(())
            } else {
                Err(format!(
                    "states {:?} do not follow from {before:?} by the executed events {:?} (expected {x:?})",
                    record.states, record.executed
                ))
            }
        })
    };
    outcome.map_err(|why| TestCaseError::fail(format!("scan {scan}: {why}")))
}

/// A scan that starts in fault mode executes nothing and either keeps the
/// state vector or resets it.
pub(crate) fn check_fault_scan(
    project: &Project,
    before: &[u32],
    record: &Record,
) -> Result<(), String> {
    if !record.executed.is_empty() {
        return Err(format!("executed {:?} in fault mode", record.executed));
    }
    if record.states != before && record.states != initial_states(project) {
        return Err(format!(
            "states {before:?} -> {:?} in fault mode (neither kept nor reset)",
            record.states
        ));
    }
    Ok(())
}

/// The state vector after `executed` from `before`, moving along
/// [`des::Automaton::successor`]; an error names the first event some
/// supervisor having it does not allow.
pub(crate) fn replay(
    project: &Project,
    before: &[u32],
    executed: &[usize],
) -> Result<Vec<u32>, String> {
    let mut x = before.to_vec();
    for &e in executed {
        if let Some(g) = project.guarded.iter().find(|g| !g.allows(e, &x)) {
            return Err(format!(
                "executed event {e} while the guard of symbolic supervisor `{}` does not hold in {x:?}",
                g.name
            ));
        }
        for (j, sup) in project.supervisors.iter().enumerate() {
            let Some(&(_, id)) = sup.local_events.iter().find(|&&(g, _)| g == e) else {
                continue;
            };
            let next = sup.automaton.successor(StateId(x[j]), id).ok_or_else(|| {
                let kind = if project.events[e].controllable {
                    "controllable"
                } else {
                    "uncontrollable"
                };
                format!(
                    "executed {kind} event {e} is undefined in supervisor {j} at state {}",
                    x[j]
                )
            })?;
            x[j] = next.0;
        }
        let mut first = project.supervisors.len();
        for net in &project.nets {
            let groups = first..first + groups_of(net);
            first = groups.end;
            let Some(t) = transition_of(net, e) else {
                continue;
            };
            let marking = unpack_marking(net, &x[groups.clone()]);
            let next = net.net.fire(&marking, t).ok_or_else(|| {
                format!(
                    "executed event {e} is transition {t} of net `{}`, not enabled in {marking:?}",
                    net.name
                )
            })?;
            x.splice(groups, pack_marking(net, &next));
        }
    }
    Ok(x)
}

/// Runs `samples` (time, raw input image) through the reference and both
/// backends, comparing every scan and checking control equivalence.
pub(crate) fn check_run(
    project: &Project,
    samples: &[(u32, Vec<bool>)],
) -> Result<(), TestCaseError> {
    let table = TableImage::new(project).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let mut by_table = Controller::new(&table, HeapMemory::for_config(&table.config()))
        .map_err(|e| TestCaseError::fail(format!("table controller: {e:?}")))?;
    // Petri nets run on the table backend only: then its twin stands in
    // for the logic backend.
    let logic = if project.nets.is_empty() {
        Some(LogicImage::new(project).map_err(|e| TestCaseError::fail(e.to_string()))?)
    } else {
        None
    };
    let twin = TableImage::new(project).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let mut by_logic: Controller<&dyn Program, _> = match &logic {
        Some(logic) => Controller::new(
            logic as &dyn Program,
            HeapMemory::for_config(&logic.config()),
        ),
        None => Controller::new(
            &twin as &dyn Program,
            HeapMemory::for_config(&twin.config()),
        ),
    }
    .map_err(|e| TestCaseError::fail(format!("logic controller: {e:?}")))?;
    let mut reference = Reference::new(project);
    let mut before = initial_states(project);
    let mut was_faulted = false;
    for (k, (now, raw)) in samples.iter().enumerate() {
        let r = reference.scan(*now, raw);
        let t = Record::from(by_table.scan(*now, raw));
        let l = Record::from(by_logic.scan(*now, raw));
        compare(k, &r, &t, &l)?;
        // The three records are equal now: checking one checks all.
        check_control(project, k, &before, was_faulted, &t)?;
        before = t.states;
        was_faulted = t.fault.is_some();
    }
    let last = samples.len();
    agree(
        last,
        "counters.ignored (after the last scan)",
        &reference.ignored,
        &by_table.counters().ignored,
        &by_logic.counters().ignored,
    )
}
