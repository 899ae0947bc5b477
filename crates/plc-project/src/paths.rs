//! File names a build script can print: cargo reads a build script's
//! standard output as lines split at `\n`, each trimmed, a line that is not
//! UTF-8 skipped, and every line starting with `cargo:` taken as a
//! directive. A model file is named to cargo (`cargo:rerun-if-changed`), so
//! a project refuses, at the line that names it, a file whose name cargo
//! would not read back unchanged.

use std::fmt;
use std::path::Path;

/// Why a path cannot go into a `cargo:` line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnprintablePath {
    /// Not valid UTF-8: cargo skips a line that is not UTF-8.
    NotUtf8,
    /// A control character: a line feed ends the directive and starts
    /// another, a carriage return hides text on a terminal.
    Control(char),
    /// Whitespace at the end, which cargo trims off the line.
    TrailingWhitespace,
}

impl fmt::Display for UnprintablePath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UnprintablePath::NotUtf8 => f.write_str("it is not valid UTF-8"),
            UnprintablePath::Control(c) => {
                write!(f, "it holds the control character U+{:04X}", u32::from(*c))
            }
            UnprintablePath::TrailingWhitespace => f.write_str("it ends in whitespace"),
        }
    }
}

/// `path` as text that cargo reads back unchanged from a `cargo:` line, or
/// why there is none.
pub fn printable_path(path: &Path) -> std::result::Result<&str, UnprintablePath> {
    let text = path.to_str().ok_or(UnprintablePath::NotUtf8)?;
    if let Some(c) = text.chars().find(|c| c.is_control()) {
        return Err(UnprintablePath::Control(c));
    }
    if text.ends_with(char::is_whitespace) {
        return Err(UnprintablePath::TrailingWhitespace);
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::{printable_path, UnprintablePath};
    use std::path::Path;

    #[test]
    fn a_path_cargo_would_misread_is_refused() {
        let refused = |path: &str| printable_path(Path::new(path)).unwrap_err();
        assert_eq!(
            refused("plant/a\ncargo:rustc-env=PWNED=1.toml"),
            UnprintablePath::Control('\n')
        );
        assert_eq!(refused("plant/a\r.toml"), UnprintablePath::Control('\r'));
        assert_eq!(
            refused("plant/a\u{1b}[2K.toml"),
            UnprintablePath::Control('\u{1b}')
        );
        assert_eq!(
            refused("plant/a.toml "),
            UnprintablePath::TrailingWhitespace
        );
        assert_eq!(
            refused("plant/a.toml\u{a0}"),
            UnprintablePath::TrailingWhitespace
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_path_that_is_not_utf8_is_refused() {
        use std::os::unix::ffi::OsStrExt;
        let path = Path::new(std::ffi::OsStr::from_bytes(b"plant/\xff.toml"));
        assert_eq!(printable_path(path), Err(UnprintablePath::NotUtf8));
    }
}
