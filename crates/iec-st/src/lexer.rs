//! Tokens of Structured Text: identifiers and keywords (any case), integer
//! literals (decimal, based, with `_` separators), typed-literal prefixes,
//! duration literals (`T#1m30s`), directly represented variables and
//! operators. Comments `(* *)`, `//` and
//! pragmas `{ }` are skipped.

use crate::error::{Error, ErrorKind, Pos};

/// A reserved word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kw {
    Program,
    EndProgram,
    FunctionBlock,
    EndFunctionBlock,
    Function,
    EndFunction,
    Var,
    VarInput,
    VarOutput,
    VarInOut,
    VarTemp,
    VarGlobal,
    VarExternal,
    EndVar,
    Constant,
    Retain,
    NonRetain,
    At,
    Array,
    Of,
    If,
    Then,
    Elsif,
    Else,
    EndIf,
    Case,
    EndCase,
    For,
    To,
    By,
    Do,
    EndFor,
    While,
    EndWhile,
    Repeat,
    Until,
    EndRepeat,
    Exit,
    Return,
    And,
    Or,
    Xor,
    Not,
    Mod,
    True,
    False,
    Type,
    EndType,
    Struct,
    EndStruct,
    Configuration,
    EndConfiguration,
    Resource,
    EndResource,
    On,
    Task,
    With,
    Interval,
    Priority,
    Single,
}

const KEYWORDS: &[(&str, Kw)] = &[
    ("PROGRAM", Kw::Program),
    ("END_PROGRAM", Kw::EndProgram),
    ("FUNCTION_BLOCK", Kw::FunctionBlock),
    ("END_FUNCTION_BLOCK", Kw::EndFunctionBlock),
    ("FUNCTION", Kw::Function),
    ("END_FUNCTION", Kw::EndFunction),
    ("VAR", Kw::Var),
    ("VAR_INPUT", Kw::VarInput),
    ("VAR_OUTPUT", Kw::VarOutput),
    ("VAR_IN_OUT", Kw::VarInOut),
    ("VAR_TEMP", Kw::VarTemp),
    ("VAR_GLOBAL", Kw::VarGlobal),
    ("VAR_EXTERNAL", Kw::VarExternal),
    ("END_VAR", Kw::EndVar),
    ("CONSTANT", Kw::Constant),
    ("RETAIN", Kw::Retain),
    ("NON_RETAIN", Kw::NonRetain),
    ("AT", Kw::At),
    ("ARRAY", Kw::Array),
    ("OF", Kw::Of),
    ("IF", Kw::If),
    ("THEN", Kw::Then),
    ("ELSIF", Kw::Elsif),
    ("ELSE", Kw::Else),
    ("END_IF", Kw::EndIf),
    ("CASE", Kw::Case),
    ("END_CASE", Kw::EndCase),
    ("FOR", Kw::For),
    ("TO", Kw::To),
    ("BY", Kw::By),
    ("DO", Kw::Do),
    ("END_FOR", Kw::EndFor),
    ("WHILE", Kw::While),
    ("END_WHILE", Kw::EndWhile),
    ("REPEAT", Kw::Repeat),
    ("UNTIL", Kw::Until),
    ("END_REPEAT", Kw::EndRepeat),
    ("EXIT", Kw::Exit),
    ("RETURN", Kw::Return),
    ("AND", Kw::And),
    ("OR", Kw::Or),
    ("XOR", Kw::Xor),
    ("NOT", Kw::Not),
    ("MOD", Kw::Mod),
    ("TRUE", Kw::True),
    ("FALSE", Kw::False),
    ("TYPE", Kw::Type),
    ("END_TYPE", Kw::EndType),
    ("STRUCT", Kw::Struct),
    ("END_STRUCT", Kw::EndStruct),
    ("CONFIGURATION", Kw::Configuration),
    ("END_CONFIGURATION", Kw::EndConfiguration),
    ("RESOURCE", Kw::Resource),
    ("END_RESOURCE", Kw::EndResource),
    ("ON", Kw::On),
    ("TASK", Kw::Task),
    ("WITH", Kw::With),
    ("INTERVAL", Kw::Interval),
    ("PRIORITY", Kw::Priority),
    ("SINGLE", Kw::Single),
];

impl Kw {
    fn lookup(word: &str) -> Option<Kw> {
        KEYWORDS
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(word))
            .map(|&(_, kw)| kw)
    }

    /// The keyword as written in the standard.
    pub(crate) fn text(self) -> &'static str {
        KEYWORDS
            .iter()
            .find(|&&(_, kw)| kw == self)
            .map_or("?", |&(k, _)| k)
    }
}

/// One token.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Tok {
    /// An identifier, as written.
    Ident(String),
    Kw(Kw),
    /// An unsigned integer literal (a sign is a separate token).
    Int(u128),
    /// `NAME#` before a typed literal, name as written.
    TypePrefix(String),
    /// A duration literal (`T#...`, `TIME#...`) in milliseconds.
    Time(i64),
    /// A directly represented variable such as `%IX0.3`, upper case.
    Address(String),
    Assign,
    Arrow,
    Colon,
    Semi,
    Comma,
    Dot,
    DotDot,
    LParen,
    RParen,
    LBracket,
    RBracket,
    Plus,
    Minus,
    Star,
    Power,
    Slash,
    Amp,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Eof,
}

impl Tok {
    /// How the token reads in an error message.
    pub(crate) fn describe(&self) -> String {
        match self {
            Tok::Ident(s) => format!("identifier `{s}`"),
            Tok::Kw(k) => format!("`{}`", k.text()),
            Tok::Int(v) => format!("literal `{v}`"),
            Tok::TypePrefix(s) => format!("`{s}#`"),
            Tok::Time(ms) => format!("duration `T#{ms}ms`"),
            Tok::Address(s) => format!("address `{s}`"),
            Tok::Eof => "end of file".to_string(),
            other => format!("`{}`", other.symbol()),
        }
    }

    fn symbol(&self) -> &'static str {
        match self {
            Tok::Assign => ":=",
            Tok::Arrow => "=>",
            Tok::Colon => ":",
            Tok::Semi => ";",
            Tok::Comma => ",",
            Tok::Dot => ".",
            Tok::DotDot => "..",
            Tok::LParen => "(",
            Tok::RParen => ")",
            Tok::LBracket => "[",
            Tok::RBracket => "]",
            Tok::Plus => "+",
            Tok::Minus => "-",
            Tok::Star => "*",
            Tok::Power => "**",
            Tok::Slash => "/",
            Tok::Amp => "&",
            Tok::Eq => "=",
            Tok::Ne => "<>",
            Tok::Lt => "<",
            Tok::Le => "<=",
            Tok::Gt => ">",
            Tok::Ge => ">=",
            _ => "?",
        }
    }
}

/// A token and where it starts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Token {
    pub tok: Tok,
    pub pos: Pos,
}

/// Splits `source` into tokens, ending with [`Tok::Eof`].
pub(crate) fn tokenize(source: &str) -> Result<Vec<Token>, Error> {
    let mut lexer = Lexer {
        src: source.as_bytes(),
        at: 0,
        line: 1,
        line_start: 0,
        tokens: Vec::new(),
    };
    lexer.run()?;
    Ok(lexer.tokens)
}

struct Lexer<'a> {
    src: &'a [u8],
    at: usize,
    line: u32,
    line_start: usize,
    tokens: Vec<Token>,
}

impl Lexer<'_> {
    fn pos(&self) -> Pos {
        Pos {
            line: self.line,
            column: (self.at - self.line_start + 1) as u32,
        }
    }

    fn peek(&self, ahead: usize) -> u8 {
        self.src.get(self.at + ahead).copied().unwrap_or(0)
    }

    fn bump(&mut self) {
        if self.peek(0) == b'\n' {
            self.line += 1;
            self.line_start = self.at + 1;
        }
        self.at += 1;
    }

    fn error(&self, pos: Pos, message: impl Into<String>) -> Error {
        Error::at(ErrorKind::Lexical, pos, message)
    }

    fn run(&mut self) -> Result<(), Error> {
        loop {
            self.skip_trivia()?;
            let pos = self.pos();
            let c = self.peek(0);
            if self.at >= self.src.len() {
                self.tokens.push(Token { tok: Tok::Eof, pos });
                return Ok(());
            }
            let tok = if c.is_ascii_alphabetic() || c == b'_' {
                self.word(pos)?
            } else if c.is_ascii_digit() {
                Tok::Int(self.number(pos)?)
            } else if c == b'%' {
                self.address(pos)?
            } else {
                self.symbol(pos)?
            };
            self.tokens.push(Token { tok, pos });
        }
    }

    fn skip_trivia(&mut self) -> Result<(), Error> {
        loop {
            let c = self.peek(0);
            if c.is_ascii_whitespace() {
                self.bump();
            } else if c == b'(' && self.peek(1) == b'*' {
                let pos = self.pos();
                self.bump();
                self.bump();
                while !(self.peek(0) == b'*' && self.peek(1) == b')') {
                    if self.at >= self.src.len() {
                        return Err(self.error(pos, "comment `(*` is never closed"));
                    }
                    self.bump();
                }
                self.bump();
                self.bump();
            } else if c == b'/' && self.peek(1) == b'/' {
                while self.at < self.src.len() && self.peek(0) != b'\n' {
                    self.bump();
                }
            } else if c == b'{' {
                let pos = self.pos();
                while self.peek(0) != b'}' {
                    if self.at >= self.src.len() {
                        return Err(self.error(pos, "pragma `{` is never closed"));
                    }
                    self.bump();
                }
                self.bump();
            } else {
                return Ok(());
            }
        }
    }

    /// An identifier or keyword; `NAME#` becomes a typed-literal prefix.
    fn word(&mut self, pos: Pos) -> Result<Tok, Error> {
        let start = self.at;
        while self.peek(0).is_ascii_alphanumeric() || self.peek(0) == b'_' {
            self.bump();
        }
        let text = std::str::from_utf8(&self.src[start..self.at]).expect("ASCII");
        let bytes = text.as_bytes();
        let well_formed = !(bytes.windows(2).any(|w| w == b"__") || bytes.ends_with(b"_"));
        if !well_formed {
            return Err(self.error(
                pos,
                format!(
                    "`{text}` is no identifier: underscores must be single and followed by a letter or digit"
                ),
            ));
        }
        if self.peek(0) == b'#' {
            if ["T", "TIME"].iter().any(|p| p.eq_ignore_ascii_case(text)) {
                self.bump();
                return Ok(Tok::Time(self.duration(pos)?));
            }
            const OTHER_TIME_PREFIXES: [&str; 8] = [
                "LT",
                "LTIME",
                "D",
                "DATE",
                "TOD",
                "TIME_OF_DAY",
                "DT",
                "DATE_AND_TIME",
            ];
            if OTHER_TIME_PREFIXES
                .iter()
                .any(|p| p.eq_ignore_ascii_case(text))
            {
                return Err(Error::at(
                    ErrorKind::Unsupported,
                    pos,
                    format!("`{text}#` literals (LTIME, dates and times of day) are not supported"),
                ));
            }
            self.bump();
            return Ok(Tok::TypePrefix(text.to_string()));
        }
        Ok(match Kw::lookup(text) {
            Some(kw) => Tok::Kw(kw),
            None => Tok::Ident(text.to_string()),
        })
    }

    /// Digits in `radix` with single `_` separators between them.
    fn digits(&mut self, radix: u32, pos: Pos) -> Result<u128, Error> {
        let mut value: u128 = 0;
        let mut any = false;
        let mut last_underscore = false;
        loop {
            let c = self.peek(0);
            if c == b'_' {
                if !any || last_underscore {
                    return Err(self.error(pos, "misplaced `_` in an integer literal"));
                }
                last_underscore = true;
            } else if let Some(d) = (c as char).to_digit(radix) {
                value = value
                    .checked_mul(u128::from(radix))
                    .and_then(|v| v.checked_add(u128::from(d)))
                    .ok_or_else(|| self.error(pos, "integer literal too large"))?;
                any = true;
                last_underscore = false;
            } else if c.is_ascii_alphanumeric() {
                return Err(self.error(pos, format!("`{}` is no digit in base {radix}", c as char)));
            } else {
                break;
            }
            self.bump();
        }
        if !any || last_underscore {
            return Err(self.error(pos, "integer literal without digits or ending in `_`"));
        }
        Ok(value)
    }

    fn number(&mut self, pos: Pos) -> Result<u128, Error> {
        let start = self.at;
        while self.peek(0).is_ascii_digit() || self.peek(0) == b'_' {
            self.bump();
        }
        if self.peek(0) == b'#' {
            let base = &self.src[start..self.at];
            let radix = match base {
                b"2" => 2,
                b"8" => 8,
                b"16" => 16,
                _ => {
                    return Err(
                        self.error(pos, "a based literal's base must be 2, 8 or 16".to_string())
                    )
                }
            };
            self.bump();
            return self.digits(radix, pos);
        }
        if self.peek(0) == b'.' && self.peek(1).is_ascii_digit() {
            return Err(Error::at(
                ErrorKind::Unsupported,
                pos,
                "REAL literals are not supported",
            ));
        }
        // Digits never span lines, so rewinding keeps the line bookkeeping.
        self.at = start;
        self.digits(10, pos)
    }

    /// The interval after `T#`: `[+|-]` then components such as `1d`,
    /// `2h`, `30m`, `15s`, `500ms` (also `us`, `ns`) in strictly
    /// decreasing units, optionally joined by `_`; the last may have a
    /// fraction (`1.5s`). IEC 61131-3 3rd edition, duration literals. The
    /// result is in milliseconds and must be a whole number of them.
    fn duration(&mut self, pos: Pos) -> Result<i64, Error> {
        const UNITS_NS: [(&str, i128); 7] = [
            ("d", 86_400_000_000_000),
            ("h", 3_600_000_000_000),
            ("m", 60_000_000_000),
            ("s", 1_000_000_000),
            ("ms", 1_000_000),
            ("us", 1_000),
            ("ns", 1),
        ];
        /// Fraction digits kept exact; more cannot matter at 1 ns.
        const MAX_FRACTION_DIGITS: u32 = 18;
        let negative = self.peek(0) == b'-';
        if matches!(self.peek(0), b'-' | b'+') {
            self.bump();
        }
        let too_large = || Error::at(ErrorKind::Range, pos, "duration literal too large");
        // Nanoseconds, scaled by 10^digits of the fraction (if any).
        let mut total_ns: i128 = 0;
        let mut scale: i128 = 1;
        let mut smallest_unit = usize::MAX;
        let mut fraction_seen = false;
        loop {
            if !self.peek(0).is_ascii_digit() {
                return Err(self.error(
                    pos,
                    "a duration needs a number with a unit (d, h, m, s, ms, us, ns)",
                ));
            }
            if fraction_seen {
                return Err(self.error(pos, "only a duration's last component may have a fraction"));
            }
            let whole = self.duration_digits(pos)?;
            let (mut fraction, mut fraction_scale) = (0i128, 1i128);
            if self.peek(0) == b'.' && self.peek(1).is_ascii_digit() {
                self.bump();
                let mut digits = 0;
                while self.peek(0).is_ascii_digit() {
                    digits += 1;
                    if digits > MAX_FRACTION_DIGITS {
                        return Err(self.error(pos, "too many fraction digits in a duration"));
                    }
                    fraction = fraction * 10 + i128::from(self.peek(0) - b'0');
                    fraction_scale *= 10;
                    self.bump();
                }
                fraction_seen = true;
            }
            let start = self.at;
            while self.peek(0).is_ascii_alphabetic() {
                self.bump();
            }
            let unit = std::str::from_utf8(&self.src[start..self.at])
                .expect("ASCII")
                .to_ascii_lowercase();
            let Some(rank) = UNITS_NS.iter().position(|(u, _)| *u == unit) else {
                let found = if unit.is_empty() {
                    "a number without a unit".to_string()
                } else {
                    format!("`{unit}`")
                };
                return Err(self.error(
                    pos,
                    format!("{found} in a duration: the units are d, h, m, s, ms, us, ns"),
                ));
            };
            if smallest_unit != usize::MAX && rank <= smallest_unit {
                return Err(self.error(
                    pos,
                    "a duration's units must go from larger to smaller, each once",
                ));
            }
            smallest_unit = rank;
            let unit_ns = UNITS_NS[rank].1;
            total_ns = whole
                .checked_mul(unit_ns)
                .and_then(|w| w.checked_mul(fraction_scale))
                .and_then(|w| w.checked_add(fraction * unit_ns))
                .and_then(|c| total_ns.checked_mul(fraction_scale)?.checked_add(c))
                .ok_or_else(too_large)?;
            scale *= fraction_scale;
            if self.peek(0) == b'_' && self.peek(1).is_ascii_digit() {
                self.bump();
            } else if !self.peek(0).is_ascii_digit() {
                break;
            }
        }
        if self.peek(0) == b'_' || self.peek(0).is_ascii_alphanumeric() {
            return Err(self.error(pos, "malformed duration literal"));
        }
        let per_ms = scale * 1_000_000;
        if total_ns % per_ms != 0 {
            return Err(Error::at(
                ErrorKind::Unsupported,
                pos,
                "a duration finer than a millisecond is not supported",
            ));
        }
        let ms = i64::try_from(total_ns / per_ms).map_err(|_| too_large())?;
        Ok(if negative { -ms } else { ms })
    }

    /// A duration component's digits, with single `_` between them.
    fn duration_digits(&mut self, pos: Pos) -> Result<i128, Error> {
        let mut value: i128 = 0;
        loop {
            value = value
                .checked_mul(10)
                .and_then(|v| v.checked_add(i128::from(self.peek(0) - b'0')))
                .ok_or_else(|| Error::at(ErrorKind::Range, pos, "duration literal too large"))?;
            self.bump();
            if self.peek(0) == b'_' {
                if !self.peek(1).is_ascii_digit() {
                    return Err(self.error(pos, "misplaced `_` in a duration"));
                }
                self.bump();
            } else if !self.peek(0).is_ascii_digit() {
                return Ok(value);
            }
        }
    }

    fn address(&mut self, pos: Pos) -> Result<Tok, Error> {
        let start = self.at;
        self.bump();
        while self.peek(0).is_ascii_alphanumeric() || self.peek(0) == b'.' || self.peek(0) == b'*' {
            self.bump();
        }
        let text = std::str::from_utf8(&self.src[start..self.at])
            .expect("ASCII")
            .to_ascii_uppercase();
        let rest = &text[1..];
        let area_ok = rest.starts_with(['I', 'Q', 'M']);
        let body = rest.get(1..).unwrap_or("");
        let body = body.strip_prefix(['X', 'B', 'W', 'D', 'L']).unwrap_or(body);
        // `%I*`, `%Q*`: a location left to the configuration (IEC
        // 61131-3, partly specified addresses).
        let numbers_ok = rest.get(1..) == Some("*")
            || !body.is_empty()
                && body
                    .split('.')
                    .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()));
        if !area_ok || !numbers_ok {
            return Err(self.error(pos, format!("`{text}` is no directly represented variable")));
        }
        Ok(Tok::Address(text))
    }

    fn symbol(&mut self, pos: Pos) -> Result<Tok, Error> {
        let c = self.peek(0);
        let next = self.peek(1);
        let (tok, len) = match (c, next) {
            (b':', b'=') => (Tok::Assign, 2),
            (b'=', b'>') => (Tok::Arrow, 2),
            (b'.', b'.') => (Tok::DotDot, 2),
            (b'*', b'*') => (Tok::Power, 2),
            (b'<', b'>') => (Tok::Ne, 2),
            (b'<', b'=') => (Tok::Le, 2),
            (b'>', b'=') => (Tok::Ge, 2),
            (b':', _) => (Tok::Colon, 1),
            (b';', _) => (Tok::Semi, 1),
            (b',', _) => (Tok::Comma, 1),
            (b'.', _) => (Tok::Dot, 1),
            (b'(', _) => (Tok::LParen, 1),
            (b')', _) => (Tok::RParen, 1),
            (b'[', _) => (Tok::LBracket, 1),
            (b']', _) => (Tok::RBracket, 1),
            (b'+', _) => (Tok::Plus, 1),
            (b'-', _) => (Tok::Minus, 1),
            (b'*', _) => (Tok::Star, 1),
            (b'/', _) => (Tok::Slash, 1),
            (b'&', _) => (Tok::Amp, 1),
            (b'=', _) => (Tok::Eq, 1),
            (b'<', _) => (Tok::Lt, 1),
            (b'>', _) => (Tok::Gt, 1),
            (b'\'' | b'"', _) => {
                return Err(Error::at(
                    ErrorKind::Unsupported,
                    pos,
                    "string literals are not supported",
                ))
            }
            _ => {
                let shown = std::str::from_utf8(&self.src[self.at..])
                    .ok()
                    .and_then(|s| s.chars().next())
                    .unwrap_or(c as char);
                return Err(self.error(pos, format!("unexpected character `{shown}`")));
            }
        };
        for _ in 0..len {
            self.bump();
        }
        Ok(tok)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(src: &str) -> Vec<Tok> {
        tokenize(src).unwrap().into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn keywords_are_case_insensitive_and_identifiers_keep_their_spelling() {
        assert_eq!(
            toks("If end_IF Motor_1"),
            [
                Tok::Kw(Kw::If),
                Tok::Kw(Kw::EndIf),
                Tok::Ident("Motor_1".into()),
                Tok::Eof
            ]
        );
    }

    #[test]
    fn integer_literals_decimal_based_and_separated() {
        assert_eq!(
            toks("1_000 2#1010 8#17 16#FF_ff"),
            [
                Tok::Int(1000),
                Tok::Int(10),
                Tok::Int(15),
                Tok::Int(0xFFFF),
                Tok::Eof
            ]
        );
    }

    #[test]
    fn typed_literal_prefixes_split_from_their_value() {
        assert_eq!(
            toks("UDINT#16#FFFF_FFFF SINT#-3"),
            [
                Tok::TypePrefix("UDINT".into()),
                Tok::Int(0xFFFF_FFFF),
                Tok::TypePrefix("SINT".into()),
                Tok::Minus,
                Tok::Int(3),
                Tok::Eof
            ]
        );
    }

    #[test]
    fn comments_and_pragmas_are_skipped_and_lines_counted() {
        let tokens = tokenize("(* a\n comment *) x // rest\n{attribute 'x'} y").unwrap();
        assert_eq!(tokens[0].tok, Tok::Ident("x".into()));
        assert_eq!(
            tokens[0].pos,
            Pos {
                line: 2,
                column: 13
            }
        );
        assert_eq!(tokens[1].tok, Tok::Ident("y".into()));
        assert_eq!(tokens[1].pos.line, 3);
    }

    #[test]
    fn operators_longest_match_first() {
        assert_eq!(
            toks(":= => .. <> <= >= < > = : ."),
            [
                Tok::Assign,
                Tok::Arrow,
                Tok::DotDot,
                Tok::Ne,
                Tok::Le,
                Tok::Ge,
                Tok::Lt,
                Tok::Gt,
                Tok::Eq,
                Tok::Colon,
                Tok::Dot,
                Tok::Eof
            ]
        );
        assert_eq!(
            toks("1..5"),
            [Tok::Int(1), Tok::DotDot, Tok::Int(5), Tok::Eof]
        );
    }

    #[test]
    fn addresses_are_one_token() {
        assert_eq!(
            toks("%ix0.3 %QW12 %i*"),
            [
                Tok::Address("%IX0.3".into()),
                Tok::Address("%QW12".into()),
                Tok::Address("%I*".into()),
                Tok::Eof
            ]
        );
    }

    #[test]
    fn duration_literals_are_exact_milliseconds() {
        for (src, ms) in [
            ("T#10ms", 10),
            ("TIME#1s", 1_000),
            ("T#1m30s500ms", 90_500),
            ("t#2h", 7_200_000),
            ("time#1d_2h_3m_4s_5ms", 93_784_005),
            ("T#1_000ms", 1_000),
            ("T#1.5s", 1_500),
            ("T#0.25m", 15_000),
            ("T#1h30.5s", 3_630_500),
            ("T#2000us", 2),
            ("T#3000000ns", 3),
            ("T#-14ms", -14),
            ("T#+7S", 7_000),
            ("T#0ms", 0),
        ] {
            assert_eq!(toks(src), [Tok::Time(ms), Tok::Eof], "{src}");
        }
        assert_eq!(
            toks("(INTERVAL := T#10ms, PRIORITY := 0)"),
            [
                Tok::LParen,
                Tok::Kw(Kw::Interval),
                Tok::Assign,
                Tok::Time(10),
                Tok::Comma,
                Tok::Kw(Kw::Priority),
                Tok::Assign,
                Tok::Int(0),
                Tok::RParen,
                Tok::Eof
            ]
        );
    }

    #[test]
    fn malformed_durations_are_errors_at_the_literal() {
        for (src, kind, needle) in [
            ("x := T#10;", ErrorKind::Lexical, "without a unit"),
            ("x := T#10min;", ErrorKind::Lexical, "`min`"),
            ("x := T#;", ErrorKind::Lexical, "needs a number"),
            ("x := T#1s1m;", ErrorKind::Lexical, "larger to smaller"),
            ("x := T#1s2s;", ErrorKind::Lexical, "larger to smaller"),
            ("x := T#1.5m30s;", ErrorKind::Lexical, "last component"),
            ("x := T#1s_;", ErrorKind::Lexical, "malformed"),
            ("x := T#1__0ms;", ErrorKind::Lexical, "misplaced `_`"),
            ("x := T#1_ms;", ErrorKind::Lexical, "misplaced `_`"),
            (
                "x := T#1500us;",
                ErrorKind::Unsupported,
                "finer than a millisecond",
            ),
            (
                "x := T#1.0005s;",
                ErrorKind::Unsupported,
                "finer than a millisecond",
            ),
            (
                "x := T#999999999999999999999999999d;",
                ErrorKind::Range,
                "too large",
            ),
            ("x := LTIME#1s;", ErrorKind::Unsupported, "LTIME"),
            (
                "x := TOD#12:00:00;",
                ErrorKind::Unsupported,
                "not supported",
            ),
        ] {
            let err = tokenize(src).unwrap_err();
            assert_eq!(err.kind(), Some(kind), "{src}: {err}");
            let Error::Source { pos, .. } = &err else {
                unreachable!()
            };
            assert_eq!((pos.line, pos.column), (1, 6), "{src}");
            assert!(err.to_string().contains(needle), "{src}: {err}");
        }
    }

    #[test]
    fn configuration_words_are_reserved() {
        for word in [
            "CONFIGURATION",
            "end_configuration",
            "Resource",
            "END_RESOURCE",
            "on",
            "TASK",
            "with",
            "INTERVAL",
            "PRIORITY",
            "SINGLE",
        ] {
            assert!(matches!(toks(word)[0], Tok::Kw(_)), "{word}");
        }
    }

    #[test]
    fn malformed_input_is_reported_with_its_position() {
        for (src, line, column) in [
            ("a__b", 1, 1),
            ("x\n  bad_", 2, 3),
            ("3#12", 1, 1),
            ("16#FG", 1, 1),
            ("1__0", 1, 1),
            ("x (* open", 1, 3),
            ("x $", 1, 3),
            ("%X1", 1, 1),
        ] {
            let err = tokenize(src).unwrap_err();
            assert_eq!(err.line(), Some(line), "{src}: {err}");
            let Error::Source { pos, .. } = err else {
                unreachable!()
            };
            assert_eq!(pos.column, column, "{src}");
        }
    }
}
