//! Input image: debounce and edge detection.

use crate::memory::Ram;
use crate::program::{Config, Index};

/// Samples `raw` into the filtered image F\[k\], keeping F\[k-1\].
///
/// An input with `debounce_scans = d > 1` follows its raw value only after
/// the raw value has differed from the filtered one for `d` consecutive
/// scans, counting this one. On the first scan the filtered image is the
/// raw sample itself and F\[-1\] = F\[0\], so scan 0 has no edges. A raw
/// image shorter than the input list reads the missing inputs as 0.
pub(crate) fn sample(config: &Config<'_>, ram: &mut Ram<'_>, raw: &[bool], first: bool) {
    for (i, spec) in config.inputs.iter().enumerate() {
        let value = raw.get(i).copied().unwrap_or(false);
        if first {
            ram.filtered[i] = value;
            ram.previous[i] = value;
            ram.debounce[i] = 0;
            continue;
        }
        ram.previous[i] = ram.filtered[i];
        if spec.debounce_scans <= 1 || value == ram.filtered[i] {
            ram.filtered[i] = value;
            ram.debounce[i] = 0;
        } else {
            ram.debounce[i] = ram.debounce[i].saturating_add(1);
            if ram.debounce[i] >= spec.debounce_scans {
                ram.filtered[i] = value;
                ram.debounce[i] = 0;
            }
        }
    }
}

/// The OR of the listed inputs in `image`.
#[inline]
pub(crate) fn any(list: &[Index], image: &[bool]) -> bool {
    list.iter()
        .any(|&i| image.get(i as usize).copied().unwrap_or(false))
}

/// `true` when every listed input is 1 in `image`.
#[inline]
pub(crate) fn all(list: &[Index], image: &[bool]) -> bool {
    list.iter()
        .all(|&i| image.get(i as usize).copied().unwrap_or(false))
}

/// Rising edge of the OR of `list` between F\[k-1\] and F\[k\].
#[inline]
pub(crate) fn rising(list: &[Index], ram: &Ram<'_>) -> bool {
    any(list, ram.filtered) && !any(list, ram.previous)
}

/// Falling edge of the OR of `list`.
#[inline]
pub(crate) fn falling(list: &[Index], ram: &Ram<'_>) -> bool {
    !any(list, ram.filtered) && any(list, ram.previous)
}
