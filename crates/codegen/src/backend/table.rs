//! Table backend: a supervisor as bit-packed transition tables.
//!
//! The encoding is specified (with a worked example) in the executor's
//! `table` module, which decodes it; this module produces it. Layout
//! choice: dense (entry per state × event), sparse (defined pairs only,
//! with row starts) or keyed (sparse targets, each distinct row of
//! defined-bits stored once, a key and a row start per state): the fewer
//! words of dense and sparse (dense on a tie), unless keyed saves at least
//! an eighth of them ([`KEYED_SHARE`]).

use des::automaton::{Automaton, EventId, StateId};
use executor::table::{keyed_record, keyed_stride, Rows, SupervisorTable};

/// Which target layout a table uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Layout {
    /// Every state × event pair.
    Dense,
    /// Defined pairs only.
    Sparse,
    /// Defined pairs only, the distinct rows of defined-bits as a
    /// dictionary and a (key, row start) record per state.
    Keyed,
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
    /// `n·m` defined-bits; the distinct rows of them (keyed layout).
    pub defined: Vec<u32>,
    /// Packed targets.
    pub targets: Vec<u32>,
    /// Packed row starts (sparse layout); the mask of each counter (net
    /// layout); packed records of a key and a row start (keyed layout).
    pub row_starts: Vec<u32>,
    /// Width of a row start (sparse and keyed layouts only).
    pub start_bits: u8,
    /// Width of a row key (keyed layout only).
    pub key_bits: u8,
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

/// The keyed layout's dictionary and records from the `n·m` defined-bits
/// `defined` and each state's row start (entries of `start_bits` bits):
/// the distinct rows in order of first appearance (one every
/// [`keyed_stride`] bits), a record of `key |
/// start << key_bits` per state, and `key_bits`. `None` when a record
/// would not fit in 32 bits.
fn keyed_rows(
    defined: &[u32],
    n: usize,
    m: usize,
    starts: &[u32],
    start_bits: u8,
) -> Option<(Vec<u32>, Vec<u32>, u8)> {
    let row_of = |s: usize| -> Vec<bool> {
        (0..m)
            .map(|e| executor::table::bit(defined, s * m + e))
            .collect()
    };
    let mut keys: std::collections::HashMap<Vec<bool>, u32> = Default::default();
    let mut rows: Vec<Vec<bool>> = Vec::new();
    let state_keys: Vec<u32> = (0..n)
        .map(|s| {
            let row = row_of(s);
            *keys.entry(row.clone()).or_insert_with(|| {
                rows.push(row);
                rows.len() as u32 - 1
            })
        })
        .collect();
    let key_bits = bits_for(rows.len().saturating_sub(1) as u64);
    let record_bits = key_bits + start_bits;
    if record_bits > 32 {
        return None;
    }
    let stride = keyed_stride(m);
    let mut dictionary = vec![0u32; words_for(rows.len() * stride)];
    for (r, row) in rows.iter().enumerate() {
        for (e, _) in row.iter().enumerate().filter(|(_, &d)| d) {
            let bit = r * stride + e;
            dictionary[bit / 32] |= 1 << (bit % 32);
        }
    }
    let mut records = Vec::new();
    for (s, (&key, &start)) in state_keys.iter().zip(starts).enumerate() {
        write_bits(&mut records, s, record_bits, key | start << key_bits);
    }
    records.resize(words_for(n * record_bits as usize), 0);
    Some((dictionary, records, key_bits))
}

/// The keyed layout is chosen when it takes at most this share
/// (numerator, denominator) of the words of the better of dense and
/// sparse: 7/8, at least an eighth saved.
pub const KEYED_SHARE: (usize, usize) = (7, 8);

impl EncodedTable {
    /// Encodes `a`'s transition function over the local alphabet `local`
    /// (local index `i` is event `local[i]` of `a`), in the layout of
    /// fewest words of dense and sparse (dense on a tie), or keyed when
    /// it saves at least an eighth of those ([`KEYED_SHARE`]).
    pub fn encode(a: &Automaton, local: &[EventId]) -> EncodedTable {
        let mut candidates = Self::candidates(a, local).into_iter();
        let dense = candidates
            .next()
            .expect("the dense layout is always a candidate");
        let sparse = candidates
            .next()
            .expect("the sparse layout is always a candidate");
        let best = if sparse.words() < dense.words() {
            sparse
        } else {
            dense
        };
        // Keyed only when it saves a real share: its lookup reads one
        // word more, and a program with a keyed table links its decoder.
        match candidates.next() {
            Some(keyed) if keyed.words() * KEYED_SHARE.1 <= best.words() * KEYED_SHARE.0 => keyed,
            _ => best,
        }
    }

    /// `a`'s transition function over `local` in each layout that can
    /// hold it: dense, sparse, then keyed (left out when its records
    /// would be wider than 32 bits).
    pub fn candidates(a: &Automaton, local: &[EventId]) -> Vec<EncodedTable> {
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
        let table = |layout, defined, targets, row_starts, start_bits, key_bits| EncodedTable {
            events: m as u16,
            states: n as u32,
            state_bits,
            defined,
            targets,
            row_starts,
            start_bits,
            key_bits,
            layout,
        };
        let keyed = keyed_rows(&defined, n, m, &starts, start_bits).map(
            |(dictionary, records, key_bits)| {
                table(
                    Layout::Keyed,
                    dictionary,
                    sparse.clone(),
                    records,
                    start_bits,
                    key_bits,
                )
            },
        );
        let mut candidates = vec![
            table(Layout::Dense, defined.clone(), dense, Vec::new(), 0, 0),
            table(Layout::Sparse, defined, sparse, row_starts, start_bits, 0),
        ];
        candidates.extend(keyed);
        candidates
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
            key_bits: 0,
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
                Layout::Keyed => Rows::Keyed {
                    states: &self.row_starts,
                    key_bits: self.key_bits,
                    start_bits: self.start_bits,
                },
                Layout::Net => Rows::Net {
                    fields: &self.row_starts,
                },
            },
        }
    }

    /// The number of rows of defined-bits stored: `n` but in the keyed
    /// layout, where it is the distinct rows (one more than the largest
    /// key); 0 for a net group.
    pub fn stored_rows(&self) -> u32 {
        match self.layout {
            Layout::Dense | Layout::Sparse => self.states,
            Layout::Net => 0,
            Layout::Keyed => {
                let (records, key_bits, start_bits) =
                    (&self.row_starts, self.key_bits, self.start_bits);
                let key = |s: u32| keyed_record(records, key_bits, start_bits, s).0 as u32;
                (0..self.states).map(key).max().map_or(0, |k| k + 1)
            }
        }
    }

    /// Flash bytes of the tables (words only; the small header is shared
    /// by every encoding).
    pub fn bytes(&self) -> usize {
        4 * self.words()
    }

    /// Words of the tables: `defined`, `targets` and `row_starts`.
    pub fn words(&self) -> usize {
        self.defined.len() + self.targets.len() + self.row_starts.len()
    }

    /// Bytes of the naive encoding: a `u16` per state × event pair, with a
    /// sentinel for undefined pairs.
    pub fn naive_bytes(&self) -> usize {
        2 * self.states as usize * self.events as usize
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use des::automaton::AutomatonBuilder;
    use des::testing::auto;
    use proptest::prelude::*;

    fn ids(a: &Automaton, names: &[&str]) -> Vec<EventId> {
        names.iter().map(|n| a.alphabet().id(n).unwrap()).collect()
    }

    /// The worked example of the executor's `table` module docs.
    fn worked_example() -> Automaton {
        auto(
            "ex",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("1", "b", "2"), ("2", "a", "0")],
            &[],
        )
    }

    #[test]
    fn the_worked_example_of_the_executor_docs() {
        let a = worked_example();
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
        // A chain of 31 states over 30 events, one transition per state,
        // each by another event: no row repeats but the last one's (none),
        // so keyed rows would only add keys.
        let events: Vec<(String, bool)> = (0..30).map(|i| (format!("e{i}"), i % 2 == 0)).collect();
        let event_refs: Vec<(&str, bool)> = events.iter().map(|(n, c)| (n.as_str(), *c)).collect();
        let names: Vec<String> = (0..31).map(|i| i.to_string()).collect();
        let trans: Vec<(&str, &str, &str)> = (0..30)
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
        decodes_as(&t, &a, &local);
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

    /// An automaton of `n` states `s0 …` over `m` events `e0 …` (even
    /// ones controllable), initial state `s0`, with δ(s, e) = `delta(s,
    /// e)`; its events in order.
    pub(crate) fn automaton(
        n: usize,
        m: usize,
        delta: impl Fn(usize, usize) -> Option<usize>,
    ) -> (Automaton, Vec<EventId>) {
        let mut b = AutomatonBuilder::new("random");
        let events: Vec<EventId> = (0..m)
            .map(|e| b.add_event(&format!("e{e}"), e % 2 == 0).unwrap())
            .collect();
        let states: Vec<StateId> = (0..n).map(|s| b.add_state(&format!("s{s}"))).collect();
        b.set_initial(states[0]).unwrap();
        for s in 0..n {
            for (e, &event) in events.iter().enumerate() {
                if let Some(t) = delta(s, e) {
                    b.add_transition(states[s], event, states[t], 0);
                }
            }
        }
        (b.build().unwrap(), events)
    }

    /// An automaton of `n` states over `m` events whose state `s` has
    /// the row of defined events `rows[s % rows.len()]` (bit `e` for
    /// event `e`), moving to `(s·7 + e·3 + 1) mod n`.
    fn repeating_rows(n: usize, m: usize, rows: &[u64]) -> (Automaton, Vec<EventId>) {
        automaton(n, m, |s, e| {
            (rows[s % rows.len()] >> e & 1 == 1).then_some((s * 7 + e * 3 + 1) % n)
        })
    }

    /// Every (state, event) of `t` decodes to `a`'s δ, and every row of
    /// defined-bits to the events δ defines.
    fn decodes_as(t: &EncodedTable, a: &Automaton, local: &[EventId]) {
        let view = t.view();
        let m = local.len();
        for s in a.states() {
            for (i, &e) in local.iter().enumerate() {
                assert_eq!(
                    view.next_state(s.0, i as u16),
                    a.successor(s, e).map(|x| x.0),
                    "{:?}: state {s} event {i}",
                    t.layout
                );
            }
            assert_eq!(view.next_state(s.0, m as u16), None);
            for from in (0..m).step_by(32) {
                let row = (from..m.min(from + 32))
                    .filter(|&i| a.successor(s, local[i]).is_some())
                    .fold(0u32, |row, i| row | 1 << (i - from));
                assert_eq!(
                    view.enabled(s.0, from as u16, 32),
                    row,
                    "{:?}: row",
                    t.layout
                );
            }
        }
    }

    #[test]
    fn keyed_rows_win_when_rows_repeat_and_decode_correctly() {
        // 300 states, 26 events, 5 distinct rows.
        let rows = [0x3ff_ffff, 0x155_5555, 0x0f0_f0f0, 0x1, 0x200_0001];
        let (a, local) = repeating_rows(300, 26, &rows);
        let t = EncodedTable::encode(&a, &local);
        assert_eq!(t.layout, Layout::Keyed);
        let total: usize = (0..300).map(|s| rows[s % 5].count_ones() as usize).sum();
        assert_eq!((t.key_bits, t.start_bits), (3, bits_for(total as u64)));
        assert_eq!(t.stored_rows(), 5);
        assert_eq!(
            t.defined.len(),
            (5 * 26usize).div_ceil(32),
            "the dictionary"
        );
        assert_eq!(
            t.row_starts.len(),
            (300 * (3 + t.start_bits as usize)).div_ceil(32)
        );
        assert_eq!(
            t.targets.len(),
            (total * 9).div_ceil(32),
            "the sparse targets"
        );
        let smaller = EncodedTable::candidates(&a, &local);
        assert!(smaller
            .iter()
            .all(|c| c.layout == Layout::Keyed || c.words() > t.words()));
        decodes_as(&t, &a, &local);
        // Rows longer than a word: counted word by word.
        let (a, local) = repeating_rows(100, 40, &[0xff_ffff_ffff, 0x80_0000_0001, 0x55_5555_5555]);
        let t = EncodedTable::encode(&a, &local);
        assert_eq!((t.layout, t.stored_rows()), (Layout::Keyed, 3));
        decodes_as(&t, &a, &local);
    }

    /// Keyed only when it saves an eighth of the better plain layout's
    /// words: with more and more distinct rows its saving shrinks, and
    /// some table it would make smaller stays sparse.
    #[test]
    fn keyed_needs_to_save_an_eighth() {
        let mut smaller_but_plain = 0;
        let mut chosen = 0;
        for distinct in [2usize, 5, 20, 60, 120, 200] {
            let rows: Vec<u64> = (0..distinct as u64)
                .map(|k| (k * 0x9e37_79b9).rotate_left(k as u32) & 0x3ff_ffff)
                .collect();
            let (a, local) = repeating_rows(240, 26, &rows);
            let c = EncodedTable::candidates(&a, &local);
            let plain = c[0].words().min(c[1].words());
            let t = EncodedTable::encode(&a, &local);
            if c[2].words() * KEYED_SHARE.1 <= plain * KEYED_SHARE.0 {
                assert_eq!(t.layout, Layout::Keyed, "{distinct} rows");
                chosen += 1;
            } else {
                assert_ne!(t.layout, Layout::Keyed, "{distinct} rows");
                assert_eq!(t.words(), plain);
                smaller_but_plain += usize::from(c[2].words() < plain);
            }
            decodes_as(&t, &a, &local);
        }
        assert!(chosen > 0, "keyed chosen for few distinct rows");
        assert!(
            smaller_but_plain > 0,
            "a small saving keeps the plain layout"
        );
    }

    #[test]
    fn ties_go_to_dense_then_sparse() {
        // The worked example: dense takes 2 words, sparse 3, keyed 4 (a
        // dictionary word per row).
        let a = worked_example();
        let local = ids(&a, &["a", "b"]);
        let words: Vec<(Layout, usize)> = EncodedTable::candidates(&a, &local)
            .iter()
            .map(|t| (t.layout, t.words()))
            .collect();
        assert_eq!(
            words,
            [(Layout::Dense, 2), (Layout::Sparse, 3), (Layout::Keyed, 4)]
        );
        let keyed = &EncodedTable::candidates(&a, &local)[2];
        // The keyed table of the executor's worked example.
        assert_eq!(keyed.defined, [0x1, 0x2]);
        assert_eq!(keyed.row_starts, [0x118]);
        assert_eq!((keyed.key_bits, keyed.start_bits), (1, 2));
        assert_eq!(EncodedTable::encode(&a, &local).layout, Layout::Dense);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Random automata, their rows drawn from a few: every candidate
        /// layout decodes to δ, and the one chosen is the fewer words of
        /// dense and sparse unless keyed saves an eighth of them.
        #[test]
        fn every_layout_decodes_random_automata_to_their_transitions(
            n in 1usize..=60,
            m in 1usize..=40,
            rows in proptest::collection::vec(any::<u64>(), 1..=6),
            seed in any::<u64>(),
        ) {
            let (a, events) = automaton(n, m, |s, e| {
                let row = rows[(s as u64 ^ seed) as usize % rows.len()];
                let t = seed.rotate_left((s * m + e) as u32 % 64) % n as u64;
                (row >> e & 1 == 1).then_some(t as usize)
            });
            let candidates = EncodedTable::candidates(&a, &events);
            prop_assert_eq!(candidates.len(), 3);
            for t in &candidates {
                decodes_as(t, &a, &events);
            }
            let chosen = EncodedTable::encode(&a, &events);
            let plain = candidates[0].words().min(candidates[1].words());
            let keyed = candidates[2].words();
            if keyed * 8 <= plain * 7 {
                prop_assert_eq!(chosen.layout, Layout::Keyed);
            } else {
                prop_assert_eq!(chosen.words(), plain);
                prop_assert!(chosen.layout != Layout::Keyed);
            }
        }
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
