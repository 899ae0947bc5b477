#!/usr/bin/env python3
"""libFAUDES oracle for `tests/faudes_diff.rs`.

Reads a JSON list of problems on stdin and writes a JSON list of results on
stdout, one result per problem, in order. An automaton is

    {"name": str, "events": [[name, controllable], ...], "states": n,
     "initial": index or null, "marked": [index, ...],
     "transitions": [[source, event_name, target], ...]}

with states numbered 0..n-1. Problems come in these kinds:

- synthesis: {"id", "plant": [automaton, ...], "spec": [automaton, ...]}.
  plant = Parallel of the plant components, spec = Parallel of the spec
  components, extended to the plant alphabet by InvProject (self-loops of
  the plant events it lacks), sup = SupCon(plant, spec), min =
  StateMin(sup). Result: {"id", "plant_size": [states, transitions],
  "spec_size": [...], "sup": automaton, "sup_size": [...], "sup_trim":
  bool, "min": automaton, "min_size": [...]}.
- minimisation: {"id", "minimize": automaton}. Result: {"id", "min":
  automaton, "min_size": [states, transitions]}.
- projection: {"id", "project": automaton, "keep": [event name, ...]}.
  Result: {"id", "projection": Project(automaton, keep), "observer":
  IsNaturalObserver(automaton, keep)}.
- normality: {"id", "normal": {"plant": automaton, "k": automaton,
  "observable": [event, ...]}}. Result: {"id", "normal": IsNormal on the
  marked languages, "normal_closed": IsNormal on the generated ones}.
- supremal normal sublanguage: {"id", "supnorm": {"plant", "k",
  "observable"}}. Result: {"id", "sup": SupNorm, "sup_closed":
  SupNormClosed}, automata.
- supremal controllable normal sublanguage: {"id", "supconnorm":
  {"plant": [automaton, ...], "spec": [automaton, ...], "controllable":
  [event, ...], "observable": [event, ...]}}, composed as for synthesis.
  Result: {"id", "sup": SupConNorm, "sup_closed": SupConNormClosed}.

Either kind may carry "gen": [{"what": str, "text": str}, ...], files in
libFAUDES's .gen format as our writer produced them. Each is read with
libFAUDES itself (System.FromString) and the result lists what libFAUDES
read, in "gen_read": [{"what", "states": [name, ...], "initial": [name,
...], "marked": [name, ...], "events": [[name, controllable], ...],
"transitions": [[source name, event, target name], ...]}, ...], a state
without a name standing as its index ("7"); or {"what", "error": message}
when libFAUDES refuses the file.

A problem on which libFAUDES throws gives {"id", "error": message}.

Results are automata with states renumbered densely in libFAUDES's state
order (ascending index). Everything libFAUDES prints (warnings about
optional graphics modules on import, exception traces) goes to stderr: the
real stdout carries nothing but the JSON.
"""

import json
import os
import sys


def main():
    # Keep the real stdout for the JSON and send fd 1 (Python and C++
    # alike) to stderr while libFAUDES runs.
    out = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    try:
        import faudes
    except ImportError as e:
        sys.stderr.write(
            "oracle.py: cannot import the Python package `faudes` "
            f"(libFAUDES; pip install faudes): {e}\n"
        )
        return 3

    problems = json.load(sys.stdin)
    results = []
    for problem in problems:
        pid = problem.get("id")
        try:
            if "normal" in problem:
                result = normality(faudes, problem)
            elif "supnorm" in problem:
                result = supnorm(faudes, problem)
            elif "supconnorm" in problem:
                result = supconnorm(faudes, problem)
            elif "minimize" in problem:
                result = minimize(faudes, problem)
            elif "project" in problem:
                result = project(faudes, problem)
            else:
                result = synthesise(faudes, problem)
        except Exception as e:  # libFAUDES throws plain Exceptions
            result = {"id": pid, "error": f"{type(e).__name__}: {e}"}
        if "gen" in problem:
            result["gen_read"] = [read_gen(faudes, f) for f in problem["gen"]]
        results.append(result)
    sys.stdout.flush()
    json.dump(results, out)
    out.write("\n")
    out.flush()
    return 0


def controllability(automata):
    """Event name -> controllable, over all given automata."""
    table = {}
    for a in automata:
        for name, controllable in a["events"]:
            table[name] = bool(controllable)
    return table


def build(faudes, a):
    """A faudes.Generator from a JSON automaton."""
    g = faudes.Generator()
    g.Name(a["name"])
    for name, _ in a["events"]:
        g.InsEvent(name)
    xs = [g.InsState() for _ in range(a["states"])]
    if a["initial"] is not None:
        g.SetInitState(xs[a["initial"]])
    for m in a["marked"]:
        g.SetMarkedState(xs[m])
    for s, e, t in a["transitions"]:
        g.SetTransition(xs[s], g.EventIndex(e), xs[t])
    return g


def compose(faudes, gens):
    """Parallel composition of a list of generators (none: the marked
    empty string, the neutral element). The result is accessible."""
    if not gens:
        neutral = faudes.Generator()
        neutral.SetMarkedState(neutral.InsInitState())
        return neutral
    result = faudes.Generator(gens[0])
    # Parallel results are accessible; a lone component is made so too,
    # as our `sync` of one automaton is its reachable part.
    result.Accessible()
    for g in gens[1:]:
        nxt = faudes.Generator()
        faudes.Parallel(result, g, nxt)
        result = nxt
    return result


def iterate(begin, end):
    it = begin
    while it != end:
        yield it
        it.Inc()


def to_json(g, controllable, name):
    """A JSON automaton from a generator, states numbered densely."""
    index = {}
    for it in iterate(g.StatesBegin(), g.StatesEnd()):
        index[it.Index()] = len(index)
    events = [
        [g.EventName(it.Index()), controllable.get(g.EventName(it.Index()), False)]
        for it in iterate(g.AlphabetBegin(), g.AlphabetEnd())
    ]
    initial = [index[it.Index()] for it in iterate(g.InitStatesBegin(), g.InitStatesEnd())]
    if len(initial) > 1:
        raise RuntimeError(f"{name}: {len(initial)} initial states")
    marked = sorted(index[it.Index()] for it in iterate(g.MarkedStatesBegin(), g.MarkedStatesEnd()))
    transitions = [
        [index[it.X1()], g.EventName(it.Ev()), index[it.X2()]]
        for it in iterate(g.TransRelBegin(), g.TransRelEnd())
    ]
    return {
        "name": name,
        "events": events,
        "states": len(index),
        "initial": initial[0] if initial else None,
        "marked": marked,
        "transitions": transitions,
    }


def read_gen(faudes, file):
    """What libFAUDES reads from the .gen text `file["text"]`."""
    g = faudes.System()
    try:
        g.FromString(file["text"])
    except Exception as e:  # libFAUDES throws plain Exceptions
        return {"what": file["what"], "error": f"{type(e).__name__}: {e}"}

    def state(index):
        return g.StateName(index) or str(index)

    def states(begin, end):
        return [state(it.Index()) for it in iterate(begin, end)]

    return {
        "what": file["what"],
        "states": states(g.StatesBegin(), g.StatesEnd()),
        "initial": states(g.InitStatesBegin(), g.InitStatesEnd()),
        "marked": states(g.MarkedStatesBegin(), g.MarkedStatesEnd()),
        "events": [
            [g.EventName(it.Index()), bool(g.Controllable(it.Index()))]
            for it in iterate(g.AlphabetBegin(), g.AlphabetEnd())
        ],
        "transitions": [
            [state(it.X1()), g.EventName(it.Ev()), state(it.X2())]
            for it in iterate(g.TransRelBegin(), g.TransRelEnd())
        ],
    }


def size(g):
    return [g.Size(), g.TransRelSize()]


def synthesise(faudes, problem):
    table = controllability(problem["plant"] + problem["spec"])
    plant = compose(faudes, [build(faudes, a) for a in problem["plant"]])
    spec = compose(faudes, [build(faudes, a) for a in problem["spec"]])
    faudes.InvProject(spec, plant.Alphabet())
    contr = faudes.EventSet()
    for name, c in table.items():
        if c:
            contr.Insert(name)
    sup = faudes.Generator()
    faudes.SupCon(plant, contr, spec, sup)
    minimal = faudes.Generator()
    faudes.StateMin(sup, minimal)
    reduced = supreduce(faudes, plant, sup, contr, table) if sup.Size() > 0 else None
    return {
        "id": problem["id"],
        "reduced": reduced,
        "plant_size": size(plant),
        "spec_size": size(spec),
        "sup": to_json(sup, table, "sup"),
        "sup_size": size(sup),
        "sup_trim": bool(sup.IsTrim()) or sup.Size() == 0,
        "min": to_json(minimal, table, "min"),
        "min_size": size(minimal),
    }


def supreduce(faudes, plant, sup, contr, table):
    """libFAUDES's SupReduce of `sup` for `plant`, run in a forked child:
    it crashes on some inputs (SIGSEGV), which must not take the other
    problems of the batch with it. The reduced supervisor as JSON, or
    {"crashed": signal}."""
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read_end)
        try:
            system = faudes.System(sup)
            system.SetControllable(contr)
            plant_system = faudes.System(plant)
            plant_system.SetControllable(contr)
            reduced = faudes.System()
            faudes.SupReduce(plant_system, system, reduced)
            text = json.dumps(to_json(reduced, table, "reduced"))
        except Exception as e:  # libFAUDES throws plain Exceptions
            text = json.dumps({"error": f"{type(e).__name__}: {e}"})
        with os.fdopen(write_end, "w") as w:
            w.write(text)
        os._exit(0)
    os.close(write_end)
    with os.fdopen(read_end) as r:
        text = r.read()
    _, status = os.waitpid(pid, 0)
    if os.WIFSIGNALED(status):
        return {"crashed": os.WTERMSIG(status)}
    return json.loads(text)


def minimize(faudes, problem):
    a = problem["minimize"]
    table = controllability([a])
    minimal = faudes.Generator()
    faudes.StateMin(build(faudes, a), minimal)
    return {
        "id": problem["id"],
        "min": to_json(minimal, table, "min"),
        "min_size": size(minimal),
    }


def project(faudes, problem):
    """Natural projection and the natural observer property."""
    a = problem["project"]
    keep = faudes.EventSet()
    for name in problem["keep"]:
        keep.Insert(name)
    g = build(faudes, a)
    projection = faudes.Generator()
    faudes.Project(g, keep, projection)
    return {
        "id": problem["id"],
        "projection": to_json(projection, controllability([a]), "projection"),
        "observer": bool(faudes.IsNaturalObserver(g, keep)),
    }


# ---------------------------------------------------------------------
# Partial observation: IsNormal, SupNorm, SupConNorm


def event_set(faudes, names):
    result = faudes.EventSet()
    for name in names:
        result.Insert(name)
    return result


def closure(faudes, g):
    """A copy of `g` with every state marked: its marked language is its
    generated one."""
    result = faudes.Generator(g)
    for it in iterate(g.StatesBegin(), g.StatesEnd()):
        result.SetMarkedState(it.Index())
    return result


def normality(faudes, problem):
    """IsNormal of K's marked language w.r.t. the plant's, and of the
    generated languages (every state marked)."""
    case = problem["normal"]
    plant = build(faudes, case["plant"])
    k = build(faudes, case["k"])
    obs = event_set(faudes, case["observable"])
    closed = faudes.IsNormal(closure(faudes, plant), obs, closure(faudes, k))
    return {
        "id": problem["id"],
        "normal": bool(faudes.IsNormal(plant, obs, k)),
        "normal_closed": bool(closed),
    }


def supnorm(faudes, problem):
    """SupNorm and SupNormClosed of K w.r.t. the plant."""
    case = problem["supnorm"]
    table = controllability([case["plant"], case["k"]])
    plant = build(faudes, case["plant"])
    k = build(faudes, case["k"])
    obs = event_set(faudes, case["observable"])
    sup = faudes.Generator()
    faudes.SupNorm(plant, obs, k, sup)
    sup_closed = faudes.Generator()
    faudes.SupNormClosed(plant, obs, k, sup_closed)
    return {
        "id": problem["id"],
        "sup": to_json(sup, table, "supnorm"),
        "sup_closed": to_json(sup_closed, table, "supnormclosed"),
    }


def supconnorm(faudes, problem):
    """SupConNorm and SupConNormClosed of the composed plant and the
    composed specification (extended to the plant alphabet)."""
    case = problem["supconnorm"]
    table = controllability(case["plant"] + case["spec"])
    plant = compose(faudes, [build(faudes, a) for a in case["plant"]])
    spec = compose(faudes, [build(faudes, a) for a in case["spec"]])
    faudes.InvProject(spec, plant.Alphabet())
    # Minimal first: the same languages, and SupConNormClosed can take
    # minutes on an unminimised specification of 50 states that it does
    # in a second minimised.
    minimal = faudes.Generator()
    faudes.StateMin(spec, minimal)
    spec = minimal
    contr = event_set(faudes, case["controllable"])
    obs = event_set(faudes, case["observable"])
    sup = faudes.Generator()
    faudes.SupConNorm(plant, contr, obs, spec, sup)
    sup_closed = faudes.Generator()
    faudes.SupConNormClosed(plant, contr, obs, spec, sup_closed)
    return {
        "id": problem["id"],
        "sup": to_json(sup, table, "supconnorm"),
        "sup_closed": to_json(sup_closed, table, "supconnormclosed"),
    }


if __name__ == "__main__":
    sys.exit(main())
