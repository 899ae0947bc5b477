//! Variable access: paths to slots or array elements, with the rules of
//! what a POU may read and write.

use super::expr::{error, ETy, Typed};
use super::{lookup, Cx};
use crate::ast::{self, Section, VarRef};
use crate::code::{Dim, ElemRef, Expr, Place};
use crate::error::{Error, ErrorKind, Pos};
use crate::program::{Pou, VarType, Variable};
use crate::types::Type;

/// A resolved variable access.
pub(super) struct Access<'v> {
    pub place: Place,
    pub ty: Type,
    /// The variable named first in the path.
    pub root: &'v Variable,
}

impl<'c> Cx<'c> {
    /// Reads a variable, an array element or an instance's input/output.
    pub(super) fn load(&mut self, r: &VarRef) -> Result<Typed, Error> {
        let access = self.resolve(r, false)?;
        let code = match access.place {
            Place::Slot(slot) => {
                let var = access.root;
                let constant_scalar =
                    var.constant && r.parts.len() == 1 && matches!(var.ty, VarType::Scalar(_));
                if constant_scalar {
                    Expr::Const(self.init[var.slot as usize])
                } else {
                    Expr::Load(slot)
                }
            }
            Place::Elem(elem) => Expr::LoadElem(elem),
        };
        Ok(Typed {
            code,
            ty: ETy::from(access.ty),
        })
    }

    /// The place a variable path names, with the access rules of a read or
    /// (`write`) a write from this POU's body.
    pub(super) fn resolve(&mut self, r: &VarRef, write: bool) -> Result<Access<'c>, Error> {
        let first = &r.parts[0];
        let key = first.name.key();
        let Some(root) = lookup(self.vars, self.var_index, &key) else {
            let message = if self.index.contains_key(&key) {
                format!("`{}` is a POU, not a variable", first.name.text)
            } else {
                format!("undeclared variable `{}`", first.name.text)
            };
            return Err(error(ErrorKind::Name, first.name.pos, message));
        };
        if self.initialiser && !(root.constant && r.parts.len() == 1 && first.index.is_none()) {
            return Err(error(
                ErrorKind::Type,
                first.name.pos,
                format!(
                    "an initial value may use literals and earlier scalar constants only, not `{}`",
                    first.name.text
                ),
            ));
        }
        if write {
            self.check_writable(root, first.name.pos)?;
        }
        let mut slot = root.slot;
        let mut var = root;
        let mut dynamic: Option<Box<ElemRef>> = None;
        for (k, part) in r.parts.iter().enumerate() {
            if k > 0 {
                let Some(fb) = var.instance_of.filter(|_| dynamic.is_none()) else {
                    return Err(error(
                        ErrorKind::Name,
                        part.name.pos,
                        format!("`{}` has no members", var.name),
                    ));
                };
                let fb = self.pou(fb as usize);
                let Some(member) = fb.var(&part.name.text) else {
                    return Err(error(
                        ErrorKind::Name,
                        part.name.pos,
                        format!(
                            "function block `{}` has no variable `{}`",
                            fb.name, part.name.text
                        ),
                    ));
                };
                check_visible(var, member, fb, write, part.name.pos)?;
                slot += member.slot;
                var = member;
            }
            if let Some(indices) = &part.index {
                dynamic = Some(self.index_into(var, slot, indices, part.name.pos)?);
            }
        }
        let ty = match (
            &var.ty,
            &dynamic,
            r.parts.last().and_then(|p| p.index.as_ref()),
        ) {
            (VarType::Scalar(ty), _, None) => *ty,
            (VarType::Array { element, .. }, Some(_), Some(_)) => *element,
            (VarType::Array { .. }, _, _) => {
                return Err(error(
                    ErrorKind::Type,
                    r.pos(),
                    format!("`{}` is an array; index it", var.name),
                ))
            }
            (VarType::Instance(fb), _, None) => {
                return Err(error(
                    ErrorKind::Type,
                    r.pos(),
                    format!("`{}` is an instance of {fb}, not a value", var.name),
                ))
            }
            _ => {
                return Err(error(
                    ErrorKind::Type,
                    r.pos(),
                    format!("`{}` is not an array", var.name),
                ))
            }
        };
        let place = match dynamic {
            Some(elem) if elem.dims.iter().all(|d| matches!(d.index, Expr::Const(_))) => {
                Place::Slot(elem.base + static_offset(&elem))
            }
            Some(elem) => Place::Elem(elem),
            None => Place::Slot(slot),
        };
        Ok(Access { place, ty, root })
    }

    fn check_writable(&self, var: &Variable, pos: Pos) -> Result<(), Error> {
        let reason = if var.constant {
            "is a constant"
        } else if var.section == Section::Input {
            "is an input (VAR_INPUT); a POU does not assign its inputs"
        } else if var.is_located_input() {
            "is located at an input address"
        } else if self.for_vars.contains(&var.slot) {
            "is the control variable of an enclosing FOR loop"
        } else {
            return Ok(());
        };
        Err(error(
            ErrorKind::Access,
            pos,
            format!("`{}` {reason}", var.name),
        ))
    }

    /// An array element: bounds checked now for constant indices.
    fn index_into(
        &mut self,
        var: &Variable,
        base: u32,
        indices: &[ast::Expr],
        pos: Pos,
    ) -> Result<Box<ElemRef>, Error> {
        let VarType::Array { dims, .. } = &var.ty else {
            return Err(error(
                ErrorKind::Type,
                pos,
                format!("`{}` is not an array", var.name),
            ));
        };
        if dims.len() != indices.len() {
            return Err(error(
                ErrorKind::Type,
                pos,
                format!(
                    "`{}` has {} dimension(s), indexed with {}",
                    var.name,
                    dims.len(),
                    indices.len()
                ),
            ));
        }
        let mut stride: u32 = 1;
        let mut out = Vec::with_capacity(dims.len());
        for (&(lo, hi), e) in dims.iter().zip(indices).rev() {
            let outer = self.expected.take();
            let typed = self.expr(e);
            self.expected = outer;
            let typed = typed?;
            let (index, unsigned) = match typed.ty {
                ETy::Literal(v) => {
                    if v < i128::from(lo) || v > i128::from(hi) {
                        return Err(error(
                            ErrorKind::Range,
                            e.pos(),
                            format!("index {v} outside {lo}..{hi} of `{}`", var.name),
                        ));
                    }
                    (Expr::Const(v as i64), false)
                }
                ETy::Int(t) if !t.is_bit_string() => {
                    if let Expr::Const(cell) = typed.code {
                        let v = t.value_of(cell);
                        if v < i128::from(lo) || v > i128::from(hi) {
                            return Err(error(
                                ErrorKind::Range,
                                e.pos(),
                                format!("index {v} outside {lo}..{hi} of `{}`", var.name),
                            ));
                        }
                        (Expr::Const(v as i64), false)
                    } else {
                        (typed.code, !t.is_signed())
                    }
                }
                ty => {
                    return Err(error(
                        ErrorKind::Type,
                        e.pos(),
                        format!("an array index must be an integer, found {ty}"),
                    ))
                }
            };
            out.push(Dim {
                lo,
                hi,
                stride,
                index,
                unsigned,
            });
            stride *= (hi - lo + 1) as u32;
        }
        out.reverse();
        Ok(Box::new(ElemRef {
            base,
            dims: out.into_boxed_slice(),
            line: pos.line,
        }))
    }
}

/// The offset of an element whose indices are all constant.
fn static_offset(elem: &ElemRef) -> u32 {
    elem.dims
        .iter()
        .map(|d| {
            let Expr::Const(i) = d.index else {
                unreachable!("checked constant")
            };
            (i - d.lo) as u32 * d.stride
        })
        .sum()
}

/// What an instance shows outside: inputs (read) and outputs (read); both
/// are written only by a call.
fn check_visible(
    instance: &Variable,
    member: &Variable,
    fb: &Pou,
    write: bool,
    pos: Pos,
) -> Result<(), Error> {
    let shown = matches!(member.section, Section::Input | Section::Output);
    if !shown {
        return Err(error(
            ErrorKind::Access,
            pos,
            format!(
                "`{}.{}` is internal to {}; only inputs and outputs are visible outside",
                instance.name, member.name, fb.name
            ),
        ));
    }
    if write {
        let how = if member.section == Section::Input {
            format!(
                "is set by a call `{}({} := ...)`",
                instance.name, member.name
            )
        } else {
            format!("is an output, written only by {}", fb.name)
        };
        return Err(error(
            ErrorKind::Access,
            pos,
            format!("`{}.{}` {how}", instance.name, member.name),
        ));
    }
    Ok(())
}
