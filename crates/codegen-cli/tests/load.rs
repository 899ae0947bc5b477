//! `codegen load` against a simulated PLC on the other end of a
//! pseudo-terminal: the field-update endpoint over RAM slots, as the
//! firmware runs it on its serial port.

#![cfg(unix)]

use field_update::header::{version, HEADER_WORDS};
use field_update::host::SlotFile;
use field_update::loader::{Endpoint, Loader, Running};
use field_update::slot::{Check, RamSlots, Slot, SlotStore};
use field_update::CRC_ALGORITHM;
use serialport::{SerialPort, TTYPort};
use std::io::{Read, Write};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::{self, JoinHandle};
use std::time::Duration;

static CRC: crc::Crc<u32> = crc::Crc::<u32>::new(&CRC_ALGORITHM);

/// Refuses images whose first word is 0 (code 9).
struct FirstWordCheck;
impl Check for FirstWordCheck {
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
        let mut endpoint = Endpoint::new(Loader::new(&CRC, None));
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
    let good = SlotFile::new(image.clone(), 1, version(1, 2, 3), &CRC);
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
        "before: `press` runs from the program built into the firmware, image CRC 0x12345678\n\
         loaded 300 words into slot A (sequence 1): it runs from the next scan\n\
         after: `press` runs from slot A, version 1.2.3, image CRC 0x12345678\n"
    );

    let mut bad_image = image.clone();
    bad_image[0] = 0;
    let bad = SlotFile::new(bad_image, 1, version(2, 0, 0), &CRC);
    let bad_path = dir.path().join("bad.bin");
    std::fs::write(&bad_path, bad.to_bytes(&CRC)).expect("written");
    let out = codegen(&["load", bad_path.to_str().expect("utf-8"), "--port", &port]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("the PLC refused Commit: Rejected(Structure(9))"),
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
