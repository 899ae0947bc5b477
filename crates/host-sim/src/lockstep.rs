//! Both backends side by side: one project run as bit-packed tables and as
//! CMSSM logic on the same inputs, every scan compared.
//!
//! This is how scenario tests drive a project: they get the trace of one
//! backend and the guarantee that the other produced exactly the same row.

use crate::sim::{Sim, SimError};
use crate::trace::TraceRow;
use codegen::backend::Backend;
use plc_project::Project;
use std::path::Path;

/// The same project on both backends, driven in lockstep.
pub struct Lockstep {
    table: Sim,
    logic: Sim,
}

impl Lockstep {
    /// Loads the project at `path` once per backend.
    pub fn load(path: &Path) -> Result<Lockstep, SimError> {
        let project = plc_project::load(path)?;
        Lockstep::new(project)
    }

    /// Both backends of `project`.
    pub fn new(project: Project) -> Result<Lockstep, SimError> {
        Ok(Lockstep {
            table: Sim::new(project.clone(), Backend::Table)?,
            logic: Sim::new(project, Backend::Logic)?,
        })
    }

    /// The project.
    pub fn project(&self) -> &Project {
        self.table.project()
    }

    /// The table-backend simulation (the reference for names and states).
    pub fn sim(&self) -> &Sim {
        &self.table
    }

    /// Sets the raw value of input `name` on both.
    pub fn set(&mut self, name: &str, value: bool) -> Result<&mut Self, SimError> {
        self.table.set(name, value)?;
        self.logic.set(name, value)?;
        Ok(self)
    }

    /// One scan on both; the row, or [`SimError::Diverged`].
    pub fn scan(&mut self) -> Result<TraceRow, SimError> {
        let row = self.table.scan().clone();
        let other = self.logic.scan();
        if &row != other {
            return Err(SimError::Diverged {
                table: Box::new(row),
                logic: Box::new(other.clone()),
            });
        }
        Ok(row)
    }

    /// [`Sim::stall`] on both: they hang for `ms` after their last scan.
    pub fn stall(&mut self, ms: u64) {
        self.logic.stall(ms);
        self.table.stall(ms);
    }

    /// `scans` scans; their rows.
    pub fn run(&mut self, scans: usize) -> Result<Vec<TraceRow>, SimError> {
        (0..scans).map(|_| self.scan()).collect()
    }

    /// The current state (name) of supervisor `name`.
    pub fn state(&self, name: &str) -> Result<String, SimError> {
        self.table.state(name)
    }

    /// The current level of output `name`.
    pub fn output(&self, name: &str) -> Result<bool, SimError> {
        self.table.output(name)
    }
}
