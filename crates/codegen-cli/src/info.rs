//! `codegen info`: sizes and properties of automata.

use super::error::CliError;
use super::output::{outln, Out};
use super::{Outcome, Size};
use des::formats;
use des::ops;
use std::path::PathBuf;

#[derive(Debug, serde::Serialize)]
struct Info {
    file: String,
    name: String,
    kind: String,
    #[serde(flatten)]
    size: Size,
    marked: usize,
    deterministic: bool,
    has_initial_state: bool,
    reachable: usize,
    coreachable: usize,
    trim: bool,
    nonblocking: bool,
    /// Events the controller cannot see (partial observation).
    unobservable: Vec<String>,
}

pub fn run(files: &[PathBuf], json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let mut infos = Vec::new();
    for file in files {
        for c in formats::read_file(file)? {
            let a = &c.automaton;
            let reach = ops::reachable(a);
            let co = ops::coreachable(a);
            let reachable = reach.count_ones(..);
            infos.push(Info {
                file: file.display().to_string(),
                name: a.name().to_owned(),
                kind: c.kind.to_string(),
                size: Size::of(a),
                marked: a.marked().count_ones(..),
                // Nondeterministic files are refused when read.
                deterministic: true,
                has_initial_state: a.initial().is_some(),
                reachable,
                coreachable: co.count_ones(..),
                trim: reachable == a.num_states() && co.count_ones(..) == a.num_states(),
                nonblocking: reach.is_subset(&co),
                unobservable: a
                    .alphabet()
                    .unobservable()
                    .map(|(_, e)| e.name.clone())
                    .collect(),
            });
        }
    }
    if json {
        out.json(&infos);
        return Ok(Outcome::Holds);
    }
    for i in &infos {
        let yes = |b: bool| if b { "yes" } else { "no" };
        outln!(out, "{} ({}, {}):", i.name, i.kind, i.file);
        outln!(out, "  {}", i.size);
        outln!(out, "  marked states: {}", i.marked);
        outln!(out, "  deterministic: yes");
        outln!(
            out,
            "  reachable:     {} of {}{}",
            i.reachable,
            i.size.states,
            if i.has_initial_state {
                ""
            } else {
                " (no initial state)"
            }
        );
        outln!(
            out,
            "  coreachable:   {} of {}",
            i.coreachable,
            i.size.states
        );
        outln!(out, "  trim:          {}", yes(i.trim));
        outln!(out, "  nonblocking:   {}", yes(i.nonblocking));
        if !i.unobservable.is_empty() {
            outln!(out, "  unobservable:  {}", i.unobservable.join(", "));
        }
    }
    Ok(Outcome::Holds)
}
