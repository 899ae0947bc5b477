//! What must hold on every scan of the cell in closed loop: on the plant
//! (valves, levels, heat-up), on the controlled net's marking as read
//! from the controller (the place invariants of its control places, and
//! the marking against the valves it drives), and on the controller (it
//! never faults).

use super::params::CellParams;
use super::physics::CellState;
use super::signals::Unit;
use des::petri::constraints::Constraint;
use des::petri::PetriNet;
use std::fmt;

/// One invariant.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Rule {
    /// Two supply valves open into one mixing tank.
    TwoSupplyValves(Unit),
    /// A mixing tank's discharge valve open with both reactor inlets it
    /// feeds open: one mixture into two reactors.
    DischargeIntoTwoReactors(Unit),
    /// A mixing tank's filling valve open while its marking does not hold
    /// exactly one batch in preparation (p_m3 + p_m4 = 1): the paper's
    /// double-booked filling valve.
    FillValveBooking(Unit),
    /// A mixing tank's discharge valve open while the marking does not
    /// have exactly one reactor filling from it.
    DischargeValveBooking(Unit),
    /// Both reactors heating up at once: both hot-water valves wide open,
    /// or p_ra9 + p_rb9 > 1 (constraint (6)).
    BothHeatingUp,
    /// A mixing tank above its brim.
    MixerOverflow(Unit),
    /// A reactor above its brim.
    ReactorOverflow(Unit),
    /// `L·m + m_c ≠ b` for the named constraint on the marking read from
    /// the controller.
    PlaceInvariant(String),
    /// The controller is in fault mode (its cause).
    ControllerFault(String),
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rule::TwoSupplyValves(u) => {
                write!(f, "two supply valves into mixing tank {}", u.letter())
            }
            Rule::DischargeIntoTwoReactors(u) => {
                write!(
                    f,
                    "mixing tank {} discharging into both reactors",
                    u.letter()
                )
            }
            Rule::FillValveBooking(u) => {
                write!(
                    f,
                    "filling valve of mixing tank {} not serving exactly one batch",
                    u.letter()
                )
            }
            Rule::DischargeValveBooking(u) => write!(
                f,
                "discharge valve of mixing tank {} not serving exactly one reactor",
                u.letter()
            ),
            Rule::BothHeatingUp => write!(f, "both reactors heating up"),
            Rule::MixerOverflow(u) => write!(f, "mixing tank {} overflows", u.letter()),
            Rule::ReactorOverflow(u) => write!(f, "reactor {} overflows", u.letter()),
            Rule::PlaceInvariant(c) => write!(f, "place invariant of `{c}` broken"),
            Rule::ControllerFault(cause) => write!(f, "controller fault: {cause}"),
        }
    }
}

/// A rule broken at a time.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Violation {
    /// Plant time, ms.
    pub time_ms: u64,
    /// The rule.
    pub rule: Rule,
}

/// The places a unit's checks read, by index in the controlled net.
#[derive(Debug, Clone, Copy)]
struct UnitPlaces {
    /// p_m3, p_m4: the mixing tank preparing A, B.
    preparing: [usize; 2],
    /// p_r3: this reactor filling chemical A (from this unit's tank).
    filling_a: usize,
    /// p_r6 of the other reactor: filling chemical B from this unit's
    /// tank.
    other_filling_b: usize,
    /// p_r9: this reactor heating up.
    heating: usize,
}

/// The checks of one closed-loop run.
#[derive(Debug, Clone)]
pub struct Checker {
    params: CellParams,
    units: [UnitPlaces; 2],
    /// Each constraint's weights, bound and control place.
    constraints: Vec<(Constraint, usize)>,
}

impl Checker {
    /// Checks for `net`, the controlled net the controller runs (plant
    /// places first, then one control place per constraint of
    /// `constraints`, in order). Panics when `net` lacks a place of the
    /// cell, which only a different net has.
    pub fn new(params: &CellParams, net: &PetriNet, constraints: Vec<Constraint>) -> Checker {
        let place = |id: String| {
            net.place(&id)
                .unwrap_or_else(|| panic!("the cell's net has place `{id}`"))
        };
        let unit = |u: Unit| {
            let (m, r, other) = (u.letter(), u.letter(), u.other().letter());
            UnitPlaces {
                preparing: [place(format!("m{m}3")), place(format!("m{m}4"))],
                filling_a: place(format!("r{r}3")),
                other_filling_b: place(format!("r{other}6")),
                heating: place(format!("r{r}9")),
            }
        };
        let first_control = net.places().len() - constraints.len();
        Checker {
            params: *params,
            units: [unit(Unit::A), unit(Unit::B)],
            constraints: constraints
                .into_iter()
                .enumerate()
                .map(|(k, c)| (c, first_control + k))
                .collect(),
        }
    }

    /// The rules `state` (the plant and the valves driven), `marking`
    /// (the controlled net's, read from the controller) and `fault` (the
    /// controller's fault cause) break.
    pub fn check(&self, state: &CellState, marking: &[u32], fault: Option<String>) -> Vec<Rule> {
        let p = &self.params;
        let mut broken = Vec::new();
        let count = |places: &[usize]| places.iter().map(|&i| marking[i]).sum::<u32>();
        for u in Unit::BOTH {
            let (i, o) = (u as usize, u.other() as usize);
            let places = &self.units[i];
            let mixer = &state.valves.mixers[i];
            if mixer.supply.iter().filter(|&&open| open).count() > 1 {
                broken.push(Rule::TwoSupplyValves(u));
            }
            if mixer.discharge
                && state.valves.reactors[i].inlet_a
                && state.valves.reactors[o].inlet_b
            {
                broken.push(Rule::DischargeIntoTwoReactors(u));
            }
            if mixer.fill && count(&places.preparing) != 1 {
                broken.push(Rule::FillValveBooking(u));
            }
            if mixer.discharge && count(&[places.filling_a, places.other_filling_b]) != 1 {
                broken.push(Rule::DischargeValveBooking(u));
            }
            if state.mixer_levels[i] > p.mixer_height {
                broken.push(Rule::MixerOverflow(u));
            }
            if state.reactors[i].level > p.reactor_height {
                broken.push(Rule::ReactorOverflow(u));
            }
        }
        let heating_up = state
            .reactors
            .iter()
            .filter(|r| r.tc.hot_opening() > p.heating_up_opening)
            .count();
        if heating_up > 1 || count(&[self.units[0].heating, self.units[1].heating]) > 1 {
            broken.push(Rule::BothHeatingUp);
        }
        for (c, control) in &self.constraints {
            if c.weighted(marking) + i128::from(marking[*control]) != i128::from(c.bound) {
                broken.push(Rule::PlaceInvariant(c.name.clone()));
            }
        }
        if let Some(cause) = fault {
            broken.push(Rule::ControllerFault(cause));
        }
        broken
    }
}
