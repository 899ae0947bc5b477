//! A flame as the burner sees it: it forms once its ignition conditions
//! have held for a delay (gas and spark for the pilot; pilot, gas and air
//! for the main flame) and dies a delay after its fuel or air goes. A
//! blow-out keeps it from forming again for a while.

/// A flame: it forms after its conditions have held for a while and dies a
/// while after they go.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Flame {
    lit: bool,
    /// Conditions held for this long (while unlit).
    forming_ms: u64,
    /// Fuel or air gone for this long (while lit).
    starving_ms: u64,
    /// Cannot form before this time.
    blocked_until_ms: u64,
}

impl Flame {
    /// The flame burns.
    pub(super) fn lit(&self) -> bool {
        self.lit
    }

    /// Advances by `dt_ms` from `now_ms`: `can_form` says the ignition
    /// conditions hold, `fed` that a lit flame keeps its fuel and air.
    pub(super) fn step(
        &mut self,
        now_ms: u64,
        dt_ms: u64,
        can_form: bool,
        fed: bool,
        form_ms: u64,
        die_ms: u64,
    ) {
        if self.lit {
            self.starving_ms = if fed { 0 } else { self.starving_ms + dt_ms };
            if self.starving_ms >= die_ms {
                self.lit = false;
                self.starving_ms = 0;
            }
        } else if can_form && now_ms + dt_ms > self.blocked_until_ms {
            let from = self.blocked_until_ms.max(now_ms);
            self.forming_ms += now_ms + dt_ms - from;
            if self.forming_ms >= form_ms {
                self.lit = true;
                self.forming_ms = 0;
            }
        } else {
            self.forming_ms = 0;
        }
    }

    /// Puts the flame out now; it cannot form again before `until_ms`.
    pub(super) fn blow_out(&mut self, until_ms: u64) {
        *self = Flame {
            blocked_until_ms: until_ms,
            ..Flame::default()
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steps `flame` in 10 ms steps from `from_ms` to `to_ms`.
    fn hold(flame: &mut Flame, from_ms: u64, to_ms: u64, can_form: bool, fed: bool) {
        for now in (from_ms..to_ms).step_by(10) {
            flame.step(now, 10, can_form, fed, 100, 30);
        }
    }

    #[test]
    fn a_flame_forms_after_its_delay_and_dies_after_its_own() {
        let mut flame = Flame::default();
        hold(&mut flame, 0, 90, true, true);
        assert!(!flame.lit());
        hold(&mut flame, 90, 100, true, true);
        assert!(flame.lit());
        hold(&mut flame, 100, 120, false, false);
        assert!(flame.lit(), "still burning 20 ms after its fuel went");
        hold(&mut flame, 120, 130, false, false);
        assert!(!flame.lit());
    }

    #[test]
    fn a_blown_out_flame_counts_its_delay_from_the_end_of_the_block() {
        let mut flame = Flame::default();
        flame.blow_out(1_000);
        hold(&mut flame, 0, 1_090, true, true);
        assert!(!flame.lit(), "90 ms of conditions after the block");
        hold(&mut flame, 1_090, 1_100, true, true);
        assert!(flame.lit());
    }
}
