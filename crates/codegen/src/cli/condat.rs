//! `codegen condat`: disabled controllable events per supervisor state.

use super::{load, print_json, Outcome, Role};
use codegen::formats;
use codegen::ops;
use codegen::{Automaton, Error};
use std::path::{Path, PathBuf};

#[derive(Debug, serde::Serialize)]
struct Row {
    state: String,
    disabled: Vec<String>,
}

pub fn run(plants: &[PathBuf], sup: &Path, json: bool) -> Result<Outcome, Error> {
    let plants = load(plants, Role::Plant)?;
    let refs: Vec<&Automaton> = plants.iter().collect();
    let plant = ops::sync(&refs)?;
    let sup = formats::read_automaton(sup)?;
    let data = ops::condat(&plant, &sup)?;
    let rows: Vec<Row> = sup
        .states()
        .map(|x| Row {
            state: sup.state_name(x).into_owned(),
            disabled: data
                .at(x)
                .iter()
                .map(|&e| sup.alphabet().name(e).to_owned())
                .collect(),
        })
        .collect();
    if json {
        print_json(&rows);
    } else {
        println!("{}: controllable events disabled per state", sup.name());
        for r in &rows {
            println!("  {}: {}", r.state, r.disabled.join(" "));
        }
    }
    Ok(Outcome::Holds)
}
