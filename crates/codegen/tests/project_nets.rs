//! `[[net]]` in PLC projects: nets read or synthesised, checked against
//! the events, laid out as counters; every refusal at its line.

mod common;

use codegen::lower::{NetGroups, NetLayout, Supervisors, TableImage};
use common::{assert_errors_at_marked_lines, load_err, load_ok};
use executor::memory::HeapMemory;
use executor::{Controller, Program};
use plc_project::{Drive, NetSource};

/// The events of `nets/two.toml`: `go` a command, `done` on a rising edge.
const EVENTS: &str = "[inputs]\nfinished = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"finished\" }\n";

#[test]
fn a_net_with_constraints_runs_as_counters_with_its_control_place() {
    let p = load_ok(&format!(
        "[plc]\nname = \"x\"\n{EVENTS}[outputs]\nrunning = {{ places = {{ two = [\"busy\"] }} }}\n[[net]]\nname = \"two\"\nfile = \"nets/two.toml\"\nconstraints = \"nets/one_busy.constraints.toml\"\n"
    ));
    let net = &p.nets[0];
    assert!(matches!(
        net.source,
        NetSource::Synthesized {
            transform: false,
            ..
        }
    ));
    assert_eq!(net.control_places, 1);
    // free ≤ 2 (2 bits), busy ≤ 1, the control place ≤ 1: 4 bits, one group.
    assert_eq!(net.bounds, [2, 1, 1]);
    assert_eq!(net.widths(), [2, 1, 1]);
    assert_eq!(net.events, [0, 1]);
    assert_eq!(p.outputs[0].drive, Drive::Places(vec![(0, vec![1])]));
    let image = TableImage::new(&p).unwrap();
    let layout = &image.pools.nets[0];
    assert_eq!(layout.group_bits, [4]);
    let supervisors = Supervisors::new(&p, &image.pools.nets);
    assert_eq!(supervisors.len(), 1);
    assert_eq!(supervisors.name(0), "two");
    assert_eq!(
        supervisors.state_name(0, layout.pack(0, net.net.initial())),
        "2·free + c1"
    );

    // Run it: `go` once (the control place allows one busy machine),
    // then nothing until `done`.
    let mut c = Controller::new(&image, HeapMemory::for_config(&image.config())).unwrap();
    let r = c.scan(0, &[false]);
    assert_eq!(r.executed, [0]);
    assert_eq!(r.outputs, [true]);
    assert_eq!(supervisors.state_name(0, r.states[0]), "free + busy");
    let r = c.scan(10, &[false]);
    assert!(
        r.executed.is_empty(),
        "the control place holds the second start"
    );
    let r = c.scan(20, &[true]);
    assert_eq!(r.executed, [1, 0], "done, then go again");
    assert_eq!(supervisors.state_name(0, r.states[0]), "free + busy");
}

#[test]
fn an_uncontrollable_transition_the_net_does_not_enable_is_unexpected() {
    let p = load_ok(
        "[plc]\nname = \"x\"\n[inputs]\nfinished = {}\nstart = {}\n[events]\ngo = { controllable = true, request = \"start\" }\ndone = { rising = \"finished\" }\n[[net]]\nname = \"two\"\nfile = \"nets/two.toml\"\n",
    );
    let image = TableImage::new(&p).unwrap();
    let mut c = Controller::new(&image, HeapMemory::for_config(&image.config())).unwrap();
    assert!(c.scan(0, &[false, false]).executed.is_empty());
    // `done` with no machine busy: the net does not enable it.
    let r = c.scan(10, &[true, false]);
    assert_eq!(r.unexpected, [1]);
    assert_eq!(c.fault(), Some(executor::Fault::Unexpected { event: 1 }));
}

#[test]
fn dead_markings_are_a_warning_with_a_firing_sequence() {
    let p = load_ok(
        "[plc]\nname = \"x\"\n[events]\ngo = { controllable = true }\n[[net]]\nname = \"d\"\nfile = \"nets/dead.toml\"\n",
    );
    assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    assert_eq!(p.warnings[0].line, 5);
    assert!(
        p.warnings[0]
            .message
            .contains("1 dead marking(s), e.g. b after go"),
        "{}",
        p.warnings[0].message
    );
}

#[test]
fn every_net_rule_rejects_its_violation_at_the_offending_line() {
    let net = "[[net]]\nname = \"two\"\nfile = \"nets/two.toml\"\n";
    let cases: Vec<(String, &str)> = vec![
        (
            "[plc]\nname = \"x\"\n[events]\ngo = { controllable = true }\n[[net]] # <-\nname = \"two\"\nfile = \"nets/two.toml\"\n".to_owned(),
            "transition `done` of net `two` (`",
        ),
        (
            format!("[plc]\nname = \"x\"\n[inputs]\nf = {{}}\n[events]\ngo = {{ rising = \"f\" }} # <-\ndone = {{ rising = \"f\" }}\n{net}"),
            "event `go` is uncontrollable here but controllable in net `two`",
        ),
        (
            "[plc]\nname = \"x\"\n[inputs]\nf = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"f\" }\n[[net]] # <-\nname = \"h\"\nfile = \"nets/hidden.toml\"\n".to_owned(),
            "transition `done` of net `h` (`",
        ),
        (
            "[plc]\nname = \"x\"\n[events]\ngo = { controllable = true }\n[[net]] # <-\nname = \"u\"\nfile = \"nets/unbounded.toml\"\n".to_owned(),
            "net `u`: ",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[[net]] # <-\nname = \"two\"\nfile = \"nets/two.toml\"\nmax_markings = 2\n"),
            "net `two`: the reachability graph of `two` exceeds the limit of 2 states (raise it with \
             `max_markings`); a net runs with a counter per place, so it must be bounded",
        ),
        (
            "[plc]\nname = \"x\"\n[events]\ngo = { controllable = true }\n[[net]]\nname = \"u\"\nfile = \"nets/unbounded.toml\"\nmax_markings = 0 # <-\n".to_owned(),
            "max_markings must be a positive number of markings",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[[net]]\nname = \"two\"\nfile = \"nets/missing.toml\" # <-\n"),
            "cannot read net file `",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[[net]]\nname = \"two\"\nfile = \"nets/two.toml\"\ntransform = true # <-\n"),
            "`transform` applies to `constraints`; this net has none",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[outputs]\nlamp = {{ places = {{ two = [\"idle\"] }} }} # <-\n{net}"),
            "net `two` has no place `idle`",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[outputs]\nlamp = {{ places = {{ other = [\"busy\"] }} }} # <-\n{net}"),
            "unknown net `other`",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[outputs]\nlamp = {{ initial = true, places = {{ two = [\"busy\"] }} }} # <-\n{net}"),
            "output `lamp` has a place map (a Moore output): it takes no `initial`",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[outputs]\nlamp = {{}}\n[[net]]\nname = \"lamp\" # <-\nfile = \"nets/two.toml\"\n"),
            "lamp",
        ),
        // A net reserves its group names, however many groups it packs into.
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}[outputs]\ntwo_1 = {{}}\n[[net]]\nname = \"two\" # <-\nfile = \"nets/two.toml\"\n"),
            "net `two` reserves `two.1`, `two.2`, … for its groups, and output `two_1` (line 9) becomes one of their identifiers",
        ),
        (
            "[plc]\nname = \"x\"\n[inputs]\nfinished = {}\n\"two.2\" = {}\n[events]\ngo = { controllable = true }\ndone = { rising = \"finished\" }\n[[net]]\nname = \"two\" # <-\nfile = \"nets/two.toml\"\n".to_owned(),
            "net `two` reserves `two.1`, `two.2`, … for its groups, and input `two.2` (line 5) becomes one of their identifiers",
        ),
        (
            format!("[plc]\nname = \"x\"\n{EVENTS}{net}[[net]]\nname = \"two.12\" # <-\nfile = \"nets/two.toml\"\n"),
            "net name `two.12` becomes the identifier `TWO_12`, which net `two`",
        ),
    ];
    assert_errors_at_marked_lines(cases);
}

#[test]
fn an_inadmissible_constraint_is_refused_in_its_file_or_transformed() {
    let text = |transform: &str| {
        format!("[plc]\nname = \"x\"\n{EVENTS}[[net]]\nname = \"two\"\nfile = \"nets/two.toml\"\nconstraints = \"nets/no_free.constraints.toml\"\n{transform}")
    };
    let msg = load_err(&text(""));
    assert!(msg.contains("no_free.constraints.toml:"), "{msg}");
    assert!(msg.contains("`done`"), "{msg}");
    // free ≤ 2 through `done` (uncontrollable) is free + busy ≤ 2 once
    // transformed, which the net keeps by itself: both machines start.
    let p = load_ok(&text("transform = true\n"));
    assert_eq!(p.nets[0].control_places, 1);
    let image = TableImage::new(&p).unwrap();
    let mut c = Controller::new(&image, HeapMemory::for_config(&image.config())).unwrap();
    assert_eq!(c.scan(0, &[false]).executed, [0]);
    let r = c.scan(10, &[false]);
    assert_eq!(r.executed, [0]);
    let supervisors = Supervisors::new(&p, &image.pools.nets);
    assert_eq!(supervisors.state_name(0, r.states[0]), "2·busy");
}

#[test]
fn nets_run_on_the_table_backend_only() {
    let p = load_ok(&format!(
        "[plc]\nname = \"x\"\n{EVENTS}[[net]]\nname = \"two\"\nfile = \"nets/two.toml\"\n"
    ));
    for backend in [
        codegen::backend::Backend::Logic,
        codegen::backend::Backend::Match,
    ] {
        let err = codegen::emit::generate(&p, backend, "").unwrap_err();
        assert!(
            matches!(
                &err,
                codegen::Error::TableOnly { location, net, backend: b }
                    if location.line == 8 && net == "two" && *b == backend
            ),
            "{err:?}"
        );
        let msg = err.to_string();
        assert!(msg.contains("t.plc.toml:8:"), "{msg}");
        assert!(
            msg.ends_with(&format!(
                ": net `two`: Petri nets run on the table backend only, not the {} backend \
                 (use `--backend table`)",
                backend.name()
            )),
            "{msg}"
        );
    }
}

#[test]
fn a_control_place_beyond_a_nets_arithmetic_is_refused_not_wrapped() {
    // Wrapped, the control place had no arcs and the project fired `go`,
    // the very transition the constraint forbids.
    let msg = load_err(&format!(
        "[plc]\nname = \"x\"\n{EVENTS}[[net]]\nname = \"fours\"\nfile = \"nets/fours.toml\"\nconstraints = \"nets/never_busy_2e62.constraints.toml\"\n"
    ));
    assert!(
        msg.contains("never_busy_2e62.constraints.toml:4:1: constraint `never busy`"),
        "{msg}"
    );
    assert!(
        msg.contains("an arc of weight 18446744073709551616 on transition `go`"),
        "{msg}"
    );
    assert!(msg.contains("(2^32 − 1)"), "{msg}");
}

/// A net counter group's trace name reads back to its state whatever the
/// place ids hold (`a + b`, `0`, `2·x`, a quote): such ids are quoted.
#[test]
fn net_state_names_read_back_whatever_the_place_ids() {
    let p = load_ok(&format!(
        "[plc]\nname = \"x\"\n{EVENTS}[[net]]\nname = \"odd\"\nfile = \"nets/odd_ids.toml\"\n"
    ));
    let layout = NetLayout::of(&p.nets[0]);
    let net = NetGroups {
        net: &p.nets[0],
        layout: &layout,
    };
    let markings: [&[u32]; 4] = [&[1, 0, 0, 0], &[0, 2, 1, 0], &[1, 0, 0, 1], &[0, 0, 0, 0]];
    let mut names = std::collections::HashSet::new();
    for m in markings {
        let state = layout.pack(0, m);
        let name = net.state_name(0, state);
        assert_eq!(net.parse_state(0, &name), Some(state), "{name}");
        assert!(names.insert(name.clone()), "{name} twice");
    }
    assert_eq!(
        net.state_name(0, layout.pack(0, &[0, 2, 1, 0])),
        "2·\"0\" + \"2·x\""
    );
    assert_eq!(
        net.state_name(0, layout.pack(0, &[1, 0, 0, 1])),
        "\"a + b\" + \"q\\\"\""
    );
    assert_eq!(net.parse_state(0, "\"a + b"), None, "an open quote");
    assert_eq!(
        net.parse_state(0, "a + b"),
        None,
        "unquoted, two unknown places"
    );
}
