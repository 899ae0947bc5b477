//! Supremica / Waters modules (`.wmod`).
//!
//! # The format
//!
//! A module is an XML document in the namespace
//! `http://waters.sourceforge.net/xsd/module` (comments and attribute
//! maps use `http://waters.sourceforge.net/xsd/base`). It declares its
//! events once, in `<EventDeclList>`, each with a `Kind`:
//! `CONTROLLABLE`, `UNCONTROLLABLE` or `PROPOSITION` (propositions such
//! as `:accepting` label states, not transitions). `<ComponentList>`
//! holds the automata: one `<SimpleComponent Kind="PLANT|SPEC|SUPERVISOR|PROPERTY">`
//! each, whose `<Graph>` lists nodes (`<SimpleNode Name=… Initial="true">`,
//! marked nodes carry `:accepting` in their `<EventList>`) and edges
//! (`<Edge Source=… Target=…>` with the events in a `<LabelBlock>`).
//!
//! # How modules map to automata
//!
//! - One [`Component`] per `SimpleComponent`, in file order, with its
//!   kind; nodes become states in list order.
//! - A component's alphabet is the events on its edges plus those in its
//!   graph's own `<LabelBlock>` (events the component blocks), in the
//!   module's declaration order.
//! - When `:accepting` occurs neither on a node nor in the graph's
//!   `<LabelBlock>`, the proposition is outside the component's alphabet
//!   and every state counts as marked (Waters' convention).
//! - Layout (`PointGeometry`, `SplineGeometry`, …), comments and attribute
//!   maps are ignored. Constructs that change the meaning of a module but
//!   have no counterpart here (indexed identifiers, `ForeachComponent`,
//!   `Instance`, `VariableComponent` and other EFA features, guards and
//!   actions, parameters, aliases, propositions other than `:accepting`)
//!   are rejected with an error naming the construct and its position,
//!   never silently dropped.
//!
//! # Writing
//!
//! [`write()`] emits one `SimpleComponent` per component (`Kind="PLANT"` for
//! plants and components of unstated role), declares every event once
//! (controllability taken from the first component that has it) and
//! `:accepting` when needed, groups all events between the same pair of
//! nodes into one edge, and lists alphabet events that occur on no edge
//! in the graph's `<LabelBlock>`. A component with states but no marked
//! state lists `:accepting` there too, so that it does not read back as
//! "all marked". A name holding a character that XML 1.0 cannot carry at
//! all (most ASCII control characters) is refused by
//! [`super::write_string`] ([`unwritable_name`]); [`write()`] itself
//! writes such a character as U+FFFD.

use super::{Component, Kind, XmlSource as Ctx};
use crate::automaton::{Alphabet, AutomatonBuilder, BuildError, StateId};
use crate::error::{line_column, Error, Location, Result};
use rustc_hash::FxHashMap;
use std::fmt::Write as _;
use std::path::Path;

/// The Waters module namespace.
pub const MODULE_NS: &str = "http://waters.sourceforge.net/xsd/module";
/// The Waters base namespace (`B:Comment`, attribute maps).
pub const BASE_NS: &str = "http://waters.sourceforge.net/xsd/base";
/// The proposition that marks states.
pub const ACCEPTING: &str = ":accepting";

type Node<'a, 'i> = roxmltree::Node<'a, 'i>;

impl Ctx<'_> {
    fn unsupported(&self, node: Node<'_, '_>, what: &str) -> Error {
        let loc = self.at(node);
        Error::model(
            loc.clone(),
            format!("unsupported Waters construct `{what}` at {loc}"),
        )
    }

    fn attr<'a>(&self, node: Node<'a, '_>, key: &str) -> Result<&'a str> {
        node.attribute(key).ok_or_else(|| {
            self.syntax(
                node,
                format!("`<{}>` lacks its `{key}` attribute", node.tag_name().name()),
            )
        })
    }
}

fn elements<'a, 'i>(node: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(|c| c.is_element())
}

fn name_of<'a>(node: Node<'a, '_>) -> &'a str {
    node.tag_name().name()
}

/// Elements that only carry layout or annotations.
fn is_decoration(node: Node<'_, '_>) -> bool {
    node.tag_name().namespace() == Some(BASE_NS)
        || matches!(
            name_of(node),
            "PointGeometry"
                | "LabelGeometry"
                | "InitialArrowGeometry"
                | "SplineGeometry"
                | "StartPointGeometry"
                | "EndPointGeometry"
                | "ColorGeometry"
                | "BoxGeometry"
                | "Comment"
                | "AttributeMap"
        )
}

/// An event declaration.
#[derive(Clone, Copy)]
struct Decl {
    /// Position in the declaration list.
    order: usize,
    /// `None` for propositions.
    controllable: Option<bool>,
    /// `Observable="false"` makes it unobservable.
    observable: bool,
}

/// The attributes an `<EventDecl>` may have; any other is refused rather
/// than dropped.
const DECL_ATTRIBUTES: [&str; 4] = ["Kind", "Name", "Observable", "Scope"];

/// Parses a Waters module; `origin` names the file in errors.
pub fn read(text: &str, origin: &Path) -> Result<Vec<Component>> {
    let doc = super::parse_xml(text, origin)?;
    let cx = Ctx { text, origin };
    let root = doc.root_element();
    if name_of(root) == "ModuleSequence" {
        return Err(cx.unsupported(root, "ModuleSequence"));
    }
    if name_of(root) != "Module" {
        return Err(cx.syntax(
            root,
            format!(
                "expected a Waters `<Module>` root element, found `<{}>`",
                name_of(root)
            ),
        ));
    }
    match root.tag_name().namespace() {
        None | Some(MODULE_NS) => {}
        Some(ns) => {
            return Err(cx.syntax(
                root,
                format!("expected the Waters module namespace `{MODULE_NS}`, found `{ns}`"),
            ))
        }
    }

    let mut decls: FxHashMap<&str, Decl> = FxHashMap::default();
    let mut decl_names: Vec<&str> = Vec::new();
    let mut component_lists = Vec::new();
    for child in elements(root) {
        match name_of(child) {
            _ if is_decoration(child) => {}
            "EventDeclList" => {
                for d in elements(child) {
                    if is_decoration(d) {
                        continue;
                    }
                    if name_of(d) != "EventDecl" {
                        return Err(cx.unsupported(d, name_of(d)));
                    }
                    read_decl(&cx, d, &mut decls, &mut decl_names)?;
                }
            }
            "ConstantAliasList" | "EventAliasList" => {
                if let Some(alias) = elements(child).find(|n| !is_decoration(*n)) {
                    return Err(cx.unsupported(alias, name_of(alias)));
                }
            }
            "ComponentList" => component_lists.push(child),
            other => return Err(cx.unsupported(child, other)),
        }
    }

    let mut components = Vec::new();
    for list in component_lists {
        for c in elements(list) {
            match name_of(c) {
                _ if is_decoration(c) => {}
                "SimpleComponent" => components.push(read_component(&cx, c, &decls, &decl_names)?),
                other => return Err(cx.unsupported(c, other)),
            }
        }
    }
    Ok(components)
}

fn read_decl<'a>(
    cx: &Ctx<'_>,
    d: Node<'a, '_>,
    decls: &mut FxHashMap<&'a str, Decl>,
    names: &mut Vec<&'a str>,
) -> Result<()> {
    let name = match d.attribute("Name") {
        Some(n) => n,
        None => {
            return Err(
                match elements(d).find(|c| name_of(*c) == "IndexedIdentifier") {
                    Some(ix) => cx.unsupported(ix, "IndexedIdentifier"),
                    None => cx.syntax(d, "`<EventDecl>` lacks its `Name` attribute"),
                },
            )
        }
    };
    if let Some(scope) = d.attribute("Scope") {
        if scope != "LOCAL" {
            return Err(cx.unsupported(d, &format!("event parameter (Scope=\"{scope}\")")));
        }
    }
    if let Some(c) = elements(d).find(|c| !is_decoration(*c)) {
        // Index ranges (`RangeList`, …) make an event array.
        return Err(cx.unsupported(c, name_of(c)));
    }
    if let Some(other) = d
        .attributes()
        .find(|a| a.namespace().is_none() && !DECL_ATTRIBUTES.contains(&a.name()))
    {
        return Err(cx.unsupported(d, &format!("event attribute `{}`", other.name())));
    }
    let observable = match d.attribute("Observable") {
        None | Some("true") => true,
        Some("false") => false,
        Some(other) => {
            return Err(cx.syntax(
                d,
                format!("`Observable=\"{other}\"` (expected true or false)"),
            ))
        }
    };
    let controllable = match cx.attr(d, "Kind")? {
        "CONTROLLABLE" => Some(true),
        "UNCONTROLLABLE" => Some(false),
        "PROPOSITION" => None,
        other => {
            return Err(cx.syntax(
                d,
                format!(
                    "unknown event kind `{other}` (expected CONTROLLABLE, UNCONTROLLABLE or PROPOSITION)"
                ),
            ))
        }
    };
    if decls.contains_key(name) {
        return Err(cx.model(d, format!("event `{name}` is declared twice")));
    }
    decls.insert(
        name,
        Decl {
            order: names.len(),
            controllable,
            observable,
        },
    );
    names.push(name);
    Ok(())
}

/// The names in a `<LabelBlock>` or `<EventList>`.
fn identifiers<'a, 'i>(cx: &Ctx<'_>, block: Node<'a, 'i>) -> Result<Vec<(&'a str, Node<'a, 'i>)>> {
    let mut out = Vec::new();
    for id in elements(block) {
        match name_of(id) {
            _ if is_decoration(id) => {}
            "SimpleIdentifier" => out.push((cx.attr(id, "Name")?, id)),
            other => return Err(cx.unsupported(id, other)),
        }
    }
    Ok(out)
}

fn read_component(
    cx: &Ctx<'_>,
    c: Node<'_, '_>,
    decls: &FxHashMap<&str, Decl>,
    decl_names: &[&str],
) -> Result<Component> {
    let name = match c.attribute("Name") {
        Some(n) => n,
        None => {
            return Err(
                match elements(c).find(|n| name_of(*n).ends_with("Identifier")) {
                    Some(ix) => cx.unsupported(ix, name_of(ix)),
                    None => cx.syntax(c, "`<SimpleComponent>` lacks its `Name` attribute"),
                },
            )
        }
    };
    let kind = match cx.attr(c, "Kind")? {
        "PLANT" => Kind::Plant,
        "SPEC" => Kind::Spec,
        "SUPERVISOR" => Kind::Supervisor,
        "PROPERTY" => Kind::Property,
        other => {
            return Err(cx.syntax(
                c,
                format!(
                "unknown component kind `{other}` (expected PLANT, SPEC, SUPERVISOR or PROPERTY)"
            ),
            ))
        }
    };
    let mut graph = None;
    for child in elements(c) {
        match name_of(child) {
            _ if is_decoration(child) => {}
            "Graph" if graph.is_none() => graph = Some(child),
            other => return Err(cx.unsupported(child, other)),
        }
    }
    let graph =
        graph.ok_or_else(|| cx.syntax(c, format!("component `{name}` has no `<Graph>`")))?;

    // Events and propositions, checked against the declarations.
    let event = |name: &str, at: Node<'_, '_>| -> Result<(usize, Option<bool>)> {
        match decls.get(name) {
            Some(d) => Ok((d.order, d.controllable)),
            None => Err(cx.model(
                at,
                format!("event `{name}` is not declared in the module's <EventDeclList>"),
            )),
        }
    };
    let mut in_alphabet = vec![false; decl_names.len()];
    let mut explicit_marking = false;
    let (mut blocks, mut node_list, mut edge_list) = (None, None, None);
    for child in elements(graph) {
        match name_of(child) {
            _ if is_decoration(child) => {}
            "LabelBlock" if blocks.is_none() => blocks = Some(child),
            "NodeList" if node_list.is_none() => node_list = Some(child),
            "EdgeList" if edge_list.is_none() => edge_list = Some(child),
            other => return Err(cx.unsupported(child, other)),
        }
    }
    if let Some(block) = blocks {
        for (ev, at) in identifiers(cx, block)? {
            let (order, controllable) = event(ev, at)?;
            match controllable {
                Some(_) => in_alphabet[order] = true,
                None if ev == ACCEPTING => explicit_marking = true,
                None => return Err(cx.unsupported(at, &format!("proposition {ev}"))),
            }
        }
    }

    // Nodes.
    struct NodeInfo {
        initial: bool,
        accepting: bool,
        pos: usize,
    }
    let mut nodes: Vec<(&str, NodeInfo)> = Vec::new();
    let mut node_index: FxHashMap<&str, usize> = FxHashMap::default();
    if let Some(list) = node_list {
        for n in elements(list) {
            match name_of(n) {
                _ if is_decoration(n) => continue,
                "SimpleNode" => {}
                other => return Err(cx.unsupported(n, other)),
            }
            let node_name = cx.attr(n, "Name")?;
            let initial = match n.attribute("Initial") {
                None | Some("false") => false,
                Some("true") => true,
                Some(other) => {
                    return Err(cx.syntax(
                        n,
                        format!("`Initial` must be `true` or `false`, found `{other}`"),
                    ))
                }
            };
            let mut accepting = false;
            for child in elements(n) {
                match name_of(child) {
                    _ if is_decoration(child) => {}
                    "EventList" => {
                        for (prop, at) in identifiers(cx, child)? {
                            match event(prop, at)? {
                                (_, None) if prop == ACCEPTING => accepting = true,
                                (_, None) => {
                                    return Err(cx.unsupported(at, &format!("proposition {prop}")))
                                }
                                (_, Some(_)) => {
                                    return Err(cx.model(
                                        at,
                                        format!(
                                        "`{prop}` labels a node but is an event, not a proposition"
                                    ),
                                    ))
                                }
                            }
                        }
                    }
                    other => return Err(cx.unsupported(child, other)),
                }
            }
            explicit_marking |= accepting;
            if node_index.insert(node_name, nodes.len()).is_some() {
                return Err(cx.model(
                    n,
                    format!("component `{name}` has two nodes called `{node_name}`"),
                ));
            }
            nodes.push((
                node_name,
                NodeInfo {
                    initial,
                    accepting,
                    pos: n.range().start,
                },
            ));
        }
    }

    // Edges.
    let mut edges: Vec<(usize, usize, usize, usize)> = Vec::new(); // (source, decl order, target, pos)
    if let Some(list) = edge_list {
        for e in elements(list) {
            match name_of(e) {
                _ if is_decoration(e) => continue,
                "Edge" => {}
                other => return Err(cx.unsupported(e, other)),
            }
            let endpoint = |key: &str| -> Result<usize> {
                let n = cx.attr(e, key)?;
                node_index.get(n).copied().ok_or_else(|| {
                    cx.model(
                        e,
                        format!("edge {key} `{n}` is not a node of component `{name}`"),
                    )
                })
            };
            let (s, t) = (endpoint("Source")?, endpoint("Target")?);
            for child in elements(e) {
                match name_of(child) {
                    _ if is_decoration(child) => {}
                    "LabelBlock" => {
                        for (ev, at) in identifiers(cx, child)? {
                            match event(ev, at)? {
                                (order, Some(_)) => {
                                    in_alphabet[order] = true;
                                    edges.push((s, order, t, at.range().start));
                                }
                                (_, None) => {
                                    return Err(cx.model(
                                        at,
                                        format!("`{ev}` is a proposition and cannot label an edge"),
                                    ))
                                }
                            }
                        }
                    }
                    other => return Err(cx.unsupported(child, other)),
                }
            }
        }
    }

    // Build.
    let mut b = AutomatonBuilder::new(name);
    let mut event_ids = vec![None; decl_names.len()];
    for (order, &n) in decl_names.iter().enumerate() {
        if in_alphabet[order] {
            let decl = decls.get(n);
            let controllable = decl.and_then(|d| d.controllable).unwrap_or(false);
            let id = b
                .add_event(n, controllable)
                .map_err(|e| Error::model(Location::file(cx.origin), e.to_string()))?;
            if decl.is_some_and(|d| !d.observable) {
                b.set_unobservable(id);
            }
            event_ids[order] = Some(id);
        }
    }
    let mut states = Vec::with_capacity(nodes.len());
    for (node_name, info) in &nodes {
        let s = b.add_state(node_name);
        if info.initial {
            b.set_initial(s).map_err(|e| {
                Error::model(
                    Location::at_offset(cx.origin, cx.text, info.pos),
                    e.to_string(),
                )
            })?;
        }
        if info.accepting || !explicit_marking {
            b.mark(s);
        }
        states.push(s);
    }
    for (s, order, t, pos) in edges {
        if let Some(e) = event_ids[order] {
            b.add_transition(
                states[s],
                e,
                states[t],
                u32::try_from(pos).unwrap_or(u32::MAX),
            );
        }
    }
    let mut a = b.build().map_err(|e| match &e {
        BuildError::Nondeterministic {
            line, first_line, ..
        } => {
            let (l, c) = line_column(cx.text, *first_line as usize);
            Error::model(
                Location::at_offset(cx.origin, cx.text, *line as usize),
                format!("{e} (the other transition is at line {l}, column {c})"),
            )
        }
        _ => Error::model(Location::file(cx.origin), e.to_string()),
    })?;
    super::gen::drop_index_names(&mut a);
    Ok(Component { kind, automaton: a })
}

/// Escapes text for an XML attribute value; characters XML 1.0 cannot
/// carry become U+FFFD ([`write_string`](super::write_string) refuses
/// names holding them first, see [`unwritable_name`]).
fn escape_into(out: &mut String, s: &str) {
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '\t' => out.push_str("&#9;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            '\u{0}'..='\u{1f}' | '\u{fffe}' | '\u{ffff}' => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
}

fn attr(out: &mut String, key: &str, value: &str) {
    out.push(' ');
    out.push_str(key);
    out.push_str("=\"");
    escape_into(out, value);
    out.push('"');
}

fn identifier(out: &mut String, indent: &str, name: &str) {
    out.push_str(indent);
    out.push_str("<SimpleIdentifier");
    attr(out, "Name", name);
    out.push_str("/>\n");
}

/// A character XML 1.0 cannot carry (escaping cannot help).
fn unwritable(c: char) -> bool {
    matches!(c, '\u{0}'..='\u{8}' | '\u{b}' | '\u{c}' | '\u{e}'..='\u{1f}' | '\u{fffe}' | '\u{ffff}')
}

/// The first name of `components` (automaton, event or state) holding a
/// character a `.wmod` file cannot carry, described for an error: written
/// anyway it would become U+FFFD, and two names could collapse into one.
pub fn unwritable_name(components: &[Component]) -> Option<String> {
    let bad = |what: String, name: &str| {
        name.chars().find(|&c| unwritable(c)).map(|c| {
            format!(
                "{what} {name:?} holds U+{:04X}, which a .wmod file (XML 1.0) cannot carry; rename it",
                c as u32
            )
        })
    };
    components.iter().find_map(|c| {
        let a = &c.automaton;
        bad("automaton".into(), a.name())
            .or_else(|| {
                a.alphabet()
                    .iter()
                    .find_map(|(_, e)| bad(format!("event of `{}`", a.name()), &e.name))
            })
            .or_else(|| {
                a.states()
                    .find_map(|s| bad(format!("state of `{}`", a.name()), &a.state_name(s)))
            })
    })
}

/// Renders components as one Waters module.
pub fn write(components: &[Component]) -> String {
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"yes\"?>\n<Module");
    let module_name = match components {
        [only] => only.automaton.name(),
        _ => "module",
    };
    attr(&mut out, "Name", module_name);
    let _ = writeln!(out, " xmlns=\"{MODULE_NS}\" xmlns:B=\"{BASE_NS}\">");

    // Declarations: the union of the alphabets, first controllability
    // wins, unobservable where any component says so.
    let mut all = Alphabet::new();
    for c in components {
        for (_, e) in c.automaton.alphabet().iter() {
            match all.id(&e.name) {
                Some(id) if !e.observable => all.set_unobservable(id),
                Some(_) => {}
                None => {
                    let _ = all.insert_event(e);
                }
            }
        }
    }
    // A component needs the proposition unless it marks every state.
    let needs_accepting = |c: &Component| {
        let a = &c.automaton;
        a.num_states() > 0 && a.marked_states().count() < a.num_states()
    };
    let any_accepting = components.iter().any(needs_accepting);
    out.push_str("  <EventDeclList>\n");
    for (_, e) in all.iter() {
        out.push_str("    <EventDecl");
        attr(
            &mut out,
            "Kind",
            if e.controllable {
                "CONTROLLABLE"
            } else {
                "UNCONTROLLABLE"
            },
        );
        attr(&mut out, "Name", &e.name);
        if !e.observable {
            attr(&mut out, "Observable", "false");
        }
        out.push_str("/>\n");
    }
    if any_accepting {
        out.push_str("    <EventDecl Kind=\"PROPOSITION\" Name=\":accepting\"/>\n");
    }
    out.push_str("  </EventDeclList>\n  <ComponentList>\n");
    for c in components {
        write_component(&mut out, c, needs_accepting(c));
    }
    out.push_str("  </ComponentList>\n</Module>\n");
    out
}

fn write_component(out: &mut String, c: &Component, accepting: bool) {
    let a = &c.automaton;
    out.push_str("    <SimpleComponent");
    attr(
        out,
        "Kind",
        match c.kind {
            Kind::Plant | Kind::Unspecified => "PLANT",
            Kind::Spec => "SPEC",
            Kind::Supervisor => "SUPERVISOR",
            Kind::Property => "PROPERTY",
        },
    );
    attr(out, "Name", a.name());
    out.push_str(">\n      <Graph>\n");

    let mut used = vec![false; a.alphabet().len()];
    for (_, e, _) in a.iter_transitions() {
        used[e.index()] = true;
    }
    // Marking is explicit when some state is unmarked; with no marked
    // state at all, the proposition goes into the graph's label block.
    let none_marked = a.num_states() > 0 && a.marked_states().next().is_none();
    let blocked: Vec<&str> = a
        .alphabet()
        .iter()
        .filter(|(id, _)| !used[id.index()])
        .map(|(_, e)| e.name.as_str())
        .chain((accepting && none_marked).then_some(ACCEPTING))
        .collect();
    if !blocked.is_empty() {
        out.push_str("        <LabelBlock>\n");
        for n in blocked {
            identifier(out, "          ", n);
        }
        out.push_str("        </LabelBlock>\n");
    }
    if a.num_states() > 0 {
        out.push_str("        <NodeList>\n");
        for s in a.states() {
            out.push_str("          <SimpleNode");
            if a.initial() == Some(s) {
                out.push_str(" Initial=\"true\"");
            }
            attr(out, "Name", &a.state_name(s));
            if accepting && a.is_marked(s) {
                out.push_str(">\n            <EventList>\n");
                identifier(out, "              ", ACCEPTING);
                out.push_str("            </EventList>\n          </SimpleNode>\n");
            } else {
                out.push_str("/>\n");
            }
        }
        out.push_str("        </NodeList>\n");
    }
    if a.num_transitions() > 0 {
        out.push_str("        <EdgeList>\n");
        for s in a.states() {
            // Group this state's transitions by target, in order of the
            // first event to each target.
            let mut groups: Vec<(StateId, Vec<&str>)> = Vec::new();
            for t in a.transitions(s) {
                let name = a.alphabet().name(t.event);
                match groups.iter_mut().find(|(target, _)| *target == t.target) {
                    Some((_, events)) => events.push(name),
                    None => groups.push((t.target, vec![name])),
                }
            }
            for (target, events) in groups {
                out.push_str("          <Edge");
                attr(out, "Source", &a.state_name(s));
                attr(out, "Target", &a.state_name(target));
                out.push_str(">\n            <LabelBlock>\n");
                for e in events {
                    identifier(out, "              ", e);
                }
                out.push_str("            </LabelBlock>\n          </Edge>\n");
            }
        }
        out.push_str("        </EdgeList>\n");
    }
    out.push_str("      </Graph>\n    </SimpleComponent>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_xml_cannot_carry_are_refused_not_collapsed() {
        let mut b = AutomatonBuilder::new("m");
        b.add_event("go\u{1}", true).unwrap();
        b.add_event("go\u{2}", true).unwrap();
        let c = Component {
            kind: Kind::Plant,
            automaton: b.build().unwrap(),
        };
        let err = super::super::write_string(super::super::Format::Wmod, std::slice::from_ref(&c))
            .unwrap_err()
            .to_string();
        assert!(err.contains("U+0001"), "{err}");
        // Written to a file, the error names it, and no file is left.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.wmod");
        let err = super::super::write_file(&path, &[c])
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with(&format!("{}: event", path.display())),
            "{err}"
        );
        assert!(!path.exists());
        // Tabs and line breaks are escaped, not refused.
        let mut b = AutomatonBuilder::new("m\tn");
        b.add_event("go\nnow", true).unwrap();
        let c = Component {
            kind: Kind::Plant,
            automaton: b.build().unwrap(),
        };
        assert!(super::super::write_string(super::super::Format::Wmod, &[c]).is_ok());
    }

    const SMALL: &str = r#"<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<Module Name="small" xmlns="http://waters.sourceforge.net/xsd/module" xmlns:B="http://waters.sourceforge.net/xsd/base">
<B:Comment>A machine and a buffer.</B:Comment>
<EventDeclList>
<EventDecl Kind="CONTROLLABLE" Name="start"/>
<EventDecl Kind="UNCONTROLLABLE" Name="finish"/>
<EventDecl Kind="UNCONTROLLABLE" Name="break"/>
<EventDecl Kind="PROPOSITION" Name=":accepting"/>
</EventDeclList>
<ComponentList>
<SimpleComponent Kind="PLANT" Name="M">
<Graph Deterministic="true">
<LabelBlock><SimpleIdentifier Name="break"/><LabelGeometry Anchor="NW"><Point X="1" Y="2"/></LabelGeometry></LabelBlock>
<NodeList>
<SimpleNode Initial="true" Name="idle">
<EventList><SimpleIdentifier Name=":accepting"/></EventList>
<PointGeometry><Point X="10" Y="10"/></PointGeometry>
</SimpleNode>
<SimpleNode Name="working"><PointGeometry><Point X="10" Y="50"/></PointGeometry></SimpleNode>
</NodeList>
<EdgeList>
<Edge Source="idle" Target="working">
<LabelBlock><SimpleIdentifier Name="start"/></LabelBlock>
<SplineGeometry><Point X="1" Y="1"/></SplineGeometry>
</Edge>
<Edge Source="working" Target="idle">
<LabelBlock><SimpleIdentifier Name="finish"/></LabelBlock>
</Edge>
</EdgeList>
</Graph>
</SimpleComponent>
<SimpleComponent Kind="SPEC" Name="S">
<Graph>
<NodeList><SimpleNode Initial="true" Name="0"/><SimpleNode Name="1"/></NodeList>
<EdgeList><Edge Source="0" Target="1"><LabelBlock><SimpleIdentifier Name="finish"/><SimpleIdentifier Name="start"/></LabelBlock></Edge></EdgeList>
</Graph>
</SimpleComponent>
</ComponentList>
</Module>
"#;

    fn p() -> &'static Path {
        Path::new("m.wmod")
    }

    fn err(text: &str) -> (u32, u32, String) {
        let e = read(text, p()).unwrap_err();
        let (l, m) = e.located().unwrap_or_else(|| panic!("unexpected {e:?}"));
        (l.line, l.column, m.to_owned())
    }

    #[test]
    fn a_module_reads_into_components() {
        let cs = read(SMALL, p()).unwrap();
        assert_eq!(cs.len(), 2);
        assert_eq!(cs[0].kind, Kind::Plant);
        let m = &cs[0].automaton;
        assert_eq!(m.name(), "M");
        assert_eq!((m.num_states(), m.num_transitions()), (2, 2));
        assert_eq!(m.alphabet().len(), 3, "blocked `break` is in the alphabet");
        assert!(m
            .alphabet()
            .is_controllable(m.alphabet().id("start").unwrap()));
        assert_eq!(m.marked_states().collect::<Vec<_>>(), [StateId(0)]);
        let s = &cs[1].automaton;
        assert_eq!(cs[1].kind, Kind::Spec);
        assert_eq!(s.num_transitions(), 2);
        assert_eq!(s.marked_states().count(), 2, "no :accepting: all marked");
        assert!(!s.has_state_names());
    }

    #[test]
    fn round_trip_keeps_alphabet_marking_and_kinds() {
        let cs = read(SMALL, p()).unwrap();
        let text = write(&cs);
        assert_eq!(read(&text, p()).unwrap(), cs);
        // One edge with both events of the spec.
        assert_eq!(text.matches("<Edge ").count(), 3, "{text}");
    }

    #[test]
    fn no_marked_state_round_trips() {
        let mut b = AutomatonBuilder::new("dead");
        let s = b.add_state("only");
        b.set_initial(s).unwrap();
        b.add_event("a", true).unwrap();
        let c = Component {
            kind: Kind::Supervisor,
            automaton: b.build().unwrap(),
        };
        let back = read(&write(std::slice::from_ref(&c)), p()).unwrap();
        assert_eq!(back, [c]);
    }

    #[test]
    fn unobservable_events_round_trip_and_unknown_event_attributes_are_refused() {
        let hidden = SMALL.replace(
            "<EventDecl Kind=\"UNCONTROLLABLE\" Name=\"break\"/>",
            "<EventDecl Kind=\"UNCONTROLLABLE\" Name=\"break\" Observable=\"false\"/>",
        );
        let cs = read(&hidden, p()).unwrap();
        let m = cs[0].automaton.alphabet();
        assert!(!m.is_observable(m.id("break").unwrap()));
        assert!(m.is_observable(m.id("finish").unwrap()));
        let text = write(&cs);
        assert!(
            text.contains("Name=\"break\" Observable=\"false\"/>"),
            "{text}"
        );
        assert_eq!(read(&text, p()).unwrap(), cs);
        assert_eq!(
            read(
                &hidden.replace("Observable=\"false\"", "Observable=\"true\""),
                p()
            )
            .unwrap(),
            read(SMALL, p()).unwrap()
        );
        let (l, _, m) = err(&hidden.replace("Observable=\"false\"", "Observable=\"no\""));
        assert_eq!(l, 7, "{m}");
        assert!(m.contains("expected true or false"), "{m}");
        let (l, _, m) =
            err(&SMALL.replace("Name=\"finish\"/>", "Name=\"finish\" Forcible=\"true\"/>"));
        assert_eq!(l, 6, "{m}");
        assert!(
            m.contains("unsupported Waters construct `event attribute `Forcible``"),
            "{m}"
        );
    }

    #[test]
    fn errors_and_unsupported_constructs_are_located() {
        let (l, c, m) = err(&SMALL.replace(
            "<SimpleIdentifier Name=\"finish\"/></LabelBlock>\n</Edge>",
            "<SimpleIdentifier Name=\"fnish\"/></LabelBlock>\n</Edge>",
        ));
        assert_eq!((l, c), (27, 13), "{m}");
        assert!(m.contains("`fnish` is not declared"), "{m}");

        let (l, _, m) = err(&SMALL.replace(
            "<SimpleIdentifier Name=\"start\"/></LabelBlock>\n<Spline",
            "<SimpleIdentifier Name=\"start\"/></LabelBlock><GuardActionBlock/>\n<Spline",
        ));
        assert_eq!(l, 23, "{m}");
        assert!(
            m.contains("unsupported Waters construct `GuardActionBlock` at m.wmod:23:"),
            "{m}"
        );

        let (l, _, m) = err(&SMALL.replace(
            "<SimpleComponent Kind=\"SPEC\"",
            "<ForeachComponent Name=\"i\"/>\n<SimpleComponent Kind=\"SPEC\"",
        ));
        assert_eq!(l, 32, "{m}");
        assert!(m.contains("`ForeachComponent`"), "{m}");

        let (l, _, m) = err(&SMALL.replace(
            "<Edge Source=\"working\" Target=\"idle\">\n<LabelBlock><SimpleIdentifier Name=\"finish\"/>",
            "<Edge Source=\"idle\" Target=\"idle\">\n<LabelBlock><SimpleIdentifier Name=\"start\"/>",
        ));
        assert_eq!(l, 27, "{m}");
        assert!(
            m.contains("nondeterministic") && m.contains("line 23"),
            "{m}"
        );

        let (l, _, m) = err(&SMALL.replace(
            "<SimpleNode Name=\"working\">",
            "<SimpleNode Name=\"working\" Initial=\"true\">",
        ));
        assert_eq!(l, 19, "{m}");
        assert!(m.contains("two initial states"), "{m}");

        let (l, c, m) = err(&SMALL.replace("<NodeList>\n", "<NodeList>\n<Simple"));
        assert_eq!((l, c), (15, 8), "{m}");
        assert!(m.contains("malformed XML"), "{m}");
    }
}
