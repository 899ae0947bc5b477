//! Axis ticks: round steps (1, 2 or 5 times a power of ten) and their
//! labels.

/// The smallest round step (1, 2 or 5 × 10^k) that cuts `span` into at
/// most `most` parts; 1 for an empty span.
pub(super) fn step(span: f64, most: u32) -> f64 {
    if span <= 0.0 || !span.is_finite() {
        return 1.0;
    }
    let mut power = 10f64.powi((span / f64::from(most)).log10().floor() as i32);
    loop {
        for m in [1.0, 2.0, 5.0] {
            if span / (m * power) <= f64::from(most) {
                return m * power;
            }
        }
        power *= 10.0;
    }
}

/// `range` widened to hold `value`: its far end moved out to the next
/// multiple of the range's tick step.
pub(super) fn widen((bottom, top): (f64, f64), value: f64) -> (f64, f64) {
    let step = step(top - bottom, 5);
    if value > top {
        (bottom, (value / step).ceil() * step)
    } else if value < bottom {
        ((value / step).floor() * step, top)
    } else {
        (bottom, top)
    }
}

/// The ticks of a time axis from `start` to `end` (ms): at most 10, at
/// round times, with their labels (`20 ms`, `1.5 s`, `60 s`).
pub(super) fn time(start: u64, end: u64) -> Vec<(u64, String)> {
    let step = step((end - start) as f64, 10).max(1.0) as u64;
    let first = start.div_ceil(step) * step;
    (0..)
        .map(|k| first + k * step)
        .take_while(|&t| t <= end)
        .map(|t| (t, time_label(t, step)))
        .collect()
}

fn time_label(t: u64, step: u64) -> String {
    if step < 1000 && t < 10_000 {
        format!("{t} ms")
    } else if step % 1000 == 0 {
        format!("{} s", t / 1000)
    } else {
        let decimals = if step % 100 == 0 { 1 } else { 2 };
        format!("{:.*} s", decimals, t as f64 / 1000.0)
    }
}

/// The ticks of a value axis over `(bottom, top)`: at most 5 parts.
pub(super) fn values((bottom, top): (f64, f64)) -> Vec<f64> {
    let step = step(top - bottom, 5);
    let first = (bottom / step).ceil() as i64;
    (first..)
        .map(|k| k as f64 * step)
        .take_while(|&v| v <= top + step * 1e-9)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_round_and_cut_the_span_into_at_most_so_many_parts() {
        assert_eq!(step(240.0, 10), 50.0);
        assert_eq!(step(60_000.0, 10), 10_000.0);
        assert_eq!(step(100.0, 5), 20.0);
        assert_eq!(step(7.0, 10), 1.0);
        assert_eq!(step(0.0, 10), 1.0);
    }

    #[test]
    fn time_ticks_read_in_milliseconds_for_short_runs_and_seconds_for_long_ones() {
        let short: Vec<String> = time(0, 240).into_iter().map(|(_, l)| l).collect();
        assert_eq!(short, ["0 ms", "50 ms", "100 ms", "150 ms", "200 ms"]);
        let long = time(0, 75_000);
        assert_eq!(long[1], (10_000, "10 s".to_owned()));
        assert_eq!(long.len(), 8);
        assert_eq!(time(0, 4_000)[1].1, "500 ms");
        assert_eq!(time(0, 14_000)[1], (2_000, "2 s".to_owned()));
    }

    #[test]
    fn value_ticks_cover_the_scale() {
        assert_eq!(values((0.0, 100.0)), [0.0, 20.0, 40.0, 60.0, 80.0, 100.0]);
        assert_eq!(widen((0.0, 100.0), 230.0), (0.0, 240.0));
        assert_eq!(widen((0.0, 100.0), 50.0), (0.0, 100.0));
    }
}
