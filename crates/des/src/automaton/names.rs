//! State names: none (states are named by their index), stored one string
//! per state, or composed on demand from the states of the components of a
//! product.
//!
//! A product of `k` components names state `s` by joining its components'
//! names with `.`. Storing those strings costs a heap allocation and a few
//! dozen bytes per state, most of a large synthesis's memory; a
//! [`StateNames::Composed`] keeps the tuple of component states (`4 × k`
//! bytes) and the components' own names, and produces the string when it is
//! asked for.

use super::tuples::Tuples;
use std::borrow::Cow;
use std::sync::Arc;

/// The names of an automaton's states.
#[derive(Debug, Clone, Default)]
pub(crate) enum StateNames {
    /// States are named by their index.
    #[default]
    Indices,
    /// One name per state.
    Stored(Vec<String>),
    /// Names joined from the components' names, see [`Composed`].
    Composed(Arc<Composed>),
}

/// The names of product states: per state a tuple of component states,
/// named by each component's [`StateNames`] and joined by `.`.
#[derive(Debug)]
pub(crate) struct Composed {
    parts: Vec<StateNames>,
    tuples: Arc<Tuples>,
    /// When set, product state `s` is tuple `select[s]`; else tuple `s`.
    select: Option<Vec<u32>>,
}

impl Composed {
    /// Names of a product whose state `s` is tuple `s` of `tuples`, one
    /// component per part.
    pub(crate) fn new(parts: Vec<StateNames>, tuples: Arc<Tuples>) -> Composed {
        debug_assert_eq!(parts.len(), tuples.width());
        Composed {
            parts,
            tuples,
            select: None,
        }
    }

    fn write(&self, s: usize, out: &mut String) {
        let i = self.select.as_ref().map_or(s, |sel| sel[s] as usize);
        for (j, part) in self.parts.iter().enumerate() {
            if j > 0 {
                out.push('.');
            }
            part.write(self.tuples.get(i, j) as usize, out);
        }
    }
}

/// Appends `s` in decimal (what `write!` does, without its machinery: this
/// runs once per component of every state name written).
fn push_index(out: &mut String, mut s: usize) {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    loop {
        at -= 1;
        digits[at] = b'0' + (s % 10) as u8;
        s /= 10;
        if s == 0 {
            break;
        }
    }
    for &d in &digits[at..] {
        out.push(char::from(d));
    }
}

impl StateNames {
    /// Stored names, or indices for `None`.
    pub(crate) fn from_option(names: Option<Vec<String>>) -> StateNames {
        names.map_or(StateNames::Indices, StateNames::Stored)
    }

    /// `false` for index names.
    pub(crate) fn is_named(&self) -> bool {
        !matches!(self, StateNames::Indices)
    }

    /// The name of state `s`.
    pub(crate) fn name(&self, s: usize) -> Cow<'_, str> {
        match self {
            StateNames::Indices => Cow::Owned(s.to_string()),
            StateNames::Stored(names) => Cow::Borrowed(&names[s]),
            StateNames::Composed(c) => {
                let mut out = String::new();
                c.write(s, &mut out);
                Cow::Owned(out)
            }
        }
    }

    /// Appends the name of state `s` to `out`.
    pub(crate) fn write(&self, s: usize, out: &mut String) {
        match self {
            StateNames::Indices => push_index(out, s),
            StateNames::Stored(names) => out.push_str(&names[s]),
            StateNames::Composed(c) => c.write(s, out),
        }
    }

    /// The names of the states `old` (in this order) of this automaton,
    /// as the states `0..old.len()` of a sub-automaton.
    pub(crate) fn select(&self, old: &[u32]) -> StateNames {
        match self {
            // Renumbered states keep being named by their (new) index.
            StateNames::Indices => StateNames::Indices,
            StateNames::Stored(names) => {
                StateNames::Stored(old.iter().map(|&s| names[s as usize].clone()).collect())
            }
            StateNames::Composed(c) => {
                let select = match &c.select {
                    Some(sel) => old.iter().map(|&s| sel[s as usize]).collect(),
                    None => old.to_vec(),
                };
                StateNames::Composed(Arc::new(Composed {
                    parts: c.parts.clone(),
                    tuples: Arc::clone(&c.tuples),
                    select: Some(select),
                }))
            }
        }
    }

    /// Approximate heap bytes owned by these names.
    pub(crate) fn heap_bytes(&self) -> usize {
        match self {
            StateNames::Indices => 0,
            StateNames::Stored(v) => v.iter().map(|n| n.capacity() + 24).sum(),
            StateNames::Composed(c) => {
                c.tuples.heap_bytes() + c.select.as_ref().map_or(0, |s| s.capacity() * 4)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::push_index;

    #[test]
    fn indices_are_written_in_decimal() {
        for n in [0, 7, 10, 99, 100, 4_294_967_295, usize::MAX] {
            let mut out = String::from("x");
            push_index(&mut out, n);
            assert_eq!(out, format!("x{n}"));
        }
    }
}
