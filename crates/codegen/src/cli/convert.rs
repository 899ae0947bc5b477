//! `codegen convert` and `codegen dot`.

use super::{load_components, print_json, Outcome};
use codegen::formats;
use codegen::Error;
use std::path::Path;

pub fn convert(
    input: &Path,
    output: &Path,
    component: Option<&str>,
    json: bool,
) -> Result<Outcome, Error> {
    let components = load_components(input, component)?;
    formats::write_file(output, &components)?;
    if json {
        let names: Vec<&str> = components.iter().map(|c| c.automaton.name()).collect();
        print_json(&serde_json::json!({
            "input": input.display().to_string(),
            "output": output.display().to_string(),
            "components": names,
        }));
    } else {
        println!("wrote {} ({} automata)", output.display(), components.len());
    }
    Ok(Outcome::Holds)
}

pub fn dot(file: &Path, component: Option<&str>, json: bool) -> Result<Outcome, Error> {
    let components = load_components(file, component)?;
    if json {
        let graphs: Vec<_> = components
            .iter()
            .map(|c| {
                serde_json::json!({
                    "name": c.automaton.name(),
                    "dot": codegen::dot::to_dot(&c.automaton),
                })
            })
            .collect();
        print_json(&graphs);
    } else {
        for c in &components {
            print!("{}", codegen::dot::to_dot(&c.automaton));
        }
    }
    Ok(Outcome::Holds)
}
