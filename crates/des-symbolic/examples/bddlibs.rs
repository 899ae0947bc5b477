//! The BDD library comparison behind the choice of biodivine-lib-bdd:
//! forward reachability of one family instance with partitioned
//! relations and chaining, the same algorithm on each library.
//!
//! ```text
//! cargo build --release -p des-symbolic --features compare-bdd --example bddlibs
//! /usr/bin/time -v target/release/examples/bddlibs biodivine ringb 16
//! /usr/bin/time -v target/release/examples/bddlibs oxidd ringb 16
//! ```
//!
//! One library per process, so that `/usr/bin/time -v` reports each one's
//! peak memory.

use des_symbolic::encoding::Layout;
use des_symbolic::families;
use std::process::ExitCode;
use std::time::Instant;

/// What a run found.
struct Outcome {
    states: f64,
    nodes: usize,
    sweeps: usize,
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(lib), Some(family), Some(n)) = (
        args.first(),
        args.get(1),
        args.get(2).and_then(|n| n.parse::<usize>().ok()),
    ) else {
        eprintln!("usage: bddlibs biodivine|oxidd FAMILY N");
        return ExitCode::from(2);
    };
    let Some(Ok(f)) = families::by_name(family, n) else {
        eprintln!("no family `{family}` of size {n}");
        return ExitCode::from(2);
    };
    let layout = match Layout::new(&f.plants, &f.specs) {
        Ok(l) => l,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let start = Instant::now();
    let outcome = match lib.as_str() {
        "biodivine" => bio::reach(&layout),
        "oxidd" => match oxi::reach(&layout) {
            Ok(o) => o,
            Err(()) => {
                eprintln!("oxidd ran out of nodes");
                return ExitCode::FAILURE;
            }
        },
        _ => {
            eprintln!("unknown library `{lib}`");
            return ExitCode::from(2);
        }
    };
    println!(
        "{lib} {}: {} reachable states, {} nodes, {} sweeps, {:.3} s",
        f.name,
        outcome.states,
        outcome.nodes,
        outcome.sweeps,
        start.elapsed().as_secs_f64()
    );
    ExitCode::SUCCESS
}

/// The code of `state` on a component's current (or next) bits, as
/// `(variable, value)` literals.
fn literals(layout: &Layout, c: usize, state: u32, next: bool) -> Vec<(usize, bool)> {
    let comp = &layout.components[c];
    (0..comp.bits)
        .map(|k| {
            let v = if next {
                comp.next_var(k)
            } else {
                comp.current_var(k)
            };
            (v, comp.bit(state, k))
        })
        .collect()
}

mod bio {
    use super::{literals, Layout, Outcome};
    use biodivine_lib_bdd::{op_function, Bdd, BddNode, BddVariable, BddVariableSet};

    fn cube(vars: &BddVariableSet, lits: &[(usize, bool)]) -> Bdd {
        lits.iter().fold(vars.mk_true(), |b, &(v, x)| {
            b.and(&vars.mk_literal(BddVariable::from_index(v), x))
        })
    }

    fn shift_down(bdd: &Bdd, mask: &[bool]) -> Bdd {
        let mut nodes = bdd.clone().to_nodes();
        for node in nodes.iter_mut().skip(2) {
            let v = node.var.to_index();
            if mask[v] {
                *node = BddNode::mk_node(
                    BddVariable::from_index(v - 1),
                    node.low_link,
                    node.high_link,
                );
            }
        }
        Bdd::from_nodes(&nodes).expect("order kept")
    }

    pub fn reach(layout: &Layout) -> Outcome {
        let vars = BddVariableSet::new_anonymous(layout.num_vars as u16);
        let mut rels = Vec::new();
        for (e, ev) in layout.events.iter().enumerate() {
            let mut rel = vars.mk_true();
            let mut quant = Vec::new();
            let mut mask = vec![false; layout.num_vars];
            for &c in &ev.participants {
                let comp = &layout.components[c];
                let mut moves = vars.mk_false();
                for &(s, _, t) in comp.transitions.iter().filter(|t| t.1 == e) {
                    let mut lits = literals(layout, c, s, false);
                    lits.extend(literals(layout, c, t, true));
                    moves = moves.or(&cube(&vars, &lits));
                }
                rel = rel.and(&moves);
                for k in 0..comp.bits {
                    quant.push(BddVariable::from_index(comp.current_var(k)));
                    mask[comp.next_var(k)] = true;
                }
            }
            rels.push((rel, quant, mask));
        }
        let mut reached = vars.mk_true();
        for (c, comp) in layout.components.iter().enumerate() {
            reached = reached.and(&cube(
                &vars,
                &literals(layout, c, comp.initial.unwrap_or(0), false),
            ));
        }
        let mut frontier = reached.clone();
        let mut sweeps = 0;
        while !frontier.is_false() {
            sweeps += 1;
            let mut found = vars.mk_false();
            for (rel, quant, mask) in &rels {
                let image = Bdd::binary_op_with_exists(&frontier, rel, op_function::and, quant);
                let new = shift_down(&image, mask).and_not(&reached);
                if !new.is_false() {
                    reached = reached.or(&new);
                    found = found.or(&new);
                    frontier = frontier.or(&new);
                }
            }
            frontier = found;
        }
        Outcome {
            states: reached.cardinality() / 2f64.powi(layout.num_vars as i32 / 2),
            nodes: reached.size(),
            sweeps,
        }
    }
}

mod oxi {
    use super::{literals, Layout, Outcome};
    use oxidd::bdd::BDDFunction;
    use oxidd::util::{num::F64, AllocResult, SatCountCache};
    use oxidd::{BooleanFunction, BooleanFunctionQuant, BooleanOperator, Function, FunctionSubst};
    use oxidd::{Manager, ManagerRef, Subst};

    pub fn reach(layout: &Layout) -> Result<Outcome, ()> {
        run(layout).map_err(|_| ())
    }

    fn run(layout: &Layout) -> AllocResult<Outcome> {
        let n = layout.num_vars;
        let mref = oxidd::bdd::new_manager(1 << 22, 1 << 20, 1);
        let vars: Vec<BDDFunction> = mref.with_manager_exclusive(|m| {
            m.add_vars(n as u32);
            (0..n as u32)
                .map(|v| BDDFunction::var(m, v))
                .collect::<AllocResult<Vec<_>>>()
        })?;
        let (t, f) = mref.with_manager_shared(|m| (BDDFunction::t(m), BDDFunction::f(m)));
        let cube = |lits: &[(usize, bool)]| -> AllocResult<BDDFunction> {
            let mut b = t.clone();
            for &(v, x) in lits {
                let lit = if x { vars[v].clone() } else { vars[v].not()? };
                b = b.and(&lit)?;
            }
            Ok(b)
        };
        let mut rels = Vec::new();
        for (e, ev) in layout.events.iter().enumerate() {
            let mut rel = t.clone();
            let mut quant = t.clone();
            let mut from = Vec::new();
            let mut to = Vec::new();
            for &c in &ev.participants {
                let comp = &layout.components[c];
                let mut moves = f.clone();
                for &(s, _, tg) in comp.transitions.iter().filter(|t| t.1 == e) {
                    let mut lits = literals(layout, c, s, false);
                    lits.extend(literals(layout, c, tg, true));
                    moves = moves.or(&cube(&lits)?)?;
                }
                rel = rel.and(&moves)?;
                for k in 0..comp.bits {
                    quant = quant.and(&vars[comp.current_var(k)])?;
                    from.push(comp.next_var(k) as u32);
                    to.push(vars[comp.current_var(k)].clone());
                }
            }
            rels.push((rel, quant, Subst::new(from, to)));
        }
        let mut reached = t.clone();
        for (c, comp) in layout.components.iter().enumerate() {
            reached = reached.and(&cube(&literals(
                layout,
                c,
                comp.initial.unwrap_or(0),
                false,
            ))?)?;
        }
        let mut frontier = reached.clone();
        let mut sweeps = 0;
        while frontier.satisfiable() {
            sweeps += 1;
            let mut found = f.clone();
            for (rel, quant, subst) in &rels {
                let image = frontier.apply_exists(BooleanOperator::And, rel, quant)?;
                // `a.imp_strict(b)` is `¬a ∧ b`.
                let new = reached.imp_strict(&image.substitute(subst)?)?;
                if new.satisfiable() {
                    reached = reached.or(&new)?;
                    found = found.or(&new)?;
                    frontier = frontier.or(&new)?;
                }
            }
            frontier = found;
        }
        let count: F64 = reached.sat_count(
            n as u32,
            &mut SatCountCache::<F64, std::hash::RandomState>::default(),
        );
        let count = count.0;
        Ok(Outcome {
            states: count / 2f64.powi(n as i32 / 2),
            nodes: reached.node_count(),
            sweeps,
        })
    }
}
