//! Guard files (`*.guards.toml`, docs/formats.md "Guard files"): a
//! symbolic supervisor as data a target can run without a BDD library.
//!
//! The file lists the components (plants, then specifications, each with
//! its state names and the bits of its state code) and, for each
//! controllable event, its guard twice: as readable text over component
//! states, and as a node table evaluated in at most one step per state
//! bit ([`GuardTable::eval`]). An event with a guard may fire only where
//! the guard holds; events without one are never disabled.
//!
//! Reading checks everything a runner relies on (node order, bit ranges,
//! one guard per event, state counts against bits) and names the line of
//! what it refuses.

use crate::encoding::{bits_for, Role};
use crate::guards::GuardForm;
use crate::Synthesis;
use biodivine_lib_bdd::{Bdd, BddPointer, BddVariable};
use des::Automaton;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;
use thiserror::Error;
use toml::Spanned;

/// The `format` line of the files this version writes and reads.
pub const FORMAT: &str = "guards/1";

/// The most DNF terms a guard's text lists before it says at most how
/// many more there are (the node table is exact either way).
pub const MAX_TERMS: usize = 64;

/// Why a guard file is refused.
#[derive(Debug, Error)]
#[error("{file}:{line}: {message}")]
pub struct GuardFileError {
    /// The file.
    pub file: String,
    /// Its line (1-based), 0 when the file as a whole is at fault.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// A symbolic supervisor: components and one guard per controllable
/// event.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuardFile {
    /// [`FORMAT`].
    pub format: String,
    /// The supervisor's name.
    pub name: String,
    /// States of the closed loop (decimal, exact).
    pub supervisor_states: String,
    /// The components, plants first, in the order their states are given
    /// to [`GuardFile::allows`].
    #[serde(rename = "component")]
    pub components: Vec<Component>,
    /// The guards, by event name.
    #[serde(rename = "guard", default)]
    pub guards: Vec<GuardTable>,
}

/// A component automaton as the guards see it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Component {
    /// Its name.
    pub name: String,
    /// `plant` or `spec`.
    pub role: String,
    /// The automaton's file, relative to the guard file's directory, when
    /// it was read from one: a runner takes the component's transitions
    /// from there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// Its state names, by state number.
    pub states: Vec<String>,
    /// The first of its bits among all state bits.
    pub first_bit: u32,
    /// Bits of its state code: `⌈log2 states⌉`, most significant first.
    pub bits: u32,
}

/// The guard of one controllable event.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuardTable {
    /// The event.
    pub event: String,
    /// `allowed` (where it may fire) or `not-forbidden` (the complement
    /// of where it may not): which side was smaller to state.
    pub form: String,
    /// The guard over component states, `∧`, `∨`, `¬` and `∈`.
    pub text: String,
    /// The root: 0 false, 1 true, `k ≥ 2` the node `nodes[k − 2]`.
    pub root: u32,
    /// Decision nodes `[bit, low, high]`: test state bit `bit`, go to
    /// `high` when it is 1, `low` when 0; children come before parents.
    #[serde(default)]
    pub nodes: Vec<[u32; 3]>,
}

impl GuardTable {
    /// The guard's value for the state bits `bit` reads.
    pub fn eval(&self, bit: impl Fn(u32) -> bool) -> bool {
        walk(self.root, &self.nodes, bit)
    }
}

/// The value of the node table `root`, `nodes` (as in [`GuardTable`]) for
/// the state bits `bit` reads. The table must be well formed (children
/// before parents, as [`GuardFile::parse`] checks).
pub fn walk(root: u32, nodes: &[[u32; 3]], bit: impl Fn(u32) -> bool) -> bool {
    let mut at = root;
    while at >= 2 {
        let [b, low, high] = nodes[at as usize - 2];
        at = if bit(b) { high } else { low };
    }
    at == 1
}

/// Where each bit of the state code is: (component, shift in its state).
fn bit_places(components: &[Component]) -> Vec<(usize, u32)> {
    let total: u32 = components.iter().map(|c| c.bits).sum();
    let mut places = vec![(0, 0); total as usize];
    for (c, comp) in components.iter().enumerate() {
        for k in 0..comp.bits {
            places[(comp.first_bit + k) as usize] = (c, comp.bits - 1 - k);
        }
    }
    places
}

impl GuardFile {
    /// The guard file of `synthesis`, whose components are `plants` then
    /// `specs` (for their state names).
    pub fn new(
        name: &str,
        synthesis: &Synthesis,
        plants: &[Automaton],
        specs: &[Automaton],
    ) -> GuardFile {
        let layout = synthesis.model.layout();
        let automata: Vec<&Automaton> = plants.iter().chain(specs).collect();
        let components: Vec<Component> = layout
            .components
            .iter()
            .zip(&automata)
            .map(|(c, a)| Component {
                name: c.name.clone(),
                role: match c.role {
                    Role::Plant => "plant",
                    Role::Spec => "spec",
                }
                .to_owned(),
                file: None,
                states: a.states().map(|s| a.state_name(s).into_owned()).collect(),
                first_bit: c.offset as u32,
                bits: c.bits as u32,
            })
            .collect();
        let guards = synthesis
            .guards
            .iter()
            .map(|g| {
                let (root, nodes) = node_table(&g.bdd);
                let (form, text) = match g.form {
                    GuardForm::Allowed => ("allowed", dnf(&g.bdd, &components)),
                    GuardForm::NotForbidden => {
                        let forbidden = dnf(&g.bdd.not(), &components);
                        ("not-forbidden", format!("¬({forbidden})"))
                    }
                };
                GuardTable {
                    event: layout.events[g.event].name.clone(),
                    form: form.to_owned(),
                    text,
                    root,
                    nodes,
                }
            })
            .collect();
        GuardFile {
            format: FORMAT.to_owned(),
            name: name.to_owned(),
            supervisor_states: synthesis.supervisor_states().to_string(),
            components,
            guards,
        }
    }

    /// The file's text.
    pub fn to_toml(&self) -> String {
        let body = toml::to_string(self).expect("a guard file serialises");
        format!(
            "# A symbolic supervisor (docs/formats.md, \"Guard files\"), written by codegen synth --symbolic.\n{body}"
        )
    }

    /// Reads and checks the guard file `text`, named `path` in errors.
    pub fn parse(text: &str, path: &Path) -> Result<GuardFile, GuardFileError> {
        let file = path.display().to_string();
        let line_of =
            |span: Range<usize>| text[..span.start.min(text.len())].matches('\n').count() + 1;
        let err = |line: usize, message: String| GuardFileError {
            file: file.clone(),
            line,
            message,
        };
        // Spans for errors, then the plain values.
        #[derive(Deserialize)]
        struct Located {
            format: Spanned<String>,
            #[serde(rename = "component", default)]
            components: Vec<Spanned<toml::Value>>,
            #[serde(rename = "guard", default)]
            guards: Vec<Spanned<toml::Value>>,
        }
        let located: Located = toml::from_str(text).map_err(|e| {
            let line = e.span().map_or(0, &line_of);
            err(line, e.message().to_owned())
        })?;
        if located.format.get_ref() != FORMAT {
            return Err(err(
                line_of(located.format.span()),
                format!(
                    "format `{}` is not `{FORMAT}`, the one this version reads",
                    located.format.get_ref()
                ),
            ));
        }
        let g: GuardFile = toml::from_str(text).map_err(|e| {
            let line = e.span().map_or(0, &line_of);
            err(line, e.message().to_owned())
        })?;
        let component_line = |c: usize| located.components.get(c).map_or(0, |s| line_of(s.span()));
        let guard_line = |k: usize| located.guards.get(k).map_or(0, |s| line_of(s.span()));

        let mut next_bit = 0u32;
        let mut names = BTreeSet::new();
        for (c, comp) in g.components.iter().enumerate() {
            let at = component_line(c);
            if !names.insert(comp.name.as_str()) {
                return Err(err(at, format!("component `{}` twice", comp.name)));
            }
            if comp.role != "plant" && comp.role != "spec" {
                return Err(err(
                    at,
                    format!(
                        "component `{}`: role must be `plant` or `spec`, not `{}`",
                        comp.name, comp.role
                    ),
                ));
            }
            if comp.states.is_empty() {
                return Err(err(at, format!("component `{}` has no states", comp.name)));
            }
            let bits = bits_for(comp.states.len()) as u32;
            if comp.bits != bits {
                return Err(err(
                    at,
                    format!(
                        "component `{}` has {} states, which take {bits} bits, not {}",
                        comp.name,
                        comp.states.len(),
                        comp.bits
                    ),
                ));
            }
            next_bit = next_bit.max(comp.first_bit.saturating_add(comp.bits));
        }
        // Every bit belongs to exactly one component.
        let mut owner = vec![None; next_bit as usize];
        for (c, comp) in g.components.iter().enumerate() {
            for b in comp.first_bit..comp.first_bit + comp.bits {
                if let Some(other) = owner[b as usize].replace(c) {
                    return Err(err(
                        component_line(c),
                        format!(
                            "bit {b} of component `{}` is also a bit of `{}`",
                            comp.name, g.components[other].name
                        ),
                    ));
                }
            }
        }
        if let Some(b) = owner.iter().position(Option::is_none) {
            return Err(err(0, format!("state bit {b} belongs to no component")));
        }
        let mut events = BTreeSet::new();
        for (k, guard) in g.guards.iter().enumerate() {
            let at = guard_line(k);
            if !events.insert(guard.event.as_str()) {
                return Err(err(at, format!("event `{}` has two guards", guard.event)));
            }
            if guard.form != "allowed" && guard.form != "not-forbidden" {
                return Err(err(
                    at,
                    format!(
                        "guard of `{}`: form must be `allowed` or `not-forbidden`",
                        guard.event
                    ),
                ));
            }
            for (n, &[bit, low, high]) in guard.nodes.iter().enumerate() {
                let index = n as u32 + 2;
                if bit >= next_bit {
                    return Err(err(
                        at,
                        format!("guard of `{}`: node {index} tests bit {bit}; the states have {next_bit}", guard.event),
                    ));
                }
                if low >= index || high >= index {
                    return Err(err(
                        at,
                        format!(
                            "guard of `{}`: node {index} points to a later node (children come first)",
                            guard.event
                        ),
                    ));
                }
            }
            if guard.root as usize >= guard.nodes.len() + 2
                || (guard.root >= 2 && guard.root as usize != guard.nodes.len() + 1)
            {
                return Err(err(
                    at,
                    format!(
                        "guard of `{}`: the root must be the last node (or 0 or 1)",
                        guard.event
                    ),
                ));
            }
        }
        Ok(g)
    }

    /// The components' state bits, in order: a state tuple `states`
    /// (plants, then specifications) as the bit `b` reads it.
    fn bit(&self, places: &[(usize, u32)], states: &[u32], b: u32) -> bool {
        let (c, shift) = places[b as usize];
        (states[c] >> shift) & 1 == 1
    }

    /// Whether `event` may fire in the component states `states`: `None`
    /// if the tuple does not fit the components.
    pub fn allows(&self, event: &str, states: &[u32]) -> Option<bool> {
        if states.len() != self.components.len()
            || states
                .iter()
                .zip(&self.components)
                .any(|(&s, c)| s as usize >= c.states.len())
        {
            return None;
        }
        let places = bit_places(&self.components);
        Some(match self.guards.iter().find(|g| g.event == event) {
            None => true,
            Some(g) => g.eval(|b| self.bit(&places, states, b)),
        })
    }

    /// Where each state bit is: (component, by position among
    /// [`GuardFile::components`]; the bit's shift in its state number).
    pub fn bit_places(&self) -> Vec<(usize, u32)> {
        bit_places(&self.components)
    }

    /// Nodes of every guard's table, summed.
    pub fn nodes(&self) -> usize {
        self.guards.iter().map(|g| g.nodes.len()).sum()
    }
}

/// `bdd` (over current-state variables) as a node table: root and nodes,
/// children first, bit `b` for variable `2b`.
fn node_table(bdd: &Bdd) -> (u32, Vec<[u32; 3]>) {
    if bdd.is_false() {
        return (0, Vec::new());
    }
    if bdd.is_true() {
        return (1, Vec::new());
    }
    // biodivine keeps its nodes children first, terminals at 0 and 1.
    let index = |p: BddPointer| p.to_index() as u32;
    let nodes = bdd
        .pointers()
        .skip(2)
        .map(|p| {
            let var = bdd.var_of(p).to_index();
            debug_assert_eq!(var % 2, 0, "guards range over current-state variables");
            [
                (var / 2) as u32,
                index(bdd.low_link_of(p)),
                index(bdd.high_link_of(p)),
            ]
        })
        .collect();
    (index(bdd.root_pointer()), nodes)
}

/// `bdd` as a disjunction of terms over component states (at most
/// [`MAX_TERMS`], then a bound on how many more).
fn dnf(bdd: &Bdd, components: &[Component]) -> String {
    if bdd.is_false() {
        return "false".to_owned();
    }
    if bdd.is_true() {
        return "true".to_owned();
    }
    let mut terms = Vec::new();
    let mut seen = 0u128;
    for clause in bdd.sat_clauses() {
        if terms.len() == MAX_TERMS {
            break;
        }
        seen += 1;
        let mut literals = Vec::new();
        for comp in components {
            let fixed: Vec<(u32, bool)> = (0..comp.bits)
                .filter_map(|k| {
                    let var = BddVariable::from_index(2 * (comp.first_bit + k) as usize);
                    clause.get_value(var).map(|v| (comp.bits - 1 - k, v))
                })
                .collect();
            if fixed.is_empty() {
                continue;
            }
            let states: Vec<&str> = (0..comp.states.len() as u32)
                .filter(|&s| fixed.iter().all(|&(shift, v)| ((s >> shift) & 1 == 1) == v))
                .map(|s| comp.states[s as usize].as_str())
                .collect();
            match states.as_slice() {
                [] => literals.push("false".to_owned()),
                [one] => literals.push(format!("{} = {one}", comp.name)),
                many if many.len() < comp.states.len() => {
                    literals.push(format!("{} ∈ {{{}}}", comp.name, many.join(", ")))
                }
                _ => {}
            }
        }
        if literals.iter().any(|l| l == "false") {
            continue;
        }
        terms.push(if literals.is_empty() {
            "true".to_owned()
        } else {
            literals.join(" ∧ ")
        });
    }
    let mut text = match terms.len() {
        0 => "false".to_owned(),
        1 => terms.remove(0),
        _ => terms
            .iter()
            .map(|t| {
                if t.contains(" ∧ ") {
                    format!("({t})")
                } else {
                    t.clone()
                }
            })
            .collect::<Vec<_>>()
            .join(" ∨ "),
    };
    let more = paths(bdd).saturating_sub(seen);
    if more > 0 {
        let _ = write!(text, " ∨ … (up to {more} more terms)");
    }
    text
}

/// The number of paths from the root of `bdd` to `true` (saturating): an
/// upper bound on its terms, counted without listing them.
fn paths(bdd: &Bdd) -> u128 {
    let (root, nodes) = node_table(bdd);
    // Children come first, so one pass in order counts every node.
    let mut count = vec![0u128, 1];
    for &[_, low, high] in &nodes {
        count.push(count[low as usize].saturating_add(count[high as usize]));
    }
    count[root as usize]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::families;
    use des::StateId;

    #[test]
    fn the_file_runs_as_the_bdds_do_and_reads_back() {
        for n in 2..=4 {
            let f = families::ring(n).unwrap();
            let s = crate::synthesize(&f.plants, &f.specs).unwrap();
            let file = GuardFile::new("ring", &s, &f.plants, &f.specs);
            let text = file.to_toml();
            let back = GuardFile::parse(&text, Path::new("ring.guards.toml")).unwrap();
            assert_eq!(back, file);
            // Every state tuple, every controllable event: table = BDD.
            let sizes: Vec<usize> = file.components.iter().map(|c| c.states.len()).collect();
            let mut tuple = vec![0u32; sizes.len()];
            let mut checked = 0;
            'all: loop {
                let ids: Vec<StateId> = tuple.iter().map(|&x| StateId(x)).collect();
                for g in &file.guards {
                    assert_eq!(
                        file.allows(&g.event, &tuple),
                        Some(s.allows(&g.event, &ids).unwrap()),
                        "ring{n}, {} at {tuple:?}",
                        g.event
                    );
                    checked += 1;
                }
                for (x, &size) in tuple.iter_mut().zip(&sizes) {
                    *x += 1;
                    if (*x as usize) < size {
                        continue 'all;
                    }
                    *x = 0;
                }
                break;
            }
            assert!(checked > 0);
        }
    }

    #[test]
    fn a_damaged_file_is_refused_at_its_line() {
        let f = families::ring(3).unwrap();
        let s = crate::synthesize(&f.plants, &f.specs).unwrap();
        let text = GuardFile::new("ring", &s, &f.plants, &f.specs).to_toml();
        let path = Path::new("r.guards.toml");
        let bad = text.replacen("format = \"guards/1\"", "format = \"guards/9\"", 1);
        let e = GuardFile::parse(&bad, path).unwrap_err();
        assert_eq!(e.line, 2, "{e}");
        assert!(e.to_string().contains("format `guards/9`"), "{e}");
        let bad = text.replacen("bits = 1", "bits = 3", 1);
        let e = GuardFile::parse(&bad, path).unwrap_err();
        assert!(e.message.contains("take 1 bits, not 3"), "{e}");
        assert!(e.line > 2, "{e}");
        let bad = format!("{text}\n[[guard]]\nevent = \"x\"\nform = \"allowed\"\ntext = \"\"\nroot = 2\nnodes = [[0, 5, 1]]\n");
        let e = GuardFile::parse(&bad, path).unwrap_err();
        assert!(e.message.contains("points to a later node"), "{e}");
        assert_eq!(e.line, text.lines().count() + 2, "{e}");
        let e = GuardFile::parse("format = ", path).unwrap_err();
        assert_eq!(e.line, 1, "{e}");
    }

    #[test]
    fn guards_read_as_component_states() {
        let f = families::ring(3).unwrap();
        let s = crate::synthesize(&f.plants, &f.specs).unwrap();
        let file = GuardFile::new("ring", &s, &f.plants, &f.specs);
        for g in &file.guards {
            assert!(!g.text.is_empty());
            // Names of components and states, never raw bits.
            assert!(
                g.text == "true"
                    || g.text == "false"
                    || file
                        .components
                        .iter()
                        .any(|c| g.text.contains(&format!("{} ", c.name))),
                "{}: {}",
                g.event,
                g.text
            );
        }
    }

    #[test]
    fn a_long_guard_lists_its_first_terms_and_bounds_the_rest() {
        use biodivine_lib_bdd::BddVariableSet;
        // The parity of 8 one-bit components: 128 terms, none shorter.
        let vars = BddVariableSet::new_anonymous(16);
        let parity = (0..8).fold(vars.mk_false(), |x, k| {
            x.xor(&vars.mk_var(BddVariable::from_index(2 * k)))
        });
        assert_eq!(paths(&parity), 128);
        let components: Vec<Component> = (0..8)
            .map(|k| Component {
                name: format!("C{k}"),
                role: "plant".to_owned(),
                file: None,
                states: vec!["off".to_owned(), "on".to_owned()],
                first_bit: k,
                bits: 1,
            })
            .collect();
        let text = dnf(&parity, &components);
        assert!(text.ends_with(" ∨ … (up to 64 more terms)"), "{text}");
        assert_eq!(text.matches(" ∨ ").count(), MAX_TERMS, "{text}");
        assert!(text.starts_with("(C0 = "), "{text}");
    }
}
