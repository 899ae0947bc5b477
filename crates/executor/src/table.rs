//! Bit-packed supervisor tables and the program that runs them.
//!
//! # Encoding
//!
//! A supervisor with `n` states and `m` local events stores its states in
//! `b = max(1, ⌈log2 n⌉)` bits. Its table has three parts, all arrays of
//! `u32` words with bit `i` at word `i / 32`, bit `i % 32` (least
//! significant first):
//!
//! - `defined`: `n·m` bits, bit `s·m + e` set when δ(s, e) is defined. For a
//!   controllable event this is "enabled", for an uncontrollable one
//!   "expected": an event whose bit is clear is unexpected in that state.
//! - `targets`: `b`-bit entries holding δ(s, e), in one of two layouts:
//!   - **dense**: entry `s·m + e` (entries of undefined pairs are 0);
//!   - **sparse**: only defined pairs, row by row; the entry of (s, e) is
//!     `row_start[s]` plus the number of defined events of `s` before `e`.
//!     `row_start` holds `n` entries of `⌈log2(total + 1)⌉` bits.
//!
//! The generator picks the one of dense and sparse with fewer words
//! (dense on a tie: it is one step faster), and keyed (below) instead
//! when that saves at least an eighth of them: its lookup reads one word
//! more. A program compiled into the firmware links only the decoders of
//! the layouts its tables use ([`Layouts`]).
//!
//! # Keyed rows
//!
//! A fourth layout, [`Rows::Keyed`], stores each distinct row of
//! defined-bits once: many states of a large supervisor enable the same
//! events. `defined` is then a dictionary of the `k` distinct rows, row
//! `r` at bits `r·w .. r·w + m` for the row stride `w` ([`keyed_stride`]:
//! 32 for up to 32 events, so that a row is one word and a lookup reads
//! it with one load, else `m`; `⌈k·w / 32⌉` words); `targets` is the
//! sparse layout's; and `states` holds one record of `key_bits +
//! start_bits` bits (at most 32) per state: the low `key_bits` the
//! state's row in the dictionary (its *key*, `key_bits = max(1,
//! ⌈log2 k⌉)`), the high `start_bits` its row start, as the sparse
//! layout's. A lookup reads the record, the dictionary row, counts the
//! defined events before `e` in it, and reads one target: the sparse
//! layout's steps, with one more read.
//!
//! # Petri nets
//!
//! A third layout, [`Rows::Net`], runs a group of places of a Petri net
//! as one supervisor: its state is the group's marking, each place a
//! counter of a few bits (a *field*, `fields[f]` the mask of its bits,
//! wide enough for the place's bound), its local events the transitions
//! with an arc to a place of the group. `defined` holds one word per local
//! transition, `PRE[t]`: the weight of each input arc in its place's field;
//! `targets` likewise holds `POST[t]`, the output arcs. δ(x, t) is defined
//! when every field of `x` holds at least `PRE[t]`'s, and is then
//! `x − PRE[t] + POST[t]` (no borrow crosses a field, since each holds
//! enough), undefined if a counter would overflow its field (a bounded net
//! never does; a corrupt marking may). `b` is the sum of the fields'
//! widths, at most 31, and every `b`-bit value is a state. A net of more
//! places runs as several such supervisors: the executor's synchronous
//! product of them (a transition fires when every group it touches
//! enables it, and moves each) is the net's firing rule.
//!
//! For example places `p` (bit 0) and `q` (bits 1–2, bound 3) and
//! `t: p → 2·q`: `fields = [0b001, 0b110]`, `PRE[t] = 0b001`,
//! `POST[t] = 0b100`; from `x = 0b011` (p = 1, q = 1), δ(x, t) = 0b110
//! (p = 0, q = 3); from `0b010` it is undefined (p empty), and from
//! `0b111` too (q would hold 4).
//!
//! # Worked example
//!
//! Three states, events `a` (local 0) and `b` (local 1), δ(0,a)=1,
//! δ(1,b)=2, δ(2,a)=0. Then `b = 2`, and
//!
//! | part | bits (low first) | word |
//! |---|---|---|
//! | defined | `1 0 · 0 1 · 1 0` | `0x19` |
//! | dense targets | `01 00 · 00 10 · 00 00` | `0x81` |
//! | sparse targets | `01 · 10 · 00` | `0x09` |
//! | sparse row starts (2 bits) | `00 · 01 · 10` | `0x24` |
//! | keyed dictionary (rows `a`, `b`, a word each) | `1 0 …` · `0 1 …` | `0x1`, `0x2` |
//! | keyed records (1-bit key, 2-bit start) | `0 00 · 1 10 · 0 01` | `0x118` |
//!
//! Looking up δ(1, b): bit `1·2 + 1 = 3` of `defined` is set; dense entry 3
//! is bits 6–7 of `0x81` = `10` = state 2; sparse: row start of state 1 is
//! 1, no defined event of state 1 precedes `b`, entry 1 is `10` = 2.
//! Keyed (targets as sparse): the record of state 1 is `0b011`, key 1 and
//! start 1; bit 1 of dictionary word 1 is set, nothing before it in
//! row 1, entry 1 is state 2.
//!
//! # Integrity
//!
//! The tables are part of the program image ([`crate::image`]): every
//! word of `defined`, `targets` and `row_starts` (`states`) is covered by the image
//! CRC ([`crate::image::table_image_crc`]), which the generator records and the controller
//! checks at start-up and, in the background, scan after scan.

/// Most bits of a Petri-net group's packed marking, its state ("Petri
/// nets" above): a group of `b` bits has `2^b` states, `1 ≤ b ≤` this.
pub const NET_GROUP_BITS: u32 = 31;

use crate::program::{Config, Index, Program, SupervisorSpec};

/// The tables' data, defined beside the [`Program`] trait that hands them
/// out; this module decodes them.
pub use crate::program::{Layouts, Rows, SupervisorTable};

/// The `width`-bit entry `index` of a packed array (0 if out of range).
#[inline]
pub fn read_bits(words: &[u32], index: usize, width: u8) -> u32 {
    if width == 0 {
        return 0;
    }
    read_bits_at(words, index * usize::from(width), width)
}

/// [`read_bits`] without a branch on whether the entry straddles two
/// words: both are read (a missing one reads 0) and joined. For entries
/// that straddle often (a keyed table's records and targets, of 10 to
/// 32 bits); narrow ones rarely do, and [`read_bits`] skips the second
/// read for them.
#[inline]
fn read_bits_joined(words: &[u32], index: usize, width: u8) -> u32 {
    let bit = index * usize::from(width);
    let (word, offset) = (bit / 32, (bit % 32) as u32);
    let low = words.get(word).copied().unwrap_or(0);
    let high = words.get(word + 1).copied().unwrap_or(0);
    // `high << (32 - offset)` without the shift by 32 at offset 0.
    let value = low >> offset | high << 1 << (31 - offset);
    match width {
        0 => 0,
        1..=31 => value & ((1u32 << width) - 1),
        _ => value,
    }
}

/// The `width` bits (`1..=32`) starting at bit `bit` of a bit array (bits
/// past its end read 0).
#[inline]
fn read_bits_at(words: &[u32], bit: usize, width: u8) -> u32 {
    let (word, offset) = (bit / 32, bit % 32);
    let low = words.get(word).copied().unwrap_or(0) >> offset;
    let value = if offset + width as usize > 32 {
        low | (words.get(word + 1).copied().unwrap_or(0) << (32 - offset))
    } else {
        low
    };
    if width >= 32 {
        value
    } else {
        value & ((1u32 << width) - 1)
    }
}

// The stored allowed sets' index is a packed array too: decoded here.
impl<'a> Config<'a> {
    /// The number of `spec`'s stored allowed set in `state`
    /// ([`crate::program::AllowedSets`]), `None` when its sets are computed.
    #[inline]
    pub fn stored_set(&self, spec: &SupervisorSpec, state: u32) -> Option<usize> {
        let sets = spec.allowed;
        sets.is_stored().then(|| {
            read_bits(sets.index.of(self.allowed_index), state as usize, sets.bits) as usize
        })
    }

    /// Event set `k` of [`Config::event_masks`], words `k·w .. (k + 1)·w`
    /// (`w` = [`crate::program::words`]`(events)`); `None` past the pool.
    #[inline]
    pub fn event_set(&self, k: usize) -> Option<&'a [u32]> {
        let w = crate::program::words(self.events.len());
        let start = k.checked_mul(w)?;
        self.event_masks.get(start..start.checked_add(w)?)
    }
}

/// Bit `index` of a bit array (false past its end): the executor's bit
/// sets and the tables' defined-bits are one layout.
pub use crate::bits::contains as bit;
use crate::bits::insert as bit_insert;

/// The record of `state` in a keyed table's `states` ([`Rows::Keyed`]):
/// its dictionary row (the low `key_bits`) and its row start (the high
/// `start_bits`). Shifts wrap rather than panic on widths that the
/// structure check refuses.
#[inline]
pub fn keyed_record(states: &[u32], key_bits: u8, start_bits: u8, state: u32) -> (usize, usize) {
    let record = read_bits_joined(states, state as usize, key_bits.wrapping_add(start_bits));
    let start = record.wrapping_shr(u32::from(key_bits));
    let key = record ^ start.wrapping_shl(u32::from(key_bits));
    (key as usize, start as usize)
}

/// Bits from one row of a keyed table's dictionary to the next
/// ([`Rows::Keyed`]) for `events` local events: a whole word for up to
/// 32 (each row one word; the generator writes its bits past the events
/// as 0, and no lookup reads them), else `events` (rows packed as the
/// sparse layout's).
#[inline]
pub const fn keyed_stride(events: usize) -> usize {
    if events <= 32 {
        32
    } else {
        events
    }
}

/// Number of set bits in `from..to`: one count of at most 32 bits read
/// at once (a sparse table's row prefix, when its supervisor has at most
/// 33 events), else word by word.
#[inline]
pub(crate) fn ones_between(words: &[u32], from: usize, to: usize) -> usize {
    let len = to.saturating_sub(from);
    if len <= 32 {
        return read_bits_at(words, from, len as u8).count_ones() as usize;
    }
    let mut count = 0;
    let mut i = from;
    while i < to {
        let word = words.get(i / 32).copied().unwrap_or(0) >> (i % 32);
        let take = (32 - i % 32).min(to - i);
        let mask = if take >= 32 {
            u32::MAX
        } else {
            (1u32 << take) - 1
        };
        count += (word & mask).count_ones() as usize;
        i += take;
    }
    count
}

impl SupervisorTable<'static> {
    /// A table of no events and no words: what a buffer of tables holds
    /// before [`crate::parse::load`] fills it.
    pub const EMPTY: SupervisorTable<'static> = SupervisorTable {
        events: 0,
        state_bits: 1,
        defined: &[],
        targets: &[],
        rows: Rows::Dense,
    };
}

impl SupervisorTable<'_> {
    /// δ(state, local), `None` when undefined.
    #[inline]
    pub fn next_state(&self, state: u32, local: Index) -> Option<u32> {
        self.next_state_in(Layouts::ALL, state, local)
    }

    /// [`SupervisorTable::next_state`] of a table whose layout is one of
    /// `layouts` (`None` when it is not: the decoders of the others are
    /// left out where `layouts` is a constant).
    #[inline]
    pub fn next_state_in(&self, layouts: Layouts, state: u32, local: Index) -> Option<u32> {
        let m = self.events as usize;
        let local = local as usize;
        if local >= m {
            return None;
        }
        match self.rows {
            Rows::Net { fields } if layouts.has(Layouts::NET) => {
                let (pre, post) = (*self.defined.get(local)?, *self.targets.get(local)?);
                return self.fire(fields, state, pre, post);
            }
            Rows::Keyed {
                states,
                key_bits,
                start_bits,
            } if layouts.has(Layouts::KEYED) => {
                let (key, start) = keyed_record(states, key_bits, start_bits, state);
                return self.keyed_next(key, start, local);
            }
            _ => {}
        }
        let row = state as usize * m;
        let pair = row + local;
        let entry = if m <= 32 {
            // The state's whole row of defined-bits in one read: the
            // event's bit, and for a sparse row the count before it.
            let bits = read_bits_at(self.defined, row, m as u8);
            if bits >> local & 1 == 0 {
                return None;
            }
            match self.rows {
                Rows::Dense if layouts.has(Layouts::DENSE) => pair,
                Rows::Sparse {
                    row_starts,
                    start_bits,
                } if layouts.has(Layouts::SPARSE) => {
                    let before = bits & ((1u32 << local) - 1);
                    read_bits(row_starts, state as usize, start_bits) as usize
                        + before.count_ones() as usize
                }
                _ => return None,
            }
        } else {
            if !bit(self.defined, pair) {
                return None;
            }
            match self.rows {
                Rows::Dense if layouts.has(Layouts::DENSE) => pair,
                Rows::Sparse {
                    row_starts,
                    start_bits,
                } if layouts.has(Layouts::SPARSE) => {
                    read_bits(row_starts, state as usize, start_bits) as usize
                        + ones_between(self.defined, row, pair)
                }
                _ => return None,
            }
        };
        Some(read_bits(self.targets, entry, self.state_bits))
    }

    /// The defined-bits of the local events `from..from + len` in `state`
    /// (`len ≤ 32`): bit `k` for local event `from + k`; events past the
    /// table's read as undefined.
    #[inline]
    pub fn enabled(&self, state: u32, from: Index, len: u8) -> u32 {
        self.enabled_in(Layouts::ALL, state, from, len)
    }

    /// [`SupervisorTable::enabled`] of a table whose layout is one of
    /// `layouts` (0 when it is not), as [`SupervisorTable::next_state_in`];
    /// dense and sparse rows are read alike, under either layout.
    #[inline]
    pub fn enabled_in(&self, layouts: Layouts, state: u32, from: Index, len: u8) -> u32 {
        let m = self.events as usize;
        let from = from as usize;
        let len = (len.min(32) as usize).min(m.saturating_sub(from));
        if len == 0 {
            return 0;
        }
        match self.rows {
            // One arm for both: their rows are the same bits, and two
            // guarded arms of one body were two copies of it.
            Rows::Dense | Rows::Sparse { .. }
                if layouts.has(Layouts::DENSE) || layouts.has(Layouts::SPARSE) =>
            {
                read_bits_at(self.defined, state as usize * m + from, len as u8)
            }
            Rows::Net { fields } if layouts.has(Layouts::NET) => {
                self.net_enabled(fields, state, from, len)
            }
            Rows::Keyed {
                states,
                key_bits,
                start_bits,
            } if layouts.has(Layouts::KEYED) => {
                let (key, _) = keyed_record(states, key_bits, start_bits, state);
                if m <= 32 {
                    // The row is word `key`; `from < m`, `len ≤ m - from`.
                    let row = self.defined.get(key).copied().unwrap_or(0) >> from;
                    return if len >= 32 {
                        row
                    } else {
                        row & ((1u32 << len) - 1)
                    };
                }
                read_bits_at(self.defined, key * keyed_stride(m) + from, len as u8)
            }
            _ => 0,
        }
    }

    /// [`SupervisorTable::next_state`] of the keyed layout: the state's
    /// row is dictionary row `key`, its targets start at entry `start`
    /// (`local` is below the table's events, so `m ≥ 1`).
    #[inline]
    fn keyed_next(&self, key: usize, start: usize, local: usize) -> Option<u32> {
        let m = self.events as usize;
        let entry = if m <= 32 {
            // The dictionary row is word `key` ([`keyed_stride`]): one load.
            let bits = self.defined.get(key).copied().unwrap_or(0);
            if bits >> local & 1 == 0 {
                return None;
            }
            start + (bits & ((1u32 << local) - 1)).count_ones() as usize
        } else {
            let row = key * keyed_stride(m);
            if !bit(self.defined, row + local) {
                return None;
            }
            start + ones_between(self.defined, row, row + local)
        };
        Some(read_bits_joined(self.targets, entry, self.state_bits))
    }

    /// For a table of the net layout: adds to `allowed` (a bit set of
    /// events) the event `alphabet[t]` (an event list's words, as the
    /// configuration stores them) of every local transition `t` that
    /// fires from the marking `state`, and returns `true`; `false`, adding
    /// nothing, for the other layouts. One test per transition (that of
    /// [`SupervisorTable::enabled`]) straight into the set, without rows
    /// of 32 transitions to build and scatter.
    #[inline]
    pub fn insert_enabled_net(&self, state: u32, alphabet: &[u32], allowed: &mut [u32]) -> bool {
        let Rows::Net { fields } = self.rows else {
            return false;
        };
        let transitions = self.defined.iter().zip(self.targets).zip(alphabet);
        if fields.len() == usize::from(self.state_bits) {
            for ((&pre, &post), &e) in transitions {
                if state & (pre | post) == pre {
                    bit_insert(allowed, e as usize);
                }
            }
        } else {
            for ((&pre, &post), &e) in transitions {
                if fire(fields, state, pre, post).is_some() {
                    bit_insert(allowed, e as usize);
                }
            }
        }
        true
    }

    /// [`SupervisorTable::enabled`] of the net layout: the local
    /// transitions `from..from + len` (`len ≤ 32`) that fire from the
    /// marking `state`. A group of one-bit counters asks one test per
    /// transition, with no branch: `t` fires from `x` exactly when
    /// `x & (PRE[t] | POST[t]) == PRE[t]` (every input place marked, and
    /// no output place outside the inputs marked, which would overflow).
    /// Other groups ask [`fire`] per transition.
    #[inline]
    fn net_enabled(&self, fields: &[u32], state: u32, from: usize, len: usize) -> u32 {
        let pre = self.defined.get(from..).unwrap_or_default();
        let post = self.targets.get(from..).unwrap_or_default();
        let arcs = pre.iter().zip(post).take(len);
        if fields.len() == usize::from(self.state_bits) {
            // Built from the last transition down, so that each step is a
            // shift and an OR.
            return arcs.rev().fold(0, |row, (&pre, &post)| {
                row << 1 | u32::from(state & (pre | post) == pre)
            });
        }
        arcs.enumerate().fold(0, |row, (k, (&pre, &post))| {
            row | u32::from(fire(fields, state, pre, post).is_some()) << k
        })
    }
}

impl SupervisorTable<'_> {
    /// The net layout's δ for this group: [`fire`], or for a group of
    /// one-bit counters (a safe net's places: as many fields as bits) the
    /// same in two masks: every input place marked, and no output place
    /// marked once the inputs are taken.
    #[inline]
    fn fire(&self, fields: &[u32], x: u32, pre: u32, post: u32) -> Option<u32> {
        if fields.len() == usize::from(self.state_bits) {
            let left = x & !pre;
            return (x & pre == pre && left & post == 0).then_some(left | post);
        }
        fire(fields, x, pre, post)
    }
}

/// The net layout's δ: `x − pre + post` when every field of `x` holds at
/// least `pre`'s and no field overflows (module docs, "Petri nets").
#[inline]
pub fn fire(fields: &[u32], x: u32, pre: u32, post: u32) -> Option<u32> {
    let mut next = x;
    for &field in fields {
        let (held, taken, added) = (x & field, pre & field, post & field);
        // Each operand lies within `field`, so the sum overflows the
        // field exactly when it exceeds the mask.
        let left = held.checked_sub(taken)?;
        let counter = left.checked_add(added).filter(|&c| c <= field)?;
        next = next & !field | counter;
    }
    Some(next)
}

/// A program made of a [`Config`] and one [`SupervisorTable`] per
/// supervisor, with the image CRC recorded at generation.
#[derive(Debug, Clone, Copy)]
pub struct TableProgram<'a> {
    /// The static description.
    pub config: Config<'a>,
    /// One table per supervisor, in order.
    pub tables: &'a [SupervisorTable<'a>],
    /// The image CRC as computed by the generator
    /// ([`crate::image::table_image_crc`]).
    pub crc: u32,
}

impl Program for TableProgram<'_> {
    fn config(&self) -> Config<'_> {
        self.config
    }

    #[inline]
    fn next_state(&self, supervisor: Index, state: u32, local: Index) -> Option<u32> {
        self.tables
            .get(supervisor as usize)?
            .next_state(state, local)
    }

    #[inline]
    fn enabled(&self, supervisor: Index, state: u32, from: Index, len: u8) -> u32 {
        self.tables
            .get(supervisor as usize)
            .map_or(0, |t| t.enabled(state, from, len))
    }

    fn table(&self, supervisor: Index) -> Option<SupervisorTable<'_>> {
        self.tables.get(usize::from(supervisor)).copied()
    }

    fn recorded_crc(&self) -> u32 {
        self.crc
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The worked example of the module docs, both layouts.
    const DENSE: SupervisorTable<'static> = SupervisorTable {
        events: 2,
        state_bits: 2,
        defined: &[0x19],
        targets: &[0x81],
        rows: Rows::Dense,
    };
    const SPARSE: SupervisorTable<'static> = SupervisorTable {
        events: 2,
        state_bits: 2,
        defined: &[0x19],
        targets: &[0x09],
        rows: Rows::Sparse {
            row_starts: &[0x24],
            start_bits: 2,
        },
    };

    const KEYED: SupervisorTable<'static> = SupervisorTable {
        events: 2,
        state_bits: 2,
        defined: &[0x1, 0x2],
        targets: &[0x09],
        rows: Rows::Keyed {
            states: &[0x118],
            key_bits: 1,
            start_bits: 2,
        },
    };

    #[test]
    fn worked_example_decodes_in_every_layout() {
        assert_eq!(keyed_record(&[0x118], 1, 2, 1), (1, 1));
        assert_eq!(keyed_record(&[0x118], 1, 2, 2), (0, 2));
        for t in [DENSE, SPARSE, KEYED] {
            assert_eq!(t.next_state(0, 0), Some(1));
            assert_eq!(t.next_state(0, 1), None);
            assert_eq!(t.next_state(1, 0), None);
            assert_eq!(t.next_state(1, 1), Some(2));
            assert_eq!(t.next_state(2, 0), Some(0));
            assert_eq!(t.next_state(2, 1), None);
            assert_eq!(t.next_state(2, 7), None, "local event out of range");
            assert_eq!(t.enabled(0, 0, 2), 0b01);
            assert_eq!(t.enabled(1, 0, 2), 0b10);
            assert_eq!(t.enabled(1, 1, 1), 0b1);
            assert_eq!(t.enabled(2, 0, 32), 0b01, "rows end at the table's events");
        }
    }

    /// A program knows its tables' layouts at build time; a table read as
    /// a layout it is not refuses every event and enables none, so that
    /// the decoders of the others can be left out. Dense and sparse rows
    /// of defined-bits are one layout for the enabled events: either
    /// layout reads both.
    #[test]
    fn layouts_of_tables_and_lookups_restricted_to_them() {
        assert_eq!(Layouts::of(&[]), Layouts::NONE);
        let of = Layouts::of(&[DENSE, NET]);
        assert!(of.has(Layouts::DENSE) && of.has(Layouts::NET));
        assert!(!of.has(Layouts::SPARSE) && !of.has(Layouts::KEYED));
        assert_eq!(Layouts::of(&[SPARSE, KEYED, SPARSE]).0, 2 | 8);
        assert_eq!(Layouts::of(&[DENSE, SPARSE, NET, KEYED]), Layouts::ALL);
        for t in [DENSE, SPARSE, KEYED, NET] {
            let own = Layouts::of(&[t]);
            let others = Layouts(Layouts::ALL.0 & !own.0);
            for state in 0..3 {
                for local in 0..2 {
                    assert_eq!(
                        t.next_state_in(own, state, local),
                        t.next_state(state, local)
                    );
                    assert_eq!(t.next_state_in(others, state, local), None, "{own:?}");
                }
                assert_eq!(t.enabled_in(own, state, 0, 2), t.enabled(state, 0, 2));
                let rows = Layouts(Layouts::DENSE.0 | Layouts::SPARSE.0);
                let (apart, expected) = if rows.has(own) {
                    (Layouts(Layouts::ALL.0 & !rows.0), t.enabled(state, 0, 2))
                } else {
                    (others, 0)
                };
                assert_eq!(t.enabled_in(apart, state, 0, 2), 0, "{own:?}");
                assert_eq!(t.enabled_in(others, state, 0, 2), expected, "{own:?}");
            }
        }
    }

    /// The net example of the module docs: `p` at bit 0, `q` at bits 1–2,
    /// `t: p → 2·q`, and `u: q → p` as a second transition.
    const NET: SupervisorTable<'static> = SupervisorTable {
        events: 2,
        state_bits: 3,
        defined: &[0b001, 0b010],
        targets: &[0b100, 0b001],
        rows: Rows::Net {
            fields: &[0b001, 0b110],
        },
    };

    #[test]
    fn net_example_fires_by_its_counters() {
        assert_eq!(NET.next_state(0b011, 0), Some(0b110), "p=1,q=1 → p=0,q=3");
        assert_eq!(NET.next_state(0b010, 0), None, "p empty");
        assert_eq!(NET.next_state(0b111, 0), None, "q would hold 4");
        assert_eq!(NET.next_state(0b111, 1), None, "p would hold 2");
        assert_eq!(NET.next_state(0b110, 1), Some(0b101), "q=3 → q=2, p=1");
        assert_eq!(NET.next_state(0b100, 1), Some(0b011), "q=2 → q=1, p=1");
        assert_eq!(NET.next_state(0b011, 2), None, "local event out of range");
        assert_eq!(
            NET.enabled(0b011, 0, 2),
            0b01,
            "u would put a second token on p"
        );
        assert_eq!(NET.enabled(0b001, 0, 2), 0b01);
        assert_eq!(
            NET.enabled(0b110, 0, 32),
            0b10,
            "rows end at the table's events"
        );
        assert_eq!(NET.enabled(0b010, 1, 1), 0b1);
    }

    #[test]
    fn net_firing_agrees_with_counter_arithmetic() {
        // Every state and every pair of arcs on three 2-bit counters.
        let fields = [0b000011, 0b001100, 0b110000];
        let counters = |x: u32| [x & 3, x >> 2 & 3, x >> 4 & 3];
        for x in 0..64u32 {
            for pre in 0..64u32 {
                for post in [0u32, 0b000001, 0b000110, 0b110000, 0b111111] {
                    let (have, take, add) = (counters(x), counters(pre), counters(post));
                    let expected = (0..3)
                        .all(|f| have[f] >= take[f] && have[f] - take[f] + add[f] <= 3)
                        .then(|| {
                            (0..3)
                                .map(|f| (have[f] - take[f] + add[f]) << (2 * f))
                                .sum()
                        });
                    assert_eq!(
                        fire(&fields, x, pre, post),
                        expected,
                        "x={x:#b} pre={pre:#b} post={post:#b}"
                    );
                }
            }
        }
    }

    #[test]
    fn one_bit_counters_take_the_mask_path_with_the_same_result() {
        let fields = [1, 2, 4, 8];
        let table = SupervisorTable {
            events: 0,
            state_bits: 4,
            defined: &[],
            targets: &[],
            rows: Rows::Net { fields: &fields },
        };
        for x in 0..16 {
            for pre in 0..16 {
                for post in 0..16 {
                    assert_eq!(
                        table.fire(&fields, x, pre, post),
                        fire(&fields, x, pre, post),
                        "x={x:#b} pre={pre:#b} post={post:#b}"
                    );
                }
            }
        }
    }

    /// Every transition of a group tested at once (a row, or inserted
    /// into an event set) agrees with δ transition by transition: one-bit
    /// groups (the branch-free test) and wider counters ([`fire`]), with
    /// more transitions than a row holds.
    #[test]
    fn net_rows_and_event_sets_agree_with_next_state() {
        extern crate std;
        use std::vec::Vec;
        // Every PRE and POST pair on 4 places but a few, as 40 transitions
        // at a time; events numbered backwards from 70 (two words).
        let pairs: Vec<(u32, u32)> = (0..16u32)
            .flat_map(|pre| (0..16u32).map(move |post| (pre, post)))
            .collect();
        for narrow in [true, false] {
            let fields: &[u32] = if narrow {
                &[1, 2, 4, 8]
            } else {
                &[0b11, 0b1100]
            };
            for arcs in pairs.chunks(40) {
                let defined: Vec<u32> = arcs.iter().map(|a| a.0).collect();
                let targets: Vec<u32> = arcs.iter().map(|a| a.1).collect();
                let alphabet: Vec<u32> = (0..arcs.len() as u32).map(|k| 70 - k).collect();
                let table = SupervisorTable {
                    events: arcs.len() as Index,
                    state_bits: 4,
                    defined: &defined,
                    targets: &targets,
                    rows: Rows::Net { fields },
                };
                for x in 0..16 {
                    let mut set = [0u32; 3];
                    assert!(table.insert_enabled_net(x, &alphabet, &mut set));
                    for (k, &e) in alphabet.iter().enumerate() {
                        let fires = table.next_state(x, k as Index).is_some();
                        let row = table.enabled(x, k as Index / 32 * 32, 32);
                        assert_eq!(row >> (k % 32) & 1 == 1, fires, "row, x={x:#b} t={k}");
                        assert_eq!(bit(&set, e as usize), fires, "set, x={x:#b} t={k}");
                    }
                    let others = set.iter().map(|w| w.count_ones()).sum::<u32>() as usize;
                    let fired = (0..arcs.len())
                        .filter(|&k| table.next_state(x, k as Index).is_some())
                        .count();
                    assert_eq!(others, fired, "no event outside the alphabet");
                }
            }
        }
        let mut set = [0u32; 1];
        assert!(!DENSE.insert_enabled_net(0, &[0, 1], &mut set), "not a net");
        assert_eq!(set, [0]);
    }

    /// Rows of exactly 32 and of 31 local events (read whole, one count
    /// per lookup), and of 40 (counted word by word): the sparse and keyed
    /// layouts give the dense layout's targets, events 30 and 31
    /// included, and undefined pairs stay undefined.
    #[test]
    fn sparse_and_keyed_rows_agree_with_dense() {
        extern crate std;
        use std::{vec, vec::Vec};
        fn put(words: &mut [u32], index: usize, width: usize, value: u32) {
            for b in 0..width {
                if value >> b & 1 == 1 {
                    let bit = index * width + b;
                    words[bit / 32] |= 1 << (bit % 32);
                }
            }
        }
        for m in [31usize, 32, 40] {
            let (n, width) = (7usize, 3usize);
            let defined_at = |s: usize, e: usize| !(s * 7 + e * 3).is_multiple_of(5) || e >= 30;
            let target = |s: usize, e: usize| ((s + e) % n) as u32;
            let mut defined = vec![0u32; (n * m).div_ceil(32)];
            let mut dense = vec![0u32; (n * m * width).div_ceil(32)];
            let mut sparse = vec![0u32; (n * m * width).div_ceil(32)];
            let mut row_starts = vec![0u32; (n * 9).div_ceil(32)];
            // Keyed: rows repeat every 5 states; 3-bit keys, 9-bit starts.
            let stride = keyed_stride(m);
            let mut dictionary = vec![0u32; (5 * stride).div_ceil(32)];
            let mut records = vec![0u32; (n * 12).div_ceil(32)];
            let mut keys: Vec<usize> = Vec::new();
            let mut k = 0;
            for s in 0..n {
                put(&mut row_starts, s, 9, k as u32);
                let key = (s * 7) % 5;
                put(&mut records, s, 12, key as u32 | (k as u32) << 3);
                if !keys.contains(&key) {
                    keys.push(key);
                    for e in (0..m).filter(|&e| defined_at(s, e)) {
                        put(&mut dictionary, key * stride + e, 1, 1);
                    }
                }
                for e in 0..m {
                    if defined_at(s, e) {
                        put(&mut defined, s * m + e, 1, 1);
                        put(&mut dense, s * m + e, width, target(s, e));
                        put(&mut sparse, k, width, target(s, e));
                        k += 1;
                    }
                }
            }
            let table = |targets, rows| SupervisorTable {
                events: m as Index,
                state_bits: width as u8,
                defined: &defined,
                targets,
                rows,
            };
            let sparse_targets = sparse.clone();
            let dense = table(&dense, Rows::Dense);
            let sparse = table(
                &sparse,
                Rows::Sparse {
                    row_starts: &row_starts,
                    start_bits: 9,
                },
            );
            let keyed = SupervisorTable {
                defined: &dictionary,
                ..table(
                    &sparse_targets,
                    Rows::Keyed {
                        states: &records,
                        key_bits: 3,
                        start_bits: 9,
                    },
                )
            };
            for s in 0..n {
                for e in 0..m {
                    let expected = defined_at(s, e).then(|| target(s, e));
                    let (state, local) = (s as u32, e as Index);
                    assert_eq!(
                        dense.next_state(state, local),
                        expected,
                        "dense {m} {s} {e}"
                    );
                    assert_eq!(
                        sparse.next_state(state, local),
                        expected,
                        "sparse {m} {s} {e}"
                    );
                    assert_eq!(
                        keyed.next_state(state, local),
                        expected,
                        "keyed {m} {s} {e}"
                    );
                }
                for from in (0..m).step_by(32) {
                    let (from, len) = (from as Index, 32);
                    assert_eq!(
                        keyed.enabled(s as u32, from, len),
                        dense.enabled(s as u32, from, len),
                        "keyed row {m} {s} {from}"
                    );
                }
            }
        }
    }

    #[test]
    fn rows_longer_than_a_word_read_in_slices() {
        // 40 local events, 2 states: state 1's row starts at bit 40.
        let mut defined = [0u32; 3];
        for e in [0usize, 31, 32, 39] {
            let bit = 40 + e;
            defined[bit / 32] |= 1 << (bit % 32);
        }
        let t = SupervisorTable {
            events: 40,
            state_bits: 1,
            defined: &defined,
            targets: &[0, 0, 0],
            rows: Rows::Dense,
        };
        assert_eq!(t.enabled(1, 0, 32), 1 | 1 << 31);
        assert_eq!(t.enabled(1, 32, 32), 1 | 1 << 7);
        assert_eq!(t.enabled(0, 0, 32), 0);
        let by_lookup = (0..40u16).filter(|&e| t.next_state(1, e).is_some()).count();
        assert_eq!(by_lookup, 4, "the same row as the lookups see");
    }

    #[test]
    fn entries_straddling_a_word_boundary_read_back() {
        // 5-bit entries: entry 6 spans bits 30..35.
        let mut words = [0u32; 2];
        let value = 0b10111u32;
        words[0] |= value << 30;
        words[1] |= value >> 2;
        assert_eq!(read_bits(&words, 6, 5), value);
        assert_eq!(read_bits(&words, 5, 5), 0);
        assert_eq!(read_bits(&words, 100, 5), 0, "out of range reads 0");
    }

    #[test]
    fn counting_ones_across_words() {
        let words = [u32::MAX, 0b101];
        assert_eq!(ones_between(&words, 0, 64), 34);
        assert_eq!(ones_between(&words, 30, 35), 4);
        assert_eq!(ones_between(&words, 33, 33), 0);
    }
}
