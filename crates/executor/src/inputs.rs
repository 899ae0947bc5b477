//! Input image: packing, debounce and edge detection, 32 inputs per word.
//!
//! Images are bit sets (bit `i % 32` of word `i / 32` is input `i`), so
//! the filter, the edges and every binding are a few operations per word,
//! whatever the number of inputs: an unfiltered input takes its raw bit by
//! one AND/OR per word, only debounced inputs have a counter, and the set
//! of inputs that changed is `F[k] ^ F[k-1]`.

use crate::bits;
use crate::memory::Ram;
use crate::program::{Config, InputSpec};

/// Packs one value per input into `words` (inputs past `raw`'s end read
/// as 0; values past `inputs` are ignored).
pub(crate) fn pack(raw: &[bool], inputs: usize, words: &mut [u32]) {
    let raw = raw.get(..inputs).unwrap_or(raw);
    let mut chunks = raw.chunks(32);
    for word in words.iter_mut() {
        *word = chunks.next().map_or(0, |chunk| {
            chunk
                .iter()
                .enumerate()
                .fold(0, |w, (b, &v)| w | (u32::from(v) << b))
        });
    }
}

/// Copies packed raw values into `words`, clearing the bits past the last
/// input (and reading missing words as 0).
pub(crate) fn copy_packed(raw: &[u32], inputs: usize, words: &mut [u32]) {
    for (k, word) in words.iter_mut().enumerate() {
        *word = raw.get(k).copied().unwrap_or(0) & valid_bits(k, inputs);
    }
}

/// The bits of word `k` that stand for one of `inputs` inputs.
#[inline]
fn valid_bits(k: usize, inputs: usize) -> u32 {
    match inputs.saturating_sub(k * 32) {
        n if n >= 32 => u32::MAX,
        n => (1u32 << n) - 1,
    }
}

/// Filters the raw image (`ram.raw`) into F\[k\] (`ram.filtered`), keeping
/// F\[k-1\] (`ram.previous`); `true` when some filtered value changed.
/// `counting` tells whether some debounce counter is not 0, before and
/// after.
///
/// A debounced input (`debounce_scans = d ≥ 2`) follows its raw value only
/// after the raw value has differed from the filtered one for `d`
/// consecutive scans, counting this one; every other input takes its raw
/// value. On the first scan the filtered image is the raw sample itself
/// and F\[-1\] = F\[0\], so scan 0 has no edges.
pub(crate) fn sample(
    config: &Config<'_>,
    ram: &mut Ram<'_>,
    first: bool,
    counting: &mut bool,
) -> bool {
    if first {
        ram.filtered.copy_from_slice(ram.raw);
        ram.previous.copy_from_slice(ram.raw);
        ram.debounce.fill(0);
        *counting = false;
        return false;
    }
    let debounced = config.debounce_mask.of(config.input_masks);
    let mut differing = 0;
    for k in 0..ram.filtered.len() {
        let old = ram.filtered[k];
        let held = debounced.get(k).copied().unwrap_or(0);
        ram.previous[k] = old;
        ram.filtered[k] = (ram.raw[k] & !held) | (old & held);
        differing |= (ram.raw[k] ^ old) & held;
    }
    // With no debounced input differing and every counter at 0 there is
    // nothing to count or clear.
    if differing != 0 || *counting {
        *counting = debounce(config, ram);
    }
    ram.filtered
        .iter()
        .zip(ram.previous.iter())
        .any(|(now, before)| now != before)
}

/// Steps the counter of every debounced input; an input whose raw value
/// has differed for its `debounce_scans` takes it. `true` when some
/// counter is left above 0.
fn debounce(config: &Config<'_>, ram: &mut Ram<'_>) -> bool {
    let mut counting = false;
    for (count, &i) in ram.debounce.iter_mut().zip(config.debounced) {
        let (k, bit) = (i as usize / 32, 1u32 << (i % 32));
        let (Some(raw), Some(filtered)) = (ram.raw.get(k), ram.filtered.get_mut(k)) else {
            continue;
        };
        if (raw ^ *filtered) & bit == 0 {
            *count = 0;
            continue;
        }
        *count = count.saturating_add(1);
        let scans = config
            .inputs
            .get(i as usize)
            .map_or(0, |s| InputSpec::from_words(s).debounce_scans);
        if *count >= scans {
            *filtered ^= bit;
            *count = 0;
        }
        counting |= *count != 0;
    }
    counting
}

/// `true` when some input of `mask` is 1 in `image`.
#[inline]
pub(crate) fn any(mask: &[u32], image: &[u32]) -> bool {
    mask.iter().zip(image).any(|(m, w)| m & w != 0)
}

/// `true` when every input of `mask` is 1 in `image`.
#[inline]
pub(crate) fn all(mask: &[u32], image: &[u32]) -> bool {
    mask.iter()
        .enumerate()
        .all(|(k, m)| image.get(k).copied().unwrap_or(0) & m == *m)
}

/// Rising edge of the OR of `mask` between F\[k-1\] and F\[k\].
#[inline]
pub(crate) fn rising(mask: &[u32], ram: &Ram<'_>) -> bool {
    any(mask, ram.filtered) && !any(mask, ram.previous)
}

/// Falling edge of the OR of `mask`.
#[inline]
pub(crate) fn falling(mask: &[u32], ram: &Ram<'_>) -> bool {
    !any(mask, ram.filtered) && any(mask, ram.previous)
}

/// `true` when input `i` rose between F\[k-1\] and F\[k\].
#[inline]
pub(crate) fn input_rose(i: usize, ram: &Ram<'_>) -> bool {
    bits::contains(ram.filtered, i) && !bits::contains(ram.previous, i)
}

/// `true` when input `i` is 1 in F\[k\].
#[inline]
pub(crate) fn input_on(i: usize, ram: &Ram<'_>) -> bool {
    bits::contains(ram.filtered, i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_puts_input_i_at_bit_i_mod_32_of_word_i_div_32() {
        let mut raw = [false; 40];
        raw[0] = true;
        raw[33] = true;
        let mut words = [u32::MAX; 2];
        pack(&raw, 40, &mut words);
        assert_eq!(words, [1, 2]);
        pack(&raw[..1], 40, &mut words);
        assert_eq!(words, [1, 0], "missing inputs read as 0");
        pack(&[true; 40], 33, &mut words);
        assert_eq!(words, [u32::MAX, 1], "values past the inputs are ignored");
    }

    #[test]
    fn packed_images_lose_the_bits_of_no_input() {
        let mut words = [0; 2];
        copy_packed(&[u32::MAX, u32::MAX], 35, &mut words);
        assert_eq!(words, [u32::MAX, 0b111]);
        copy_packed(&[5], 35, &mut words);
        assert_eq!(words, [5, 0], "missing words read as 0");
        assert_eq!(valid_bits(0, 32), u32::MAX);
        assert_eq!(valid_bits(1, 32), 0);
    }

    #[test]
    fn masks_test_sets_of_inputs_word_by_word() {
        let image = [0b0110, 0b1];
        assert!(any(&[0b0100, 0], &image));
        assert!(!any(&[0b1001, 0b10], &image));
        assert!(all(&[0b0110, 0b1], &image));
        assert!(!all(&[0b0111, 0], &image));
        assert!(all(&[0, 0], &image), "the empty set holds");
        assert!(!all(&[0, 0, 1], &image), "words past the image read as 0");
    }
}
