//! Reading the files a user names: every file the tools read from a path
//! (model files, nets, constraints, and in the crates above, projects,
//! I/O maps, inputs) comes through [`open`], [`read_bytes`] or
//! [`read_text`], so each gets the same rules:
//!
//! - it is a **regular file**: a device such as `/dev/zero` could be read
//!   until memory runs out, a FIFO could block for ever, a directory is a
//!   mistake;
//! - it holds at most the **size limit of its kind** ([`FileKind`]), which
//!   the crate owning the format sets (the limit is checked before reading
//!   and enforced while reading, so a file that grows meanwhile is still
//!   refused rather than read without end);
//! - a refusal is an [`Error::Io`] naming the file, the kind and the
//!   reason.

use crate::error::{Error, Result};
use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// A kind of input file and the most bytes one may hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FileKind {
    /// What the file is, as errors name it ("project file", "I/O map").
    pub what: &'static str,
    /// The largest such file, in bytes.
    pub max_bytes: u64,
}

impl FileKind {
    /// A kind called `what` of at most `max_bytes` bytes.
    pub const fn new(what: &'static str, max_bytes: u64) -> FileKind {
        FileKind { what, max_bytes }
    }

    /// The limit in words: `256 MiB`, `64 KiB`, `100 bytes`.
    pub fn limit(&self) -> String {
        size(self.max_bytes)
    }
}

/// `n` bytes in the largest binary unit that divides it.
fn size(n: u64) -> String {
    for (shift, unit) in [(40, "TiB"), (30, "GiB"), (20, "MiB"), (10, "KiB")] {
        if n >= 1 << shift && n % (1 << shift) == 0 {
            return format!("{} {unit}", n >> shift);
        }
    }
    format!("{n} bytes")
}

/// An error of `path` with `kind`'s reason.
fn refused(path: &Path, kind: io::ErrorKind, message: String) -> Error {
    Error::io(path, io::Error::new(kind, message))
}

/// An open input file that refuses to deliver more than its kind's limit:
/// a read past it is an error ([`io::ErrorKind::InvalidData`]) saying so
/// (without the path, which the caller adds as it adds it to every error
/// of the file).
#[derive(Debug)]
pub struct Bounded<R> {
    inner: R,
    /// Bytes still allowed.
    left: u64,
    kind: FileKind,
}

impl<R: Read> Bounded<R> {
    /// `inner`, a file of kind `kind`, limited to its size.
    pub fn new(inner: R, kind: FileKind) -> Bounded<R> {
        Bounded {
            inner,
            left: kind.max_bytes,
            kind,
        }
    }

    fn too_large(&self) -> io::Error {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "longer than {}, the most the {} may hold",
                self.kind.limit(),
                self.kind.what
            ),
        )
    }
}

impl<R: Read> Read for Bounded<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if buf.is_empty() {
            return Ok(0);
        }
        if self.left == 0 {
            // One byte beyond the limit tells a file of exactly the limit
            // from a longer one.
            let mut probe = [0u8; 1];
            return match self.inner.read(&mut probe)? {
                0 => Ok(0),
                _ => Err(self.too_large()),
            };
        }
        let room = usize::try_from(self.left)
            .unwrap_or(usize::MAX)
            .min(buf.len());
        let n = self.inner.read(&mut buf[..room])?;
        self.left -= n as u64;
        Ok(n)
    }
}

/// Opens the file at `path` for reading as a `kind`: a regular file of at
/// most `kind.max_bytes`, and a reader that refuses to go past that.
pub fn open(path: &Path, kind: FileKind) -> Result<Bounded<File>> {
    // Looked at before opening: opening a FIFO blocks until a writer comes.
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    check(path, kind, &meta)?;
    let file = File::open(path).map_err(|e| Error::io(path, e))?;
    // And again on what was opened, in case the path changed meanwhile.
    let meta = file.metadata().map_err(|e| Error::io(path, e))?;
    check(path, kind, &meta)?;
    Ok(Bounded::new(file, kind))
}

fn check(path: &Path, kind: FileKind, meta: &std::fs::Metadata) -> Result<()> {
    if !meta.is_file() {
        return Err(refused(
            path,
            io::ErrorKind::InvalidInput,
            format!(
                "not a regular file (the {} must be a file, not a device, FIFO or directory)",
                kind.what
            ),
        ));
    }
    if meta.len() > kind.max_bytes {
        return Err(refused(
            path,
            io::ErrorKind::InvalidData,
            format!(
                "{} bytes, more than {}, the most the {} may hold",
                meta.len(),
                kind.limit(),
                kind.what
            ),
        ));
    }
    Ok(())
}

/// The bytes of the file at `path`, a `kind` ([`open`]'s rules).
pub fn read_bytes(path: &Path, kind: FileKind) -> Result<Vec<u8>> {
    let mut file = open(path, kind)?;
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    Ok(bytes)
}

/// The text of the file at `path`, a `kind` ([`open`]'s rules), which
/// must be UTF-8.
pub fn read_text(path: &Path, kind: FileKind) -> Result<String> {
    String::from_utf8(read_bytes(path, kind)?).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        refused(
            path,
            io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (byte {at} starts an invalid sequence); the {} must be UTF-8",
                kind.what
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SMALL: FileKind = FileKind::new("test file", 8);

    #[test]
    fn limits_read_in_their_unit() {
        assert_eq!(FileKind::new("x", 256 << 20).limit(), "256 MiB");
        assert_eq!(FileKind::new("x", 16 << 30).limit(), "16 GiB");
        assert_eq!(FileKind::new("x", 1536).limit(), "1536 bytes");
        assert_eq!(FileKind::new("x", 3 << 10).limit(), "3 KiB");
    }

    #[test]
    fn a_file_of_exactly_the_limit_reads_and_one_byte_more_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.txt");
        std::fs::write(&path, "12345678").unwrap();
        assert_eq!(read_text(&path, SMALL).unwrap(), "12345678");
        std::fs::write(&path, "123456789").unwrap();
        let err = read_text(&path, SMALL).unwrap_err().to_string();
        assert!(
            err.starts_with(&format!(
                "{}: 9 bytes, more than 8 bytes, the most the test file may hold",
                path.display()
            )),
            "{err}"
        );
    }

    #[test]
    fn the_reader_stops_at_the_limit_whatever_the_file_claimed() {
        // An endless stream, as a device or a growing file would give.
        let mut r = Bounded::new(io::repeat(b'a'), SMALL);
        let mut all = Vec::new();
        let err = r.read_to_end(&mut all).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidData);
        assert_eq!(
            err.to_string(),
            "longer than 8 bytes, the most the test file may hold"
        );
        assert_eq!(all.len(), 8);
        let mut exact = Bounded::new(&b"12345678"[..], SMALL);
        let mut all = Vec::new();
        exact.read_to_end(&mut all).unwrap();
        assert_eq!(all, b"12345678");
    }

    #[test]
    fn text_must_be_utf8() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.txt");
        std::fs::write(&path, b"ab\xffc").unwrap();
        let err = read_text(&path, SMALL).unwrap_err().to_string();
        assert!(err.contains("not UTF-8 text (byte 2"), "{err}");
    }

    #[cfg(unix)]
    #[test]
    fn devices_fifos_and_directories_are_refused_without_reading() {
        let dir = tempfile::tempdir().unwrap();
        for path in crate::testing::not_regular_files(dir.path(), "f") {
            let err = read_bytes(&path, SMALL).unwrap_err().to_string();
            assert_eq!(
                err,
                format!(
                    "{}: not a regular file (the test file must be a file, not a device, FIFO or directory)",
                    path.display()
                )
            );
        }
    }
}
