//! The `codegen` command: synthesis, checks and conversions on automata.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
