//! Images written as one run of words and read back.

extern crate std;

use super::{Blob, ParseError};
use crate::image::{self, IMAGE_CRC};
use crate::program::Program;
use crate::rom_test::tests::{every_pool, ring};
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
    for program in [every_pool(), ring(16)] {
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
