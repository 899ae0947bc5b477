//! PLCopen XML (TC6 XML v2.01) back to Structured Text, as an IDE that
//! imports the XML (Beremiz, OpenPLC Editor) hands it to its compiler:
//! each POU's interface from its `<interface>` elements, its body from
//! `<body><ST>`, the configurations from `<instances>`. Written from the
//! schema for the subset `codegen plcopen` writes (elementary, array and
//! derived types, simple and array initial values, addresses, constant
//! blocks, cyclic tasks); anything else is an error, never skipped.

#![allow(dead_code)]

use roxmltree::{Document, Node};

/// The ST text of every POU of `xml` (ST bodies only), then its
/// configurations.
pub fn to_st(xml: &str) -> Result<String, String> {
    let doc = Document::parse(xml).map_err(|e| format!("not XML: {e}"))?;
    let project = doc.root_element();
    let mut out = String::new();
    for pou in descendants(project, "pou") {
        out.push_str(&pou_st(pou)?);
        out.push('\n');
    }
    for configuration in descendants(project, "configuration") {
        out.push_str(&configuration_st(configuration)?);
    }
    Ok(out)
}

fn descendants<'a, 'i>(
    node: Node<'a, 'i>,
    name: &'static str,
) -> impl Iterator<Item = Node<'a, 'i>> {
    node.descendants()
        .filter(move |n| n.is_element() && n.tag_name().name() == name)
}

fn children<'a, 'i>(node: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(Node::is_element)
}

fn child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    children(node).find(|n| n.tag_name().name() == name)
}

fn attr<'a>(node: Node<'a, '_>, name: &str) -> Result<&'a str, String> {
    node.attribute(name)
        .ok_or_else(|| format!("<{}> without {name}", node.tag_name().name()))
}

fn pou_st(pou: Node) -> Result<String, String> {
    let name = attr(pou, "name")?;
    let (open, close) = match attr(pou, "pouType")? {
        "functionBlock" => ("FUNCTION_BLOCK", "END_FUNCTION_BLOCK"),
        "program" => ("PROGRAM", "END_PROGRAM"),
        other => return Err(format!("pou {name}: pouType {other} not expected")),
    };
    let interface = child(pou, "interface").ok_or(format!("pou {name}: no interface"))?;
    let mut out = format!("{open} {name}\n");
    for block in children(interface) {
        let keyword = match block.tag_name().name() {
            "inputVars" => "VAR_INPUT",
            "outputVars" => "VAR_OUTPUT",
            "localVars" => "VAR",
            other => return Err(format!("pou {name}: <{other}> not expected")),
        };
        let constant = block.attribute("constant") == Some("true");
        out.push_str(keyword);
        if constant {
            out.push_str(" CONSTANT");
        }
        out.push('\n');
        for var in children(block).filter(|v| v.tag_name().name() == "variable") {
            out.push_str(&format!("    {}", attr(var, "name")?));
            if let Some(address) = var.attribute("address") {
                out.push_str(&format!(" AT {address}"));
            }
            let ty = child(var, "type").ok_or("a variable without type")?;
            out.push_str(&format!(" : {}", type_st(ty)?));
            if let Some(init) = child(var, "initialValue") {
                out.push_str(&format!(" := {}", value_st(init)?));
            }
            out.push_str(";\n");
        }
        out.push_str("END_VAR\n");
    }
    let body = child(pou, "body").ok_or(format!("pou {name}: no body"))?;
    let st = child(body, "ST").ok_or(format!("pou {name}: the body is not ST"))?;
    let text: String = descendants(st, "p").filter_map(|p| p.text()).collect();
    out.push_str(&text);
    out.push('\n');
    out.push_str(close);
    out.push('\n');
    Ok(out)
}

fn type_st(ty: Node) -> Result<String, String> {
    let inner = children(ty).next().ok_or("an empty <type>")?;
    match inner.tag_name().name() {
        "array" => {
            let dims: Vec<String> = children(inner)
                .filter(|d| d.tag_name().name() == "dimension")
                .map(|d| Ok(format!("{}..{}", attr(d, "lower")?, attr(d, "upper")?)))
                .collect::<Result<_, String>>()?;
            let base = child(inner, "baseType").ok_or("an array without baseType")?;
            Ok(format!("ARRAY [{}] OF {}", dims.join(", "), type_st(base)?))
        }
        "derived" => Ok(attr(inner, "name")?.to_owned()),
        elementary => Ok(elementary.to_owned()),
    }
}

fn value_st(init: Node) -> Result<String, String> {
    let inner = children(init).next().ok_or("an empty value")?;
    match inner.tag_name().name() {
        "simpleValue" => Ok(attr(inner, "value")?.to_owned()),
        "arrayValue" => {
            let values: Vec<String> = children(inner)
                .map(value_st)
                .collect::<Result<_, String>>()?;
            Ok(format!("[{}]", values.join(", ")))
        }
        other => Err(format!("<{other}> initial values not expected")),
    }
}

fn configuration_st(configuration: Node) -> Result<String, String> {
    let mut out = format!("CONFIGURATION {}\n", attr(configuration, "name")?);
    for resource in children(configuration).filter(|r| r.tag_name().name() == "resource") {
        out.push_str(&format!(
            "    RESOURCE {} ON PLC\n",
            attr(resource, "name")?
        ));
        let mut instances = String::new();
        for task in children(resource).filter(|t| t.tag_name().name() == "task") {
            let name = attr(task, "name")?;
            out.push_str(&format!(
                "        TASK {name}(INTERVAL := {}, PRIORITY := {});\n",
                attr(task, "interval")?,
                attr(task, "priority")?
            ));
            for instance in children(task).filter(|i| i.tag_name().name() == "pouInstance") {
                instances.push_str(&format!(
                    "        PROGRAM {} WITH {name} : {};\n",
                    attr(instance, "name")?,
                    attr(instance, "typeName")?
                ));
            }
        }
        out.push_str(&instances);
        out.push_str("    END_RESOURCE\n");
    }
    out.push_str("END_CONFIGURATION\n");
    Ok(out)
}
