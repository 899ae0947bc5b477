//! Place and transition invariants: the minimal semi-positive solutions
//! of `yᵀ·D = 0` (P-semiflows: weighted token sums every firing keeps,
//! so `y·m = y·m0` in every reachable marking) and of `D·x = 0`
//! (T-semiflows: firing counts that lead back to the same marking).
//!
//! Computed with the Farkas algorithm (the Martínez–Silva elimination):
//! start from `[D | I]` and cancel the columns of `D` one by one by
//! positive combinations of row pairs, keeping only rows of minimal
//! support. Every semi-positive invariant is a nonnegative rational
//! combination of the minimal ones returned. The number of minimal
//! invariants can grow exponentially with the net; past
//! [`MAX_ROWS`] intermediate rows the computation is refused rather than
//! exhausting memory.

use super::PetriNet;
use crate::error::{Error, Result};

/// The most rows the elimination may hold at once.
pub const MAX_ROWS: usize = 20_000;

/// One minimal semi-positive invariant: (index, weight > 0), by index.
pub type Semiflow = Vec<(usize, u64)>;

/// The minimal P-semiflows of `net` (indices are places).
pub fn place_invariants(net: &PetriNet) -> Result<Vec<Semiflow>> {
    semiflows(&net.incidence(), net.name(), "place")
}

/// The minimal T-semiflows of `net` (indices are transitions).
pub fn transition_invariants(net: &PetriNet) -> Result<Vec<Semiflow>> {
    let d = net.incidence();
    let places = d.len();
    let transitions = net.transitions().len();
    let transposed: Vec<Vec<i64>> = (0..transitions)
        .map(|t| (0..places).map(|p| d[p][t]).collect())
        .collect();
    semiflows(&transposed, net.name(), "transition")
}

/// The minimal semi-positive `y` with `yᵀ·a = 0`, for `a` of `n` rows.
fn semiflows(a: &[Vec<i64>], net: &str, what: &str) -> Result<Vec<Semiflow>> {
    let n = a.len();
    let columns = a.first().map_or(0, Vec::len);
    // Each row: the remaining columns of `a`, then its `y` (identity).
    let mut rows: Vec<(Vec<i128>, Vec<i128>)> = (0..n)
        .map(|i| {
            let mut y = vec![0i128; n];
            y[i] = 1;
            (a[i].iter().map(|&v| i128::from(v)).collect(), y)
        })
        .collect();
    for j in 0..columns {
        let mut next: Vec<(Vec<i128>, Vec<i128>)> = Vec::new();
        let (zero, nonzero): (Vec<_>, Vec<_>) = rows.into_iter().partition(|(c, _)| c[j] == 0);
        next.extend(zero);
        let (positive, negative): (Vec<_>, Vec<_>) =
            nonzero.into_iter().partition(|(c, _)| c[j] > 0);
        for (cp, yp) in &positive {
            for (cn, yn) in &negative {
                let (a, b) = (cp[j], -cn[j]);
                let combine = |u: &[i128], v: &[i128]| -> Vec<i128> {
                    u.iter().zip(v).map(|(x, y)| b * x + a * y).collect()
                };
                let (mut c, mut y) = (combine(cp, cn), combine(yp, yn));
                let g = c.iter().chain(&y).fold(0i128, |g, &v| gcd(g, v.abs()));
                if g > 1 {
                    c.iter_mut().chain(y.iter_mut()).for_each(|v| *v /= g);
                }
                next.push((c, y));
            }
        }
        // Keep the rows of minimal support (no other row's support is a
        // proper subset, and one row per support).
        let support = |y: &[i128]| -> Vec<bool> { y.iter().map(|&v| v != 0).collect() };
        let supports: Vec<Vec<bool>> = next.iter().map(|(_, y)| support(y)).collect();
        let mut keep = vec![true; next.len()];
        for i in 0..next.len() {
            for k in 0..next.len() {
                if i == k || !keep[k] {
                    continue;
                }
                let within = supports[k].iter().zip(&supports[i]).all(|(&s, &t)| !s || t);
                if within && (supports[k] != supports[i] || k < i) {
                    keep[i] = false;
                    break;
                }
            }
        }
        rows = next
            .into_iter()
            .zip(keep)
            .filter_map(|(row, k)| k.then_some(row))
            .collect();
        if rows.len() > MAX_ROWS {
            return Err(Error::Incompatible(format!(
                "the {what} invariants of `{net}` need more than {MAX_ROWS} intermediate rows"
            )));
        }
    }
    let mut out: Vec<Semiflow> = rows
        .into_iter()
        .map(|(_, y)| {
            y.iter()
                .enumerate()
                .filter(|&(_, &v)| v != 0)
                .map(|(i, &v)| (i, v as u64))
                .collect()
        })
        .filter(|s: &Semiflow| !s.is_empty())
        .collect();
    out.sort();
    Ok(out)
}

fn gcd(a: i128, b: i128) -> i128 {
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
                if w == 1 {
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
}
