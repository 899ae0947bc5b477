//! Making an inadmissible constraint admissible, in the manner of Moody
//! and Antsaklis: `L'·m ≤ b` with `L' = L + R1`, `R1 ≥ 0` (here with
//! their `R2 = 1`). Since `R1·m ≥ 0`, every marking that satisfies the new
//! constraint satisfies the old one, so enforcing it is safe; it is
//! admissible when no uncontrollable transition raises `L'·m`.
//!
//! The weights are found greedily: while an uncontrollable transition
//! `t` raises `L'·m` by `e > 0`, the first place upstream of it (one that
//! `t` consumes from, `D[p][t] < 0`) is counted too, with weight
//! `⌈e / −D[p][t]⌉`, so that `t` no longer raises it: the supervisor must
//! then act before the tokens reach `t`. The result may be more
//! restrictive than necessary; `codegen petri synth` compares it with
//! supcon and says so when it is. Refused, with the reason: an
//! uncontrollable transition that raises `L'·m` from nowhere (no place
//! upstream), an unobservable transition that changes `L'·m`, no
//! admissible form within a bounded number of steps (a cycle of
//! uncontrollable transitions feeding the constraint), or an initial
//! marking that violates the admissible form (the constraint cannot be
//! enforced from the start).

use super::constraints::Constraint;
use super::PetriNet;
use crate::error::{Error, Result};

/// The constraints to enforce for `constraints` on `net`: with
/// `transform`, each made admissible ([`make_admissible`]; a failure is an
/// error at the constraint's location), otherwise as they are (synthesis
/// then refuses an inadmissible one).
pub fn enforced(
    net: &PetriNet,
    constraints: &[Constraint],
    transform: bool,
) -> Result<Vec<Constraint>> {
    if !transform {
        return Ok(constraints.to_vec());
    }
    constraints
        .iter()
        .map(|c| make_admissible(net, c).map_err(|why| Error::model(c.location.clone(), why)))
        .collect()
}

/// An admissible constraint that implies `c`, or why none was found.
///
/// The weights are kept exactly (`i128` while they are worked out) and
/// must stay within a constraint weight's range (`i64`): a greedy search
/// whose weights keep growing (uncontrollable transitions that multiply
/// tokens around a cycle) is refused naming that limit, never wrapped.
pub fn make_admissible(net: &PetriNet, c: &Constraint) -> Result<Constraint, String> {
    let columns: Vec<Vec<i64>> = (0..net.transitions().len())
        .map(|t| net.change(t))
        .collect();
    let places = net.places().len();
    let transitions = net.transitions();
    let mut l = vec![0i128; places];
    for &(p, w) in &c.weights {
        l[p] += i128::from(w);
    }
    // Every weight stays within i64 (checked as it changes), so each term
    // is below 2^95 and the sum is exact in i128.
    let raised = |l: &[i128], t: usize| -> i128 {
        (0..places).map(|p| l[p] * i128::from(columns[t][p])).sum()
    };
    let mut steps = 0;
    while let Some(t) =
        (0..transitions.len()).find(|&t| !transitions[t].controllable && raised(&l, t) > 0)
    {
        steps += 1;
        if steps > 4 * places * transitions.len().max(1) {
            return Err(format!(
                "no admissible form of `{}` found: uncontrollable transitions keep feeding it",
                c.name
            ));
        }
        let excess = raised(&l, t);
        let Some(p) = (0..places).find(|&p| columns[t][p] < 0) else {
            return Err(format!(
                "the uncontrollable transition `{}` raises `{}` and consumes from no place: \
                 nothing upstream can be counted instead",
                transitions[t].id, c.name
            ));
        };
        let per_token = -i128::from(columns[t][p]);
        l[p] += (excess + per_token - 1) / per_token;
        if i64::try_from(l[p]).is_err() {
            return Err(format!(
                "no admissible form of `{}` within a constraint weight's range: counting place \
                 `{}` upstream of the uncontrollable transition `{}` would need a weight of {}, \
                 beyond 2^63 − 1",
                c.name,
                net.places()[p].id,
                transitions[t].id,
                l[p]
            ));
        }
    }
    if let Some(t) =
        (0..transitions.len()).find(|&t| !transitions[t].observable && raised(&l, t) != 0)
    {
        return Err(format!(
            "the unobservable transition `{}` changes `{}`: its control place would have to see it",
            transitions[t].id, c.name
        ));
    }
    let weights: Vec<(usize, i64)> = l
        .iter()
        .enumerate()
        .filter(|&(_, &w)| w != 0)
        .filter_map(|(p, &w)| i64::try_from(w).ok().map(|w| (p, w)))
        .collect();
    let admissible = Constraint {
        name: c.name.clone(),
        weights,
        bound: c.bound,
        location: c.location.clone(),
    };
    if admissible.weighted(net.initial()) > i128::from(admissible.bound) {
        return Err(format!(
            "the admissible form of `{}` is violated by the initial marking: uncontrollable \
             transitions can break the constraint before any control acts",
            c.name
        ));
    }
    Ok(admissible)
}

#[cfg(test)]
mod tests {
    use super::super::{constraints, toml};
    use super::*;
    use std::path::Path;

    const MIXERS: &str = include_str!("../../../../models/petri/mixers.toml");
    const SUPPLY: &str = include_str!("../../../../models/petri/mixers.constraints.toml");

    #[test]
    fn an_uncontrollable_start_makes_the_constraint_count_the_idle_mixer() {
        // A starts filling on its own (t1 uncontrollable): m3 ≤ 1 cannot
        // block t1, so it must count A's idle token: m3 + ma1 ≤ 1 (B may
        // not fill while A is idle, and A may not return to idle while B
        // fills).
        let text = MIXERS.replace(
            "{ id = \"t1\", controllable = true",
            "{ id = \"t1\", controllable = false",
        );
        let net = toml::read(&text, Path::new("m.toml")).unwrap();
        let cs = constraints::read(SUPPLY, Path::new("c.toml"), &net).unwrap();
        let a = make_admissible(&net, &cs[0]).unwrap();
        assert_eq!(a.weights, [(0, 1), (2, 1)], "ma1 + m3");
        assert_eq!(a.bound, 1);
        // Both starts uncontrollable: nothing can keep them apart.
        let both = text.replace(
            "{ id = \"t5\", controllable = true",
            "{ id = \"t5\", controllable = false",
        );
        let net = toml::read(&both, Path::new("m.toml")).unwrap();
        let err = make_admissible(&net, &cs[0]).unwrap_err();
        assert!(err.contains("violated by the initial marking"), "{err}");
    }

    #[test]
    fn weights_that_keep_growing_are_refused_at_the_limit_not_wrapped() {
        // u turns a token of a into 10^6 of b, v one of b into 10^6 of a,
        // both uncontrollable: counting upstream multiplies the weights by
        // 10^6 a step, past i64 after a few steps (they once wrapped).
        let net = toml::read(
            "name = \"double\"\nplaces = [{ id = \"a\", tokens = 1 }, { id = \"b\" }]\n\
             transitions = [{ id = \"u\", controllable = false, input = { a = 1 }, output = { b = 1000000 } },\n\
             { id = \"v\", controllable = false, input = { b = 1 }, output = { a = 1000000 } }]\n",
            Path::new("d.toml"),
        )
        .unwrap();
        let cs = constraints::read(
            "[[constraint]]\nname = \"b small\"\nweights = { b = 1 }\nbound = 5\n",
            Path::new("c.toml"),
            &net,
        )
        .unwrap();
        let err = make_admissible(&net, &cs[0]).unwrap_err();
        assert_eq!(
            err,
            "no admissible form of `b small` within a constraint weight's range: counting place `b` \
             upstream of the uncontrollable transition `v` would need a weight of \
             1000000000000000000000000, beyond 2^63 − 1"
        );
    }
}
