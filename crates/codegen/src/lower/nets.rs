//! The executor's layout of a Petri net ([`NetLayout`]): each place a
//! counter of the width validation gave it ([`Net::counter_widths`]),
//! packed in place order into *groups* of at most
//! [`executor::table::NET_GROUP_BITS`] bits; each group is one executor
//! supervisor whose state is the group's packed marking.
//!
//! [`NetGroups`] reads a net through its layout: group names, the places
//! and transitions of a group, markings packed and unpacked, and a
//! group's state named as a marking (`free + 2·busy`) and read back.

use crate::backend::table::EncodedTable;
use executor::table::NET_GROUP_BITS;
use plc_project::Net;

/// A place's counter: which group of the net holds it, and where.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlaceField {
    /// The group (an executor supervisor of the net), from 0.
    pub group: usize,
    /// Its lowest bit in the group's packed marking.
    pub shift: u8,
    /// Its width in bits (enough for the place's bound, at least 1).
    pub width: u8,
}

impl PlaceField {
    /// The mask of the counter's bits.
    pub fn mask(&self) -> u32 {
        (((1u64 << self.width) - 1) as u32) << self.shift
    }
}

/// How a net's counters are packed into executor supervisors.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NetLayout {
    /// The counter of each place, in place order.
    pub fields: Vec<PlaceField>,
    /// The bits of each group.
    pub group_bits: Vec<u8>,
}

impl NetLayout {
    /// Packs `net`'s counters in place order, a new group whenever the
    /// next counter does not fit the current one.
    ///
    /// Validation keeps every counter within [`NET_GROUP_BITS`]
    /// (`plc_project::COUNTER_BITS`), so every counter fits an empty group.
    pub fn of(net: &Net) -> NetLayout {
        let mut fields = Vec::with_capacity(net.bounds.len());
        let mut group_bits: Vec<u8> = Vec::new();
        for width in net.widths() {
            debug_assert!(width <= NET_GROUP_BITS, "validation bounds counters");
            let fits = group_bits
                .last()
                .is_some_and(|&used| u32::from(used) + width <= NET_GROUP_BITS);
            if !fits {
                group_bits.push(0);
            }
            let group = group_bits.len() - 1;
            fields.push(PlaceField {
                group,
                shift: group_bits[group],
                width: width as u8,
            });
            group_bits[group] += width as u8;
        }
        NetLayout { fields, group_bits }
    }

    /// Number of groups (executor supervisors).
    pub fn groups(&self) -> usize {
        self.group_bits.len()
    }

    /// The places of group `g`, in place order.
    pub fn group_places(&self, g: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.fields.len()).filter(move |&p| self.fields[p].group == g)
    }

    /// A marking packed into group `g`'s state.
    pub fn pack(&self, g: usize, marking: &[u32]) -> u32 {
        self.group_places(g)
            .map(|p| (marking[p] << self.fields[p].shift) & self.fields[p].mask())
            .fold(0, |x, bits| x | bits)
    }

    /// The marking of the net from the states of its groups, in group
    /// order (a missing group reads as no tokens).
    pub fn unpack(&self, groups: &[u32]) -> des::petri::Marking {
        self.fields
            .iter()
            .map(|f| {
                groups
                    .get(f.group)
                    .map_or(0, |&x| (x & f.mask()) >> f.shift)
            })
            .collect()
    }
}

/// A net read through its layout.
#[derive(Debug, Clone, Copy)]
pub struct NetGroups<'a> {
    /// The validated net.
    pub net: &'a Net,
    /// Its layout.
    pub layout: &'a NetLayout,
}

impl NetGroups<'_> {
    /// Number of groups (executor supervisors).
    pub fn groups(&self) -> usize {
        self.layout.groups()
    }

    /// The name of group `g`: the net's name when it has one group,
    /// `name.1`, `name.2`, … otherwise (validation reserves these names).
    pub fn group_name(&self, g: usize) -> String {
        if self.groups() == 1 {
            self.net.name.clone()
        } else {
            format!("{}.{}", self.net.name, g + 1)
        }
    }

    /// The transitions with an arc to a place of group `g`, in transition
    /// order: the group's local events.
    pub fn group_transitions(&self, g: usize) -> Vec<usize> {
        let fields = &self.layout.fields;
        let touches = |arcs: &[(usize, u32)]| arcs.iter().any(|&(p, _)| fields[p].group == g);
        let transitions = self.net.net.transitions();
        (0..transitions.len())
            .filter(|&t| touches(&transitions[t].input) || touches(&transitions[t].output))
            .collect()
    }

    /// `arcs` (place, weight) on group `g`'s places as a word in the
    /// group's packed marking: a transition's `PRE` or `POST`.
    pub fn arc_word(&self, g: usize, arcs: &[(usize, u32)]) -> u32 {
        let fields = &self.layout.fields;
        arcs.iter()
            .filter(|&&(p, _)| fields[p].group == g)
            .fold(0, |x, &(p, w)| {
                x | (w << fields[p].shift) & fields[p].mask()
            })
    }

    /// Group `g` in the executor's net layout: one `PRE` and one `POST`
    /// word per transition touching it, one counter mask per place.
    pub fn encode(&self, g: usize) -> EncodedTable {
        let all = self.net.net.transitions();
        let transitions = self.group_transitions(g);
        let words = |arcs: fn(&des::petri::Transition) -> &[(usize, u32)]| -> Vec<u32> {
            transitions
                .iter()
                .map(|&t| self.arc_word(g, arcs(&all[t])))
                .collect()
        };
        let masks = self
            .layout
            .group_places(g)
            .map(|p| self.layout.fields[p].mask());
        EncodedTable::net_group(
            self.layout.group_bits[g],
            words(|t| &t.input),
            words(|t| &t.output),
            masks.collect(),
        )
    }

    /// Whether every transition of event `e` (a project event) is enabled
    /// in the marking whose groups' states are `groups`.
    pub fn event_enabled(&self, e: usize, groups: &[u32]) -> bool {
        let marking = self.layout.unpack(groups);
        (0..self.net.events.len())
            .filter(|&t| self.net.events[t] == e)
            .all(|t| self.net.net.is_enabled(&marking, t))
    }

    /// Group `g`'s state read as the marking of its places: `p_1 + 2·p_3`
    /// style, `0` for no token; an id that could be misread (`a + b`, `0`)
    /// quoted, so that [`NetGroups::parse_state`] reads every name back.
    pub fn state_name(&self, g: usize, state: u32) -> String {
        let terms: Vec<String> = self
            .layout
            .group_places(g)
            .filter_map(|p| {
                let f = self.layout.fields[p];
                let count = (state & f.mask()) >> f.shift;
                let id = des::petri::marking_term(&self.net.net.places()[p].id, "0");
                match count {
                    0 => None,
                    1 => Some(id),
                    k => Some(format!("{k}·{id}")),
                }
            })
            .collect();
        if terms.is_empty() {
            "0".to_owned()
        } else {
            terms.join(" + ")
        }
    }

    /// The state of group `g` named by [`NetGroups::state_name`], `None`
    /// if the name is not a marking of the group's places.
    pub fn parse_state(&self, g: usize, name: &str) -> Option<u32> {
        use des::petri::read_marking_term;
        if name == "0" {
            return Some(0);
        }
        let mut x = 0u32;
        let mut rest = name;
        loop {
            // A count `k·` before the id, when more than one token.
            let (count, after) = match rest.split_once('·') {
                Some((k, after)) if !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()) => {
                    (k.parse::<u32>().ok()?, after)
                }
                _ => (1, rest),
            };
            let (id, tail) = read_marking_term(after, " + ")?;
            let p = self.net.net.place(&id)?;
            let f = self.layout.fields[p];
            if f.group != g || count > f.mask() >> f.shift {
                return None;
            }
            x |= count << f.shift;
            match tail.strip_prefix(" + ") {
                Some(next) => rest = next,
                None if tail.is_empty() => return Some(x),
                None => return None,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use des::petri::NetBuilder;
    use des::Location;
    use plc_project::NetSource;

    /// A net of three places whose markings have `bounds`, one
    /// transition moving a token from the first to the last.
    fn net(bounds: [u32; 3]) -> Net {
        let at = || Location::new("n.toml", 1, 1);
        let mut b = NetBuilder::new("n".to_owned());
        for p in 0..3 {
            b.add_place(&format!("p{p}"), None, 0, at()).unwrap();
        }
        b.add_transition("t", None, true, true, at()).unwrap();
        b.add_arc("p0", "t", 1, at()).unwrap();
        b.add_arc("t", "p2", 1, at()).unwrap();
        let net = b.build();
        Net {
            name: "n".to_owned(),
            events: vec![0],
            bounds: bounds.to_vec(),
            markings: 0,
            control_places: 0,
            source: NetSource::File("n.toml".into()),
            line: 1,
            net,
        }
    }

    #[test]
    fn counters_fill_a_group_then_open_the_next() {
        // 21 bits, then 21 that do not fit beside them, then 1 that does.
        let layout = NetLayout::of(&net([1 << 20, 1 << 20, 1]));
        let field = |group, shift, width| PlaceField {
            group,
            shift,
            width,
        };
        assert_eq!(
            layout.fields,
            [field(0, 0, 21), field(1, 0, 21), field(1, 21, 1)]
        );
        assert_eq!(layout.group_bits, [21, 22]);
        // At least one bit for a place that never holds a token.
        let small = NetLayout::of(&net([3, 0, 1]));
        assert_eq!(
            small.fields,
            [field(0, 0, 2), field(0, 2, 1), field(0, 3, 1)]
        );
        assert_eq!(small.group_bits, [4]);
    }

    #[test]
    fn a_marking_packs_and_unpacks_and_names_itself() {
        // p0 fills group 0; p1 (11 bits) and p2 (4 bits) share group 1.
        let n = net([1 << 20, 1 << 10, 9]);
        let layout = NetLayout::of(&n);
        let groups = NetGroups {
            net: &n,
            layout: &layout,
        };
        assert_eq!(groups.groups(), 2);
        assert_eq!(groups.group_name(1), "n.2");
        let marking = [7, 5, 9];
        let states: Vec<u32> = (0..2).map(|g| layout.pack(g, &marking)).collect();
        assert_eq!(layout.unpack(&states), marking);
        assert_eq!(groups.state_name(1, states[1]), "5·p1 + 9·p2");
        assert_eq!(groups.parse_state(1, "5·p1 + 9·p2"), Some(states[1]));
        assert_eq!(groups.parse_state(1, "p0"), None, "p0 is in group 0");
        // `t` takes from p0 (group 0) and gives to p2 (group 1).
        assert_eq!(groups.group_transitions(0), [0]);
        assert_eq!(groups.group_transitions(1), [0]);
        assert!(groups.event_enabled(0, &states));
        assert!(!groups.event_enabled(0, &[0, states[1]]));
    }
}
