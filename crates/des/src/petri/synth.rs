//! Place-invariant synthesis (Yamalidou, Moody, Lemmon, Antsaklis 1996),
//! as the seed paper applies it.
//!
//! Each constraint `L·m ≤ b` over the plant's places becomes one control
//! place `c` whose incidence row is `D_c = −L·D_p` and whose initial
//! marking is `m_c0 = b − L·m_p0`. Then `L·m_p + m_c = b` is a place
//! invariant of the controlled net, so `m_c ≥ 0` is the constraint:
//! a transition that would break it lacks the token of `c` it needs.
//!
//! Refused, at the constraint's line: an initial marking that already
//! violates the constraint (`m_c0 < 0`); a constraint that would have to
//! keep an uncontrollable transition from firing (`D_c[t] < 0`, that is
//! `L·D_uc ≤ 0` fails) or that needs to see an unobservable one
//! (`D_c[t] ≠ 0`), naming those transitions; and a control place a net
//! cannot hold (an arc or an initial marking above 2^32 − 1). The
//! arithmetic is exact, never wrapped. ([`super::admissible`] transforms
//! an inadmissible constraint into an admissible one.)

use super::constraints::Constraint;
use super::{PetriNet, Place};
use crate::error::{Error, Result};

/// The control place one constraint gives.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ControlPlace {
    /// The constraint's name (also the place's name).
    pub constraint: String,
    /// The place's id in the controlled net (`c1`, `c2`, …, made unique).
    pub id: String,
    /// `D_c`: its incidence row, by plant transition.
    pub incidence: Vec<i64>,
    /// `m_c0`.
    pub initial: u32,
}

/// The controlled net and its control places.
#[derive(Debug, Clone)]
pub struct Supervised {
    /// The plant's places, transitions and arcs unchanged, plus one place
    /// per constraint (after the plant's) with its arcs and marking.
    pub net: PetriNet,
    /// The control places, in constraint order.
    pub control: Vec<ControlPlace>,
}

/// Synthesises the control places of `constraints` for `plant`.
///
/// The arithmetic is exact (`i128`: a weight below 2^63 times an
/// incidence below 2^32, summed over the places), and a result a net
/// cannot hold is refused at the constraint's line with the limit named:
/// an arc weight `|D_c[t]|` or an initial marking `m_c0` above 2^32 − 1.
pub fn synthesize(plant: &PetriNet, constraints: &[Constraint]) -> Result<Supervised> {
    let transitions = plant.transitions();
    let columns: Vec<Vec<i64>> = (0..transitions.len()).map(|t| plant.change(t)).collect();
    let mut net = plant.clone();
    let mut control = Vec::with_capacity(constraints.len());
    for (k, c) in constraints.iter().enumerate() {
        // D_c = −L·D_p, m_c0 = b − L·m_p0, exactly.
        let exact: Vec<i128> = columns
            .iter()
            .map(|column| {
                -c.weights
                    .iter()
                    .map(|&(p, w)| i128::from(w) * i128::from(column[p]))
                    .sum::<i128>()
            })
            .collect();
        let weighted = c.weighted(plant.initial());
        let initial = i128::from(c.bound) - weighted;
        if initial < 0 {
            return Err(Error::model(
                c.location.clone(),
                format!(
                    "constraint `{}`: the initial marking already violates it (L·m0 = {weighted} > {})",
                    c.name, c.bound
                ),
            ));
        }
        let initial = u32::try_from(initial).map_err(|_| {
            Error::model(
                c.location.clone(),
                format!(
                    "constraint `{}`: its control place would start with m_c0 = b − L·m0 = {initial} \
                     tokens, more than a place holds (2^32 − 1)",
                    c.name
                ),
            )
        })?;
        let offending = |keep: &dyn Fn(usize) -> bool| -> Vec<&str> {
            (0..transitions.len())
                .filter(|&t| keep(t))
                .map(|t| transitions[t].id.as_str())
                .collect()
        };
        let blocks = offending(&|t| !transitions[t].controllable && exact[t] < 0);
        if !blocks.is_empty() {
            return Err(Error::model(
                c.location.clone(),
                format!(
                    "constraint `{}` is not admissible: enforcing it would mean keeping the \
                     uncontrollable transition(s) {} from firing (L·D_uc ≤ 0 fails); \
                     change the constraint so that they never raise L·m (`codegen petri synth \
                     --transform` finds such a form)",
                    c.name,
                    quoted_list(&blocks)
                ),
            ));
        }
        let unseen = offending(&|t| !transitions[t].observable && exact[t] != 0);
        if !unseen.is_empty() {
            return Err(Error::model(
                c.location.clone(),
                format!(
                    "constraint `{}` is not admissible: its control place would have to see \
                     the unobservable transition(s) {} fire (L·D_uo = 0 fails)",
                    c.name,
                    quoted_list(&unseen)
                ),
            ));
        }
        // D_c with every entry checked to fit an arc, hence an i64.
        let mut row: Vec<i64> = Vec::with_capacity(exact.len());
        let mut arcs: Vec<(usize, i64, u32)> = Vec::new();
        for (t, &w) in exact.iter().enumerate() {
            let weight = u32::try_from(w.unsigned_abs()).map_err(|_| {
                Error::model(
                    c.location.clone(),
                    format!(
                        "constraint `{}`: its control place would need an arc of weight {} on \
                         transition `{}` (D_c = −L·D_p), more than an arc holds (2^32 − 1)",
                        c.name,
                        w.unsigned_abs(),
                        transitions[t].id
                    ),
                )
            })?;
            let signed = if w < 0 {
                -i64::from(weight)
            } else {
                i64::from(weight)
            };
            row.push(signed);
            if signed != 0 {
                arcs.push((t, signed, weight));
            }
        }
        let id = fresh_id(&net, k + 1);
        let place = net.places.len();
        net.places.push(Place {
            id: id.clone(),
            name: Some(c.name.clone()),
        });
        net.initial.push(initial);
        for (t, signed, weight) in arcs {
            if signed > 0 {
                net.transitions[t].output.push((place, weight));
            } else {
                net.transitions[t].input.push((place, weight));
            }
        }
        control.push(ControlPlace {
            constraint: c.name.clone(),
            id,
            incidence: row,
            initial,
        });
    }
    Ok(Supervised { net, control })
}

/// `c{k}`, with `_` appended until no place or transition of `net` has it.
fn fresh_id(net: &PetriNet, k: usize) -> String {
    let mut id = format!("c{k}");
    while net.place(&id).is_some() || net.transition(&id).is_some() {
        id.push('_');
    }
    id
}

fn quoted_list(ids: &[&str]) -> String {
    ids.iter()
        .map(|id| format!("`{id}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::super::{constraints, reach, toml};
    use super::*;
    use std::path::Path;

    fn repo(path: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path)
    }

    fn mixers() -> PetriNet {
        super::super::read_file(&repo("models/petri/mixers.toml")).unwrap()
    }

    fn constraint(net: &PetriNet, text: &str) -> Result<Vec<Constraint>> {
        constraints::read(text, Path::new("c.toml"), net)
    }

    #[test]
    fn the_mixers_get_the_papers_control_place_and_become_safe() {
        let plant = mixers();
        let cs =
            constraints::read_file(&repo("models/petri/mixers.constraints.toml"), &plant).unwrap();
        let s = synthesize(&plant, &cs).unwrap();
        // SEEDS.md D: D_c = [−1 1 0 0 −1 1 0 0], m_c0 = 1.
        assert_eq!(s.control[0].incidence, [-1, 1, 0, 0, -1, 1, 0, 0]);
        assert_eq!(s.control[0].initial, 1);
        assert_eq!(s.control[0].id, "c1");
        // The plant is unchanged inside the controlled net.
        assert_eq!(&s.net.places()[..9], plant.places());
        assert_eq!(&s.net.initial()[..9], &plant.initial()[..]);
        let r = reach::reachability(&s.net, 1000).unwrap();
        assert!(r.is_safe(), "bounds {:?}", r.bounds);
        assert!(r.dead.is_empty());
        // The invariant μ_m3 + μ_c1 = 1 (SEEDS.md D) in every marking.
        for m in &r.markings {
            assert_eq!(m[2] + m[9], 1, "{}", s.net.marking_name(m));
        }
        // Of the plant's 4 × 4 stage pairs only "both filling" is gone.
        assert_eq!(r.markings.len(), 15);
        assert!(
            r.automaton.state_by_name("ma2+m3+mb1").is_some(),
            "A fills alone"
        );
        assert!(
            r.automaton.state_by_name("ma1+mb1+c1").is_some(),
            "the initial marking"
        );
    }

    #[test]
    fn inadmissible_and_violated_constraints_are_refused_at_their_line() {
        // The mixers with t2 ("A full", consumes m3) uncontrollable is still
        // fine (it lowers m3); t1 uncontrollable is not (it raises m3).
        let text = std::fs::read_to_string(repo("models/petri/mixers.toml")).unwrap();
        let t1_wild = text.replace(
            "{ id = \"t1\", controllable = true",
            "{ id = \"t1\", controllable = false",
        );
        let plant = toml::read(&t1_wild, Path::new("m.toml")).unwrap();
        let cs = constraint(
            &plant,
            "\n[[constraint]]\nname = \"supply\"\nweights = { m3 = 1 }\nbound = 1\n",
        )
        .unwrap();
        let err = synthesize(&plant, &cs).unwrap_err().to_string();
        assert!(
            err.starts_with("c.toml:2:1: constraint `supply` is not admissible: enforcing it would mean keeping the uncontrollable transition(s) `t1` from firing"),
            "{err}"
        );
        let t2_wild = text.replace(
            "{ id = \"t2\", controllable = true",
            "{ id = \"t2\", controllable = false",
        );
        let plant = toml::read(&t2_wild, Path::new("m.toml")).unwrap();
        assert!(synthesize(&plant, &cs).is_ok());

        let plant = mixers();
        let cs = constraint(
            &plant,
            "[[constraint]]\nname = \"none idle\"\nweights = { ma1 = 1, mb1 = 1 }\nbound = 1\n",
        )
        .unwrap();
        let err = synthesize(&plant, &cs).unwrap_err().to_string();
        assert_eq!(
            err,
            "c.toml:1:1: constraint `none idle`: the initial marking already violates it (L·m0 = 2 > 1)"
        );
    }

    #[test]
    fn constraint_files_are_checked_against_the_net() {
        let plant = mixers();
        let err = |text: &str| constraint(&plant, text).unwrap_err().to_string();
        assert_eq!(
            err("[[constraint]]\nname = \"x\"\nweights = { m9 = 1 }\nbound = 1\n"),
            "c.toml:1:1: `m9` is no place of net `mixers`"
        );
        assert_eq!(
            err("[[constraint]]\nname = \"x\"\nweights = { m3 = 0 }\nbound = 1\n"),
            "c.toml:1:1: constraint `x` weighs no place"
        );
        assert_eq!(
            err("[[constraint]]\nname = \"x\"\nweights = { m3 = 1 }\nbound = 1\n[[constraint]]\nname = \"x\"\nweights = { m3 = 1 }\nbound = 1\n"),
            "c.toml:5:1: constraint `x` is already declared at line 1"
        );
        assert!(err("").contains("no [[constraint]]"));
        // One place by id and by name: refused, not summed (to zero here).
        assert_eq!(
            err("[[constraint]]\nname = \"x\"\nweights = { m3 = 1, \"mixers on the supply\" = -1 }\nbound = 1\n"),
            "c.toml:1:1: constraint `x` weighs place `m3` twice (as `m3` and as `mixers on the supply`): give it one weight"
        );
        // By name where one place has it.
        let cs = constraint(
            &plant,
            "[[constraint]]\nname = \"x\"\nweights = { \"mixers on the supply\" = 1 }\nbound = 1\n",
        )
        .unwrap();
        assert_eq!(cs[0].weights, [(2, 1)]);
    }

    /// `go` puts four tokens in `busy`, `done` (uncontrollable) takes them.
    const FOURS: &str = "name = \"fours\"\nplaces = [{ id = \"free\", tokens = 1 }, { id = \"busy\" }]\n\
        transitions = [{ id = \"go\", controllable = true, input = { free = 1 }, output = { busy = 4 } },\n\
        { id = \"done\", controllable = false, input = { busy = 4 }, output = { free = 1 } }]\n";

    #[test]
    fn a_control_place_beyond_an_arc_or_a_place_is_refused_not_wrapped() {
        let plant = toml::read(FOURS, Path::new("f.toml")).unwrap();
        // busy weighted 2^62: D_c[go] = −2^64, which a 64-bit product
        // wrapped to 0: a control place without arcs, `go` never held.
        let cs = constraint(
            &plant,
            "[[constraint]]\nname = \"never busy\"\nweights = { busy = 4611686018427387904 }\nbound = 0\n",
        )
        .unwrap();
        assert_eq!(
            synthesize(&plant, &cs).unwrap_err().to_string(),
            "c.toml:1:1: constraint `never busy`: its control place would need an arc of weight \
             18446744073709551616 on transition `go` (D_c = −L·D_p), more than an arc holds (2^32 − 1)"
        );
        // m_c0 = b − L·m0 beyond a place's 2^32 − 1 tokens.
        let cs = constraint(
            &plant,
            "[[constraint]]\nname = \"loose\"\nweights = { busy = 1 }\nbound = 9223372036854775807\n",
        )
        .unwrap();
        assert_eq!(
            synthesize(&plant, &cs).unwrap_err().to_string(),
            "c.toml:1:1: constraint `loose`: its control place would start with m_c0 = b − L·m0 = \
             9223372036854775807 tokens, more than a place holds (2^32 − 1)"
        );
        // Where L·D_p is 0 exactly (4·free + busy is kept: 2^62 and 2^60
        // times it here), the control place has no arcs, and rightly.
        let cs = constraint(
            &plant,
            "[[constraint]]\nname = \"kept\"\nweights = { free = 4611686018427387904, busy = 1152921504606846976 }\nbound = 4611686018427387904\n",
        )
        .unwrap();
        let s = synthesize(&plant, &cs).unwrap();
        assert_eq!(
            (&s.control[0].incidence[..], s.control[0].initial),
            (&[0, 0][..], 0)
        );
    }
}
