//! Shorthand for building automata in unit tests, and paths that are no
//! regular files for the tests of file arguments.

use crate::automaton::{Automaton, AutomatonBuilder};
use std::path::{Path, PathBuf};

/// An automaton from its events, transitions and marked states; the
/// initial state is `"0"`.
pub fn auto(
    name: &str,
    events: &[(&str, bool)],
    trans: &[(&str, &str, &str)],
    marked: &[&str],
) -> Automaton {
    let mut b = AutomatonBuilder::new(name);
    for &(e, c) in events {
        b.add_event(e, c).unwrap();
    }
    b.set_initial_by_name("0").unwrap();
    for &(s, e, t) in trans {
        b.add_transition_by_name(s, e, t, 0).unwrap();
    }
    for m in marked {
        b.mark_by_name(m);
    }
    b.build().unwrap()
}

/// Paths named `name` (so that their extension is the one a command
/// expects) in subdirectories of `dir` that are no regular files: a link
/// to `/dev/zero` (read, it never ends), a directory and a FIFO when
/// `mkfifo` is there (read, it blocks until a writer comes). A thread
/// opens the FIFO for writing and closes it at once, so that a reader
/// that wrongly reads it sees an empty file rather than hanging the test.
#[cfg(unix)]
pub fn not_regular_files(dir: &Path, name: &str) -> Vec<PathBuf> {
    let place = |sub: &str| {
        let d = dir.join(sub);
        std::fs::create_dir_all(&d).unwrap();
        d.join(name)
    };
    let zero = place("zero");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let folder = place("folder");
    std::fs::create_dir(&folder).unwrap();
    let mut paths = vec![zero, folder];
    let fifo = place("fifo");
    if std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        let writer = fifo.clone();
        std::thread::spawn(move || {
            let _ = std::fs::OpenOptions::new().write(true).open(writer);
        });
        paths.push(fifo);
    }
    paths
}
