//! PNML: place/transition nets as ISO/IEC 15909-2 writes them.
//!
//! Read: the one `<net>` of a `<pnml>` document, of the P/T-net type
//! (`…/ptnet`), its name and its pages; on each page (pages nest) its
//! places, transitions and arcs with their `<name><text>`,
//! `<initialMarking><text>` (default 0) and `<inscription><text>` (default
//! 1). Only that structure is read: labels, `<graphics>` and other tools'
//! `<toolspecific>` elements are skipped whole, so nothing inside them (a
//! `<place>` in another tool's data, say) is taken for a net element, and
//! a node outside a page is refused rather than dropped. Names are kept
//! exactly, whitespace included; numbers may have spaces around them.
//!
//! PNML has no word for controllability, so each transition we write
//! carries it in a tool-specific element, which other tools keep and
//! ignore:
//!
//! ```xml
//! <transition id="ta2">
//!   <toolspecific tool="codegen" version="1">
//!     <controllable>false</controllable>
//!     <observable>true</observable>   <!-- optional, default true -->
//!   </toolspecific>
//! </transition>
//! ```
//!
//! A net from another tool has none: its controllability is stated beside
//! the file ([`super::control`], [`read_with`]), and a transition whose
//! controllability nobody states is refused: taking it as controllable by
//! default would let a supervisor count on disabling what it cannot.
//! Reference nodes (`referencePlace`, `referenceTransition`) and other net
//! types are refused.
//!
//! Written: the same, on one page, every name and id exactly as in the
//! net. XML 1.0 cannot carry the control characters other than tab, line
//! feed and carriage return, nor U+FFFE and U+FFFF, not even as character
//! references: a net with one in a name or id is refused by [`write()`],
//! naming the element, rather than written as a file no reader accepts or
//! with the name changed.

use super::control::{Control, Stated};
use super::{NetBuilder, PetriNet};
use crate::error::{Error, Result};
use crate::formats::XmlSource as Ctx;
use std::fmt::Write as _;
use std::path::Path;

/// The `tool` of our tool-specific elements.
pub const TOOL: &str = "codegen";

type Node<'a, 'i> = roxmltree::Node<'a, 'i>;

impl Ctx<'_> {
    fn id<'a>(&self, node: Node<'a, '_>) -> Result<&'a str> {
        node.attribute("id").ok_or_else(|| {
            self.model(
                node,
                format!("<{}> without an `id`", node.tag_name().name()),
            )
        })
    }

    /// The `<text>` of child `tag` of `node` exactly as written, with the
    /// text's node.
    fn text_of<'a, 'i>(&self, node: Node<'a, 'i>, tag: &str) -> Option<(Node<'a, 'i>, String)> {
        let child = node.children().find(|c| c.has_tag_name(tag))?;
        let text = child.children().find(|c| c.has_tag_name("text"))?;
        // Comments may split the text into several nodes.
        let content = text
            .children()
            .filter(|c| c.is_text())
            .filter_map(|c| c.text())
            .collect();
        Some((text, content))
    }

    /// A whole number from the `<text>` of child `tag`, or `default`.
    fn number(&self, node: Node<'_, '_>, tag: &str, default: u32) -> Result<u32> {
        match self.text_of(node, tag) {
            None => Ok(default),
            Some((at, text)) => text.trim().parse().map_err(|_| {
                self.model(
                    at,
                    format!(
                        "<{tag}> must be a whole number from 0 to 2^32 - 1, not `{}`",
                        text.trim()
                    ),
                )
            }),
        }
    }
}

/// Parses a PNML document; `origin` names the file in errors. Every
/// transition must state its controllability ([`read_with`] takes it from
/// elsewhere).
pub fn read(text: &str, origin: &Path) -> Result<PetriNet> {
    read_with(text, origin, &Control::default())
}

/// The nodes of a net, page by page, in document order.
#[derive(Default)]
struct Nodes<'a, 'i> {
    places: Vec<Node<'a, 'i>>,
    transitions: Vec<Node<'a, 'i>>,
    arcs: Vec<Node<'a, 'i>>,
}

impl<'a, 'i> Nodes<'a, 'i> {
    /// Collects the nodes of `page` and of the pages in it.
    fn page(&mut self, cx: &Ctx<'_>, page: Node<'a, 'i>) -> Result<()> {
        for node in page.children().filter(|n| n.is_element()) {
            match node.tag_name().name() {
                "page" => self.page(cx, node)?,
                "place" => self.places.push(node),
                "transition" => self.transitions.push(node),
                "arc" => self.arcs.push(node),
                "referencePlace" | "referenceTransition" => {
                    return Err(
                        cx.model(node, "reference nodes are not read: merge the pages first")
                    );
                }
                // Labels, graphics, tool-specific data: not net elements.
                _ => {}
            }
        }
        Ok(())
    }
}

/// Parses a PNML document, with the controllability and observability of
/// transitions stated in `control` where the file does not (or must agree
/// with it where it does; [`super::control`]); `origin` names the file.
pub fn read_with(text: &str, origin: &Path, control: &Control) -> Result<PetriNet> {
    let doc = crate::formats::parse_xml(text, origin)?;
    let cx = Ctx { text, origin };
    let root = doc.root_element();
    if !root.has_tag_name("pnml") {
        return Err(cx.model(
            root,
            format!(
                "expected a <pnml> document, found <{}>",
                root.tag_name().name()
            ),
        ));
    }
    let nets: Vec<Node<'_, '_>> = root.children().filter(|c| c.has_tag_name("net")).collect();
    let net = match nets[..] {
        [net] => net,
        [] => return Err(cx.model(root, "the document holds no <net>")),
        [_, second, ..] => {
            return Err(cx.model(
                second,
                format!(
                    "the document holds {} nets; give each its own file",
                    nets.len()
                ),
            ))
        }
    };
    let kind = net.attribute("type").unwrap_or("");
    if !kind.ends_with("/ptnet") {
        return Err(cx.model(
            net,
            format!("net type `{kind}`: only place/transition nets (…/grammar/ptnet) are read"),
        ));
    }
    let mut nodes = Nodes::default();
    for child in net.children().filter(|n| n.is_element()) {
        match child.tag_name().name() {
            "page" => nodes.page(&cx, child)?,
            tag @ ("place" | "transition" | "arc" | "referencePlace" | "referenceTransition") => {
                return Err(cx.model(
                    child,
                    format!(
                        "a <{tag}> directly in the <net>: PNML puts the net's nodes on a <page>"
                    ),
                ))
            }
            _ => {}
        }
    }
    let name = match cx.text_of(net, "name") {
        Some((_, name)) => name,
        None => cx.id(net)?.to_owned(),
    };
    let mut b = NetBuilder::new(name);
    let name = |node| cx.text_of(node, "name").map(|(_, n)| n);
    for &node in &nodes.places {
        let tokens = cx.number(node, "initialMarking", 0)?;
        b.add_place(cx.id(node)?, name(node), tokens, cx.at(node))?;
    }
    let stated: Vec<Stated> = nodes
        .transitions
        .iter()
        .map(|&t| stated(&cx, t))
        .collect::<Result<_>>()?;
    let unstated = stated.iter().all(|s| s.controllable.is_none());
    if !control.states_controllability() && unstated && !nodes.transitions.is_empty() {
        return Err(control.unstated(cx.at(net), nodes.transitions.len()));
    }
    for (&node, stated) in nodes.transitions.iter().zip(stated) {
        let id = cx.id(node)?;
        let at = cx.at(node);
        let (controllable, observable) = control.resolve(id, stated, &at)?;
        b.add_transition(id, name(node), controllable, observable, at)?;
    }
    for &arc in &nodes.arcs {
        let end = |key: &str| {
            arc.attribute(key)
                .ok_or_else(|| cx.model(arc, format!("<arc> without a `{key}`")))
        };
        let weight = cx.number(arc, "inscription", 1)?;
        b.add_arc(end("source")?, end("target")?, weight, cx.at(arc))?;
    }
    let net = b.build();
    control.check_names(&net, origin)?;
    Ok(net)
}

/// What transition `t`'s tool-specific element of ours states.
fn stated(cx: &Ctx<'_>, t: Node<'_, '_>) -> Result<Stated> {
    let Some(ours) = t
        .children()
        .find(|c| c.has_tag_name("toolspecific") && c.attribute("tool") == Some(TOOL))
    else {
        return Ok(Stated::default());
    };
    let flag = |tag: &str| -> Result<Option<bool>> {
        match ours.children().find(|c| c.has_tag_name(tag)) {
            None => Ok(None),
            Some(node) => match node.text().unwrap_or("").trim() {
                "true" => Ok(Some(true)),
                "false" => Ok(Some(false)),
                other => Err(cx.model(
                    node,
                    format!("<{tag}> must be true or false, not `{other}`"),
                )),
            },
        }
    };
    Ok(Stated {
        controllable: flag("controllable")?,
        observable: flag("observable")?,
    })
}

/// Renders `net` as a PNML document (one page; arcs numbered `a1`, `a2`,
/// … in transition order). A name or id holding a character XML 1.0
/// cannot carry is refused, naming the element.
pub fn write(net: &PetriNet) -> Result<String> {
    check_writable(net)?;
    let mut out = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <pnml xmlns=\"http://www.pnml.org/version-2009/grammar/pnml\">\n",
    );
    let _ = writeln!(
        out,
        "  <net id=\"net\" type=\"http://www.pnml.org/version-2009/grammar/ptnet\">\n    \
         <name><text>{}</text></name>\n    <page id=\"page\">",
        escape(net.name())
    );
    for (p, place) in net.places().iter().enumerate() {
        let _ = writeln!(out, "      <place id=\"{}\">", escape(&place.id));
        if let Some(name) = &place.name {
            let _ = writeln!(out, "        <name><text>{}</text></name>", escape(name));
        }
        if net.initial()[p] > 0 {
            let _ = writeln!(
                out,
                "        <initialMarking><text>{}</text></initialMarking>",
                net.initial()[p]
            );
        }
        out.push_str("      </place>\n");
    }
    for t in net.transitions() {
        let _ = writeln!(out, "      <transition id=\"{}\">", escape(&t.id));
        if let Some(name) = &t.name {
            let _ = writeln!(out, "        <name><text>{}</text></name>", escape(name));
        }
        let _ = writeln!(
            out,
            "        <toolspecific tool=\"{TOOL}\" version=\"1\">\
             <controllable>{}</controllable><observable>{}</observable></toolspecific>\n      \
             </transition>",
            t.controllable, t.observable
        );
    }
    let mut k = 0;
    for t in net.transitions() {
        let arcs = t
            .input
            .iter()
            .map(|&(p, w)| (&net.places()[p].id, &t.id, w))
            .chain(
                t.output
                    .iter()
                    .map(|&(p, w)| (&t.id, &net.places()[p].id, w)),
            );
        for (source, target, weight) in arcs {
            k += 1;
            let _ = write!(
                out,
                "      <arc id=\"a{k}\" source=\"{}\" target=\"{}\">",
                escape(source),
                escape(target)
            );
            if weight != 1 {
                let _ = write!(out, "<inscription><text>{weight}</text></inscription>");
            }
            out.push_str("</arc>\n");
        }
    }
    out.push_str("    </page>\n  </net>\n</pnml>\n");
    Ok(out)
}

/// Whether XML 1.0 can carry `c` (its `Char` production; Rust strings hold
/// no surrogates).
fn xml_char(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r' | ' '..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}' | '\u{10000}'..)
}

/// Refuses a net with a name or id that XML 1.0 cannot carry.
fn check_writable(net: &PetriNet) -> Result<()> {
    let mut texts: Vec<(String, &str)> = vec![("the net's name".to_owned(), net.name())];
    for p in net.places() {
        texts.push((format!("the id of place `{}`", p.id.escape_debug()), &p.id));
        if let Some(name) = &p.name {
            texts.push((format!("the name of place `{}`", p.id.escape_debug()), name));
        }
    }
    for t in net.transitions() {
        texts.push((
            format!("the id of transition `{}`", t.id.escape_debug()),
            &t.id,
        ));
        if let Some(name) = &t.name {
            texts.push((
                format!("the name of transition `{}`", t.id.escape_debug()),
                name,
            ));
        }
    }
    for (what, text) in texts {
        if let Some(c) = text.chars().find(|&c| !xml_char(c)) {
            return Err(Error::Incompatible(format!(
                "{what} holds U+{:04X}, which XML 1.0 cannot carry, so PNML cannot hold it \
                 (rename it, or keep the net in the native .toml)",
                u32::from(c)
            )));
        }
    }
    Ok(())
}

/// Text for XML content and attribute values: markup characters as
/// entities, and tab, line feed and carriage return as character
/// references, which a reader keeps where it would normalise the
/// characters themselves (in attributes; `\r` everywhere).
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            '\t' => out.push_str("&#9;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_str(text: &str) -> Result<PetriNet> {
        read(text, Path::new("n.pnml"))
    }

    const NET: &str = r#"<?xml version="1.0"?>
<pnml xmlns="http://www.pnml.org/version-2009/grammar/pnml">
  <net id="n1" type="http://www.pnml.org/version-2009/grammar/ptnet">
    <page id="p1">
      <place id="free"><initialMarking><text>2</text></initialMarking><graphics/></place>
      <page id="inner">
        <place id="full"><name><text>full slots</text></name></place>
      </page>
      <transition id="put"><toolspecific tool="codegen" version="1"><controllable>true</controllable></toolspecific></transition>
      <transition id="get"><toolspecific tool="codegen" version="1"><controllable>false</controllable><observable>false</observable></toolspecific></transition>
      <arc id="a1" source="free" target="put"/>
      <arc id="a2" source="put" target="full"><inscription><text>3</text></inscription></arc>
      <arc id="a3" source="full" target="get"/>
      <arc id="a4" source="get" target="free"/>
    </page>
  </net>
</pnml>
"#;

    #[test]
    fn a_net_on_nested_pages_reads_and_writes_back_to_itself() {
        let net = read_str(NET).unwrap();
        assert_eq!(net.name(), "n1", "the id when the net has no name");
        assert_eq!(net.initial(), &[2, 0]);
        assert_eq!(net.places()[1].name.as_deref(), Some("full slots"));
        assert_eq!(net.incidence(), [[-1, 1], [3, -1]]);
        assert!(net.transitions()[0].controllable && !net.transitions()[1].controllable);
        assert!(!net.transitions()[1].observable);
        let written = write(&net).unwrap();
        let again = read_str(&written).unwrap();
        assert_eq!(again.places(), net.places());
        assert_eq!(again.transitions(), net.transitions());
        assert_eq!(again.initial(), net.initial());
        // The native form and PNML carry the same net.
        let native = super::super::toml::write(&net);
        let via_toml = super::super::toml::read(&native, Path::new("n.toml")).unwrap();
        assert_eq!(write(&via_toml).unwrap(), written);
    }

    #[test]
    fn mistakes_are_located() {
        let cases = [
            (
                NET.replace(
                    r#"<toolspecific tool="codegen" version="1"><controllable>true</controllable></toolspecific>"#,
                    "",
                ),
                "n.pnml:9:7: transition `put` does not say whether it is controllable",
            ),
            (
                NET.replace("<text>3</text>", "<text>x</text>"),
                "n.pnml:12:60: <inscription> must be a whole number",
            ),
            (NET.replace("target=\"full\"", "target=\"fool\""), "n.pnml:12:7: arc names `fool`"),
            (NET.replace("ptnet", "symmetricnet"), "n.pnml:3:3: net type"),
            (NET.replace("<controllable>false", "<controllable>no"), "n.pnml:10:69: <controllable> must be true or false"),
            (NET.replace("<place id=\"full\">", "<place>"), "n.pnml:7:9: <place> without an `id`"),
            (
                NET.replace("<pnml xmlns", "<!DOCTYPE x [<!ENTITY a \"b\">]>\n<pnml xmlns"),
                "n.pnml:2:14: XML entity declarations are not accepted",
            ),
        ];
        for (text, expected) in cases {
            let err = read_str(&text).unwrap_err().to_string();
            assert!(err.starts_with(expected), "expected {expected}\ngot {err}");
        }
    }

    /// A net from another tool: nodes on a page, its own tool-specific
    /// data and labels holding things that look like nodes, and no word on
    /// controllability.
    const FOREIGN: &str = r#"<?xml version="1.0"?>
<pnml xmlns="http://www.pnml.org/version-2009/grammar/pnml">
  <net id="n" type="http://www.pnml.org/version-2009/grammar/ptnet">
    <name><text> spaced  net </text><place id="in-name"/></name>
    <toolspecific tool="PIPE" version="4"><place id="in-tool"/><transition id="t-tool"/></toolspecific>
    <page id="p">
      <place id="a"><name><text> a </text><graphics><place id="in-graphics"/></graphics></name><initialMarking><text> 1 </text></initialMarking></place>
      <place id="b"><toolspecific tool="TINA"><place id="deep"/></toolspecific></place>
      <transition id="go"><name><text>go	now</text></name></transition>
      <transition id="back"/>
      <arc id="x" source="a" target="go"/>
      <arc id="y" source="go" target="b"/>
      <arc id="z" source="b" target="back"/>
      <arc id="w" source="back" target="a"/>
    </page>
  </net>
</pnml>
"#;

    fn uncontrollable(ids: &[&str]) -> Control {
        Control {
            uncontrollable: Some(super::super::control::Listed::from_option(
                "--uncontrollable",
                ids.iter().map(|s| s.to_string()),
            )),
            ..Control::none("give --uncontrollable")
        }
    }

    #[test]
    fn only_the_page_structure_is_read_and_names_keep_their_whitespace() {
        let net = read_with(FOREIGN, Path::new("n.pnml"), &uncontrollable(&["back"])).unwrap();
        let ids = |v: Vec<&str>| v.join(" ");
        assert_eq!(
            ids(net.places().iter().map(|p| p.id.as_str()).collect()),
            "a b"
        );
        assert_eq!(
            ids(net.transitions().iter().map(|t| t.id.as_str()).collect()),
            "go back"
        );
        assert_eq!(net.name(), " spaced  net ");
        assert_eq!(net.places()[0].name.as_deref(), Some(" a "));
        assert_eq!(net.transitions()[0].name.as_deref(), Some("go\tnow"));
        assert_eq!(net.initial(), &[1, 0]);
        assert!(net.transitions()[0].controllable && !net.transitions()[1].controllable);
    }

    #[test]
    fn a_net_that_never_says_what_is_controllable_is_refused_unless_told() {
        let err = read_str(FOREIGN).unwrap_err().to_string();
        assert_eq!(
            err,
            "n.pnml:3:3: none of the net's 2 transitions says whether it is controllable \
             (PNML from other tools carries no controllability): state which transitions \
             are uncontrollable beside the file"
        );
        let err = read_with(FOREIGN, Path::new("n.pnml"), &uncontrollable(&["a"]))
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "--uncontrollable names `a`, which is a place, not a transition, of `n.pnml`"
        );
        // Every transition controllable is a statement too.
        let net = read_with(FOREIGN, Path::new("n.pnml"), &uncontrollable(&[])).unwrap();
        assert!(net
            .transitions()
            .iter()
            .all(|t| t.controllable && t.observable));
    }

    #[test]
    fn nodes_outside_a_page_are_refused_not_dropped() {
        let text = FOREIGN.replace(
            "    <page id=\"p\">\n",
            "    <place id=\"stray\"/>\n    <page id=\"p\">\n",
        );
        let err = read_with(&text, Path::new("n.pnml"), &uncontrollable(&[]))
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("n.pnml:6:5: a <place> directly in the <net>: PNML puts the net's nodes on a <page>"),
            "{err}"
        );
    }

    #[test]
    fn the_writer_refuses_what_xml_cannot_carry_naming_the_element() {
        let mut b = NetBuilder::new("n");
        let at = || crate::error::Location::file("n.toml");
        b.add_place("p", Some("bad\u{1}name".into()), 0, at())
            .unwrap();
        let err = write(&b.build()).unwrap_err().to_string();
        assert_eq!(
            err,
            "the name of place `p` holds U+0001, which XML 1.0 cannot carry, so PNML cannot \
             hold it (rename it, or keep the net in the native .toml)"
        );
        let mut b = NetBuilder::new("n");
        b.add_transition("t\u{fffe}", None, true, true, at())
            .unwrap();
        let err = write(&b.build()).unwrap_err().to_string();
        assert!(
            err.starts_with("the id of transition `t\\u{fffe}` holds U+FFFE"),
            "{err}"
        );
    }

    mod round_trip {
        use super::*;
        use proptest::prelude::*;

        /// Names from a mix of characters that need care: spaces at
        /// either end, XML markup, line ends, tabs, control characters
        /// XML cannot carry, non-characters, non-ASCII.
        fn text() -> impl Strategy<Value = String> {
            let carried = prop::sample::select(vec![
                " ", "  ", "a", "Z9", "&", "<", ">", "\"", "'", "]]>", "\n", "\r", "\r\n", "\t",
                "\u{7f}", "\u{85}", "é", "🙂", "&amp;", "&#1;",
            ]);
            let refused = prop::sample::select(vec!["\u{1}", "\u{1f}", "\u{fffe}", "\u{ffff}"]);
            // Mostly names XML can carry, so that about half the nets
            // round-trip and the others are refused.
            let pieces = prop_oneof![30 => carried, 1 => refused];
            prop::collection::vec(pieces, 0..6).prop_map(|v| v.concat())
        }

        fn net() -> impl Strategy<Value = PetriNet> {
            (
                text(),
                prop::collection::vec((text(), prop::option::of(text()), 0u32..3), 1..4),
                prop::collection::vec((text(), prop::option::of(text()), any::<bool>()), 0..3),
            )
                .prop_map(|(name, places, transitions)| {
                    let at = || crate::error::Location::file("n.toml");
                    let mut b = NetBuilder::new(name);
                    // Ids made unique and non-empty by a numbered prefix.
                    let mut first = String::new();
                    for (k, (id, label, tokens)) in places.into_iter().enumerate() {
                        let id = format!("p{k}{id}");
                        b.add_place(&id, label, tokens, at()).unwrap();
                        if k == 0 {
                            first = id;
                        }
                    }
                    for (k, (id, label, controllable)) in transitions.into_iter().enumerate() {
                        let id = format!("t{k}{id}");
                        b.add_transition(&id, label, controllable, !controllable, at())
                            .unwrap();
                        b.add_arc(&first, &id, 1, at()).unwrap();
                    }
                    b.build()
                })
        }

        fn carries(net: &PetriNet) -> bool {
            let texts = std::iter::once(net.name())
                .chain(
                    net.places()
                        .iter()
                        .flat_map(|p| [Some(p.id.as_str()), p.name.as_deref()])
                        .flatten(),
                )
                .chain(
                    net.transitions()
                        .iter()
                        .flat_map(|t| [Some(t.id.as_str()), t.name.as_deref()])
                        .flatten(),
                )
                .collect::<Vec<_>>();
            texts.iter().all(|t| t.chars().all(xml_char))
        }

        proptest! {
            #[test]
            fn names_survive_write_and_read_or_are_refused(net in net()) {
                match write(&net) {
                    Ok(text) => {
                        prop_assert!(carries(&net));
                        let back = read_str(&text).unwrap();
                        prop_assert_eq!(back, net);
                    }
                    Err(_) => prop_assert!(!carries(&net)),
                }
            }
        }
    }
}
