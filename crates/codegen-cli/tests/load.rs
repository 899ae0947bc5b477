//! `codegen load` against a simulated PLC on the other end of a
//! pseudo-terminal: the field-update endpoint over RAM slots, as the
//! firmware runs it on its serial port.

#![cfg(unix)]

use field_update::header::{version, HEADER_WORDS};
use field_update::host::SlotFile;
use field_update::loader::{Endpoint, Loader, Running};
use field_update::slot::{Check, RamSlots, Slot, SlotStore};
use field_update::CRC_ALGORITHM;
use plc_project as project;
use serialport::{SerialPort, TTYPort};
use std::io::{Read, Write};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::{self, JoinHandle};
use std::time::Duration;

static CRC: crc::Crc<u32> = crc::Crc::<u32>::new(&CRC_ALGORITHM);

/// The simulated PLC's wiring signature.
const WIRING: u32 = 0x0BAD_CAFE;

/// Refuses images whose first word is 0 (code 9).
struct FirstWordCheck;
impl Check for FirstWordCheck {
    fn wiring(&self) -> u32 {
        WIRING
    }
    fn check(&mut self, image: &[u32]) -> Result<(), u16> {
        if image.first() == Some(&0) {
            Err(9)
        } else {
            Ok(())
        }
    }
}

/// The PLC side: answers on `master` until `stop`; returns its slots.
fn plc(mut master: TTYPort, stop: Arc<AtomicBool>) -> JoinHandle<(Vec<u32>, Vec<u32>)> {
    thread::spawn(move || {
        let (mut a, mut b) = (vec![u32::MAX; 1024], vec![u32::MAX; 1024]);
        let mut endpoint = Endpoint::new(Loader::new(&CRC, None, &FirstWordCheck));
        master
            .set_timeout(Duration::from_millis(20))
            .expect("timeout");
        let running = Running {
            name: "press",
            image_crc: 0x1234_5678,
        };
        let mut byte = [0u8; 1];
        while !stop.load(Ordering::Relaxed) {
            if !matches!(master.read(&mut byte), Ok(1)) {
                continue;
            }
            let mut slots = RamSlots::new(&mut a, &mut b);
            if let Some(frame) = endpoint.receive(byte[0], &mut slots, running) {
                master.write_all(frame).expect("answer");
            }
            while endpoint.loader().is_checking() {
                if let Some((_, frame)) = endpoint.poll(&mut slots, &mut FirstWordCheck, 64) {
                    master.write_all(frame).expect("answer");
                }
            }
        }
        (a, b)
    })
}

fn codegen(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_codegen"))
        .args(args)
        .output()
        .expect("codegen runs")
}

#[test]
fn a_slot_file_is_loaded_over_a_serial_port_and_a_bad_one_is_refused() {
    let (master, slave) = TTYPort::pair().expect("a pseudo-terminal");
    let port = slave.name().expect("the slave's path");
    let stop = Arc::new(AtomicBool::new(false));
    let plc = plc(master, Arc::clone(&stop));
    let dir = tempfile::tempdir().expect("temp dir");

    let image: Vec<u32> = (1..=300u32)
        .map(|k| k.wrapping_mul(2_654_435_761))
        .collect();
    let good = SlotFile::new(image.clone(), 1, version(1, 2, 3), WIRING, &CRC);
    let good_path = dir.path().join("good.bin");
    std::fs::write(&good_path, good.to_bytes(&CRC)).expect("written");
    let good_path = good_path.to_str().expect("utf-8");
    let out = codegen(&["load", good_path, "--port", &port, "--timeout-ms", "500"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        stdout,
        "before: `press` runs from the program built into the firmware, image CRC 0x12345678, \
         wiring 0x0badcafe\n\
         loaded 300 words into slot A (sequence 1): it runs from the next scan\n\
         after: `press` runs from slot A, version 1.2.3, image CRC 0x12345678, wiring 0x0badcafe\n"
    );

    let mut bad_image = image.clone();
    bad_image[0] = 0;
    let bad = SlotFile::new(bad_image, 1, version(2, 0, 0), WIRING, &CRC);
    let bad_path = dir.path().join("bad.bin");
    std::fs::write(&bad_path, bad.to_bytes(&CRC)).expect("written");
    let out = codegen(&["load", bad_path.to_str().expect("utf-8"), "--port", &port]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(
            "the PLC refused Commit: the image was checked and refused: structure check code 0x0009"
        ),
        "{stderr}"
    );

    // An image made for other wiring is refused at `Begin`, before the
    // PLC erases anything.
    let other = SlotFile::new(image.clone(), 1, version(3, 0, 0), WIRING ^ 1, &CRC);
    let other_path = dir.path().join("other.bin");
    std::fs::write(&other_path, other.to_bytes(&CRC)).expect("written");
    let out = codegen(&["load", other_path.to_str().expect("utf-8"), "--port", &port]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(
            "the PLC refused Begin: the image was made for other wiring (signature 0x0badcaff; \
             this firmware's is 0x0badcafe"
        ),
        "{stderr}"
    );

    // A slot file damaged on disk never leaves the PC.
    let mut damaged = good.to_bytes(&CRC);
    damaged[HEADER_WORDS * 4 + 5] ^= 1;
    std::fs::write(dir.path().join("damaged.bin"), damaged).expect("written");
    let out = codegen(&[
        "load",
        dir.path().join("damaged.bin").to_str().expect("utf-8"),
        "--port",
        &port,
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a slot file: the image's CRC is"));

    let out = codegen(&["--json", "load", "--port", &port]);
    let status: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(status["before"]["slot"], "A");
    assert_eq!(status["before"]["version"], "1.2.3");
    assert_eq!(status["before"]["wiring"], "0x0badcafe");

    stop.store(true, Ordering::Relaxed);
    drop(slave);
    let (mut a, mut b) = plc.join().expect("the PLC thread ends");
    let slots = RamSlots::new(&mut a, &mut b);
    assert_eq!(
        &slots.contents(Slot::A)[HEADER_WORDS..HEADER_WORDS + 300],
        &image[..]
    );
    assert_eq!(
        slots.contents(Slot::B)[0],
        u32::MAX,
        "the refused image got no header"
    );
}

/// The field-update check of the firmware: the image read back and
/// checked as a generator checks it (`executor::parse::load`).
struct ExecutorCheck;
impl Check for ExecutorCheck {
    fn wiring(&self) -> u32 {
        0
    }
    fn check(&mut self, image: &[u32]) -> Result<(), u16> {
        let mut name = vec![0u8; 256];
        let mut tables = vec![executor::table::SupervisorTable::EMPTY; 64];
        executor::parse::load(image, &mut name, &mut tables, 0)
            .map(|_| ())
            .map_err(|refusal| refusal.code())
    }
}

/// The words of a slot file written by `codegen image`.
fn image_of(project: &str, dir: &std::path::Path) -> Vec<u32> {
    let path = dir.join("image.bin");
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../");
    let out = codegen(&[
        "image",
        &format!("{root}{project}"),
        "-o",
        path.to_str().expect("utf-8"),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let file =
        SlotFile::parse(&std::fs::read(&path).expect("written"), &CRC).expect("a valid slot file");
    let project = project::load(std::path::Path::new(&format!("{root}{project}")))
        .expect("the project loads");
    assert_eq!(
        file.header.wiring,
        codegen::board::wiring_signature(&project),
        "the header records the project's wiring"
    );
    file.image
}

/// Loads `image` announcing `image_crc`; the outcome, and the slot's
/// image words when it switched.
fn load_direct(image: &[u32], image_crc: u32) -> (field_update::loader::Outcome, Option<Vec<u32>>) {
    use field_update::loader::{Outcome, Reply};
    use field_update::protocol::{data_requests, Request};
    let (mut a, mut b) = (
        vec![u32::MAX; image.len() + 16],
        vec![u32::MAX; image.len() + 16],
    );
    let mut slots = RamSlots::new(&mut a, &mut b);
    let mut loader = Loader::new(&CRC, None, &ExecutorCheck);
    let begin = Request::Begin {
        words: image.len() as u32,
        image_crc,
        version: 1,
        wiring: 0,
    };
    let bytes: Vec<u8> = image.iter().flat_map(|w| w.to_le_bytes()).collect();
    for request in [begin]
        .into_iter()
        .chain(data_requests(&bytes))
        .chain([Request::Commit])
    {
        match loader.handle(request, &mut slots) {
            Reply::Later => loop {
                if let Some(outcome) = loader.poll(&mut slots, &mut ExecutorCheck, 1 << 12) {
                    let words = matches!(outcome, Outcome::Switched(_)).then(|| {
                        slots.contents(Slot::A)[HEADER_WORDS..HEADER_WORDS + image.len()].to_vec()
                    });
                    return (outcome, words);
                }
            },
            Reply::Send(field_update::protocol::Response::Refused(why)) => {
                return (Outcome::Refused(why), None)
            }
            _ => {}
        }
    }
    unreachable!("Commit is answered by poll")
}

/// Runs `image` (loaded from a slot) for `scans` scans of pseudo-random
/// inputs; with `reference`, compares every scan with it.
fn run_loaded(
    image: &[u32],
    reference: Option<&codegen::lower::Lowered>,
    scans: u32,
    mut seed: u32,
) {
    use executor::memory::HeapMemory;
    use executor::program::Program;
    use executor::Controller;
    let mut name = vec![0u8; 256];
    let mut tables = vec![executor::table::SupervisorTable::EMPTY; 64];
    let crc = field_update::crc_of_words(&CRC, image);
    let loaded = executor::parse::load(image, &mut name, &mut tables, crc).expect("checked");
    let inputs = loaded.config().inputs.len();
    let mut c = Controller::new(&loaded, HeapMemory::for_config(&loaded.config())).expect("fits");
    let mut r =
        reference.map(|p| Controller::new(p, HeapMemory::for_config(&p.config())).expect("fits"));
    let mut raw = vec![false; inputs];
    for k in 0..scans {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        if inputs != 0 && seed % 3 == 0 {
            let i = (seed >> 8) as usize % inputs;
            raw[i] = !raw[i];
        }
        let got = c.scan(10 * k, &raw);
        let got = (
            got.executed.to_vec(),
            got.states.to_vec(),
            got.outputs.to_vec(),
            got.fault,
        );
        if let Some(r) = r.as_mut() {
            let want = r.scan(10 * k, &raw);
            assert_eq!(
                got,
                (
                    want.executed.to_vec(),
                    want.states.to_vec(),
                    want.outputs.to_vec(),
                    want.fault
                ),
                "scan {k}"
            );
        }
    }
}

#[test]
fn an_image_from_codegen_image_loads_and_runs_as_the_compiled_program() {
    let dir = tempfile::tempdir().expect("temp dir");
    for project in [
        "models/press.plc.toml",
        "models/petri/cell/cell.plc.toml",
        "models/agv.plc.toml",
    ] {
        let image = image_of(project, dir.path());
        let (outcome, words) = load_direct(&image, field_update::crc_of_words(&CRC, &image));
        assert!(
            matches!(outcome, field_update::loader::Outcome::Switched(_)),
            "{project}: {outcome:?}"
        );
        let loaded = project::load(std::path::Path::new(&format!(
            "{}/../../{project}",
            env!("CARGO_MANIFEST_DIR")
        )))
        .expect("loads");
        let lowered = codegen::lower::Lowered::new(&loaded, codegen::backend::Backend::Table, &())
            .expect("lowers");
        run_loaded(
            &words.expect("switched"),
            Some(&lowered),
            2_000,
            0x9e37_79b9,
        );
    }
}

/// Issue 27's goal: no corrupt image runs, in at least 10^5 damaged
/// images. Damaged images whose announced CRC is the original's must all
/// be refused; hostile ones (CRC recomputed over the damage) are refused
/// or are programs every generator check accepts, which then run without
/// a panic.
#[test]
fn no_damaged_image_runs_in_a_hundred_thousand() {
    use field_update::loader::Outcome;
    let dir = tempfile::tempdir().expect("temp dir");
    let images: Vec<Vec<u32>> = [
        "models/press.plc.toml",
        "models/conveyor.plc.toml",
        "models/crane.plc.toml",
        "models/petri/mixers.plc.toml",
        "models/petri/cell/cell.plc.toml",
    ]
    .iter()
    .map(|p| image_of(p, dir.path()))
    .collect();
    let mut seed = 0x1234_5679_u32;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed
    };
    let (mut corrupt_refused, mut hostile_refused, mut hostile_ran) = (0u32, 0u32, 0u32);
    const CASES: u32 = 100_000;
    for case in 0..CASES {
        let original = &images[case as usize % images.len()];
        let mut damaged = original.clone();
        let k = next() as usize % damaged.len();
        match next() % 4 {
            0 => damaged[k] ^= 1 << (next() % 32),
            1 => damaged[k] = next(),
            2 => damaged[k] = damaged[k].wrapping_add(if next() % 2 == 0 { 1 } else { u32::MAX }),
            _ => damaged.truncate(k.max(1)),
        }
        if damaged == *original {
            continue;
        }
        // Damaged in the slot: the CRC announced is the original's.
        let (outcome, _) = load_direct(&damaged, field_update::crc_of_words(&CRC, original));
        assert!(
            matches!(outcome, Outcome::Refused(_)),
            "case {case}: a corrupt image was accepted"
        );
        corrupt_refused += 1;
        // Hostile: the CRC announced is the damaged image's own.
        match load_direct(&damaged, field_update::crc_of_words(&CRC, &damaged)) {
            (Outcome::Switched(_), Some(words)) => {
                hostile_ran += 1;
                if hostile_ran % 16 == 0 {
                    run_loaded(&words, None, 50, case);
                }
            }
            (Outcome::Refused(_), _) => hostile_refused += 1,
            other => panic!("case {case}: {other:?}"),
        }
    }
    eprintln!(
        "{CASES} damaged images: {corrupt_refused} corrupt refused; hostile: {hostile_refused} refused, {hostile_ran} accepted as programs"
    );
    assert!(corrupt_refused >= CASES * 99 / 100);
    assert!(hostile_refused > 0 && hostile_ran > 0);
}
