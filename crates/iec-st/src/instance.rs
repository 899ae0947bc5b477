//! The host API: a checked source file, its instances, and access to their
//! variables by path or by pre-resolved slot.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use crate::ast::{PouKind, Section};
use crate::configuration::Configuration;
use crate::error::{Error, RuntimeError};
use crate::program::{Pou, Program, VarType, Variable};
use crate::run::Machine;
use crate::types::Type;
use crate::value::Value;

/// Loop iterations one [`Instance::call`] may run before it fails.
pub const DEFAULT_ITERATION_LIMIT: u64 = 10_000_000;

/// Tells slots of different files apart.
static NEXT_FILE_ID: AtomicU64 = AtomicU64::new(1);

/// A parsed and checked source file (see [`crate::parse`]).
#[derive(Clone, Debug)]
pub struct SourceFile {
    program: Arc<Program>,
    id: u64,
}

impl SourceFile {
    pub(crate) fn new(program: Program) -> SourceFile {
        SourceFile {
            program: Arc::new(program),
            id: NEXT_FILE_ID.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// The POUs in declaration order: name and kind.
    pub fn pous(&self) -> impl Iterator<Item = (&str, PouKind)> + '_ {
        self.program.pous.iter().map(|p| (p.name.as_str(), p.kind))
    }

    /// The file's `CONFIGURATION`s in declaration order, checked against
    /// its POUs.
    pub fn configurations(&self) -> &[Configuration] {
        &self.program.configurations
    }

    /// The variables POU `pou` declares, in declaration order (a function's
    /// result variable first).
    pub fn variables(&self, pou: &str) -> Result<&[Variable], Error> {
        Ok(&self.program.pous[self.pou_id(pou)?].vars)
    }

    fn pou_id(&self, pou: &str) -> Result<usize, Error> {
        self.program
            .index
            .get(&pou.to_ascii_uppercase())
            .copied()
            .ok_or_else(|| Error::host(pou, "no such POU"))
    }

    /// A fresh instance of a PROGRAM or FUNCTION_BLOCK, every variable at
    /// its initial value.
    pub fn instantiate(&self, pou: &str) -> Result<Instance, Error> {
        let id = self.pou_id(pou)?;
        let program = &self.program;
        if program.pous[id].kind == PouKind::Function {
            return Err(Error::host(
                pou,
                "a FUNCTION has no instance; instantiate a PROGRAM or FUNCTION_BLOCK",
            ));
        }
        let mut instance = Instance {
            program: Arc::clone(program),
            file: self.id,
            pou: id,
            mem: Vec::new(),
            stack: Vec::new(),
            iteration_limit: DEFAULT_ITERATION_LIMIT,
        };
        instance.reset();
        Ok(instance)
    }
}

/// A running PROGRAM or FUNCTION_BLOCK instance and its memory.
#[derive(Clone, Debug)]
pub struct Instance {
    program: Arc<Program>,
    file: u64,
    pou: usize,
    /// The functions' frames, then this instance's frame.
    mem: Vec<i64>,
    stack: Vec<i64>,
    iteration_limit: u64,
}

/// A variable or array element resolved once by [`Instance::slot`], for
/// fast access in every scan. Valid for every instance of the same POU of
/// the same [`SourceFile`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Slot {
    file: u64,
    pou: u32,
    cell: u32,
    ty: Type,
    /// A top-level input or located input: [`Instance::set_slot`] may write it.
    input: bool,
    constant: bool,
}

impl Slot {
    /// The type of the variable.
    pub fn ty(&self) -> Type {
        self.ty
    }

    /// May [`Instance::set_slot`] write it (a top-level VAR_INPUT or `AT %I`)?
    pub fn is_input(&self) -> bool {
        self.input
    }
}

impl Instance {
    /// The POU this is an instance of.
    pub fn pou_name(&self) -> &str {
        &self.top().name
    }

    /// The variables of the instance's POU.
    pub fn variables(&self) -> &[Variable] {
        &self.top().vars
    }

    fn top(&self) -> &Pou {
        &self.program.pous[self.pou]
    }

    /// Sets every variable back to its initial value.
    pub fn reset(&mut self) {
        let program = &self.program;
        let top = &program.pous[self.pou];
        self.mem.clear();
        self.mem.resize(program.functions_size, 0);
        self.mem.extend_from_slice(&top.init);
    }

    /// Changes how many loop iterations one call may run (default
    /// [`DEFAULT_ITERATION_LIMIT`]).
    pub fn set_iteration_limit(&mut self, limit: u64) {
        self.iteration_limit = limit;
    }

    /// Runs the body once: one PLC task cycle. On a fault the writes done
    /// before it stay.
    pub fn call(&mut self) -> Result<(), RuntimeError> {
        let program = &*self.program;
        let mut machine = Machine {
            pous: &program.pous,
            mem: &mut self.mem,
            stack: &mut self.stack,
            iterations: 0,
            iteration_limit: self.iteration_limit,
        };
        machine.stack.clear();
        machine
            .run_pou(self.pou, program.functions_size)
            .map_err(|e| *e)
    }

    /// Resolves a path: `x`, `M[3]`, `D[2, -1]`, `inst.q`, `inst.T[1,2]`
    /// (any variable, case-insensitive).
    pub fn slot(&self, path: &str) -> Result<Slot, Error> {
        let program = &*self.program;
        let segments: Vec<&str> = path.split('.').collect();
        let mut pou = self.top();
        let mut cell = program.functions_size;
        for (k, segment) in segments.iter().enumerate() {
            let last = k + 1 == segments.len();
            let (name, indices) = split_segment(segment).ok_or_else(|| {
                Error::host(path, format!("`{segment}` is not `name` or `name[i, ...]`"))
            })?;
            let var = pou.var(name).ok_or_else(|| {
                Error::host(path, format!("{} has no variable `{name}`", pou.name))
            })?;
            cell += var.slot as usize;
            let scalar = |ty: Type| Slot {
                file: 0,
                pou: 0,
                cell: 0,
                ty,
                input: k == 0 && (var.section == Section::Input || var.is_located_input()),
                constant: var.constant,
            };
            let found = match (&var.ty, indices, last) {
                (VarType::Instance(_), None, false) => {
                    pou = &program.pous[var.instance_of.expect("instance") as usize];
                    continue;
                }
                (VarType::Scalar(ty), None, true) => scalar(*ty),
                (VarType::Array { element, dims }, Some(indices), true) => {
                    cell += element_offset(dims, &indices)
                        .map_err(|message| Error::host(path, message))?;
                    scalar(*element)
                }
                (VarType::Array { .. }, None, true) => {
                    return Err(Error::host(path, format!("`{name}` is an array; index it")))
                }
                (VarType::Instance(fb), None, true) => {
                    return Err(Error::host(
                        path,
                        format!("`{name}` is an instance of {fb}; name one of its variables"),
                    ))
                }
                _ => {
                    return Err(Error::host(
                        path,
                        format!("`{segment}` does not match the declaration of `{name}`"),
                    ))
                }
            };
            return Ok(Slot {
                file: self.file,
                pou: self.pou as u32,
                cell: cell as u32,
                ..found
            });
        }
        Err(Error::host(path, "empty path"))
    }

    /// The top-level variable located at `address` (`%IX0.3`, any case).
    pub fn slot_at(&self, address: &str) -> Result<Slot, Error> {
        let var = self
            .top()
            .vars
            .iter()
            .find(|v| {
                v.address
                    .as_deref()
                    .is_some_and(|a| a.eq_ignore_ascii_case(address))
            })
            .ok_or_else(|| {
                Error::host(
                    address,
                    format!("no variable of {} is located there", self.pou_name()),
                )
            })?;
        self.slot(&var.name)
    }

    fn check(&self, slot: Slot) -> Result<usize, Error> {
        if slot.file != self.file || slot.pou as usize != self.pou {
            return Err(Error::host(
                format!("slot {}", slot.cell),
                format!("resolved for another POU than {}", self.pou_name()),
            ));
        }
        Ok(slot.cell as usize)
    }

    /// The value at a slot.
    pub fn get_slot(&self, slot: Slot) -> Result<Value, Error> {
        let cell = self.check(slot)?;
        Ok(Value::from_cell(slot.ty, self.mem[cell]))
    }

    /// Writes a top-level input (VAR_INPUT or `AT %I`), as the PLC's input
    /// image would.
    pub fn set_slot(&mut self, slot: Slot, value: Value) -> Result<(), Error> {
        if !slot.input {
            return Err(Error::host(
                format!("slot {}", slot.cell),
                "not an input of the instance (use force_slot to override it)",
            ));
        }
        self.force_slot(slot, value)
    }

    /// Writes any variable that is not a constant (for tests).
    pub fn force_slot(&mut self, slot: Slot, value: Value) -> Result<(), Error> {
        let cell = self.check(slot)?;
        if slot.constant {
            return Err(Error::host(
                format!("slot {}", slot.cell),
                "a constant cannot be written",
            ));
        }
        self.mem[cell] = cell_of(slot.ty, value)
            .map_err(|message| Error::host(format!("slot {}", slot.cell), message))?;
        Ok(())
    }

    /// The value of a variable, element or instance member (see [`Instance::slot`]).
    pub fn get(&self, path: &str) -> Result<Value, Error> {
        self.get_slot(self.slot(path)?)
    }

    /// Writes a top-level input (VAR_INPUT or `AT %I`).
    pub fn set(&mut self, path: &str, value: Value) -> Result<(), Error> {
        let slot = self.slot(path)?;
        self.set_slot(slot, value).map_err(|e| rename(e, path))
    }

    /// Writes any variable that is not a constant (for tests).
    pub fn force(&mut self, path: &str, value: Value) -> Result<(), Error> {
        let slot = self.slot(path)?;
        self.force_slot(slot, value).map_err(|e| rename(e, path))
    }
}

/// Reports a slot error under the path the host used.
fn rename(error: Error, path: &str) -> Error {
    match error {
        Error::Host { message, .. } => Error::host(path, message),
        other => other,
    }
}

/// The stored cell of `value` in a variable of type `ty`: the same type or
/// an implicit widening.
fn cell_of(ty: Type, value: Value) -> Result<i64, String> {
    match (ty, value) {
        (Type::Bool, Value::Bool(b)) => Ok(i64::from(b)),
        (Type::Int(to), Value::Int { ty: from, value }) if from.widens_to(to) => {
            if from.contains(value) {
                Ok(to.cell_of(value))
            } else {
                Err(format!("{value} is outside {from}'s range"))
            }
        }
        _ => Err(format!("a {} value cannot be stored in a {ty}", value.ty())),
    }
}

/// `name` or `name[i, j]`.
fn split_segment(segment: &str) -> Option<(&str, Option<Vec<i128>>)> {
    let segment = segment.trim();
    let Some(open) = segment.find('[') else {
        return (!segment.is_empty()).then_some((segment, None));
    };
    let inner = segment[open + 1..].strip_suffix(']')?;
    let indices = inner
        .split(',')
        .map(|s| s.trim().parse::<i128>().ok())
        .collect::<Option<Vec<_>>>()?;
    Some((segment[..open].trim(), Some(indices)))
}

/// Row-major offset of an element (last index fastest).
fn element_offset(dims: &[(i64, i64)], indices: &[i128]) -> Result<usize, String> {
    if dims.len() != indices.len() {
        return Err(format!(
            "{} index(es) for an array of {} dimension(s)",
            indices.len(),
            dims.len()
        ));
    }
    let mut offset = 0usize;
    for (&(lo, hi), &i) in dims.iter().zip(indices) {
        if i < i128::from(lo) || i > i128::from(hi) {
            return Err(format!("index {i} outside {lo}..{hi}"));
        }
        offset = offset * (hi - lo + 1) as usize + (i - i128::from(lo)) as usize;
    }
    Ok(offset)
}
