//! Why a command failed (exit code 2): the errors of the crates below,
//! unchanged, and what only the command line can say (its flags).

/// Everything a command can fail with.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// A model, net or project file cannot be read, written or used, or
    /// an operation on automata or nets failed: the automaton layer's and
    /// the front end's error, unchanged.
    #[error(transparent)]
    Model(#[from] des::Error),
    /// Generation refused the project: code generation's error,
    /// unchanged.
    #[error(transparent)]
    Codegen(#[from] codegen::Error),
    /// Symbolic synthesis refused its models: the symbolic layer's error,
    /// unchanged.
    #[error(transparent)]
    Symbolic(#[from] des_symbolic::Error),
    /// A composition or reachability graph reached the bound on states
    /// that the command's `--max-states` sets.
    #[error("{source} (raise it with --max-states)")]
    MaxStates {
        /// The refusal ([`des::Error::StateLimit`]), naming the limit.
        source: des::Error,
    },
    /// The arguments ask for what the verb or the files named cannot give
    /// (a flag of another verb, a component that is not there, a project
    /// without `[board]`): the message says what to do instead.
    #[error("{0}")]
    Usage(String),
    /// A load over the serial link failed or the PLC refused it: the
    /// field-update link's error, unchanged.
    #[error(transparent)]
    Load(#[from] field_update::host::LinkError),
}

impl CliError {
    /// `error`, which `--max-states` raises if it is a state bound
    /// ([`CliError::MaxStates`]).
    pub fn max_states(error: des::Error) -> CliError {
        match error {
            des::Error::StateLimit { .. } => CliError::MaxStates { source: error },
            error => CliError::Model(error),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::CliError;

    #[test]
    fn a_state_bound_is_raised_with_the_flag_and_nothing_else_changes() {
        let limit = des::Error::StateLimit {
            max_states: 5,
            message: "composition `a||b` exceeds the limit of 5 states".into(),
        };
        let err = CliError::max_states(limit);
        assert!(matches!(err, CliError::MaxStates { .. }), "{err:?}");
        assert_eq!(
            err.to_string(),
            "composition `a||b` exceeds the limit of 5 states (raise it with --max-states)"
        );
        let other = CliError::max_states(des::Error::Incompatible("no".into()));
        assert!(matches!(other, CliError::Model(_)), "{other:?}");
        assert_eq!(other.to_string(), "no");
    }
}
