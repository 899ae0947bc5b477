//! Scenario-test helpers: a seed project from `models/`, run on both
//! backends in lockstep (every row compared), with panicking accessors so
//! a scenario reads as a script.

#![allow(dead_code)]

pub mod plant;
pub mod waveform;

use host_sim::{Lockstep, TraceRow};
use std::path::PathBuf;

/// The path of `models/<file>` in the repository.
pub fn model(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../models")
        .join(file)
}

/// A project running on both backends.
pub struct Run {
    ls: Lockstep,
}

impl Run {
    /// Loads `models/<file>`.
    pub fn load(file: &str) -> Run {
        let path = model(file);
        let ls = Lockstep::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        Run { ls }
    }

    /// Sets raw input `name`.
    pub fn set(&mut self, name: &str, value: bool) -> &mut Run {
        self.ls.set(name, value).unwrap();
        self
    }

    /// One scan; its row (the same on both backends).
    pub fn scan(&mut self) -> TraceRow {
        self.ls.scan().unwrap_or_else(|e| panic!("{e}"))
    }

    /// `n` scans; their rows.
    pub fn scans(&mut self, n: usize) -> Vec<TraceRow> {
        (0..n).map(|_| self.scan()).collect()
    }

    /// Sets `name` and scans once.
    pub fn step(&mut self, name: &str, value: bool) -> TraceRow {
        self.set(name, value);
        self.scan()
    }

    /// Scans until a row executes `event` (at most `limit` scans); that row.
    pub fn until_event(&mut self, event: &str, limit: usize) -> TraceRow {
        for _ in 0..limit {
            let row = self.scan();
            if row.events.iter().any(|e| e == event) {
                return row;
            }
        }
        panic!("`{event}` not executed within {limit} scans");
    }

    /// Current state of supervisor `sup`.
    pub fn state(&self, sup: &str) -> String {
        self.ls.state(sup).unwrap()
    }

    /// Current level of output `name`.
    pub fn out(&self, name: &str) -> bool {
        self.ls.output(name).unwrap()
    }

    /// The outputs that are 1 in `row`, by name.
    pub fn on(&self, row: &TraceRow) -> Vec<String> {
        self.ls
            .project()
            .outputs
            .iter()
            .zip(&row.outputs)
            .filter(|(_, &v)| v)
            .map(|(o, _)| o.name.clone())
            .collect()
    }

    /// Every scan so far.
    pub fn trace(&self) -> &[TraceRow] {
        self.ls.sim().trace()
    }
}

/// `row.events` as `&str`s.
pub fn events(row: &TraceRow) -> Vec<&str> {
    row.events.iter().map(String::as_str).collect()
}
