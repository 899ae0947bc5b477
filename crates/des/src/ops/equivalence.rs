//! Language equality, inclusion and isomorphism of deterministic
//! automata, with shortest counterexamples.

use crate::automaton::{Automaton, EventId, StateId};
use std::collections::VecDeque;

/// Which language a difference is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LanguageKind {
    /// The prefix-closed language L.
    Closed,
    /// The marked language Lm.
    Marked,
}

/// A string in the given language of one automaton but not the other.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct LanguageDifference {
    /// The distinguishing string.
    pub string: Vec<String>,
    /// The language it distinguishes.
    pub language: LanguageKind,
    /// `true` if the string is in the first automaton's language.
    pub in_first: bool,
}

/// Compares the closed and marked languages of `a` and `b` (events
/// identified by name). `None` means both are equal; otherwise a shortest
/// distinguishing string.
pub fn language_difference(a: &Automaton, b: &Automaton) -> Option<LanguageDifference> {
    first_difference(a, b, Direction::Both)
}

/// A shortest string of `a`'s closed or marked language that is not in
/// `b`'s (`in_first` is then `true`); `None` when `L(a) ⊆ L(b)` and
/// `Lm(a) ⊆ Lm(b)` (events identified by name).
pub fn inclusion_counterexample(a: &Automaton, b: &Automaton) -> Option<LanguageDifference> {
    first_difference(a, b, Direction::FirstOnly)
}

/// `true` when the closed and marked languages of `a` are within those of
/// `b`.
pub fn language_included(a: &Automaton, b: &Automaton) -> bool {
    inclusion_counterexample(a, b).is_none()
}

/// Which strings [`first_difference`] looks for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Direction {
    /// In either automaton's language and not the other's.
    Both,
    /// In the first automaton's language and not the second's.
    FirstOnly,
}

/// Breadth-first over pairs of states of `a` and `b`: the first string
/// found that one language has and the other lacks (with
/// [`Direction::FirstOnly`], only those `a` has). Marking is compared as a
/// pair is reached, so a marked difference is found no later than a closed
/// one of the same length: the string is a shortest one.
fn first_difference(
    a: &Automaton,
    b: &Automaton,
    direction: Direction,
) -> Option<LanguageDifference> {
    let both = direction == Direction::Both;
    let (ia, ib) = match (a.initial(), b.initial()) {
        (None, _) if !both => return None,
        (None, None) => return None,
        (Some(_), None) | (None, Some(_)) => {
            return Some(LanguageDifference {
                string: Vec::new(),
                language: LanguageKind::Closed,
                in_first: a.initial().is_some(),
            })
        }
        (Some(ia), Some(ib)) => (ia, ib),
    };
    // b's event id for each of a's events, and vice versa.
    let a_to_b: Vec<Option<EventId>> = a
        .alphabet()
        .iter()
        .map(|(_, e)| b.alphabet().id(&e.name))
        .collect();
    let b_to_a: Vec<Option<EventId>> = b
        .alphabet()
        .iter()
        .map(|(_, e)| a.alphabet().id(&e.name))
        .collect();

    // `parent` rebuilds the shortest string.
    let mut index = rustc_hash::FxHashMap::default();
    let mut parent: Vec<(u32, EventId)> = Vec::new();
    let mut pairs: Vec<(StateId, StateId)> = Vec::new();
    let mut queue = VecDeque::new();
    let string_to = |mut i: u32, parent: &[(u32, EventId)]| {
        let mut s = Vec::new();
        while parent[i as usize].0 != u32::MAX {
            s.push(a.alphabet().name(parent[i as usize].1).to_owned());
            i = parent[i as usize].0;
        }
        s.reverse();
        s
    };
    // A marked difference at the pair `(sa, sb)`.
    let marking = |sa: StateId, sb: StateId| {
        let (ma, mb) = (a.is_marked(sa), b.is_marked(sb));
        (ma != mb && (both || ma)).then_some(ma)
    };
    let marked_difference =
        |i: u32, in_first: bool, parent: &[(u32, EventId)]| LanguageDifference {
            string: string_to(i, parent),
            language: LanguageKind::Marked,
            in_first,
        };
    index.insert((ia, ib), 0u32);
    pairs.push((ia, ib));
    parent.push((u32::MAX, EventId(0)));
    if let Some(in_first) = marking(ia, ib) {
        return Some(marked_difference(0, in_first, &parent));
    }
    queue.push_back(0u32);
    while let Some(i) = queue.pop_front() {
        let (sa, sb) = pairs[i as usize];
        for t in a.transitions(sa) {
            let tb = a_to_b[t.event.index()].and_then(|e| b.successor(sb, e));
            let Some(tb) = tb else {
                let mut string = string_to(i, &parent);
                string.push(a.alphabet().name(t.event).to_owned());
                return Some(LanguageDifference {
                    string,
                    language: LanguageKind::Closed,
                    in_first: true,
                });
            };
            if let std::collections::hash_map::Entry::Vacant(v) = index.entry((t.target, tb)) {
                let j = pairs.len() as u32;
                v.insert(j);
                pairs.push((t.target, tb));
                parent.push((i, t.event));
                if let Some(in_first) = marking(t.target, tb) {
                    return Some(marked_difference(j, in_first, &parent));
                }
                queue.push_back(j);
            }
        }
        if !both {
            continue;
        }
        for t in b.transitions(sb) {
            let defined = b_to_a[t.event.index()].is_some_and(|e| a.successor(sa, e).is_some());
            if !defined {
                let mut string = string_to(i, &parent);
                string.push(b.alphabet().name(t.event).to_owned());
                return Some(LanguageDifference {
                    string,
                    language: LanguageKind::Closed,
                    in_first: false,
                });
            }
        }
    }
    None
}

/// `true` when `a` and `b` have the same closed and marked languages.
pub fn language_equal(a: &Automaton, b: &Automaton) -> bool {
    language_difference(a, b).is_none()
}

/// `true` when the accessible parts of `a` and `b` are the same automaton
/// up to renaming states: same event names and controllability, and a
/// bijection of states preserving the initial state, marking and every
/// transition.
pub fn isomorphic(a: &Automaton, b: &Automaton) -> bool {
    if !a.alphabet().same_events(b.alphabet()) {
        return false;
    }
    let (ia, ib) = match (a.initial(), b.initial()) {
        (None, None) => return true,
        (Some(ia), Some(ib)) => (ia, ib),
        _ => return false,
    };
    let a_to_b: Vec<EventId> = a
        .alphabet()
        .iter()
        .map(|(_, e)| b.alphabet().id(&e.name).expect("same events"))
        .collect();
    let mut fa = vec![u32::MAX; a.num_states()];
    let mut fb = vec![u32::MAX; b.num_states()];
    fa[ia.index()] = ib.0;
    fb[ib.index()] = ia.0;
    let mut stack = vec![(ia, ib)];
    while let Some((sa, sb)) = stack.pop() {
        if a.is_marked(sa) != b.is_marked(sb) || a.transitions(sa).len() != b.transitions(sb).len()
        {
            return false;
        }
        for t in a.transitions(sa) {
            let Some(tb) = b.successor(sb, a_to_b[t.event.index()]) else {
                return false;
            };
            match (fa[t.target.index()], fb[tb.index()]) {
                (u32::MAX, u32::MAX) => {
                    fa[t.target.index()] = tb.0;
                    fb[tb.index()] = t.target.0;
                    stack.push((t.target, tb));
                }
                (x, y) if x == tb.0 && y == t.target.0 => {}
                _ => return false,
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::minstate::minstate;
    use crate::testing::auto;

    fn two_loop() -> Automaton {
        auto(
            "G",
            &[("a", true), ("b", false)],
            &[
                ("0", "a", "1"),
                ("1", "b", "2"),
                ("2", "a", "3"),
                ("3", "b", "0"),
            ],
            &["0", "2"],
        )
    }

    #[test]
    fn unfolded_and_minimal_loops_have_equal_languages_but_are_not_isomorphic() {
        let g = two_loop();
        let m = minstate(&g);
        assert!(language_equal(&g, &m));
        assert!(!isomorphic(&g, &m));
        assert!(isomorphic(&m, &minstate(&m)));
        assert!(isomorphic(&g, &g));
    }

    #[test]
    fn marking_difference_is_found_with_its_string() {
        let g = two_loop();
        let h = auto(
            "H",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("1", "b", "0")],
            &["1"],
        );
        let d = language_difference(&g, &h).unwrap();
        assert_eq!(d.language, LanguageKind::Marked);
        assert!(d.string.is_empty() && d.in_first);
    }

    #[test]
    fn closed_difference_is_found_on_either_side() {
        let g = two_loop();
        let h = auto(
            "H",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("1", "b", "2"), ("2", "a", "3")],
            &["0", "2"],
        );
        let d = language_difference(&g, &h).unwrap();
        assert_eq!(
            (d.string.clone(), d.in_first),
            (vec!["a".into(), "b".into(), "a".into(), "b".into()], true)
        );
        assert_eq!(d.language, LanguageKind::Closed);
        let d = language_difference(&h, &g).unwrap();
        assert!(!d.in_first);
    }

    #[test]
    fn empty_automata_are_equal_to_each_other_only() {
        let e = Automaton::empty("E", crate::automaton::Alphabet::new());
        assert!(language_equal(&e, &e));
        assert!(!language_equal(&e, &two_loop()));
        assert!(isomorphic(
            &e,
            &Automaton::empty("F", crate::automaton::Alphabet::new())
        ));
    }

    #[test]
    fn inclusion_finds_only_strings_of_the_first_language() {
        let g = two_loop();
        // H: a b only, marked as G. L(H) ⊆ L(G), Lm(H) ⊆ Lm(G).
        let h = auto(
            "H",
            &[("a", true), ("b", false)],
            &[("0", "a", "1"), ("1", "b", "2")],
            &["0", "2"],
        );
        assert!(language_included(&h, &g));
        let d = inclusion_counterexample(&g, &h).unwrap();
        assert_eq!(d.string, ["a", "b", "a"]);
        assert_eq!((d.language, d.in_first), (LanguageKind::Closed, true));
        // G marks the empty string, H does not.
        let h0 = auto(
            "H",
            &[("a", true), ("b", false)],
            &[("0", "a", "1")],
            &["1"],
        );
        let d = inclusion_counterexample(&g, &h0).unwrap();
        assert!(d.string.is_empty());
        assert_eq!(d.language, LanguageKind::Marked);
        let e = Automaton::empty("E", crate::automaton::Alphabet::new());
        assert!(language_included(&e, &g));
        assert_eq!(
            inclusion_counterexample(&g, &e).unwrap().string,
            Vec::<String>::new()
        );
    }

    #[test]
    fn a_marked_difference_is_not_passed_over_for_a_longer_closed_one() {
        // After `a` only G goes on with `c` (a closed difference of
        // length 2); after `b` only G is marked (length 1).
        let g = auto(
            "G",
            &[("a", true), ("b", true), ("c", true)],
            &[("0", "a", "1"), ("1", "c", "3"), ("0", "b", "2")],
            &["2"],
        );
        let h = auto(
            "H",
            &[("a", true), ("b", true), ("c", true)],
            &[("0", "a", "1"), ("0", "b", "2")],
            &[],
        );
        let d = language_difference(&g, &h).unwrap();
        assert_eq!(
            (d.string, d.language),
            (vec!["b".to_owned()], LanguageKind::Marked)
        );
    }
}
