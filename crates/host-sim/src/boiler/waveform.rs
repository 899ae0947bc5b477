//! The VCD of a closed-loop run: what the controller read, wrote and did
//! in every scan, in the scopes of [`crate::vcd`], and in a `plant` scope
//! the true state of the plant when the controller read its inputs:
//!
//! - `bath_c`, `flue_c`: the bath and flue-gas temperatures (°C, `real`);
//! - `firing_kw`, `load_kw`: the burner input and the process load (kW,
//!   `real`);
//! - `pilot_lit`, `main_lit`: the flames themselves (wires), which the
//!   detectors in `inputs` show through their wiring and its faults;
//! - `selector`: the position the operator set (`off`, `low`, `high`).
//!
//! [`save_file`] gives its GTKWave save file, the `real` quantities drawn
//! as analog traces.
//!
//! Temperatures and powers are rounded to 0.01 (°C, kW): finer than a
//! viewer draws, and a slow temperature then changes, and is written,
//! only now and then instead of every scan.

use super::error::BoilerError;
use super::record::Run;
use super::signals::{Input, IoMap, Output};
use crate::vcd::{write_scans, Quantity, Samples, Scan};
use codegen::lower::Supervisors;
use std::io::Write;
use std::path::Path;
use vcd::Value;

/// Writes the VCD of `run`, a run of the project whose lowered program
/// has `supervisors` ([`crate::Sim::supervisors`]), to `out`. The
/// project's inputs and outputs other than the boiler's, which a run
/// neither drives nor records, are `x`.
pub fn write(out: impl Write, supervisors: Supervisors<'_>, run: &Run) -> Result<(), BoilerError> {
    let project = supervisors.project();
    let io = IoMap::new(project)?;
    let scans: Vec<Scan<'_>> = run
        .rows
        .iter()
        .map(|row| {
            let mut inputs = vec![Value::X; project.inputs.len()];
            for input in Input::ALL {
                inputs[io.input(input)] = Value::from(row.inputs.get(input));
            }
            let mut outputs = vec![Value::X; project.outputs.len()];
            for output in Output::ALL {
                outputs[io.output(output)] = Value::from(row.outputs.get(output));
            }
            Scan {
                time_ms: row.time_ms,
                inputs,
                outputs,
                states: &row.states,
                events: &row.events,
                fault: row.fault.is_some(),
            }
        })
        .collect();
    write_scans(out, supervisors, &scans, &quantities(run))?;
    Ok(())
}

/// The GTKWave save file of the VCD of `run` written to `dump` by
/// [`write()`] ([`crate::gtkw`]).
pub fn save_file(dump: &Path, supervisors: Supervisors<'_>, run: &Run) -> String {
    crate::gtkw::save_file(dump, supervisors, &quantities(run))
}

/// The plant quantities of `run`, one sample per scan each.
fn quantities(run: &Run) -> [Quantity; 7] {
    let real = |f: fn(&super::BoilerState) -> f64| {
        Samples::Real(run.rows.iter().map(|r| hundredths(f(&r.plant))).collect())
    };
    [
        Quantity {
            name: "bath_c",
            samples: real(|p| p.bath_c),
        },
        Quantity {
            name: "flue_c",
            samples: real(|p| p.flue_c),
        },
        Quantity {
            name: "firing_kw",
            samples: real(|p| p.firing_kw),
        },
        Quantity {
            name: "load_kw",
            samples: real(|p| p.load_kw),
        },
        Quantity {
            name: "pilot_lit",
            samples: Samples::Bit(run.rows.iter().map(|r| r.plant.pilot_flame).collect()),
        },
        Quantity {
            name: "main_lit",
            samples: Samples::Bit(run.rows.iter().map(|r| r.plant.main_flame).collect()),
        },
        Quantity {
            name: "selector",
            samples: Samples::Text(run.rows.iter().map(|r| r.plant.selector.name()).collect()),
        },
    ]
}

/// `x` rounded to 0.01.
fn hundredths(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}
