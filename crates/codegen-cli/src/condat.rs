//! `codegen condat`: disabled controllable events per supervisor state.
//!
//! Beside each supervisor state stands the plant state it occurs with in
//! the closed loop, under a header naming the plant components: the key to
//! the state names `synth` gives (plant components first, then the
//! specifications).

use super::error::CliError;
use super::key::{plant_states_per_supervisor_state, Key};
use super::output::{outln, Out};
use super::{load, Outcome, Role};
use des::formats;
use des::ops;
use des::Automaton;
use std::path::{Path, PathBuf};

#[derive(Debug, serde::Serialize)]
struct Row {
    state: String,
    disabled: Vec<String>,
    /// The plant states (one state per plant component) this supervisor
    /// state occurs with in the closed loop; none if it is unreachable.
    plant: Vec<Key>,
}

pub fn run(plants: &[PathBuf], sup: &Path, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let plants = load(plants, Role::Plant)?;
    let refs: Vec<&Automaton> = plants.iter().collect();
    let plant = ops::sync(&refs)?;
    let sup = formats::read_automaton(sup)?;
    let data = ops::condat(&plant, &sup)?;
    let mut with_plant = plant_states_per_supervisor_state(&plants, &sup)?;
    let rows: Vec<Row> = sup
        .states()
        .map(|x| Row {
            state: sup.state_name(x).into_owned(),
            disabled: data
                .at(x)
                .iter()
                .map(|&e| sup.alphabet().name(e).to_owned())
                .collect(),
            plant: std::mem::take(&mut with_plant[x.index()]),
        })
        .collect();
    if json {
        out.json(&rows);
        return Ok(Outcome::Holds);
    }
    let names: Vec<&str> = plants.iter().map(Automaton::name).collect();
    outln!(
        out,
        "{}: controllable events disabled per state, with the plant state ({}) \
         it occurs with",
        sup.name(),
        names.join(", ")
    );
    for r in &rows {
        let plant = match r.plant.as_slice() {
            [] => "(unreachable)".to_owned(),
            [one] => one.states(),
            several => format!("({} plant states)", several.len()),
        };
        let disabled = if r.disabled.is_empty() {
            "nothing".to_owned()
        } else {
            r.disabled.join(" ")
        };
        outln!(out, "  {} {plant}: {disabled}", r.state);
    }
    Ok(Outcome::Holds)
}
