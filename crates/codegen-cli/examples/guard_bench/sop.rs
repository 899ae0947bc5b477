//! A guard's node table as a minimised sum of products over the state
//! bits it reads, packed into one word.
//!
//! The bits a guard reads are ordered by (component, shift) and numbered
//! 0, 1, … in that order: packed bit `p` is read bit `p`. Consecutive
//! shifts of one component land on consecutive packed bits, so the
//! target gathers them in one step per run ([`Gather`]). The node table
//! becomes a BDD (biodivine-lib-bdd), whose greedily optimised DNF
//! (`Bdd::to_optimized_dnf`) of the guard and of its complement are the
//! ON-set and OFF-set covers Espresso starts from; each is minimised
//! against the other, and the smaller cover is kept: the guard holds when
//! a cube of the ON cover matches, or when none of the OFF cover does
//! ([`Sop::complement`]).

use biodivine_lib_bdd::{Bdd, BddNode, BddPointer, BddVariable};
use espresso_logic::espresso::{Espresso, EspressoCover};

/// Most packed bits (one `u64`; the target uses a `u32` up to 32).
pub const MAX_BITS: usize = 64;

/// Most DNF clauses of either polarity given to Espresso.
pub const MAX_CLAUSES: usize = 20_000;

/// One run of state bits copied into the packed word:
/// `word |= ((states[component] >> shift) & (2^width − 1)) << dest`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Gather {
    /// The component (index in the state vector).
    pub component: u16,
    /// Shift of the run's lowest bit in the component's state.
    pub shift: u8,
    /// Bits in the run (1 ..= 32).
    pub width: u8,
    /// Where the run's lowest bit goes in the packed word.
    pub dest: u8,
}

/// A cube: the packed word matches when `word & mask == value`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cube {
    /// The bits the cube fixes.
    pub mask: u64,
    /// Their values.
    pub value: u64,
}

/// A guard as gathers and cubes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sop {
    /// The runs that build the packed word.
    pub gathers: Vec<Gather>,
    /// Bits of the packed word.
    pub width: usize,
    /// The cover, first hit wins.
    pub cubes: Vec<Cube>,
    /// `true`: the cubes cover the OFF-set (the guard holds when none
    /// matches); `false`: the ON-set.
    pub complement: bool,
}

impl Sop {
    /// The guard's value in the component states `states`.
    pub fn holds(&self, states: &[u32]) -> bool {
        let word = self.gathers.iter().fold(0u64, |w, g| {
            let run = (states[usize::from(g.component)] >> g.shift) & (u32::MAX >> (32 - g.width));
            w | u64::from(run) << g.dest
        });
        self.cubes.iter().any(|c| word & c.mask == c.value) != self.complement
    }
}

/// `nodes` (`[bit, low, high]`, children first, `bit` indexing `bits`,
/// bits in the diagram's variable order) from `root` as a minimised sum
/// of products; `bits` are the (component, shift) of each state bit.
pub fn convert(root: u32, nodes: &[[u32; 3]], bits: &[(usize, u32)]) -> Result<Sop, String> {
    // The bits read, packed in (component, shift) order.
    let mut read: Vec<u32> = nodes.iter().map(|n| n[0]).collect();
    read.sort_by_key(|&b| bits[b as usize]);
    read.dedup();
    if read.len() > MAX_BITS {
        return Err(format!(
            "the guard reads {} state bits; the packed word holds {MAX_BITS}",
            read.len()
        ));
    }
    let mut packed = vec![usize::MAX; bits.len()];
    for (p, &b) in read.iter().enumerate() {
        packed[b as usize] = p;
    }
    let mut gathers: Vec<Gather> = Vec::new();
    for (p, &b) in read.iter().enumerate() {
        let (component, shift) = bits[b as usize];
        let component = u16::try_from(component).map_err(|_| "component index past u16")?;
        let shift = u8::try_from(shift).map_err(|_| "shift past u8")?;
        match gathers.last_mut() {
            Some(g)
                if g.component == component
                    && u32::from(g.shift) + u32::from(g.width) == u32::from(shift)
                    // A run never straddles the two halves of a wide word.
                    && (p != 32) =>
            {
                g.width += 1;
            }
            _ => gathers.push(Gather {
                component,
                shift,
                width: 1,
                dest: p as u8,
            }),
        }
    }

    let n = read.len();
    let bdd = to_bdd(root, nodes, bits.len())?;
    let on = clauses(&bdd, &packed, n)?;
    let off = clauses(&bdd.not(), &packed, n)?;
    let on_cover = minimise(n, &on, &off)?;
    let off_cover = minimise(n, &off, &on)?;
    let (cubes, complement) = if off_cover.len() < on_cover.len() {
        (off_cover, true)
    } else {
        (on_cover, false)
    };
    Ok(Sop {
        gathers,
        width: n,
        cubes,
        complement,
    })
}

/// The node table as a biodivine BDD over `vars` variables (bit `b` is
/// variable `b`; node indices are the same: 0 false, 1 true, then the
/// nodes children first).
fn to_bdd(root: u32, nodes: &[[u32; 3]], vars: usize) -> Result<Bdd, String> {
    let vars = u16::try_from(vars).map_err(|_| "too many state bits")?;
    let pointer = |k: u32| BddPointer::from_index(k as usize);
    let mut raw = vec![BddNode::mk_zero(vars), BddNode::mk_one(vars)];
    let used = if root < 2 { 0 } else { root as usize - 1 };
    for &[bit, low, high] in nodes.get(..used).ok_or("root past the table")? {
        raw.push(BddNode::mk_node(
            BddVariable::from_index(bit as usize),
            pointer(low),
            pointer(high),
        ));
    }
    // The root is the last node (0 alone is false, 0 and 1 true).
    raw.truncate(if root < 2 {
        root as usize + 1
    } else {
        raw.len()
    });
    Bdd::from_nodes(&raw)
}

/// The optimised DNF of `bdd` as cubes over the packed bits (0, 1, or 2
/// for a bit the clause leaves free).
fn clauses(bdd: &Bdd, packed: &[usize], n: usize) -> Result<Vec<Vec<u8>>, String> {
    let dnf = bdd
        ._to_optimized_dnf(true, &|d: &[_]| {
            if d.len() > MAX_CLAUSES {
                Err(())
            } else {
                Ok(())
            }
        })
        .map_err(|()| format!("more than {MAX_CLAUSES} DNF clauses"))?;
    Ok(dnf
        .iter()
        .map(|clause| {
            let mut cube = vec![2u8; n];
            for (var, value) in clause.to_values() {
                cube[packed[var.to_index()]] = u8::from(value);
            }
            cube
        })
        .collect())
}

/// A minimised cover of `on`, with `off` as the OFF-set (the two cover
/// the space: nothing is don't care).
fn minimise(n: usize, on: &[Vec<u8>], off: &[Vec<u8>]) -> Result<Vec<Cube>, String> {
    if on.is_empty() {
        return Ok(Vec::new());
    }
    if off.is_empty() {
        // The constant 1: one cube that fixes nothing.
        return Ok(vec![Cube { mask: 0, value: 0 }]);
    }
    let err = |e: espresso_logic::error::MinimizationError| format!("Espresso: {e}");
    // The instance fixes the dimensions of the covers below and must
    // outlive them.
    let esp =
        Espresso::try_new(n, 1, Some(&espresso_logic::EspressoConfig::default())).map_err(err)?;
    let build = |rows: &[Vec<u8>]| {
        let refs: Vec<(&[u8], &[u8])> = rows.iter().map(|r| (r.as_slice(), &[1u8][..])).collect();
        EspressoCover::from_cubes(&refs, n, 1)
    };
    let f = build(on).map_err(err)?;
    let r = build(off).map_err(err)?;
    let (minimised, _, _) = esp.try_minimize(&f, None, Some(&r)).map_err(err)?;
    let mut cubes = Vec::new();
    for cube in minimised.to_cubes(n, 1, espresso_logic::CubeType::F) {
        let mut c = Cube { mask: 0, value: 0 };
        for p in 0..n {
            if let Some(v) = cube.inputs().value_at(p) {
                c.mask |= 1 << p;
                c.value |= u64::from(v) << p;
            }
        }
        cubes.push(c);
    }
    Ok(cubes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use des_symbolic::guard_file::walk;

    /// Three components: `a` of 4 states (2 bits), `b` of 2, `c` of 8.
    const BITS: [(usize, u32); 6] = [(0, 1), (0, 0), (1, 0), (2, 2), (2, 1), (2, 0)];
    const STATES: [u32; 3] = [4, 2, 8];

    /// Every state vector of the three components.
    fn vectors() -> impl Iterator<Item = [u32; 3]> {
        (0..STATES.iter().product::<u32>()).map(|mut k| {
            core::array::from_fn(|c| {
                let s = k % STATES[c];
                k /= STATES[c];
                s
            })
        })
    }

    fn assert_same(root: u32, nodes: &[[u32; 3]]) -> Sop {
        let sop = convert(root, nodes, &BITS).unwrap();
        for states in vectors() {
            let bdd = walk(root, nodes, |b| {
                let (c, shift) = BITS[b as usize];
                states[c] >> shift & 1 == 1
            });
            assert_eq!(sop.holds(&states), bdd, "{states:?}: {sop:?}");
        }
        sop
    }

    #[test]
    fn cubes_compute_the_node_table_on_every_state_vector() {
        // a.high XOR c.low: 2 cubes either way.
        let xor = [[5, 0, 1], [5, 1, 0], [0, 2, 3]];
        let sop = assert_same(4, &xor);
        assert_eq!(sop.cubes.len(), 2);
        // b ∧ c.mid ∧ ¬a.low: one cube, three runs (a, b, c).
        let and = [[4, 0, 1], [2, 0, 2], [1, 3, 0]];
        let sop = assert_same(4, &and);
        assert_eq!(sop.cubes.len(), 1);
        assert_eq!(sop.gathers.len(), 3);
        // ¬(a = 3 ∧ b): the OFF-set is one cube, the ON-set two.
        let nand = [[2, 1, 0], [1, 1, 2], [0, 1, 3]];
        let sop = assert_same(4, &nand);
        assert!(sop.complement);
        assert_eq!(sop.cubes.len(), 1);
        // Parity of all six bits: 32 cubes, no fewer.
        let mut parity = Vec::new();
        let (mut even, mut odd) = (0u32, 1u32);
        for bit in (0..6).rev() {
            let base = parity.len() as u32 + 2;
            parity.push([bit, even, odd]);
            parity.push([bit, odd, even]);
            (even, odd) = (base, base + 1);
        }
        let sop = assert_same(odd, &parity);
        assert_eq!(sop.cubes.len(), 32);
        // Constants: false has no cube; a run of c's three bits is one gather.
        assert_eq!(assert_same(0, &[]).cubes, vec![]);
        let c_is_5 = [[5, 0, 1], [4, 2, 0], [3, 0, 3]];
        let sop = assert_same(4, &c_is_5);
        assert_eq!(sop.gathers.len(), 1);
        assert_eq!(sop.gathers[0].width, 3);
    }
}
