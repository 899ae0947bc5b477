//! Feeds arbitrary text as a project file through validation and code
//! generation (see `codegen_fuzz::check_project`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The directory the project file is read in, with copies of the seed
/// projects' model directories (made once per process).
fn root() -> &'static Path {
    static ROOT: OnceLock<PathBuf> = OnceLock::new();
    ROOT.get_or_init(|| {
        let here = Path::new(env!("CARGO_MANIFEST_DIR"));
        let root = here.join("target/models");
        codegen_fuzz::model_root(&here.join("../../.."), &root).expect("copying the models");
        root
    })
}

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        codegen_fuzz::check_project(text, root());
    }
});
