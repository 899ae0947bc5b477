#!/usr/bin/env python3
"""libFAUDES side of `cargo xtask bench-faudes`.

Composes the plant and specification files given on the command line with
libFAUDES (pip package `faudes`), extends the specification to the plant
alphabet, runs SupCon, and prints one JSON object: sizes, milliseconds per
phase (best and median of --runs) and the peak resident memory of this
process. File reading is outside the timed phases, as on our side.
"""

import argparse
import contextlib
import io
import json
import resource
import statistics
import sys
import time


def load_faudes():
    # faudes prints warnings about optional plotting modules on import.
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        import faudes
    return faudes


def compose(faudes, gens):
    result = faudes.System(gens[0])
    for g in gens[1:]:
        nxt = faudes.System()
        faudes.Parallel(result, g, nxt)
        result = nxt
    return result


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plant", nargs="+", required=True)
    ap.add_argument("--spec", nargs="*", default=[])
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    faudes = load_faudes()
    plants = [faudes.System(p) for p in args.plant]
    specs = [faudes.System(s) for s in args.spec]
    timings = {"compose_plant": [], "compose_spec": [], "supcon": []}
    for _ in range(args.runs):
        t0 = time.perf_counter()
        plant = compose(faudes, plants)
        t1 = time.perf_counter()
        if specs:
            spec = compose(faudes, specs)
            faudes.InvProject(spec, plant.Alphabet())
        else:
            # No specification: everything the plant can do, marked.
            spec = faudes.System()
            spec.InjectAlphabet(plant.Alphabet())
            x = spec.InsInitState()
            spec.SetMarkedState(x)
            for ev in plant.Alphabet():
                spec.SetTransition(x, ev, x)
        t2 = time.perf_counter()
        sup = faudes.System()
        faudes.SupCon(plant, spec, sup)
        t3 = time.perf_counter()
        timings["compose_plant"].append((t1 - t0) * 1e3)
        timings["compose_spec"].append((t2 - t1) * 1e3)
        timings["supcon"].append((t3 - t2) * 1e3)
    totals = [a + b + c for a, b, c in zip(*timings.values())]
    print(json.dumps({
        "plant": [plant.Size(), plant.TransRelSize()],
        "supervisor": [sup.Size(), sup.TransRelSize()],
        "ms_median": {k: statistics.median(v) for k, v in timings.items()},
        "total_ms_median": statistics.median(totals),
        "total_ms_best": min(totals),
        "peak_rss_kib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
    }))


if __name__ == "__main__":
    sys.exit(main())
