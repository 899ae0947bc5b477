//! Natural projection and the observer property against libFAUDES
//! (`Project`, `IsNaturalObserver`).
//!
//! Random accessible automata (1–10 states, 1–5 events, often blocking)
//! are projected onto random subsets of their events, none and all
//! included. Per case:
//!
//! - our projection and libFAUDES's have the same closed and marked
//!   languages (state numbering differs, so languages are compared);
//! - libFAUDES's `IsNaturalObserver` holds exactly when our projection is
//!   both an `Lm(G)`- and an `L(G)`-observer;
//! - where one of ours fails, its witness is checked on its own terms: `s`
//!   is a string of the automaton, `P(s)·t` is in libFAUDES's projection
//!   (marked there, for `Lm`), and the automaton after `s` reaches no
//!   marked state (for `L`: no state) along a string whose projection is
//!   `t`.
//!
//! `FAUDES_DIFF_CASES` × 5 cases (1,000 by default); with 100 or more the
//! test insists on at least 20% observers, 10% non-observers, 20% inputs
//! with events erased, 10% blocking inputs and 2% `Lm(G)`-observers that
//! are no `L(G)`-observers.

use super::*;
use des::ops::sync::DEFAULT_MAX_STATES as LIMIT;
use des::ops::{check_observer, project, LanguageKind, ObserverWitness};

/// Projection cases per `FAUDES_DIFF_CASES`: each is small.
const PER_CASE: usize = 5;

#[derive(Debug, Clone, Serialize)]
struct ProjectionProblem {
    id: usize,
    project: JsonAutomaton,
    keep: Vec<String>,
}

impl Case for ProjectionProblem {
    fn id(&self) -> usize {
        self.id
    }
}

#[derive(Debug, Clone, Deserialize)]
struct ProjectionAnswer {
    id: usize,
    error: Option<String>,
    projection: Option<JsonAutomaton>,
    observer: Option<bool>,
}

impl Case for ProjectionAnswer {
    fn id(&self) -> usize {
        self.id
    }
}

fn projection_problem(seed: u64, id: usize) -> ProjectionProblem {
    let mut rng = Rng::for_case(seed ^ 0x5052_4F4A_4543_5400, id);
    let events: Vec<(String, bool)> = (0..rng.range(1, 5))
        .map(|i| (format!("e{i}"), rng.chance(0.5)))
        .collect();
    let density = one_of(&mut rng, &[0.3, 0.5, 0.7]);
    let marking = one_of(&mut rng, &[0.1, 0.3, 0.6]);
    let shape = Shape {
        states: rng.range(1, 10),
        controllable: density,
        uncontrollable: density,
        marking,
        initial_marked: marking,
        resting_start: 0.0,
    };
    let a = random_automaton(&mut rng, "G", &events, shape);
    let keep_chance = one_of(&mut rng, &[0.3, 0.6, 0.9]);
    let keep = events
        .iter()
        .filter(|_| rng.chance(keep_chance))
        .map(|e| e.0.clone())
        .collect();
    ProjectionProblem {
        id,
        project: to_json(&accessible(&a.build()), "G"),
        keep,
    }
}

/// The states of `g` reachable from `seeds` by events outside `keep`.
fn closure(g: &Automaton, keep: &[String], seeds: Vec<StateId>) -> Vec<StateId> {
    let mut seen = seeds.clone();
    let mut stack = seeds;
    while let Some(s) = stack.pop() {
        for t in g.transitions(s) {
            let erased = !keep.iter().any(|k| k == g.alphabet().name(t.event));
            if erased && !seen.contains(&t.target) {
                seen.push(t.target);
                stack.push(t.target);
            }
        }
    }
    seen
}

/// What is wrong with `w` as a counterexample to the `language`-observer
/// property of `g` onto `keep`, `theirs` being libFAUDES's projection.
fn witness_fault(
    g: &Automaton,
    keep: &[String],
    theirs: &Automaton,
    language: LanguageKind,
    w: &ObserverWitness,
) -> Option<String> {
    let marked = |a: &Automaton, s: StateId| language == LanguageKind::Closed || a.is_marked(s);
    let run = |a: &Automaton, string: &[String]| {
        string
            .iter()
            .try_fold(a.initial()?, |s, e| a.successor(s, a.alphabet().id(e)?))
    };
    let Some(x) = run(g, &w.string) else {
        return Some(format!("{:?} is not a string of the automaton", w.string));
    };
    if g.state_name(x) != w.state {
        return Some(format!(
            "{:?} leads to {}, not {}",
            w.string,
            g.state_name(x),
            w.state
        ));
    }
    let projected: Vec<String> = w
        .string
        .iter()
        .filter(|e| keep.contains(e))
        .cloned()
        .collect();
    if projected != w.projected {
        return Some(format!(
            "P({:?}) is {projected:?}, not {:?}",
            w.string, w.projected
        ));
    }
    let promised: Vec<String> = projected.iter().chain(&w.continuation).cloned().collect();
    if !run(theirs, &promised).is_some_and(|s| marked(theirs, s)) {
        return Some(format!("{promised:?} is not in libFAUDES's projection"));
    }
    let mut set = closure(g, keep, vec![x]);
    for e in &w.continuation {
        let id = g.alphabet().id(e).expect("a kept event");
        let next = set.iter().filter_map(|&s| g.successor(s, id)).collect();
        set = closure(g, keep, next);
    }
    set.iter().any(|&s| marked(g, s)).then(|| {
        format!(
            "the automaton can follow {:?} after {:?}",
            w.continuation, w.string
        )
    })
}

#[test]
#[ignore = "needs python3 with faudes (pip install faudes); run by cargo xtask ci"]
fn projection_and_observer_agree_with_libfaudes() {
    require_faudes();
    let settings = Settings::from_env();
    let start = Instant::now();
    let ids: Vec<usize> = match settings.only {
        Some(id) => vec![id],
        None => (0..settings.cases * PER_CASE).collect(),
    };
    let problems: Vec<ProjectionProblem> = ids
        .into_iter()
        .map(|id| projection_problem(settings.seed, id))
        .collect();
    let answers: Vec<ProjectionAnswer> = ask(&problems);
    let oracle_time = start.elapsed();
    let mut report = Report::new(
        settings.seed,
        "projection_and_observer_agree_with_libfaudes",
    );
    let (mut observers, mut marked_only, mut erased, mut blocking, mut shrunk) = (0, 0, 0, 0, 0);
    for (problem, answer) in problems.iter().zip(&answers) {
        let mut issues = Issues::default();
        if let Some(e) = &answer.error {
            issues.add(format!("libFAUDES threw: {e}"));
            report.case(problem, issues);
            continue;
        }
        let g = problem.project.build();
        let keep = &problem.keep;
        let ours = project(&g, keep, LIMIT).expect("a small projection");
        let theirs = answer.projection.as_ref().expect("projection").build();
        issues.language("projection", &ours, &theirs);
        let witnesses = [LanguageKind::Marked, LanguageKind::Closed].map(|language| {
            let w = check_observer(&g, keep, language, LIMIT).expect("a small check");
            if let Some(fault) = w
                .as_ref()
                .and_then(|w| witness_fault(&g, keep, &theirs, language, w))
            {
                issues.add(format!("{language:?} observer witness {w:?}: {fault}"));
            }
            w
        });
        let observer = witnesses.iter().all(Option::is_none);
        if Some(observer) != answer.observer {
            issues.add(format!(
                "observer: ours {observer} (witnesses {witnesses:?}), libFAUDES {:?}",
                answer.observer
            ));
        }
        report.case(problem, issues);
        observers += usize::from(observer);
        marked_only += usize::from(witnesses[0].is_none() && witnesses[1].is_some());
        erased += usize::from(keep.len() < g.alphabet().len());
        blocking += usize::from(!is_trim(&g));
        shrunk += usize::from(ours.num_states() < g.num_states());
    }
    let n = problems.len();
    eprintln!(
        "faudes_diff projection: seed {:#x}, {n} cases, {} disagree; inputs: {:.1}% with \
         events erased, {:.1}% blocking; projections: {:.1}% smaller than their input, \
         {:.1}% observers, {:.1}% Lm(G)- but no L(G)-observers; {:.2?} (oracle {:.2?})",
        settings.seed,
        report.failed.len(),
        percent(erased, n),
        percent(blocking, n),
        percent(shrunk, n),
        percent(observers, n),
        percent(marked_only, n),
        start.elapsed(),
        oracle_time,
    );
    report.finish(n);
    if settings.only.is_none() && n >= 100 {
        assert!(observers * 5 >= n, "fewer than 20% observers");
        assert!((n - observers) * 10 >= n, "fewer than 10% non-observers");
        assert!(erased * 5 >= n, "fewer than 20% inputs with events erased");
        assert!(blocking * 10 >= n, "fewer than 10% blocking inputs");
        assert!(
            marked_only * 50 >= n,
            "fewer than 2% Lm(G)- but no L(G)-observers"
        );
    }
}
