//! Checks a configuration against the file's POUs: every program instance
//! names a PROGRAM and a task of its own resource, names are unique where
//! the standard scopes them, and intervals are positive.

use rustc_hash::{FxHashMap, FxHashSet};

use super::check_not_reserved;
use crate::ast::{self, PouKind};
use crate::configuration::{Configuration, ProgramInstance, Resource, Task};
use crate::error::{Error, ErrorKind};

/// The checked configurations of a file whose POUs are `pous`, indexed by
/// upper-case name in `index`.
pub(crate) fn check(
    decls: &[ast::ConfigurationDecl],
    pous: &[ast::Pou],
    index: &FxHashMap<String, usize>,
) -> Result<Vec<Configuration>, Error> {
    let mut names = Unique::default();
    decls
        .iter()
        .map(|decl| {
            names.insert(&decl.name, "configuration")?;
            let mut resource_names = Unique::default();
            let resources = decl
                .resources
                .iter()
                .map(|resource| {
                    if let Some(name) = &resource.name {
                        resource_names.insert(name, "resource")?;
                    }
                    check_resource(resource, pous, index)
                })
                .collect::<Result<_, _>>()?;
            Ok(Configuration {
                name: decl.name.text.clone(),
                resources,
            })
        })
        .collect()
}

fn check_resource(
    decl: &ast::ResourceDecl,
    pous: &[ast::Pou],
    index: &FxHashMap<String, usize>,
) -> Result<Resource, Error> {
    let mut task_names = Unique::default();
    let mut tasks = Vec::with_capacity(decl.tasks.len());
    for task in &decl.tasks {
        task_names.insert(&task.name, "task")?;
        let interval_ms = match task.interval {
            None => None,
            Some((ms, pos)) => Some(u64::try_from(ms).ok().filter(|&ms| ms > 0).ok_or_else(
                || {
                    Error::at(
                        ErrorKind::Range,
                        pos,
                        format!(
                            "task `{}` has interval {ms} ms; a cyclic task's INTERVAL must be positive",
                            task.name.text
                        ),
                    )
                },
            )?),
        };
        tasks.push(Task {
            name: task.name.text.clone(),
            interval_ms,
            priority: task.priority,
        });
    }
    let mut instance_names = Unique::default();
    let mut programs = Vec::with_capacity(decl.programs.len());
    for program in &decl.programs {
        instance_names.insert(&program.name, "program instance")?;
        let Some(&id) = index.get(&program.pou.key()) else {
            return Err(Error::at(
                ErrorKind::Name,
                program.pou.pos,
                format!("no PROGRAM `{}` is declared", program.pou.text),
            ));
        };
        let pou = &pous[id];
        if pou.kind != PouKind::Program {
            let kind = match pou.kind {
                PouKind::FunctionBlock => "FUNCTION_BLOCK",
                _ => "FUNCTION",
            };
            return Err(Error::at(
                ErrorKind::Name,
                program.pou.pos,
                format!(
                    "`{}` is a {kind}; a resource runs instances of a PROGRAM",
                    program.pou.text
                ),
            ));
        }
        let task = match &program.task {
            None => None,
            Some(task) => {
                let Some(declared) = decl.tasks.iter().find(|t| t.name.key() == task.key()) else {
                    return Err(Error::at(
                        ErrorKind::Name,
                        task.pos,
                        format!("no task `{}` is declared in this resource", task.text),
                    ));
                };
                Some(declared.name.text.clone())
            }
        };
        programs.push(ProgramInstance {
            name: program.name.text.clone(),
            task,
            pou: pou.name.text.clone(),
        });
    }
    Ok(Resource {
        name: decl.name.as_ref().map(|n| n.text.clone()),
        on: decl.on.as_ref().map(|n| n.text.clone()),
        tasks,
        programs,
    })
}

/// Names declared in one scope, compared without case.
#[derive(Default)]
struct Unique(FxHashSet<String>);

impl Unique {
    fn insert(&mut self, name: &ast::Ident, what: &str) -> Result<(), Error> {
        check_not_reserved(name)?;
        if !self.0.insert(name.key()) {
            return Err(Error::at(
                ErrorKind::Name,
                name.pos,
                format!("{what} `{}` is declared twice", name.text),
            ));
        }
        Ok(())
    }
}
