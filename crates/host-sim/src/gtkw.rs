//! GTKWave save files: written next to every VCD host-sim writes (`X.vcd`
//! → `X.gtkw`), so that `gtkwave X.gtkw` (or `gtkwave X.vcd X.gtkw`)
//! opens the run with its signals already shown, in collapsible groups:
//!
//! - `inputs`, `outputs`: one trace per wire;
//! - `events`: `last_events` (the events of the last scan that executed
//!   any, numbered and held until the next: readable where an event
//!   wire's one-scan pulse is a hairline), then one wire per event;
//! - `supervisor states`: each supervisor's state by name (the VCD's
//!   string variables, which GTKWave draws as labelled segments);
//! - `fault`: fault mode;
//! - `plant` (the boiler): flames and selector, then `analog`: each `real`
//!   quantity drawn as an interpolated analog trace, four rows high.
//!
//! Names are the VCD's (`<project>.<scope>.<name>`, [`crate::vcd`]). The
//! automaton numbers of the states (`state_numbers`) are left out: the
//! names say the same.

use crate::vcd::{identifier, Quantity, Samples};
use codegen::lower::Supervisors;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// GTKWave trace flags (`@<hex>` lines), from its `TR_*` bits.
mod flag {
    /// Binary, right-justified: a wire or a string.
    pub const WIRE: u32 = 0x28;
    /// Right-justified real number, drawn as an interpolated analog trace.
    pub const ANALOG: u32 = 0x20 | 0x1_0000 | 0x4_0000;
    /// A blank row stretching the analog trace above it.
    pub const ANALOG_ROW: u32 = 0x2_0000;
    /// Start of a group (blank row).
    pub const GROUP_BEGIN: u32 = 0x80_0000 | 0x200;
    /// End of a group (blank row).
    pub const GROUP_END: u32 = 0x100_0000 | 0x200;
}

/// Extra rows under an analog trace.
const ANALOG_ROWS: usize = 3;

/// The save file's text for the VCD of a replay of the project of
/// `supervisors`, the dump named `dump`.
pub fn replay(dump: &Path, supervisors: Supervisors<'_>) -> String {
    save_file(dump, supervisors, &[])
}

/// The save file's text for a VCD with `plant` quantities
/// ([`crate::vcd::write_scans`]).
pub(crate) fn save_file(dump: &Path, supervisors: Supervisors<'_>, plant: &[Quantity]) -> String {
    let project = supervisors.project();
    let top = identifier(&project.name);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "[*] GTKWave save file written by host-sim for project {top}"
    );
    let name = dump.file_name().unwrap_or(dump.as_os_str());
    let _ = writeln!(s, "[dumpfile] \"{}\"", name.to_string_lossy());
    let _ = writeln!(s, "[timestart] 0");
    let _ = writeln!(s, "[treeopen] {top}.");
    let mut group = |title: &str, traces: Vec<(u32, String)>| {
        if traces.is_empty() {
            return;
        }
        let _ = writeln!(s, "@{:x}\n-{title}", flag::GROUP_BEGIN);
        let mut last = None;
        for (flags, trace) in traces {
            if last != Some(flags) {
                let _ = writeln!(s, "@{flags:x}");
                last = Some(flags);
            }
            let _ = writeln!(s, "{top}.{trace}");
            if flags == flag::ANALOG {
                for _ in 0..ANALOG_ROWS {
                    let _ = writeln!(s, "@{:x}\n-", flag::ANALOG_ROW);
                }
                last = Some(flag::ANALOG_ROW);
            }
        }
        let _ = writeln!(s, "@{:x}\n-{title}", flag::GROUP_END);
    };
    let wires = |scope: &str, names: &mut dyn Iterator<Item = String>| -> Vec<(u32, String)> {
        names
            .map(|n| (flag::WIRE, format!("{scope}.{}", identifier(&n))))
            .collect()
    };
    group(
        "inputs",
        wires("inputs", &mut project.inputs.iter().map(|i| i.name.clone())),
    );
    group(
        "outputs",
        wires(
            "outputs",
            &mut project.outputs.iter().map(|o| o.name.clone()),
        ),
    );
    let mut events = vec![(flag::WIRE, "last_events".to_owned())];
    events.extend(wires(
        "events",
        &mut project.events.iter().map(|e| e.name.clone()),
    ));
    group("events", events);
    group(
        "supervisor states",
        wires(
            "states",
            &mut (0..supervisors.len()).map(|j| supervisors.name(j)),
        ),
    );
    group("fault", vec![(flag::WIRE, "fault".to_owned())]);
    let plant_trace = |q: &Quantity| (flag::WIRE, format!("plant.{}", identifier(q.name)));
    group(
        "plant",
        plant
            .iter()
            .filter(|q| !matches!(q.samples, Samples::Real(_)))
            .map(plant_trace)
            .collect(),
    );
    group(
        "analog",
        plant
            .iter()
            .filter(|q| matches!(q.samples, Samples::Real(_)))
            .map(|q| (flag::ANALOG, plant_trace(q).1))
            .collect(),
    );
    s
}

/// Where the save file of the VCD at `vcd` goes: `X.vcd` → `X.gtkw`;
/// none for a VCD written to something other than a regular file
/// (`/dev/null`, a pipe).
pub fn path_for(vcd: &Path) -> Option<PathBuf> {
    let special = std::fs::metadata(vcd).is_ok_and(|m| !m.is_file());
    (!special).then(|| vcd.with_extension("gtkw"))
}

/// Writes `text` as the save file of the VCD at `vcd` ([`path_for`]) and
/// returns its path, or `None` when the VCD has no save file.
pub fn write_next_to(vcd: &Path, text: &str) -> Result<Option<PathBuf>, String> {
    let Some(path) = path_for(vcd) else {
        return Ok(None);
    };
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(Some(path))
}
