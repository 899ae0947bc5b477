//! `inputs.csv` (docs/formats.md, "inputs.csv"): a header `scan,time_ms,<inputs…>`, then a
//! row per scan with consecutive scan numbers, non-decreasing times and
//! 0/1 input values.
//!
//! Files are read one record at a time ([`InputRows`]), so a replay runs in
//! constant memory: a file is a regular file of at most [`INPUTS_FILE`]'s
//! size ([`open`]), and a record (a line, or several when a quoted field
//! holds line breaks) of at most [`MAX_RECORD_BYTES`], refused at its line
//! beyond that rather than read until memory runs out.

use des::files::{self, Bounded, FileKind};
use plc_project::Project;
use std::cell::Cell;
use std::io::{self, BufRead, BufReader, Read};
use std::path::Path;
use std::rc::Rc;

/// Inputs files as [`des::files`] reads them: a regular file of at
/// most 64 GiB (about three billion scans of a project with eight inputs;
/// it is streamed, so the limit bounds the time a run takes, not its
/// memory).
pub const INPUTS_FILE: FileKind = FileKind::new("inputs file", 64 << 30);

/// The longest record of an inputs file: 16 MiB, room for a header naming
/// 65,535 inputs (the executor's limit) of 200 bytes each.
pub const MAX_RECORD_BYTES: u64 = 16 << 20;

/// Opens the inputs file at `path` for [`InputRows`] ([`INPUTS_FILE`]'s
/// rules: a regular file, not a device or FIFO, within the size limit).
pub fn open(path: &Path) -> Result<Bounded<std::fs::File>, String> {
    files::open(path, INPUTS_FILE).map_err(|e| e.to_string())
}

/// The reader under the CSV parser: it refuses to deliver more than
/// `allowed` bytes in all, which [`InputRows`] moves forward after every
/// record, so that one record (or field) longer than the limit is an error
/// instead of a buffer that grows until memory runs out.
struct RecordLimit<R> {
    inner: R,
    /// Bytes delivered so far.
    delivered: u64,
    /// Bytes that may be delivered in all, set from the parser's position.
    allowed: Rc<Cell<u64>>,
}

impl<R: Read> Read for RecordLimit<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let room = self.allowed.get().saturating_sub(self.delivered);
        if room == 0 && !buf.is_empty() {
            return Err(io::Error::new(io::ErrorKind::InvalidData, RecordTooLong));
        }
        let room = usize::try_from(room).unwrap_or(usize::MAX).min(buf.len());
        let n = self.inner.read(&mut buf[..room])?;
        self.delivered += n as u64;
        Ok(n)
    }
}

/// The error [`RecordLimit`] gives, to tell it from the file's own errors.
#[derive(Debug)]
struct RecordTooLong;

impl std::fmt::Display for RecordTooLong {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "a record longer than {} MiB", MAX_RECORD_BYTES >> 20)
    }
}

impl std::error::Error for RecordTooLong {}

/// The parser reads ahead by at most its buffer (8 KiB): with this much
/// room a record within the limit never makes [`RecordLimit`] refuse, and
/// one beyond it is refused after its end by its length.
const READ_AHEAD: u64 = 64 << 10;

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
    reader: csv::Reader<RecordLimit<BufReader<R>>>,
    /// What the reader may deliver, moved forward after each record.
    allowed: Rc<Cell<u64>>,
    /// The longest record allowed (a parameter for tests).
    max_record: u64,
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
        Self::with_record_limit(reader, file, project, MAX_RECORD_BYTES)
    }

    /// [`InputRows::new`] with records of at most `max_record` bytes.
    pub fn with_record_limit(
        reader: R,
        file: &Path,
        project: &Project,
        max_record: u64,
    ) -> Result<Self, InputsError> {
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
        let allowed = Rc::new(Cell::new(max_record.saturating_add(READ_AHEAD)));
        let reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .trim(csv::Trim::All)
            .from_reader(RecordLimit {
                inner: reader,
                delivered: 0,
                allowed: allowed.clone(),
            });
        let mut rows = InputRows {
            reader,
            allowed,
            max_record,
            file: file.clone(),
            columns: Vec::new(),
            inputs: project.inputs.len(),
            scans: 0,
            last_time: 0,
            failed: false,
        };
        let header = match rows.record()? {
            None => {
                return Err(err(
                    1,
                    "empty file: expected the header `scan,time_ms,<inputs…>`".into(),
                ))
            }
            Some(r) => r,
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
        rows.columns = columns;
        Ok(rows)
    }

    /// The next record that is not blank, `None` at the end of the file;
    /// a record longer than the limit is an error at its line.
    fn record(&mut self) -> Result<Option<csv::StringRecord>, InputsError> {
        let mut record = csv::StringRecord::new();
        loop {
            let start = self.reader.position().byte();
            match self.reader.read_record(&mut record) {
                Ok(false) => return Ok(None),
                Ok(true) => {}
                Err(e) => {
                    // The line the parser had reached: within the record.
                    let line = self.reader.position().line() as usize;
                    return Err(match e.kind() {
                        csv::ErrorKind::Io(io)
                            if io
                                .get_ref()
                                .is_some_and(|inner| inner.is::<RecordTooLong>()) =>
                        {
                            self.too_long(line)
                        }
                        csv::ErrorKind::Io(io) => self.err(line, format!("cannot read: {io}")),
                        _ => self.err(line_of_error(&e), format!("not CSV: {e}")),
                    });
                }
            }
            let end = self.reader.position().byte();
            if end - start > self.max_record {
                return Err(self.too_long(line_of(&record)));
            }
            self.allowed.set(
                end.saturating_add(self.max_record)
                    .saturating_add(READ_AHEAD),
            );
            if !is_blank(&record) {
                return Ok(Some(record));
            }
        }
    }

    fn too_long(&self, line: usize) -> InputsError {
        self.err(
            line,
            format!(
                "a record longer than {}: an inputs file has one short line per scan",
                FileKind::new("", self.max_record).limit()
            ),
        )
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
        let result = match self.record() {
            Ok(None) => return None,
            Ok(Some(r)) => self.row(&r),
            Err(e) => Err(e),
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn press() -> Project {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../models/press.plc.toml");
        plc_project::load(&path).unwrap()
    }

    const HEADER: &str = "scan,time_ms,auto_pb,stop_pb,reset_pb,part,top_ls,bottom_ls\n";

    fn rows(text: &str, limit: u64) -> Result<Vec<InputRow>, InputsError> {
        InputRows::with_record_limit(text.as_bytes(), Path::new("in.csv"), &press(), limit)?
            .collect()
    }

    #[test]
    fn an_endless_first_line_is_refused_at_line_1_without_reading_it_all() {
        let project = press();
        let err = InputRows::new(io::repeat(b'a'), Path::new("zero"), &project)
            .err()
            .unwrap();
        assert_eq!(
            err.to_string(),
            "zero:1: a record longer than 16 MiB: an inputs file has one short line per scan"
        );
    }

    #[test]
    fn a_record_beyond_the_limit_is_refused_at_its_line_whatever_its_shape() {
        let row = "0,0,0,0,0,0,1,0\n";
        assert_eq!(rows(&format!("{HEADER}{row}"), 64).unwrap().len(), 1);
        // One long field, far beyond the parser's read-ahead.
        let long = format!("{HEADER}{row}1,10,{},0,0,0,1,0\n", "1".repeat(1 << 20));
        let err = rows(&long, 64).unwrap_err().to_string();
        assert_eq!(
            err,
            "in.csv:3: a record longer than 64 bytes: an inputs file has one short line per scan"
        );
        // Just beyond the limit, within the read-ahead: refused by length.
        let spaces = format!("{HEADER}{row}1,10,{}0,0,0,0,1,0\n", " ".repeat(60));
        assert!(rows(&spaces, 64)
            .unwrap_err()
            .to_string()
            .starts_with("in.csv:3: a record longer than 64 bytes"));
        // A quoted field of many short lines is one record.
        let quoted = format!("{HEADER}\"{}\",0,0,0,0,0,1,0\n", "1\n".repeat(1000));
        assert!(rows(&quoted, 64)
            .unwrap_err()
            .to_string()
            .starts_with("in.csv:2: a record longer"));
        // Records within the limit read however many there are.
        let many: String = (0..2000)
            .map(|k| format!("{k},{k},0,0,0,0,1,0\n"))
            .collect();
        assert_eq!(rows(&format!("{HEADER}{many}"), 64).unwrap().len(), 2000);
    }
}
