//! The compile step: lays out every POU's frame, evaluates initial values,
//! checks types and access rules, and resolves names in bodies to slots.

mod access;
mod call;
mod configuration;
mod expr;
mod layout;
mod stmt;

use rustc_hash::FxHashMap;

use crate::ast::{self, PouKind};
use crate::error::{Error, ErrorKind, Pos};
use crate::program::{Pou, Program, Variable};
use crate::types::Type;

pub(crate) use expr::Cx;

/// Standard functions other than the `<A>_TO_<B>` conversions.
pub(crate) const BUILTINS: [&str; 9] = [
    "ABS", "MIN", "MAX", "LIMIT", "SEL", "SHL", "SHR", "ROL", "ROR",
];

/// IEC types outside the subset: named in errors as unsupported, not unknown.
const UNSUPPORTED_TYPES: [&str; 14] = [
    "REAL",
    "LREAL",
    "TIME",
    "LTIME",
    "DATE",
    "LDATE",
    "TIME_OF_DAY",
    "TOD",
    "DATE_AND_TIME",
    "DT",
    "STRING",
    "WSTRING",
    "CHAR",
    "WCHAR",
];

/// `A_TO_B` for two elementary types.
pub(crate) fn conversion(name: &str) -> Option<(Type, Type)> {
    let upper = name.to_ascii_uppercase();
    let (from, to) = upper.split_once("_TO_")?;
    Some((Type::from_name(from)?, Type::from_name(to)?))
}

/// Names a POU or variable may not take.
fn check_not_reserved(name: &ast::Ident) -> Result<(), Error> {
    let key = name.key();
    let reserved = Type::from_name(&key).is_some()
        || UNSUPPORTED_TYPES.contains(&key.as_str())
        || BUILTINS.contains(&key.as_str())
        || conversion(&key).is_some();
    if reserved {
        return Err(Error::at(
            ErrorKind::Name,
            name.pos,
            format!(
                "`{}` is a reserved name (a standard type or function)",
                name.text
            ),
        ));
    }
    Ok(())
}

/// Compiles all POUs of a file, then checks its configurations.
pub(crate) fn compile(file: &ast::SourceAst) -> Result<Program, Error> {
    let asts = &file.pous[..];
    let mut index = FxHashMap::default();
    for (id, pou) in asts.iter().enumerate() {
        check_not_reserved(&pou.name)?;
        if index.insert(pou.name.key(), id).is_some() {
            return Err(Error::at(
                ErrorKind::Name,
                pou.name.pos,
                format!("POU `{}` is declared twice", pou.name.text),
            ));
        }
    }
    let mut compiler = layout::Layouts {
        asts,
        index: &index,
        pous: vec![None; asts.len()],
        visiting: vec![false; asts.len()],
    };
    for id in 0..asts.len() {
        compiler.layout(id, None)?;
    }
    let mut pous = compiler.pous;

    // Functions run in frames of their own ahead of the top instance's.
    let mut functions_size = 0;
    for pou in pous.iter_mut().flatten() {
        if pou.kind == PouKind::Function {
            pou.base = functions_size;
            functions_size += pou.size;
        }
    }

    let mut bodies = Vec::with_capacity(pous.len());
    let mut calls = Vec::with_capacity(pous.len());
    for (id, ast) in asts.iter().enumerate() {
        let mut cx = Cx::for_body(&pous, &index, id);
        bodies.push(cx.block(&ast.body)?);
        calls.push(cx.calls);
    }
    check_no_recursion(asts, &calls)?;
    let configurations = configuration::check(&file.configurations, asts, &index)?;
    let pous = pous
        .into_iter()
        .zip(bodies)
        .map(|(pou, body)| Pou {
            body,
            ..pou.expect("every POU laid out")
        })
        .collect();
    Ok(Program {
        pous,
        index,
        functions_size,
        configurations,
    })
}

/// Functions share one frame each, so no function may reach itself.
fn check_no_recursion(asts: &[ast::Pou], calls: &[Vec<(usize, Pos)>]) -> Result<(), Error> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    fn visit(
        f: usize,
        asts: &[ast::Pou],
        calls: &[Vec<(usize, Pos)>],
        marks: &mut [Mark],
    ) -> Result<(), Error> {
        marks[f] = Mark::Open;
        for &(g, pos) in &calls[f] {
            match marks[g] {
                Mark::Open => {
                    return Err(Error::at(
                        ErrorKind::Name,
                        pos,
                        format!(
                            "recursive call of function `{}` (IEC functions may not recurse)",
                            asts[g].name.text
                        ),
                    ))
                }
                Mark::New => visit(g, asts, calls, marks)?,
                Mark::Done => {}
            }
        }
        marks[f] = Mark::Done;
        Ok(())
    }
    let mut marks = vec![Mark::New; asts.len()];
    for f in 0..asts.len() {
        if marks[f] == Mark::New {
            visit(f, asts, calls, &mut marks)?;
        }
    }
    Ok(())
}

/// The variable named `key` (upper case) in `vars`.
pub(crate) fn lookup<'v>(
    vars: &'v [Variable],
    index: &FxHashMap<String, usize>,
    key: &str,
) -> Option<&'v Variable> {
    index.get(key).map(|&i| &vars[i])
}
