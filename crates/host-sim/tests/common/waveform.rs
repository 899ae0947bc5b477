//! A VCD read back with the `vcd` crate's parser: each variable by its
//! path (`boiler.plant.bath_c`), its declared type, and its value at any
//! time.

use std::collections::HashMap;
use vcd::{Command, IdCode, ScopeItem, Value, VarType};

/// A value as written in a value change.
#[derive(Debug, Clone, PartialEq)]
pub enum Sample {
    /// `0`, `1`, `x`, `z`.
    Bit(Value),
    /// `b…`.
    Vector(Vec<Value>),
    /// `r…`.
    Real(f64),
    /// `s…`.
    Text(String),
}

impl Sample {
    /// A wire's level; panics on anything else.
    pub fn bit(&self) -> bool {
        match self {
            Sample::Bit(Value::V1) => true,
            Sample::Bit(Value::V0) => false,
            other => panic!("expected 0 or 1, got {other:?}"),
        }
    }

    /// A `real` variable's value; panics on anything else.
    pub fn real(&self) -> f64 {
        match self {
            Sample::Real(x) => *x,
            other => panic!("expected a real, got {other:?}"),
        }
    }

    /// A string variable's value; panics on anything else.
    pub fn text(&self) -> &str {
        match self {
            Sample::Text(s) => s,
            other => panic!("expected a string, got {other:?}"),
        }
    }

    /// A vector as a number (`None` if a bit is not 0 or 1).
    pub fn number(&self) -> Option<u64> {
        match self {
            Sample::Vector(bits) => bits.iter().try_fold(0, |n, b| match b {
                Value::V0 => Some(n << 1),
                Value::V1 => Some(n << 1 | 1),
                _ => None,
            }),
            other => panic!("expected a vector, got {other:?}"),
        }
    }
}

/// A parsed VCD.
pub struct Waveform {
    /// Type, width and code of each variable by path.
    vars: HashMap<String, (VarType, u32, IdCode)>,
    /// Every change of each code in file order, with its time.
    changes: HashMap<IdCode, Vec<(u64, Sample)>>,
    /// The last timestamp.
    pub end: u64,
}

fn collect(items: &[ScopeItem], prefix: &str, vars: &mut HashMap<String, (VarType, u32, IdCode)>) {
    for item in items {
        match item {
            ScopeItem::Scope(s) => collect(&s.items, &format!("{prefix}{}.", s.identifier), vars),
            ScopeItem::Var(v) => {
                let path = format!("{prefix}{}", v.reference);
                assert!(
                    vars.insert(path.clone(), (v.var_type, v.size, v.code))
                        .is_none(),
                    "{path} declared twice"
                );
            }
            _ => {}
        }
    }
}

impl Waveform {
    /// Parses `bytes`; panics on anything the parser rejects.
    pub fn parse(bytes: &[u8]) -> Waveform {
        let mut parser = vcd::Parser::new(bytes);
        let header = parser.parse_header().expect("a VCD header");
        let mut vars = HashMap::new();
        collect(&header.items, "", &mut vars);
        let mut changes: HashMap<IdCode, Vec<(u64, Sample)>> = HashMap::new();
        let mut now = 0;
        for command in parser {
            let (id, sample) = match command.expect("a VCD value change") {
                Command::Timestamp(t) => {
                    now = t;
                    continue;
                }
                Command::ChangeScalar(id, v) => (id, Sample::Bit(v)),
                Command::ChangeVector(id, v) => (id, Sample::Vector(v.iter().collect())),
                Command::ChangeReal(id, v) => (id, Sample::Real(v)),
                Command::ChangeString(id, v) => (id, Sample::Text(v)),
                _ => continue,
            };
            changes.entry(id).or_default().push((now, sample));
        }
        Waveform {
            vars,
            changes,
            end: now,
        }
    }

    /// The declared type of the variable at `path`.
    pub fn var_type(&self, path: &str) -> VarType {
        self.var(path).0
    }

    /// The declared width of the variable at `path`.
    pub fn width(&self, path: &str) -> u32 {
        self.var(path).1
    }

    /// The paths of all variables.
    pub fn paths(&self) -> impl Iterator<Item = &str> {
        self.vars.keys().map(String::as_str)
    }

    /// Every change of the variable at `path`, in time order.
    pub fn changes(&self, path: &str) -> &[(u64, Sample)] {
        self.changes
            .get(&self.var(path).2)
            .map_or(&[], Vec::as_slice)
    }

    /// The value of the variable at `path` at `time` (the last change at
    /// or before it); panics before its first change.
    pub fn at(&self, path: &str, time: u64) -> &Sample {
        self.changes(path)
            .iter()
            .rev()
            .find(|(t, _)| *t <= time)
            .map(|(_, s)| s)
            .unwrap_or_else(|| panic!("{path} has no value at {time} ms"))
    }

    fn var(&self, path: &str) -> (VarType, u32, IdCode) {
        *self.vars.get(path).unwrap_or_else(|| {
            let mut known: Vec<&str> = self.paths().collect();
            known.sort_unstable();
            panic!("no variable {path} in the VCD; it has {known:?}")
        })
    }
}

/// A GTKWave save file read back: its groups, and each trace it shows
/// with its group and the flags (`@<hex>`) it is drawn with.
pub struct SaveFile {
    /// `(group, flags, signal)` in file order.
    pub traces: Vec<(String, u32, String)>,
    /// Group titles in order.
    pub groups: Vec<String>,
}

impl SaveFile {
    /// Parses `text`; panics on a line it does not know or a group left
    /// open.
    pub fn parse(text: &str) -> SaveFile {
        const GROUP_BEGIN: u32 = 0x80_0000;
        const GROUP_END: u32 = 0x100_0000;
        let (mut traces, mut groups) = (Vec::new(), Vec::new());
        let (mut flags, mut open): (u32, Option<String>) = (0, None);
        for line in text.lines() {
            if line.starts_with("[*]") || line.starts_with('[') {
                continue;
            } else if let Some(hex) = line.strip_prefix('@') {
                flags = u32::from_str_radix(hex, 16).expect("hex flags");
            } else if let Some(title) = line.strip_prefix('-') {
                if flags & GROUP_BEGIN != 0 {
                    assert!(open.is_none(), "group {title} inside another");
                    open = Some(title.to_owned());
                    groups.push(title.to_owned());
                } else if flags & GROUP_END != 0 {
                    assert_eq!(open.take().as_deref(), Some(title), "group closed");
                }
            } else {
                let group = open.clone().expect("a trace inside a group");
                traces.push((group, flags, line.to_owned()));
            }
        }
        assert!(open.is_none(), "group {open:?} left open");
        SaveFile { traces, groups }
    }

    /// The signals it names.
    pub fn signals(&self) -> impl Iterator<Item = &str> {
        self.traces.iter().map(|(_, _, s)| s.as_str())
    }
}
