//! Frame layout: declarations to slots, types and initial cells, with
//! function block instances embedded in their owner's frame.

use rustc_hash::FxHashMap;

use super::{check_not_reserved, Cx, UNSUPPORTED_TYPES};
use crate::ast::{self, ArrayInit, Init, PouKind, Section, TypeRef};
use crate::error::{Error, ErrorKind, Pos};
use crate::program::{Pou, VarType, Variable};
use crate::types::Type;

/// Most cells one array may have (guards against typos like `0..1000000000`).
const MAX_ARRAY_CELLS: i128 = 1 << 24;

pub(super) struct Layouts<'a> {
    pub asts: &'a [ast::Pou],
    pub index: &'a FxHashMap<String, usize>,
    pub pous: Vec<Option<Pou>>,
    /// POUs whose layout is under way (an instance cycle if met again).
    pub visiting: Vec<bool>,
}

/// A frame being laid out.
pub(super) struct Frame {
    pub vars: Vec<Variable>,
    pub index: FxHashMap<String, usize>,
    pub init: Vec<i64>,
    pub temps: Vec<(u32, i64)>,
    pub inputs: Vec<usize>,
}

fn error(kind: ErrorKind, pos: Pos, message: impl Into<String>) -> Error {
    Error::at(kind, pos, message)
}

impl Layouts<'_> {
    /// Lays out POU `id` (after the function blocks it instantiates).
    pub fn layout(&mut self, id: usize, used_at: Option<Pos>) -> Result<(), Error> {
        let asts = self.asts;
        let ast = &asts[id];
        if self.pous[id].is_some() {
            return Ok(());
        }
        if self.visiting[id] {
            return Err(error(
                ErrorKind::Name,
                used_at.unwrap_or(ast.name.pos),
                format!(
                    "function block `{}` contains an instance of itself",
                    ast.name.text
                ),
            ));
        }
        self.visiting[id] = true;
        let mut frame = Frame {
            vars: Vec::new(),
            index: FxHashMap::default(),
            init: Vec::new(),
            temps: Vec::new(),
            inputs: Vec::new(),
        };
        let mut result = None;
        if let Some(ty) = &ast.result {
            let ty = match ty {
                TypeRef::Named(name) => self.elementary(name)?,
                TypeRef::Array { pos, .. } => {
                    return Err(error(
                        ErrorKind::Unsupported,
                        *pos,
                        "a function returning an array is not supported",
                    ))
                }
            };
            result = Some((0, ty));
            frame.index.insert(ast.name.key(), 0);
            frame.vars.push(Variable {
                name: ast.name.text.clone(),
                section: Section::Output,
                constant: false,
                address: None,
                ty: VarType::Scalar(ty),
                slot: 0,
                instance_of: None,
            });
            frame.init.push(Type::DEFAULT_CELL);
        }
        for block in &ast.blocks {
            for decl in &block.decls {
                self.declare(&mut frame, ast, block, decl)?;
            }
        }
        self.visiting[id] = false;
        self.pous[id] = Some(Pou {
            name: ast.name.text.clone(),
            kind: ast.kind,
            size: frame.init.len(),
            init: frame.init,
            temps: frame.temps,
            vars: frame.vars,
            index: frame.index,
            inputs: frame.inputs,
            result,
            base: 0,
            body: Vec::new(),
        });
        Ok(())
    }

    fn elementary(&self, name: &ast::Ident) -> Result<Type, Error> {
        if let Some(ty) = Type::from_name(&name.text) {
            return Ok(ty);
        }
        let key = name.key();
        if UNSUPPORTED_TYPES.contains(&key.as_str()) {
            return Err(error(
                ErrorKind::Unsupported,
                name.pos,
                format!("type `{}` is not supported", name.text),
            ));
        }
        Err(error(
            ErrorKind::Type,
            name.pos,
            format!("`{}` is not an elementary type", name.text),
        ))
    }

    /// The declared type; lays out a function block type first.
    fn var_type(
        &mut self,
        owner: &ast::Pou,
        ty: &TypeRef,
    ) -> Result<(VarType, Option<u32>), Error> {
        match ty {
            TypeRef::Named(name) => {
                if Type::from_name(&name.text).is_some()
                    || UNSUPPORTED_TYPES.contains(&name.key().as_str())
                {
                    return Ok((VarType::Scalar(self.elementary(name)?), None));
                }
                let Some(&fb) = self.index.get(&name.key()) else {
                    return Err(error(
                        ErrorKind::Name,
                        name.pos,
                        format!("unknown type `{}`", name.text),
                    ));
                };
                if self.asts[fb].kind != PouKind::FunctionBlock {
                    return Err(error(
                        ErrorKind::Type,
                        name.pos,
                        format!("`{}` is not a function block type", name.text),
                    ));
                }
                if owner.kind == PouKind::Function {
                    return Err(error(
                        ErrorKind::Type,
                        name.pos,
                        "a function cannot contain function block instances",
                    ));
                }
                self.layout(fb, Some(name.pos))?;
                let fb_name = self.asts[fb].name.text.clone();
                Ok((VarType::Instance(fb_name), Some(fb as u32)))
            }
            TypeRef::Array { dims, element, pos } => {
                let element = self.elementary(element)?;
                let mut cells: i128 = 1;
                let mut bounds = Vec::with_capacity(dims.len());
                for &(lo, hi) in dims {
                    let (Ok(lo64), Ok(hi64)) = (i64::try_from(lo), i64::try_from(hi)) else {
                        return Err(error(ErrorKind::Range, *pos, "array bound too large"));
                    };
                    if lo > hi {
                        return Err(error(
                            ErrorKind::Range,
                            *pos,
                            format!("array bounds {lo}..{hi}: the lower bound exceeds the upper"),
                        ));
                    }
                    cells = cells.saturating_mul(hi - lo + 1);
                    bounds.push((lo64, hi64));
                }
                if cells > MAX_ARRAY_CELLS {
                    return Err(error(
                        ErrorKind::Range,
                        *pos,
                        format!("array of {cells} elements exceeds the limit of {MAX_ARRAY_CELLS}"),
                    ));
                }
                Ok((
                    VarType::Array {
                        element,
                        dims: bounds,
                    },
                    None,
                ))
            }
        }
    }

    fn declare(
        &mut self,
        frame: &mut Frame,
        owner: &ast::Pou,
        block: &ast::VarBlock,
        decl: &ast::VarDecl,
    ) -> Result<(), Error> {
        let name_pos = decl.names[0].pos;
        if owner.kind == PouKind::Function && block.section == Section::Output {
            return Err(error(
                ErrorKind::Unsupported,
                name_pos,
                "VAR_OUTPUT in a FUNCTION is not supported",
            ));
        }
        let (ty, instance_of) = self.var_type(owner, &decl.ty)?;
        if instance_of.is_some() {
            if block.constant || block.section != Section::Local {
                return Err(error(
                    ErrorKind::Unsupported,
                    name_pos,
                    "function block instances are supported in VAR only (not CONSTANT, inputs, outputs or temps)",
                ));
            }
            if decl.init.is_some() {
                return Err(error(
                    ErrorKind::Unsupported,
                    name_pos,
                    "initialising a function block instance is not supported",
                ));
            }
        }
        if let Some((address, pos)) = &decl.address {
            check_address(owner, block.section, address, &ty, *pos)?;
        }
        let cells = self.initial_cells(frame, &ty, instance_of, decl.init.as_ref())?;
        for name in &decl.names {
            check_not_reserved(name)?;
            let key = name.key();
            if frame.index.contains_key(&key) {
                return Err(error(
                    ErrorKind::Name,
                    name.pos,
                    format!("`{}` is declared twice", name.text),
                ));
            }
            let slot = frame.init.len() as u32;
            if block.section == Section::Temp {
                frame
                    .temps
                    .extend(cells.iter().enumerate().map(|(k, &c)| (slot + k as u32, c)));
            }
            frame.init.extend_from_slice(&cells);
            frame.index.insert(key, frame.vars.len());
            if block.section == Section::Input {
                frame.inputs.push(frame.vars.len());
            }
            frame.vars.push(Variable {
                name: name.text.clone(),
                section: block.section,
                constant: block.constant,
                address: decl.address.as_ref().map(|(a, _)| a.clone()),
                ty: ty.clone(),
                slot,
                instance_of,
            });
        }
        Ok(())
    }

    /// The cells a variable starts with.
    fn initial_cells(
        &self,
        frame: &Frame,
        ty: &VarType,
        instance_of: Option<u32>,
        init: Option<&Init>,
    ) -> Result<Vec<i64>, Error> {
        let mut cx = Cx::for_initialiser(&self.pous, self.index, frame);
        match (ty, init) {
            (VarType::Instance(_), _) => {
                let fb = self.pous[instance_of.expect("instance") as usize]
                    .as_ref()
                    .expect("laid out before its instances");
                Ok(fb.init.clone())
            }
            (VarType::Scalar(_), None) => Ok(vec![Type::DEFAULT_CELL]),
            (VarType::Scalar(ty), Some(Init::Scalar(e))) => Ok(vec![cx.constant(e, *ty)?]),
            (VarType::Array { dims, .. }, None) => {
                let n = dims
                    .iter()
                    .map(|&(lo, hi)| (hi - lo + 1) as usize)
                    .product();
                Ok(vec![Type::DEFAULT_CELL; n])
            }
            (VarType::Array { element, dims }, Some(Init::Array(items, _))) => {
                let n: usize = dims
                    .iter()
                    .map(|&(lo, hi)| (hi - lo + 1) as usize)
                    .product();
                let mut cells = Vec::with_capacity(n);
                for item in items {
                    let (count, value, at) = match item {
                        ArrayInit::Value(e) => (1, Some(e), e.pos()),
                        ArrayInit::Repeat { count, value, pos } => (*count, value.as_ref(), *pos),
                    };
                    let cell = match value {
                        Some(e) => cx.constant(e, *element)?,
                        None => Type::DEFAULT_CELL,
                    };
                    if (cells.len() as u128).saturating_add(count) > n as u128 {
                        return Err(error(
                            ErrorKind::Range,
                            at,
                            format!("more initial values than the array's {n} elements"),
                        ));
                    }
                    cells.extend(std::iter::repeat_n(cell, count as usize));
                }
                cells.resize(n, Type::DEFAULT_CELL);
                Ok(cells)
            }
            (VarType::Scalar(_), Some(Init::Array(_, pos))) => Err(error(
                ErrorKind::Type,
                *pos,
                "a list initialiser `[...]` needs an ARRAY variable",
            )),
            (VarType::Array { .. }, Some(Init::Scalar(e))) => Err(error(
                ErrorKind::Type,
                e.pos(),
                "an ARRAY is initialised with a list `[...]`",
            )),
        }
    }
}

/// `AT %I/Q/M[X|B|W|D|L]n.m`: only in a PROGRAM, on a scalar whose width
/// matches the size prefix (none means a bit).
fn check_address(
    owner: &ast::Pou,
    section: Section,
    address: &str,
    ty: &VarType,
    pos: Pos,
) -> Result<(), Error> {
    if owner.kind != PouKind::Program || section == Section::Temp {
        return Err(error(
            ErrorKind::Syntax,
            pos,
            "located variables (AT) are allowed in a PROGRAM's VAR, VAR_INPUT and VAR_OUTPUT only",
        ));
    }
    let VarType::Scalar(ty) = ty else {
        return Err(error(
            ErrorKind::Unsupported,
            pos,
            "a located array or instance is not supported",
        ));
    };
    let bits = match address.as_bytes().get(2) {
        Some(b'B') => 8,
        Some(b'W') => 16,
        Some(b'D') => 32,
        Some(b'L') => 64,
        _ => 1,
    };
    let fits = match ty {
        Type::Bool => bits == 1,
        Type::Int(t) => t.bits() == bits,
    };
    if !fits {
        return Err(error(
            ErrorKind::Type,
            pos,
            format!("`{address}` is a {bits}-bit location; it cannot hold a {ty}"),
        ));
    }
    Ok(())
}
