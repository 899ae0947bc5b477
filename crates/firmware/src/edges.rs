//! Lost edges (docs/semantics.md, "Fault mode": `LostEdge`). An interrupt on both
//! edges of an input's EXTI line counts its changes between two samples;
//! the scan sees only the level at each sample, so a second change in
//! between (a pulse shorter than the scan period, or a bounce) was never
//! seen: more than one change is a lost edge.
//!
//! The counts are plain data here; the board keeps them in a
//! `critical_section::Mutex<Cell<…>>` shared with the interrupt handlers
//! and takes them in the same critical section that reads the pins.

/// Changes of each input since the last sample, saturating at 255.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChangeCounts<const N: usize> {
    counts: [u8; N],
}

impl<const N: usize> Default for ChangeCounts<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> ChangeCounts<N> {
    /// No changes.
    pub const fn new() -> Self {
        ChangeCounts { counts: [0; N] }
    }

    /// One change of `input` (ignored when out of range).
    pub fn record(&mut self, input: usize) {
        if let Some(c) = self.counts.get_mut(input) {
            *c = c.saturating_add(1);
        }
    }

    /// The changes of `input` (0 when out of range).
    pub fn get(&self, input: usize) -> u8 {
        self.counts.get(input).copied().unwrap_or(0)
    }

    /// The counts so far, leaving none: what a sample does.
    pub fn take(&mut self) -> Self {
        core::mem::take(self)
    }

    /// The inputs that changed more than once, with their change counts,
    /// in input order: one lost edge each.
    pub fn lost(&self) -> impl Iterator<Item = (usize, u8)> + '_ {
        self.counts
            .iter()
            .enumerate()
            .filter(|&(_, &c)| c > 1)
            .map(|(i, &c)| (i, c))
    }
}

/// How many edge lines the chip has (`MCU.exti_lines`: 16 EXTI lines on
/// the STM32F411, 30 on the RP2040, one per GPIO); line *n*
/// listens to pin *n* of one port (`boards::Chip::exti_line`).
const LINES: usize = crate::MCU.exti_lines as usize;

/// Which input each EXTI line 0–15 counts for (one input per line: a
/// line listens to one port).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LineMap {
    inputs: [Option<u16>; LINES],
}

impl LineMap {
    /// The map from `lines[i]`, the EXTI line of input `i` when it is
    /// edge-latched. Meant for a `const`: a line above 15, a line claimed
    /// twice or more than 65 536 inputs fail to compile.
    pub const fn new(lines: &[Option<u8>]) -> LineMap {
        assert!(lines.len() <= 1 << 16, "more inputs than an Index holds");
        let mut inputs = [None; LINES];
        let mut i = 0;
        while i < lines.len() {
            if let Some(line) = lines[i] {
                assert!((line as usize) < LINES, "a line past the chip's edge lines");
                assert!(
                    inputs[line as usize].is_none(),
                    "two inputs latched on one EXTI line"
                );
                inputs[line as usize] = Some(i as u16);
            }
            i += 1;
        }
        LineMap { inputs }
    }

    /// The input line `line` counts for.
    pub const fn input(&self, line: usize) -> Option<usize> {
        if line < LINES {
            if let Some(i) = self.inputs[line] {
                return Some(i as usize);
            }
        }
        None
    }

    /// The lines in use, as a bit mask (bit n = line n).
    pub const fn mask(&self) -> u32 {
        let mut mask = 0;
        let mut line = 0;
        while line < LINES {
            if self.inputs[line].is_some() {
                mask |= 1 << line;
            }
            line += 1;
        }
        mask
    }

    /// The inputs of the lines set in `pending` (bit n = line n), in line
    /// order.
    pub fn inputs_of(&self, pending: u32) -> impl Iterator<Item = usize> + '_ {
        (0..LINES)
            .filter(move |line| pending & (1 << line) != 0)
            .filter_map(|line| self.input(line))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_than_one_change_between_samples_is_a_lost_edge() {
        let mut c = ChangeCounts::<4>::new();
        c.record(0); // a plain edge
        c.record(2);
        c.record(2); // a pulse between two samples
        c.record(3);
        c.record(3);
        c.record(3); // a pulse and an edge
        c.record(9); // out of range: ignored
        let sample = c.take();
        assert_eq!(c, ChangeCounts::new());
        assert_eq!(sample.get(0), 1);
        assert_eq!(sample.get(9), 0);
        let lost: Vec<(usize, u8)> = sample.lost().collect();
        assert_eq!(lost, [(2, 2), (3, 3)]);
        assert_eq!(c.lost().count(), 0);
    }

    #[test]
    fn counts_saturate() {
        let mut c = ChangeCounts::<1>::new();
        for _ in 0..1000 {
            c.record(0);
        }
        assert_eq!(c.get(0), 255);
    }

    #[test]
    fn the_line_map_finds_the_input_of_each_pending_line() {
        const MAP: LineMap = LineMap::new(&[Some(13), None, Some(0), Some(5)]);
        assert_eq!(MAP.input(13), Some(0));
        assert_eq!(MAP.input(0), Some(2));
        assert_eq!(MAP.input(5), Some(3));
        assert_eq!(MAP.input(1), None);
        assert_eq!(MAP.input(99), None);
        assert_eq!(MAP.mask(), (1 << 13) | (1 << 5) | 1);
        let pending = (1 << 13) | (1 << 5) | (1 << 7) | 1;
        assert_eq!(MAP.inputs_of(pending).collect::<Vec<_>>(), [2, 3, 0]);
    }

    #[test]
    #[should_panic(expected = "two inputs latched on one EXTI line")]
    fn a_line_serves_one_input() {
        let _ = LineMap::new(&[Some(4), Some(4)]);
    }

    #[test]
    #[should_panic(expected = "a line past the chip's edge lines")]
    fn lines_stop_at_15() {
        let _ = LineMap::new(&[Some(16)]);
    }
}
