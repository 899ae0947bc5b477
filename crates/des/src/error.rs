//! Errors of the automaton layer.
//!
//! Every error that stems from a file names the file and, where the format
//! has them, the line and column, so that a user can jump straight to it.

use std::fmt;
use std::path::{Path, PathBuf};

/// A position in a source file (1-based line and column; 0 = unknown).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file as the user named it.
    pub file: PathBuf,
    /// 1-based line, 0 when unknown.
    pub line: u32,
    /// 1-based column, 0 when unknown.
    pub column: u32,
}

impl Location {
    /// A location at `line:column` of `file`.
    pub fn new(file: impl Into<PathBuf>, line: u32, column: u32) -> Self {
        Location {
            file: file.into(),
            line,
            column,
        }
    }

    /// The whole file, no line known.
    pub fn file(file: impl Into<PathBuf>) -> Self {
        Location::new(file, 0, 0)
    }

    /// The location of byte `offset` in `text`.
    pub fn at_offset(file: impl Into<PathBuf>, text: &str, offset: usize) -> Self {
        let (line, column) = line_column(text, offset);
        Location::new(file, line, column)
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if self.line > 0 {
            write!(f, ":{}", self.line)?;
            if self.column > 0 {
                write!(f, ":{}", self.column)?;
            }
        }
        Ok(())
    }
}

/// 1-based line and column (in characters) of byte `offset` in `text`.
pub fn line_column(text: &str, offset: usize) -> (u32, u32) {
    let offset = offset.min(text.len());
    let before = &text.as_bytes()[..offset];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    (
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(column).unwrap_or(u32::MAX),
    )
}

/// The line starts of a text, found once, so that locating many offsets
/// costs a binary search each instead of a scan from the start of the text
/// ([`line_column`], which is linear in the offset).
#[derive(Debug, Clone)]
pub struct LineIndex<'a> {
    text: &'a str,
    /// Byte offset of the first byte of every line; `starts[0] == 0`.
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    /// Indexes the lines of `text`.
    pub fn new(text: &'a str) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex { text, starts }
    }

    /// 1-based line and column (in characters) of byte `offset`: the same
    /// as [`line_column`] on the indexed text.
    pub fn line_column(&self, offset: usize) -> (u32, u32) {
        let offset = offset.min(self.text.len());
        // `starts[0] == 0 <= offset`, so at least one line starts at or
        // before `offset`.
        let line = self.starts.partition_point(|&start| start <= offset);
        let line_start = self.starts[line - 1];
        let column = String::from_utf8_lossy(&self.text.as_bytes()[line_start..offset])
            .chars()
            .count()
            + 1;
        (
            u32::try_from(line).unwrap_or(u32::MAX),
            u32::try_from(column).unwrap_or(u32::MAX),
        )
    }

    /// The location of byte `offset` in `file`, the file of the indexed text.
    pub fn location(&self, file: impl Into<PathBuf>, offset: usize) -> Location {
        let (line, column) = self.line_column(offset);
        Location::new(file, line, column)
    }
}

/// Everything that can go wrong reading, building or operating on automata.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// A file does not follow its format.
    #[error("{location}: {message}")]
    Syntax {
        /// Where the problem is.
        location: Location,
        /// What was expected.
        message: String,
    },
    /// A file is well-formed but describes an invalid model (two
    /// transitions for one state and event, an undeclared event, …).
    #[error("{location}: {message}")]
    Model {
        /// Where the problem is (the line of the offending entry).
        location: Location,
        /// What is wrong.
        message: String,
    },
    /// The file extension names no format we know.
    #[error("{}: unknown model format (expected .toml, .gen, .ads or .wmod)", path.display())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// Automata that are combined disagree, or an operation's precondition
    /// does not hold (e.g. a specification event the plant does not know).
    #[error("{0}")]
    Incompatible(String),
    /// A composition or a reachability graph grew past its bound on states
    /// (or past what that bound allows of the token counts, firings and
    /// state names kept with a graph), and was given up before it exhausted
    /// memory. The message names what grew and the limit it reached; how a
    /// user raises the bound (a command-line flag, a project key) is for
    /// the caller to add, which is why this is a variant of its own.
    #[error("{message}")]
    StateLimit {
        /// The bound on states in force: what raising lets the operation
        /// go further.
        max_states: usize,
        /// What exceeded it and which limit it reached.
        message: String,
    },
}

impl Error {
    /// A syntax error at `location`.
    pub fn syntax(location: Location, message: impl Into<String>) -> Self {
        Error::Syntax {
            location,
            message: message.into(),
        }
    }

    /// A model error at `location`.
    pub fn model(location: Location, message: impl Into<String>) -> Self {
        Error::Model {
            location,
            message: message.into(),
        }
    }

    /// The location and message of a syntax or model error (`None` for the
    /// other kinds), for editors and tests that point at the offending line.
    pub fn located(&self) -> Option<(&Location, &str)> {
        match self {
            Error::Syntax { location, message } | Error::Model { location, message } => {
                Some((location, message))
            }
            _ => None,
        }
    }

    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        Error::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// Result with the crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_are_one_based_and_count_characters() {
        let text = "ab\nçd\nef";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 3), (2, 1));
        // 'ç' is two bytes; 'd' is the second character of line 2.
        assert_eq!(line_column(text, 5), (2, 2));
        assert_eq!(line_column(text, 100), (3, 3));
    }

    #[test]
    fn the_line_index_locates_every_offset_as_a_scan_does() {
        for text in ["", "\n", "ab\nçd\nef", "a\n\nb\n", "x\r\ny€z\n\n"] {
            let index = LineIndex::new(text);
            for offset in 0..=text.len() + 2 {
                assert_eq!(
                    index.line_column(offset),
                    line_column(text, offset),
                    "{text:?} at {offset}"
                );
            }
        }
        let index = LineIndex::new("ab\nçd");
        assert_eq!(index.location("p.toml", 5).to_string(), "p.toml:2:2");
    }

    #[test]
    fn location_prints_like_a_compiler() {
        assert_eq!(Location::new("m.gen", 4, 2).to_string(), "m.gen:4:2");
        assert_eq!(Location::new("m.gen", 4, 0).to_string(), "m.gen:4");
        assert_eq!(Location::file("m.gen").to_string(), "m.gen");
    }
}
