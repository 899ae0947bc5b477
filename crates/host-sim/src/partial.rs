//! Output files that appear only once complete: written under a
//! temporary name next to the final one and renamed at the end, so that a
//! run stopped by bad input leaves no half-written trace or scenario.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A buffered file written as `<path>.partial` until [`Partial::commit`];
/// dropped uncommitted, it is removed.
pub struct Partial {
    path: PathBuf,
    partial: PathBuf,
    writer: Option<BufWriter<File>>,
}

impl Partial {
    /// Creates `<path>.partial` (the whole name kept, so that two outputs
    /// that differ by extension never share it). A `path` that exists and
    /// is not a regular file (`/dev/null`, `/dev/stdout`, a FIFO) is
    /// written directly: renaming over it would replace the device.
    pub fn create(path: &Path) -> Result<Partial, String> {
        let special = std::fs::metadata(path).is_ok_and(|m| !m.is_file());
        let partial = if special {
            path.to_owned()
        } else {
            let mut partial = path.as_os_str().to_owned();
            partial.push(".partial");
            PathBuf::from(partial)
        };
        let file = File::create(&partial).map_err(|e| io(&partial, e))?;
        Ok(Partial {
            path: path.to_owned(),
            partial,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// Creates `<path>.partial` ([`Partial::create`]) holding `bytes`,
    /// to commit with the files it goes with.
    pub fn holding(path: &Path, bytes: &[u8]) -> Result<Partial, String> {
        let mut file = Partial::create(path)?;
        file.writer()
            .write_all(bytes)
            .map_err(|e| io(&file.partial, e))?;
        Ok(file)
    }

    /// The writer.
    pub fn writer(&mut self) -> &mut BufWriter<File> {
        self.writer
            .as_mut()
            .expect("a Partial writes until committed")
    }

    /// Writes `line` and a line break.
    pub fn line(&mut self, line: &str) -> Result<(), String> {
        writeln!(self.writer(), "{line}").map_err(|e| io(&self.partial, e))
    }

    /// Flushes the file and gives it its final name.
    pub fn commit(mut self) -> Result<(), String> {
        let mut writer = self.writer.take().expect("committed once");
        writer.flush().map_err(|e| io(&self.partial, e))?;
        drop(writer);
        if self.partial == self.path {
            return Ok(());
        }
        std::fs::rename(&self.partial, &self.path).map_err(|e| io(&self.path, e))
    }
}

impl Write for Partial {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.writer().write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.writer().flush()
    }
}

impl Drop for Partial {
    fn drop(&mut self) {
        if self.writer.take().is_some() && self.partial != self.path {
            let _ = std::fs::remove_file(&self.partial);
        }
    }
}

fn io(path: &Path, e: std::io::Error) -> String {
    format!("{}: {e}", path.display())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_committed_file_appears_under_its_name_and_a_dropped_one_nowhere() {
        let dir = tempfile::tempdir().unwrap();
        let kept = dir.path().join("kept.csv");
        let mut p = Partial::create(&kept).unwrap();
        p.line("a,b").unwrap();
        assert!(!kept.exists() && dir.path().join("kept.csv.partial").exists());
        p.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&kept).unwrap(), "a,b\n");

        let lost = dir.path().join("lost.csv");
        let mut p = Partial::create(&lost).unwrap();
        p.line("x").unwrap();
        drop(p);
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "only kept.csv"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_written_in_place_never_renamed_over_or_removed() {
        let null = Path::new("/dev/null");
        let mut p = Partial::create(null).unwrap();
        p.line("discarded").unwrap();
        p.commit().unwrap();
        drop(Partial::create(null).unwrap());
        let meta = std::fs::metadata(null).unwrap();
        assert!(!meta.is_file(), "/dev/null is still the device");
        assert!(!Path::new("/dev/null.partial").exists());
    }
}
