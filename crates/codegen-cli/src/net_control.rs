//! The options of every `codegen petri` verb that reads a net: which
//! transitions are uncontrollable or unobservable when the net file does
//! not say (PNML from other tools), `des::petri::control`'s rules.

use des::petri::control::{self, Control, Listed};
use des::petri::{self, PetriNet};
use des::Error;
use std::path::{Path, PathBuf};

/// What the command line states about the net's transitions.
#[derive(Debug, Clone, clap::Args)]
pub struct ControlArgs {
    /// The uncontrollable transitions, by id, separated by commas; every
    /// other one is controllable ('' for none). Needed for a net whose file
    /// does not say (PNML from other tools); must agree with one that does
    #[arg(long, value_name = "IDS", conflicts_with = "control")]
    uncontrollable: Option<String>,
    /// The unobservable transitions, by id, separated by commas; every
    /// other one is observable
    #[arg(long, value_name = "IDS", conflicts_with = "control")]
    unobservable: Option<String>,
    /// A TOML file stating `uncontrollable = [...]` and/or
    /// `unobservable = [...]`
    #[arg(long, value_name = "FILE")]
    control: Option<PathBuf>,
}

/// How a user of the command line states controllability.
const HINT: &str =
    "give --uncontrollable T1,T2,… (the others are controllable; '' for none) or --control FILE";

fn list(option: &str, ids: &Option<String>) -> Option<Listed> {
    ids.as_ref().map(|ids| {
        Listed::from_option(
            option,
            ids.split(',')
                .map(str::trim)
                .filter(|id| !id.is_empty())
                .map(str::to_owned),
        )
    })
}

impl ControlArgs {
    /// The statement these options make.
    fn control(&self) -> Result<Control, Error> {
        match &self.control {
            Some(path) => control::read_file(path, HINT),
            None => Ok(Control {
                uncontrollable: list("--uncontrollable", &self.uncontrollable),
                unobservable: list("--unobservable", &self.unobservable),
                hint: HINT.to_owned(),
            }),
        }
    }

    /// Whether any of these options was given.
    pub fn given(&self) -> bool {
        self.uncontrollable.is_some() || self.unobservable.is_some() || self.control.is_some()
    }

    /// Reads the net at `path` with what these options state.
    pub fn read_net(&self, path: &Path) -> Result<PetriNet, Error> {
        petri::read_file_with(path, &self.control()?)
    }
}
