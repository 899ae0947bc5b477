//! Replay: every row of an inputs file through a project, one scan each.

use crate::inputs::InputRow;
use crate::sim::{Sim, SimError};
use crate::trace::TraceRow;

/// Runs `rows` through `sim` (one scan per row at the row's time) and
/// returns the trace rows of those scans.
pub fn replay(sim: &mut Sim, rows: &[InputRow]) -> Result<Vec<TraceRow>, SimError> {
    let mut out = Vec::with_capacity(rows.len());
    for row in rows {
        out.push(sim.scan_with(row.time_ms, &row.values)?.clone());
    }
    Ok(out)
}
