//! Project names as IEC 61131-3 identifiers.
//!
//! Names in project and model files are free text; an IEC identifier is
//! a letter or `_` followed by letters, digits and single underscores,
//! compared without regard to case, and must not be a keyword. The rule
//! (docs/formats.md, "Structured Text export"), applied in declaration
//! order within one namespace:
//!
//! 1. every character other than an ASCII letter, digit or `_` becomes
//!    `_`; runs of `_` become one; leading and trailing `_` go;
//! 2. an empty result becomes `x`; one starting with a digit gets the
//!    prefix `x_`;
//! 3. a result equal, ignoring case, to a reserved word of IEC 61131-3
//!    (keywords, elementary types, standard functions and function
//!    blocks, in any typed form such as `ADD_INT` or `SINT_TO_INT`, and
//!    the library blocks matiec loads such as `PID`) or to a name already
//!    given in the namespace gets the first free suffix `_2`, `_3`, ….
//!
//! Step 3 makes the mapping collision-free by construction; the exporter
//! lists every name it changed in the header of the file.

use std::collections::HashSet;

/// Reserved words of IEC 61131-3 (3rd edition) besides the elementary
/// types ([`ELEMENTARY_TYPES`]): keywords, standard functions and
/// standard function blocks, upper case; and the words matiec (OpenPLC,
/// Beremiz) refuses as variables besides them.
const RESERVED: &[&str] = &[
    // Keywords.
    "ACTION",
    "END_ACTION",
    "ARRAY",
    "OF",
    "AT",
    "CASE",
    "ELSE",
    "END_CASE",
    "CLASS",
    "END_CLASS",
    "CONFIGURATION",
    "END_CONFIGURATION",
    "CONSTANT",
    "DO",
    "ELSIF",
    "EN",
    "ENO",
    "EXIT",
    "EXTENDS",
    "FALSE",
    "F_EDGE",
    "FINAL",
    "FOR",
    "TO",
    "BY",
    "END_FOR",
    "FUNCTION",
    "END_FUNCTION",
    "FUNCTION_BLOCK",
    "END_FUNCTION_BLOCK",
    "IF",
    "THEN",
    "END_IF",
    "IMPLEMENTS",
    "INITIAL_STEP",
    "END_STEP",
    "INTERFACE",
    "END_INTERFACE",
    "INTERNAL",
    "METHOD",
    "END_METHOD",
    "NAMESPACE",
    "END_NAMESPACE",
    "NON_RETAIN",
    "NULL",
    "OVERRIDE",
    "PRIVATE",
    "PROGRAM",
    "END_PROGRAM",
    "PROPERTY",
    "END_PROPERTY",
    "PROTECTED",
    "PUBLIC",
    "READ_ONLY",
    "READ_WRITE",
    "REF",
    "REF_TO",
    "REPEAT",
    "UNTIL",
    "END_REPEAT",
    "RESOURCE",
    "END_RESOURCE",
    "RETAIN",
    "RETURN",
    "R_EDGE",
    "STEP",
    "STRUCT",
    "END_STRUCT",
    "SUPER",
    "TASK",
    "THIS",
    "TRANSITION",
    "END_TRANSITION",
    "TRUE",
    "TYPE",
    "END_TYPE",
    "USING",
    "VAR",
    "END_VAR",
    "VAR_ACCESS",
    "VAR_CONFIG",
    "VAR_EXTERNAL",
    "VAR_GLOBAL",
    "VAR_INPUT",
    "VAR_IN_OUT",
    "VAR_OUTPUT",
    "VAR_TEMP",
    "WHILE",
    "END_WHILE",
    "WITH",
    "CONTINUE",
    "JMP",
    "FROM",
    "AND_THEN",
    "OR_ELSE",
    "VAR_INST",
    "VAR_STAT",
    "UNION",
    "END_UNION",
    "AND",
    "OR",
    "XOR",
    "NOT",
    "MOD",
    "ABSTRACT",
    "PRIORITY",
    "SINGLE",
    "INTERVAL",
    "ON",
    "READ",
    "WRITE",
    "EXPT",
    "ANY",
    "ANY_DERIVED",
    "ANY_ELEMENTARY",
    "ANY_MAGNITUDE",
    "ANY_NUM",
    "ANY_REAL",
    "ANY_INT",
    "ANY_UNSIGNED",
    "ANY_SIGNED",
    "ANY_DURATION",
    "ANY_BIT",
    "ANY_CHARS",
    "ANY_STRING",
    "ANY_CHAR",
    "ANY_DATE",
    "POINTER",
    "REFERENCE",
    "SIZEOF",
    "ADR",
    // Duration and time literal prefixes (`T#5s`, `D#2024-01-01`).
    "T",
    "D",
    "LT",
    "LD",
    // Standard functions.
    "ABS",
    "SQRT",
    "LN",
    "LOG",
    "EXP",
    "SIN",
    "COS",
    "TAN",
    "ASIN",
    "ACOS",
    "ATAN",
    "ATAN2",
    "ADD",
    "SUB",
    "MUL",
    "DIV",
    "MOVE",
    "SHL",
    "SHR",
    "ROL",
    "ROR",
    "GT",
    "GE",
    "EQ",
    "LE",
    "LT",
    "NE",
    "SEL",
    "MAX",
    "MIN",
    "LIMIT",
    "MUX",
    "LEN",
    "LEFT",
    "RIGHT",
    "MID",
    "CONCAT",
    "INSERT",
    "DELETE",
    "REPLACE",
    "FIND",
    "TRUNC",
    // Standard function blocks.
    "SR",
    "RS",
    "R_TRIG",
    "F_TRIG",
    "CTU",
    "CTD",
    "CTUD",
    "TP",
    "TON",
    "TOF",
    // Time arithmetic (2nd edition names, which matiec keeps).
    "ADD_TIME",
    "ADD_TOD_TIME",
    "ADD_DT_TIME",
    "SUB_TIME",
    "SUB_DATE_DATE",
    "SUB_TOD_TIME",
    "SUB_TOD_TOD",
    "SUB_DT_TIME",
    "SUB_DT_DT",
    "MULTIME",
    "DIVTIME",
    "CONCAT_DATE_TOD",
    "CONCAT_DAT_TOD",
    // Function blocks of the library every matiec (OpenPLC, Beremiz)
    // compilation loads.
    "PID",
    "RAMP",
    "RTC",
    "SEMA",
    "INTEGRAL",
    "DERIVATIVE",
    "HYSTERESIS",
];

/// The elementary data types of IEC 61131-3 (3rd edition), reserved
/// themselves and the words typed overloads and conversions are spelled
/// with (`ADD_INT`, `MUX_INT_BOOL`, `SINT_TO_INT`,
/// `DATE_AND_TIME_TO_TIME_OF_DAY`).
const ELEMENTARY_TYPES: &[&str] = &[
    "BOOL",
    "SINT",
    "INT",
    "DINT",
    "LINT",
    "USINT",
    "UINT",
    "UDINT",
    "ULINT",
    "REAL",
    "LREAL",
    "TIME",
    "LTIME",
    "DATE",
    "LDATE",
    "TIME_OF_DAY",
    "TOD",
    "LTIME_OF_DAY",
    "LTOD",
    "DATE_AND_TIME",
    "DT",
    "LDATE_AND_TIME",
    "LDT",
    "STRING",
    "WSTRING",
    "CHAR",
    "WCHAR",
    "BYTE",
    "WORD",
    "DWORD",
    "LWORD",
];

/// Whether `s` (upper case) is one or more of [`ELEMENTARY_TYPES`] or
/// `BCD` (the BCD forms of conversions, `UINT_TO_BCD_WORD`) joined by
/// `_`.
fn is_type_sequence(s: &str) -> bool {
    ELEMENTARY_TYPES
        .iter()
        .chain(&["BCD"])
        .any(|t| match s.strip_prefix(t) {
            Some("") => true,
            Some(rest) => rest
                .strip_prefix('_')
                .is_some_and(|rest| !rest.is_empty() && is_type_sequence(rest)),
            None => false,
        })
}

/// Whether `upper` names a typed overload of a standard function or
/// function block (`ADD_INT`, `MUX_INT_BOOL`, `CTU_DINT`, `TRUNC_INT`),
/// or a conversion (`SINT_TO_INT`, `TO_INT`, `BYTE_BCD_TO_UINT`): names a
/// PLC compiler knows as functions even where the standard lists only
/// the generic one (matiec refuses every one of them as a variable).
fn is_typed_function(upper: &str) -> bool {
    if let Some(to) = upper.strip_prefix("TO_") {
        if is_type_sequence(to) {
            return true;
        }
    }
    let mut from = 0;
    while let Some(k) = upper[from..].find("_TO_") {
        let (a, b) = (&upper[..from + k], &upper[from + k + 4..]);
        if is_type_sequence(a) && is_type_sequence(b) {
            return true;
        }
        from += k + 1;
    }
    RESERVED.iter().any(|f| {
        upper
            .strip_prefix(f)
            .and_then(|rest| rest.strip_prefix('_'))
            .is_some_and(is_type_sequence)
    })
}

/// One namespace of IEC identifiers: names given so far, and the
/// changes made.
#[derive(Debug, Default, Clone)]
pub struct Namer {
    taken: HashSet<String>,
    /// (free-text name, identifier) for every name that changed.
    pub changed: Vec<(String, String)>,
}

/// `name` after steps 1 and 2 of the rule.
pub fn identifier(name: &str) -> String {
    let mut out = String::with_capacity(name.len() + 2);
    for c in name.chars() {
        let c = if c.is_ascii_alphanumeric() { c } else { '_' };
        if !(c == '_' && (out.is_empty() || out.ends_with('_'))) {
            out.push(c);
        }
    }
    while out.ends_with('_') {
        out.pop();
    }
    if out.is_empty() {
        out.push('x');
    } else if out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert_str(0, "x_");
    }
    out
}

/// Whether `id` (any case) is a reserved word of IEC 61131-3, a
/// standard function or function block in any typed form, or a
/// conversion function.
pub fn is_reserved(id: &str) -> bool {
    let upper = id.to_ascii_uppercase();
    RESERVED.contains(&upper.as_str())
        || ELEMENTARY_TYPES.contains(&upper.as_str())
        || is_typed_function(&upper)
}

impl Namer {
    /// An empty namespace.
    pub fn new() -> Namer {
        Namer::default()
    }

    /// Reserves an identifier of the exporter's own (already valid).
    pub fn reserve(&mut self, id: &str) {
        self.taken.insert(id.to_ascii_uppercase());
    }

    /// The identifier for free-text `name` (with `prefix`, itself a valid
    /// identifier start such as `EV_`, put before it), unique in the
    /// namespace; a change is remembered in [`Namer::changed`] when
    /// `name` is a project name (no prefix).
    pub fn name(&mut self, prefix: &str, name: &str) -> String {
        let base = format!("{prefix}{}", identifier(name));
        let base = if prefix.is_empty() {
            base
        } else {
            identifier(&base)
        };
        let mut id = base.clone();
        let mut k = 2;
        while is_reserved(&id) || self.taken.contains(&id.to_ascii_uppercase()) {
            id = format!("{base}_{k}");
            k += 1;
        }
        self.taken.insert(id.to_ascii_uppercase());
        if prefix.is_empty() && id != name {
            self.changed.push((name.to_owned(), id.clone()));
        }
        id
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An IEC identifier: letter or `_` then letters, digits and single
    /// underscores, no trailing `_`.
    fn valid(id: &str) -> bool {
        let b = id.as_bytes();
        !b.is_empty()
            && (b[0].is_ascii_alphabetic() || b[0] == b'_')
            && b.iter().all(|c| c.is_ascii_alphanumeric() || *c == b'_')
            && !id.contains("__")
            && !id.ends_with('_')
    }

    #[test]
    fn free_text_becomes_a_valid_identifier() {
        assert_eq!(identifier("part-in"), "part_in");
        assert_eq!(identifier("__a  b__"), "a_b");
        assert_eq!(identifier("2nd stage"), "x_2nd_stage");
        assert_eq!(identifier("***"), "x");
        assert_eq!(identifier("Ölventil"), "lventil");
        for name in ["a", "x__y", "_", "9", "é", "a.b.c", "END_IF", "-"] {
            let mut n = Namer::new();
            let id = n.name("", name);
            assert!(valid(&id), "{name:?} -> {id:?}");
        }
    }

    #[test]
    fn reserved_words_and_case_insensitive_repeats_get_suffixes() {
        let mut n = Namer::new();
        n.reserve("FAULT");
        assert_eq!(n.name("", "fault"), "fault_2");
        assert_eq!(n.name("", "IF"), "IF_2");
        assert_eq!(n.name("", "ton"), "ton_2");
        assert_eq!(n.name("", "valve-1"), "valve_1");
        assert_eq!(n.name("", "valve_1"), "valve_1_2");
        assert_eq!(n.name("", "Valve 1"), "Valve_1_3");
        assert_eq!(n.name("", "valve_1_2"), "valve_1_2_2");
        assert_eq!(n.name("EV_", "go"), "EV_go");
        assert_eq!(n.name("EV_", "_go"), "EV_go_2");
        assert_eq!(n.changed.len(), 7, "{:?}", n.changed);
    }

    /// Every word here is refused as a variable name by matiec (OpenPLC's
    /// and Beremiz's compiler, measured) or by blark (3rd edition).
    #[test]
    fn compiler_keywords_and_typed_functions_are_reserved() {
        for word in [
            "continue",
            "jmp",
            "and_then",
            "or_else",
            "var_inst",
            "var_stat",
            "union",
            "end_union",
            "from",
            "add_int",
            "mux_dint_bool",
            "sint_to_int",
            "date_and_time_to_time_of_day",
            "byte_bcd_to_uint",
            "uint_to_bcd_word",
            "udint_to_bcd",
            "bcd_to_usint",
            "to_int",
            "ctu_dint",
            "trunc_int",
            "sub_dt_dt",
            "divtime_real",
            "pid",
            "hysteresis",
        ] {
            assert!(is_reserved(word), "{word}");
        }
        for word in [
            "int_to",
            "add_x",
            "valve_to_tank",
            "x_to_int",
            "integral2",
            "tod_",
        ] {
            assert!(!is_reserved(word), "{word}");
        }
    }

    #[test]
    fn no_two_names_meet_whatever_they_are() {
        let names = [
            "a",
            "A",
            "a_",
            "_a",
            "a__",
            "a-",
            "a_2",
            "A_2",
            "a 2",
            "x_",
            "",
            "_",
            "1",
            "x_1",
            "END_VAR",
            "end_var",
            "end_var_2",
        ];
        let mut n = Namer::new();
        let ids: Vec<String> = names.iter().map(|s| n.name("", s)).collect();
        let upper: HashSet<String> = ids.iter().map(|s| s.to_ascii_uppercase()).collect();
        assert_eq!(upper.len(), ids.len(), "{ids:?}");
        assert!(
            ids.iter().all(|id| valid(id) && !is_reserved(id)),
            "{ids:?}"
        );
    }
}
