//! A picture of a closed-loop run ([`crate::plot`]): the inputs the
//! controller read, its outputs, the true flames, the executed events,
//! each supervisor's state and fault mode as lanes, over the bath and
//! flue-gas temperatures and the burner's and load's power on fixed
//! scales.
//!
//! The scales are the plant's, not the run's: the bath 0–100 °C (water),
//! the flue gas 0–300 °C (its high limit), power 0–200 kW (high fire is
//! 150 kW); a scenario that leaves a scale widens it to the next tick. The
//! bath's line is nearly flat on its scale because the bath is: 2,000 l of
//! water warm by about 1 K a minute at high fire, so its label gives its
//! first and last values.

use super::record::Run;
use super::signals::{Input, Output};
use crate::plot::Plot;

/// The SVG text of `run`, titled `title`.
pub fn render(run: &Run, title: &str) -> String {
    plot(run, title).to_svg()
}

/// The picture of `run`, titled `title`.
pub fn plot(run: &Run, title: &str) -> Plot {
    let mut plot = Plot::new(title);
    let inputs = Input::ALL.map(|i| plot.digital("inputs", i.name()));
    let outputs = Output::ALL.map(|o| plot.digital("outputs", o.name()));
    let pilot = plot.digital("plant", "pilot flame");
    let main = plot.digital("plant", "main flame");
    let supervisors: Vec<_> = run.rows.first().map_or(Vec::new(), |row| {
        row.states
            .iter()
            .map(|(name, _)| plot.supervisor(name))
            .collect()
    });
    let bath = plot.analog("bath", "°C", (0.0, 100.0), &[("bath", "darkgreen")]);
    let flue = plot.analog("flue gas", "°C", (0.0, 300.0), &[("flue gas", "firebrick")]);
    let power = plot.analog(
        "power",
        "kW",
        (0.0, 200.0),
        &[("firing", "darkorange"), ("load", "purple")],
    );
    for row in &run.rows {
        plot.scan(row.time_ms);
        for (lane, input) in inputs.iter().zip(Input::ALL) {
            plot.set_digital(*lane, row.inputs.get(input));
        }
        for (lane, output) in outputs.iter().zip(Output::ALL) {
            plot.set_digital(*lane, row.outputs.get(output));
        }
        plot.set_digital(pilot, row.plant.pilot_flame);
        plot.set_digital(main, row.plant.main_flame);
        for (lane, (_, state)) in supervisors.iter().zip(&row.states) {
            plot.set_state(*lane, state);
        }
        plot.events(&row.events);
        plot.fault(row.fault.as_deref());
        plot.set_analog(bath[0], row.plant.bath_c);
        plot.set_analog(flue[0], row.plant.flue_c);
        plot.set_analog(power[0], row.plant.firing_kw);
        plot.set_analog(power[1], row.plant.load_kw);
    }
    plot
}
