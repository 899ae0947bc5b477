//! `codegen wiring`: which pin carries each signal of a project's
//! `[board]` section, as a Markdown table (or JSON rows).

use super::error::CliError;
use super::output::{warn, Out};
use super::Outcome;
use codegen::board::{wiring_rows, wiring_table};
use plc_project as project;
use std::path::Path;

pub fn run(path: &Path, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let project = project::load(path)?;
    for w in &project.warnings {
        warn(format_args!(
            "warning: {}:{}: {}",
            path.display(),
            w.line,
            w.message
        ));
    }
    let (Some(board), Some(rows)) = (&project.board, wiring_rows(&project)) else {
        return Err(CliError::Usage(format!(
            "{}: the project has no [board] section (see docs/board.md)",
            path.display()
        )));
    };
    if json {
        out.json(&serde_json::json!({
            "project": project.name,
            "chip": board.chip,
            "signals": rows,
            // What a field-update image for this wiring records
            // (docs/field-update.md).
            "signature": format!("{:#010x}", codegen::board::wiring_signature(&project)),
        }));
    } else {
        out.push_str(&wiring_table(&project));
    }
    Ok(Outcome::Holds)
}
