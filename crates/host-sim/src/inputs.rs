//! `inputs.csv` (docs/formats.md, "inputs.csv"): a header `scan,time_ms,<inputs…>`, then a
//! row per scan with consecutive scan numbers, non-decreasing times and
//! 0/1 input values.

use codegen::project::Project;
use std::io::{BufRead, BufReader, Read};
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
    InputRows::new(text.as_bytes(), file, project)?.collect()
}

/// The rows of an inputs file read one at a time, so that a replay runs in
/// constant memory however long the file ([`parse`] collects them).
pub struct InputRows<R: Read> {
    records: csv::StringRecordsIntoIter<BufReader<R>>,
    file: String,
    /// For each column after `scan,time_ms`: its name and the input it feeds.
    columns: Vec<(String, usize)>,
    inputs: usize,
    scans: u64,
    last_time: u64,
    failed: bool,
}

impl<R: Read> InputRows<R> {
    /// Reads and checks the header of `reader` (the file `file`) against
    /// `project`'s inputs.
    pub fn new(reader: R, file: &Path, project: &Project) -> Result<Self, InputsError> {
        let file = file.display().to_string();
        let err = |line: usize, message: String| InputsError {
            file: file.clone(),
            line,
            message,
        };
        // A byte-order mark (spreadsheet exports write one) is not part of
        // the header; fields may be quoted as the trace writer quotes them.
        let mut reader = BufReader::new(reader);
        let bom = reader
            .fill_buf()
            .map_err(|e| err(1, format!("cannot read: {e}")))?
            .starts_with("\u{feff}".as_bytes());
        if bom {
            reader.consume(3);
        }
        let mut records = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .trim(csv::Trim::All)
            .from_reader(reader)
            .into_records();
        let header = loop {
            match records.next() {
                None => {
                    return Err(err(
                        1,
                        "empty file: expected the header `scan,time_ms,<inputs…>`".into(),
                    ))
                }
                Some(Err(e)) => return Err(err(line_of_error(&e), format!("not CSV: {e}"))),
                Some(Ok(r)) if is_blank(&r) => continue,
                Some(Ok(r)) => break r,
            }
        };
        let hline = line_of(&header);
        let names: Vec<&str> = header.iter().collect();
        if names.len() < 2 || names[0] != "scan" || names[1] != "time_ms" {
            return Err(err(
                hline,
                "the header must start with `scan,time_ms`".into(),
            ));
        }
        // For each column after the first two, the project input it feeds.
        let mut columns: Vec<(String, usize)> = Vec::new();
        for name in &names[2..] {
            let Some(i) = project.input(name) else {
                return Err(err(
                    hline,
                    format!("`{name}` is not an input of the project"),
                ));
            };
            if columns.iter().any(|&(_, j)| j == i) {
                return Err(err(hline, format!("input `{name}` appears twice")));
            }
            columns.push(((*name).to_owned(), i));
        }
        if let Some(missing) = project
            .inputs
            .iter()
            .enumerate()
            .find(|(i, _)| !columns.iter().any(|&(_, j)| j == *i))
        {
            return Err(err(
                hline,
                format!("no column for input `{}`", missing.1.name),
            ));
        }
        Ok(InputRows {
            records,
            file,
            columns,
            inputs: project.inputs.len(),
            scans: 0,
            last_time: 0,
            failed: false,
        })
    }

    fn err(&self, line: usize, message: String) -> InputsError {
        InputsError {
            file: self.file.clone(),
            line,
            message,
        }
    }

    /// Checks one data record.
    fn row(&mut self, record: &csv::StringRecord) -> Result<InputRow, InputsError> {
        let n = line_of(record);
        let cells: Vec<&str> = record.iter().collect();
        let width = self.columns.len() + 2;
        if cells.len() != width {
            return Err(self.err(n, format!("expected {width} values, found {}", cells.len())));
        }
        let scan: u64 = cells[0]
            .parse()
            .map_err(|_| self.err(n, format!("scan `{}` is not a number", cells[0])))?;
        if scan != self.scans {
            return Err(self.err(n, format!("expected scan {}, found {scan}", self.scans)));
        }
        let time: u64 = cells[1]
            .parse()
            .map_err(|_| self.err(n, format!("time_ms `{}` is not a number", cells[1])))?;
        let last_time = self.last_time;
        if time < last_time {
            return Err(self.err(n, format!("time_ms goes back from {last_time} to {time}")));
        }
        // The controller's clock compares times modulo 2^32 as signed
        // differences: a longer gap would hide every timer expiry in it.
        if self.scans > 0 && time - last_time >= 1 << 31 {
            return Err(self.err(
                n,
                format!(
                    "time_ms jumps by {} ms from {last_time}: gaps between scans must stay below 2^31 ms (about 24.8 days)",
                    time - last_time
                ),
            ));
        }
        let mut values = vec![false; self.inputs];
        for (k, cell) in cells[2..].iter().enumerate() {
            let (name, slot) = &self.columns[k];
            values[*slot] = match *cell {
                "0" => false,
                "1" => true,
                other => {
                    return Err(
                        self.err(n, format!("`{other}` for input `{name}`: expected 0 or 1"))
                    )
                }
            };
        }
        self.scans += 1;
        self.last_time = time;
        Ok(InputRow {
            time_ms: time,
            values,
        })
    }
}

impl<R: Read> Iterator for InputRows<R> {
    type Item = Result<InputRow, InputsError>;

    /// The next row; after an error, `None`.
    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let result = loop {
            match self.records.next()? {
                Err(e) => break Err(self.err(line_of_error(&e), format!("not CSV: {e}"))),
                Ok(r) if is_blank(&r) => continue,
                Ok(r) => break self.row(&r),
            }
        };
        self.failed = result.is_err();
        Some(result)
    }
}

/// A blank line reads as one empty field.
fn is_blank(record: &csv::StringRecord) -> bool {
    record.len() == 1 && record[0].is_empty()
}

fn line_of(record: &csv::StringRecord) -> usize {
    record.position().map_or(1, |p| p.line() as usize)
}

fn line_of_error(e: &csv::Error) -> usize {
    e.position().map_or(1, |p| p.line() as usize)
}

/// The header line of an inputs file for `project` (no line break).
pub fn csv_header(project: &Project) -> String {
    let mut out = String::from("scan,time_ms");
    for i in &project.inputs {
        out.push(',');
        out.push_str(&crate::trace::field(&i.name));
    }
    out
}

/// Row `scan` of an inputs file (no line break).
pub fn csv_line(scan: u64, row: &InputRow) -> String {
    let mut out = format!("{scan},{}", row.time_ms);
    for &v in &row.values {
        out.push_str(if v { ",1" } else { ",0" });
    }
    out
}

/// The inputs file text for `rows` of `project`.
pub fn to_csv(project: &Project, rows: &[InputRow]) -> String {
    let mut out = csv_header(project);
    out.push('\n');
    for (k, r) in rows.iter().enumerate() {
        out.push_str(&csv_line(k as u64, r));
        out.push('\n');
    }
    out
}
