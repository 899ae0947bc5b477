//! Guards of symbolic supervisors, evaluated in the scan.
//!
//! A symbolic supervisor (docs/formats.md, "Guard files") is a set of
//! component automata, run as ordinary supervisors, plus one guard per
//! controllable event: a Boolean function of the components' current
//! states. A controllable event with a guard ([`Guards::events`]) is
//! feasible when every supervisor having it enables it *and* its guard
//! holds (docs/semantics.md, "Feasible"). Guards hold only commands back
//! and only moves change them, so the controller asks them where it
//! chooses commands: of the commands the supervisors allow, in
//! declaration order, the first whose guard holds (a program without
//! guards runs the scan it had before them).
//!
//! Each guard is a decision diagram written as a node table. Evaluation
//! starts at the root and reads one state bit per node, so it takes at
//! most one step per state bit and no memory. Node indices: 0 is false, 1
//! is true, `k ≥ 2` is `nodes[k − 2]`. A node's children come before it
//! (`low`, `high` < its own index), which [`GuardTable::eval`] checks as
//! it walks: a table that breaks the rule, points past its end or reads a
//! bit that does not exist is refused (`None`) instead of looping or
//! reading out of range. The structure check ([`crate::validate`]) refuses
//! such an image before it runs; the scan treats a refused walk as a
//! guard that does not hold (disabling a command is always safe).

pub use crate::program::{GuardNode, GuardSpec, Guards, StateBit};

/// A guard as a node table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GuardTable<'a> {
    /// The root: 0 false, 1 true, `k ≥ 2` the node `nodes[k − 2]`.
    pub root: u16,
    /// The decision nodes, children first ([`GuardNode`] records).
    pub nodes: &'a [[u32; 2]],
}

impl<'a> Guards<'a> {
    /// The node table of `guard` (empty when its span lies past the pool).
    pub fn table(&self, guard: &GuardSpec) -> GuardTable<'a> {
        GuardTable {
            root: guard.root,
            nodes: guard.nodes.of(self.nodes),
        }
    }

    /// Whether `guard` holds in the supervisor states `states`; `false`
    /// for a malformed table.
    #[inline]
    pub fn holds(&self, guard: &GuardSpec, states: &[u32]) -> bool {
        self.table(guard).eval(self.bits, states) == Some(true)
    }
}

impl GuardTable<'_> {
    /// The guard's value in the component states `states`, whose bits are
    /// found through `bits`; `None` for a malformed table or a bit source
    /// past `states`.
    pub fn eval(&self, bits: &[[u32; 1]], states: &[u32]) -> Option<bool> {
        let mut at = self.root;
        while at >= 2 {
            let node = GuardNode::from_words(self.nodes.get(usize::from(at) - 2)?);
            let source = StateBit::from_words(bits.get(usize::from(node.bit))?);
            let state = states.get(usize::from(source.component))?;
            let next = if state.checked_shr(source.shift.into())? & 1 == 1 {
                node.high
            } else {
                node.low
            };
            // Children come first: every step goes down, so the walk ends.
            if next >= at {
                return None;
            }
            at = next;
        }
        Some(at == 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::program::leak::records;

    /// Two one-bit components `a`, `b`: bit 0 is `a`, bit 1 is `b`.
    const BITS: [StateBit; 2] = [
        StateBit {
            component: 0,
            shift: 0,
        },
        StateBit {
            component: 1,
            shift: 0,
        },
    ];

    /// `a XOR b`: node 2 reads `b` (0 → false, 1 → true), node 3 reads
    /// `b` the other way round, node 4 reads `a`.
    const XOR: [GuardNode; 3] = [
        GuardNode {
            bit: 1,
            low: 0,
            high: 1,
        },
        GuardNode {
            bit: 1,
            low: 1,
            high: 0,
        },
        GuardNode {
            bit: 0,
            low: 2,
            high: 3,
        },
    ];

    #[test]
    fn a_table_computes_its_function_bit_by_bit() {
        let xor = GuardTable {
            root: 4,
            nodes: records(&XOR),
        };
        for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            assert_eq!(xor.eval(records(&BITS), &[a, b]), Some(a != b), "{a} {b}");
        }
        let constant = |root| GuardTable { root, nodes: &[] };
        assert_eq!(constant(0).eval(records(&BITS), &[1, 1]), Some(false));
        assert_eq!(constant(1).eval(records(&BITS), &[0, 0]), Some(true));
    }

    #[test]
    fn a_wider_state_reads_the_bit_at_its_shift() {
        // One component of 4 states: bit 0 is its high bit, bit 1 its low.
        let bits = [
            StateBit {
                component: 0,
                shift: 1,
            },
            StateBit {
                component: 0,
                shift: 0,
            },
        ];
        // State 2 (binary 10) and only it.
        let nodes = [
            GuardNode {
                bit: 1,
                low: 1,
                high: 0,
            },
            GuardNode {
                bit: 0,
                low: 0,
                high: 2,
            },
        ];
        let only_2 = GuardTable {
            root: 3,
            nodes: records(&nodes),
        };
        let allowed: [bool; 4] =
            core::array::from_fn(|s| only_2.eval(records(&bits), &[s as u32]).unwrap());
        assert_eq!(allowed, [false, false, true, false]);
    }

    #[test]
    fn a_malformed_table_is_refused_not_followed() {
        let up = [GuardNode {
            bit: 0,
            low: 2,
            high: 1,
        }];
        // A node pointing to itself would loop for ever.
        assert_eq!(
            GuardTable {
                root: 2,
                nodes: records(&up)
            }
            .eval(records(&BITS), &[0, 0]),
            None
        );
        // Past the end of the table, of the bit sources, of the states.
        assert_eq!(
            GuardTable {
                root: 3,
                nodes: records(&up)
            }
            .eval(records(&BITS), &[0, 0]),
            None
        );
        let far_bit = [GuardNode {
            bit: 7,
            low: 0,
            high: 1,
        }];
        assert_eq!(
            GuardTable {
                root: 2,
                nodes: records(&far_bit)
            }
            .eval(records(&BITS), &[0, 0]),
            None
        );
        assert_eq!(
            GuardTable {
                root: 4,
                nodes: records(&XOR)
            }
            .eval(records(&BITS), &[0]),
            None
        );
    }
}
