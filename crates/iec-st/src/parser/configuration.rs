//! `CONFIGURATION` ... `END_CONFIGURATION`: resources, tasks and program
//! instances (IEC 61131-3, configuration elements). Global variables,
//! access paths, instance-specific initialisations, `SINGLE` tasks and
//! program configuration elements are outside the subset.

use super::{Parser, Result};
use crate::ast::{ConfigurationDecl, ProgramDecl, ResourceDecl, TaskDecl};
use crate::error::{Error, ErrorKind};
use crate::lexer::{Kw, Tok};

impl Parser {
    /// `CONFIGURATION name (RESOURCE ... END_RESOURCE)+ END_CONFIGURATION`,
    /// or with the tasks and programs of a single resource directly inside.
    pub(super) fn configuration(&mut self) -> Result<ConfigurationDecl> {
        self.expect_kw(Kw::Configuration)?;
        let name = self.ident()?;
        self.no_global_variables()?;
        let mut resources = Vec::new();
        if self.peek() == &Tok::Kw(Kw::Resource) {
            while self.eat(&Tok::Kw(Kw::Resource)) {
                let name = self.ident()?;
                self.expect_kw(Kw::On)?;
                let on = self.ident()?;
                self.no_global_variables()?;
                let (tasks, programs) = self.tasks_and_programs()?;
                self.expect_kw(Kw::EndResource)?;
                resources.push(ResourceDecl {
                    name: Some(name),
                    on: Some(on),
                    tasks,
                    programs,
                });
            }
        } else {
            let (tasks, programs) = self.tasks_and_programs()?;
            resources.push(ResourceDecl {
                name: None,
                on: None,
                tasks,
                programs,
            });
        }
        if let Tok::Ident(word) = self.peek() {
            if ["VAR_ACCESS", "VAR_CONFIG"]
                .iter()
                .any(|k| k.eq_ignore_ascii_case(word))
            {
                return Err(self.unsupported(&format!("`{word}` in a configuration")));
            }
        }
        self.expect_kw(Kw::EndConfiguration)?;
        Ok(ConfigurationDecl { name, resources })
    }

    fn no_global_variables(&self) -> Result<()> {
        if self.peek() == &Tok::Kw(Kw::VarGlobal) {
            return Err(self.unsupported("`VAR_GLOBAL` in a configuration"));
        }
        Ok(())
    }

    /// `{TASK ...;} PROGRAM ...; {PROGRAM ...;}`: tasks first, then at
    /// least one program instance.
    fn tasks_and_programs(&mut self) -> Result<(Vec<TaskDecl>, Vec<ProgramDecl>)> {
        let mut tasks = Vec::new();
        while self.peek() == &Tok::Kw(Kw::Task) {
            tasks.push(self.task()?);
            self.expect(Tok::Semi)?;
        }
        let mut programs = Vec::new();
        while self.peek() == &Tok::Kw(Kw::Program) {
            programs.push(self.program_instance()?);
            self.expect(Tok::Semi)?;
        }
        if programs.is_empty() {
            return Err(self.unexpected("`TASK` or `PROGRAM`"));
        }
        if self.peek() == &Tok::Kw(Kw::Task) {
            return Err(Error::at(
                ErrorKind::Syntax,
                self.pos(),
                "a resource declares its TASKs before its PROGRAMs",
            ));
        }
        Ok((tasks, programs))
    }

    /// `TASK name ([INTERVAL := T#...] [, PRIORITY := n])`, properties in
    /// any order, each at most once.
    fn task(&mut self) -> Result<TaskDecl> {
        self.expect_kw(Kw::Task)?;
        let name = self.ident()?;
        self.expect(Tok::LParen)?;
        let mut task = TaskDecl {
            name,
            interval: None,
            priority: None,
        };
        if self.eat(&Tok::RParen) {
            return Ok(task);
        }
        loop {
            let pos = self.pos();
            let property = self.peek().clone();
            let given_twice = match property {
                Tok::Kw(Kw::Interval) => {
                    self.next();
                    self.expect(Tok::Assign)?;
                    let value_pos = self.pos();
                    let ms = match *self.peek() {
                        Tok::Time(ms) => ms,
                        Tok::Ident(_) => {
                            return Err(self.unsupported("an INTERVAL read from a variable"))
                        }
                        _ => return Err(self.unexpected("a duration such as `T#10ms`")),
                    };
                    self.next();
                    task.interval.replace((ms, value_pos)).is_some()
                }
                Tok::Kw(Kw::Priority) => {
                    self.next();
                    self.expect(Tok::Assign)?;
                    let Tok::Int(value) = *self.peek() else {
                        return Err(self.unexpected("an unsigned integer priority"));
                    };
                    let value = i64::try_from(value).map_err(|_| {
                        Error::at(ErrorKind::Range, self.pos(), "priority too large")
                    })?;
                    self.next();
                    task.priority.replace(value).is_some()
                }
                Tok::Kw(Kw::Single) => {
                    return Err(self.unsupported("`SINGLE` (an event-triggered task)"))
                }
                _ => return Err(self.unexpected("`INTERVAL` or `PRIORITY`")),
            };
            if given_twice {
                return Err(Error::at(
                    ErrorKind::Syntax,
                    pos,
                    format!("{} is given twice", property.describe()),
                ));
            }
            if !self.eat(&Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RParen)?;
        Ok(task)
    }

    /// `PROGRAM instance [WITH task] : pou`.
    fn program_instance(&mut self) -> Result<ProgramDecl> {
        self.expect_kw(Kw::Program)?;
        if matches!(self.peek(), Tok::Kw(Kw::Retain | Kw::NonRetain)) {
            return Err(self.unsupported("a RETAIN or NON_RETAIN program instance"));
        }
        let name = self.ident()?;
        let task = if self.eat(&Tok::Kw(Kw::With)) {
            Some(self.ident()?)
        } else {
            None
        };
        self.expect(Tok::Colon)?;
        let pou = self.ident()?;
        if self.peek() == &Tok::LParen {
            return Err(self.unsupported("connecting a program instance's variables"));
        }
        Ok(ProgramDecl { name, task, pou })
    }
}
