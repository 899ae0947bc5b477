//! A place/transition net: places as circles holding their initial
//! tokens (dots up to three, a number beyond), transitions as boxes named
//! after their event (dashed when uncontrollable, grey when
//! unobservable), arcs with their weight when it is above 1. The control
//! places of a supervised net (those `--constraints` adds, as `petri
//! synth` does) and their arcs are red. Tokens flow left to right.

use super::{graph_header, Drawing, Graph};
use des::dot::quote;
use des::petri::PetriNet;
use std::fmt::Write;

/// Draws `net`; the places whose index is in `control` are control
/// places.
pub fn draw(net: &PetriNet, drawing: &Drawing, control: &[usize]) -> Graph {
    let title: Vec<String> = if control.is_empty() {
        Vec::new()
    } else {
        let places = match control.len() {
            1 => "1 control place".to_owned(),
            n => format!("{n} control places"),
        };
        vec![format!("{places} (red) added by the constraints")]
    };
    let mut out = graph_header(net.name(), drawing, "LR", &title);
    for (p, (place, &tokens)) in net.places().iter().zip(net.initial()).enumerate() {
        let mut attributes = vec![
            "shape=circle".to_owned(),
            format!("label={}", quote(&place_label(&place.id, tokens))),
        ];
        if let Some(name) = &place.name {
            attributes.push(format!("tooltip={}", quote(name)));
        }
        if control.contains(&p) {
            attributes.push("color=red, fontcolor=red, penwidth=2".to_owned());
        }
        writeln!(out, "  p{p} [{}];", attributes.join(", ")).unwrap();
    }
    let mut arcs = 0;
    for (t, transition) in net.transitions().iter().enumerate() {
        let mut attributes = vec![
            "shape=box".to_owned(),
            "height=0.3".to_owned(),
            format!("label={}", quote(&transition.id)),
        ];
        if !transition.controllable {
            attributes.push("style=dashed".to_owned());
        }
        if !transition.observable {
            attributes.push("color=grey, fontcolor=grey".to_owned());
        }
        if let Some(name) = &transition.name {
            attributes.push(format!("tooltip={}", quote(name)));
        }
        writeln!(out, "  t{t} [{}];", attributes.join(", ")).unwrap();
        let inputs = transition.input.iter().map(|&(p, w)| (p, w, true));
        let outputs = transition.output.iter().map(|&(p, w)| (p, w, false));
        for (p, weight, input) in inputs.chain(outputs) {
            arcs += 1;
            if input {
                write!(out, "  p{p} -> t{t}").unwrap();
            } else {
                write!(out, "  t{t} -> p{p}").unwrap();
            }
            let mut attributes = Vec::new();
            if weight > 1 {
                attributes.push(format!("label=\"{weight}\""));
            }
            if control.contains(&p) {
                attributes.push("color=red".to_owned());
            }
            if !attributes.is_empty() {
                write!(out, " [{}]", attributes.join(", ")).unwrap();
            }
            out.push_str(";\n");
        }
    }
    out.push_str("}\n");
    Graph {
        dot: out,
        nodes: net.places().len() + net.transitions().len(),
        edges: arcs,
        notes: Vec::new(),
    }
}

/// A place's id over its initial tokens as the textbooks draw them: up
/// to three dots, a number beyond, nothing for none.
fn place_label(id: &str, tokens: u32) -> String {
    match tokens {
        0 => id.to_owned(),
        1..=3 => format!("{id}\n{}", "●".repeat(tokens as usize)),
        n => format!("{id}\n{n}"),
    }
}

#[cfg(test)]
mod tests {
    use super::place_label;

    #[test]
    fn tokens_are_dots_up_to_three_then_a_number() {
        assert_eq!(place_label("p", 0), "p");
        assert_eq!(place_label("p", 2), "p\n●●");
        assert_eq!(place_label("p", 4), "p\n4");
    }
}
