//! The token-format parser: `<Generator>` and its sections, one method a
//! section, over the tokens of [`super::lex`].

use super::super::{parse_kind, Component, Kind, KINDS};
use super::lex::{all_digits, attribute, decode, describe, shorten, split_explicit_index};
use super::lex::{Lexer, Tok, Token};
use super::states::{build_error, default_name, drop_index_names, tag, StateDecl, States};
use super::MAX_RANGE_STATES;
use crate::automaton::{AutomatonBuilder, StateId};
use crate::error::{Error, Location, Result};
use std::borrow::Cow;
use std::path::Path;

/// Reads one generator of the token format.
pub(super) struct Parser<'a> {
    lx: Lexer<'a>,
    text: &'a str,
    origin: &'a Path,
    b: AutomatonBuilder,
    states: Option<States>,
    /// Some event carried an attribute (`+C+`, `+oF+`, …).
    attributed: bool,
}

impl<'a> Parser<'a> {
    /// A parser at the start of `text`; `origin` names the file in errors.
    pub(super) fn new(text: &'a str, origin: &'a Path) -> Self {
        Parser {
            lx: Lexer::new(text, origin),
            text,
            origin,
            b: AutomatonBuilder::new(""),
            states: None,
            attributed: false,
        }
    }

    fn syntax(&self, pos: usize, msg: impl Into<String>) -> Error {
        Error::syntax(Location::at_offset(self.origin, self.text, pos), msg)
    }

    fn model(&self, pos: usize, msg: impl Into<String>) -> Error {
        Error::model(Location::at_offset(self.origin, self.text, pos), msg)
    }

    fn end_pos(&self) -> usize {
        self.text.len()
    }

    fn pos_of(&self, t: Option<&Token<'_>>) -> usize {
        t.map_or(self.end_pos(), |t| t.pos)
    }

    /// Reads the whole file: one `<Generator>` and nothing after it.
    pub(super) fn generator(mut self) -> Result<Component> {
        let first = self.lx.next()?;
        let tag_pos = self.pos_of(first.as_ref());
        let (attrs, empty) = match first.map(|t| t.tok) {
            Some(Tok::Begin {
                name: "Generator",
                attrs,
                empty,
            }) => (attrs, empty),
            _ => {
                return Err(self.syntax(
                    self.pos_of(first.as_ref()),
                    format!("expected `<Generator>`, found {}", describe(first.as_ref())),
                ))
            }
        };
        let mut name = attribute(attrs, "name").map(Cow::into_owned);
        let system = attribute(attrs, "ftype").is_some_and(|t| t == "System");
        let kind = match attribute(attrs, "kind") {
            None => Kind::Unspecified,
            Some(k) => parse_kind(&k).ok_or_else(|| {
                self.model(
                    tag_pos,
                    format!("unknown kind `{}` (expected {KINDS})", shorten(&k)),
                )
            })?,
        };
        if !empty {
            if let Some(t) = self.lx.peek()? {
                if let Tok::Quoted(_) | Tok::Symbol(_) = t.tok {
                    self.lx.next()?;
                    if name.is_none() {
                        name = Some(self.value(&t).into_owned());
                    }
                }
            }
        }
        self.b
            .set_name(name.unwrap_or_else(|| default_name(self.origin)));
        if !empty {
            self.sections()?;
        }
        // A plain generator without any event attribute does not state
        // controllability (typically a specification): it defers to the
        // automata it is combined with.
        if !system && !self.attributed {
            self.b.set_controllability_stated(false);
        }
        if let Some(t) = self.lx.next()? {
            return Err(self.syntax(
                t.pos,
                format!("unexpected {} after `</Generator>`", describe(Some(&t))),
            ));
        }
        let text = self.text;
        let origin = self.origin;
        let mut a = self.b.build().map_err(|e| build_error(e, text, origin))?;
        drop_index_names(&mut a);
        Ok(Component { kind, automaton: a })
    }

    fn value(&self, t: &Token<'a>) -> Cow<'a, str> {
        match t.tok {
            Tok::Quoted(s) => decode(s),
            Tok::Symbol(s) => Cow::Borrowed(s),
            _ => Cow::Borrowed(""),
        }
    }

    fn sections(&mut self) -> Result<()> {
        let mut seen: Vec<&'a str> = Vec::new();
        loop {
            let t = self.lx.next()?;
            let Some(tok) = t else {
                return Err(self.syntax(
                    self.end_pos(),
                    "unexpected end of file (expected `</Generator>`)",
                ));
            };
            match tok.tok {
                Tok::End("Generator") => return Ok(()),
                Tok::Begin { name, empty, .. } => {
                    if seen.contains(&name) {
                        return Err(self.syntax(tok.pos, format!("duplicate section `<{name}>`")));
                    }
                    seen.push(name);
                    match name {
                        "Alphabet" => self.alphabet(empty)?,
                        "States" => self.state_decls(empty)?,
                        "TransRel" => self.trans_rel(empty)?,
                        "InitStates" => self.state_list(empty, "InitStates", true)?,
                        "MarkedStates" => self.state_list(empty, "MarkedStates", false)?,
                        _ => {
                            return Err(self.syntax(
                                tok.pos,
                                format!(
                                    "unsupported section `<{name}>` (expected <Alphabet>, <States>, <TransRel>, <InitStates>, <MarkedStates> or </Generator>)"
                                ),
                            ))
                        }
                    }
                }
                _ => {
                    return Err(self.syntax(
                        tok.pos,
                        format!(
                            "expected a section (<Alphabet>, <States>, <TransRel>, <InitStates>, <MarkedStates>) or `</Generator>`, found {}",
                            describe(Some(&tok))
                        ),
                    ))
                }
            }
        }
    }

    /// Skips to the `</name>` matching an already consumed `<name>`.
    fn skip_element(&mut self, name: &str, pos: usize) -> Result<()> {
        let mut depth = 1usize;
        loop {
            match self.lx.next()?.map(|t| t.tok) {
                None => return Err(self.syntax(pos, format!("section `<{name}>` is never closed"))),
                Some(Tok::Begin { empty: false, .. }) => depth += 1,
                Some(Tok::End(_)) => {
                    depth -= 1;
                    if depth == 0 {
                        return Ok(());
                    }
                }
                Some(_) => {}
            }
        }
    }

    /// The next token inside `<section>`: `None` at its end tag.
    fn item(&mut self, section: &str) -> Result<Option<Token<'a>>> {
        let t = self.lx.next()?;
        match t.map(|t| t.tok) {
            None => Err(self.syntax(
                self.end_pos(),
                format!("unexpected end of file (expected `</{section}>`)"),
            )),
            Some(Tok::End(name)) if name == section => Ok(None),
            Some(Tok::End(name)) => Err(self.syntax(
                self.pos_of(t.as_ref()),
                format!("expected `</{section}>`, found `</{name}>`"),
            )),
            _ => Ok(t),
        }
    }

    fn alphabet(&mut self, empty: bool) -> Result<()> {
        if empty {
            return Ok(());
        }
        while let Some(t) = self.item("Alphabet")? {
            match t.tok {
                Tok::Quoted(_) | Tok::Symbol(_) => {
                    let name = self.value(&t);
                    let (controllable, observable) = match self.lx.peek()? {
                        Some(Token {
                            tok: Tok::Attr(a),
                            pos,
                        }) => {
                            self.lx.next()?;
                            self.attributed = true;
                            event_flags(a).map_err(|m| {
                                self.model(pos, format!("event `{}`: {m}", shorten(&name)))
                            })?
                        }
                        _ => (false, true),
                    };
                    if let Some(extra) = self.lx.peek()? {
                        if matches!(extra.tok, Tok::Attr(_) | Tok::Block | Tok::Begin { .. }) {
                            return Err(self.model(
                                extra.pos,
                                format!(
                                    "event `{}` carries {}, which cannot be carried here \
                                     (an event takes one `+…+` of libFAUDES System flags)",
                                    shorten(&name),
                                    describe(Some(&extra))
                                ),
                            ));
                        }
                    }
                    let id = self
                        .b
                        .add_event(&name, controllable)
                        .map_err(|e| self.model(t.pos, e.to_string()))?;
                    if !observable {
                        self.b.set_unobservable(id);
                    }
                }
                _ => {
                    return Err(self.syntax(
                        t.pos,
                        format!(
                            "expected an event name or `</Alphabet>`, found {}",
                            describe(Some(&t))
                        ),
                    ))
                }
            }
        }
        Ok(())
    }

    fn index(&self, t: &Token<'_>, s: &str) -> Result<u64> {
        s.parse::<u64>()
            .map_err(|_| self.syntax(t.pos, format!("state index `{}` is too large", shorten(s))))
    }

    fn state_decls(&mut self, empty: bool) -> Result<()> {
        let mut decls: Vec<StateDecl<'a>> = Vec::new();
        let mut range_states: u64 = 0;
        if !empty {
            while let Some(t) = self.item("States")? {
                match t.tok {
                    Tok::Symbol(s) if all_digits(s) => {
                        let index = self.index(&t, s)?;
                        decls.push(StateDecl {
                            name: None,
                            index: Some(index),
                            pos: t.pos,
                            initial: false,
                            marked: false,
                        });
                    }
                    Tok::Quoted(_) | Tok::Symbol(_) => {
                        let v = self.value(&t);
                        let (name, index) = match split_explicit_index(&v) {
                            Some((n, i)) => (Cow::Owned(n.to_owned()), Some(i)),
                            None => (v, None),
                        };
                        decls.push(StateDecl {
                            name: Some(name),
                            index,
                            pos: t.pos,
                            initial: false,
                            marked: false,
                        });
                    }
                    Tok::Attr(_) | Tok::Block => {}
                    Tok::Begin {
                        name: "Consecutive",
                        empty,
                        ..
                    } => {
                        let (first, last) = self.consecutive(&t, empty, &mut range_states)?;
                        decls.extend((first..=last).map(|i| StateDecl {
                            name: None,
                            index: Some(i),
                            pos: t.pos,
                            initial: false,
                            marked: false,
                        }));
                    }
                    Tok::Begin { name, empty, .. } => {
                        // An attribute of the previous state.
                        if !empty {
                            self.skip_element(name, t.pos)?;
                        }
                    }
                    Tok::End(_) => {} // `item` consumed the end tag
                }
            }
        }
        let text = self.text;
        let origin = self.origin;
        let err =
            |pos: usize, msg: String| Error::model(Location::at_offset(origin, text, pos), msg);
        self.states = Some(States::commit(&mut self.b, &decls, &err)?);
        self.b.close_states();
        Ok(())
    }

    /// Reads the two bounds and the end tag of a `<Consecutive>` range
    /// whose begin tag `t` has been read; `range_states` counts the states
    /// of the ranges so far, against [`MAX_RANGE_STATES`].
    fn consecutive(
        &mut self,
        t: &Token<'a>,
        empty: bool,
        range_states: &mut u64,
    ) -> Result<(u64, u64)> {
        let mut bounds = [0u64; 2];
        if empty {
            return Err(self.syntax(
                t.pos,
                "`<Consecutive/>` needs two indices (expected `<Consecutive> first last </Consecutive>`)",
            ));
        }
        for bound in &mut bounds {
            let n = self.lx.next()?;
            match n.map(|n| n.tok) {
                Some(Tok::Symbol(s)) if all_digits(s) => {
                    *bound = self.index(n.as_ref().unwrap_or(t), s)?;
                }
                _ => {
                    return Err(self.syntax(
                        self.pos_of(n.as_ref()),
                        format!(
                            "expected a state index in `<Consecutive>`, found {}",
                            describe(n.as_ref())
                        ),
                    ))
                }
            }
        }
        let n = self.lx.next()?;
        if !matches!(n.map(|n| n.tok), Some(Tok::End("Consecutive"))) {
            return Err(self.syntax(
                self.pos_of(n.as_ref()),
                format!("expected `</Consecutive>`, found {}", describe(n.as_ref())),
            ));
        }
        let [first, last] = bounds;
        if first > last {
            return Err(self.syntax(
                t.pos,
                format!("empty index range {first} to {last} in `<Consecutive>`"),
            ));
        }
        *range_states = range_states.saturating_add(last - first + 1);
        if *range_states > MAX_RANGE_STATES {
            return Err(self.model(
                t.pos,
                format!(
                    "too many states declared by `<Consecutive>` ranges (at most {MAX_RANGE_STATES} are supported)"
                ),
            ));
        }
        Ok((first, last))
    }

    /// Resolves a state reference (a name, or an unquoted index).
    fn state_ref(&self, t: &Token<'a>) -> Result<StateId> {
        let by_index = |i: u64| {
            self.states
                .as_ref()
                .and_then(|s| s.by_index.get(&i).copied())
        };
        let found = match t.tok {
            Tok::Symbol(s) if all_digits(s) => s
                .parse::<u64>()
                .ok()
                .and_then(by_index)
                .or_else(|| self.b.find_state(s)),
            Tok::Quoted(_) | Tok::Symbol(_) => {
                let v = self.value(t);
                self.b.find_state(&v).or_else(|| {
                    if all_digits(&v) {
                        v.parse::<u64>().ok().and_then(by_index)
                    } else {
                        split_explicit_index(&v)
                            .and_then(|(n, i)| by_index(i).or_else(|| self.b.find_state(n)))
                    }
                })
            }
            _ => {
                return Err(self.syntax(
                    t.pos,
                    format!("expected a state, found {}", describe(Some(t))),
                ))
            }
        };
        found.ok_or_else(|| {
            let what = match t.tok {
                Tok::Symbol(s) if all_digits(s) => format!("state index {s}"),
                _ => format!("state `{}`", self.value(t)),
            };
            self.model(t.pos, format!("{what} is not declared in <States>"))
        })
    }

    fn trans_rel(&mut self, empty: bool) -> Result<()> {
        if empty {
            return Ok(());
        }
        while let Some(t) = self.item("TransRel")? {
            match t.tok {
                Tok::Quoted(_) | Tok::Symbol(_) => {}
                Tok::Attr(_) | Tok::Block => continue,
                Tok::Begin { name, empty, .. } => {
                    if !empty {
                        self.skip_element(name, t.pos)?;
                    }
                    continue;
                }
                Tok::End(_) => {} // `item` consumed the end tag
            }
            let source = self.state_ref(&t)?;
            let et = self.lx.next()?;
            let event = match et {
                Some(
                    et @ Token {
                        tok: Tok::Quoted(_) | Tok::Symbol(_),
                        ..
                    },
                ) => {
                    let name = self.value(&et);
                    self.b.alphabet().id(&name).ok_or_else(|| {
                        self.model(et.pos, format!("event `{name}` is not in the <Alphabet>"))
                    })?
                }
                _ => {
                    return Err(self.syntax(
                        self.pos_of(et.as_ref()),
                        format!(
                            "expected the event of the transition, found {}",
                            describe(et.as_ref())
                        ),
                    ))
                }
            };
            let tt = self.lx.next()?;
            let target = match tt {
                Some(
                    tt @ Token {
                        tok: Tok::Quoted(_) | Tok::Symbol(_),
                        ..
                    },
                ) => self.state_ref(&tt)?,
                _ => {
                    return Err(self.syntax(
                        self.pos_of(tt.as_ref()),
                        format!(
                            "expected the target state of the transition, found {}",
                            describe(tt.as_ref())
                        ),
                    ))
                }
            };
            self.b.add_transition(source, event, target, tag(t.pos));
        }
        Ok(())
    }

    fn state_list(&mut self, empty: bool, section: &str, initial: bool) -> Result<()> {
        if empty {
            return Ok(());
        }
        while let Some(t) = self.item(section)? {
            match t.tok {
                Tok::Quoted(_) | Tok::Symbol(_) => {
                    let s = self.state_ref(&t)?;
                    if initial {
                        self.b
                            .set_initial(s)
                            .map_err(|e| self.model(t.pos, e.to_string()))?;
                    } else {
                        self.b.mark(s);
                    }
                }
                Tok::Attr(_) | Tok::Block => {}
                Tok::Begin { name, empty, .. } => {
                    if !empty {
                        self.skip_element(name, t.pos)?;
                    }
                }
                Tok::End(_) => {} // `item` consumed the end tag
            }
        }
        Ok(())
    }
}

/// The libFAUDES System flags of an event attribute `+…+`: (controllable,
/// observable). `C`/`c` and `O`/`o` say controllable and observable or
/// not; `f` (not forcible) is the default and changes nothing. Anything
/// else is refused rather than dropped: forcible events (`F`) and the
/// letters of other libFAUDES attribute types (HIO, colours, …) mean
/// something no automaton here can hold.
fn event_flags(attr: &str) -> std::result::Result<(bool, bool), String> {
    let (mut controllable, mut observable) = (false, true);
    for c in attr.trim_matches('+').chars() {
        match c {
            'C' => controllable = true,
            'c' => controllable = false,
            'O' => observable = true,
            'o' => observable = false,
            'f' => {}
            'F' => {
                return Err(format!(
                    "`{attr}` makes it forcible, which cannot be carried here (no forcible events)"
                ))
            }
            other => {
                return Err(format!(
                    "unknown flag `{other}` in `{attr}` (libFAUDES System flags: C/c controllable, O/o observable)"
                ))
            }
        }
    }
    Ok((controllable, observable))
}

#[cfg(test)]
mod tests {
    use super::super::{p, read};
    use crate::automaton::StateId;

    fn err_at(text: &str) -> (u32, u32, String) {
        let e = read(text, p()).unwrap_err();
        let (l, m) = e.located().unwrap_or_else(|| panic!("unexpected {e:?}"));
        (l.line, l.column, m.to_owned())
    }

    #[test]
    fn old_style_file_with_quoted_names_reads() {
        let a = read(
            "<Generator>\n\"MACH1\"\n<Alphabet>\n\"e10\" \n\"e11\" +C+\n</Alphabet>\n<States>\n\"0\"\n\"1\"\n</States>\n<TransRel>\n\"0\" \"e11\" \"1\"\n\"1\" \"e10\" \"0\"\n</TransRel>\n<InitStates>\n\"0\"\n</InitStates>\n<MarkedStates>\n\"0\"\n</MarkedStates>\n</Generator>\n",
            p(),
        )
        .unwrap();
        assert_eq!(a.name(), "MACH1");
        assert_eq!((a.num_states(), a.num_transitions()), (2, 2));
        assert!(!a.has_state_names(), "names 0, 1 in order read as indices");
        let e11 = a.alphabet().id("e11").unwrap();
        assert!(a.alphabet().is_controllable(e11));
        assert!(!a
            .alphabet()
            .is_controllable(a.alphabet().id("e10").unwrap()));
        assert_eq!(a.initial(), Some(StateId(0)));
        assert!(a.is_marked(StateId(0)) && !a.is_marked(StateId(1)));
    }

    #[test]
    fn explicit_indices_ranges_attributes_and_comments() {
        let text = r#"% a comment
<Generator name="my gen" ftype="System">
<Alphabet> a +C+ "b" +of+ c </Alphabet>   % trailing comment
<States>
1 2 <Consecutive> 4 6 </Consecutive> "idle#9" busy#12 +S+
</States>
<TransRel>
idle a busy
12 b 4 {attr}
4 c "idle"
2 a 1 <Attr> 1 2 </Attr>
</TransRel>
<InitStates> 9 </InitStates>
<MarkedStates/>
</Generator>"#;
        let a = read(text, p()).unwrap();
        assert_eq!(a.name(), "my gen");
        assert_eq!((a.num_states(), a.num_transitions()), (7, 4));
        let names: Vec<_> = a.states().map(|s| a.state_name(s).into_owned()).collect();
        assert_eq!(names, ["1", "2", "4", "5", "6", "idle", "busy"]);
        assert_eq!(a.initial(), a.state_by_name("idle"));
        assert!(a.alphabet().is_controllable(a.alphabet().id("a").unwrap()));
        assert!(!a.alphabet().is_controllable(a.alphabet().id("b").unwrap()));
        let unobservable: Vec<&str> = a
            .alphabet()
            .unobservable()
            .map(|(_, e)| e.name.as_str())
            .collect();
        assert_eq!(unobservable, ["b"]);
        let busy = a.state_by_name("busy").unwrap();
        let b = a.alphabet().id("b").unwrap();
        assert_eq!(a.successor(busy, b), a.state_by_name("4"));
        assert_eq!(a.marked_states().count(), 0);
    }

    #[test]
    fn event_flags_no_automaton_here_can_hold_are_refused_at_their_line() {
        let gen = |alphabet: &str| {
            format!(
                "<Generator name=\"g\" ftype=\"System\">\n<Alphabet>\n{alphabet}\n</Alphabet>\n<States> x </States><TransRel/><InitStates> x </InitStates><MarkedStates/></Generator>"
            )
        };
        for (alphabet, says) in [
            ("a +CF+", "forcible"),
            ("a +Y+", "unknown flag `Y`"),
            ("a +C+ {clock}", "cannot be carried"),
            ("a +C+ +o+", "cannot be carried"),
        ] {
            let err = read(&gen(alphabet), p()).unwrap_err().to_string();
            assert!(err.contains("t.gen:3:"), "{alphabet}: {err}");
            assert!(err.contains(says), "{alphabet}: {err}");
        }
        let a = read(&gen("a +Co+ b +o+ c +cOf+ d"), p()).unwrap();
        let flags: Vec<(bool, bool)> = a
            .alphabet()
            .iter()
            .map(|(_, e)| (e.controllable, e.observable))
            .collect();
        assert_eq!(
            flags,
            [(true, false), (false, false), (false, true), (false, true)]
        );
        let text = super::super::write(&a);
        assert!(text.contains("a +Co+\nb +o+\nc\nd\n"), "{text}");
        assert_eq!(read(&text, p()).unwrap().alphabet(), a.alphabet());
    }

    #[test]
    fn unnamed_states_are_renumbered_densely() {
        let a = read(
            "<Generator name=\"g\"><Alphabet>a</Alphabet><States>3 7 <Consecutive>10 11</Consecutive></States><TransRel>3 a 11</TransRel><InitStates>7</InitStates><MarkedStates>10</MarkedStates></Generator>",
            p(),
        )
        .unwrap();
        assert!(!a.has_state_names());
        assert_eq!(a.num_states(), 4);
        assert_eq!(a.initial(), Some(StateId(1)));
        assert!(a.is_marked(StateId(2)));
        assert_eq!(a.iter_transitions().next().map(|t| t.2), Some(StateId(3)));
    }

    #[test]
    fn errors_name_line_and_column() {
        let (l, c, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x </States>\n<TransRel>\nx b x\n</TransRel>\n</Generator>");
        assert_eq!((l, c), (5, 3), "{m}");
        assert!(m.contains("event `b`"), "{m}");

        let (l, c, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x </States>\n<TransRel>\nx a y\n</TransRel>\n</Generator>");
        assert_eq!((l, c), (5, 5), "{m}");
        assert!(m.contains("state `y` is not declared"), "{m}");

        let (l, _, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x y </States>\n<TransRel>\nx a y\nx a x\n</TransRel>\n</Generator>");
        assert_eq!(l, 6, "{m}");
        assert!(
            m.contains("nondeterministic") && m.contains("line 5"),
            "{m}"
        );

        let (l, c, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n<States> x y </States>\n<InitStates>\nx\n  y\n</InitStates>\n</Generator>");
        assert_eq!((l, c), (6, 3), "{m}");
        assert!(m.contains("two initial states"), "{m}");

        let (l, c, m) = err_at("<Generator>\n<Alphabet>\n \"a\n</Alphabet>");
        assert_eq!((l, c), (3, 2), "{m}");
        assert!(m.contains("unterminated"), "{m}");

        let (l, c, m) = err_at("<Generator>\n<Alphabet> a +C </Alphabet>\n");
        assert_eq!((l, c), (2, 14), "{m}");

        let (l, _, m) =
            err_at("<Generator>\n<Alphabet> a </Alphabet>\n<Clocks> x </Clocks>\n</Generator>");
        assert_eq!(l, 3, "{m}");

        let (l, _, m) = err_at("<Generator>\n<Alphabet> a </Alphabet>\n</Generator>\nextra");
        assert_eq!(l, 4, "{m}");

        let (l, _, m) =
            err_at("<Generator>\n<States>\n<Consecutive> 1 99999999999 </Consecutive>\n</States>\n</Generator>");
        assert_eq!(l, 3, "{m}");
        assert!(m.contains("too many states"), "{m}");

        let (l, _, m) = err_at("<Generator>\n<States> x#1 y#1 </States>\n</Generator>");
        assert_eq!(l, 2, "{m}");
        assert!(m.contains("index 1"), "{m}");
    }
}
