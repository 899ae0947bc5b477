//! Symbolic-supervisor projects built from plant and specification
//! automata: their model files and the project text.
//!
//! Included by `guarded.rs` (guards executed = the monolithic table
//! executed) and `st_lockstep.rs` (synthesised guards in exported ST).

#![allow(dead_code)]

use des::formats::{write_file, Component, Kind};
use des::Automaton;
use std::path::Path;

/// Writes `plants` under `dir/plant` and `specs` under `dir/spec`, one
/// file per automaton; the events, in first-seen order, with their
/// controllability.
pub fn write_models(dir: &Path, plants: &[Automaton], specs: &[Automaton]) -> Vec<(String, bool)> {
    let mut events: Vec<(String, bool)> = Vec::new();
    for (kind, sub, automata) in [(Kind::Plant, "plant", plants), (Kind::Spec, "spec", specs)] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
        for a in automata.iter() {
            for (id, e) in a.alphabet().iter() {
                if !events.iter().any(|(n, _)| *n == e.name) {
                    events.push((e.name.clone(), a.alphabet().is_controllable(id)));
                }
            }
            let component = Component {
                kind,
                automaton: a.clone(),
            };
            write_file(
                &dir.join(sub).join(format!("{}.toml", a.name())),
                &[component],
            )
            .unwrap();
        }
    }
    events
}

/// The project text: each uncontrollable event the rising edge of its own
/// input, each controllable one a command without actions; the supervisor
/// synthesised from `plant/*.toml` and `spec/*.toml`, symbolically or as
/// one automaton.
pub fn project_text(
    events: &[(String, bool)],
    symbolic: bool,
    policy: &str,
    commands: u16,
) -> String {
    let mut text = format!(
        "[plc]\nname = \"x\"\nscan_period_ms = 10\nmax_commands_per_scan = {commands}\nunexpected = \"{policy}\"\nreset = \"reset\"\n[inputs]\nreset = {{}}\n"
    );
    for (e, controllable) in events {
        if !controllable {
            text.push_str(&format!("in_{e} = {{}}\n"));
        }
    }
    text.push_str("[events]\n");
    for (e, controllable) in events {
        if *controllable {
            text.push_str(&format!("{e} = {{ controllable = true }}\n"));
        } else {
            text.push_str(&format!("{e} = {{ rising = \"in_{e}\" }}\n"));
        }
    }
    text.push_str(&format!(
        "[[supervisor]]\nname = \"sup\"\nsynthesize = {{ plants = [\"plant/*.toml\"], specs = [\"spec/*.toml\"]{} }}\n",
        if symbolic { ", symbolic = true" } else { "" }
    ));
    text
}
