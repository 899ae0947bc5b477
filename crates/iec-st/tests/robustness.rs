//! Bad input is an error, never a panic: arbitrary token soup and damaged
//! copies of a valid file go through `parse` (and, if accepted, a call).

use proptest::prelude::*;

const VALID: &str = "
FUNCTION_BLOCK fb
VAR_INPUT a : BOOL; n : INT; END_VAR
VAR_OUTPUT q : BOOL; s : SINT; END_VAR
VAR CONSTANT T : ARRAY [0..1, -1..1] OF SINT := [1, 2(-1), 3()]; END_VAR
VAR i : INT; END_VAR
FOR i := 0 TO 1 DO
  IF a AND T[i, n MOD 2] >= 0 THEN s := T[i, n MOD 2]; ELSE EXIT; END_IF;
END_FOR;
CASE n OF 1, 2: q := TRUE; 3..5: q := NOT q; ELSE q := FALSE; END_CASE;
END_FUNCTION_BLOCK
PROGRAM p VAR f : fb; x AT %IX0.0 : BOOL; END_VAR f(a := x, n := 3); END_PROGRAM
";

const WORDS: &[&str] = &[
    "PROGRAM",
    "END_PROGRAM",
    "FUNCTION_BLOCK",
    "END_FUNCTION_BLOCK",
    "FUNCTION",
    "VAR",
    "VAR_INPUT",
    "END_VAR",
    "IF",
    "THEN",
    "ELSE",
    "END_IF",
    "CASE",
    "OF",
    "END_CASE",
    "FOR",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "ARRAY",
    "[",
    "]",
    "..",
    "(",
    ")",
    ":=",
    "=>",
    ":",
    ";",
    ",",
    ".",
    "+",
    "-",
    "*",
    "/",
    "MOD",
    "AND",
    "NOT",
    "<",
    "=",
    "x",
    "y",
    "INT",
    "BOOL",
    "UDINT",
    "0",
    "1",
    "255",
    "16#FF",
    "INT#",
    "-",
    "TRUE",
    "%IX0.1",
    "AT",
    "(*",
    "*)",
    "//",
    "\n",
    "EXIT",
    "RETURN",
    "WHILE",
    "REPEAT",
    "UNTIL",
    "fb",
    "f",
    "CONFIGURATION",
    "END_CONFIGURATION",
    "RESOURCE",
    "END_RESOURCE",
    "ON",
    "TASK",
    "WITH",
    "INTERVAL",
    "PRIORITY",
    "T#10ms",
    "T#1.5",
    "t#1m_",
];

proptest! {
    #[test]
    fn token_soup_never_panics(words in prop::collection::vec(0..WORDS.len(), 0..60)) {
        let src: Vec<&str> = words.iter().map(|&k| WORDS[k]).collect();
        let _ = iec_st::parse(&src.join(" "));
    }

    #[test]
    fn damaged_files_never_panic(start in 0..VALID.len(), len in 0usize..12, insert in 0..WORDS.len()) {
        let end = (start + len).min(VALID.len());
        let src = format!("{}{}{}", &VALID[..start], WORDS[insert], &VALID[end..]);
        if let Ok(file) = iec_st::parse(&src) {
            for (name, kind) in file.pous().map(|(n, k)| (n.to_string(), k)).collect::<Vec<_>>() {
                if kind != iec_st::PouKind::Function {
                    let mut inst = file.instantiate(&name).unwrap();
                    inst.set_iteration_limit(10_000);
                    for _ in 0..3 {
                        let _ = inst.call();
                    }
                }
            }
        }
    }
}

#[test]
fn the_undamaged_file_is_accepted() {
    let file = iec_st::parse(VALID).unwrap();
    let mut p = file.instantiate("p").unwrap();
    p.set("x", true.into()).unwrap();
    p.call().unwrap();
    // T[0, 1] = -1: EXIT at i = 0; n = 3 takes the `NOT q` arm.
    assert_eq!(p.get("f.i").unwrap().as_i64(), Some(0));
    assert_eq!(p.get("f.s").unwrap().as_i64(), Some(0));
    assert_eq!(p.get("f.q").unwrap(), iec_st::Value::Bool(true));
}
