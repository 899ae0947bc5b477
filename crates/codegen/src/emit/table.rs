//! The table backend's text: each supervisor as constant bit-packed
//! tables (`<NAME>_DEFINED`, `<NAME>_TARGETS`, and `<NAME>_ROW_STARTS`
//! when sparse or `<NAME>_STATES` when keyed) that the executor decodes,
//! and the `Tables` program over them.

use super::{doc_text, ident, quoted, Emitter, SupervisorStats};
use crate::backend::table::Layout;
use crate::lower::TableImage;
use std::fmt::Write;

/// Words as hexadecimal literals.
fn words(list: &[u32]) -> String {
    list.iter()
        .map(|w| format!("{w:#010x}"))
        .collect::<Vec<_>>()
        .join(", ")
}

impl Emitter<'_> {
    /// Doc lines showing the first rows of a supervisor's transitions.
    fn decoded_rows(&self, j: usize, rows: usize) -> String {
        let sup = &self.project.supervisors[j];
        let a = &sup.automaton;
        let mut doc = String::new();
        for s in a.states().take(rows) {
            let moves: Vec<String> = sup
                .local_events
                .iter()
                .filter_map(|&(g, id)| {
                    a.successor(s, id)
                        .map(|t| format!("{} → {}", self.project.events[g].name, a.state_name(t)))
                })
                .collect();
            let _ = writeln!(
                doc,
                "/// - state {} {}: {}",
                s.0,
                quoted(&a.state_name(s)),
                if moves.is_empty() {
                    "(no transitions)".to_owned()
                } else {
                    doc_text(&moves.join(", "))
                }
            );
        }
        if a.num_states() > rows {
            let _ = writeln!(doc, "/// - … {} more states", a.num_states() - rows);
        }
        doc
    }

    /// The supervisors as constant tables, `TABLES`, `IMAGE_CRC` and the
    /// `Tables` program.
    pub(super) fn tables(&mut self, image: &TableImage, crc_doc: &str) -> Vec<SupervisorStats> {
        let mut stats = Vec::new();
        let mut views = Vec::new();
        for (j, (sup, table)) in self
            .project
            .supervisors
            .iter()
            .zip(&image.tables)
            .enumerate()
        {
            let id = ident(&sup.name);
            let rows = self.decoded_rows(j, 8);
            let layout = match table.layout {
                Layout::Dense => "dense layout".to_owned(),
                Layout::Sparse => "sparse layout".to_owned(),
                Layout::Keyed => format!(
                    "keyed layout ({} distinct rows of defined-bits in `{id}_DEFINED`)",
                    table.stored_rows()
                ),
                Layout::Net => "net layout".to_owned(),
            };
            let _ = writeln!(
                self.out,
                "/// Supervisor {} ({}): {} states in {} bits, {} local events, {layout}, {} bytes.\n/// {}\n/// Transitions of the first states:\n{rows}const {id}_DEFINED: [u32; {}] = [{}];\n/// Packed targets of {}.\nconst {id}_TARGETS: [u32; {}] = [{}];",
                quoted(&sup.name),
                self.source_line(j),
                table.states,
                table.state_bits,
                table.events,
                table.bytes(),
                self.local_events_line(j),
                table.defined.len(),
                words(&table.defined),
                quoted(&sup.name),
                table.targets.len(),
                words(&table.targets),
            );
            let rows = match table.layout {
                Layout::Dense | Layout::Net => "Rows::Dense".to_owned(),
                Layout::Keyed => {
                    let _ = writeln!(
                        self.out,
                        "/// Per state of {}: its row of `{id}_DEFINED` (low {} bits) and its first entry in `{id}_TARGETS` (high {} bits).\nconst {id}_STATES: [u32; {}] = [{}];",
                        quoted(&sup.name),
                        table.key_bits,
                        table.start_bits,
                        table.row_starts.len(),
                        words(&table.row_starts)
                    );
                    format!(
                        "Rows::Keyed {{ states: &{id}_STATES, key_bits: {}, start_bits: {} }}",
                        table.key_bits, table.start_bits
                    )
                }
                Layout::Sparse => {
                    let _ = writeln!(
                        self.out,
                        "/// Row starts of {}.\nconst {id}_ROW_STARTS: [u32; {}] = [{}];",
                        quoted(&sup.name),
                        table.row_starts.len(),
                        words(&table.row_starts)
                    );
                    format!(
                        "Rows::Sparse {{ row_starts: &{id}_ROW_STARTS, start_bits: {} }}",
                        table.start_bits
                    )
                }
            };
            views.push(format!(
                "SupervisorTable {{ events: {}, state_bits: {}, defined: &{id}_DEFINED, targets: &{id}_TARGETS, rows: {rows} }}",
                table.events, table.state_bits
            ));
            stats.push(SupervisorStats::of_table(&sup.name, table));
        }
        let nets = image
            .tables
            .get(self.project.supervisors.len()..)
            .unwrap_or(&[]);
        let mut groups = nets.iter();
        let supervisors = self.supervisors();
        for n in 0..self.project.nets.len() {
            let net = supervisors.net(n);
            let (fields, places_of) = (&net.layout.fields, net.net.net.places());
            for g in 0..net.groups() {
                let Some(table) = groups.next() else { break };
                let name = net.group_name(g);
                let id = ident(&name);
                let places: Vec<String> = net
                    .layout
                    .group_places(g)
                    .map(|p| {
                        let f = fields[p];
                        let bits = if f.width == 1 {
                            format!("bit {}", f.shift)
                        } else {
                            format!("bits {}–{}", f.shift, f.shift + f.width - 1)
                        };
                        format!("{} ({bits})", places_of[p].id)
                    })
                    .collect();
                let transitions = net.group_transitions(g);
                let arcs = |arcs: &[(usize, u32)]| -> String {
                    let terms: Vec<String> = arcs
                        .iter()
                        .filter(|&&(p, _)| fields[p].group == g)
                        .map(|&(p, w)| match w {
                            1 => places_of[p].id.clone(),
                            w => format!("{w}·{}", places_of[p].id),
                        })
                        .collect();
                    if terms.is_empty() {
                        "∅".to_owned()
                    } else {
                        terms.join(" + ")
                    }
                };
                let moves: Vec<String> = transitions
                    .iter()
                    .map(|&t| {
                        let tr = &net.net.net.transitions()[t];
                        format!(
                            "/// - {}: {} → {}\n",
                            quoted(&tr.id),
                            doc_text(&arcs(&tr.input)),
                            doc_text(&arcs(&tr.output))
                        )
                    })
                    .collect();
                let _ = writeln!(
                    self.out,
                    "/// Net group {} ({} places as counters in {} bits, {} local transitions, net layout, {} bytes).\n/// Places: {}.\n/// Local transitions (`PRE` → `POST`):\n{}const {id}_PRE: [u32; {}] = [{}];\n/// `POST` words of {}.\nconst {id}_POST: [u32; {}] = [{}];\n/// Counter masks of {}, in the order of its places.\nconst {id}_FIELDS: [u32; {}] = [{}];",
                    quoted(&name),
                    table.row_starts.len(),
                    table.state_bits,
                    table.events,
                    table.bytes(),
                    doc_text(&places.join(", ")),
                    moves.concat(),
                    table.defined.len(),
                    words(&table.defined),
                    quoted(&name),
                    table.targets.len(),
                    words(&table.targets),
                    quoted(&name),
                    table.row_starts.len(),
                    words(&table.row_starts),
                );
                views.push(format!(
                    "SupervisorTable {{ events: {}, state_bits: {}, defined: &{id}_PRE, targets: &{id}_POST, rows: Rows::Net {{ fields: &{id}_FIELDS }} }}",
                    table.events, table.state_bits
                ));
                stats.push(SupervisorStats {
                    states: u32::try_from(net.net.markings).unwrap_or(u32::MAX),
                    naive_bytes: 0,
                    ..SupervisorStats::of_table(&name, table)
                });
            }
        }
        let _ = writeln!(
            self.out,
            "/// One table per supervisor.\nconst TABLES: [SupervisorTable<'static>; {}] = [{}];\n{crc_doc}\n#[allow(dead_code)]\npub const IMAGE_CRC: u32 = {:#010x};\n/// The program's data: the configuration and the tables above, as constants\n/// the compiler can see through (`executor::compiled`).\n#[allow(dead_code)]\npub struct Tables;\nimpl ProgramData for Tables {{\n    const CONFIG: Config<'static> = CONFIG;\n    const IMAGE_CRC: u32 = IMAGE_CRC;\n    const TABLES: &'static [SupervisorTable<'static>] = &TABLES;\n}}\n/// The program: run it with `executor::Controller::new(&PROGRAM, Memory::new())`.\n#[allow(dead_code)]\npub static PROGRAM: Compiled<Tables> = Compiled::new();",
            views.len(),
            views.join(", "),
            image.crc
        );
        stats
    }
}
