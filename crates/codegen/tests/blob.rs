//! Generated images written as one run of words (what a field update
//! loads into a flash slot) and read back: the same image, the same CRC,
//! the same scans.

use codegen::lower::{LogicImage, TableImage};
use executor::image;
use executor::memory::HeapMemory;
use executor::parse::Blob;
use executor::program::Program;
use executor::validate::validate;
use executor::{Controller, TableProgram};
use plc_project as project;
use std::path::Path;

fn model(name: &str) -> project::Project {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(name);
    project::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Every scan of `a` and `b` over the same pseudo-random inputs: the same
/// events, states, outputs and faults.
fn same_scans<A: Program, B: Program>(a: &A, b: &B, scans: u32) {
    let inputs = a.config().inputs.len();
    let mut ca = Controller::new(a, HeapMemory::for_config(&a.config())).unwrap();
    let mut cb = Controller::new(b, HeapMemory::for_config(&b.config())).unwrap();
    let mut seed = 0x2545_f491_u32;
    let mut raw = vec![false; inputs];
    for k in 0..scans {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        if inputs != 0 && seed % 3 == 0 {
            let i = (seed >> 8) as usize % inputs;
            raw[i] = !raw[i];
        }
        let (ra, rb) = (ca.scan(10 * k, &raw), cb.scan(10 * k, &raw));
        let a = (ra.executed, ra.unexpected, ra.states, ra.outputs, ra.fault);
        assert_eq!(
            a,
            (rb.executed, rb.unexpected, rb.states, rb.outputs, rb.fault),
            "scan {k}"
        );
    }
}

#[test]
fn a_generated_image_read_back_from_its_words_is_the_same_program() {
    for name in [
        "press.plc.toml",
        "crane.plc.toml",
        "agv.plc.toml",
        "conveyor.plc.toml",
    ] {
        let project = model(name);
        let program = TableImage::new(&project).unwrap();
        let words = image::words(&program);
        assert_eq!(4 * words.len(), image::bytes(&program), "{name}");
        let mut buffer = [0u8; 64];
        let blob = Blob::parse(&words, &mut buffer).unwrap_or_else(|e| panic!("{name}: {e}"));
        let tables: Vec<_> = blob.tables().collect();
        assert_eq!(tables.len(), blob.table_count());
        let parsed = TableProgram {
            config: blob.config,
            tables: &tables,
            crc: program.recorded_crc(),
        };
        assert_eq!(image::crc(&parsed), program.recorded_crc(), "{name}");
        assert_eq!(image::words(&parsed), words, "{name}");
        assert_eq!(validate(&parsed), Ok(()), "{name}");
        same_scans(&program, &parsed, 3_000);
    }
}

#[test]
fn a_logic_image_is_its_configuration_alone() {
    let program = LogicImage::new(&model("press.plc.toml")).unwrap();
    let words = image::words(&program);
    let mut buffer = [0u8; 64];
    let blob = Blob::parse(&words, &mut buffer).unwrap();
    assert_eq!(blob.table_count(), 0);
    assert_eq!(image::config_crc(&blob.config), program.recorded_crc());
}
