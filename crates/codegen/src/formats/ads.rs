//! Placeholder, being written.
use crate::automaton::Automaton;
use crate::error::Result;
use std::path::Path;

/// Parses the text of a file.
pub fn read(_text: &str, _origin: &Path) -> Result<Automaton> {
    unimplemented!()
}
/// Renders a file.
pub fn write(_a: &Automaton) -> String {
    unimplemented!()
}
