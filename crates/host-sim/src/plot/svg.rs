//! A [`Plot`] as SVG: a fixed layout of lanes, top to bottom: digital
//! lanes by group, the event lane, one lane per supervisor, the fault
//! lane, analog lanes, the time axis.
//!
//! Every signal is one `<path>` carrying `data-signal="<group>/<name>"`
//! (`inputs/part`, `outputs/up_sol`, `states/press`, `events`, `fault`,
//! `analog/<lane>/<series>`), made of its transitions only. Text is added
//! where it fits: event names and state names where their room on the time
//! axis allows, with every event mark and every state segment at least
//! [`HIT`] pixels wide naming itself on hover (`<title>`).

use super::{ticks, Plot};
use std::fmt::Write as _;

/// Width of the picture (px).
const WIDTH: f64 = 1200.0;
/// Right margin (px).
const RIGHT: f64 = 16.0;
/// Height of a digital lane (px).
const DIGITAL: f64 = 16.0;
/// Height of a supervisor's lane (px).
const STATE: f64 = 18.0;
/// Height of the event lane (px): marks and two rows of names.
const EVENTS: f64 = 40.0;
/// Height of an analog lane (px).
const ANALOG: f64 = 120.0;
/// Height of a group heading (px).
const HEADING: f64 = 16.0;
/// Approximate width of a character of the 10 px labels (px).
const CHAR: f64 = 6.0;
/// Event marks closer than this (px) share one mark and one hover text.
const HIT: f64 = 3.0;

/// The picture's x scale.
struct Scale {
    left: f64,
    start: u64,
    span: f64,
}

impl Scale {
    fn x(&self, t: u64) -> f64 {
        self.left + (WIDTH - RIGHT - self.left) * t.saturating_sub(self.start) as f64 / self.span
    }

    fn right(&self) -> f64 {
        WIDTH - RIGHT
    }
}

/// `<path>` data, coordinates to 0.1 px.
#[derive(Default)]
struct PathData(String);

impl PathData {
    fn op(&mut self, op: char, values: &[f64]) {
        self.0.push(op);
        for (k, v) in values.iter().enumerate() {
            if k > 0 {
                self.0.push(' ');
            }
            let _ = write!(self.0, "{}", (v * 10.0).round() / 10.0);
        }
    }
}

pub(super) fn render(plot: &Plot) -> String {
    let (start, end) = plot.span.unwrap_or((0, 0));
    let longest = plot
        .digital
        .iter()
        .map(|d| d.name.chars().count())
        .chain(plot.states.iter().map(|s| s.name.chars().count()))
        .chain(plot.analog.iter().map(|a| a.name.chars().count()))
        .max()
        .unwrap_or(0);
    let scale = Scale {
        left: (longest as f64 * 7.0 + 24.0).clamp(90.0, 260.0),
        start,
        span: (end - start).max(1) as f64,
    };
    let mut out = Svg {
        body: String::new(),
        y: 30.0,
        scale,
        end,
    };
    let mut groups: Vec<&str> = Vec::new();
    for d in &plot.digital {
        if !groups.contains(&d.group) {
            groups.push(d.group);
        }
    }
    let lanes_top = out.y;
    for group in groups {
        out.heading(group);
        for d in plot.digital.iter().filter(|d| d.group == group) {
            out.digital(group, &d.name, &d.changes);
        }
    }
    out.heading("events");
    out.events(&plot.events);
    if !plot.states.is_empty() {
        out.heading("supervisor states");
        for s in &plot.states {
            out.states(&s.name, &s.changes);
        }
    }
    out.heading("fault mode");
    out.fault_lane(&plot.faults);
    for a in &plot.analog {
        out.heading(&format!("{} ({})", a.name, a.unit));
        out.analog(a);
    }
    let lanes_bottom = out.y;
    out.shade_faults(&plot.faults, lanes_top, lanes_bottom);
    out.time_axis(lanes_top, lanes_bottom);

    let height = out.y + 10.0;
    let mut s = String::with_capacity(out.body.len() + 512);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height}" viewBox="0 0 {WIDTH} {height}" font-family="sans-serif" font-size="10">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="8" y="18" font-size="14" font-weight="bold">{}</text>"#,
        escape(&plot.title)
    );
    s.push_str(&out.body);
    s.push_str("</svg>\n");
    s
}

/// The picture being drawn, top to bottom.
struct Svg {
    body: String,
    /// Top of the next lane.
    y: f64,
    scale: Scale,
    /// Time of the last scan.
    end: u64,
}

impl Svg {
    fn heading(&mut self, text: &str) {
        let _ = writeln!(
            self.body,
            r##"<text x="8" y="{}" font-weight="bold" fill="#555">{}</text>"##,
            self.y + 12.0,
            escape(text)
        );
        self.y += HEADING;
    }

    fn label(&mut self, name: &str, height: f64) {
        let _ = writeln!(
            self.body,
            r#"<text x="16" y="{}">{}</text>"#,
            self.y + height / 2.0 + 4.0,
            escape(name)
        );
    }

    fn path(&mut self, signal: &str, data: &PathData, style: &str) {
        let _ = writeln!(
            self.body,
            r#"<path data-signal="{}" d="{}" {style}/>"#,
            escape(signal),
            data.0
        );
    }

    /// The path of a level in a digital lane at the current height, from
    /// its `(time, level)` changes to the end of the run.
    fn levels(&self, changes: impl Iterator<Item = (u64, bool)>) -> PathData {
        let (high, low) = (self.y + 3.0, self.y + DIGITAL - 3.0);
        let mut d = PathData::default();
        for (t, level) in changes {
            let y = if level { high } else { low };
            if d.0.is_empty() {
                d.op('M', &[self.scale.x(t), y]);
            } else {
                d.op('H', &[self.scale.x(t)]);
                d.op('V', &[y]);
            }
        }
        if !d.0.is_empty() {
            d.op('H', &[self.scale.x(self.end)]);
        }
        d
    }

    /// A level over time: one path of horizontal runs and vertical edges.
    fn digital(&mut self, group: &str, name: &str, changes: &[(u64, bool)]) {
        self.label(name, DIGITAL);
        let d = self.levels(changes.iter().copied());
        self.path(
            &format!("{group}/{name}"),
            &d,
            r#"fill="none" stroke="steelblue" stroke-width="1.5""#,
        );
        self.y += DIGITAL;
    }

    /// Executed events: a mark per scan that executed any (marks closer
    /// than [`HIT`] merged), named below where there is room, every mark
    /// named on hover.
    fn events(&mut self, events: &[(u64, Vec<String>)]) {
        let top = self.y;
        let mut marks = PathData::default();
        let mut free = [f64::MIN; 2];
        let mut k = 0;
        while k < events.len() {
            let x = self.scale.x(events[k].0);
            let mut end = k + 1;
            while end < events.len() && self.scale.x(events[end].0) - x < HIT {
                end += 1;
            }
            let group = &events[k..end];
            marks.op('M', &[x, top + 2.0]);
            marks.op('V', &[top + 14.0]);
            let mut hover = String::new();
            for (n, (t, names)) in group.iter().enumerate() {
                if n == 8 {
                    let _ = write!(hover, "\n… {} more scans", group.len() - n);
                    break;
                }
                let _ = write!(
                    hover,
                    "{}{} ms: {}",
                    if n == 0 { "" } else { "\n" },
                    t,
                    names.join(" ")
                );
            }
            let _ = writeln!(
                self.body,
                r#"<rect x="{:.1}" y="{top}" width="{HIT}" height="14" fill-opacity="0"><title>{}</title></rect>"#,
                x - HIT / 2.0,
                escape(&hover)
            );
            let text = group[0].1.join(" ");
            let more = if group.len() > 1 || group[0].1.len() > 1 {
                "…"
            } else {
                ""
            };
            let name = if more.is_empty() {
                text
            } else {
                format!("{}{more}", group[0].1[0])
            };
            let width = name.chars().count() as f64 * CHAR;
            if let Some(row) =
                (0..2).find(|&r| free[r] <= x && x + width <= self.scale.right() + RIGHT)
            {
                let _ = writeln!(
                    self.body,
                    r#"<text x="{x:.1}" y="{}" font-size="9">{}</text>"#,
                    top + 24.0 + 11.0 * row as f64,
                    escape(&name)
                );
                free[row] = x + width + 4.0;
            }
            k = end;
        }
        self.path(
            "events",
            &marks,
            r#"fill="none" stroke="darkorange" stroke-width="2""#,
        );
        self.y += EVENTS;
    }

    /// A supervisor's states: a band cut at each change, each segment
    /// named where it is wide enough and on hover.
    fn states(&mut self, name: &str, changes: &[(u64, String)]) {
        self.label(name, STATE);
        let (top, bottom) = (self.y + 2.0, self.y + STATE - 2.0);
        let (left, right) = (self.scale.x(self.scale.start), self.scale.right());
        let mut d = PathData::default();
        d.op('M', &[left, top]);
        d.op('H', &[right]);
        d.op('M', &[left, bottom]);
        d.op('H', &[right]);
        for (k, (t, state)) in changes.iter().enumerate() {
            let x = self.scale.x(*t);
            let until = changes.get(k + 1).map_or(self.end, |c| c.0);
            let x_end = self.scale.x(until);
            d.op('M', &[x, top]);
            d.op('V', &[bottom]);
            if x_end - x >= HIT {
                let fits = state.chars().count() as f64 * CHAR + 4.0 <= x_end - x;
                let _ = writeln!(
                    self.body,
                    r#"<g><title>{} = {} from {} ms</title><rect x="{x:.1}" y="{top}" width="{:.1}" height="{}" fill-opacity="0"/>{}</g>"#,
                    escape(name),
                    escape(state),
                    t,
                    x_end - x,
                    bottom - top,
                    if fits {
                        format!(
                            r#"<text x="{:.1}" y="{}">{}</text>"#,
                            x + 2.0,
                            bottom - 3.0,
                            escape(state)
                        )
                    } else {
                        String::new()
                    }
                );
            }
        }
        self.path(
            &format!("states/{name}"),
            &d,
            r#"fill="none" stroke="slategray" stroke-width="1""#,
        );
        self.y += STATE;
    }

    /// The fault lane: a band while in fault mode, its cause written at
    /// its start where there is room and on hover.
    fn fault_lane(&mut self, faults: &[(u64, Option<String>)]) {
        self.label("fault", DIGITAL);
        let (high, low) = (self.y + 3.0, self.y + DIGITAL - 3.0);
        let d = self.levels(faults.iter().map(|(t, cause)| (*t, cause.is_some())));
        let mut free = f64::MIN;
        for (t, cause) in faults {
            let x = self.scale.x(*t);
            if let Some(cause) = cause {
                let _ = writeln!(
                    self.body,
                    r#"<rect x="{x:.1}" y="{high}" width="{HIT}" height="{}" fill-opacity="0"><title>fault from {t} ms: {}</title></rect>"#,
                    low - high,
                    escape(cause)
                );
                let width = cause.chars().count() as f64 * CHAR;
                if x >= free && x + 3.0 + width <= WIDTH {
                    let _ = writeln!(
                        self.body,
                        r#"<text x="{:.1}" y="{}" fill="firebrick">{}</text>"#,
                        x + 3.0,
                        low - 1.0,
                        escape(cause)
                    );
                    free = x + width + 8.0;
                }
            }
        }
        self.path(
            "fault",
            &d,
            r#"fill="none" stroke="firebrick" stroke-width="1.5""#,
        );
        self.y += DIGITAL;
    }

    /// Fault mode shaded across every lane, as one path of rectangles.
    fn shade_faults(&mut self, faults: &[(u64, Option<String>)], top: f64, bottom: f64) {
        let mut d = PathData::default();
        for (k, (t, cause)) in faults.iter().enumerate() {
            if cause.is_none() {
                continue;
            }
            let until = faults.get(k + 1).map_or(self.end, |f| f.0);
            let (x0, x1) = (
                self.scale.x(*t),
                self.scale.x(until).max(self.scale.x(*t) + 1.0),
            );
            d.op('M', &[x0, top]);
            d.op('H', &[x1]);
            d.op('V', &[bottom]);
            d.op('H', &[x0]);
            d.op('Z', &[]);
        }
        self.path("fault-shading", &d, r#"fill="red" fill-opacity="0.1""#);
    }

    /// An analog lane: a labelled tick axis on its fixed scale, one path
    /// per quantity, its name at its last value.
    fn analog(&mut self, lane: &super::Analog) {
        let (top, bottom) = (self.y + 6.0, self.y + ANALOG - 6.0);
        let (lo, hi) = lane.range;
        let y = |v: f64| bottom - (bottom - top) * (v - lo) / (hi - lo).max(f64::MIN_POSITIVE);
        let (left, right) = (self.scale.x(self.scale.start), self.scale.right());
        let mut grid = PathData::default();
        for v in ticks::values(lane.range) {
            grid.op('M', &[left, y(v)]);
            grid.op('H', &[right]);
            let _ = writeln!(
                self.body,
                r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{v} {}</text>"#,
                left - 4.0,
                y(v) + 3.0,
                escape(lane.unit)
            );
        }
        let _ = writeln!(
            self.body,
            r##"<path d="{}" fill="none" stroke="#ddd"/>"##,
            grid.0
        );
        for series in &lane.series {
            let mut d = PathData::default();
            // A point is kept where the line has moved half a pixel since
            // the last one kept, with the sample before it (so that a step
            // stays a step), and the last point always.
            let mut last: Option<(f64, f64)> = None;
            let mut skipped: Option<(f64, f64)> = None;
            let samples = &series.samples;
            for (k, &(t, v)) in samples.iter().enumerate() {
                let point = (self.scale.x(t), y(v));
                match last {
                    None => d.op('M', &[point.0, point.1]),
                    Some((_, ly)) if (point.1 - ly).abs() >= 0.5 || k + 1 == samples.len() => {
                        let moved = (point.1 - ly).abs() >= 0.5;
                        if let Some(held) = skipped.take().filter(|_| moved) {
                            d.op('L', &[held.0, held.1]);
                        }
                        d.op('L', &[point.0, point.1]);
                    }
                    Some(_) => {
                        skipped = Some(point);
                        continue;
                    }
                }
                last = Some(point);
            }
            self.path(
                &format!("analog/{}/{}", lane.name, series.name),
                &d,
                &format!(
                    r#"fill="none" stroke="{}" stroke-width="1.5""#,
                    series.colour
                ),
            );
            if let (Some(&(_, first)), Some(&(_, v))) = (samples.first(), samples.last()) {
                let _ = writeln!(
                    self.body,
                    r#"<text x="{:.1}" y="{:.1}" text-anchor="end" fill="{}">{} {first:.1} → {v:.1} {}</text>"#,
                    right - 2.0,
                    y(v) - 4.0,
                    series.colour,
                    escape(&series.name),
                    escape(lane.unit)
                );
            }
        }
        self.y += ANALOG;
    }

    /// The time axis under the lanes, its ticks' grid lines across them.
    fn time_axis(&mut self, top: f64, bottom: f64) {
        let mut grid = PathData::default();
        for (t, label) in ticks::time(self.scale.start, self.end.max(self.scale.start)) {
            let x = self.scale.x(t);
            grid.op('M', &[x, top]);
            grid.op('V', &[bottom + 4.0]);
            let _ = writeln!(
                self.body,
                r#"<text x="{x:.1}" y="{}" text-anchor="middle">{label}</text>"#,
                bottom + 16.0
            );
        }
        let _ = writeln!(
            self.body,
            r##"<path d="{}" fill="none" stroke="#ccc" stroke-width="0.5"/>"##,
            grid.0
        );
        self.y = bottom + 22.0;
    }
}

/// `text` for SVG text and attribute values.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path_of<'a>(svg: &'a str, signal: &str) -> &'a str {
        let key = format!("data-signal=\"{signal}\" d=\"");
        let rest = &svg[svg.find(&key).expect(signal) + key.len()..];
        &rest[..rest.find('"').unwrap()]
    }

    #[test]
    fn an_analog_step_stays_a_step() {
        let mut plot = Plot::new("t");
        let power = plot.analog("power", "kW", (0.0, 200.0), &[("firing", "red")]);
        for t in 0..1000 {
            plot.scan(t * 10);
            plot.set_analog(power[0], if t < 500 { 0.0 } else { 150.0 });
        }
        let svg = render(&plot);
        let d = path_of(&svg, "analog/power/firing");
        // From 0 ms, held to 4,990 ms, up at 5,000 ms, held to the end.
        assert_eq!(d.matches(['M', 'L']).count(), 4, "{d}");
    }

    #[test]
    fn a_fault_cause_is_written_only_where_it_fits_in_the_picture() {
        let mut plot = Plot::new("t");
        for t in 0..100 {
            plot.scan(t * 10);
            plot.fault((t == 20 || t == 99).then_some("Unexpected:t2_at13"));
        }
        let svg = render(&plot);
        assert_eq!(svg.matches(">Unexpected:t2_at13</text>").count(), 1);
        assert_eq!(svg.matches("<title>fault from").count(), 2, "both on hover");
        assert_eq!(path_of(&svg, "fault-shading").matches('Z').count(), 2);
    }
}
