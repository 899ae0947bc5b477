//! Corrupts a real generated program image as the input says and runs
//! scans on it: no panic, the safe image on anything invalid (see
//! `executor_fuzz::run_image`).
#![no_main]

use codegen::lower::TableImage;
use libfuzzer_sys::fuzz_target;
use std::path::Path;
use std::sync::OnceLock;

fn images() -> &'static [TableImage] {
    static IMAGES: OnceLock<Vec<TableImage>> = OnceLock::new();
    IMAGES.get_or_init(|| {
        executor_fuzz::seed_images(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../models"))
    })
}

fuzz_target!(|data: &[u8]| executor_fuzz::run_image(images(), data));
