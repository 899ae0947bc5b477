//! Placeholder, being written.
use super::Component;
use crate::error::Result;
use std::path::Path;

/// Parses the text of a file.
pub fn read(_text: &str, _origin: &Path) -> Result<Vec<Component>> {
    unimplemented!()
}
/// Renders a file.
pub fn write(_c: &[Component]) -> String {
    unimplemented!()
}
