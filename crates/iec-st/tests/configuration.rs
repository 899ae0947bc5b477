//! A `CONFIGURATION` is parsed into its resources, tasks and program
//! instances and checked against the POUs: what a PLC tool would refuse to
//! download is an error at its line.

use iec_st::{parse, Configuration, ErrorKind, ProgramInstance, Resource, Task};

/// A program, a function block and a configuration (from line 8) built
/// around `resource`.
fn file(resource: &str) -> String {
    format!(
        "PROGRAM press_main\n\
         VAR n : UINT; END_VAR\n\
         n := n + 1;\n\
         END_PROGRAM\n\
         FUNCTION_BLOCK press_controller\n\
         VAR_OUTPUT q : BOOL; END_VAR\n\
         END_FUNCTION_BLOCK\n\
         CONFIGURATION press_config\n\
         {resource}\n\
         END_CONFIGURATION\n"
    )
}

#[test]
fn a_configuration_lists_its_resources_tasks_and_program_instances() {
    let source = file(
        "RESOURCE press_resource ON PLC
            TASK scan_task (INTERVAL := T#10ms, PRIORITY := 0);
            TASK slow (PRIORITY := 3, INTERVAL := TIME#1m30s500ms);
            TASK idle ();
            PROGRAM main WITH Scan_Task : PRESS_MAIN;
            PROGRAM logger : press_main;
        END_RESOURCE
        RESOURCE spare ON CPU2
            PROGRAM main WITH fast : press_main;
            TASK fast (INTERVAL := t#1.5s);",
    );
    // The second resource is out of order (TASK after PROGRAM).
    let err = parse(&source).unwrap_err();
    assert_eq!(err.kind(), Some(ErrorKind::Syntax), "{err}");
    assert_eq!(err.line(), Some(18), "{err}");

    let source = source.replace(
        "PROGRAM main WITH fast : press_main;\n            TASK fast (INTERVAL := t#1.5s);",
        "TASK fast (INTERVAL := t#1.5s);\n            PROGRAM main WITH fast : press_main;\n        END_RESOURCE",
    );
    let parsed = parse(&source).expect("valid configuration");
    let task = |name: &str, interval_ms, priority| Task {
        name: name.into(),
        interval_ms,
        priority,
    };
    let instance = |name: &str, task: Option<&str>| ProgramInstance {
        name: name.into(),
        task: task.map(Into::into),
        pou: "press_main".into(),
    };
    assert_eq!(
        parsed.configurations(),
        [Configuration {
            name: "press_config".into(),
            resources: vec![
                Resource {
                    name: Some("press_resource".into()),
                    on: Some("PLC".into()),
                    tasks: vec![
                        task("scan_task", Some(10), Some(0)),
                        task("slow", Some(90_500), Some(3)),
                        task("idle", None, None),
                    ],
                    programs: vec![
                        instance("main", Some("scan_task")),
                        instance("logger", None),
                    ],
                },
                Resource {
                    name: Some("spare".into()),
                    on: Some("CPU2".into()),
                    tasks: vec![task("fast", Some(1_500), None)],
                    programs: vec![instance("main", Some("fast"))],
                },
            ],
        }]
    );
    // The POUs are unaffected: the program named by the task still runs.
    let mut program = parsed
        .instantiate(&parsed.configurations()[0].resources[0].programs[0].pou)
        .expect("a PROGRAM");
    program.call().expect("runs");
    program.call().expect("runs");
    assert_eq!(program.get("n").unwrap().as_i64(), Some(2));
}

#[test]
fn a_configuration_without_resource_declares_one_unnamed_resource() {
    let parsed = parse(&file(
        "TASK t (INTERVAL := T#250ms); PROGRAM p WITH t : press_main;",
    ))
    .expect("valid configuration");
    let [config] = parsed.configurations() else {
        panic!("one configuration")
    };
    let [resource] = &config.resources[..] else {
        panic!("one resource")
    };
    assert_eq!(
        (resource.name.as_deref(), resource.on.as_deref()),
        (None, None)
    );
    assert_eq!(resource.tasks[0].interval_ms, Some(250));
    assert_eq!(resource.programs[0].task.as_deref(), Some("t"));
}

#[test]
fn configuration_errors_carry_their_line() {
    // The resource starts on line 9.
    let table: &[(&str, ErrorKind, u32, &str)] = &[
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := T#10ms);\nPROGRAM main WITH t : press_mian;\nEND_RESOURCE",
            ErrorKind::Name,
            11,
            "no PROGRAM `press_mian`",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := T#10ms);\n\nPROGRAM main WITH t : press_controller;\nEND_RESOURCE",
            ErrorKind::Name,
            12,
            "`press_controller` is a FUNCTION_BLOCK",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := T#10ms);\nPROGRAM main WITH fast : press_main;\nEND_RESOURCE",
            ErrorKind::Name,
            11,
            "no task `fast`",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := T#10ms);\nTASK T (INTERVAL := T#20ms);\nPROGRAM main WITH t : press_main;\nEND_RESOURCE",
            ErrorKind::Name,
            11,
            "task `T` is declared twice",
        ),
        (
            "RESOURCE r ON PLC\nPROGRAM main : press_main;\nPROGRAM Main : press_main;\nEND_RESOURCE",
            ErrorKind::Name,
            11,
            "program instance `Main` is declared twice",
        ),
        (
            "RESOURCE r ON PLC\n\nTASK t (INTERVAL := T#0ms);\nPROGRAM main WITH t : press_main;\nEND_RESOURCE",
            ErrorKind::Range,
            11,
            "must be positive",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := T#-5ms);\nPROGRAM main WITH t : press_main;\nEND_RESOURCE",
            ErrorKind::Range,
            10,
            "must be positive",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := T#5ms, INTERVAL := T#6ms);\nPROGRAM main : press_main;\nEND_RESOURCE",
            ErrorKind::Syntax,
            10,
            "`INTERVAL` is given twice",
        ),
        (
            "RESOURCE r ON PLC\nPROGRAM main : press_main;\nEND_RESOURCE\nRESOURCE r ON PLC\nPROGRAM main : press_main;\nEND_RESOURCE",
            ErrorKind::Name,
            12,
            "resource `r` is declared twice",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := T#10ms);\nEND_RESOURCE",
            ErrorKind::Syntax,
            11,
            "expected `TASK` or `PROGRAM`",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (SINGLE := trigger);\nPROGRAM main : press_main;\nEND_RESOURCE",
            ErrorKind::Unsupported,
            10,
            "`SINGLE`",
        ),
        (
            "RESOURCE r ON PLC\nTASK t (INTERVAL := period);\nPROGRAM main : press_main;\nEND_RESOURCE",
            ErrorKind::Unsupported,
            10,
            "from a variable",
        ),
        (
            "VAR_GLOBAL g : BOOL; END_VAR\nRESOURCE r ON PLC\nPROGRAM main : press_main;\nEND_RESOURCE",
            ErrorKind::Unsupported,
            9,
            "`VAR_GLOBAL`",
        ),
        (
            "RESOURCE r ON PLC\nPROGRAM main : press_main (n := 1);\nEND_RESOURCE",
            ErrorKind::Unsupported,
            10,
            "not supported",
        ),
        (
            "RESOURCE r ON PLC\nTASK INT (INTERVAL := T#10ms);\nPROGRAM main : press_main;\nEND_RESOURCE",
            ErrorKind::Name,
            10,
            "reserved",
        ),
    ];
    for &(resource, kind, line, needle) in table {
        let err = match parse(&file(resource)) {
            Ok(_) => panic!("accepted:\n{resource}"),
            Err(e) => e,
        };
        let text = err.to_string();
        assert_eq!(err.kind(), Some(kind), "{resource}: {text}");
        assert_eq!(err.line(), Some(line), "{resource}: {text}");
        assert!(
            text.contains(needle),
            "{resource}: `{text}` lacks `{needle}`"
        );
    }
}

#[test]
fn configuration_keywords_are_not_identifiers() {
    for word in [
        "task",
        "ON",
        "With",
        "resource",
        "CONFIGURATION",
        "interval",
    ] {
        let err = parse(&format!(
            "PROGRAM p\nVAR\n{word} : BOOL; END_VAR\nEND_PROGRAM"
        ))
        .unwrap_err();
        assert_eq!(err.kind(), Some(ErrorKind::Syntax), "{word}: {err}");
        assert_eq!(err.line(), Some(3), "{word}: {err}");
    }
}

#[test]
fn a_configuration_may_come_before_the_programs_it_runs() {
    let parsed = parse(
        "CONFIGURATION c RESOURCE r ON PLC TASK t (INTERVAL := T#2ms);
           PROGRAM i WITH t : later; END_RESOURCE END_CONFIGURATION
         PROGRAM later END_PROGRAM",
    )
    .expect("valid");
    assert_eq!(
        parsed.configurations()[0].resources[0].programs[0].pou,
        "later"
    );
}
