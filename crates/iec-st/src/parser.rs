//! Recursive-descent parser from tokens to the syntax tree.
//!
//! Operator precedence, loosest first: `OR`; `XOR`; `AND`/`&`; `=`/`<>`;
//! `<` `>` `<=` `>=`; `+` `-`; `*` `/` `MOD`; unary `-` `NOT`; primaries.
//! Binary operators associate to the left.

use crate::ast::*;
use crate::error::{Error, ErrorKind, Pos};
use crate::lexer::{tokenize, Kw, Tok, Token};

mod configuration;

/// Parses a whole source file into its POUs and configurations.
pub(crate) fn parse_file(source: &str) -> Result<SourceAst> {
    let tokens = tokenize(source)?;
    let mut parser = Parser { tokens, at: 0 };
    let mut file = SourceAst::default();
    while parser.peek() != &Tok::Eof {
        if parser.peek() == &Tok::Kw(Kw::Configuration) {
            file.configurations.push(parser.configuration()?);
        } else {
            file.pous.push(parser.pou()?);
        }
    }
    Ok(file)
}

struct Parser {
    tokens: Vec<Token>,
    at: usize,
}

type Result<T> = std::result::Result<T, Error>;

impl Parser {
    fn peek(&self) -> &Tok {
        &self.tokens[self.at].tok
    }

    fn peek_at(&self, ahead: usize) -> &Tok {
        let i = (self.at + ahead).min(self.tokens.len() - 1);
        &self.tokens[i].tok
    }

    fn pos(&self) -> Pos {
        self.tokens[self.at].pos
    }

    fn next(&mut self) -> Token {
        let token = self.tokens[self.at].clone();
        if token.tok != Tok::Eof {
            self.at += 1;
        }
        token
    }

    fn eat(&mut self, tok: &Tok) -> bool {
        if self.peek() == tok {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn unexpected(&self, expected: &str) -> Error {
        Error::at(
            ErrorKind::Syntax,
            self.pos(),
            format!("expected {expected}, found {}", self.peek().describe()),
        )
    }

    fn expect(&mut self, tok: Tok) -> Result<Pos> {
        let pos = self.pos();
        if self.eat(&tok) {
            Ok(pos)
        } else {
            Err(self.unexpected(&tok.describe()))
        }
    }

    fn expect_kw(&mut self, kw: Kw) -> Result<Pos> {
        self.expect(Tok::Kw(kw))
    }

    fn ident(&mut self) -> Result<Ident> {
        match self.peek().clone() {
            Tok::Ident(text) => {
                let pos = self.pos();
                self.at += 1;
                Ok(Ident { text, pos })
            }
            _ => Err(self.unexpected("an identifier")),
        }
    }

    fn unsupported(&self, what: &str) -> Error {
        Error::at(
            ErrorKind::Unsupported,
            self.pos(),
            format!("{what} is not supported"),
        )
    }

    fn pou(&mut self) -> Result<Pou> {
        let (kind, end) = match self.peek() {
            Tok::Kw(Kw::Program) => (PouKind::Program, Kw::EndProgram),
            Tok::Kw(Kw::FunctionBlock) => (PouKind::FunctionBlock, Kw::EndFunctionBlock),
            Tok::Kw(Kw::Function) => (PouKind::Function, Kw::EndFunction),
            Tok::Kw(Kw::Type) => return Err(self.unsupported("`TYPE` (user-defined types)")),
            Tok::Kw(Kw::VarGlobal) => return Err(self.unsupported("`VAR_GLOBAL`")),
            _ => {
                return Err(
                    self.unexpected("`PROGRAM`, `FUNCTION_BLOCK`, `FUNCTION` or `CONFIGURATION`")
                )
            }
        };
        self.next();
        let name = self.ident()?;
        let result = if kind == PouKind::Function {
            self.expect(Tok::Colon)?;
            Some(self.type_ref()?)
        } else {
            None
        };
        let mut blocks = Vec::new();
        while let Some(block) = self.var_block()? {
            blocks.push(block);
        }
        let body = self.statements(false)?;
        self.expect_kw(end)?;
        Ok(Pou {
            kind,
            name,
            result,
            blocks,
            body,
        })
    }

    fn var_block(&mut self) -> Result<Option<VarBlock>> {
        let section = match self.peek() {
            Tok::Kw(Kw::VarInput) => Section::Input,
            Tok::Kw(Kw::VarOutput) => Section::Output,
            Tok::Kw(Kw::Var) => Section::Local,
            Tok::Kw(Kw::VarTemp) => Section::Temp,
            Tok::Kw(Kw::VarInOut) => return Err(self.unsupported("`VAR_IN_OUT`")),
            Tok::Kw(Kw::VarGlobal) => return Err(self.unsupported("`VAR_GLOBAL`")),
            Tok::Kw(Kw::VarExternal) => return Err(self.unsupported("`VAR_EXTERNAL`")),
            _ => return Ok(None),
        };
        self.next();
        let mut constant = false;
        loop {
            match self.peek() {
                Tok::Kw(Kw::Constant) if section == Section::Local => constant = true,
                Tok::Kw(Kw::Retain | Kw::NonRetain) if section != Section::Temp => {}
                _ => break,
            }
            self.next();
        }
        let mut decls = Vec::new();
        while !self.eat(&Tok::Kw(Kw::EndVar)) {
            decls.push(self.var_decl()?);
        }
        Ok(Some(VarBlock {
            section,
            constant,
            decls,
        }))
    }

    fn var_decl(&mut self) -> Result<VarDecl> {
        let mut names = vec![self.ident()?];
        while self.eat(&Tok::Comma) {
            names.push(self.ident()?);
        }
        let address = if self.eat(&Tok::Kw(Kw::At)) {
            let pos = self.pos();
            let Tok::Address(address) = self.peek().clone() else {
                return Err(self.unexpected("an address such as `%IX0.0`"));
            };
            if names.len() > 1 {
                return Err(Error::at(
                    ErrorKind::Syntax,
                    pos,
                    "`AT` locates one variable, not a list",
                ));
            }
            self.next();
            Some((address, pos))
        } else {
            None
        };
        self.expect(Tok::Colon)?;
        let ty = self.type_ref()?;
        let init = if self.eat(&Tok::Assign) {
            Some(self.init()?)
        } else {
            None
        };
        self.expect(Tok::Semi)?;
        Ok(VarDecl {
            names,
            address,
            ty,
            init,
        })
    }

    fn type_ref(&mut self) -> Result<TypeRef> {
        let pos = self.pos();
        if !self.eat(&Tok::Kw(Kw::Array)) {
            return Ok(TypeRef::Named(self.ident()?));
        }
        self.expect(Tok::LBracket)?;
        let mut dims = Vec::new();
        loop {
            let lo = self.signed_int()?;
            self.expect(Tok::DotDot)?;
            let hi = self.signed_int()?;
            dims.push((lo, hi));
            if !self.eat(&Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RBracket)?;
        self.expect_kw(Kw::Of)?;
        if self.peek() == &Tok::Kw(Kw::Array) {
            return Err(self.unsupported("an array of arrays"));
        }
        let element = self.ident()?;
        Ok(TypeRef::Array { dims, element, pos })
    }

    fn signed_int(&mut self) -> Result<i128> {
        let negative = self.eat(&Tok::Minus);
        if !negative {
            self.eat(&Tok::Plus);
        }
        match *self.peek() {
            Tok::Int(v) => {
                self.next();
                let v = i128::try_from(v).map_err(|_| {
                    Error::at(ErrorKind::Range, self.pos(), "integer literal too large")
                })?;
                Ok(if negative { -v } else { v })
            }
            _ => Err(self.unexpected("an integer literal")),
        }
    }

    fn init(&mut self) -> Result<Init> {
        let pos = self.pos();
        if !self.eat(&Tok::LBracket) {
            return Ok(Init::Scalar(self.expr()?));
        }
        let mut items = Vec::new();
        loop {
            if let (Tok::Int(count), Tok::LParen) = (self.peek().clone(), self.peek_at(1)) {
                let pos = self.pos();
                self.at += 2;
                let value = if self.peek() == &Tok::RParen {
                    None
                } else {
                    Some(self.expr()?)
                };
                self.expect(Tok::RParen)?;
                items.push(ArrayInit::Repeat { count, value, pos });
            } else {
                items.push(ArrayInit::Value(self.expr()?));
            }
            if !self.eat(&Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RBracket)?;
        Ok(Init::Array(items, pos))
    }

    /// Could the next tokens start a CASE label (rather than a statement)?
    fn at_case_label(&self) -> bool {
        match self.peek() {
            Tok::Int(_) | Tok::Minus | Tok::TypePrefix(_) => true,
            Tok::Ident(_) => matches!(self.peek_at(1), Tok::Colon | Tok::Comma | Tok::DotDot),
            _ => false,
        }
    }

    /// Statements up to (not including) a token that cannot start one.
    fn statements(&mut self, in_case: bool) -> Result<Vec<Stmt>> {
        let mut list = Vec::new();
        loop {
            if in_case && self.at_case_label() {
                return Ok(list);
            }
            match self.peek() {
                Tok::Semi => {
                    self.next();
                }
                Tok::Ident(_)
                | Tok::Kw(
                    Kw::If | Kw::Case | Kw::For | Kw::While | Kw::Repeat | Kw::Exit | Kw::Return,
                ) => {
                    list.push(self.statement()?);
                    self.expect(Tok::Semi)?;
                }
                _ => return Ok(list),
            }
        }
    }

    fn statement(&mut self) -> Result<Stmt> {
        let pos = self.pos();
        let Tok::Kw(kw) = *self.peek() else {
            return self.assignment_or_call();
        };
        self.next();
        match kw {
            Kw::If => {
                let mut branches = Vec::new();
                let cond = self.expr()?;
                self.expect_kw(Kw::Then)?;
                branches.push((cond, self.statements(false)?));
                while self.eat(&Tok::Kw(Kw::Elsif)) {
                    let cond = self.expr()?;
                    self.expect_kw(Kw::Then)?;
                    branches.push((cond, self.statements(false)?));
                }
                let otherwise = if self.eat(&Tok::Kw(Kw::Else)) {
                    self.statements(false)?
                } else {
                    Vec::new()
                };
                self.expect_kw(Kw::EndIf)?;
                Ok(Stmt::If {
                    branches,
                    otherwise,
                })
            }
            Kw::Case => {
                let selector = self.expr()?;
                self.expect_kw(Kw::Of)?;
                let mut arms = Vec::new();
                while self.at_case_label() {
                    let mut labels = Vec::new();
                    loop {
                        let lo = self.case_value()?;
                        labels.push(if self.eat(&Tok::DotDot) {
                            CaseLabel::Range(lo, self.case_value()?)
                        } else {
                            CaseLabel::Value(lo)
                        });
                        if !self.eat(&Tok::Comma) {
                            break;
                        }
                    }
                    self.expect(Tok::Colon)?;
                    let body = self.statements(true)?;
                    arms.push(CaseArm { labels, body });
                }
                let otherwise = if self.eat(&Tok::Kw(Kw::Else)) {
                    self.statements(false)?
                } else {
                    Vec::new()
                };
                self.expect_kw(Kw::EndCase)?;
                Ok(Stmt::Case {
                    selector,
                    arms,
                    otherwise,
                })
            }
            Kw::For => {
                let var = self.ident()?;
                self.expect(Tok::Assign)?;
                let from = self.expr()?;
                self.expect_kw(Kw::To)?;
                let to = self.expr()?;
                let by = if self.eat(&Tok::Kw(Kw::By)) {
                    Some(self.expr()?)
                } else {
                    None
                };
                self.expect_kw(Kw::Do)?;
                let body = self.statements(false)?;
                self.expect_kw(Kw::EndFor)?;
                Ok(Stmt::For {
                    var,
                    from,
                    to,
                    by,
                    body,
                    pos,
                })
            }
            Kw::While => {
                let cond = self.expr()?;
                self.expect_kw(Kw::Do)?;
                let body = self.statements(false)?;
                self.expect_kw(Kw::EndWhile)?;
                Ok(Stmt::While { cond, body, pos })
            }
            Kw::Repeat => {
                let body = self.statements(false)?;
                self.expect_kw(Kw::Until)?;
                let until = self.expr()?;
                self.expect_kw(Kw::EndRepeat)?;
                Ok(Stmt::Repeat { body, until, pos })
            }
            Kw::Exit => Ok(Stmt::Exit(pos)),
            Kw::Return => Ok(Stmt::Return),
            _ => unreachable!("statements() only dispatches statement keywords"),
        }
    }

    /// A CASE label bound: a signed literal, a typed literal or a constant.
    fn case_value(&mut self) -> Result<Expr> {
        if self.peek() == &Tok::Minus {
            let pos = self.pos();
            self.next();
            let operand = Box::new(self.primary()?);
            return Ok(Expr::Unary {
                op: UnaryOp::Neg,
                operand,
                pos,
            });
        }
        self.primary()
    }

    fn assignment_or_call(&mut self) -> Result<Stmt> {
        let name = self.ident()?;
        if self.peek() == &Tok::LParen {
            let args = self.args()?;
            return Ok(Stmt::Call { name, args });
        }
        let target = self.var_ref(name)?;
        let pos = self.expect(Tok::Assign)?;
        let value = self.expr()?;
        Ok(Stmt::Assign { target, value, pos })
    }

    fn var_ref(&mut self, first: Ident) -> Result<VarRef> {
        let mut parts = Vec::new();
        let mut name = first;
        loop {
            let index = if self.eat(&Tok::LBracket) {
                let mut list = vec![self.expr()?];
                while self.eat(&Tok::Comma) {
                    list.push(self.expr()?);
                }
                self.expect(Tok::RBracket)?;
                Some(list)
            } else {
                None
            };
            parts.push(PathPart { name, index });
            if !self.eat(&Tok::Dot) {
                return Ok(VarRef { parts });
            }
            name = self.ident()?;
        }
    }

    fn args(&mut self) -> Result<Vec<Arg>> {
        self.expect(Tok::LParen)?;
        let mut args = Vec::new();
        if self.eat(&Tok::RParen) {
            return Ok(args);
        }
        loop {
            let arg = match (self.peek(), self.peek_at(1)) {
                (Tok::Ident(_), Tok::Assign) => {
                    let name = self.ident()?;
                    self.next();
                    Arg::Input(name, self.expr()?)
                }
                (Tok::Ident(_), Tok::Arrow) => {
                    let name = self.ident()?;
                    self.next();
                    let first = self.ident()?;
                    Arg::Output(name, self.var_ref(first)?)
                }
                _ => Arg::Positional(self.expr()?),
            };
            args.push(arg);
            if !self.eat(&Tok::Comma) {
                break;
            }
        }
        self.expect(Tok::RParen)?;
        Ok(args)
    }

    pub(crate) fn expr(&mut self) -> Result<Expr> {
        self.binary(0)
    }

    /// Precedence climbing over the binary levels, loosest first.
    fn binary(&mut self, level: usize) -> Result<Expr> {
        const LEVELS: usize = 7;
        if level == LEVELS {
            return self.unary();
        }
        let mut left = self.binary(level + 1)?;
        loop {
            let op = match (level, self.peek()) {
                (0, Tok::Kw(Kw::Or)) => BinaryOp::Or,
                (1, Tok::Kw(Kw::Xor)) => BinaryOp::Xor,
                (2, Tok::Kw(Kw::And) | Tok::Amp) => BinaryOp::And,
                (3, Tok::Eq) => BinaryOp::Eq,
                (3, Tok::Ne) => BinaryOp::Ne,
                (4, Tok::Lt) => BinaryOp::Lt,
                (4, Tok::Gt) => BinaryOp::Gt,
                (4, Tok::Le) => BinaryOp::Le,
                (4, Tok::Ge) => BinaryOp::Ge,
                (5, Tok::Plus) => BinaryOp::Add,
                (5, Tok::Minus) => BinaryOp::Sub,
                (6, Tok::Star) => BinaryOp::Mul,
                (6, Tok::Slash) => BinaryOp::Div,
                (6, Tok::Kw(Kw::Mod)) => BinaryOp::Mod,
                _ => return Ok(left),
            };
            let pos = self.pos();
            self.next();
            let right = self.binary(level + 1)?;
            left = Expr::Binary {
                op,
                left: Box::new(left),
                right: Box::new(right),
                pos,
            };
        }
    }

    fn unary(&mut self) -> Result<Expr> {
        let pos = self.pos();
        let op = match self.peek() {
            Tok::Minus => UnaryOp::Neg,
            Tok::Kw(Kw::Not) => UnaryOp::Not,
            Tok::Plus => {
                self.next();
                return self.unary();
            }
            _ => return self.power(),
        };
        self.next();
        let operand = Box::new(self.unary()?);
        Ok(Expr::Unary { op, operand, pos })
    }

    fn power(&mut self) -> Result<Expr> {
        let base = self.primary()?;
        if self.peek() == &Tok::Power {
            return Err(self.unsupported("`**`"));
        }
        Ok(base)
    }

    fn primary(&mut self) -> Result<Expr> {
        let pos = self.pos();
        match self.peek().clone() {
            Tok::Int(v) => {
                self.next();
                Ok(Expr::Int(v, pos))
            }
            Tok::Kw(Kw::True) => {
                self.next();
                Ok(Expr::Bool(true, pos))
            }
            Tok::Kw(Kw::False) => {
                self.next();
                Ok(Expr::Bool(false, pos))
            }
            Tok::Time(_) => Err(Error::at(
                ErrorKind::Unsupported,
                pos,
                "duration literals (TIME values) are supported only as a task's INTERVAL",
            )),
            Tok::TypePrefix(text) => {
                self.next();
                let ty = Ident { text, pos };
                let value = match self.peek() {
                    Tok::Kw(Kw::True) => {
                        self.next();
                        TypedValue::Bool(true)
                    }
                    Tok::Kw(Kw::False) => {
                        self.next();
                        TypedValue::Bool(false)
                    }
                    _ => TypedValue::Int(self.signed_int()?),
                };
                Ok(Expr::Typed { ty, value, pos })
            }
            Tok::LParen => {
                self.next();
                let inner = self.expr()?;
                self.expect(Tok::RParen)?;
                Ok(inner)
            }
            Tok::Ident(_) => {
                let name = self.ident()?;
                if self.peek() == &Tok::LParen {
                    let args = self.args()?;
                    Ok(Expr::Call { name, args })
                } else {
                    Ok(Expr::Var(self.var_ref(name)?))
                }
            }
            _ => Err(self.unexpected("an expression")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_pous(source: &str) -> Result<Vec<Pou>> {
        parse_file(source).map(|file| file.pous)
    }

    /// The expression in Lisp-like notation, to assert its shape.
    fn show(e: &Expr) -> String {
        match e {
            Expr::Int(v, _) => v.to_string(),
            Expr::Bool(b, _) => b.to_string(),
            Expr::Typed { ty, value, .. } => format!("{}#{value:?}", ty.text),
            Expr::Var(v) => v
                .parts
                .iter()
                .map(|p| match &p.index {
                    None => p.name.text.clone(),
                    Some(ix) => format!(
                        "{}[{}]",
                        p.name.text,
                        ix.iter().map(show).collect::<Vec<_>>().join(",")
                    ),
                })
                .collect::<Vec<_>>()
                .join("."),
            Expr::Call { name, args } => format!("{}/{}", name.text, args.len()),
            Expr::Unary { op, operand, .. } => format!("({op:?} {})", show(operand)),
            Expr::Binary {
                op, left, right, ..
            } => format!("({} {} {})", op.symbol(), show(left), show(right)),
        }
    }

    fn parse_expr(src: &str) -> String {
        let mut p = Parser {
            tokens: tokenize(src).unwrap(),
            at: 0,
        };
        let e = p.expr().unwrap();
        assert_eq!(p.peek(), &Tok::Eof, "{src}: trailing tokens");
        show(&e)
    }

    #[test]
    fn precedence_follows_iec_61131_3() {
        for (src, tree) in [
            ("NOT a AND b", "(AND (Not a) b)"),
            ("x = 1 AND y", "(AND (= x 1) y)"),
            ("a OR b XOR c AND d", "(OR a (XOR b (AND c d)))"),
            ("a & b OR c", "(OR (AND a b) c)"),
            ("1 + 2 * 3 - 4", "(- (+ 1 (* 2 3)) 4)"),
            ("a < b = c > d", "(= (< a b) (> c d))"),
            ("-x * y MOD 3", "(MOD (* (Neg x) y) 3)"),
            ("(a OR b) AND c", "(AND (OR a b) c)"),
            ("a - b - c", "(- (- a b) c)"),
            ("t[i + 1, 2].q", "t[(+ i 1),2].q"),
            ("NOT NOT a", "(Not (Not a))"),
            ("f(1, 2) + g()", "(+ f/2 g/0)"),
            ("SINT#-3 + INT#16#10", "(+ SINT#Int(-3) INT#Int(16))"),
            ("BOOL#1 OR BOOL#TRUE", "(OR BOOL#Int(1) BOOL#Bool(true))"),
        ] {
            assert_eq!(parse_expr(src), tree, "{src}");
        }
    }

    fn body(src: &str) -> Vec<Stmt> {
        let pous = parse_pous(&format!("PROGRAM p {src} END_PROGRAM")).unwrap();
        pous.into_iter().next().unwrap().body
    }

    #[test]
    fn every_statement_kind_parses() {
        let stmts = body(
            "x := 1; ; fb(A := 1, Q => y); fb();
             IF a THEN x := 1; ELSIF b THEN x := 2; ELSE x := 3; END_IF;
             CASE s OF 1: x := 1; 2, 3: x := 2; 4..6, -1: ; c: x := 0; ELSE x := 9; END_CASE;
             FOR i := 1 TO 10 BY 2 DO EXIT; END_FOR;
             WHILE a DO RETURN; END_WHILE;
             REPEAT x := x + 1; UNTIL x > 3 END_REPEAT;",
        );
        let kinds: Vec<&str> = stmts
            .iter()
            .map(|s| match s {
                Stmt::Assign { .. } => "assign",
                Stmt::Call { .. } => "call",
                Stmt::If { .. } => "if",
                Stmt::Case { .. } => "case",
                Stmt::For { .. } => "for",
                Stmt::While { .. } => "while",
                Stmt::Repeat { .. } => "repeat",
                Stmt::Exit(_) => "exit",
                Stmt::Return => "return",
            })
            .collect();
        assert_eq!(
            kinds,
            ["assign", "call", "call", "if", "case", "for", "while", "repeat"]
        );
        let Stmt::If {
            branches,
            otherwise,
        } = &stmts[3]
        else {
            unreachable!()
        };
        assert_eq!((branches.len(), otherwise.len()), (2, 1));
        let Stmt::Case {
            arms, otherwise, ..
        } = &stmts[4]
        else {
            unreachable!()
        };
        let labels: Vec<usize> = arms.iter().map(|a| a.labels.len()).collect();
        assert_eq!(labels, [1, 2, 2, 1]);
        assert_eq!(arms[2].body.len(), 0);
        assert_eq!(otherwise.len(), 1);
        let Stmt::Call { args, .. } = &stmts[1] else {
            unreachable!()
        };
        assert!(matches!(args[0], Arg::Input(..)) && matches!(args[1], Arg::Output(..)));
    }

    #[test]
    fn declarations_with_addresses_arrays_and_initialisers() {
        let pous = parse_pous(
            "FUNCTION_BLOCK f
             VAR_INPUT a, b : BOOL; END_VAR
             VAR CONSTANT T : ARRAY [-1..1, 0..2] OF INT := [2(7), 3(), 1, -2]; END_VAR
             VAR x AT %IX0.3 : BOOL; n : UDINT := UDINT#16#FFFF_FFFF; END_VAR
             END_FUNCTION_BLOCK
             FUNCTION g : INT VAR_INPUT i : INT; END_VAR g := i; END_FUNCTION",
        )
        .unwrap();
        assert_eq!(pous.len(), 2);
        let f = &pous[0];
        assert_eq!(f.blocks[0].decls[0].names.len(), 2);
        assert!(f.blocks[1].constant);
        let TypeRef::Array { dims, .. } = &f.blocks[1].decls[0].ty else {
            unreachable!()
        };
        assert_eq!(dims, &[(-1, 1), (0, 2)]);
        let Some(Init::Array(items, _)) = &f.blocks[1].decls[0].init else {
            unreachable!()
        };
        assert!(matches!(
            items[0],
            ArrayInit::Repeat {
                count: 2,
                value: Some(_),
                ..
            }
        ));
        assert!(matches!(
            items[1],
            ArrayInit::Repeat {
                count: 3,
                value: None,
                ..
            }
        ));
        assert_eq!(items.len(), 4);
        assert_eq!(
            f.blocks[2].decls[0].address.as_ref().map(|a| a.0.as_str()),
            Some("%IX0.3")
        );
        assert_eq!(pous[1].kind, PouKind::Function);
    }

    #[test]
    fn syntax_errors_name_the_line_and_what_was_expected() {
        for (src, line, needle) in [
            (
                "PROGRAM p\n x := 1\n y := 2; END_PROGRAM",
                3,
                "expected `;`",
            ),
            (
                "PROGRAM p\nIF a THEN x := 1; END_PROGRAM",
                2,
                "expected `END_IF`",
            ),
            (
                "PROGRAM p VAR a : BOOL END_VAR END_PROGRAM",
                1,
                "expected `;`",
            ),
            (
                "PROGRAM p\n\n x := 2 ** 3; END_PROGRAM",
                3,
                "`**` is not supported",
            ),
            (
                "PROGRAM p x := (1 + ; END_PROGRAM",
                1,
                "expected an expression",
            ),
            ("TYPE t : INT; END_TYPE", 1, "not supported"),
        ] {
            let err = parse_pous(src).unwrap_err();
            assert_eq!(err.line(), Some(line), "{src}: {err}");
            assert!(err.to_string().contains(needle), "{src}: {err}");
        }
    }
}
