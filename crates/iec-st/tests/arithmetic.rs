//! Integer arithmetic wraps modulo the type's width, exactly as on a PLC;
//! conversions reinterpret or truncate modulo the target width.

use iec_st::{parse, Value};

/// `a op b` computed by the interpreter in type `ty`, as a mathematical value.
fn compute(ty: &str, a: &str, op: &str, b: &str) -> i128 {
    let src = format!(
        "PROGRAM p VAR a : {ty} := {a}; b : {ty} := {b}; r : {ty}; END_VAR
         r := a {op} b;
         END_PROGRAM"
    );
    let file = parse(&src).unwrap_or_else(|e| panic!("{src}: {e}"));
    let mut p = file.instantiate("p").unwrap();
    p.call().unwrap();
    p.get("r").unwrap().as_i128().unwrap()
}

#[test]
fn each_width_wraps_around() {
    let table: &[(&str, &str, &str, &str, i128)] = &[
        ("SINT", "127", "+", "1", -128),
        ("SINT", "-128", "-", "1", 127),
        ("SINT", "64", "*", "2", -128),
        ("SINT", "-128", "/", "-1", -128),
        ("INT", "32767", "+", "1", -32768),
        ("INT", "300", "*", "300", 24_464),
        ("DINT", "2147483647", "+", "1", -2_147_483_648),
        ("DINT", "100000", "*", "100000", 1_410_065_408),
        ("LINT", "9223372036854775807", "+", "1", i64::MIN as i128),
        ("LINT", "-9223372036854775808", "-", "1", i64::MAX as i128),
        ("USINT", "0", "-", "1", 255),
        ("USINT", "200", "+", "100", 44),
        ("USINT", "16", "*", "16", 0),
        ("UINT", "0", "-", "1", 65_535),
        ("UINT", "65535", "*", "65535", 1),
        ("UDINT", "5", "-", "7", 4_294_967_294),
        ("UDINT", "4294967295", "+", "1", 0),
        ("UDINT", "65536", "*", "65536", 0),
        ("UDINT", "4294967295", "/", "2", 2_147_483_647),
        ("ULINT", "0", "-", "1", u64::MAX as i128),
        (
            "ULINT",
            "18446744073709551615",
            "/",
            "3",
            6_148_914_691_236_517_205,
        ),
        ("ULINT", "18446744073709551615", "MOD", "10", 5),
    ];
    for &(ty, a, op, b, expected) in table {
        assert_eq!(compute(ty, a, op, b), expected, "{ty}: {a} {op} {b}");
    }
}

#[test]
fn division_truncates_toward_zero_and_mod_takes_the_dividends_sign() {
    for &(a, op, b, expected) in &[
        ("-7", "/", "2", -3),
        ("7", "/", "-2", -3),
        ("-7", "MOD", "2", -1),
        ("7", "MOD", "-2", 1),
        ("-8", "/", "2", -4),
    ] {
        assert_eq!(compute("DINT", a, op, b), expected, "{a} {op} {b}");
    }
}

#[test]
fn unsigned_comparisons_use_the_full_range() {
    let file = parse(
        "PROGRAM p
         VAR big : ULINT := 18446744073709551615; one : ULINT := 1;
             gt, lt : BOOL; neg : LINT := -1; slt : BOOL; END_VAR
         gt := big > one; lt := big < one; slt := neg < 1;
         END_PROGRAM",
    )
    .unwrap();
    let mut p = file.instantiate("p").unwrap();
    p.call().unwrap();
    assert_eq!(p.get("gt").unwrap(), Value::Bool(true));
    assert_eq!(p.get("lt").unwrap(), Value::Bool(false));
    assert_eq!(p.get("slt").unwrap(), Value::Bool(true));
}

#[test]
fn bitwise_operators_on_bit_strings_and_shifts() {
    let file = parse(
        "PROGRAM p
         VAR w : WORD := 16#F0F0; b : BYTE := 2#1000_0001;
             a, o, x, n : WORD; l, r, rl, rr : BYTE; big : LWORD := LWORD#16#8000_0000_0000_0001;
             bl : LWORD; END_VAR
         a := w AND 16#0FF0; o := w OR 16#000F; x := w XOR 16#FFFF; n := NOT w;
         l := SHL(b, 1); r := SHR(b, 7); rl := ROL(b, 1); rr := ROR(b, 1);
         bl := ROL(big, 4);
         END_PROGRAM",
    )
    .unwrap();
    let mut p = file.instantiate("p").unwrap();
    p.call().unwrap();
    let get = |n: &str| p.get(n).unwrap().as_i128().unwrap();
    assert_eq!(get("a"), 0x00F0);
    assert_eq!(get("o"), 0xF0FF);
    assert_eq!(get("x"), 0x0F0F);
    assert_eq!(get("n"), 0x0F0F);
    assert_eq!(get("l"), 0x02);
    assert_eq!(get("r"), 0x01);
    assert_eq!(get("rl"), 0x03);
    assert_eq!(get("rr"), 0xC0);
    assert_eq!(get("bl"), 0x18);
}

#[test]
fn conversions_truncate_or_reinterpret_modulo_the_target_width() {
    let table: &[(&str, &str, Value)] = &[
        ("UDINT_TO_DINT(UDINT#16#FFFF_FFFF)", "DINT", int("DINT", -1)),
        (
            "DINT_TO_UDINT(DINT#-1)",
            "UDINT",
            int("UDINT", 4_294_967_295),
        ),
        ("INT_TO_SINT(INT#300)", "SINT", int("SINT", 44)),
        ("INT_TO_SINT(INT#200)", "SINT", int("SINT", -56)),
        ("DINT_TO_INT(DINT#70000)", "INT", int("INT", 4_464)),
        (
            "SINT_TO_UDINT(SINT#-1)",
            "UDINT",
            int("UDINT", 4_294_967_295),
        ),
        (
            "LINT_TO_ULINT(LINT#-1)",
            "ULINT",
            int("ULINT", u64::MAX as i128),
        ),
        (
            "ULINT_TO_LINT(ULINT#18446744073709551615)",
            "LINT",
            int("LINT", -1),
        ),
        ("WORD_TO_INT(WORD#16#FFFF)", "INT", int("INT", -1)),
        ("INT_TO_WORD(INT#-2)", "WORD", int("WORD", 0xFFFE)),
        ("USINT_TO_UINT(USINT#255)", "UINT", int("UINT", 255)),
        ("INT_TO_BOOL(INT#0)", "BOOL", Value::Bool(false)),
        ("INT_TO_BOOL(INT#-5)", "BOOL", Value::Bool(true)),
        ("BYTE_TO_BOOL(BYTE#16#10)", "BOOL", Value::Bool(true)),
        ("BOOL_TO_INT(TRUE)", "INT", int("INT", 1)),
        ("BOOL_TO_ULINT(FALSE)", "ULINT", int("ULINT", 0)),
        ("BOOL_TO_BYTE(TRUE)", "BYTE", int("BYTE", 1)),
    ];
    for (call, ty, expected) in table {
        // Through a variable too, so the run-time path is exercised, not
        // only constant folding.
        let arg = &call[call.find('(').unwrap() + 1..call.len() - 1];
        let from = &call[..call.find("_TO_").unwrap()];
        let conv = &call[..call.find('(').unwrap()];
        let src = format!(
            "PROGRAM p VAR v : {from} := {arg}; folded, run : {ty}; END_VAR
             folded := {call}; run := {conv}(v);
             END_PROGRAM"
        );
        let mut p = parse(&src)
            .unwrap_or_else(|e| panic!("{src}: {e}"))
            .instantiate("p")
            .unwrap();
        p.call().unwrap();
        assert_eq!(p.get("folded").unwrap(), *expected, "{call} folded");
        assert_eq!(p.get("run").unwrap(), *expected, "{call} at run time");
    }
}

fn int(ty: &str, value: i128) -> Value {
    Value::int(iec_st::IntType::from_name(ty).unwrap(), value).unwrap()
}

#[test]
fn literals_take_the_type_of_their_context() {
    let file = parse(
        "PROGRAM p
         VAR s : SINT := SINT#-3; u : USINT := 250; b : BOOL := BOOL#1; f : BOOL := BOOL#FALSE;
             k : SINT := 100 + 100 - 150; big : UDINT := UDINT#16#FFFF_FFFF;
             bt : BYTE := 16#FF; o : UINT := 8#777; bin : USINT := 2#1010_1010;
             r1, r2 : USINT; e : DINT; d : DINT := 1_000_000; END_VAR
         r1 := u + 5;     (* USINT arithmetic: wraps to 255 *)
         r2 := u + 6;     (* wraps to 0 *)
         e := -d * 3 + s; (* SINT widens to DINT *)
         END_PROGRAM",
    )
    .unwrap();
    let mut p = file.instantiate("p").unwrap();
    p.call().unwrap();
    let get = |n: &str| p.get(n).unwrap();
    assert_eq!(get("s"), int("SINT", -3));
    assert_eq!(get("b"), Value::Bool(true));
    assert_eq!(get("f"), Value::Bool(false));
    assert_eq!(get("k"), int("SINT", 50));
    assert_eq!(get("big"), int("UDINT", 4_294_967_295));
    assert_eq!(get("bt"), int("BYTE", 255));
    assert_eq!(get("o"), int("UINT", 511));
    assert_eq!(get("bin"), int("USINT", 170));
    assert_eq!(get("r1"), int("USINT", 255));
    assert_eq!(get("r2"), int("USINT", 0));
    assert_eq!(get("e"), int("DINT", -3_000_003));
}

#[test]
fn standard_functions_abs_min_max_limit_sel() {
    let file = parse(
        "PROGRAM p
         VAR i : INT := -5; m : SINT := -128; u : UDINT := 4000000000;
             a, lo, hi, lim, chosen : INT; am : SINT; um : UDINT; END_VAR
         a := ABS(i); am := ABS(m);
         lo := MIN(i, 3, -7); hi := MAX(i, 3, SINT#9);
         lim := LIMIT(0, i, 10); chosen := SEL(i < 0, 1, 2);
         um := MAX(u, 5);
         END_PROGRAM",
    )
    .unwrap();
    let mut p = file.instantiate("p").unwrap();
    p.call().unwrap();
    let get = |n: &str| p.get(n).unwrap().as_i128().unwrap();
    assert_eq!(get("a"), 5);
    assert_eq!(get("am"), -128, "ABS(SINT -128) wraps like the PLC");
    assert_eq!(get("lo"), -7);
    assert_eq!(get("hi"), 9);
    assert_eq!(get("lim"), 0);
    assert_eq!(get("chosen"), 2);
    assert_eq!(get("um"), 4_000_000_000);
}
