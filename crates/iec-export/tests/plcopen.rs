//! The PLCopen XML export read back: every POU, variable, type, address,
//! initial value and body of the export is in the file as the schema
//! places it, for every seed project and for hostile names. (The schema
//! itself and an independent ST parser are checked by `cargo xtask iec`.)

use iec_export::plcopen::{self, CREATION_DATE_TIME, NAMESPACE, XHTML};
use iec_export::pou::{Init, PouKind, Section, Type};
use iec_export::{self as iec, comment_text, Export, IoMap};
use plc_project::{self as project, Project};
use roxmltree::{Document, Node};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The seed projects (docs/seeds.md) and the boiler, modular and
/// monolithic.
fn seeds() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root().join("models"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".plc.toml"))
        .collect();
    paths.sort();
    for p in [
        "models/boiler/boiler.plc.toml",
        "models/boiler/boiler_mono.plc.toml",
        "models/petri/mixers.plc.toml",
        "models/petri/cell/cell.plc.toml",
    ] {
        paths.push(root().join(p));
    }
    assert!(paths.len() >= 10, "{paths:?}");
    paths
}

fn export_of(project: &Project, io: &IoMap) -> Export {
    iec::export(project, io, "codegen plcopen t.plc.toml").unwrap()
}

fn el<'a>(node: Node<'a, 'a>, name: &'a str) -> Node<'a, 'a> {
    children(node, name)
        .next()
        .unwrap_or_else(|| panic!("<{}> has no <{name}>", node.tag_name().name()))
}

fn children<'a>(node: Node<'a, 'a>, name: &'a str) -> impl Iterator<Item = Node<'a, 'a>> {
    node.children()
        .filter(move |c| c.is_element() && c.has_tag_name((NAMESPACE, name)))
}

fn elements<'a>(node: Node<'a, 'a>) -> Vec<Node<'a, 'a>> {
    node.children().filter(|c| c.is_element()).collect()
}

fn attr<'a>(node: Node<'a, '_>, name: &str) -> &'a str {
    node.attribute(name)
        .unwrap_or_else(|| panic!("<{}> has no {name}", node.tag_name().name()))
}

/// The text of a formatted-text element: one `xhtml:p`, CDATA inside.
fn formatted(node: Node) -> String {
    let ps = elements(node);
    assert_eq!(ps.len(), 1, "one xhtml:p");
    assert!(ps[0].has_tag_name((XHTML, "p")));
    ps[0]
        .descendants()
        .filter(|n| n.is_text())
        .map(|n| n.text().unwrap())
        .collect()
}

/// A `dataType` element's content as a [`Type`].
fn read_type(node: Node) -> Type {
    let inner = elements(node);
    assert_eq!(inner.len(), 1, "one type");
    let t = inner[0];
    assert_eq!(t.tag_name().namespace(), Some(NAMESPACE));
    match t.tag_name().name() {
        "BOOL" => Type::Bool,
        "SINT" => Type::Sint,
        "INT" => Type::Int,
        "DINT" => Type::Dint,
        "UDINT" => Type::Udint,
        "derived" => Type::Instance(attr(t, "name").to_owned()),
        "array" => Type::Array {
            dims: children(t, "dimension")
                .map(|d| {
                    (
                        attr(d, "lower").parse().unwrap(),
                        attr(d, "upper").parse().unwrap(),
                    )
                })
                .collect(),
            elem: Box::new(read_type(el(t, "baseType"))),
        },
        other => panic!("unexpected type <{other}>"),
    }
}

/// An initial value: one literal, or the elements of an array.
#[derive(Debug, PartialEq)]
enum Value {
    Simple(String),
    Array(Vec<String>),
}

fn expected_value(init: &Init) -> Value {
    match init {
        Init::Value(v) => Value::Simple(v.clone()),
        Init::Rows(rows) => Value::Array(rows.iter().flat_map(|(_, v)| v.clone()).collect()),
    }
}

fn read_value(node: Node) -> Value {
    let inner = elements(node);
    assert_eq!(inner.len(), 1);
    match inner[0].tag_name().name() {
        "simpleValue" => Value::Simple(attr(inner[0], "value").to_owned()),
        "arrayValue" => Value::Array(
            children(inner[0], "value")
                .map(|v| {
                    assert_eq!(v.attribute("repetitionValue"), None);
                    attr(el(v, "simpleValue"), "value").to_owned()
                })
                .collect(),
        ),
        other => panic!("unexpected value <{other}>"),
    }
}

/// Every part of `export` is in `xml` where TC6 v2.01 puts it.
fn assert_matches(xml: &str, export: &Export) {
    let doc = Document::parse(xml).unwrap_or_else(|e| panic!("not well-formed: {e}"));
    let project = doc.root_element();
    assert!(project.has_tag_name((NAMESPACE, "project")));
    let top: Vec<&str> = elements(project)
        .iter()
        .map(|n| n.tag_name().name())
        .collect();
    assert_eq!(
        top,
        ["fileHeader", "contentHeader", "types", "instances"],
        "the schema's order"
    );

    let header = el(project, "fileHeader");
    assert_eq!(attr(header, "creationDateTime"), CREATION_DATE_TIME);
    assert_eq!(attr(header, "productName"), "codegen");
    assert_eq!(attr(header, "productVersion"), env!("CARGO_PKG_VERSION"));
    let content = el(project, "contentHeader");
    assert_eq!(attr(content, "name"), comment_text(&export.project));
    let comment = el(content, "Comment").text().unwrap();
    assert!(comment.contains(&export.regenerate), "{comment}");
    for (from, to) in &export.renamed {
        assert!(
            comment.contains(&format!("'{}' -> {to};", comment_text(from))),
            "{comment}"
        );
    }
    for language in ["fbd", "ld", "sfc"] {
        let scaling = el(el(el(content, "coordinateInfo"), language), "scaling");
        assert_eq!((attr(scaling, "x"), attr(scaling, "y")), ("1", "1"));
    }

    let types = el(project, "types");
    assert!(elements(el(types, "dataTypes")).is_empty());
    let pous: Vec<Node> = elements(el(types, "pous"));
    assert_eq!(pous.len(), export.pous.len());
    for (node, pou) in pous.iter().zip(&export.pous) {
        assert!(node.has_tag_name((NAMESPACE, "pou")));
        assert_eq!(attr(*node, "name"), pou.name);
        let kind = match pou.kind {
            PouKind::FunctionBlock => "functionBlock",
            PouKind::Program => "program",
        };
        assert_eq!(attr(*node, "pouType"), kind);
        let parts: Vec<&str> = elements(*node)
            .iter()
            .map(|n| n.tag_name().name())
            .collect();
        assert_eq!(
            parts,
            ["interface", "body", "documentation"],
            "{}",
            pou.name
        );

        let lists = elements(el(*node, "interface"));
        assert_eq!(lists.len(), pou.blocks.len(), "{}", pou.name);
        for (list, block) in lists.iter().zip(&pou.blocks) {
            let (tag, constant) = match block.section {
                Section::Input => ("inputVars", None),
                Section::Output => ("outputVars", None),
                Section::Local => ("localVars", None),
                Section::Constant => ("localVars", Some("true")),
            };
            assert_eq!(list.tag_name().name(), tag);
            assert_eq!(list.attribute("constant"), constant);
            let vars = elements(*list);
            assert_eq!(vars.len(), block.vars.len(), "{}", pou.name);
            for (v, var) in vars.iter().zip(&block.vars) {
                let what = format!("{}.{}", pou.name, var.name);
                assert!(v.has_tag_name((NAMESPACE, "variable")), "{what}");
                assert_eq!(attr(*v, "name"), var.name);
                assert_eq!(v.attribute("address"), var.address.as_deref(), "{what}");
                assert_eq!(read_type(el(*v, "type")), var.ty, "{what}");
                let init = children(*v, "initialValue").next().map(read_value);
                assert_eq!(init, var.init.as_ref().map(expected_value), "{what}");
                assert_eq!(formatted(el(*v, "documentation")), var.doc, "{what}");
            }
        }
        let body = el(*node, "body");
        assert_eq!(elements(body).len(), 1);
        assert_eq!(
            formatted(el(body, "ST")),
            pou.body.join("\n"),
            "{}",
            pou.name
        );
        assert_eq!(formatted(el(*node, "documentation")), pou.doc.join("\n"));
    }

    let configurations = el(el(project, "instances"), "configurations");
    let [configuration, resource, task, instance] = &export.names.configuration;
    let configs = elements(configurations);
    assert_eq!(configs.len(), 1);
    assert_eq!(attr(configs[0], "name"), configuration);
    let resources = elements(configs[0]);
    assert_eq!(resources.len(), 1);
    assert_eq!(attr(resources[0], "name"), resource);
    let tasks = elements(resources[0]);
    assert_eq!(tasks.len(), 1);
    assert!(tasks[0].has_tag_name((NAMESPACE, "task")));
    assert_eq!(attr(tasks[0], "name"), task);
    assert_eq!(
        attr(tasks[0], "interval"),
        format!("T#{}ms", export.scan_period_ms)
    );
    let instances = elements(tasks[0]);
    assert_eq!(instances.len(), 1);
    assert!(instances[0].has_tag_name((NAMESPACE, "pouInstance")));
    assert_eq!(attr(instances[0], "name"), instance);
    assert_eq!(attr(instances[0], "typeName"), export.names.program);
}

#[test]
fn every_seed_project_is_in_its_xml_as_exported() {
    for path in seeds() {
        let project = project::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let export = export_of(&project, &IoMap::sequential());
        let xml = plcopen::print(&export);
        assert_matches(&xml, &export);
        assert_eq!(xml, plcopen::print(&export), "reproducible");
    }
}

#[test]
fn located_variables_take_the_addresses_of_the_io_map() {
    let project = project::load(&root().join("models/press.plc.toml")).unwrap();
    let mut map = String::from("[inputs]\n");
    for (k, input) in project.inputs.iter().enumerate() {
        map.push_str(&format!(
            "\"{}\" = \"%IX{}.{}\"\n",
            input.name,
            3 + k / 8,
            k % 8
        ));
    }
    map.push_str("[outputs]\n");
    for output in &project.outputs {
        map.push_str(&format!("\"{}\" = \"%Q*\"\n", output.name));
    }
    let io = IoMap::parse(&map, Path::new("press.io.toml")).unwrap();
    let export = export_of(&project, &io);
    let xml = plcopen::print(&export);
    assert_matches(&xml, &export);
    assert!(xml.contains(r#"address="%IX3.0""#), "{xml}");
    assert!(xml.contains(r#"address="%Q*""#));
}

#[test]
fn hostile_names_stay_text_and_never_markup() {
    // The repository's hostile fixture: bidirectional overrides, keywords,
    // a leading digit.
    let fixture = project::load(&root().join("tests/fixtures/hostile/hostile.plc.toml")).unwrap();
    let export = export_of(&fixture, &IoMap::sequential());
    assert_matches(&plcopen::print(&export), &export);

    // Markup, a CDATA end, an ST comment end, XML-forbidden characters.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.toml"),
        "name = \"m\"\ninitial = \"idle\"\ncontrollable = [\"go\"]\n\
         uncontrollable = [\"done\"]\nstates = [\"idle\", \"]]> <busy> & *)\"]\n\
         transitions = [[\"idle\", \"go\", \"]]> <busy> & *)\"], [\"]]> <busy> & *)\", \"done\", \"idle\"]]\n",
    )
    .unwrap();
    let text = "[plc]\nname = \"a]]>b & <c> \\\"d\\\" 'e' \\uFFFF \\u0001 (* f *)\"\n\
                [inputs]\n\"<sensor> & ]]>\" = {}\n\
                [outputs]\n\"lamp\\\"'\" = {}\n\
                [events]\ngo = { controllable = true, set = [\"lamp\\\"'\"] }\n\
                done = { rising = \"<sensor> & ]]>\" }\n\
                [[supervisor]]\nname = \"</pou>\"\nfile = \"m.toml\"\n";
    let path = dir.path().join("h.plc.toml");
    std::fs::write(&path, text).unwrap();
    let project = project::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let export = export_of(&project, &IoMap::sequential());
    let xml = plcopen::print(&export);
    assert_matches(&xml, &export);
    let doc = Document::parse(&xml).unwrap();
    let name = attr(el(doc.root_element(), "contentHeader"), "name");
    assert_eq!(
        name,
        format!("a] ]>b & <c> \"d\" 'e'{}( * f * )", " ".repeat(5))
    );
    let input_doc = doc
        .descendants()
        .find(|n| n.has_tag_name((NAMESPACE, "variable")))
        .and_then(|n| n.next_sibling_element())
        .map(|n| formatted(el(n, "documentation")))
        .unwrap();
    assert_eq!(input_doc, "input '<sensor> & ] ]>'");
    assert!(
        doc.descendants()
            .all(|n| !n.has_tag_name("sensor") && !n.has_tag_name("busy")),
        "markup from a name"
    );
    assert_eq!(
        doc.descendants()
            .filter(|n| n.has_tag_name((NAMESPACE, "pou")))
            .count(),
        2
    );
    assert!(!xml.contains('\u{FFFF}') && !xml.contains('\u{1}'));
}

#[test]
fn further_pous_follow_the_exported_ones() {
    let project = project::load(&root().join("models/motivating.plc.toml")).unwrap();
    let export = export_of(&project, &IoMap::sequential());
    let ladder = r#"<pou name="ladder" pouType="program"><body><LD/></body></pou>"#;
    let xml = plcopen::print_with(&export, &[ladder.to_owned()]);
    let doc = Document::parse(&xml).unwrap();
    let pous = el(el(doc.root_element(), "types"), "pous");
    let names: Vec<&str> = elements(pous).iter().map(|p| attr(*p, "name")).collect();
    assert_eq!(names, ["motivating_ctrl", "motivating_main", "ladder"]);
    assert!(el(el(elements(pous)[2], "body"), "LD").is_element());
}
