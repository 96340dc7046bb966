#!/usr/bin/env python3
"""Sweeps the knobs of the default numerics (docs/verification.md "Default numerics", "Knobs").

    /usr/bin/python3 scripts/verification/defaults_sweep.py [--build BUILD] [--only saltzman sedov ...]
                     [--q1 1.5 ...] [--q2 0.06 ...] [--merit 2 ...] [--sets Q1:Q2:MERIT ...]
                     [--extra KEY=VALUE ...]

Every combination of the tensor q's quadratic (q1) and linear (q2) coefficients and the merit
factor of the subzonal triangles runs through defaults_table.py's runner and metrics (every
check on, one thread, runs cached in BUILD/defaults/) and prints its markdown table; --sets
lists the combinations instead. The table of docs/verification.md "Default numerics" (the sweep):

    defaults_sweep.py --only saltzman sedov --sets 1.5:0.06:2 1.5:0.06:2.5 1.5:0.06:3 2:0.06:2.5 \
        2.5:0.06:2.5 3:0.06:2.5 2.5:0.06:3 3:0.06:3
"""
import argparse
import itertools
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import defaults_table as dt  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(dt.ROOT, "build"))
    ap.add_argument("--only", nargs="*", default=["saltzman", "sedov"])
    ap.add_argument("--q1", nargs="*", type=float, default=[1.5])
    ap.add_argument("--q2", nargs="*", type=float, default=[0.06])
    ap.add_argument("--merit", nargs="*", type=float, default=[2.0])
    ap.add_argument("--sets", nargs="*", default=None, help="Q1:Q2:MERIT combinations instead of the product")
    ap.add_argument("--viscosity", default="tensor")
    ap.add_argument("--extra", nargs="*", default=[], help="more --set overrides for every run")
    args = ap.parse_args()
    names = []
    combos = ([tuple(float(v) for v in c.split(":")) for c in args.sets] if args.sets else
              itertools.product(args.q1, args.q2, args.merit))
    for q1, q2, merit in combos:
        name = f"{args.viscosity} q1 {q1:g} q2 {q2:g} + triangles {merit:g}" + "".join(f", {e}" for e in args.extra)
        dt.OPTIONS[name] = dt.numerics(args.viscosity, "subzonal_triangles", merit,
                                       [f"numerics.q1={q1}", f"numerics.q2={q2}"] + args.extra)
        names.append(name)
    work = os.path.join(args.build, "defaults")
    results = {}
    for name in names:
        for problem in args.only:
            out, s = dt.run(args.build, work, problem, name, False)
            results[(name, problem)] = dt.metrics(problem, out, s)
            print(name, problem, {k: v for k, v in results[(name, problem)].items() if k != "summary"},
                  file=sys.stderr, flush=True)
    print(dt.table(results, names, args.only))


if __name__ == "__main__":
    main()
