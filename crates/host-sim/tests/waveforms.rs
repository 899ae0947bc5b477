//! The VCD as a viewer reads it: written by host-sim and parsed back with
//! the `vcd` crate, it shows every scan of the trace (inputs, outputs,
//! each supervisor's state by name and by number, event pulses, fault
//! mode), writes a variable only when it changes, and for a closed-loop
//! boiler run adds the plant: temperatures and powers as `real`
//! variables, the flames, the selector.

mod common;

use codegen::backend::Backend;
use common::waveform::{Sample, Waveform};
use host_sim::boiler::{self, scenarios, BoilerError, BoilerParams, BoilerPlant, Input, Output};
use host_sim::{inputs, replay, Sim};
use vcd::{Value, VarType};

/// The press's reviewed cycle replayed: the project, its input rows, the
/// trace and the VCD written from them.
fn press_cycle() -> (Sim, Vec<inputs::InputRow>, Vec<host_sim::TraceRow>) {
    let mut sim = Sim::load(&common::model("press.plc.toml"), Backend::Table).unwrap();
    let path = common::model("press/cycle.inputs.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let rows = inputs::parse(&text, &path, sim.project()).unwrap();
    let trace = replay::replay(&mut sim, &rows).unwrap();
    (sim, rows, trace)
}

/// A value is written when it differs from the one before, never again
/// (event wires excepted: they pulse).
fn assert_written_on_change_only(w: &Waveform) {
    for path in w.paths().filter(|p| !p.contains(".events.")) {
        for pair in w.changes(path).windows(2) {
            assert_ne!(pair[0].1, pair[1].1, "{path} rewritten at {} ms", pair[1].0);
        }
    }
}

#[test]
fn a_replay_waveform_shows_every_scan_of_the_trace() {
    let (sim, rows, trace) = press_cycle();
    let project = sim.project();
    let mut buf = Vec::new();
    host_sim::vcd::write(&mut buf, sim.supervisors(), &rows, &trace).unwrap();
    let w = Waveform::parse(&buf);
    let top = "stamping-press";
    for (k, row) in trace.iter().enumerate() {
        let t = row.time_ms;
        for (input, &level) in project.inputs.iter().zip(&rows[k].values) {
            let path = format!("{top}.inputs.{}", input.name);
            assert_eq!(w.at(&path, t).bit(), level, "{path} at {t} ms");
        }
        for (output, &level) in project.outputs.iter().zip(&row.outputs) {
            let path = format!("{top}.outputs.{}", output.name);
            assert_eq!(w.at(&path, t).bit(), level, "{path} at {t} ms");
        }
        for (sup, (name, state)) in project.supervisors.iter().zip(&row.states) {
            let by_name = format!("{top}.states.{name}");
            assert_eq!(w.at(&by_name, t).text(), state, "{by_name} at {t} ms");
            let by_number = format!("{top}.state_numbers.{name}");
            let number = sup.automaton.state_by_name(state).unwrap().0;
            assert_eq!(w.at(&by_number, t).number(), Some(u64::from(number)));
        }
        for event in &project.events {
            let path = format!("{top}.events.{}", event.name);
            let executed = row.events.contains(&event.name);
            assert_eq!(w.at(&path, t).bit(), executed, "{path} at {t} ms");
        }
        let fault = w.at(&format!("{top}.fault"), t).bit();
        assert_eq!(fault, row.fault.is_some(), "fault at {t} ms");
    }
    for sup in &project.supervisors {
        let path = format!("{top}.states.{}", sup.name);
        assert_eq!(w.var_type(&path), VarType::String);
        assert!(
            w.changes(&path).len() > 3,
            "{path} names the cycle's states"
        );
        let states = sup.automaton.num_states() as u64;
        let width = w.width(&format!("{top}.state_numbers.{}", sup.name));
        assert!(1 << width >= states && 1 << (width - 1) < states.max(2));
    }
    assert_eq!(
        w.end,
        trace.last().unwrap().time_ms,
        "lasts to the last scan"
    );
    assert_written_on_change_only(&w);
}

#[test]
fn inputs_of_scans_without_an_input_row_are_unknown() {
    let (sim, rows, trace) = press_cycle();
    let project = sim.project();
    let mut buf = Vec::new();
    host_sim::vcd::write(&mut buf, sim.supervisors(), &rows[..3], &trace).unwrap();
    let w = Waveform::parse(&buf);
    let path = format!("stamping-press.inputs.{}", project.inputs[0].name);
    assert_eq!(*w.at(&path, trace[3].time_ms), Sample::Bit(Value::X));
    assert_eq!(w.at(&path, trace[2].time_ms).bit(), rows[2].values[0]);
}

#[test]
fn a_boiler_waveform_adds_the_plants_temperatures_flames_and_selector() {
    let mut sim = Sim::load(&common::model("boiler/boiler.plc.toml"), Backend::Table).unwrap();
    let mut plant = BoilerPlant::new(BoilerParams::default(), 1);
    let (script, duration) = scenarios::named("main-flame-failure").unwrap();
    let run = boiler::run(&mut sim, &mut plant, &script, duration).unwrap();
    let mut buf = Vec::new();
    boiler::waveform::write(&mut buf, sim.supervisors(), &run).unwrap();
    let w = Waveform::parse(&buf);

    type Quantity = fn(&boiler::BoilerState) -> f64;
    let reals: [(&str, Quantity); 4] = [
        ("bath_c", |p| p.bath_c),
        ("flue_c", |p| p.flue_c),
        ("firing_kw", |p| p.firing_kw),
        ("load_kw", |p| p.load_kw),
    ];
    for (name, _) in reals {
        assert_eq!(w.var_type(&format!("boiler.plant.{name}")), VarType::Real);
    }
    for row in &run.rows {
        let t = row.time_ms;
        for (name, value) in reals {
            let shown = w.at(&format!("boiler.plant.{name}"), t).real();
            let truth = value(&row.plant);
            assert!(
                (shown - truth).abs() <= 0.005 + 1e-9,
                "{name} at {t} ms: {shown} for {truth}"
            );
        }
        assert_eq!(
            w.at("boiler.plant.pilot_lit", t).bit(),
            row.plant.pilot_flame
        );
        assert_eq!(w.at("boiler.plant.main_lit", t).bit(), row.plant.main_flame);
        assert_eq!(
            w.at("boiler.plant.selector", t).text(),
            row.plant.selector.name()
        );
        for (name, state) in &row.states {
            assert_eq!(w.at(&format!("boiler.states.{name}"), t).text(), state);
        }
        for input in Input::ALL {
            let path = format!("boiler.inputs.{}", input.name());
            assert_eq!(
                w.at(&path, t).bit(),
                row.inputs.get(input),
                "{path} at {t} ms"
            );
        }
        for output in Output::ALL {
            let path = format!("boiler.outputs.{}", output.name());
            assert_eq!(
                w.at(&path, t).bit(),
                row.outputs.get(output),
                "{path} at {t} ms"
            );
        }
        assert_eq!(w.at("boiler.fault", t).bit(), row.fault.is_some());
    }
    // The main flame forms and is lost (the scenario) while the bath warms
    // and the flue gas heats up and cools down: curves, not constants.
    let main: Vec<bool> = w
        .changes("boiler.plant.main_lit")
        .iter()
        .map(|(_, s)| s.bit())
        .collect();
    assert_eq!(main, [false, true, false]);
    let bath = w.changes("boiler.plant.bath_c");
    assert!(bath.last().unwrap().1.real() > bath[0].1.real() + 0.1);
    assert!(w.changes("boiler.plant.flue_c").len() > 100);
    assert_written_on_change_only(&w);
}

#[test]
fn a_boiler_waveform_needs_a_project_with_the_boilers_signals() {
    let mut sim = Sim::load(&common::model("boiler/boiler.plc.toml"), Backend::Table).unwrap();
    let mut plant = BoilerPlant::new(BoilerParams::default(), 1);
    let (script, duration) = scenarios::named("cold-start-low").unwrap();
    let run = boiler::run(&mut sim, &mut plant, &script, duration / 10).unwrap();
    let (press, _, _) = press_cycle();
    let err = boiler::waveform::write(Vec::new(), press.supervisors(), &run).unwrap_err();
    assert!(matches!(err, BoilerError::MissingSignals { .. }), "{err}");
    assert!(err.to_string().contains("input `sel_high`"), "{err}");
}
