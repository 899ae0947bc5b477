//! A spinner on stderr for long operations, silent when stderr is not a
//! terminal (pipes, CI logs).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::time::Duration;

/// Reports progress of `codegen::ops` on a spinner.
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
}

impl codegen::ops::Progress for Spinner {
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
