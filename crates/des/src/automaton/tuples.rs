//! The component-state tuples of a product's states, stored compactly.
//!
//! A product of `k` components needs, per state, one component state per
//! component. When the components' state counts fit in 64 bits together
//! (`Σ ⌈log2 nⱼ⌉ ≤ 64`, e.g. 26 components of 2 to 4 states), each tuple
//! is one `u64` with a bit field per component: 8 bytes a state instead of
//! `4 × k`, and one word to hash and compare when interning. Otherwise
//! the tuples are `k` consecutive `u32`s in one flat vector.

/// Where each component's state sits in a packed tuple.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Layout {
    /// `(shift, mask)` per component.
    fields: Vec<(u32, u64)>,
}

impl Layout {
    /// The packed layout for components of `sizes` states, if the fields
    /// fit in 64 bits.
    pub(crate) fn packed(sizes: &[usize]) -> Option<Layout> {
        let mut shift = 0u32;
        let mut fields = Vec::with_capacity(sizes.len());
        for &n in sizes {
            // Bits for the states 0..n (at least one).
            let bits = usize::BITS - n.saturating_sub(1).leading_zeros();
            let bits = bits.max(1);
            if shift + bits > 64 {
                return None;
            }
            fields.push((shift, (1u64 << bits) - 1));
            shift += bits;
        }
        Some(Layout { fields })
    }

    /// Two 32-bit fields: a pair of states.
    pub(crate) fn pair() -> Layout {
        Layout {
            fields: vec![(0, u64::from(u32::MAX)), (32, u64::from(u32::MAX))],
        }
    }

    /// Packs `tuple` (which must fit the layout).
    #[inline]
    pub(crate) fn pack(&self, tuple: &[u32]) -> u64 {
        tuple
            .iter()
            .zip(&self.fields)
            .fold(0, |key, (&q, &(shift, _))| key | (u64::from(q) << shift))
    }

    /// Component `j` of `key`.
    #[inline]
    pub(crate) fn get(&self, key: u64, j: usize) -> u32 {
        let (shift, mask) = self.fields[j];
        ((key >> shift) & mask) as u32
    }

    /// Number of components.
    pub(crate) fn width(&self) -> usize {
        self.fields.len()
    }
}

/// The tuples of a product's states, in state order.
#[derive(Debug, Clone)]
pub(crate) enum Tuples {
    /// One `u64` per state, fields as `layout` says.
    Packed {
        /// The packed tuples.
        keys: Vec<u64>,
        /// The fields.
        layout: Layout,
    },
    /// `width` consecutive `u32`s per state.
    Flat {
        /// The tuples, one after the other.
        data: Vec<u32>,
        /// Components per tuple.
        width: usize,
    },
}

impl Default for Tuples {
    fn default() -> Self {
        Tuples::Flat {
            data: Vec::new(),
            width: 0,
        }
    }
}

impl Tuples {
    /// Number of components per tuple.
    pub(crate) fn width(&self) -> usize {
        match self {
            Tuples::Packed { layout, .. } => layout.width(),
            Tuples::Flat { width, .. } => *width,
        }
    }

    /// Component `j` of tuple `i`.
    #[inline]
    pub(crate) fn get(&self, i: usize, j: usize) -> u32 {
        match self {
            Tuples::Packed { keys, layout } => layout.get(keys[i], j),
            Tuples::Flat { data, width } => data[i * width + j],
        }
    }

    /// Approximate heap bytes.
    pub(crate) fn heap_bytes(&self) -> usize {
        match self {
            Tuples::Packed { keys, .. } => keys.capacity() * 8,
            Tuples::Flat { data, .. } => data.capacity() * 4,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_fields_round_trip_and_overflow_falls_back() {
        let layout = Layout::packed(&[1, 2, 3, 4, 5, 1 << 20]).unwrap();
        let tuple = [0, 1, 2, 3, 4, (1 << 20) - 1];
        let key = layout.pack(&tuple);
        let back: Vec<u32> = (0..6).map(|j| layout.get(key, j)).collect();
        assert_eq!(back, tuple);
        assert!(Layout::packed(&[1 << 20, 1 << 20, 1 << 20, 1 << 20]).is_none());
        assert!(Layout::packed(&[1 << 33, 1 << 33]).is_none());
        let pair = Layout::pair();
        assert_eq!(pair.get(pair.pack(&[u32::MAX, 7]), 0), u32::MAX);
        assert_eq!(pair.get(pair.pack(&[u32::MAX, 7]), 1), 7);
    }
}
