//! `inputs.csv` (docs/formats.md, "inputs.csv"): a header `scan,time_ms,<inputs…>`, then a
//! row per scan with consecutive scan numbers, non-decreasing times and
//! 0/1 input values.

use codegen::project::Project;
use std::path::Path;

/// One scan of input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputRow {
    /// Time in ms as written (the executor sees it modulo 2^32).
    pub time_ms: u64,
    /// Raw input values in the project's declaration order.
    pub values: Vec<bool>,
}

/// A problem with an inputs file, with its line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct InputsError {
    /// The file.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// Parses an inputs file for `project`. Columns may come in any order;
/// every project input must have one, and unknown columns are errors.
pub fn parse(text: &str, file: &Path, project: &Project) -> Result<Vec<InputRow>, InputsError> {
    let err = |line: usize, message: String| InputsError {
        file: file.display().to_string(),
        line,
        message,
    };
    // A byte-order mark (spreadsheet exports write one) is not part of the
    // header; fields may be quoted as the trace writer quotes them.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let mut records = reader.records().filter(|r| {
        r.as_ref()
            .map_or(true, |r| !(r.len() == 1 && r[0].is_empty()))
    });
    let line_of = |r: &csv::StringRecord| r.position().map_or(1, |p| p.line() as usize);
    let record = |r: Option<Result<csv::StringRecord, csv::Error>>| match r {
        Some(Ok(r)) => Ok(Some(r)),
        Some(Err(e)) => {
            let line = e.position().map_or(1, |p| p.line() as usize);
            Err(err(line, format!("not CSV: {e}")))
        }
        None => Ok(None),
    };
    let Some(header) = record(records.next())? else {
        return Err(err(
            1,
            "empty file: expected the header `scan,time_ms,<inputs…>`".into(),
        ));
    };
    let hline = line_of(&header);
    let columns: Vec<&str> = header.iter().collect();
    if columns.len() < 2 || columns[0] != "scan" || columns[1] != "time_ms" {
        return Err(err(
            hline,
            "the header must start with `scan,time_ms`".into(),
        ));
    }
    // For each column after the first two, the project input it feeds.
    let mut slots = Vec::new();
    for name in &columns[2..] {
        let Some(i) = project.input(name) else {
            return Err(err(
                hline,
                format!("`{name}` is not an input of the project"),
            ));
        };
        if slots.contains(&i) {
            return Err(err(hline, format!("input `{name}` appears twice")));
        }
        slots.push(i);
    }
    if let Some(missing) = project
        .inputs
        .iter()
        .enumerate()
        .find(|(i, _)| !slots.contains(i))
    {
        return Err(err(
            hline,
            format!("no column for input `{}`", missing.1.name),
        ));
    }
    let mut rows = Vec::new();
    let mut last_time = 0u64;
    while let Some(row) = record(records.next())? {
        let n = line_of(&row);
        let cells: Vec<&str> = row.iter().collect();
        if cells.len() != columns.len() {
            return Err(err(
                n,
                format!("expected {} values, found {}", columns.len(), cells.len()),
            ));
        }
        let scan: u64 = cells[0]
            .parse()
            .map_err(|_| err(n, format!("scan `{}` is not a number", cells[0])))?;
        if scan != rows.len() as u64 {
            return Err(err(
                n,
                format!("expected scan {}, found {scan}", rows.len()),
            ));
        }
        let time: u64 = cells[1]
            .parse()
            .map_err(|_| err(n, format!("time_ms `{}` is not a number", cells[1])))?;
        if time < last_time {
            return Err(err(
                n,
                format!("time_ms goes back from {last_time} to {time}"),
            ));
        }
        // The controller's clock compares times modulo 2^32 as signed
        // differences: a longer gap would hide every timer expiry in it.
        if !rows.is_empty() && time - last_time >= 1 << 31 {
            return Err(err(
                n,
                format!(
                    "time_ms jumps by {} ms from {last_time}: gaps between scans must stay below 2^31 ms (about 24.8 days)",
                    time - last_time
                ),
            ));
        }
        last_time = time;
        let mut values = vec![false; project.inputs.len()];
        for (k, cell) in cells[2..].iter().enumerate() {
            values[slots[k]] = match *cell {
                "0" => false,
                "1" => true,
                other => {
                    return Err(err(
                        n,
                        format!("`{other}` for input `{}`: expected 0 or 1", columns[k + 2]),
                    ))
                }
            };
        }
        rows.push(InputRow {
            time_ms: time,
            values,
        });
    }
    Ok(rows)
}

/// The inputs file text for `rows` of `project`.
pub fn to_csv(project: &Project, rows: &[InputRow]) -> String {
    let mut out = String::from("scan,time_ms");
    for i in &project.inputs {
        out.push(',');
        out.push_str(&crate::trace::field(&i.name));
    }
    out.push('\n');
    for (k, r) in rows.iter().enumerate() {
        out.push_str(&format!("{k},{}", r.time_ms));
        for &v in &r.values {
            out.push_str(if v { ",1" } else { ",0" });
        }
        out.push('\n');
    }
    out
}
