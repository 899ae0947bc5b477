//! PNML: place/transition nets as ISO/IEC 15909-2 writes them.
//!
//! Read: the one `<net>` of a `<pnml>` document, of the P/T-net type
//! (`…/ptnet`), its places, transitions and arcs on every page (pages
//! nest); `<name><text>`, `<initialMarking><text>` (default 0) and
//! `<inscription><text>` (default 1). PNML has no word for
//! controllability, so each transition carries it in a tool-specific
//! element, which other tools keep and ignore:
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
//! A transition without it is refused at its line, with the element to
//! add: taking it as controllable by default would let a supervisor count
//! on disabling what it cannot. Reference nodes (`referencePlace`,
//! `referenceTransition`) and other net types are refused; graphics and
//! other tools' elements are ignored. Written: the same, on one page.

use super::{NetBuilder, PetriNet};
use crate::error::Result;
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

    /// The trimmed `<text>` of child `tag` of `node`, with the text's node.
    fn text_of<'a, 'i>(&self, node: Node<'a, 'i>, tag: &str) -> Option<(Node<'a, 'i>, String)> {
        let child = node.children().find(|c| c.has_tag_name(tag))?;
        let text = child.children().find(|c| c.has_tag_name("text"))?;
        Some((text, text.text().unwrap_or("").trim().to_owned()))
    }

    /// A whole number from the `<text>` of child `tag`, or `default`.
    fn number(&self, node: Node<'_, '_>, tag: &str, default: u32) -> Result<u32> {
        match self.text_of(node, tag) {
            None => Ok(default),
            Some((at, text)) => text.parse().map_err(|_| {
                self.model(
                    at,
                    format!("<{tag}> must be a whole number from 0 to 2^32 - 1, not `{text}`"),
                )
            }),
        }
    }
}

/// Parses a PNML document; `origin` names the file in errors.
pub fn read(text: &str, origin: &Path) -> Result<PetriNet> {
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
    let name = match cx.text_of(net, "name") {
        Some((_, name)) if !name.is_empty() => name,
        _ => cx.id(net)?.to_owned(),
    };
    let mut b = NetBuilder::new(name);
    let mut arcs = Vec::new();
    for node in net.descendants().filter(|n| n.is_element()) {
        let name = || {
            cx.text_of(node, "name")
                .map(|(_, n)| n)
                .filter(|n| !n.is_empty())
        };
        match node.tag_name().name() {
            "place" => {
                let tokens = cx.number(node, "initialMarking", 0)?;
                b.add_place(cx.id(node)?, name(), tokens, cx.at(node))?;
            }
            "transition" => {
                let (controllable, observable) = control(&cx, node)?;
                b.add_transition(cx.id(node)?, name(), controllable, observable, cx.at(node))?;
            }
            "arc" => arcs.push(node),
            "referencePlace" | "referenceTransition" => {
                return Err(cx.model(node, "reference nodes are not read: merge the pages first"));
            }
            _ => {}
        }
    }
    for arc in arcs {
        let end = |key: &str| {
            arc.attribute(key)
                .ok_or_else(|| cx.model(arc, format!("<arc> without a `{key}`")))
        };
        let weight = cx.number(arc, "inscription", 1)?;
        b.add_arc(end("source")?, end("target")?, weight, cx.at(arc))?;
    }
    Ok(b.build())
}

/// A transition's `(controllable, observable)` from our tool-specific
/// element.
fn control(cx: &Ctx<'_>, t: Node<'_, '_>) -> Result<(bool, bool)> {
    let id = t.attribute("id").unwrap_or("");
    let Some(ours) = t
        .children()
        .find(|c| c.has_tag_name("toolspecific") && c.attribute("tool") == Some(TOOL))
    else {
        return Err(cx.model(
            t,
            format!(
                "transition `{id}` does not say whether it is controllable: add \
                 <toolspecific tool=\"{TOOL}\" version=\"1\"><controllable>true</controllable></toolspecific> \
                 (or false) inside it"
            ),
        ));
    };
    let flag = |tag: &str, default: Option<bool>| -> Result<bool> {
        match ours.children().find(|c| c.has_tag_name(tag)) {
            None => default.ok_or_else(|| {
                cx.model(
                    ours,
                    format!("transition `{id}`: <toolspecific tool=\"{TOOL}\"> needs <{tag}>"),
                )
            }),
            Some(node) => match node.text().unwrap_or("").trim() {
                "true" => Ok(true),
                "false" => Ok(false),
                other => Err(cx.model(
                    node,
                    format!("<{tag}> must be true or false, not `{other}`"),
                )),
            },
        }
    };
    Ok((flag("controllable", None)?, flag("observable", Some(true))?))
}

/// Renders `net` as a PNML document (one page; arcs numbered `a1`, `a2`,
/// … in transition order).
pub fn write(net: &PetriNet) -> String {
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
    out
}

/// Text for XML content and attribute values.
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
        let written = write(&net);
        let again = read_str(&written).unwrap();
        assert_eq!(again.places(), net.places());
        assert_eq!(again.transitions(), net.transitions());
        assert_eq!(again.initial(), net.initial());
        // The native form and PNML carry the same net.
        let native = super::super::toml::write(&net);
        let via_toml = super::super::toml::read(&native, Path::new("n.toml")).unwrap();
        assert_eq!(write(&via_toml), written);
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
}
