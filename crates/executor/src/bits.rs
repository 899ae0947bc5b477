//! Bit sets in `u32` words: member `i` is bit `i % 32` of word `i / 32`.

/// `true` when `i` is in `set`.
#[inline]
pub fn contains(set: &[u32], i: usize) -> bool {
    set.get(i / 32).is_some_and(|w| (w >> (i % 32)) & 1 == 1)
}

/// Adds `i` to `set` (no effect past its end).
#[inline]
pub(crate) fn insert(set: &mut [u32], i: usize) {
    if let Some(w) = set.get_mut(i / 32) {
        *w |= 1 << (i % 32);
    }
}
