//! The symbolic model: initial and marked states, and one partitioned
//! transition relation per event, as BDDs over the [`Layout`].
//!
//! The relation of event `e` is the conjunction, over the components that
//! have `e` in their alphabet (its participants), of each one's
//! transitions on `e`; the other components keep their state, so they are
//! left out of the relation altogether ("frame" only for participants):
//! images quantify only the participants' variables and rename only their
//! bits. Renaming shifts a variable to its neighbour (`2k` ↔ `2k + 1`),
//! which keeps the variable order, so it is a relabelling of the nodes.

use crate::encoding::{ComponentInfo, Layout, Role};
use crate::error::Result;
use biodivine_lib_bdd::{op_function, Bdd, BddNode, BddValuation, BddVariable, BddVariableSet};
use des::{Automaton, StateId};
use num_bigint::BigUint;

/// One event's relation and what it quantifies.
#[derive(Debug, Clone)]
pub(crate) struct EventRelation {
    /// `T_e(x_P, x'_P)`: every participant moves on `e`.
    pub(crate) relation: Bdd,
    /// States where every plant participant enables `e`.
    pub(crate) plant_enabled: Bdd,
    /// States where every specification participant enables `e`.
    pub(crate) spec_enabled: Bdd,
    /// Current-state variables of the participants.
    current: Vec<BddVariable>,
    /// Next-state variables of the participants.
    next: Vec<BddVariable>,
    /// Per variable: is it a participant's current-state variable?
    current_mask: Vec<bool>,
    /// Per variable: is it a participant's next-state variable?
    next_mask: Vec<bool>,
}

/// Plant and specification components as BDDs (see the module docs).
#[derive(Debug, Clone)]
pub struct Model {
    layout: Layout,
    vars: BddVariableSet,
    pub(crate) relations: Vec<EventRelation>,
    initial: Bdd,
    marked: Bdd,
}

impl Model {
    /// The model of `plants` ∥ `specs` (no product is built).
    pub fn new(plants: &[Automaton], specs: &[Automaton]) -> Result<Model> {
        let layout = Layout::new(plants, specs)?;
        // Fits: Layout checks the limit.
        let vars = BddVariableSet::new_anonymous(layout.num_vars as u16);
        let mut initial = vars.mk_true();
        let mut marked = vars.mk_true();
        for c in &layout.components {
            match c.initial {
                Some(s) => initial = initial.and(&code(&vars, c, s, false)),
                None => initial = vars.mk_false(),
            }
            let mut m = vars.mk_false();
            for &s in &c.marked {
                m = m.or(&code(&vars, c, s, false));
            }
            marked = marked.and(&m);
        }
        let relations = (0..layout.events.len())
            .map(|e| event_relation(&vars, &layout, e))
            .collect();
        Ok(Model {
            layout,
            vars,
            relations,
            initial,
            marked,
        })
    }

    /// The variable layout.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The initial state (false if a component has no states).
    pub fn initial(&self) -> &Bdd {
        &self.initial
    }

    /// The marked states: every component marked.
    pub fn marked(&self) -> &Bdd {
        &self.marked
    }

    /// The constant true.
    pub fn mk_true(&self) -> Bdd {
        self.vars.mk_true()
    }

    /// The constant false.
    pub fn mk_false(&self) -> Bdd {
        self.vars.mk_false()
    }

    /// Successors of `states` on event `e` (a model event index).
    pub fn post(&self, states: &Bdd, e: usize) -> Bdd {
        let r = &self.relations[e];
        let image = Bdd::binary_op_with_exists(states, &r.relation, op_function::and, &r.current);
        shift(&image, &r.next_mask, false)
    }

    /// Predecessors of `states` on event `e`.
    pub fn pre(&self, states: &Bdd, e: usize) -> Bdd {
        let r = &self.relations[e];
        let primed = shift(states, &r.current_mask, true);
        Bdd::binary_op_with_exists(&primed, &r.relation, op_function::and, &r.next)
    }

    /// States where event `e` can occur in plant ∥ specifications.
    pub fn enabled(&self, e: usize) -> Bdd {
        let r = &self.relations[e];
        r.plant_enabled.and(&r.spec_enabled)
    }

    /// Number of states (tuples) in `states`, a set over current-state
    /// variables: exact.
    pub fn count(&self, states: &Bdd) -> BigUint {
        states.exact_cardinality() >> (self.layout.num_vars / 2)
    }

    /// Does `set` hold the tuple `states` (component states in input
    /// order: plants, then specifications)?
    pub fn contains(&self, set: &Bdd, states: &[StateId]) -> Result<bool> {
        self.layout.check_tuple(states)?;
        let mut v = BddValuation::all_false(self.vars.num_vars());
        for (c, s) in self.layout.components.iter().zip(states) {
            for k in 0..c.bits {
                v.set_value(BddVariable::from_index(c.current_var(k)), c.bit(s.0, k));
            }
        }
        Ok(set.eval_in(&v))
    }

    /// Roles of the components, in input order.
    pub fn roles(&self) -> impl Iterator<Item = Role> + '_ {
        self.layout.components.iter().map(|c| c.role)
    }
}

/// The code of `state` of component `c` on its current (or next) bits.
fn code(vars: &BddVariableSet, c: &ComponentInfo, state: u32, next: bool) -> Bdd {
    let mut b = vars.mk_true();
    for k in 0..c.bits {
        let v = if next {
            c.next_var(k)
        } else {
            c.current_var(k)
        };
        b = b.and(&vars.mk_literal(BddVariable::from_index(v), c.bit(state, k)));
    }
    b
}

fn event_relation(vars: &BddVariableSet, layout: &Layout, e: usize) -> EventRelation {
    let n = layout.num_vars;
    let mut relation = vars.mk_true();
    let mut plant_enabled = vars.mk_true();
    let mut spec_enabled = vars.mk_true();
    let mut current = Vec::new();
    let mut next = Vec::new();
    let mut current_mask = vec![false; n];
    let mut next_mask = vec![false; n];
    for &p in &layout.events[e].participants {
        let c = &layout.components[p];
        let mut moves = vars.mk_false();
        let mut enabled = vars.mk_false();
        for &(s, _, t) in c.transitions.iter().filter(|t| t.1 == e) {
            let source = code(vars, c, s, false);
            moves = moves.or(&source.and(&code(vars, c, t, true)));
            enabled = enabled.or(&source);
        }
        relation = relation.and(&moves);
        match c.role {
            Role::Plant => plant_enabled = plant_enabled.and(&enabled),
            Role::Spec => spec_enabled = spec_enabled.and(&enabled),
        }
        for k in 0..c.bits {
            current.push(BddVariable::from_index(c.current_var(k)));
            next.push(BddVariable::from_index(c.next_var(k)));
            current_mask[c.current_var(k)] = true;
            next_mask[c.next_var(k)] = true;
        }
    }
    EventRelation {
        relation,
        plant_enabled,
        spec_enabled,
        current,
        next,
        current_mask,
        next_mask,
    }
}

/// Relabels the variables in `mask` to their neighbour: `v + 1` when `up`,
/// else `v - 1`. The neighbours must not occur in `bdd`, so the order of
/// every path is kept and the result is again a reduced BDD.
fn shift(bdd: &Bdd, mask: &[bool], up: bool) -> Bdd {
    let mut nodes = bdd.clone().to_nodes();
    for node in nodes.iter_mut().skip(2) {
        let v = node.var.to_index();
        if mask[v] {
            let w = if up { v + 1 } else { v - 1 };
            *node = BddNode::mk_node(BddVariable::from_index(w), node.low_link, node.high_link);
        }
    }
    // Every node keeps its children below it in the order (the neighbour
    // of a relabelled variable is absent), so this cannot fail.
    Bdd::from_nodes(&nodes).expect("relabelling to an absent neighbour keeps the order")
}
