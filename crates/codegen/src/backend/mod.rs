//! Backends: how a supervisor becomes code the executor runs.
//!
//! - [`table`]: bit-packed transition tables, decoded by the executor.
//! - `logic`: CMSSM next-state and output functions (Leduc–Wonham),
//!   minimised with Espresso.
//!
//! [`Backend`] names them; what each lowers to is `crate::lower`.

pub mod logic;
pub mod table;

/// How supervisors are represented in the generated program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// Bit-packed transition tables (the default).
    #[default]
    Table,
    /// CMSSM next-state and output functions (Espresso-minimised).
    Logic,
    /// Baseline for measurements: one plain `match` on (state, event) per
    /// supervisor, what a hand-written state machine does.
    Match,
}

impl Backend {
    /// Every backend.
    pub const ALL: [Backend; 3] = [Backend::Table, Backend::Logic, Backend::Match];

    /// The name used on command lines and in file headers.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Table => "table",
            Backend::Logic => "logic",
            Backend::Match => "match",
        }
    }
}

impl std::str::FromStr for Backend {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Backend, String> {
        Backend::ALL
            .into_iter()
            .find(|b| b.name() == s)
            .ok_or_else(|| format!("unknown backend `{s}` (expected table, logic or match)"))
    }
}
