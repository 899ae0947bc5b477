//! Place and transition invariants: the minimal semi-positive solutions
//! of `yᵀ·D = 0` (P-semiflows: weighted token sums every firing keeps,
//! so `y·m = y·m0` in every reachable marking) and of `D·x = 0`
//! (T-semiflows: firing counts that lead back to the same marking).
//!
//! Computed with the Farkas algorithm (the Martínez–Silva elimination):
//! start from `[D | I]` and cancel the columns of `D` one by one by
//! positive combinations of row pairs, keeping only rows of minimal
//! support. Every semi-positive invariant is a nonnegative rational
//! combination of the minimal ones returned.
//!
//! **Minimal supports, incrementally.** Each row carries the support of
//! its `y` as a bit set. The rows that already have a zero in the column
//! being cancelled were minimal at the previous step and stay so (a
//! combination's support is the union of its parents', so it cannot be
//! strictly inside a row its parents were not). Only a new combination
//! needs checking, and it is checked before it is built: it is dropped
//! when its support has more than `j + 2` places after `j + 1` columns
//! (a minimal support's rows have rank one less than its size, and the
//! rank is at most the number of columns), or when a row kept so far
//! has a support inside it; a kept combination removes the earlier
//! combinations whose support strictly contains its own. On a ring of
//! `K` places this is `O(K²)` subset tests in all, where filtering every
//! row pair after every column was `O(K⁴)`.
//!
//! **Bounded work.** The number of minimal invariants can grow
//! exponentially with the net, so the elimination is refused, naming the
//! limit, as soon as it would hold more than [`MAX_ROWS`] rows or
//! [`MAX_CELLS`] numbers (checked before the next row is built), or when the candidate pairs and support tests
//! of the whole computation exceed [`MAX_SUPPORT_TESTS`].
//!
//! **Exact weights.** Rows are `i128`, every combination is checked, and
//! a weight beyond `i128` is refused rather than wrapped; the invariants
//! returned have `u128` weights (a chain of arcs of weight 2^32 − 1 has
//! an invariant weight of (2^32 − 1)^3, printed in full).

use super::PetriNet;
use crate::error::{Error, Result};
use fixedbitset::FixedBitSet;

/// The most rows the elimination may hold at once.
pub const MAX_ROWS: usize = 20_000;

/// The most numbers (rows × their width, places plus transitions) the
/// elimination may hold at once: the rows of a wide net are fewer.
pub const MAX_CELLS: usize = 1 << 24;

/// The most candidate row pairs and support-subset tests one computation
/// may make, in all.
pub const MAX_SUPPORT_TESTS: u64 = 200_000_000;

/// One minimal semi-positive invariant: (index, weight > 0), by index.
pub type Semiflow = Vec<(usize, u128)>;

/// `y·m`, exactly, or `None` beyond `u128`.
pub fn value(y: &Semiflow, m: &[u32]) -> Option<u128> {
    y.iter().try_fold(0u128, |sum, &(i, w)| {
        sum.checked_add(w.checked_mul(u128::from(m[i]))?)
    })
}

/// The limits of one computation.
#[derive(Debug, Clone, Copy)]
struct Budget {
    rows: usize,
    cells: usize,
    tests: u64,
}

const BUDGET: Budget = Budget {
    rows: MAX_ROWS,
    cells: MAX_CELLS,
    tests: MAX_SUPPORT_TESTS,
};

/// The minimal P-semiflows of `net` (indices are places).
pub fn place_invariants(net: &PetriNet) -> Result<Vec<Semiflow>> {
    semiflows(&net.incidence(), net.name(), "place", BUDGET)
}

/// The minimal T-semiflows of `net` (indices are transitions).
pub fn transition_invariants(net: &PetriNet) -> Result<Vec<Semiflow>> {
    let transposed: Vec<Vec<i64>> = (0..net.transitions().len())
        .map(|t| net.change(t))
        .collect();
    semiflows(&transposed, net.name(), "transition", BUDGET)
}

/// One row of the elimination: the remaining columns of `a`, its `y`,
/// and the support of `y`.
struct Row {
    columns: Vec<i128>,
    y: Vec<i128>,
    support: FixedBitSet,
}

/// The minimal semi-positive `y` with `yᵀ·a = 0`, for `a` of `n` rows.
fn semiflows(a: &[Vec<i64>], net: &str, what: &str, budget: Budget) -> Result<Vec<Semiflow>> {
    let n = a.len();
    let columns = a.first().map_or(0, Vec::len);
    let too_many = |why: String| {
        Error::Incompatible(format!(
            "the {what} invariants of `{net}` are not computed: {why}"
        ))
    };
    let width = (n + columns).max(1);
    let row_limit = budget.rows.min(budget.cells / width);
    let over_limit = || {
        too_many(format!(
            "more than {row_limit} intermediate rows (the limit: {} rows, and {} numbers \
             in all at {width} a row)",
            budget.rows, budget.cells
        ))
    };
    if n > row_limit {
        return Err(over_limit());
    }
    let mut rows: Vec<Row> = (0..n)
        .map(|i| {
            let mut y = vec![0i128; n];
            y[i] = 1;
            let mut support = FixedBitSet::with_capacity(n);
            support.insert(i);
            Row {
                columns: a[i].iter().map(|&v| i128::from(v)).collect(),
                y,
                support,
            }
        })
        .collect();
    let mut tests: u64 = 0;
    for j in 0..columns {
        let mut zero = Vec::new();
        let (mut positive, mut negative) = (Vec::new(), Vec::new());
        for row in rows {
            match row.columns[j].signum() {
                0 => zero.push(row),
                1 => positive.push(row),
                _ => negative.push(row),
            }
        }
        // `next[..kept_before]` are the zero rows, minimal already; the
        // combinations follow, `None` once a later one dominates them.
        let mut next: Vec<Option<Row>> = zero.into_iter().map(Some).collect();
        let zero_rows = next.len();
        let mut live = zero_rows;
        let largest_support = j + 2;
        for p in &positive {
            for q in &negative {
                tests += 1;
                let mut support = p.support.clone();
                support.union_with(&q.support);
                if support.count_ones(..) > largest_support {
                    continue;
                }
                let mut dominated = false;
                for row in next.iter().flatten() {
                    tests += 1;
                    if row.support.is_subset(&support) {
                        dominated = true;
                        break;
                    }
                }
                if tests > budget.tests {
                    return Err(too_many(format!(
                        "more than {} row pairs and support tests",
                        budget.tests
                    )));
                }
                if dominated {
                    continue;
                }
                let row = combine(p, q, j, support)
                    .ok_or_else(|| too_many("a weight beyond the 128-bit range".to_owned()))?;
                tests += (next.len() - zero_rows) as u64;
                for slot in next[zero_rows..].iter_mut() {
                    if slot
                        .as_ref()
                        .is_some_and(|r| row.support.is_subset(&r.support))
                    {
                        *slot = None;
                        live -= 1;
                    }
                }
                if live == row_limit {
                    return Err(over_limit());
                }
                next.push(Some(row));
                live += 1;
            }
        }
        rows = next.into_iter().flatten().collect();
    }
    let mut out: Vec<Semiflow> = rows
        .into_iter()
        .map(|row| {
            row.y
                .iter()
                .enumerate()
                .filter(|&(_, &v)| v != 0)
                .filter_map(|(i, &v)| u128::try_from(v).ok().map(|v| (i, v)))
                .collect()
        })
        .filter(|s: &Semiflow| !s.is_empty())
        .collect();
    out.sort();
    Ok(out)
}

/// `b·p + a·q` for `a = p[j] > 0`, `b = −q[j] > 0` (column `j` cancels),
/// divided by the gcd of its entries; `None` when an entry leaves `i128`.
fn combine(p: &Row, q: &Row, j: usize, support: FixedBitSet) -> Option<Row> {
    let (a, b) = (p.columns[j], q.columns[j].checked_neg()?);
    let mix = |u: &[i128], v: &[i128]| -> Option<Vec<i128>> {
        u.iter()
            .zip(v)
            .map(|(&x, &y)| b.checked_mul(x)?.checked_add(a.checked_mul(y)?))
            .collect()
    };
    let (mut columns, mut y) = (mix(&p.columns, &q.columns)?, mix(&p.y, &q.y)?);
    let g = columns
        .iter()
        .chain(&y)
        .fold(0u128, |g, &v| gcd(g, v.unsigned_abs()));
    if g > 1 {
        // g divides every entry, and g ≤ |entry| ≤ i128::MAX for a nonzero one.
        let g = i128::try_from(g).ok()?;
        columns.iter_mut().chain(y.iter_mut()).for_each(|v| *v /= g);
    }
    Some(Row {
        columns,
        y,
        support,
    })
}

fn gcd(a: u128, b: u128) -> u128 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{constraints, synth, toml};
    use super::*;
    use std::path::Path;

    const MIXERS: &str = include_str!("../../../../models/petri/mixers.toml");
    const SUPPLY: &str = include_str!("../../../../models/petri/mixers.constraints.toml");

    fn ids(net: &PetriNet, s: &Semiflow, places: bool) -> String {
        s.iter()
            .map(|&(i, w)| {
                let id = if places {
                    &net.places()[i].id
                } else {
                    &net.transitions()[i].id
                };
                if w == 1u128 {
                    id.clone()
                } else {
                    format!("{w}·{id}")
                }
            })
            .collect::<Vec<_>>()
            .join(" + ")
    }

    #[test]
    fn the_mixers_conserve_each_mixer_and_the_supervisor_adds_the_papers_invariant() {
        let plant = toml::read(MIXERS, Path::new("m.toml")).unwrap();
        let p: Vec<String> = place_invariants(&plant)
            .unwrap()
            .iter()
            .map(|s| ids(&plant, s, true))
            .collect();
        // Each mixer's stages; and, since m3 counts the mixers filling
        // (m3 = ma2 + mb2 is kept too, though not semi-positive), both
        // mixers' stages with m3 for the two filling ones.
        assert_eq!(
            p,
            [
                "ma1 + ma2 + ma4 + ma5",
                "ma1 + m3 + ma4 + ma5 + mb1 + mb4 + mb5",
                "mb1 + mb2 + mb4 + mb5"
            ]
        );
        let t: Vec<String> = transition_invariants(&plant)
            .unwrap()
            .iter()
            .map(|s| ids(&plant, s, false))
            .collect();
        assert_eq!(t, ["t1 + t2 + t3 + t4", "t5 + t6 + t7 + t8"]);

        let cs = constraints::read(SUPPLY, Path::new("c.toml"), &plant).unwrap();
        let s = synth::synthesize(&plant, &cs).unwrap();
        let p: Vec<String> = place_invariants(&s.net)
            .unwrap()
            .iter()
            .map(|f| ids(&s.net, f, true))
            .collect();
        // SEEDS.md D: μ_m3 + μ_c1 = 1; and the mutual exclusion it means.
        assert!(p.contains(&"m3 + c1".to_owned()), "{p:?}");
        assert!(p.contains(&"ma2 + mb2 + c1".to_owned()), "{p:?}");
    }

    #[test]
    fn weights_and_minimality() {
        // t moves one token out of a and two into b: 2·a + b is kept.
        let net = toml::read(
            "name = \"w\"\nplaces = [{ id = \"a\", tokens = 2 }, { id = \"b\" }]\n\
             transitions = [{ id = \"t\", controllable = true, input = { a = 1 }, output = { b = 2 } },\n\
             { id = \"u\", controllable = true, input = { b = 2 }, output = { a = 1 } }]\n",
            Path::new("w.toml"),
        )
        .unwrap();
        assert_eq!(place_invariants(&net).unwrap(), [vec![(0, 2), (1, 1)]]);
        assert_eq!(transition_invariants(&net).unwrap(), [vec![(0, 1), (1, 1)]]);
    }

    fn net(text: &str) -> PetriNet {
        toml::read(text, Path::new("n.toml")).unwrap()
    }

    /// A net in the native form from (id, tokens) places and
    /// (id, inputs, outputs) transitions, all controllable.
    fn build(places: &[(String, u32)], transitions: &[(String, String, String)]) -> PetriNet {
        let mut t = String::from("name = \"n\"\nplaces = [\n");
        for (id, k) in places {
            t.push_str(&format!("  {{ id = \"{id}\", tokens = {k} }},\n"));
        }
        t.push_str("]\ntransitions = [\n");
        for (id, input, output) in transitions {
            t.push_str(&format!(
                "  {{ id = \"{id}\", controllable = true, input = {{ {input} }}, output = {{ {output} }} }},\n"
            ));
        }
        t.push_str("]\n");
        net(&t)
    }

    #[test]
    fn weights_beyond_64_bits_are_exact() {
        // Each t_i turns a token of p_i into 2^32 − 1 of p_{i+1}: the
        // invariant weighs p0 by (2^32 − 1)^3 (it once printed modulo 2^64).
        let w = u32::MAX;
        let places: Vec<(String, u32)> = (0..4)
            .map(|i| (format!("p{i}"), u32::from(i == 0)))
            .collect();
        let transitions: Vec<(String, String, String)> = (0..3)
            .map(|i| {
                (
                    format!("t{i}"),
                    format!("p{i} = 1"),
                    format!("p{} = {w}", i + 1),
                )
            })
            .collect();
        let chain = build(&places, &transitions);
        let w = u128::from(w);
        let ys = place_invariants(&chain).unwrap();
        assert_eq!(ys, [vec![(0, w * w * w), (1, w * w), (2, w), (3, 1)]]);
        assert_eq!(w * w * w, 79_228_162_458_924_105_385_300_197_375);
        assert_eq!(value(&ys[0], chain.initial()), Some(w * w * w));
        assert_eq!(value(&vec![(0, u128::MAX / 2)], &[3]), None, "beyond u128");
    }

    #[test]
    fn a_ring_has_one_invariant_found_without_filtering_every_pair() {
        // 400 places in a ring: each column combines one pair; the old
        // filter compared every row with every row after every column
        // (K^4); now each new row is checked against the rows kept.
        let k = 400;
        let places: Vec<(String, u32)> = (0..k)
            .map(|i| (format!("p{i}"), u32::from(i == 0)))
            .collect();
        let transitions: Vec<(String, String, String)> = (0..k)
            .map(|i| {
                (
                    format!("t{i}"),
                    format!("p{i} = 1"),
                    format!("p{} = 1", (i + 1) % k),
                )
            })
            .collect();
        let ring = build(&places, &transitions);
        let ys = place_invariants(&ring).unwrap();
        assert_eq!(ys, [(0..k).map(|p| (p, 1)).collect::<Vec<_>>()]);
        let xs = transition_invariants(&ring).unwrap();
        assert_eq!(xs, [(0..k).map(|t| (t, 1)).collect::<Vec<_>>()]);
    }

    #[test]
    fn an_exploding_elimination_stops_at_its_limit_before_building_past_it() {
        // 100 places x_i fed by t0 and 100 places y_j drained by it: the
        // first column gives 10,000 rows (x_i + y_j); t1 moves x_50..x_99
        // into x_0..x_49, so the second column pairs 5,000 rows with
        // 5,000 (25 million candidates; they were all built, ~10^8 rows
        // and gigabytes, before the row limit was checked).
        let places: Vec<(String, u32)> = (0..100)
            .map(|i| (format!("x{i}"), 0))
            .chain((0..100).map(|j| (format!("y{j}"), 0)))
            .collect();
        let list = |prefix: &str, range: std::ops::Range<usize>| {
            range
                .map(|i| format!("{prefix}{i} = 1"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let transitions = vec![
            ("t0".to_owned(), list("y", 0..100), list("x", 0..100)),
            ("t1".to_owned(), list("x", 50..100), list("x", 0..50)),
        ];
        let blowup = build(&places, &transitions);
        // With the limits scaled down (the full ones take a second in a
        // release build, minutes in a debug one): the rows first, then
        // the work.
        let d = blowup.incidence();
        let budget = |rows, tests| Budget {
            rows,
            cells: MAX_CELLS,
            tests,
        };
        let err = semiflows(&d, "n", "place", budget(500, u64::MAX))
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "the place invariants of `n` are not computed: more than 500 intermediate rows \
             (the limit: 500 rows, and 16777216 numbers in all at 202 a row)"
        );
        let err = semiflows(&d, "n", "place", budget(20_000, 1_000_000))
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "the place invariants of `n` are not computed: more than 1000000 row pairs and \
             support tests"
        );
    }
}
