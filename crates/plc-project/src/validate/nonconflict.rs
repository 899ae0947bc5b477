//! `check_nonconflicting = true` in `[plc]`: the build proves that the
//! project's supervisors do not block each other. Each supervisor may be
//! nonblocking on its own while together they reach a state from which no
//! state marked in all of them can be reached; that is refused here, with
//! a shortest event string into such a state and where each supervisor
//! is then.
//!
//! The check runs on BDDs (`des_symbolic::verify`), never building the
//! supervisors' product, so it holds for sets of supervisors whose product
//! is far beyond what could be enumerated. It covers automaton supervisors;
//! a project with Petri nets or symbolic supervisors is refused at the
//! flag (a net is not an automaton the check reads, nor are guards).

use super::super::model::{Guarded, Net, Supervisor};
use super::Validator;
use des::error::Result;
use des::StateId;
use des_symbolic::verify::nonblocking;
use des_symbolic::Model;
use std::ops::Range;
use toml::Spanned;

impl Validator<'_> {
    /// Checks that `supervisors` are nonconflicting when `flag` asks for
    /// it.
    pub(super) fn nonconflicting(
        &self,
        flag: Option<&Spanned<bool>>,
        supervisors: &[Supervisor],
        nets: &[Net],
        guarded: &[Guarded],
    ) -> Result<()> {
        let Some(flag) = flag.filter(|f| *f.get_ref()) else {
            return Ok(());
        };
        let span: Range<usize> = flag.span();
        if let Some(net) = nets.first() {
            return Err(self.error(
                &span,
                format!(
                    "check_nonconflicting covers automaton supervisors, and net `{}` (line {}) is not one: remove the flag, or check the net with `codegen petri`",
                    net.name, net.line
                ),
            ));
        }
        if let Some(g) = guarded.first() {
            return Err(self.error(
                &span,
                format!(
                    "check_nonconflicting covers automaton supervisors, and symbolic supervisor `{}` (line {}) restricts its components by guards the check does not read: remove the flag (symbolic synthesis is nonblocking by construction), or verify with `codegen verify --nonblocking --symbolic`",
                    g.name, g.line
                ),
            ));
        }
        if supervisors.len() < 2 {
            return Err(self.error(
                &span,
                format!(
                    "check_nonconflicting needs two supervisors or more; this project has {}",
                    supervisors.len()
                ),
            ));
        }
        let automata: Vec<des::Automaton> =
            supervisors.iter().map(|s| s.automaton.clone()).collect();
        let model = Model::new(&automata, &[])
            .map_err(|e| self.error(&span, format!("check_nonconflicting: {e}")))?;
        let verdict = nonblocking(&model);
        let Some(c) = verdict.counterexample else {
            return Ok(());
        };
        let after = if c.events.is_empty() {
            "from the initial state".to_owned()
        } else {
            format!("after {}", c.events.join(" "))
        };
        let states: Vec<String> = c
            .state
            .iter()
            .zip(supervisors)
            .map(|((_, x), s)| format!("{} in {}", s.name, s.automaton.state_name(StateId(*x))))
            .collect();
        Err(self.error(
            &span,
            format!(
                "the supervisors are conflicting: {after} they are in ({}), from where no state marked in all of them can be reached ({} of {} reachable states block)",
                states.join(", "),
                verdict.blocking,
                verdict.reachable
            ),
        ))
    }
}
