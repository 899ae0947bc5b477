//! What the commands print, and how it reaches the terminal.
//!
//! A command collects its standard output in an [`Out`]; `main` writes it
//! once. A reader that stops early (`codegen dot big.gen | head`) closes the
//! pipe: like `cat` or `grep`, the command then stops quietly, and its exit
//! code is still its result (0, or 1 when a checked property fails). Rust's
//! `println!` would panic there instead. Messages on standard error go
//! through [`warn`], which ignores a closed stderr for the same reason.

use std::fmt::{self, Write as _};
use std::io::{self, Write as _};

/// The standard output of one command, written by [`Out::flush_to_stdout`].
#[derive(Debug, Default)]
pub struct Out {
    text: String,
}

/// `println!` into an [`Out`].
macro_rules! outln {
    ($out:expr) => {
        $out.line(format_args!(""))
    };
    ($out:expr, $($arg:tt)*) => {
        $out.line(format_args!($($arg)*))
    };
}
pub(crate) use outln;

impl Out {
    /// Appends `text` and a newline.
    pub fn line(&mut self, text: fmt::Arguments<'_>) {
        // Formatting into a String cannot fail.
        let _ = writeln!(self.text, "{text}");
    }

    /// Appends `text` as it is.
    pub fn push_str(&mut self, text: &str) {
        self.text.push_str(text);
    }

    /// Appends `value` as pretty-printed JSON and a newline.
    pub fn json(&mut self, value: &impl serde::Serialize) {
        self.text
            .push_str(&serde_json::to_string_pretty(value).expect("plain data serialises"));
        self.text.push('\n');
    }

    /// Forgets what was collected (an error replaces the output).
    pub fn clear(&mut self) {
        self.text.clear();
    }

    /// Writes everything to standard output. A closed pipe is not an
    /// error (the reader has what it wanted); any other failure is.
    pub fn flush_to_stdout(&self) -> io::Result<()> {
        write_quietly(&mut io::stdout().lock(), self.text.as_bytes())
    }
}

/// Writes `bytes` to `sink` and flushes; a broken pipe counts as done.
fn write_quietly(sink: &mut impl io::Write, bytes: &[u8]) -> io::Result<()> {
    match sink.write_all(bytes).and_then(|()| sink.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

/// Prints one line on standard error; nothing if stderr is closed.
pub fn warn(text: fmt::Arguments<'_>) {
    let _ = writeln!(io::stderr().lock(), "{text}");
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sink whose reader has gone away.
    struct ClosedPipe;

    impl io::Write for ClosedPipe {
        fn write(&mut self, _: &[u8]) -> io::Result<usize> {
            Err(io::ErrorKind::BrokenPipe.into())
        }
        fn flush(&mut self) -> io::Result<()> {
            Err(io::ErrorKind::BrokenPipe.into())
        }
    }

    /// A sink on a full disk.
    struct Full;

    impl io::Write for Full {
        fn write(&mut self, _: &[u8]) -> io::Result<usize> {
            Err(io::Error::other("no space left on device"))
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_closed_pipe_ends_the_output_quietly_but_other_failures_are_errors() {
        assert!(write_quietly(&mut ClosedPipe, b"digraph {}\n").is_ok());
        assert!(write_quietly(&mut Full, b"digraph {}\n").is_err());
    }

    #[test]
    fn lines_collect_in_order() {
        let mut out = Out::default();
        outln!(out, "plant: {} states", 9);
        outln!(out);
        out.push_str("x");
        assert_eq!(out.text, "plant: 9 states\n\nx");
    }
}
