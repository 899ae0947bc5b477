//! The executor's supervisors of a lowered project, in image order
//! ([`Supervisors`]): the project's automata, then the groups of each net
//! ([`super::nets`]). Names, state names and feasibility for everything
//! that shows or drives a lowered program (the emitter, traces, VCD
//! files, random inputs).

use super::nets::{NetGroups, NetLayout};
use des::automaton::StateId;
use plc_project::Project;

/// The executor's supervisors of `project` lowered into pools: the
/// automata (`0..project.supervisors.len()`), then each net's groups.
#[derive(Debug, Clone, Copy)]
pub struct Supervisors<'a> {
    project: &'a Project,
    nets: &'a [NetLayout],
}

impl<'a> Supervisors<'a> {
    /// The supervisors of `project` with its nets laid out as `nets`
    /// ([`ConfigPools::nets`](super::ConfigPools::nets) of a lowering of it).
    pub fn new(project: &'a Project, nets: &'a [NetLayout]) -> Supervisors<'a> {
        debug_assert_eq!(project.nets.len(), nets.len(), "layouts of another project");
        Supervisors { project, nets }
    }

    /// The project they were lowered from.
    pub fn project(&self) -> &'a Project {
        self.project
    }

    /// How many the executor runs.
    pub fn len(&self) -> usize {
        self.project.supervisors.len() + self.nets.iter().map(NetLayout::groups).sum::<usize>()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Net `n` read through its layout.
    pub fn net(&self, n: usize) -> NetGroups<'a> {
        NetGroups {
            net: &self.project.nets[n],
            layout: &self.nets[n],
        }
    }

    /// The net and group of supervisor `j`, `None` for an automaton.
    pub fn net_group(&self, j: usize) -> Option<(usize, usize)> {
        let mut first = self.project.supervisors.len();
        for (n, net) in self.nets.iter().enumerate() {
            if (first..first + net.groups()).contains(&j) {
                return Some((n, j - first));
            }
            first += net.groups();
        }
        None
    }

    /// The supervisor of group `g` of net `n`.
    pub fn group_supervisor(&self, n: usize, g: usize) -> usize {
        let before: usize = self.nets[..n].iter().map(NetLayout::groups).sum();
        self.project.supervisors.len() + before + g
    }

    /// The supervisors of net `n`'s groups.
    pub fn net_supervisors(&self, n: usize) -> std::ops::Range<usize> {
        let first = self.group_supervisor(n, 0);
        first..first + self.nets[n].groups()
    }

    /// The name of supervisor `j` (a net group's:
    /// [`NetGroups::group_name`]).
    pub fn name(&self, j: usize) -> String {
        match self.net_group(j) {
            Some((n, g)) => self.net(n).group_name(g),
            None => self.project.supervisors[j].name.clone(),
        }
    }

    /// The supervisor named `name`: an automaton's, or a net group's.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.project.supervisor(name).or_else(|| {
            (self.project.supervisors.len()..self.len()).find(|&j| self.name(j) == name)
        })
    }

    /// The name of state `state` of supervisor `j`: an automaton's state
    /// name (`#state` past its states), a net group's marking.
    pub fn state_name(&self, j: usize, state: u32) -> String {
        match self.net_group(j) {
            Some((n, g)) => self.net(n).state_name(g, state),
            None => {
                let a = &self.project.supervisors[j].automaton;
                if (state as usize) < a.num_states() {
                    a.state_name(StateId(state)).into_owned()
                } else {
                    format!("#{state}")
                }
            }
        }
    }

    /// The state named `name` of supervisor `j` ([`Supervisors::state_name`]
    /// read back), `None` if it has no such state.
    pub fn parse_state(&self, j: usize, name: &str) -> Option<u32> {
        match self.net_group(j) {
            Some((n, g)) => self.net(n).parse_state(g, name),
            None => self.project.supervisors[j]
                .automaton
                .state_by_name(name)
                .map(|s| s.0),
        }
    }

    /// The bits of supervisor `j`'s state numbers: a net group's packed
    /// marking, or enough for every state of an automaton (at least 1).
    pub fn state_bits(&self, j: usize) -> u32 {
        match self.net_group(j) {
            Some((n, g)) => u32::from(self.nets[n].group_bits[g]),
            None => {
                let states = self.project.supervisors[j].automaton.num_states();
                (states.saturating_sub(1).max(1) as u64).ilog2() + 1
            }
        }
    }

    /// Whether every supervisor, in the states `states` (the executor's
    /// state vector), lets event `e` occur, and every symbolic
    /// supervisor's guard of it holds.
    pub fn event_feasible(&self, e: usize, states: &[u32]) -> bool {
        let automata = self.project.supervisors.iter().enumerate().all(|(j, sup)| {
            sup.local(e).is_none_or(|(_, id)| {
                states.get(j).is_some_and(|&x| {
                    (x as usize) < sup.automaton.num_states()
                        && sup.automaton.successor(StateId(x), id).is_some()
                })
            })
        });
        let guards = self
            .project
            .guarded
            .iter()
            .all(|g| states.len() >= self.project.supervisors.len() && g.allows(e, states));
        automata
            && guards
            && (0..self.nets.len()).all(|n| {
                let groups = states.get(self.net_supervisors(n)).unwrap_or(&[]);
                self.net(n).event_enabled(e, groups)
            })
    }
}
