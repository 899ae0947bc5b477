//! Images written as one run of words and read back.

extern crate std;

use super::{Blob, ParseError};
use crate::image::{self, IMAGE_CRC};
use crate::program::Program;
use crate::rom_test::tests::{every_pool, ring, ring_keyed};
use crate::table::TableProgram;
use std::vec::Vec;

fn words_of<P: Program>(program: &P) -> Vec<u32> {
    let mut words = Vec::new();
    image::for_each_word(program, |w| words.push(w));
    words
}

fn crc_of(words: &[u32]) -> u32 {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_be_bytes()).collect();
    IMAGE_CRC.checksum(&bytes)
}

#[test]
fn an_image_read_back_is_the_same_image() {
    for program in [every_pool(), ring(16), ring_keyed(16)] {
        let words = words_of(&program);
        assert_eq!(4 * words.len(), image::bytes(&program));
        assert_eq!(
            crc_of(&words),
            image::crc(&program),
            "the blob's CRC is the image's"
        );
        let mut name = [0u8; 32];
        let blob = Blob::parse(&words, &mut name).unwrap();
        let tables: Vec<_> = blob.tables().collect();
        assert_eq!(tables, program.tables);
        let parsed = TableProgram {
            config: blob.config,
            tables: &tables,
            crc: program.crc,
        };
        assert_eq!(image::crc(&parsed), image::crc(&program));
        assert_eq!(words_of(&parsed), words);
        assert_eq!(blob.config.name, program.config.name);
    }
}

#[test]
fn a_blob_that_is_not_an_image_is_refused_without_a_panic() {
    let words = words_of(&every_pool());
    let parse = |words: &[u32]| {
        let mut name = [0u8; 32];
        Blob::parse(words, &mut name).map(|_| ())
    };
    assert_eq!(parse(&words), Ok(()));
    // Cut short anywhere, or grown.
    for n in 0..words.len() {
        assert_eq!(parse(&words[..n]), Err(ParseError::Short), "{n} words");
    }
    let mut longer = words.clone();
    longer.push(0);
    assert_eq!(parse(&longer), Err(ParseError::Trailing));
    // A name longer than the buffer.
    let mut name = [0u8; 4];
    assert_eq!(
        Blob::parse(&words, &mut name).map(|_| ()),
        Err(ParseError::Name)
    );
    // Every word of the image flipped, one bit at a time: refused or read,
    // never a panic; a header flag out of range is refused.
    for k in 0..words.len() {
        for bit in [0, 7, 16, 31] {
            let mut flipped = words.clone();
            flipped[k] ^= 1 << bit;
            let _ = parse(&flipped);
        }
    }
    let mut flag = words.clone();
    flag[6] = 2;
    assert_eq!(parse(&flag), Err(ParseError::Header { word: 6 }));
}

#[test]
fn a_loaded_image_runs_only_after_every_generator_check() {
    use super::{load, Refusal};
    use crate::table::SupervisorTable;
    let program = ring(16);
    let words = words_of(&program);
    let (mut name, mut tables) = ([0u8; 32], [SupervisorTable::EMPTY; 4]);
    let loaded = load(&words, &mut name, &mut tables, program.crc).expect("the ring loads");
    assert_eq!(words_of(&loaded), words);
    assert_eq!(image::crc(&loaded), image::crc(&program));

    // No room for its table.
    let (mut name, mut none) = ([0u8; 32], [SupervisorTable::EMPTY; 0]);
    let refused = load(&words, &mut name, &mut none, 0).map(|_| ());
    assert_eq!(refused, Err(Refusal::Tables { count: 1, room: 0 }));
    assert_eq!(Refusal::Tables { count: 1, room: 0 }.code(), 0x200);

    // Words that are no image.
    let (mut name, mut tables) = ([0u8; 32], [SupervisorTable::EMPTY; 4]);
    let refused = load(&words[..5], &mut name, &mut tables, 0).map(|_| ());
    assert_eq!(refused, Err(Refusal::Parse(ParseError::Short)));

    // Every word's lowest and highest bit flipped, one at a time: refused,
    // or a program that every generator check accepts (flipped words of a
    // table's targets can still name states), never a panic; the dense
    // ring and the keyed one.
    let keyed = words_of(&ring_keyed(16));
    let (mut name, mut tables) = ([0u8; 32], [SupervisorTable::EMPTY; 4]);
    assert!(
        load(&keyed, &mut name, &mut tables, 0).is_ok(),
        "the keyed ring loads"
    );
    for words in [words, keyed] {
        let mut accepted = 0;
        for k in 0..words.len() {
            for bit in [0, 31] {
                let mut flipped = words.clone();
                flipped[k] ^= 1 << bit;
                let (mut name, mut tables) = ([0u8; 32], [SupervisorTable::EMPTY; 4]);
                match load(&flipped, &mut name, &mut tables, 0) {
                    Ok(p) => {
                        accepted += 1;
                        assert_eq!(crate::validate::validate_generated(&p), Ok(()));
                    }
                    Err(Refusal::Structure(invalid)) => {
                        assert!((1..=24).contains(&invalid.flaw.code()), "{invalid:?}");
                    }
                    Err(_) => {}
                }
            }
        }
        assert!(accepted < 2 * words.len(), "some flips are refused");
    }
}

#[test]
fn a_keyed_table_header_with_bad_widths_is_refused() {
    let program = ring_keyed(16);
    let words = words_of(&program);
    let table = program.tables[0];
    let crate::table::Rows::Keyed { states, .. } = table.rows else {
        unreachable!()
    };
    // The table's header: the 7 words before its three runs.
    let header = words.len() - states.len() - table.targets.len() - table.defined.len() - 7;
    assert_eq!(
        words[header + 2..header + 4],
        [3, 9 | 1 << 8],
        "keyed, widths"
    );
    let parse = |k: usize, value: u32| {
        let mut changed = words.clone();
        changed[header + k] = value;
        let mut name = [0u8; 32];
        Blob::parse(&changed, &mut name).map(|_| ())
    };
    assert_eq!(parse(3, 9 | 1 << 8), Ok(()));
    assert_eq!(parse(3, 24 | 8 << 8), Ok(()), "32 bits a record");
    for widths in [0, 9, 1 << 8, 24 | 9 << 8, 9 | 1 << 16, 9 | 0x100 << 8] {
        assert_eq!(
            parse(3, widths),
            Err(ParseError::Header { word: 3 }),
            "{widths:#x}"
        );
    }
    assert!(
        matches!(parse(2, 4), Err(ParseError::Header { .. })),
        "no layout 4"
    );
}
