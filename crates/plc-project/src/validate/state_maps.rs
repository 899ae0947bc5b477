//! State maps (Moore outputs): an output that is 1 while some listed
//! supervisor is in one of the listed states.
//!
//! A state map names at least one supervisor, and at least one state of
//! each; every supervisor is declared and every state is one of its
//! automaton's (by name). A state listed twice counts once.
//!
//! A place map (`places = { net = ["p1", …] }`) is the same for Petri
//! nets: at least one place of each listed net, every place one of the
//! net's by id; the output is 1 while some listed place holds a token.

use super::super::model::{Net, Supervisor};
use super::super::parse::{names, Entries, Name, Names};
use super::{Declared, Validator};
use des::automaton::StateId;
use des::error::Result;
use toml::Spanned;

impl Validator<'_> {
    /// The state map `map` of `output`: (supervisor index, its states).
    pub(super) fn state_map(
        &self,
        output: &Name,
        map: &Spanned<Entries<Names>>,
        supervisors: &Declared<Supervisor>,
    ) -> Result<Vec<(usize, Vec<StateId>)>> {
        let out = output.get_ref();
        if map.get_ref().0.is_empty() {
            return Err(self.error(
                &map.span(),
                format!("the state map of output `{out}` names no state; a state map must name at least one state"),
            ));
        }
        let mut entries = Vec::new();
        for (sup_name, states) in &map.get_ref().0 {
            let j = self.resolve(supervisors, sup_name)?;
            let sup = &supervisors.items[j];
            let list = names(Some(states));
            if list.is_empty() {
                return Err(self.error(
                    &states.span(),
                    format!(
                        "the state map of output `{out}` lists no state of supervisor `{}`; a state map must name at least one state",
                        sup.name
                    ),
                ));
            }
            let mut ids: Vec<StateId> = Vec::with_capacity(list.len());
            for state in &list {
                let id = sup
                    .automaton
                    .state_by_name(state.get_ref())
                    .ok_or_else(|| {
                        self.error(
                            &state.span(),
                            format!(
                                "supervisor `{}` has no state `{}`",
                                sup.name,
                                state.get_ref()
                            ),
                        )
                    })?;
                if !ids.contains(&id) {
                    ids.push(id);
                }
            }
            entries.push((j, ids));
        }
        Ok(entries)
    }

    /// The place map `map` of `output`: (net index, its places).
    pub(super) fn place_map(
        &self,
        output: &Name,
        map: &Spanned<Entries<Names>>,
        nets: &Declared<Net>,
    ) -> Result<Vec<(usize, Vec<usize>)>> {
        let out = output.get_ref();
        if map.get_ref().0.is_empty() {
            return Err(self.error(
                &map.span(),
                format!("the place map of output `{out}` names no place; a place map must name at least one place"),
            ));
        }
        let mut entries = Vec::new();
        for (net_name, places) in &map.get_ref().0 {
            let n = self.resolve(nets, net_name)?;
            let net = &nets.items[n];
            let list = names(Some(places));
            if list.is_empty() {
                return Err(self.error(
                    &places.span(),
                    format!(
                        "the place map of output `{out}` lists no place of net `{}`; a place map must name at least one place",
                        net.name
                    ),
                ));
            }
            let mut ids: Vec<usize> = Vec::with_capacity(list.len());
            for place in &list {
                let p = net.net.place(place.get_ref()).ok_or_else(|| {
                    self.error(
                        &place.span(),
                        format!("net `{}` has no place `{}`", net.name, place.get_ref()),
                    )
                })?;
                if !ids.contains(&p) {
                    ids.push(p);
                }
            }
            entries.push((n, ids));
        }
        Ok(entries)
    }
}
