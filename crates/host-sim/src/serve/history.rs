//! What the plots draw: one sample per scan (inputs, outputs, fault mode,
//! analog quantities), thinned evenly once it holds [`History::CAPACITY`]
//! samples, so that a long fast-forward keeps bounded memory.

/// The samples of a run.
#[derive(Debug, Clone)]
pub struct History {
    inputs: usize,
    outputs: usize,
    analog: usize,
    /// Keep one scan in `stride` (doubles at every thinning).
    stride: u64,
    times: Vec<u64>,
    /// Per sample: inputs, outputs, then fault mode.
    bits: Vec<bool>,
    values: Vec<f32>,
}

/// Plot data: one value per series per time.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Series {
    /// Scan times, ms.
    pub time_ms: Vec<u64>,
    /// Per input, its raw level (0/1).
    pub inputs: Vec<Vec<u8>>,
    /// Per output, its level.
    pub outputs: Vec<Vec<u8>>,
    /// Per analog quantity, its value.
    pub analog: Vec<Vec<f32>>,
    /// Fault mode (0/1).
    pub faults: Vec<u8>,
}

impl History {
    /// The most samples kept before thinning.
    pub const CAPACITY: usize = 1 << 20;

    /// An empty history of a project with these signal counts.
    pub fn new(inputs: usize, outputs: usize, analog: usize) -> History {
        History {
            inputs,
            outputs,
            analog,
            stride: 1,
            times: Vec::new(),
            bits: Vec::new(),
            values: Vec::new(),
        }
    }

    /// Forgets every sample.
    pub fn clear(&mut self) {
        *self = History::new(self.inputs, self.outputs, self.analog);
    }

    /// Scan `scan`'s sample (kept when the current stride takes it).
    pub fn push(
        &mut self,
        scan: u64,
        time_ms: u64,
        inputs: &[bool],
        outputs: &[bool],
        fault: bool,
        analog: &[f64],
    ) {
        if scan % self.stride != 0 {
            return;
        }
        if self.times.len() == Self::CAPACITY {
            self.thin();
            if scan % self.stride != 0 {
                return;
            }
        }
        self.times.push(time_ms);
        self.bits.extend_from_slice(inputs);
        self.bits.extend_from_slice(outputs);
        self.bits.push(fault);
        self.values.extend(analog.iter().map(|&v| v as f32));
    }

    /// Keeps every other sample.
    fn thin(&mut self) {
        let width = self.inputs + self.outputs + 1;
        let keep = |i: usize| i % 2 == 0;
        let n = self.times.len();
        self.times = (0..n).filter(|&i| keep(i)).map(|i| self.times[i]).collect();
        self.bits = (0..n)
            .filter(|&i| keep(i))
            .flat_map(|i| self.bits[i * width..(i + 1) * width].iter().copied())
            .collect();
        self.values = (0..n)
            .filter(|&i| keep(i))
            .flat_map(|i| {
                self.values[i * self.analog..(i + 1) * self.analog]
                    .iter()
                    .copied()
            })
            .collect();
        self.stride *= 2;
    }

    /// At most `points` samples, evenly spread over the samples at or
    /// after `from_ms`, the last one always among them.
    pub fn series(&self, points: usize, from_ms: u64) -> Series {
        let start = self.times.partition_point(|&t| t < from_ms);
        let n = self.times.len() - start;
        let points = points.clamp(1, n.max(1));
        let picks: Vec<usize> = if n <= points {
            (start..self.times.len()).collect()
        } else {
            // The last sample, and evenly spaced ones before it.
            (0..points)
                .map(|k| start + (k * (n - 1)) / (points - 1).max(1))
                .collect()
        };
        let width = self.inputs + self.outputs + 1;
        let bit = |i: usize, k: usize| u8::from(self.bits[i * width + k]);
        Series {
            time_ms: picks.iter().map(|&i| self.times[i]).collect(),
            inputs: (0..self.inputs)
                .map(|k| picks.iter().map(|&i| bit(i, k)).collect())
                .collect(),
            outputs: (0..self.outputs)
                .map(|k| picks.iter().map(|&i| bit(i, self.inputs + k)).collect())
                .collect(),
            analog: (0..self.analog)
                .map(|k| {
                    picks
                        .iter()
                        .map(|&i| self.values[i * self.analog + k])
                        .collect()
                })
                .collect(),
            faults: picks.iter().map(|&i| bit(i, width - 1)).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_history_thins_evenly_and_keeps_the_last_sample_on_the_plot() {
        let mut h = History::new(1, 1, 1);
        let n = History::CAPACITY as u64 + 10;
        for scan in 0..n {
            h.push(
                scan,
                scan * 10,
                &[scan % 2 == 0],
                &[scan % 3 == 0],
                false,
                &[scan as f64],
            );
        }
        // Thinned once: every other scan from 0, then the stride-2 scans
        // after the capacity was reached.
        assert_eq!(h.times.len(), History::CAPACITY / 2 + 5);
        assert!(h.times.windows(2).all(|w| w[1] - w[0] == 20));
        let s = h.series(3, 0);
        assert_eq!(s.time_ms.len(), 3);
        assert_eq!(s.time_ms[0], 0);
        assert_eq!(*s.time_ms.last().unwrap(), (n - 2) * 10);
        assert_eq!(s.analog[0][2], (n - 2) as f32);
        // Inputs: scan even → 1; every kept scan is even.
        assert_eq!(s.inputs[0], vec![1, 1, 1]);
        let recent = h.series(100, (n - 20) * 10);
        assert!(recent.time_ms.iter().all(|&t| t >= (n - 20) * 10));
        assert_eq!(recent.time_ms.len(), 10);
    }
}
