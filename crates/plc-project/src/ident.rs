//! Identifiers generated from free-text names.
//!
//! Names in model and project files are free text. Wherever one becomes an
//! identifier in generated code (a Rust constant, an ST variable, a DOT
//! node id) it goes through [`sanitize`], which maps it to upper-case
//! ASCII letters, digits and `_`. The result can never contain anything
//! that would let a name inject code, and since it is all upper case it can
//! never be a Rust keyword (those are lower case, `Self` aside).
//!
//! Sanitising loses information (`valve-1` and `valve_1` both become
//! `VALVE_1`), so project validation rejects names whose sanitised forms
//! collide (see [`super::validate`]).

/// The upper-case identifier generated for `name`, or `None` when `name`
/// has no ASCII letter or digit (`""`, `"***"`, `"__"`), which would leave
/// an identifier made of underscores only.
///
/// ASCII letters become upper case, ASCII digits stay, every other
/// character (including every non-ASCII character, one `_` per character)
/// becomes `_`, and a leading digit gets a `_` prefix.
///
/// ```
/// use plc_project::ident::sanitize;
/// assert_eq!(sanitize("down_sol").as_deref(), Some("DOWN_SOL"));
/// assert_eq!(sanitize("valve-1").as_deref(), Some("VALVE_1"));
/// assert_eq!(sanitize("2nd stage").as_deref(), Some("_2ND_STAGE"));
/// assert_eq!(sanitize("***"), None);
/// ```
pub fn sanitize(name: &str) -> Option<String> {
    if !name.chars().any(|c| c.is_ascii_alphanumeric()) {
        return None;
    }
    let mut out = String::with_capacity(name.len() + 1);
    if name.starts_with(|c: char| c.is_ascii_digit()) {
        out.push('_');
    }
    out.extend(name.chars().map(|c| {
        if c.is_ascii_alphanumeric() {
            c.to_ascii_uppercase()
        } else {
            '_'
        }
    }));
    Some(out)
}

/// The lower-case item name of a supervisor in generated code (its module
/// and functions in the logic and `match` backends): `sup_` and its
/// identifier ([`sanitize`]) in lower case. Validation keeps identifiers
/// unique, lower-casing keeps them apart, and the prefix keeps them clear
/// of every Rust keyword, so no two supervisors can meet (`fn` and `fn_`
/// give `sup_fn` and `sup_fn_`).
///
/// ```
/// use plc_project::ident::supervisor_item;
/// assert_eq!(supervisor_item("fn"), "sup_fn");
/// assert_eq!(supervisor_item("fn_"), "sup_fn_");
/// assert_eq!(supervisor_item("Self"), "sup_self");
/// assert_eq!(supervisor_item("2nd-stage"), "sup__2nd_stage");
/// ```
pub fn supervisor_item(name: &str) -> String {
    let ident = sanitize(name).unwrap_or_else(|| "X".to_owned());
    format!("sup_{}", ident.to_ascii_lowercase())
}

/// Rust keywords (strict and reserved, all editions) that cannot name a
/// local variable.
const KEYWORDS: &[&str] = &[
    "abstract", "as", "async", "await", "become", "box", "break", "const", "continue", "crate",
    "do", "dyn", "else", "enum", "extern", "false", "final", "fn", "for", "gen", "if", "impl",
    "in", "let", "loop", "macro", "match", "mod", "move", "mut", "override", "priv", "pub", "ref",
    "return", "self", "static", "struct", "super", "trait", "true", "try", "type", "typeof",
    "unsafe", "unsized", "use", "virtual", "where", "while", "yield",
];

/// A lower-case Rust identifier for `name` (functions, modules, locals):
/// ASCII letters and digits kept (lower-cased), everything else `_`; a
/// leading digit gets a `_` prefix, keywords or the bare `_` get a `_`
/// suffix, and an empty name becomes `x`.
///
/// ```
/// use plc_project::ident::snake_ident;
/// assert_eq!(snake_ident("T1.at-13"), "t1_at_13");
/// assert_eq!(snake_ident("type"), "type_");
/// ```
pub fn snake_ident(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        s.push('x');
    }
    if s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    if s == "_" || KEYWORDS.contains(&s.as_str()) {
        s.push('_');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::{sanitize, snake_ident};

    #[test]
    fn snake_identifiers_avoid_keywords_and_leading_digits() {
        assert_eq!(snake_ident("T1.at-13"), "t1_at_13");
        assert_eq!(snake_ident("13th"), "_13th");
        assert_eq!(snake_ident("break"), "break_");
        assert_eq!(snake_ident("Self"), "self_");
        assert_eq!(snake_ident(""), "x");
        assert_eq!(snake_ident("-"), "__");
    }

    #[test]
    fn letters_go_upper_case_and_digits_stay() {
        assert_eq!(sanitize("auto_pb").as_deref(), Some("AUTO_PB"));
        assert_eq!(sanitize("Main2").as_deref(), Some("MAIN2"));
        assert_eq!(sanitize("X").as_deref(), Some("X"));
    }

    #[test]
    fn every_other_character_becomes_one_underscore() {
        assert_eq!(sanitize("a b-c.d").as_deref(), Some("A_B_C_D"));
        // One underscore per character, not per byte.
        assert_eq!(sanitize("ventil_ö").as_deref(), Some("VENTIL__"));
        assert_eq!(sanitize("a\"; }").as_deref(), Some("A____"));
        assert_eq!(sanitize("_x_").as_deref(), Some("_X_"));
    }

    #[test]
    fn a_leading_digit_gets_an_underscore_prefix() {
        assert_eq!(sanitize("1").as_deref(), Some("_1"));
        assert_eq!(sanitize("2nd").as_deref(), Some("_2ND"));
        // A leading underscore before the digit needs no second one.
        assert_eq!(sanitize("_2").as_deref(), Some("_2"));
    }

    #[test]
    fn names_without_a_letter_or_digit_are_not_identifiers() {
        for bad in ["", "_", "__", "***", "-", " ", "ü", "é_ö"] {
            assert_eq!(sanitize(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn output_is_always_an_upper_case_identifier() {
        for name in ["a", "0", "x y", "ÄÖÜ1", "self", "fn", "Self", "😀a"] {
            let id = sanitize(name).unwrap();
            assert!(id
                .chars()
                .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_'));
            assert!(!id.starts_with(|c: char| c.is_ascii_digit()), "{id}");
        }
    }

    #[test]
    fn different_names_can_collide() {
        assert_eq!(sanitize("valve-1"), sanitize("valve_1"));
        assert_eq!(sanitize("Valve"), sanitize("VALVE"));
    }
}
