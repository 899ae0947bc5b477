//! `check_nonconflicting = true`: the build proves that the supervisors do
//! not block each other, or refuses the project at the flag with a
//! shortest way into a blocking state.

mod common;

use common::{assert_errors_at_marked_lines, load_ok};

/// Two supervisors of a machine that takes a part and puts it out left or
/// right (`conflict/`): each alone never blocks.
fn project(flag: &str, supervisors: &[&str]) -> String {
    let mut text = format!(
        "[plc]\nname = \"x\"\n{flag}\n[inputs]\nl = {{}}\nr = {{}}\n[events]\ntake = {{ controllable = true }}\nleft = {{ rising = \"l\" }}\nright = {{ rising = \"r\" }}\n"
    );
    for s in supervisors {
        text.push_str(&format!(
            "[[supervisor]]\nname = \"to_{s}\"\nfile = \"conflict/{s}.toml\"\n"
        ));
    }
    text
}

#[test]
fn conflicting_supervisors_are_refused_with_a_shortest_string() {
    assert_errors_at_marked_lines([
        (
            project("check_nonconflicting = true # <-", &["right", "left"]),
            "the supervisors are conflicting: after take they are in (to_right in holding, to_left in holding), \
             from where no state marked in all of them can be reached (1 of 2 reachable states block)",
        ),
        (
            project("check_nonconflicting = true # <-", &["right"]),
            "check_nonconflicting needs two supervisors or more; this project has 1",
        ),
    ]);
}

#[test]
fn the_check_runs_only_when_asked_and_passes_supervisors_that_agree() {
    // Unasked, the conflicting pair loads (and runs into the fault it
    // deserves).
    load_ok(&project("check_nonconflicting = false", &["right", "left"]));
    load_ok(&project("", &["right", "left"]));
    // The same supervisor twice never conflicts with itself.
    let text = project("check_nonconflicting = true", &["right"])
        + "[[supervisor]]\nname = \"again\"\nfile = \"conflict/right.toml\"\n";
    load_ok(&text);
}

#[test]
fn the_boilers_seven_supervisors_are_nonconflicting() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../models/boiler/boiler.plc.toml");
    let text = std::fs::read_to_string(&path).unwrap().replacen(
        "[plc]\n",
        "[plc]\ncheck_nonconflicting = true\n",
        1,
    );
    assert!(text.contains("check_nonconflicting = true"));
    let project = plc_project::from_str(&text, &path).unwrap();
    assert_eq!(project.supervisors.len(), 7);
}
