//! Spans of the project file as lines and columns, for errors and
//! warnings.
//!
//! A project is located many times (every declaration records its line),
//! so the line starts are found once ([`LineIndex`]): locating stays
//! linear in the size of the project, where a scan from the start of the
//! text for each span was quadratic.

use des::error::{Error, LineIndex, Location};
use std::ops::Range;
use std::path::Path;

/// The project file: its path (as the user named it) and its lines.
pub(crate) struct ProjectFile<'a> {
    path: &'a Path,
    lines: LineIndex<'a>,
}

impl<'a> ProjectFile<'a> {
    /// The project file at `path`, whose text is `text`.
    pub(crate) fn new(path: &'a Path, text: &'a str) -> Self {
        ProjectFile {
            path,
            lines: LineIndex::new(text),
        }
    }

    /// The path the project file was named by.
    pub(crate) fn path(&self) -> &'a Path {
        self.path
    }

    /// Where `span` starts.
    pub(crate) fn location(&self, span: &Range<usize>) -> Location {
        self.lines.location(self.path, span.start)
    }

    /// The line `span` starts on.
    pub(crate) fn line(&self, span: &Range<usize>) -> u32 {
        self.lines.line_column(span.start).0
    }

    /// A model error at `span`.
    pub(crate) fn error(&self, span: &Range<usize>, message: impl Into<String>) -> Error {
        Error::model(self.location(span), message)
    }
}
