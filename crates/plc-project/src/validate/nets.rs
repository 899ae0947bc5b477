//! Petri nets (`[[net]]`) against the declared events (their nets are
//! read, synthesised and explored before validation:
//! [`super::super::sources`]).
//!
//! - A net's `name` joins the shared namespace ([`super::names`]) and
//!   reserves the names of its groups, `name.1`, `name.2`, … (lowering
//!   packs a net into as many groups as its counters need, so every such
//!   name is kept free, whatever the count).
//! - Every transition is the project event of the same name: declared in
//!   `[events]`, controllable exactly when the transition is, and
//!   observable (the controller fires only what it sees).
//! - Each place becomes a counter wide enough for its bound (at least one
//!   bit, at most [`COUNTER_BITS`]); lowering packs the counters into
//!   executor supervisors.
//! - A controlled net with dead markings is accepted with a warning that
//!   names a firing sequence into one (a batch plant may end on purpose).

use super::super::model::{Event, Net, NetSource, COUNTER_BITS};
use super::super::parse::RawNet;
use super::super::sources::LoadedNet;
use super::{Declared, Validator};
use des::error::Result;
use toml::Spanned;

impl Validator<'_> {
    /// Checks every `[[net]]` (`raw`) and its net (`loaded`, one per
    /// table) against the events.
    pub(super) fn nets(
        &mut self,
        raw: &[Spanned<RawNet>],
        loaded: Vec<LoadedNet>,
        events: &Declared<Event>,
    ) -> Result<Declared<Net>> {
        let mut nets = Declared::new("net", "[net]");
        for (raw, loaded) in raw.iter().zip(loaded) {
            let net = self.net(raw, loaded, events)?;
            let name = net.name.clone();
            nets.push(&name, raw.span(), net);
        }
        Ok(nets)
    }

    fn net(
        &mut self,
        raw: &Spanned<RawNet>,
        loaded: LoadedNet,
        events: &Declared<Event>,
    ) -> Result<Net> {
        let header = raw.span();
        let name = raw.get_ref().name.get_ref().clone();
        self.claim("net", &name, &raw.get_ref().name.span())?;
        let LoadedNet {
            net,
            source,
            reach,
            control_places,
        } = loaded;
        let described = match &source {
            NetSource::File(p) => format!("net `{name}` (`{}`)", p.display()),
            NetSource::Synthesized { plant, .. } => {
                format!("controlled net `{name}` (`{}`)", plant.display())
            }
        };

        let mut transition_events = Vec::with_capacity(net.transitions().len());
        for t in net.transitions() {
            let Some(&g) = events.index.get(&t.id) else {
                return Err(self.error(
                    &header,
                    format!(
                        "transition `{}` of {described} is not declared in [events]",
                        t.id
                    ),
                ));
            };
            if !t.observable {
                return Err(self.error(
                    &header,
                    format!(
                        "transition `{}` of {described} is unobservable: the controller fires only transitions it observes",
                        t.id
                    ),
                ));
            }
            let event = &events.items[g];
            if event.controllable != t.controllable {
                let word = |c: bool| if c { "controllable" } else { "uncontrollable" };
                return Err(self.error(
                    &events.spans[g],
                    format!(
                        "event `{}` is {} here but {} in {described}",
                        event.name,
                        word(event.controllable),
                        word(t.controllable)
                    ),
                ));
            }
            transition_events.push(g);
        }

        // Counters: each must fit the executor's word.
        let widths = Net::counter_widths(&net, &reach.bounds);
        if let Some(p) = widths.iter().position(|&w| w > COUNTER_BITS) {
            return Err(self.error(
                &header,
                format!(
                    "place `{}` of {described} holds up to {} tokens or has an arc that heavy: a counter holds at most {}",
                    net.places()[p].id,
                    reach.bounds[p],
                    (1u64 << COUNTER_BITS) - 1
                ),
            ));
        }
        if net.places().is_empty() {
            return Err(self.error(&header, format!("{described} has no places")));
        }

        if let Some(&dead) = reach.dead.first() {
            let sequence: Vec<&str> = reach
                .firing_sequence(dead)
                .into_iter()
                .map(|t| net.transitions()[t].id.as_str())
                .collect();
            let after = if sequence.is_empty() {
                "initially".to_owned()
            } else {
                format!("after {}", sequence.join(" "))
            };
            self.warn(
                &header,
                format!(
                    "{described} reaches {} dead marking(s), e.g. {} {after}: no transition can fire there",
                    reach.dead.len(),
                    net.marking_name(&reach.markings[dead])
                ),
            );
        }

        Ok(Net {
            name,
            events: transition_events,
            bounds: reach.bounds,
            markings: reach.markings.len(),
            control_places,
            net,
            source,
            line: self.line(&header),
        })
    }
}
