//! Statement semantics: IF, CASE, FOR (bounds evaluated once), WHILE,
//! REPEAT, EXIT, RETURN, function block and function calls, VAR_TEMP, and
//! the run-time faults.

use iec_st::{parse, Fault, Instance, IntType, Value};

fn program(body: &str, vars: &str) -> Instance {
    let src = format!("PROGRAM p\nVAR {vars} END_VAR\n{body}\nEND_PROGRAM");
    let file = parse(&src).unwrap_or_else(|e| panic!("{src}\n{e}"));
    file.instantiate("p").unwrap()
}

fn run(body: &str, vars: &str) -> Instance {
    let mut p = program(body, vars);
    p.call().unwrap();
    p
}

fn int(p: &Instance, path: &str) -> i128 {
    p.get(path).unwrap().as_i128().unwrap()
}

#[test]
fn for_counts_inclusively_and_leaves_the_variable_past_the_bound() {
    let p = run(
        "FOR i := 1 TO 10 DO sum := sum + i; END_FOR;
         FOR j := 10 TO 1 BY -3 DO down := down * 10 + j; END_FOR;
         FOR k := 5 TO 4 DO never := never + 1; END_FOR;",
        "i, sum, j, down, k, never : INT;",
    );
    assert_eq!(int(&p, "sum"), 55);
    assert_eq!(int(&p, "i"), 11);
    assert_eq!(int(&p, "down"), 10_741, "10, 7, 4, 1");
    assert_eq!(int(&p, "j"), -2);
    assert_eq!(int(&p, "never"), 0);
    assert_eq!(int(&p, "k"), 5);
}

#[test]
fn for_evaluates_its_bounds_once() {
    let p = run(
        "n := 3; FOR i := 1 TO n BY step DO n := n + 1; step := 5; count := count + 1; END_FOR;",
        "i, n, count : INT; step : INT := 1;",
    );
    assert_eq!(int(&p, "count"), 3);
    assert_eq!(int(&p, "n"), 6);
}

#[test]
fn exit_leaves_the_innermost_loop_only() {
    let p = run(
        "FOR i := 1 TO 3 DO
           FOR j := 1 TO 100 DO
             IF j > i THEN EXIT; END_IF;
             count := count + 1;
           END_FOR;
         END_FOR;
         WHILE TRUE DO w := w + 1; IF w = 4 THEN EXIT; END_IF; END_WHILE;",
        "i, j, count, w : INT;",
    );
    assert_eq!(int(&p, "count"), 1 + 2 + 3);
    assert_eq!(int(&p, "i"), 4);
    assert_eq!(int(&p, "w"), 4);
}

#[test]
fn return_ends_the_call_and_the_next_call_starts_over() {
    let mut p = program(
        "calls := calls + 1;
         IF calls = 2 THEN RETURN; END_IF;
         FOR i := 1 TO 5 DO IF i = 3 THEN RETURN; END_IF; after := after + 1; END_FOR;
         never := TRUE;",
        "calls, i, after : INT; never : BOOL;",
    );
    p.call().unwrap();
    assert_eq!((int(&p, "calls"), int(&p, "after")), (1, 2));
    p.call().unwrap();
    assert_eq!((int(&p, "calls"), int(&p, "after")), (2, 2));
    p.call().unwrap();
    assert_eq!((int(&p, "calls"), int(&p, "after")), (3, 4));
    assert_eq!(p.get("never").unwrap(), Value::Bool(false));
}

#[test]
fn while_tests_first_and_repeat_runs_at_least_once() {
    let p = run(
        "WHILE w > 0 DO w := w - 1; END_WHILE;
         REPEAT r := r + 1; UNTIL TRUE END_REPEAT;
         REPEAT n := n + 2; UNTIL n >= 7 END_REPEAT;",
        "w, r, n : INT;",
    );
    assert_eq!((int(&p, "w"), int(&p, "r"), int(&p, "n")), (0, 1, 8));
}

#[test]
fn if_takes_the_first_true_branch() {
    let mut p = program(
        "IF x < 0 THEN r := -1; ELSIF x = 0 THEN r := 0; ELSIF x < 10 THEN r := 1; ELSE r := 2; END_IF;",
        "x, r : INT;",
    );
    for (x, r) in [(-5, -1), (0, 0), (3, 1), (10, 2), (99, 2)] {
        p.force("x", Value::int(IntType::Int, x).unwrap()).unwrap();
        p.call().unwrap();
        assert_eq!(int(&p, "r"), r, "x = {x}");
    }
}

#[test]
fn case_matches_values_lists_ranges_constants_and_else() {
    let mut p = program(
        "CASE s OF
           1: r := 10;
           2, 3: r := 20;
           4..6, -2: r := 30;
           LAST: r := 40;
         ELSE r := 99;
         END_CASE;",
        "s, r : DINT; END_VAR VAR CONSTANT LAST : DINT := 100;",
    );
    for (s, r) in [
        (1, 10),
        (2, 20),
        (3, 20),
        (4, 30),
        (6, 30),
        (-2, 30),
        (100, 40),
        (7, 99),
        (0, 99),
    ] {
        p.force("s", Value::int(IntType::Dint, s).unwrap()).unwrap();
        p.call().unwrap();
        assert_eq!(int(&p, "r"), r, "s = {s}");
    }
}

const COUNTER_FB: &str = "
FUNCTION_BLOCK counter
VAR_INPUT up : BOOL; step : INT := 1; END_VAR
VAR_OUTPUT n : INT; big : BOOL; END_VAR
VAR_TEMP t : INT := 7; END_VAR
VAR seen_temp : INT; END_VAR
seen_temp := t;       (* always 7: a temp restarts at every call *)
t := 0;
IF up THEN n := n + step; END_IF;
big := n >= 10;
END_FUNCTION_BLOCK
";

#[test]
fn block_calls_assign_inputs_run_and_copy_outputs() {
    let src = format!(
        "{COUNTER_FB}
         PROGRAM p
         VAR c1, c2 : counter; n1 : INT; n1_wide : DINT; b : BOOL; go : BOOL := TRUE; END_VAR
         c1(up := go, step := 4, n => n1_wide, big => b);
         c2(up := NOT go);
         c2();
         n1 := c1.n;
         END_PROGRAM"
    );
    let mut p = parse(&src).unwrap().instantiate("p").unwrap();
    p.call().unwrap();
    assert_eq!(int(&p, "n1"), 4);
    assert_eq!(int(&p, "n1_wide"), 4);
    assert_eq!(int(&p, "c2.n"), 0);
    p.call().unwrap();
    p.call().unwrap();
    assert_eq!(int(&p, "n1"), 12);
    assert_eq!(p.get("b").unwrap(), Value::Bool(true));
    assert_eq!(
        p.get("c1.step").unwrap(),
        Value::int(IntType::Int, 4).unwrap()
    );
    assert_eq!(int(&p, "c1.seen_temp"), 7);
}

#[test]
fn inputs_keep_their_value_between_calls() {
    let src = format!(
        "{COUNTER_FB}
         PROGRAM p VAR c : counter; first : BOOL := TRUE; END_VAR
         IF first THEN c(up := TRUE, step := 3); first := FALSE; ELSE c(); END_IF;
         END_PROGRAM"
    );
    let mut p = parse(&src).unwrap().instantiate("p").unwrap();
    for _ in 0..3 {
        p.call().unwrap();
    }
    assert_eq!(int(&p, "c.n"), 9);
}

#[test]
fn functions_take_positional_or_formal_arguments_and_start_fresh() {
    let p = parse(
        "FUNCTION clamp_add : INT
         VAR_INPUT a : INT; b : INT := 100; END_VAR
         VAR acc : INT; END_VAR
         acc := acc + a + b;        (* acc restarts at 0 on every call *)
         clamp_add := LIMIT(-50, acc, 50);
         IF clamp_add = 50 THEN RETURN; END_IF;
         clamp_add := clamp_add - 1;
         END_FUNCTION
         PROGRAM p VAR r1, r2, r3, r4 : INT; END_VAR
         r1 := clamp_add(1, 2);
         r2 := clamp_add(1, 2);
         r3 := clamp_add(a := 5);
         r4 := clamp_add(clamp_add(3, 4), clamp_add(-20, -20));
         END_PROGRAM",
    )
    .unwrap();
    let mut p = p.instantiate("p").unwrap();
    p.call().unwrap();
    assert_eq!(int(&p, "r1"), 2);
    assert_eq!(int(&p, "r2"), 2);
    assert_eq!(int(&p, "r3"), 50);
    assert_eq!(int(&p, "r4"), -36, "6 + -41 = -35, minus one");
}

#[test]
fn arrays_are_row_major_with_repetition_and_defaults() {
    let p = run(
        "v := D[1, 2]; w := D[2, 0]; x := D[-1, 1];
         i := 2; j := 1; y := D[i - 1, j + 1];
         D[i, j] := 77;",
        "D : ARRAY [-1..2, 0..2] OF INT := [1, 2, 3, 2(4), 3(9), 2()];
         v, w, x, y, i, j : INT;",
    );
    // Rows -1: 1 2 3 | 0: 4 4 9 | 1: 9 9 0 | 2: 0 0 0
    assert_eq!(int(&p, "x"), 2);
    assert_eq!(int(&p, "v"), 0);
    assert_eq!(int(&p, "w"), 0);
    assert_eq!(int(&p, "y"), 0);
    assert_eq!(int(&p, "D[0, 2]"), 9);
    assert_eq!(int(&p, "D[1, 1]"), 9);
    assert_eq!(int(&p, "D[2, 1]"), 77);
    assert_eq!(int(&p, "D[-1,0]"), 1);
}

#[test]
fn an_index_out_of_range_is_a_run_time_error_not_a_clamp() {
    let mut p = program(
        "before := TRUE;\nM[i] := TRUE;\nafter := TRUE;",
        "M : ARRAY [0..3] OF BOOL; i : INT := 4; before, after : BOOL;",
    );
    let err = p.call().unwrap_err();
    assert_eq!(err.line, 4);
    assert_eq!(
        err.fault,
        Fault::IndexOutOfRange {
            index: 4,
            lo: 0,
            hi: 3
        }
    );
    assert_eq!(p.get("before").unwrap(), Value::Bool(true));
    assert_eq!(p.get("after").unwrap(), Value::Bool(false));

    let mut p = program(
        "x := M[u];",
        "M : ARRAY [1..2] OF INT; u : UDINT := 0; x : INT;",
    );
    assert!(matches!(
        p.call().unwrap_err().fault,
        Fault::IndexOutOfRange { index: 0, .. }
    ));
}

#[test]
fn division_or_mod_by_zero_is_a_run_time_error() {
    for op in ["/", "MOD"] {
        let mut p = program(&format!("\n\nr := a {op} b;"), "a : INT := 5; b, r : INT;");
        let err = p.call().unwrap_err();
        assert_eq!((err.fault, err.line), (Fault::DivisionByZero, 5), "{op}");
    }
}

#[test]
fn runaway_loops_hit_the_iteration_guard() {
    let mut p = program("WHILE TRUE DO n := n + 1; END_WHILE;", "n : UDINT;");
    p.set_iteration_limit(1000);
    let err = p.call().unwrap_err();
    assert_eq!(err.fault, Fault::IterationLimit(1000));
    assert_eq!(int(&p, "n"), 1000);

    // On a PLC, FOR up to the type's maximum never ends: the variable wraps.
    let mut p = program(
        "FOR i := 32760 TO 32767 DO n := n + 1; END_FOR;",
        "i : INT; n : UDINT;",
    );
    p.set_iteration_limit(100_000);
    assert_eq!(p.call().unwrap_err().fault, Fault::IterationLimit(100_000));
}
