//! Value Change Dump of a trace (GTKWave, Surfer), in a scope named after
//! the project:
//!
//! - `inputs`, `outputs`: one wire per signal;
//! - `states`: one string variable per supervisor carrying the name of its
//!   state (`$var string`, GTKWave's extension, which Surfer reads too);
//! - `state_numbers`: the same states as the automaton numbers them, one
//!   vector per supervisor, wide enough for all its states (`x` for a state
//!   the automaton does not have);
//! - `events`: one wire per event, 0 from the first scan, 1 during each
//!   scan it executes in;
//! - `last_events`: a string naming the events of the last scan that
//!   executed any, numbered (`3:part_in`), held until the next such scan
//!   (`-` before the first): an event wire is 1 for one scan only, a
//!   hairline in a long run, while this label changes at the same times
//!   and stays readable;
//! - `fault`: 1 on scans spent in fault mode;
//! - `plant`, for a closed-loop run ([`crate::boiler::waveform`]): the
//!   plant's quantities as `real` variables, wires or strings.
//!
//! Time unit: 1 ms. A variable is written when its value changes (an
//! event executed in consecutive scans falls to 0 and rises again at the
//! same time). In string values, whitespace, control characters and `\`
//! are written as GTKWave writes them, a backslash and three octal digits
//! (`idle hold` becomes `idle\040hold`).

use crate::inputs::InputRow;
use crate::trace::TraceRow;
use codegen::lower::Supervisors;
use plc_project::Project;
use std::io::{self, Write};
use vcd::{IdCode, TimescaleUnit, Value, VarType};

/// Writes the VCD of `rows` (with the raw `inputs` of each scan) to `out`;
/// inputs of a row without an input row are `x`. `supervisors` names the
/// lowered program's supervisors (`Sim::supervisors`).
pub fn write(
    out: impl Write,
    supervisors: Supervisors<'_>,
    inputs: &[InputRow],
    rows: &[TraceRow],
) -> io::Result<()> {
    let mut w = Waveform::new(out, supervisors)?;
    for (k, row) in rows.iter().enumerate() {
        w.scan(inputs.get(k), row)?;
    }
    w.finish()
}

/// The VCD of a run written scan by scan, as the run goes: memory stays
/// constant however long the run ([`write()`] for a run held in memory).
pub struct Waveform<'p, W: Write> {
    writer: ScanWriter<'p, W>,
}

impl<'p, W: Write> Waveform<'p, W> {
    /// Writes the declarations of the variables of the project whose
    /// lowered `supervisors` these are to `out`.
    pub fn new(out: W, supervisors: Supervisors<'p>) -> io::Result<Self> {
        Ok(Waveform {
            writer: ScanWriter::new(out, supervisors, &[])?,
        })
    }

    /// Writes the changes of one scan: its trace row and the raw inputs it
    /// read (`None`: unknown, written `x`).
    pub fn scan(&mut self, inputs: Option<&InputRow>, row: &TraceRow) -> io::Result<()> {
        let n = self.writer.project.inputs.len();
        let scan = Scan {
            time_ms: row.time_ms,
            inputs: match inputs {
                Some(input) => input.values.iter().map(|&v| Value::from(v)).collect(),
                None => vec![Value::X; n],
            },
            outputs: row.outputs.iter().map(|&v| Value::from(v)).collect(),
            states: &row.states,
            events: &row.events,
            fault: row.fault.is_some(),
        };
        self.writer.scan(&scan, std::iter::empty())
    }

    /// Ends the waveform at the last scan and flushes.
    pub fn finish(self) -> io::Result<()> {
        self.writer.finish()
    }
}

/// One scan as a waveform shows it.
pub(crate) struct Scan<'a> {
    /// Time of the scan.
    pub time_ms: u64,
    /// One level per project input.
    pub inputs: Vec<Value>,
    /// One level per project output.
    pub outputs: Vec<Value>,
    /// `(supervisor, state)` in declaration order.
    pub states: &'a [(String, String)],
    /// Executed events.
    pub events: &'a [String],
    /// The scan was spent in fault mode.
    pub fault: bool,
}

/// The values of one quantity outside the project, one per scan.
pub(crate) enum Samples {
    /// A `real` variable.
    Real(Vec<f64>),
    /// A wire.
    Bit(Vec<bool>),
    /// A string variable.
    Text(Vec<&'static str>),
}

impl Samples {
    fn len(&self) -> usize {
        match self {
            Samples::Real(v) => v.len(),
            Samples::Bit(v) => v.len(),
            Samples::Text(v) => v.len(),
        }
    }
}

/// A plant quantity for the `plant` scope.
pub(crate) struct Quantity {
    /// Its variable name.
    pub name: &'static str,
    /// Its value at every scan.
    pub samples: Samples,
}

/// A value as written, to write a variable only when it changes.
#[derive(Debug, Clone, PartialEq)]
enum Written {
    Scalar(Value),
    Vector(Option<u64>),
    Real(f64),
    Text(String),
}

/// The value change section: timestamps are written only before a change.
struct Changes<W: Write> {
    w: vcd::Writer<W>,
    /// The time of the scan being written.
    now: u64,
    /// The last timestamp written.
    stamped: Option<u64>,
    /// Last value written, by variable (in the order of declaration).
    last: Vec<Option<Written>>,
}

impl<W: Write> Changes<W> {
    fn stamp(&mut self) -> io::Result<()> {
        if self.stamped != Some(self.now) {
            self.w.timestamp(self.now)?;
            self.stamped = Some(self.now);
        }
        Ok(())
    }

    /// Writes `value` to `var` when it differs from the last value written
    /// there.
    fn set(&mut self, var: Var, value: Written) -> io::Result<()> {
        if self.last[var.slot].as_ref() == Some(&value) {
            return Ok(());
        }
        self.pulse(var, &value)?;
        self.last[var.slot] = Some(value);
        Ok(())
    }

    /// Writes `value` to variable `var` whatever was written before.
    fn pulse(&mut self, var: Var, value: &Written) -> io::Result<()> {
        self.stamp()?;
        match value {
            Written::Scalar(v) => self.w.change_scalar(var.id, *v),
            Written::Vector(v) => self.w.change_vector(var.id, bits(*v, var.width)),
            Written::Real(v) => self.w.change_real(var.id, *v),
            Written::Text(v) => self.w.change_string(var.id, v),
        }
    }
}

/// A declared variable.
#[derive(Debug, Clone, Copy)]
struct Var {
    id: IdCode,
    /// Bits of a vector.
    width: u32,
    /// Its index in [`Changes::last`].
    slot: usize,
}

/// The header: scopes and variable declarations.
struct Declarations<W: Write> {
    w: vcd::Writer<W>,
    count: usize,
}

impl<W: Write> Declarations<W> {
    fn var(&mut self, var_type: VarType, width: u32, name: &str) -> io::Result<Var> {
        let id = self.w.add_var(var_type, width, &identifier(name), None)?;
        self.count += 1;
        Ok(Var {
            id,
            width,
            slot: self.count - 1,
        })
    }

    fn scope<T>(
        &mut self,
        name: &str,
        items: impl IntoIterator<Item = T>,
        mut declare: impl FnMut(&mut Self, T) -> io::Result<Var>,
    ) -> io::Result<Vec<Var>> {
        self.w.add_module(name)?;
        let vars = items
            .into_iter()
            .map(|item| declare(self, item))
            .collect::<io::Result<_>>()?;
        self.w.upscope()?;
        Ok(vars)
    }
}

/// Writes `scans` of the project of `supervisors` to `out`, with `plant`
/// quantities (one sample per scan each) in a `plant` scope when there are
/// any.
pub(crate) fn write_scans(
    out: impl Write,
    supervisors: Supervisors<'_>,
    scans: &[Scan<'_>],
    plant: &[Quantity],
) -> io::Result<()> {
    if let Some(q) = plant.iter().find(|q| q.samples.len() != scans.len()) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "plant quantity `{}` has {} samples for {} scans",
                q.name,
                q.samples.len(),
                scans.len()
            ),
        ));
    }
    let mut w = ScanWriter::new(out, supervisors, plant)?;
    for (k, scan) in scans.iter().enumerate() {
        w.scan(
            scan,
            plant.iter().map(|q| match &q.samples {
                Samples::Real(v) => Written::Real(v[k]),
                Samples::Bit(v) => Written::Scalar(Value::from(v[k])),
                Samples::Text(v) => Written::Text(escape(v[k])),
            }),
        )?;
    }
    w.finish()
}

/// The declared variables and the value changes written so far.
struct ScanWriter<'p, W: Write> {
    project: &'p Project,
    supervisors: Supervisors<'p>,
    c: Changes<W>,
    inputs: Vec<Var>,
    outputs: Vec<Var>,
    names: Vec<Var>,
    numbers: Vec<Var>,
    events: Vec<Var>,
    quantities: Vec<Var>,
    last_events: Var,
    /// Scans that executed events so far.
    scans_with_events: u64,
    fault: Var,
    /// Events executed in the previous scan, to fall back to 0.
    pulsing: Vec<Var>,
    /// Time of the last scan written.
    last: Option<u64>,
}

impl<'p, W: Write> ScanWriter<'p, W> {
    /// Writes the header: the variables of the project of `supervisors`
    /// and, in a `plant` scope, one per quantity of `plant` (whose samples
    /// are not read).
    fn new(out: W, supervisors: Supervisors<'p>, plant: &[Quantity]) -> io::Result<Self> {
        let project = supervisors.project();
        let mut d = Declarations {
            w: vcd::Writer::new(out),
            count: 0,
        };
        d.w.timescale(1, TimescaleUnit::MS)?;
        d.w.add_module(&identifier(&project.name))?;
        let inputs = d.scope("inputs", &project.inputs, |d, i| {
            d.var(VarType::Wire, 1, &i.name)
        })?;
        let outputs = d.scope("outputs", &project.outputs, |d, o| {
            d.var(VarType::Wire, 1, &o.name)
        })?;
        let all = 0..supervisors.len();
        let names = d.scope("states", all.clone(), |d, j| {
            d.var(VarType::String, 1, &supervisors.name(j))
        })?;
        let numbers = d.scope("state_numbers", all, |d, j| {
            d.var(
                VarType::Wire,
                supervisors.state_bits(j),
                &supervisors.name(j),
            )
        })?;
        let events = d.scope("events", &project.events, |d, e| {
            d.var(VarType::Wire, 1, &e.name)
        })?;
        let quantities = if plant.is_empty() {
            Vec::new()
        } else {
            d.scope("plant", plant, |d, q| match q.samples {
                Samples::Real(_) => d.var(VarType::Real, 64, q.name),
                Samples::Bit(_) => d.var(VarType::Wire, 1, q.name),
                Samples::Text(_) => d.var(VarType::String, 1, q.name),
            })?
        };
        let last_events = d.var(VarType::String, 1, "last_events")?;
        let fault = d.var(VarType::Wire, 1, "fault")?;
        d.w.upscope()?;
        d.w.enddefinitions()?;
        Ok(ScanWriter {
            project,
            supervisors,
            c: Changes {
                w: d.w,
                now: 0,
                stamped: None,
                last: vec![None; d.count],
            },
            inputs,
            outputs,
            names,
            numbers,
            events,
            quantities,
            last_events,
            scans_with_events: 0,
            fault,
            pulsing: Vec::new(),
            last: None,
        })
    }

    /// Writes the changes of `scan`, with the plant quantities' values
    /// `plant` in declaration order.
    fn scan(&mut self, scan: &Scan<'_>, plant: impl Iterator<Item = Written>) -> io::Result<()> {
        let (project, c) = (self.project, &mut self.c);
        c.now = scan.time_ms;
        for e in self.pulsing.drain(..) {
            c.pulse(e, &Written::Scalar(Value::V0))?;
        }
        if self.last.is_none() {
            for (event, &var) in project.events.iter().zip(&self.events) {
                if !scan.events.contains(&event.name) {
                    c.pulse(var, &Written::Scalar(Value::V0))?;
                }
            }
        }
        for (&var, &v) in self.inputs.iter().zip(&scan.inputs) {
            c.set(var, Written::Scalar(v))?;
        }
        for (&var, &v) in self.outputs.iter().zip(&scan.outputs) {
            c.set(var, Written::Scalar(v))?;
        }
        for (j, (_, state)) in scan.states.iter().enumerate() {
            c.set(self.names[j], Written::Text(escape(state)))?;
            let number = self.supervisors.parse_state(j, state).map(u64::from);
            c.set(self.numbers[j], Written::Vector(number))?;
        }
        for name in scan.events {
            if let Some(e) = project.event(name) {
                c.pulse(self.events[e], &Written::Scalar(Value::V1))?;
                self.pulsing.push(self.events[e]);
            }
        }
        if !scan.events.is_empty() {
            self.scans_with_events += 1;
            let label = format!("{}:{}", self.scans_with_events, scan.events.join(" "));
            c.set(self.last_events, Written::Text(escape(&label)))?;
        } else if self.last.is_none() {
            c.set(self.last_events, Written::Text("-".to_owned()))?;
        }
        for (&var, value) in self.quantities.iter().zip(plant) {
            c.set(var, value)?;
        }
        c.set(self.fault, Written::Scalar(Value::from(scan.fault)))?;
        self.last = Some(scan.time_ms);
        Ok(())
    }

    /// The waveform lasts until the last scan, changes or not.
    fn finish(mut self) -> io::Result<()> {
        if let Some(last) = self.last {
            self.c.now = last;
            self.c.stamp()?;
        }
        self.c.w.flush()
    }
}

/// `name` as a VCD identifier: characters VCD cannot carry as `_`.
pub(crate) fn identifier(name: &str) -> String {
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

/// `value` as `width` bits, most significant first; all `x` for none.
fn bits(value: Option<u64>, width: u32) -> Vec<Value> {
    (0..width)
        .rev()
        .map(|b| match value {
            None => Value::X,
            Some(v) if v >> b & 1 == 1 => Value::V1,
            Some(_) => Value::V0,
        })
        .collect()
}

/// `text` as one VCD string token: whitespace, control characters and the
/// backslash as `\ooo` (octal), as GTKWave writes them; other characters,
/// UTF-8 included, as they are. An empty text is `""`.
fn escape(text: &str) -> String {
    if text.is_empty() {
        return "\"\"".to_owned();
    }
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c == '\\' || c.is_ascii_whitespace() || c.is_ascii_control() {
            out.push_str(&format!("\\{:03o}", c as u32));
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_string_value_stays_one_token_and_reads_as_gtkwave_writes_it() {
        assert_eq!(escape("idle"), "idle");
        assert_eq!(escape("idle hold"), "idle\\040hold");
        assert_eq!(escape("a\tb\\c"), "a\\011b\\134c");
        assert_eq!(escape("größe"), "größe");
        assert_eq!(escape(""), "\"\"");
    }

    #[test]
    fn state_numbers_are_msb_first_and_unknown_states_are_x() {
        assert_eq!(
            bits(Some(5), 4),
            [Value::V0, Value::V1, Value::V0, Value::V1]
        );
        assert_eq!(bits(None, 2), [Value::X, Value::X]);
    }
}
