//! Feeds arbitrary bytes to the Toml reader: it must return, never panic.
#![no_main]

use des::formats::{read_str, Format};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = read_str(text, Format::Toml, Path::new("fuzz"));
    }
});
