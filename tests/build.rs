//! Generates every seed project of `models/` with every backend (table, logic
//! and the `match` baseline) into
//! `OUT_DIR`, through `codegen::build::Build` exactly as the build script of
//! a firmware crate would; `generated.rs` includes and runs the results.
//!
//! Output names are `<model>_<backend>.rs` (`press_table.rs`,
//! `press_logic.rs`, `press_match.rs`, …). A project that fails to load or generate fails
//! the build with its `file:line` message. `build_names.rs` adds seeded
//! random projects whose names are drawn to break generated code.

use codegen::backend::Backend;
use codegen::build::Build;

#[path = "build_names.rs"]
mod names;

/// The seed projects (`models/<name>.plc.toml`), listed rather than globbed
/// so that a project added later does not silently join these tests.
const MODELS: [&str; 5] = ["motivating", "press", "press7", "conveyor", "crane"];

/// The seed projects with Petri nets (`models/<dir>/<name>.plc.toml`),
/// generated with the table backend, the only one that runs nets.
const NET_MODELS: [(&str, &str); 1] = [("petri", "mixers")];

fn main() {
    // Random names through every backend: compiled by `generated.rs`.
    names::generate(std::path::Path::new(&std::env::var_os("OUT_DIR").unwrap()));
    // Names chosen to break generated code: compiled by `generated.rs`.
    for backend in Backend::ALL {
        Build::new("fixtures/hostile/hostile.plc.toml")
            .backend(backend)
            .file_name(format!("hostile_{}", backend.name()))
            .generate_or_exit();
    }
    for model in MODELS {
        for backend in Backend::ALL {
            let suffix = backend.name();
            Build::new(format!("../models/{model}.plc.toml"))
                .backend(backend)
                .file_name(format!("{model}_{suffix}"))
                .generate_or_exit();
        }
    }
    for (dir, model) in NET_MODELS {
        Build::new(format!("../models/{dir}/{model}.plc.toml"))
            .backend(Backend::Table)
            .file_name(format!("{model}_table"))
            .generate_or_exit();
    }
}
