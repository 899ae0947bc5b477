//! A picture of a closed-loop run: the boiler's outputs and flames as
//! digital traces over the bath and flue-gas temperatures, as plain SVG.

use super::record::{Run, RunRow};
use super::signals::Output;
use std::fmt::Write as _;

const WIDTH: f64 = 960.0;
const LEFT: f64 = 120.0;
const ROW: f64 = 22.0;
const PLOT: f64 = 160.0;

/// The SVG text of `run`, titled `title`.
pub fn render(run: &Run, title: &str) -> String {
    let rows = &run.rows;
    let end = rows.last().map_or(1, |r| r.time_ms.max(1)) as f64;
    let x = |t: u64| LEFT + (WIDTH - LEFT - 20.0) * t as f64 / end;
    let mut traces: Vec<(String, Vec<bool>)> = Output::ALL
        .iter()
        .map(|o| {
            (
                o.name().to_owned(),
                rows.iter().map(|r| r.outputs.get(*o)).collect(),
            )
        })
        .collect();
    traces.push((
        "pilot flame".into(),
        rows.iter().map(|r| r.plant.pilot_flame).collect(),
    ));
    traces.push((
        "main flame".into(),
        rows.iter().map(|r| r.plant.main_flame).collect(),
    ));
    let digital_top = 40.0;
    let plot_top = digital_top + ROW * traces.len() as f64 + 20.0;
    let height = plot_top + PLOT + 40.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="10" y="20" font-size="14" font-weight="bold">{}</text>"#,
        escape(title)
    );
    for (k, (name, values)) in traces.iter().enumerate() {
        let base = digital_top + ROW * (k as f64 + 1.0) - 4.0;
        let _ = writeln!(s, r#"<text x="10" y="{base}">{}</text>"#, escape(name));
        let mut path = String::new();
        for (r, &v) in rows.iter().zip(values) {
            let y = if v { base - ROW * 0.6 } else { base };
            let _ = write!(
                path,
                "{}{:.1},{:.1} ",
                if path.is_empty() { "M" } else { "L" },
                x(r.time_ms),
                y
            );
        }
        let _ = writeln!(
            s,
            r#"<path d="{path}" fill="none" stroke="steelblue" stroke-width="1.5"/>"#
        );
    }
    // Temperatures, 0..max °C.
    let max = rows
        .iter()
        .map(|r| r.plant.flue_c.max(r.plant.bath_c))
        .fold(100.0f64, f64::max);
    let y = |c: f64| plot_top + PLOT * (1.0 - c / max);
    let _ = writeln!(
        s,
        r#"<text x="10" y="{}">temperature</text>"#,
        plot_top + 12.0
    );
    let _ = writeln!(
        s,
        r#"<text x="10" y="{}">0 – {max:.0} °C</text>"#,
        plot_top + 28.0
    );
    for (label, colour, pick) in [
        (
            "flue gas",
            "firebrick",
            (|r: &RunRow| r.plant.flue_c) as fn(&RunRow) -> f64,
        ),
        ("bath", "darkgreen", |r: &RunRow| r.plant.bath_c),
    ] {
        let mut path = String::new();
        for r in rows.iter().step_by((rows.len() / 2000).max(1)) {
            let _ = write!(
                path,
                "{}{:.1},{:.1} ",
                if path.is_empty() { "M" } else { "L" },
                x(r.time_ms),
                y(pick(r))
            );
        }
        let _ = writeln!(
            s,
            r#"<path d="{path}" fill="none" stroke="{colour}" stroke-width="1.5"/>"#
        );
        let last = rows.last().map_or(0.0, pick);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{:.1}" fill="{colour}">{label}</text>"#,
            WIDTH - 80.0,
            y(last) - 4.0
        );
    }
    // Time axis.
    let axis = plot_top + PLOT + 20.0;
    let step = if end > 120_000.0 { 60_000 } else { 10_000 };
    let mut t = 0;
    while t as f64 <= end {
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{axis}" text-anchor="middle">{} s</text>"#,
            x(t),
            t / 1000
        );
        let _ = writeln!(
            s,
            r##"<line x1="{0:.1}" x2="{0:.1}" y1="{digital_top}" y2="{1}" stroke="#ddd"/>"##,
            x(t),
            plot_top + PLOT
        );
        t += step;
    }
    s.push_str("</svg>\n");
    s
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
