//! What a PLC compiler rejects is rejected here, with the line and a clear
//! message; host-API misuse is an error too.

use iec_st::{parse, ErrorKind, IntType, Value};

/// Wraps `body` in a program (body starts on line 3) with `vars` declared.
fn check(vars: &str, body: &str) -> iec_st::Error {
    let src = format!(
        "FUNCTION_BLOCK fb\nVAR_INPUT a : BOOL; END_VAR VAR_OUTPUT q : BOOL; END_VAR VAR hidden : BOOL; END_VAR\nq := a;\nEND_FUNCTION_BLOCK\nPROGRAM p\nVAR {vars} END_VAR\n{body}\nEND_PROGRAM"
    );
    match parse(&src) {
        Ok(_) => panic!("accepted:\n{src}"),
        Err(e) => e,
    }
}

#[test]
fn type_and_name_errors_carry_their_line() {
    const VARS: &str = "i : INT; d : DINT; u : UINT; ud : UDINT; us : USINT; b : BOOL; w : WORD; bt : BYTE; inst : fb; M : ARRAY [0..3] OF INT;";
    // The body starts on line 7.
    let table: &[(&str, ErrorKind, u32, &str)] = &[
        (
            "\ni := d;",
            ErrorKind::Type,
            8,
            "DINT cannot be used as INT",
        ),
        ("i := u;", ErrorKind::Type, 7, "UINT cannot be used as INT"),
        (
            "\n\nd := i + u;",
            ErrorKind::Type,
            9,
            "cannot combine INT and UINT",
        ),
        ("ud := d;", ErrorKind::Type, 7, "DINT_TO_UDINT"),
        ("b := 1;", ErrorKind::Type, 7, "cannot be used as BOOL"),
        ("i := b;", ErrorKind::Type, 7, "BOOL_TO_INT"),
        ("w := i;", ErrorKind::Type, 7, "INT cannot be used as WORD"),
        ("i := bt;", ErrorKind::Type, 7, "BYTE cannot be used as INT"),
        (
            "b := i AND b;",
            ErrorKind::Type,
            7,
            "cannot combine INT and BOOL",
        ),
        ("i := i AND 3;", ErrorKind::Type, 7, "BOOL or bit string"),
        ("w := w + 1;", ErrorKind::Type, 7, "needs integer operands"),
        ("b := NOT i;", ErrorKind::Type, 7, "NOT needs BOOL"),
        (
            "IF i THEN ; END_IF;",
            ErrorKind::Type,
            7,
            "IF condition must be BOOL",
        ),
        (
            "WHILE 1 DO ; END_WHILE;",
            ErrorKind::Type,
            7,
            "WHILE condition must be BOOL",
        ),
        (
            "us := us + 300;",
            ErrorKind::Range,
            7,
            "literal 300 does not fit USINT",
        ),
        (
            "ud := -1;",
            ErrorKind::Range,
            7,
            "literal -1 does not fit UDINT",
        ),
        (
            "i := INT#40000;",
            ErrorKind::Range,
            7,
            "40000 does not fit INT",
        ),
        (
            "b := BOOL#2;",
            ErrorKind::Range,
            7,
            "BOOL literal is 0 or 1",
        ),
        ("\nx := 1;", ErrorKind::Name, 8, "undeclared variable `x`"),
        ("i := M;", ErrorKind::Type, 7, "is an array; index it"),
        ("i := M[4];", ErrorKind::Range, 7, "index 4 outside 0..3"),
        (
            "i := M[1, 2];",
            ErrorKind::Type,
            7,
            "1 dimension(s), indexed with 2",
        ),
        ("i := M[b];", ErrorKind::Type, 7, "index must be an integer"),
        ("i := i[1];", ErrorKind::Type, 7, "`i` is not an array"),
        ("b := inst.hidden;", ErrorKind::Access, 7, "internal to fb"),
        ("inst.a := TRUE;", ErrorKind::Access, 7, "set by a call"),
        (
            "inst.q := TRUE;",
            ErrorKind::Access,
            7,
            "written only by fb",
        ),
        (
            "b := inst.nope;",
            ErrorKind::Name,
            7,
            "has no variable `nope`",
        ),
        ("b := inst;", ErrorKind::Type, 7, "instance of fb"),
        (
            "inst(x := 1);",
            ErrorKind::Name,
            7,
            "`x` is not an input of fb",
        ),
        (
            "inst(q := 1);",
            ErrorKind::Name,
            7,
            "`q` is not an input of fb",
        ),
        (
            "inst(a => b);",
            ErrorKind::Name,
            7,
            "`a` is not an output of fb",
        ),
        ("inst(TRUE);", ErrorKind::Syntax, 7, "formal arguments"),
        (
            "inst(a := i);",
            ErrorKind::Type,
            7,
            "INT cannot be used as BOOL",
        ),
        (
            "inst(q => i);",
            ErrorKind::Type,
            7,
            "cannot be stored in a INT",
        ),
        (
            "i(a := TRUE);",
            ErrorKind::Type,
            7,
            "not a function block instance",
        ),
        ("fb(a := TRUE);", ErrorKind::Type, 7, "call an instance"),
        (
            "i := nofunc(1);",
            ErrorKind::Name,
            7,
            "unknown function `nofunc`",
        ),
        ("i := ABS(b);", ErrorKind::Type, 7, "ABS needs an integer"),
        ("i := MIN(i);", ErrorKind::Type, 7, "at least 2 argument"),
        (
            "i := INT_TO_DINT(i);",
            ErrorKind::Type,
            7,
            "DINT cannot be used as INT",
        ),
        ("i := i / 0;", ErrorKind::Range, 7, "division by zero"),
        ("EXIT;", ErrorKind::Syntax, 7, "EXIT outside a loop"),
        (
            "FOR i := 1 TO 3 DO i := 2; END_FOR;",
            ErrorKind::Access,
            7,
            "control variable",
        ),
        (
            "FOR b := 1 TO 3 DO END_FOR;",
            ErrorKind::Type,
            7,
            "must be an integer",
        ),
        (
            "FOR w := 1 TO 3 DO END_FOR;",
            ErrorKind::Type,
            7,
            "must be an integer",
        ),
        (
            "CASE i OF 1: ; 0..2: ; END_CASE;",
            ErrorKind::Range,
            7,
            "already covered",
        ),
        (
            "CASE i OF 3..1: ; END_CASE;",
            ErrorKind::Range,
            7,
            "empty CASE range",
        ),
        (
            "CASE d OF i: ; END_CASE;",
            ErrorKind::Type,
            7,
            "CASE label must be a constant",
        ),
        (
            "CASE b OF 1: ; END_CASE;",
            ErrorKind::Type,
            7,
            "selector must be an integer",
        ),
        ("i := 2 ** 3;", ErrorKind::Unsupported, 7, "`**`"),
        ("i := T#1s;", ErrorKind::Unsupported, 7, "duration"),
    ];
    for &(body, kind, line, needle) in table {
        let err = check(VARS, body);
        let text = err.to_string();
        assert_eq!(err.kind(), Some(kind), "{body}: {text}");
        assert_eq!(err.line(), Some(line), "{body}: {text}");
        assert!(text.contains(needle), "{body}: `{text}` lacks `{needle}`");
    }
}

#[test]
fn constants_inputs_and_located_inputs_are_not_assigned() {
    let err =
        parse("PROGRAM p\nVAR CONSTANT K : INT := 3; END_VAR\nK := 4;\nEND_PROGRAM").unwrap_err();
    assert_eq!((err.kind(), err.line()), (Some(ErrorKind::Access), Some(3)));
    assert!(err.to_string().contains("`K` is a constant"));

    let err =
        parse("FUNCTION_BLOCK f\nVAR_INPUT go : BOOL; END_VAR\n\ngo := FALSE;\nEND_FUNCTION_BLOCK")
            .unwrap_err();
    assert_eq!((err.kind(), err.line()), (Some(ErrorKind::Access), Some(4)));
    assert!(err.to_string().contains("is an input"));

    let err =
        parse("PROGRAM p\nVAR sw AT %IX0.1 : BOOL; END_VAR\nsw := TRUE;\nEND_PROGRAM").unwrap_err();
    assert_eq!((err.kind(), err.line()), (Some(ErrorKind::Access), Some(3)));
}

#[test]
fn declarations_are_checked() {
    for (src, kind, line, needle) in [
        ("PROGRAM p VAR\n x : INT;\n X : BOOL; END_VAR END_PROGRAM", ErrorKind::Name, 3, "declared twice"),
        ("PROGRAM p VAR\n x : MOTOR; END_VAR END_PROGRAM", ErrorKind::Name, 2, "unknown type `MOTOR`"),
        ("PROGRAM p VAR\n x : REAL; END_VAR END_PROGRAM", ErrorKind::Unsupported, 2, "REAL"),
        ("PROGRAM p VAR\n x : ARRAY [3..1] OF INT; END_VAR END_PROGRAM", ErrorKind::Range, 2, "lower bound exceeds"),
        ("PROGRAM p VAR\n x : ARRAY [0..1] OF INT := [1, 2, 3]; END_VAR END_PROGRAM", ErrorKind::Range, 2, "more initial values"),
        ("PROGRAM p VAR\n x : ARRAY [0..1] OF INT := [3(0)]; END_VAR END_PROGRAM", ErrorKind::Range, 2, "more initial values"),
        ("PROGRAM p VAR\n x : SINT := 128; END_VAR END_PROGRAM", ErrorKind::Range, 2, "does not fit SINT"),
        ("PROGRAM p VAR y : INT;\n x : INT := y; END_VAR END_PROGRAM", ErrorKind::Type, 2, "earlier scalar constants"),
        ("PROGRAM p VAR\n x AT %IW0 : BOOL; END_VAR END_PROGRAM", ErrorKind::Type, 2, "16-bit location"),
        ("FUNCTION_BLOCK f VAR\n x AT %IX0.0 : BOOL; END_VAR END_FUNCTION_BLOCK", ErrorKind::Syntax, 2, "PROGRAM"),
        ("FUNCTION_BLOCK f VAR\n me : f; END_VAR END_FUNCTION_BLOCK", ErrorKind::Name, 2, "contains an instance of itself"),
        ("PROGRAM p VAR\n int : INT; END_VAR END_PROGRAM", ErrorKind::Name, 2, "reserved"),
        ("PROGRAM p VAR\n abs : INT; END_VAR END_PROGRAM", ErrorKind::Name, 2, "reserved"),
        ("PROGRAM p END_PROGRAM\nFUNCTION_BLOCK P END_FUNCTION_BLOCK", ErrorKind::Name, 2, "declared twice"),
        ("FUNCTION f : INT VAR_INPUT x : INT; END_VAR\n f := f(x); END_FUNCTION", ErrorKind::Name, 2, "recursive"),
        ("FUNCTION f : INT VAR_INPUT x : INT; END_VAR f := g(x); END_FUNCTION\nFUNCTION g : INT VAR_INPUT x : INT; END_VAR\n g := f(x); END_FUNCTION", ErrorKind::Name, 3, "recursive call of function `f`"),
        ("PROGRAM p VAR_IN_OUT\n x : INT; END_VAR END_PROGRAM", ErrorKind::Unsupported, 1, "VAR_IN_OUT"),
    ] {
        let err = parse(src).unwrap_err();
        let text = err.to_string();
        assert_eq!(err.kind(), Some(kind), "{src}: {text}");
        assert_eq!(err.line(), Some(line), "{src}: {text}");
        assert!(text.contains(needle), "{src}: `{text}` lacks `{needle}`");
    }
}

#[test]
fn the_host_writes_inputs_and_forces_the_rest() {
    let file = parse(
        "PROGRAM p
         VAR_INPUT go : BOOL; level : UINT; END_VAR
         VAR sw AT %IX0.3 : BOOL; lamp AT %QX0.0 : BOOL; n : INT; END_VAR
         VAR CONSTANT K : INT := 3; END_VAR
         lamp := sw AND go;
         END_PROGRAM",
    )
    .unwrap();
    let mut p = file.instantiate("p").unwrap();
    p.set("go", Value::Bool(true)).unwrap();
    p.set("SW", Value::Bool(true)).unwrap();
    p.set("level", Value::int(IntType::Usint, 200).unwrap())
        .expect("USINT widens to UINT");
    p.call().unwrap();
    assert_eq!(p.get("lamp").unwrap(), Value::Bool(true));

    let refused = [
        p.set("n", Value::int(IntType::Int, 1).unwrap()),
        p.set("lamp", Value::Bool(false)),
        p.set("go", Value::int(IntType::Int, 1).unwrap()),
        p.set("level", Value::int(IntType::Int, 1).unwrap()),
        p.set("missing", Value::Bool(true)),
        p.force("K", Value::int(IntType::Int, 1).unwrap()),
    ];
    for result in refused {
        assert!(result.is_err());
    }
    p.force("n", Value::int(IntType::Sint, -4).unwrap())
        .unwrap();
    assert_eq!(p.get("n").unwrap().as_i64(), Some(-4));

    // Slots resolve once and serve every instance of the same POU.
    let lamp = p.slot("lamp").unwrap();
    let mut q = file.instantiate("p").unwrap();
    assert_eq!(q.get_slot(lamp).unwrap(), Value::Bool(false));
    let go = q.slot("go").unwrap();
    assert!(go.is_input() && !lamp.is_input());
    q.set_slot(go, Value::Bool(true)).unwrap();
    q.force("sw", Value::Bool(true)).unwrap();
    q.call().unwrap();
    assert_eq!(q.get_slot(lamp).unwrap(), Value::Bool(true));

    let other = parse("PROGRAM p VAR_INPUT go : BOOL; END_VAR END_PROGRAM")
        .unwrap()
        .instantiate("p")
        .unwrap();
    assert!(other.get_slot(lamp).is_err(), "a slot of another file");
    assert!(file.instantiate("nothing").is_err());
    assert!(p.get("n[1]").is_err() && p.get("n.x").is_err());
}
