//! Table backend: a supervisor as bit-packed transition tables.
//!
//! The encoding is specified (with a worked example) in the executor's
//! `table` module, which decodes it; this module produces it. Layout
//! choice: dense (entry per state × event) or sparse (defined pairs only,
//! with row starts), whichever takes fewer words, dense on a tie.

use des::automaton::{Automaton, EventId, StateId};
use executor::table::{Rows, SupervisorTable};

/// Which target layout a table uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Layout {
    /// Every state × event pair.
    Dense,
    /// Defined pairs only.
    Sparse,
    /// A group of places of a Petri net (counters, `PRE`/`POST` words).
    Net,
}

/// The encoded tables of one supervisor, owned.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EncodedTable {
    /// Local events `m`.
    pub events: u16,
    /// Number of states `n`.
    pub states: u32,
    /// Bits per state.
    pub state_bits: u8,
    /// `n·m` defined-bits.
    pub defined: Vec<u32>,
    /// Packed targets.
    pub targets: Vec<u32>,
    /// Packed row starts (sparse layout); the mask of each counter (net
    /// layout).
    pub row_starts: Vec<u32>,
    /// Width of a row start (sparse layout only).
    pub start_bits: u8,
    /// The layout chosen.
    pub layout: Layout,
}

/// Bits needed to store every value in `0..=max` (at least 1).
pub fn bits_for(max: u64) -> u8 {
    (64 - max.leading_zeros()).max(1) as u8
}

/// Appends `value` as a `width`-bit entry at entry index `index`.
pub(crate) fn write_bits(words: &mut Vec<u32>, index: usize, width: u8, value: u32) {
    let width = width as usize;
    let bit = index * width;
    let end_word = (bit + width).div_ceil(32);
    if words.len() < end_word {
        words.resize(end_word, 0);
    }
    let (word, offset) = (bit / 32, bit % 32);
    words[word] |= value << offset;
    if offset + width > 32 {
        words[word + 1] |= value >> (32 - offset);
    }
}

fn words_for(bits: usize) -> usize {
    bits.div_ceil(32)
}

impl EncodedTable {
    /// Encodes `a`'s transition function over the local alphabet `local`
    /// (local index `i` is event `local[i]` of `a`).
    pub fn encode(a: &Automaton, local: &[EventId]) -> EncodedTable {
        let n = a.num_states();
        let m = local.len();
        let state_bits = bits_for(n.saturating_sub(1) as u64);
        let mut defined = vec![0u32; words_for(n * m)];
        let mut dense = vec![0u32; words_for(n * m * state_bits as usize)];
        let mut sparse = Vec::new();
        let mut starts = Vec::with_capacity(n);
        let mut count = 0usize;
        for s in 0..n {
            starts.push(count as u32);
            for (e, &event) in local.iter().enumerate() {
                if let Some(t) = a.successor(StateId(s as u32), event) {
                    let pair = s * m + e;
                    defined[pair / 32] |= 1 << (pair % 32);
                    write_bits(&mut dense, pair, state_bits, t.0);
                    write_bits(&mut sparse, count, state_bits, t.0);
                    count += 1;
                }
            }
        }
        let start_bits = bits_for(count as u64);
        let mut row_starts = Vec::new();
        for (s, &start) in starts.iter().enumerate() {
            write_bits(&mut row_starts, s, start_bits, start);
        }
        sparse.resize(words_for(count * state_bits as usize), 0);
        row_starts.resize(words_for(n * start_bits as usize), 0);
        let (layout, targets, row_starts, start_bits) =
            if sparse.len() + row_starts.len() < dense.len() {
                (Layout::Sparse, sparse, row_starts, start_bits)
            } else {
                (Layout::Dense, dense, Vec::new(), 0)
            };
        EncodedTable {
            events: m as u16,
            states: n as u32,
            state_bits,
            defined,
            targets,
            row_starts,
            start_bits,
            layout,
        }
    }

    /// A group of a Petri net in the net layout: `pre` and `post`, the
    /// packed input and output arc weights of each transition touching the
    /// group, `masks` the counter mask of each of its places, in a state of
    /// `bits` bits (lowering packs them: `crate::lower::nets`).
    pub fn net_group(bits: u8, pre: Vec<u32>, post: Vec<u32>, masks: Vec<u32>) -> EncodedTable {
        EncodedTable {
            events: pre.len() as u16,
            states: 1 << bits,
            state_bits: bits,
            defined: pre,
            targets: post,
            row_starts: masks,
            start_bits: 0,
            layout: Layout::Net,
        }
    }

    /// A borrowed view for the executor.
    pub fn view(&self) -> SupervisorTable<'_> {
        SupervisorTable {
            events: self.events,
            state_bits: self.state_bits,
            defined: &self.defined,
            targets: &self.targets,
            rows: match self.layout {
                Layout::Dense => Rows::Dense,
                Layout::Sparse => Rows::Sparse {
                    row_starts: &self.row_starts,
                    start_bits: self.start_bits,
                },
                Layout::Net => Rows::Net {
                    fields: &self.row_starts,
                },
            },
        }
    }

    /// Flash bytes of the tables (words only; the small header is shared
    /// by every encoding).
    pub fn bytes(&self) -> usize {
        4 * (self.defined.len() + self.targets.len() + self.row_starts.len())
    }

    /// Bytes of the naive encoding: a `u16` per state × event pair, with a
    /// sentinel for undefined pairs.
    pub fn naive_bytes(&self) -> usize {
        2 * self.states as usize * self.events as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use des::testing::auto;

    fn ids(a: &Automaton, names: &[&str]) -> Vec<EventId> {
        names.iter().map(|n| a.alphabet().id(n).unwrap()).collect()
    }

    #[test]
    fn the_worked_example_of_the_executor_docs() {
        let a = auto(
            "ex",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("1", "b", "2"), ("2", "a", "0")],
            &[],
        );
        let t = EncodedTable::encode(&a, &ids(&a, &["a", "b"]));
        assert_eq!((t.state_bits, t.defined.as_slice()), (2, &[0x19][..]));
        // Dense and sparse take one word each: dense wins the tie.
        assert_eq!(t.layout, Layout::Dense);
        assert_eq!(t.targets, [0x81]);
        assert_eq!(t.bytes(), 8);
        assert_eq!(t.naive_bytes(), 12);
    }

    #[test]
    fn sparse_rows_win_when_few_pairs_are_defined_and_decode_correctly() {
        // A chain of 40 states over 30 events, one transition per state.
        let events: Vec<(String, bool)> = (0..30).map(|i| (format!("e{i}"), i % 2 == 0)).collect();
        let event_refs: Vec<(&str, bool)> = events.iter().map(|(n, c)| (n.as_str(), *c)).collect();
        let names: Vec<String> = (0..41).map(|i| i.to_string()).collect();
        let trans: Vec<(&str, &str, &str)> = (0..40)
            .map(|i| {
                (
                    names[i].as_str(),
                    events[i % 30].0.as_str(),
                    names[i + 1].as_str(),
                )
            })
            .collect();
        let a = auto("chain", &event_refs, &trans, &[]);
        let local: Vec<EventId> = a.alphabet().ids().collect();
        let t = EncodedTable::encode(&a, &local);
        assert_eq!(t.layout, Layout::Sparse);
        assert!(t.bytes() * 4 < t.naive_bytes());
        let view = t.view();
        for s in a.states() {
            for (i, &e) in local.iter().enumerate() {
                assert_eq!(
                    view.next_state(s.0, i as u16),
                    a.successor(s, e).map(|x| x.0),
                    "state {s} event {i}"
                );
            }
        }
    }

    #[test]
    fn local_order_is_the_callers() {
        let a = auto(
            "ex",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("1", "b", "0")],
            &[],
        );
        let t = EncodedTable::encode(&a, &ids(&a, &["b", "a"]));
        let v = t.view();
        assert_eq!(v.next_state(0, 1), Some(1));
        assert_eq!(v.next_state(0, 0), None);
    }

    #[test]
    fn widths() {
        assert_eq!(bits_for(0), 1);
        assert_eq!(bits_for(1), 1);
        assert_eq!(bits_for(2), 2);
        assert_eq!(bits_for(255), 8);
        assert_eq!(bits_for(256), 9);
    }
}
