//! The `match` baseline's text: each supervisor as one plain `match` on
//! (state, local event), what a hand-written state machine would be, and
//! the `Match` program over them. Used to measure the other backends.

use super::{ident, quoted, Emitter, SupervisorStats};
use executor::program as ex;
use plc_project::ident::supervisor_item;
use std::fmt::Write;

impl Emitter<'_> {
    /// The baseline: each supervisor as one `match` on (state, local event).
    pub(super) fn matches(&mut self, crc: u32, crc_doc: &str) -> Vec<SupervisorStats> {
        let mut stats = Vec::new();
        let mut arms = Vec::new();
        let _ = writeln!(
            self.out,
            "/// The supervisors as plain `match` statements on (state, local event): the\n/// baseline a hand-written state machine would be.\npub mod matches {{"
        );
        for (j, sup) in self.project.supervisors.iter().enumerate() {
            let a = &sup.automaton;
            let fn_name = supervisor_item(&sup.name);
            let mut cases = String::new();
            for s in a.states() {
                for (local, &(_, id)) in sup.local_events.iter().enumerate() {
                    if let Some(t) = a.successor(s, id) {
                        let _ = write!(cases, "({}, {local}) => Some({}),", s.0, t.0);
                    }
                }
            }
            let _ = writeln!(
                self.out,
                "/// Supervisor {} ({}).\n///\n/// {} States are the indices of `states::{}`.\n#[allow(non_snake_case)]\npub fn {fn_name}(state: u32, event: u16) -> Option<u32> {{ match (state, event) {{ {cases} _ => None }} }}",
                quoted(&sup.name),
                self.source_line(j),
                self.local_events_line(j),
                ident(&sup.name),
            );
            arms.push(format!(
                "{} => matches::{fn_name}(state, local),",
                self.supervisor(j as ex::Index)
            ));
            stats.push(SupervisorStats {
                name: sup.name.clone(),
                states: a.num_states() as u32,
                events: sup.local_events.len() as u16,
                layout: None,
                table_bytes: 0,
                naive_bytes: 2 * a.num_states() * sup.local_events.len(),
                cubes: 0,
                logic_effort: None,
                literals: 0,
            });
        }
        let _ = writeln!(self.out, "}}");
        let _ = writeln!(
            self.out,
            "{crc_doc}\n#[allow(dead_code)]\npub const IMAGE_CRC: u32 = {crc:#010x};\n/// The program's data: the configuration above, and the supervisors as\n/// `match` statements (`executor::compiled`).\n#[allow(dead_code)]\npub struct Match;\nimpl ProgramData for Match {{\n    const CONFIG: Config<'static> = CONFIG;\n    const IMAGE_CRC: u32 = IMAGE_CRC;\n    fn next_state(supervisor: Index, state: u32, local: Index) -> Option<u32> {{\n        match supervisor {{ {} _ => None }}\n    }}\n}}\n/// The program: run it with `executor::Controller::new(&PROGRAM, Memory::new())`.\n#[allow(dead_code)]\npub static PROGRAM: Compiled<Match> = Compiled::new();",
            arms.join("\n")
        );
        stats
    }
}
