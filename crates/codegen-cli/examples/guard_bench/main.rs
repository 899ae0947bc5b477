//! The data of the guard-form benchmark (`cargo xtask guard-bench`): guard
//! collections as the executor's node tables and as minimised sums of
//! products, with the state vectors to evaluate them on, written as Rust
//! source for the firmware's `guard-bench` binary:
//!
//! ```text
//! cargo run -p codegen-cli --example guard_bench -- OUT.rs
//! ```
//!
//! Collections: the module project (`models/module.plc.toml`, lowered by
//! codegen), family instances synthesised symbolically (guard files as
//! `codegen synth --symbolic` writes them, lowered as codegen lowers a
//! project's guards), and random decision diagrams over 8, 16 and 24 bits
//! (fixed seeds) with a parity guard and single-cube guards among them.
//! State vectors: those a random walk of the closed loop visits (plants ∥
//! specifications under the guards), random ones for the random guards.
//! Every sum of products is checked against its node table on every
//! vector before anything is written.

mod sop;

use codegen::lower::{GuardPools, GuardTable};
use des::{Automaton, StateId};
use sop::Sop;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Most state vectors per collection.
const VECTORS: usize = 256;

/// Most evaluations per collection and form (the target keeps each to
/// sort them).
const MAX_EVALS: usize = 16_384;

/// A guard as the executor stores it: `GuardSpec` fields and its nodes.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Spec {
    event: usize,
    root: u16,
    start: u16,
    len: u16,
}

/// The executor's guard pools (`GUARDS`, `STATE_BITS`, `GUARD_NODES`).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
struct Pools {
    guards: Vec<Spec>,
    bits: Vec<(usize, u32)>,
    nodes: Vec<[u16; 3]>,
}

impl Pools {
    /// The pools of the guards `(event, root, nodes)` over the state bits
    /// `bits` as codegen lays them out ([`codegen::lower::GuardPools`]).
    fn lower(bits: &[(usize, u32)], guards: &[GuardTable<'_>]) -> Result<Pools, String> {
        let mut pools = GuardPools::default();
        pools
            .add(bits, guards)
            .map_err(|what| format!("too many {what} for 16-bit indices"))?;
        Ok(Pools::of(&pools))
    }

    /// Codegen's pools, in the executor's types.
    fn of(pools: &GuardPools) -> Pools {
        Pools {
            guards: pools
                .guards
                .iter()
                .map(|g| Spec {
                    event: usize::from(g.event),
                    root: g.root,
                    start: g.nodes.start,
                    len: g.nodes.len,
                })
                .collect(),
            bits: pools
                .state_bits
                .iter()
                .map(|b| (usize::from(b.component), u32::from(b.shift)))
                .collect(),
            nodes: pools.nodes.iter().map(|n| [n.bit, n.low, n.high]).collect(),
        }
    }

    /// Guard `k`'s nodes as `[bit, low, high]` over [`Pools::bits`].
    fn table(&self, k: usize) -> (u32, Vec<[u32; 3]>) {
        let g = &self.guards[k];
        let nodes = &self.nodes[usize::from(g.start)..usize::from(g.start + g.len)];
        let nodes = nodes.iter().map(|n| n.map(u32::from)).collect();
        (u32::from(g.root), nodes)
    }
}

/// One collection: pools, their sums of products, state vectors.
struct Collection {
    name: String,
    components: usize,
    pools: Pools,
    /// One per guard; `None` where the sum of products is too large to
    /// build (the guard stays a node table on the target).
    sops: Vec<Option<Sop>>,
    vectors: Vec<Vec<u32>>,
    reachable: usize,
}

impl Collection {
    fn new(
        name: String,
        components: usize,
        pools: Pools,
        vectors: Vec<Vec<u32>>,
        reachable: usize,
    ) -> Result<Collection, String> {
        let mut sops = Vec::new();
        for k in 0..pools.guards.len() {
            let (root, nodes) = pools.table(k);
            let sop = match sop::convert(root, &nodes, &pools.bits) {
                Ok(sop) => sop,
                Err(e) => {
                    eprintln!(
                        "{name}, guard {k} ({} nodes): no sum of products: {e}",
                        nodes.len()
                    );
                    sops.push(None);
                    continue;
                }
            };
            for v in &vectors {
                let bdd = des_symbolic::guard_file::walk(root, &nodes, |b| {
                    let (c, shift) = pools.bits[b as usize];
                    v[c] >> shift & 1 == 1
                });
                if sop.holds(v) != bdd {
                    return Err(format!(
                        "{name}, guard {k}: the cubes differ from the nodes on {v:?}"
                    ));
                }
            }
            sops.push(Some(sop));
        }
        let per_vector = pools.guards.len().max(1);
        let mut vectors = vectors;
        vectors.truncate(MAX_EVALS / per_vector);
        let reachable = reachable.min(vectors.len());
        Ok(Collection {
            name,
            components,
            pools,
            sops,
            vectors,
            reachable,
        })
    }
}

/// A small deterministic generator (xorshift64; the seed must not be 0).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Distinct state vectors (plants then specifications) a random walk of
/// the closed loop visits: every component with the event in its
/// alphabet moves, and a controllable event needs its guard.
fn walk_states(
    automata: &[&Automaton],
    allows: impl Fn(&str, &[u32]) -> bool,
    seed: u64,
) -> Vec<Vec<u32>> {
    let mut rng = Rng(seed);
    let initial: Vec<u32> = automata
        .iter()
        .map(|a| a.initial().map_or(0, |s| s.0))
        .collect();
    let mut names: Vec<(String, bool)> = Vec::new();
    for a in automata {
        for (_, e) in a.alphabet().iter() {
            if !names.iter().any(|(n, _)| *n == e.name) {
                names.push((e.name.clone(), e.controllable));
            }
        }
    }
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    let mut at = initial.clone();
    for _ in 0..200 * VECTORS {
        if seen.insert(at.clone()) {
            out.push(at.clone());
            if out.len() == VECTORS {
                break;
            }
        }
        let mut enabled = Vec::new();
        for (name, controllable) in &names {
            let mut next = at.clone();
            let moves = automata
                .iter()
                .enumerate()
                .all(|(c, a)| match a.alphabet().id(name) {
                    None => true,
                    Some(e) => match a.successor(StateId(at[c]), e) {
                        Some(t) => {
                            next[c] = t.0;
                            true
                        }
                        None => false,
                    },
                });
            if moves && (!controllable || allows(name, &at)) {
                enabled.push(next);
            }
        }
        at = if enabled.is_empty() {
            initial.clone()
        } else {
            enabled.swap_remove(rng.below(enabled.len()))
        };
    }
    out
}

/// A family instance, synthesised symbolically: its guard file lowered
/// as codegen lowers a project's guards, and the vectors of a walk.
fn family(family: &str, n: usize) -> Result<Collection, String> {
    let instance = des_symbolic::families::by_name(family, n)
        .ok_or_else(|| format!("no family `{family}`"))?
        .map_err(|e| e.to_string())?;
    let start = Instant::now();
    let s =
        des_symbolic::synthesize(&instance.plants, &instance.specs).map_err(|e| e.to_string())?;
    let file = des_symbolic::guard_file::GuardFile::new(
        &instance.name,
        &s,
        &instance.plants,
        &instance.specs,
    );
    eprintln!(
        "{}: synthesised in {:.2} s",
        instance.name,
        start.elapsed().as_secs_f64()
    );
    let guards: Vec<_> = file
        .guards
        .iter()
        .enumerate()
        .map(|(k, g)| (k, g.root, g.nodes.as_slice()))
        .collect();
    let pools = Pools::lower(&file.bit_places(), &guards)?;
    let automata: Vec<&Automaton> = instance.plants.iter().chain(&instance.specs).collect();
    let vectors = walk_states(&automata, |e, v| file.allows(e, v) == Some(true), 1);
    let reachable = vectors.len();
    Collection::new(instance.name, automata.len(), pools, vectors, reachable)
}

/// The module project: its guard pools as codegen lowers them, and the
/// vectors of a walk of
/// `families::module(10)`, whose files the project reads.
fn module_project(root: &Path) -> Result<Collection, String> {
    let path = root.join("models/module.plc.toml");
    let project = plc_project::load(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let config = codegen::lower::ConfigPools::from_project(&project).map_err(|e| e.to_string())?;
    let lowered = Pools::of(&GuardPools {
        guards: config.guards,
        state_bits: config.state_bits,
        nodes: config.guard_nodes,
    });
    let [guarded] = project.guarded.as_slice() else {
        return Err(format!(
            "{}: one symbolic supervisor expected",
            path.display()
        ));
    };
    let instance = des_symbolic::families::module(10).map_err(|e| e.to_string())?;
    let automata: Vec<&Automaton> = instance.plants.iter().chain(&instance.specs).collect();
    if automata.len() != guarded.components.len() {
        return Err("the module project's components are not module 10's".into());
    }
    let offset = guarded.components.start;
    let supervisors = project.supervisors.len();
    let to_project = |v: &[u32]| {
        let mut full = vec![0u32; supervisors];
        full[offset..offset + v.len()].copy_from_slice(v);
        full
    };
    let allows = |e: &str, v: &[u32]| {
        project
            .event(e)
            .is_none_or(|e| guarded.allows(e, &to_project(v)))
    };
    let vectors: Vec<Vec<u32>> = walk_states(&automata, allows, 1)
        .iter()
        .map(|v| to_project(v))
        .collect();
    let reachable = vectors.len();
    Collection::new(
        "module10-project".into(),
        supervisors,
        lowered,
        vectors,
        reachable,
    )
}

/// A random reduced decision diagram over `n` bits (bit `b` the variable
/// at depth `b`), about `width` nodes per level: `(root, nodes)` children
/// first, unreachable nodes dropped.
fn random_bdd(rng: &mut Rng, n: u32, width: usize) -> (u32, Vec<[u32; 3]>) {
    let mut nodes: Vec<[u32; 3]> = Vec::new();
    // Nodes of the levels below, by index (0 and 1 the terminals).
    let mut below: Vec<u32> = vec![0, 1];
    for bit in (0..n).rev() {
        let mut level = Vec::new();
        let count = if bit == 0 { 1 } else { 1 + rng.below(width) };
        let mut tries = 0;
        while level.len() < count && tries < 100 {
            tries += 1;
            // Mostly the level just below, sometimes anything lower.
            let pick = |rng: &mut Rng| {
                let recent = below.len().saturating_sub(width).max(2);
                if rng.below(4) == 0 || below.len() <= 2 {
                    below[rng.below(below.len())]
                } else {
                    below[recent + rng.below(below.len() - recent)]
                }
            };
            let (low, high) = (pick(rng), pick(rng));
            if low == high || nodes.contains(&[bit, low, high]) {
                continue;
            }
            nodes.push([bit, low, high]);
            level.push(nodes.len() as u32 + 1);
        }
        below.extend(level);
    }
    let root = *below.last().expect("terminals at least");
    // Keep what the root reaches, children first.
    let mut order = Vec::new();
    let mut new_index = vec![u32::MAX; nodes.len() + 2];
    new_index[0] = 0;
    new_index[1] = 1;
    let mut stack = vec![(root, false)];
    while let Some((at, expanded)) = stack.pop() {
        if new_index[at as usize] != u32::MAX {
            continue;
        }
        let [bit, low, high] = nodes[at as usize - 2];
        if expanded {
            new_index[at as usize] = order.len() as u32 + 2;
            order.push([bit, new_index[low as usize], new_index[high as usize]]);
        } else {
            stack.push((at, true));
            stack.push((high, false));
            stack.push((low, false));
        }
    }
    (new_index[root as usize], order)
}

/// Parity of bits `0..k` (odd).
fn parity(k: u32) -> (u32, Vec<[u32; 3]>) {
    let mut nodes = Vec::new();
    let (mut even, mut odd) = (1u32, 0u32);
    for bit in (0..k).rev() {
        let base = nodes.len() as u32 + 2;
        nodes.push([bit, even, odd]);
        nodes.push([bit, odd, even]);
        (even, odd) = (base, base + 1);
    }
    (odd, nodes)
}

/// A conjunction of `k` literals on bits spread over `n`: one cube.
fn conjunction(rng: &mut Rng, n: u32, k: u32) -> (u32, Vec<[u32; 3]>) {
    let mut bits: Vec<u32> = (0..n).collect();
    for i in (1..bits.len()).rev() {
        bits.swap(i, rng.below(i + 1));
    }
    let mut chosen: Vec<u32> = bits[..k as usize].to_vec();
    chosen.sort_unstable();
    let mut nodes = Vec::new();
    let mut at = 1;
    for &bit in chosen.iter().rev() {
        let positive = rng.below(2) == 1;
        nodes.push(if positive { [bit, 0, at] } else { [bit, at, 0] });
        at = nodes.len() as u32 + 1;
    }
    (at, nodes)
}

/// Random guards over `n` bits held by 2-bit components (4 states each):
/// random diagrams, a parity of `parity_bits` bits and two single cubes,
/// on random state vectors.
fn random(n: u32, width: usize, parity_bits: u32, seed: u64) -> Result<Collection, String> {
    let mut rng = Rng(seed);
    let components = n.div_ceil(2) as usize;
    let bits: Vec<(usize, u32)> = (0..n).map(|b| ((b / 2) as usize, 1 - b % 2)).collect();
    let mut tables = Vec::new();
    while tables.len() < 8 {
        let (root, nodes) = random_bdd(&mut rng, n, width);
        // Keep the paths (Espresso's input) within bounds.
        if root >= 2 && path_count(root, &nodes) <= 1 << 15 {
            tables.push((root, nodes));
        }
    }
    tables.push(parity(parity_bits));
    tables.push(conjunction(&mut rng, n, n.min(6)));
    tables.push(conjunction(&mut rng, n, n / 2));
    let guards: Vec<_> = tables
        .iter()
        .enumerate()
        .map(|(k, (r, t))| (k, *r, t.as_slice()))
        .collect();
    let pools = Pools::lower(&bits, &guards)?;
    let vectors = (0..VECTORS)
        .map(|_| (0..components).map(|_| rng.below(4) as u32).collect())
        .collect();
    Collection::new(format!("random{n}"), components, pools, vectors, 0)
}

/// Paths from `root` to either terminal.
fn path_count(root: u32, nodes: &[[u32; 3]]) -> u64 {
    let mut count = vec![1u64, 1];
    for &[_, low, high] in nodes {
        count.push(count[low as usize].saturating_add(count[high as usize]));
    }
    count[root as usize]
}

/// The collections as Rust source for the firmware's `guard-bench`.
fn emit(collections: &[Collection]) -> String {
    let mut s = String::from(
        "// Generated by `cargo run -p codegen-cli --example guard_bench` (`cargo xtask guard-bench`).\n",
    );
    let list = |items: Vec<String>| items.join(", ");
    for (k, c) in collections.iter().enumerate() {
        let p = &c.pools;
        let guards = list(
            p.guards
                .iter()
                .map(|g| {
                    format!(
                        "GuardSpec {{ event: {}, root: {}, nodes: Span::new({}, {}) }}",
                        g.event, g.root, g.start, g.len
                    )
                })
                .collect(),
        );
        let bits = list(
            p.bits
                .iter()
                .map(|(c, s)| format!("StateBit {{ component: {c}, shift: {s} }}"))
                .collect(),
        );
        let nodes = list(
            p.nodes
                .iter()
                .map(|[b, l, h]| format!("GuardNode {{ bit: {b}, low: {l}, high: {h} }}"))
                .collect(),
        );
        let (mut sops, mut gathers, mut cubes) = (Vec::new(), Vec::new(), Vec::new());
        for sop in &c.sops {
            let Some(sop) = sop else {
                sops.push("SopGuard { gathers: Span::EMPTY, cubes: Span::EMPTY, complement: false, wide: false, nodes: true }".to_owned());
                continue;
            };
            // A wide guard (more than 32 bits) has two entries per cube:
            // the low word's, then the high word's.
            let wide = sop.width > 32;
            let entries: Vec<(u64, u64)> = sop
                .cubes
                .iter()
                .flat_map(|c| {
                    let low = (c.mask & 0xffff_ffff, c.value & 0xffff_ffff);
                    let high = (c.mask >> 32, c.value >> 32);
                    std::iter::once(low).chain(wide.then_some(high))
                })
                .collect();
            sops.push(format!(
                "SopGuard {{ gathers: Span::new({}, {}), cubes: Span::new({}, {}), complement: {}, wide: {wide}, nodes: false }}",
                if sop.gathers.is_empty() { 0 } else { gathers.len() },
                sop.gathers.len(),
                if entries.is_empty() { 0 } else { cubes.len() },
                entries.len(),
                sop.complement
            ));
            gathers.extend(sop.gathers.iter().map(|g| {
                format!(
                    "Gather {{ mask: {:#x}, component: {}, shift: {}, dest: {} }}",
                    u32::MAX >> (32 - g.width),
                    g.component,
                    g.shift,
                    g.dest
                )
            }));
            cubes.extend(
                entries
                    .iter()
                    .map(|(m, v)| format!("Cube {{ mask: {m:#x}, value: {v:#x} }}")),
            );
        }
        let states = list(c.vectors.iter().flatten().map(u32::to_string).collect());
        let _ = writeln!(
            s,
            "static GUARDS_{k}: [[u32; 3]; {}] = GuardSpec::records(&[{guards}]);\n\
             static BITS_{k}: [[u32; 1]; {}] = StateBit::records(&[{bits}]);\n\
             static NODES_{k}: [[u32; 2]; {}] = GuardNode::records(&[{nodes}]);\n\
             static SOPS_{k}: [SopGuard; {}] = [{}];\n\
             static GATHERS_{k}: [Gather; {}] = [{}];\n\
             static CUBES_{k}: [Cube; {}] = [{}];\n\
             static STATES_{k}: [u32; {}] = [{states}];",
            p.guards.len(),
            p.bits.len(),
            p.nodes.len(),
            sops.len(),
            list(sops),
            gathers.len(),
            list(gathers),
            cubes.len(),
            list(cubes),
            c.vectors.len() * c.components,
        );
    }
    let _ = writeln!(
        s,
        "/// The collections.\nstatic COLLECTIONS: [Collection; {}] = [",
        collections.len()
    );
    for (k, c) in collections.iter().enumerate() {
        let _ = writeln!(
            s,
            "    Collection {{ name: {:?}, components: {}, reachable: {}, guards: Guards {{ events: &GUARDS_{k}, bits: &BITS_{k}, nodes: &NODES_{k} }}, sop: SopGuards {{ guards: &SOPS_{k}, gathers: &GATHERS_{k}, cubes: &CUBES_{k} }}, states: &STATES_{k} }},",
            c.name, c.components, c.reachable
        );
    }
    s.push_str("];\n");
    s
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [out] = args.as_slice() else {
        return Err("usage: guard_bench OUT.rs".into());
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut collections = vec![module_project(&root)?];
    for (name, n) in [
        ("ringb", 12),
        ("ringb", 20),
        ("phil", 12),
        ("phil", 20),
        ("tline", 10),
    ] {
        collections.push(family(name, n)?);
    }
    collections.push(random(8, 3, 8, 8)?);
    collections.push(random(16, 3, 12, 16)?);
    collections.push(random(24, 2, 12, 24)?);
    for c in &collections {
        let cubes: usize = c.sops.iter().flatten().map(|s| s.cubes.len()).sum();
        eprintln!(
            "{}: {} guards, {} nodes, {} state bits, {} cubes, {} vectors ({} reachable)",
            c.name,
            c.pools.guards.len(),
            c.pools.nodes.len(),
            c.pools.bits.len(),
            cubes,
            c.vectors.len(),
            c.reachable
        );
    }
    let path = Path::new(out);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    std::fs::write(path, emit(&collections)).map_err(|e| format!("{}: {e}", path.display()))
}
