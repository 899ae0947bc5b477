//! A generation lowers its project once: the Rust emitter, the figures of
//! `codegen gen --stats` and the build-script API all read the one
//! [`Lowered`] program, and host runs use the same type.

use codegen::backend::Backend;
use codegen::build::Build;
use codegen::emit::generate;
use codegen::lower::{self, Lowered};
use executor::program::Program;
use std::path::{Path, PathBuf};

fn model(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(relative)
}

/// `(project, backends)`: every seed project, nets on the table backend
/// only (the others refuse them).
const PROJECTS: [(&str, &[Backend]); 7] = [
    ("motivating.plc.toml", &Backend::ALL),
    ("press.plc.toml", &Backend::ALL),
    ("press7.plc.toml", &Backend::ALL),
    ("conveyor.plc.toml", &Backend::ALL),
    ("crane.plc.toml", &Backend::ALL),
    ("petri/mixers.plc.toml", &[Backend::Table]),
    ("boiler/boiler.plc.toml", &[Backend::Table, Backend::Match]),
];

/// The lowering passes `f` runs on this thread.
fn passes_of<T>(f: impl FnOnce() -> T) -> (usize, T) {
    let before = lower::passes();
    let value = f();
    (lower::passes() - before, value)
}

#[test]
fn one_generation_lowers_its_project_once() {
    for (name, backends) in PROJECTS {
        let project = plc_project::load(&model(name)).unwrap();
        for &backend in backends {
            let (passes, generated) = passes_of(|| generate(&project, backend, "t").unwrap());
            assert_eq!(passes, 1, "{name}, {backend:?}: lowering passes");
            // What the file records is what the lowered program holds.
            let lowered = Lowered::new(&project, backend, &()).unwrap();
            assert_eq!(generated.crc, lowered.recorded_crc(), "{name}, {backend:?}");
            assert_eq!(
                generated.image,
                lowered.image_check(),
                "{name}, {backend:?}"
            );
            assert_eq!(generated.sets, lowered.scan_sets(), "{name}, {backend:?}");
        }
    }
}

#[test]
fn a_build_script_generation_lowers_once() {
    let out = tempfile::tempdir().unwrap();
    let (passes, written) = passes_of(|| {
        Build::new(model("press.plc.toml"))
            .backend(Backend::Table)
            .out_dir(out.path())
            .generate()
            .unwrap()
    });
    assert_eq!(passes, 1);
    assert!(written.0.ends_with("press.rs"), "{:?}", written.0);
}

#[test]
fn the_counter_counts_every_lowering() {
    let project = plc_project::load(&model("press.plc.toml")).unwrap();
    let (passes, _) = passes_of(|| {
        for backend in [Backend::Table, Backend::Match] {
            Lowered::new(&project, backend, &()).unwrap();
        }
    });
    assert_eq!(
        passes, 2,
        "the check above would pass with a counter that never moves"
    );
}

/// The match backend's image is its configuration: the supervisors are
/// code, so no table is under the CRC, on the target as on the host.
#[test]
fn a_match_program_has_no_table_in_its_image() {
    let project = plc_project::load(&model("press.plc.toml")).unwrap();
    let table = Lowered::new(&project, Backend::Table, &()).unwrap();
    let code = Lowered::new(&project, Backend::Match, &()).unwrap();
    assert!(table.table(0).is_some());
    assert!(code.table(0).is_none());
    assert!(code.image_check().image_bytes < table.image_check().image_bytes);
    assert_eq!(
        code.recorded_crc(),
        executor::image::config_crc(&code.config())
    );
    assert_eq!(code.recorded_crc(), executor::image::crc(&code));
    // Same transitions either way.
    for s in 0..4 {
        for e in 0..4 {
            assert_eq!(table.next_state(0, s, e), code.next_state(0, s, e));
        }
    }
}

/// Lowering copies the declared timing unchanged: the scan period, each
/// input's debounce scans and each timer's preset. The IEC exporter, a
/// backend of its own that cannot use `codegen`, reads these from the
/// project; this test is what keeps that equal to reading them from the
/// lowered configuration (and the ST lockstep tests run both scan by scan).
#[test]
fn lowering_keeps_the_declared_timing_as_the_iec_exporter_reads_it() {
    let mut timed = 0;
    for (name, _) in PROJECTS {
        let project = plc_project::load(&model(name)).unwrap();
        let lowered = Lowered::new(&project, Backend::Table, &()).unwrap();
        let config = lowered.config();
        assert_eq!(config.scan_period_ms, project.scan_period_ms, "{name}");
        let debounce: Vec<u8> = config.input_specs().map(|i| i.debounce_scans).collect();
        let declared: Vec<u8> = project.inputs.iter().map(|i| i.debounce_scans).collect();
        assert_eq!(debounce, declared, "{name}: debounce scans");
        let presets: Vec<u32> = config.timer_specs().map(|t| t.preset_ms).collect();
        let declared: Vec<u32> = project.timers.iter().map(|t| t.preset_ms).collect();
        assert_eq!(presets, declared, "{name}: timer presets");
        timed += presets.len() + debounce.iter().filter(|&&d| d >= 2).count();
    }
    assert!(timed > 0, "some project declares timers or debouncing");
}
