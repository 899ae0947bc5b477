//! Value Change Dump of a trace (GTKWave, Surfer): inputs, outputs, one
//! integer signal per supervisor state, one pulse per event.
//!
//! Time unit: 1 ms. An event's wire is 1 during the scan it executes in
//! and 0 from the next scan on.

use crate::inputs::InputRow;
use crate::trace::TraceRow;
use codegen::project::Project;
use std::io::{self, Write};
use vcd::{IdCode, TimescaleUnit, Value};

fn identifier(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| if c.is_ascii_graphic() { c } else { '_' })
        .collect();
    if clean.is_empty() {
        "_".to_owned()
    } else {
        clean
    }
}

fn bits(value: u64, width: u32) -> Vec<Value> {
    (0..width)
        .rev()
        .map(|b| {
            if value >> b & 1 == 1 {
                Value::V1
            } else {
                Value::V0
            }
        })
        .collect()
}

/// Writes the VCD of `rows` (with the raw `inputs` of each scan) to `out`.
pub fn write(
    out: impl Write,
    project: &Project,
    inputs: &[InputRow],
    rows: &[TraceRow],
) -> io::Result<()> {
    let mut w = vcd::Writer::new(out);
    w.timescale(1, TimescaleUnit::MS)?;
    w.add_module(&identifier(&project.name))?;
    w.add_module("inputs")?;
    let input_ids: Vec<IdCode> = project
        .inputs
        .iter()
        .map(|i| w.add_wire(1, &identifier(&i.name)))
        .collect::<io::Result<_>>()?;
    w.upscope()?;
    w.add_module("outputs")?;
    let output_ids: Vec<IdCode> = project
        .outputs
        .iter()
        .map(|o| w.add_wire(1, &identifier(&o.name)))
        .collect::<io::Result<_>>()?;
    w.upscope()?;
    w.add_module("states")?;
    let widths: Vec<u32> = project
        .supervisors
        .iter()
        .map(|s| u64::from(s.automaton.num_states().max(2) as u32 - 1).ilog2() + 1)
        .collect();
    let state_ids: Vec<IdCode> = project
        .supervisors
        .iter()
        .zip(&widths)
        .map(|(s, &w_)| w.add_wire(w_, &identifier(&s.name)))
        .collect::<io::Result<_>>()?;
    w.upscope()?;
    w.add_module("events")?;
    let event_ids: Vec<IdCode> = project
        .events
        .iter()
        .map(|e| w.add_wire(1, &identifier(&e.name)))
        .collect::<io::Result<_>>()?;
    w.upscope()?;
    let fault = w.add_wire(1, "fault")?;
    w.upscope()?;
    w.enddefinitions()?;
    let mut last_time = None;
    let mut pulsing: Vec<usize> = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        if last_time != Some(row.time_ms) {
            w.timestamp(row.time_ms)?;
            last_time = Some(row.time_ms);
        }
        for e in pulsing.drain(..) {
            w.change_scalar(event_ids[e], Value::V0)?;
        }
        if let Some(input) = inputs.get(k) {
            for (id, &v) in input_ids.iter().zip(&input.values) {
                w.change_scalar(*id, Value::from(v))?;
            }
        }
        for (id, &v) in output_ids.iter().zip(&row.outputs) {
            w.change_scalar(*id, Value::from(v))?;
        }
        for ((sup, (_, state)), (id, &width)) in project
            .supervisors
            .iter()
            .zip(&row.states)
            .zip(state_ids.iter().zip(&widths))
        {
            let index = sup
                .automaton
                .state_by_name(state)
                .map_or(0, |s| u64::from(s.0));
            w.change_vector(*id, bits(index, width))?;
        }
        for name in &row.events {
            if let Some(e) = project.event(name) {
                w.change_scalar(event_ids[e], Value::V1)?;
                pulsing.push(e);
            }
        }
        w.change_scalar(fault, Value::from(row.fault.is_some()))?;
    }
    Ok(())
}
