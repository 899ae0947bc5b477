#!/usr/bin/env python3
"""libFAUDES's SupReduce on the benchmark models, for the comparison in
README.md (`codegen reduce`): python3 scripts/faudes_reduce.py SET…
with SET among smallfactory, transferline, agv, phil5, phil8. Prints, per set, the
supervisor's states, the reduced supervisor's states and transitions,
and SupReduce's wall time; with FAUDES_REDUCE_OUT=DIR, writes both
supervisors there as SET.sup.gen and SET.reduced.gen. The plant is the Parallel of the plant files,
the specification the Parallel of the spec files extended to the plant
alphabet (InvProject), the supervisor SupCon's, as `codegen synth` does;
a set without specifications (the philosophers) takes the plant's own
nonblocking supervisor, SupCon against every string of its alphabet.
"""

import os
import sys
import time

import faudes

BENCH = "models/bench/"
# Where the supervisor and SupReduce's result are written (`.gen`), for
# checking the closed loops with `codegen equal`; unset: not written.
OUT = os.environ.get("FAUDES_REDUCE_OUT")
SETS = {
    "smallfactory": ("MACH1 MACH2", "BUFSPEC BRSPEC"),
    "transferline": ("M1 M2 TU", "B1SP B2SP"),
    "agv": (
        "AGV1 AGV2 AGV3 AGV4 AGV5",
        "Z1SPEC Z2SPEC Z3SPEC Z4SPEC WS1SPEC WS2SPEC WS3SPEC IPSSPEC",
    ),
    "phil5": (" ".join(f"P{i} F{i}" for i in range(1, 6)), ""),
    "phil8": (" ".join(f"P{i} F{i}" for i in range(1, 9)), ""),
}


def parallel(set_name, names):
    parts = [faudes.System(f"{BENCH}{set_name}/{n}.gen") for n in names.split()]
    result = faudes.System(parts[0])
    for part in parts[1:]:
        product = faudes.System()
        faudes.Parallel(result, part, product)
        result = product
    return result


def main():
    for set_name in sys.argv[1:]:
        plants, specs = SETS[set_name]
        plant = parallel(set_name, plants)
        if specs:
            spec = parallel(set_name, specs)
            faudes.InvProject(spec, plant.Alphabet())
        else:
            spec = faudes.System()
            spec.InsState(1)
            spec.SetInitState(1)
            spec.SetMarkedState(1)
            spec.InsEvents(plant.Alphabet())
            for event in plant.Alphabet():
                spec.SetTransition(1, event, 1)
        sup = faudes.System()
        faudes.SupCon(plant, spec, sup)
        reduced = faudes.System()
        start = time.time()
        faudes.SupReduce(plant, sup, reduced)
        took = time.time() - start
        if len(sys.argv) > 1 and OUT:
            sup.Write(f"{OUT}/{set_name}.sup.gen")
            reduced.Write(f"{OUT}/{set_name}.reduced.gen")
        print(
            f"{set_name}: {sup.Size()} -> {reduced.Size()} states, "
            f"{reduced.TransRelSize()} transitions, {took:.3f} s",
            flush=True,
        )


if __name__ == "__main__":
    main()
