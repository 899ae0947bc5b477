//! A spinner on stderr for long operations, silent when stderr is not a
//! terminal (pipes, CI logs). It shows what `des::ops` (synthesis) and the
//! logic backend report through [`des::ops::Progress`].

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::time::Duration;

/// Reports progress of `des::ops` on a spinner.
pub struct Spinner {
    bar: ProgressBar,
}

impl Spinner {
    /// A spinner that starts with `message`.
    pub fn new(message: &str) -> Spinner {
        let bar = if std::io::stderr().is_terminal() {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template("{spinner} {msg} [{elapsed}]")
                    .expect("valid template"),
            );
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        } else {
            ProgressBar::hidden()
        };
        bar.set_message(message.to_owned());
        Spinner { bar }
    }

    /// Changes the message.
    pub fn phase(&self, message: &str) {
        self.bar.set_message(message.to_owned());
    }

    /// Prints a line on stderr without tearing the spinner.
    pub fn warn(&self, text: std::fmt::Arguments<'_>) {
        self.bar.suspend(|| super::output::warn(text));
    }
}

impl des::ops::Progress for Spinner {
    fn report(&self, phase: &str, done: usize) {
        if done == 0 {
            self.bar.set_message(phase.to_owned());
        } else {
            self.bar.set_message(format!("{phase}: {done} states"));
        }
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// Loads the project at `path` behind a spinner, its warnings printed
/// with their file and line; the spinner is returned for the next phases.
pub fn load_project(path: &std::path::Path) -> Result<(plc_project::Project, Spinner), des::Error> {
    let spinner = Spinner::new(&format!("loading {}", path.display()));
    let project = plc_project::load(path)?;
    for w in &project.warnings {
        spinner.warn(format_args!(
            "warning: {}:{}: {}",
            path.display(),
            w.line,
            w.message
        ));
    }
    Ok((project, spinner))
}

#[cfg(test)]
mod tests {
    use codegen::backend::logic::{self, Encoding, LogicSupervisor, Minimisation, Settings};
    use des::formats::{read_str, Format};
    use des::ops::Progress;
    use std::cell::RefCell;
    use std::path::Path;

    /// Keeps every phase it is told.
    #[derive(Default)]
    struct Recorder(RefCell<Vec<String>>);

    impl Progress for Recorder {
        fn report(&self, phase: &str, _done: usize) {
            self.0.borrow_mut().push(phase.to_owned());
        }
    }

    #[test]
    fn the_logic_backend_reports_which_supervisor_phase_and_function_it_is_working_on() {
        let text = "name = \"press\"\ninitial = \"idle\"\ncontrollable = [\"down\"]\n\
                    uncontrollable = [\"bottom\", \"top\"]\ntransitions = [[\"idle\", \"down\", \"pressing\"], \
                    [\"pressing\", \"bottom\", \"rising\"], [\"rising\", \"top\", \"idle\"]]\n";
        let a = read_str(text, Format::Toml, Path::new("press.toml"))
            .unwrap()
            .remove(0)
            .automaton;
        let local: Vec<_> = a.alphabet().ids().collect();
        let recorder = Recorder::default();
        LogicSupervisor::synthesize_reporting(
            &a,
            &local,
            Encoding::binary(3),
            &Settings::default(),
            &recorder,
        )
        .unwrap();
        let effort =
            logic::effort(&a, &local, &Encoding::binary(3), Minimisation::PerFunction).unwrap();
        let phase = |what: &str| format!("supervisor `press` (3 states, effort {effort}): {what}");
        assert_eq!(
            recorder.0.into_inner(),
            [
                phase("minimising ω, the next-state logic (bit 1 of 2)"),
                phase("minimising ω, the next-state logic (bit 2 of 2)"),
                phase("minimising φ, the enabling logic (event 1 of 3)"),
                phase("minimising φ, the enabling logic (event 2 of 3)"),
                phase("minimising φ, the enabling logic (event 3 of 3)"),
                phase("verifying the logic against the automaton"),
            ]
        );
    }
}
