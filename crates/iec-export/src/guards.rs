//! The guards of symbolic supervisors (docs/formats.md, "Guard files") as
//! Boolean expressions over the component state variables `S_…`.
//!
//! A guard is a decision diagram over state *bits*; a reader of the PLC
//! program thinks in component *states*. [`Diagram::of`] turns the bit
//! diagram into one whose nodes each test one component: a node's
//! branches split the component's states into sets, one per child, so the
//! bits of one component become one state (in)equality or range
//! ([`condition`]). The diagram is then written in one of two forms
//! ([`Form`]):
//!
//! - **a sum of products** ([`Diagram::products`]) when it is small: at
//!   most [`MAX_PRODUCTS`] products and [`MAX_COMPARISONS`] comparisons,
//!   one line a reader checks against the guard's text, written inline in
//!   the command's feasibility test;
//! - otherwise **a chain of BOOL temporaries**, one per node, children
//!   first (`GN[k] := ((S_a = 0) AND GN[j]) OR (S_a >= 1);`): a sum of
//!   products may grow exponentially with the diagram, the chain grows
//!   with it linearly and is the diagram a reader can follow node by node.
//!
//! Both are exact on every state vector the scan can test: each state in
//! range, which the block checks at the start of every scan before any
//! command runs (docs/formats.md, "Structured Text export").

use plc_project::EventGuard;
use std::collections::HashMap;

/// A sum of products with more products than this is written as a chain.
pub const MAX_PRODUCTS: usize = 8;

/// A sum of products with more state comparisons than this is written as
/// a chain.
pub const MAX_COMPARISONS: usize = 24;

/// Where a branch of a [`Diagram`] leads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Ref {
    /// The guard does not hold.
    False,
    /// The guard holds.
    True,
    /// The node of this index in [`Diagram::nodes`].
    Node(usize),
}

/// A node testing one component: its state picks the branch.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Node {
    /// The component, as an index into `Project::supervisors`.
    pub supervisor: usize,
    /// The branches: the states (ascending, every state of the component
    /// in exactly one branch) and where they lead, at least two distinct
    /// targets.
    pub branches: Vec<(Vec<u32>, Ref)>,
}

impl Node {
    /// The states of branch `i`, or, where that takes fewer comparisons
    /// ([`comparisons`]), those and the states of the branch leading to
    /// true: a state of that branch makes the node true whatever follows,
    /// so `(c ∧ f) ∨ t` is `((c ∨ t) ∧ f) ∨ t`. (`¬(a ∧ b)` is then
    /// `¬a ∨ ¬b` rather than `¬a ∨ (a ∧ ¬b)`.)
    pub fn relaxed(&self, i: usize) -> Vec<u32> {
        let size: usize = self.branches.iter().map(|(set, _)| set.len()).sum();
        let (set, to) = &self.branches[i];
        let Some((t, _)) = self.branches.iter().find(|(_, to)| *to == Ref::True) else {
            return set.clone();
        };
        if *to == Ref::True {
            return set.clone();
        }
        let mut wide: Vec<u32> = set.iter().chain(t).copied().collect();
        wide.sort_unstable();
        if comparisons(&wide, size) < comparisons(set, size) {
            wide
        } else {
            set.clone()
        }
    }
}

/// A guard as a decision diagram over component states, nodes children
/// first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagram {
    /// The root.
    pub root: Ref,
    /// The nodes; a node's children come before it.
    pub nodes: Vec<Node>,
}

/// A conjunction of conditions `state of supervisor ∈ states` (empty:
/// true).
pub type Product = Vec<(usize, Vec<u32>)>;

impl Diagram {
    /// `guard`, whose bits are placed by `bits` (supervisor, shift), over
    /// components whose numbers of states are `sizes` (indexed as
    /// `Project::supervisors`). The guard's node table must be valid
    /// (children first), as a validated project's is.
    pub fn of(guard: &EventGuard, bits: &[(usize, u32)], sizes: &[usize]) -> Diagram {
        let table = |r: u32| guard.nodes[r as usize - 2];
        // The component-level reference of every bit node, children first.
        let mut of_node: Vec<Ref> = Vec::with_capacity(guard.nodes.len());
        let mut nodes: Vec<Node> = Vec::new();
        let mut known: HashMap<Node, usize> = HashMap::new();
        for k in 0..guard.nodes.len() {
            let at = k as u32 + 2;
            let supervisor = bits[table(at)[0] as usize].0;
            let mut branches: Vec<(Vec<u32>, Ref)> = Vec::new();
            for state in 0..sizes[supervisor] as u32 {
                // Follow the nodes that test this component's bits.
                let mut r = at;
                while r >= 2 {
                    let [bit, low, high] = table(r);
                    let (j, shift) = bits[bit as usize];
                    if j != supervisor {
                        break;
                    }
                    let next = if state >> shift & 1 == 1 { high } else { low };
                    assert!(next < r, "a validated guard table is children first");
                    r = next;
                }
                let to = match r {
                    0 => Ref::False,
                    1 => Ref::True,
                    r => of_node[r as usize - 2],
                };
                match branches.iter_mut().find(|(_, t)| *t == to) {
                    Some((states, _)) => states.push(state),
                    None => branches.push((vec![state], to)),
                }
            }
            let r = if branches.len() == 1 {
                branches[0].1
            } else {
                let node = Node {
                    supervisor,
                    branches,
                };
                let index = *known.entry(node.clone()).or_insert_with(|| {
                    nodes.push(node);
                    nodes.len() - 1
                });
                Ref::Node(index)
            };
            of_node.push(r);
        }
        let root = match guard.root {
            0 => Ref::False,
            1 => Ref::True,
            r => of_node[r as usize - 2],
        };
        Diagram { root, nodes }.reachable()
    }

    /// The same diagram with only the nodes its root reaches, children
    /// first.
    fn reachable(self) -> Diagram {
        let mut keep = vec![false; self.nodes.len()];
        if let Ref::Node(r) = self.root {
            keep[r] = true;
        }
        for k in (0..self.nodes.len()).rev() {
            if keep[k] {
                for (_, to) in &self.nodes[k].branches {
                    if let Ref::Node(c) = to {
                        keep[*c] = true;
                    }
                }
            }
        }
        let mut index = vec![usize::MAX; self.nodes.len()];
        let mut nodes = Vec::new();
        let renumber = |r: Ref, index: &[usize]| match r {
            Ref::Node(k) => Ref::Node(index[k]),
            r => r,
        };
        for (k, node) in self.nodes.into_iter().enumerate() {
            if keep[k] {
                index[k] = nodes.len();
                nodes.push(Node {
                    supervisor: node.supervisor,
                    branches: node
                        .branches
                        .into_iter()
                        .map(|(s, to)| (s, renumber(to, &index)))
                        .collect(),
                });
            }
        }
        Diagram {
            root: renumber(self.root, &index),
            nodes,
        }
    }

    /// The diagram's value when the supervisors are in `states`.
    pub fn eval(&self, states: &[u32]) -> bool {
        let mut at = self.root;
        loop {
            match at {
                Ref::False => return false,
                Ref::True => return true,
                Ref::Node(k) => {
                    let node = &self.nodes[k];
                    let s = states[node.supervisor];
                    at = node
                        .branches
                        .iter()
                        .find(|(set, _)| set.contains(&s))
                        .map_or(Ref::False, |(_, to)| *to);
                }
            }
        }
    }

    /// The paths to true as a sum of products, each branch's states
    /// [`Node::relaxed`] (a component tested twice on a path: the
    /// intersection), or `None` when there are more than `limit` paths.
    pub fn products(&self, limit: usize) -> Option<Vec<Product>> {
        // Paths to true from each node, saturating past the limit.
        let mut paths = vec![0usize; self.nodes.len()];
        let count = |r: Ref, paths: &[usize]| match r {
            Ref::False => 0,
            Ref::True => 1,
            Ref::Node(k) => paths[k],
        };
        for k in 0..self.nodes.len() {
            paths[k] = self.nodes[k]
                .branches
                .iter()
                .map(|&(_, to)| count(to, &paths))
                .fold(0, |a: usize, b| {
                    a.saturating_add(b).min(limit.saturating_add(1))
                });
        }
        if count(self.root, &paths) > limit {
            return None;
        }
        let mut out = Vec::new();
        self.collect(self.root, &mut Vec::new(), &mut out);
        Some(out)
    }

    fn collect(&self, at: Ref, path: &mut Product, out: &mut Vec<Product>) {
        match at {
            Ref::False => {}
            Ref::True => {
                // A component tested twice: the states both tests allow.
                let mut product: Product = Vec::new();
                for (j, set) in path.iter() {
                    match product.iter_mut().find(|(k, _)| k == j) {
                        Some((_, mine)) => mine.retain(|s| set.contains(s)),
                        None => product.push((*j, set.clone())),
                    }
                }
                if product.iter().all(|(_, set)| !set.is_empty()) {
                    out.push(product);
                }
            }
            Ref::Node(k) => {
                let node = &self.nodes[k];
                for (i, (_, to)) in node.branches.iter().enumerate() {
                    path.push((node.supervisor, node.relaxed(i)));
                    self.collect(*to, path, out);
                    path.pop();
                }
            }
        }
    }
}

/// `variable ∈ states` for a variable whose values are `0..size`, as the
/// fewest comparisons: `=`, `<>`, a bound or a range, or a disjunction of
/// equalities (a conjunction of inequalities when the complement is
/// smaller). `None` when `states` is every state (no condition).
pub fn condition(variable: &str, states: &[u32], size: usize) -> Option<Vec<String>> {
    let n = size as u32;
    if states.len() >= size {
        return None;
    }
    if states.is_empty() {
        return Some(vec!["FALSE".into()]);
    }
    let (lo, hi) = (states[0], states[states.len() - 1]);
    let contiguous = (hi - lo) as usize + 1 == states.len();
    let others: Vec<u32> = (0..n).filter(|s| !states.contains(s)).collect();
    let one = |op: &str, v: u32| vec![format!("({variable} {op} {v})")];
    Some(if states.len() == 1 {
        one("=", lo)
    } else if others.len() == 1 {
        one("<>", others[0])
    } else if contiguous && lo == 0 {
        one("<=", hi)
    } else if contiguous && hi == n - 1 {
        one(">=", lo)
    } else if contiguous {
        vec![format!("({variable} >= {lo} AND {variable} <= {hi})")]
    } else if states.len() <= others.len() {
        let terms: Vec<String> = states.iter().map(|s| format!("{variable} = {s}")).collect();
        vec![format!("({})", terms.join(" OR "))]
    } else {
        let terms: Vec<String> = others
            .iter()
            .map(|s| format!("{variable} <> {s}"))
            .collect();
        vec![format!("({})", terms.join(" AND "))]
    })
}

/// The number of comparisons [`condition`] writes for `states`.
pub fn comparisons(states: &[u32], size: usize) -> usize {
    let n = size as u32;
    if states.len() >= size {
        return 0;
    }
    if states.is_empty() {
        return 1;
    }
    let (lo, hi) = (states[0], states[states.len() - 1]);
    let contiguous = (hi - lo) as usize + 1 == states.len();
    let others = size - states.len();
    if states.len() == 1 || others == 1 || (contiguous && (lo == 0 || hi == n - 1)) {
        1
    } else if contiguous {
        2
    } else {
        states.len().min(others)
    }
}

/// How one guard is written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Form {
    /// An expression, inline in the feasibility test.
    Inline(String),
    /// Statements computing temporaries `GN[first..]`, children first,
    /// one of which (`GN[root]`) is the guard's value.
    Chain {
        /// The assignments, one per node.
        statements: Vec<String>,
        /// The temporaries used.
        nodes: usize,
        /// The temporary holding the guard's value (`first` included).
        root: usize,
    },
}

/// `diagram` written with the state variables `states` (indexed as
/// `Project::supervisors`, whose numbers of states are `sizes`); a chain
/// uses the temporaries `array[first..]`.
pub fn form(
    diagram: &Diagram,
    states: &[String],
    sizes: &[usize],
    array: &str,
    first: usize,
) -> Form {
    let cond = |j: usize, set: &[u32]| condition(&states[j], set, sizes[j]);
    if let Some(products) = diagram.products(MAX_PRODUCTS) {
        let count: usize = products
            .iter()
            .flat_map(|p| p.iter().map(|(j, set)| comparisons(set, sizes[*j])))
            .sum();
        if count <= MAX_COMPARISONS {
            let terms: Vec<String> = products
                .iter()
                .map(|p| {
                    let factors: Vec<String> = p
                        .iter()
                        .filter_map(|(j, set)| cond(*j, set))
                        .flatten()
                        .collect();
                    if factors.is_empty() {
                        "TRUE".to_owned()
                    } else {
                        factors.join(" AND ")
                    }
                })
                .collect();
            return Form::Inline(match terms.len() {
                0 => "FALSE".to_owned(),
                1 => terms[0].clone(),
                _ => format!(
                    "({})",
                    terms
                        .iter()
                        .map(|t| if t.contains(" AND ") {
                            format!("({t})")
                        } else {
                            t.clone()
                        })
                        .collect::<Vec<_>>()
                        .join(" OR ")
                ),
            });
        }
    }
    let temp = |k: usize| format!("{array}[{}]", first + k);
    let statements = diagram
        .nodes
        .iter()
        .enumerate()
        .map(|(k, node)| {
            let terms: Vec<String> = node
                .branches
                .iter()
                .enumerate()
                .filter_map(|(i, (_, to))| {
                    let c = cond(node.supervisor, &node.relaxed(i)).map(|c| c.join(" AND "));
                    match (to, c) {
                        (Ref::False, _) => None,
                        (Ref::True, c) => Some(c.unwrap_or_else(|| "TRUE".into())),
                        (Ref::Node(n), None) => Some(temp(*n)),
                        (Ref::Node(n), Some(c)) => Some(format!("({c} AND {})", temp(*n))),
                    }
                })
                .collect();
            format!("{} := {};", temp(k), terms.join(" OR "))
        })
        .collect();
    let root = match diagram.root {
        Ref::Node(k) => first + k,
        // A terminal root is one product or none: written inline above.
        Ref::False | Ref::True => unreachable!("a constant guard has a sum of products"),
    };
    Form::Chain {
        statements,
        nodes: diagram.nodes.len(),
        root,
    }
}

/// The longest guard text a comment carries; longer ones are cut with
/// `...`.
pub const MAX_TEXT: usize = 160;

/// A guard's text for an ST comment: comment-safe, its operators as ST
/// words (`AND`, `OR`, `NOT`, `IN`), cut after [`MAX_TEXT`] characters.
pub fn text(text: &str) -> String {
    let words = super::comment_text(text)
        .replace('∧', "AND")
        .replace('∨', "OR")
        .replace('¬', "NOT ")
        .replace('∈', "IN")
        .replace('…', "...");
    if words.chars().count() <= MAX_TEXT {
        words
    } else {
        let cut: String = words.chars().take(MAX_TEXT).collect();
        format!("{} ...", cut.trim_end())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift64).
    struct Rng(u64);

    impl Rng {
        fn below(&mut self, n: u64) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0 % n.max(1)
        }
    }

    /// Components of 1, 2, 3, 5 and 17 states and their bits (most
    /// significant first, as guard files number them).
    fn components() -> (Vec<usize>, Vec<(usize, u32)>) {
        let sizes: Vec<usize> = vec![3, 2, 17, 1, 5];
        let mut bits = Vec::new();
        for (j, &n) in sizes.iter().enumerate() {
            let width = usize::BITS - (n - 1).leading_zeros();
            for shift in (0..width).rev() {
                bits.push((j, shift));
            }
        }
        (sizes, bits)
    }

    /// A random valid node table over `bits`: each node tests a bit and
    /// points to earlier nodes or the terminals.
    fn random_guard(rng: &mut Rng, bits: usize, nodes: usize) -> EventGuard {
        let table: Vec<[u32; 3]> = (0..nodes as u32)
            .map(|k| {
                let bit = rng.below(bits as u64) as u32;
                let low = rng.below(u64::from(k) + 2) as u32;
                let high = rng.below(u64::from(k) + 2) as u32;
                [bit, low, high]
            })
            .collect();
        EventGuard {
            event: 0,
            text: String::new(),
            root: nodes as u32 + 1,
            nodes: table,
        }
    }

    fn every_state(sizes: &[usize]) -> Vec<Vec<u32>> {
        let mut all = vec![Vec::new()];
        for &n in sizes {
            all = all
                .into_iter()
                .flat_map(|v: Vec<u32>| {
                    (0..n as u32).map(move |s| {
                        let mut w = v.clone();
                        w.push(s);
                        w
                    })
                })
                .collect();
        }
        all
    }

    fn in_condition(words: &[String], state: u32) -> bool {
        // Each word is `(v op k)`, `(v >= a AND v <= b)`, a disjunction
        // of equalities or a conjunction of inequalities over `v`.
        words.iter().all(|w| {
            let w = w.trim_start_matches('(').trim_end_matches(')');
            let holds = |term: &str| {
                let parts: Vec<&str> = term.split_whitespace().collect();
                let k: u32 = parts[2].parse().unwrap();
                match parts[1] {
                    "=" => state == k,
                    "<>" => state != k,
                    "<=" => state <= k,
                    ">=" => state >= k,
                    op => panic!("{op}"),
                }
            };
            if w.contains(" OR ") {
                w.split(" OR ").any(holds)
            } else {
                w.split(" AND ").all(holds)
            }
        })
    }

    /// The component diagram, its sum of products and the conditions
    /// agree with the bit table on every state vector, for random tables.
    #[test]
    fn the_component_diagram_and_its_products_are_the_guard() {
        let (sizes, bits) = components();
        let all = every_state(&sizes);
        let mut rng = Rng(0x6A4D);
        let (mut inline, mut chained) = (0, 0);
        for round in 0..300 {
            let guard = random_guard(&mut rng, bits.len(), 1 + round % 40);
            let d = Diagram::of(&guard, &bits, &sizes);
            for (k, node) in d.nodes.iter().enumerate() {
                for (_, to) in &node.branches {
                    if let Ref::Node(c) = to {
                        assert!(*c < k, "children first");
                    }
                }
            }
            let products = d.products(usize::MAX);
            for states in &all {
                let want = guard.holds(&bits, states);
                assert_eq!(d.eval(states), want, "{guard:?} at {states:?}");
                let by_products = products.as_ref().unwrap().iter().any(|p| {
                    p.iter().all(|(j, set)| {
                        condition("v", set, sizes[*j]).is_none_or(|c| in_condition(&c, states[*j]))
                    })
                });
                assert_eq!(by_products, want, "{guard:?} at {states:?}");
            }
            let names: Vec<String> = (0..sizes.len()).map(|j| format!("S{j}")).collect();
            match form(&d, &names, &sizes, "GN", 0) {
                Form::Inline(_) => inline += 1,
                Form::Chain {
                    statements,
                    nodes,
                    root,
                } => {
                    assert_eq!(statements.len(), nodes);
                    assert!(root < nodes);
                    chained += 1;
                }
            }
        }
        assert!(
            inline > 10 && chained > 10,
            "{inline} inline, {chained} chains"
        );
    }

    #[test]
    fn conditions_are_the_fewest_comparisons() {
        let c = |set: &[u32], n| condition("S", set, n);
        assert_eq!(c(&[0, 1, 2], 3), None);
        assert_eq!(c(&[1], 3), Some(vec!["(S = 1)".into()]));
        assert_eq!(c(&[0, 2], 3), Some(vec!["(S <> 1)".into()]));
        assert_eq!(c(&[0, 1], 5), Some(vec!["(S <= 1)".into()]));
        assert_eq!(c(&[3, 4], 5), Some(vec!["(S >= 3)".into()]));
        assert_eq!(c(&[1, 2], 5), Some(vec!["(S >= 1 AND S <= 2)".into()]));
        assert_eq!(c(&[0, 3], 6), Some(vec!["(S = 0 OR S = 3)".into()]));
        assert_eq!(
            c(&[0, 2, 3, 5], 6),
            Some(vec!["(S <> 1 AND S <> 4)".into()])
        );
        let sets: [(&[u32], usize); 6] = [
            (&[1], 3),
            (&[0, 2], 3),
            (&[1, 2], 5),
            (&[0, 3], 6),
            (&[0, 2, 3, 5], 6),
            (&[0, 1, 2], 3),
        ];
        for (set, n) in sets {
            let written = c(set, n).map_or(0, |words| {
                let text = words.join(" ");
                [" = ", " <> ", " <= ", " >= "]
                    .iter()
                    .map(|op| text.matches(op).count())
                    .sum()
            });
            assert_eq!(comparisons(set, n), written, "{set:?} of {n}");
        }
    }

    #[test]
    fn guard_text_is_st_words_and_cut() {
        assert_eq!(
            text("¬(M1 = idle ∧ B ∈ {a, b})"),
            "NOT (M1 = idle AND B IN {a, b})"
        );
        let long = "x = 1 ∨ ".repeat(40);
        let t = text(&long);
        assert!(
            t.ends_with(" ...") && t.chars().count() <= MAX_TEXT + 4,
            "{t}"
        );
        assert!(!text("a *) b").contains("*)"));
    }
}
