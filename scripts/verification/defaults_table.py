#!/usr/bin/env python3
"""Measures candidate default numerics (docs/verification.md "Default numerics").

    /usr/bin/python3 scripts/verification/defaults_table.py [--build BUILD] [--work DIR]
                     [--only sod noh noh_polar sedov saltzman piston be_shell] [--options NAME ...]
                     [--rerun] [--markdown]

Runs `stagger run` on the shipped scenes with --set overrides for each option set (on top of
the scene's own keys: every numerics key an option set names is set, so the scene's own choice
of viscosity and hourglass control is replaced), with every check on
(numerics.check_corner_areas = true), reads summary.json and the last .vtu of each run (the
reader of subzonal_table.py) and prints one markdown table: rows = option sets, columns = the
metrics of the targets in docs/verification.md "Default numerics":
  Sod 400x5:         L1(rho).
  Noh Cartesian 100x100 (t = 0.6): axis jet = worst |rho - 16|/16 over the zones touching an
                     axis with 0.05 < r < 0.15; plateau as the reference reports it.
  Noh polar 25x50:   plateau and asymmetry as the reference reports them.
  Sedov 120x120:     density scatter at fixed radius, peak-density radius spread (relative to
                     the shock radius 1), shock radius error (docs/verification.md section 12).
  Saltzman (t = 0.6): worst row = max over the 10 rows of |mean rho - 4| / 4 over the row's zones
                     with 0.65 < x < 0.77 (docs/verification.md section 12).
  piston, Be shell:  the scene references' errors (shock/plateau, shell radii).
  audit:             the largest |energy audit| over the runs of the row.
Runs are cached in WORK (default build/defaults/); --rerun repeats them.
"""
import argparse
import json
import math
import os
import re
import resource
import signal
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from subzonal_table import last_vtu, noh_jet, read_vtu, sedov_metrics, zones  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "apps", "scenes")


def numerics(viscosity, hourglass, coefficient, extra=()):
    return [f"numerics.viscosity={viscosity}", f"numerics.hourglass={hourglass}",
            f"numerics.hourglass_coefficient={coefficient}"] + list(extra)


# Option sets: name -> --set overrides. Each row pins its quadratic q1 (the default 1.5, or the
# 2.5 of the last row), so the rows stay what they were measured with if the default moves.
OLD_Q1 = ["numerics.q1=1.5"]
OPTIONS = {
    "bulk q + gamma 0.1 (old default)": numerics("bulk", "gamma", 0.1, OLD_Q1),
    "bulk q + triangles 2": numerics("bulk", "subzonal_triangles", 2, OLD_Q1),
    "edge q + gamma 0.1": numerics("edge", "gamma", 0.1, OLD_Q1),
    "edge q + triangles 2": numerics("edge", "subzonal_triangles", 2, OLD_Q1),
    "tensor q + gamma 0.1": numerics("tensor", "gamma", 0.1, OLD_Q1),
    "tensor q + triangles 1": numerics("tensor", "subzonal_triangles", 1, OLD_Q1),
    "tensor q + triangles 2 (default)": numerics("tensor", "subzonal_triangles", 2, OLD_Q1),
    "tensor q + triangles 2.5": numerics("tensor", "subzonal_triangles", 2.5, OLD_Q1),
    "tensor q, q1 2.5 + triangles 3": numerics("tensor", "subzonal_triangles", 3, ["numerics.q1=2.5"]),
}

CHECKS = ["numerics.check_corner_areas=true"]
# A run needing more CPU time than this (seconds, one thread) is stopped and reported as such: the
# bulk q on the polar Noh takes 236 000 cycles (docs/verification.md section 2).
TIMEOUT = 300


def limit_cpu():
    resource.setrlimit(resource.RLIMIT_CPU, (TIMEOUT, TIMEOUT + 5))
# problem -> (scene, extra overrides)
PROBLEMS = {
    "sod": ("sod", ["mesh.refine=4", "output.dump_interval=0"]),
    "noh": ("noh", ["mesh.nx=100", "mesh.ny=100", "output.dump_interval=0"]),
    "noh_polar": ("noh_polar", ["output.dump_interval=0"]),
    "sedov": ("sedov", ["mesh.nx=120", "mesh.ny=120", "output.dump_interval=0"]),
    "saltzman": ("saltzman", ["output.dump_interval=0"]),
    "piston": ("piston", ["output.dump_interval=0"]),
    "be_shell": ("be_shell", ["output.dump_interval=0"]),
}


def slug(text):
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


def run(build, work, problem, option, rerun):
    scene, extra = PROBLEMS[problem]
    out = os.path.join(work, problem, slug(option))
    summary = os.path.join(out, "summary.json")
    timeout = os.path.join(out, "timeout.txt")
    if rerun or not (os.path.exists(summary) or os.path.exists(timeout)):
        if os.path.exists(timeout):
            os.remove(timeout)
        cmd = [os.path.join(build, "bin", "stagger"), "run", os.path.join(SCENES, scene + ".toml"), "--out", out,
               "--quiet", "--threads", "1"]
        for s in extra + CHECKS + OPTIONS[option]:
            cmd += ["--set", s]
        result = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=limit_cpu)
        if result.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
            os.makedirs(out, exist_ok=True)
            with open(timeout, "w") as f:
                f.write(f"{TIMEOUT}\n")
    if os.path.exists(timeout):
        return out, "timeout"
    if not os.path.exists(summary):
        return out, None
    return out, json.load(open(summary))


def status_of(s):
    if s is None:
        return "failed"
    if s == "timeout":
        return f"> {TIMEOUT} s CPU"
    if s["status"] == "completed":
        return "ok"
    reached = re.search(r"t = ([0-9.eE+-]+)", s["status"])
    return f"stopped t={float(reached.group(1)):.3g}" if reached else "stopped"


def saltzman_rows(arrays):
    cx, _, _, _, _ = zones(arrays)
    rho = arrays["density"]
    row = np.arange(len(rho)) // 100  # the generator numbers the zones row by row, 100 per row
    worst = 0.0
    for k in range(10):
        sel = (row == k) & (cx > 0.65) & (cx < 0.77)
        if np.any(sel):
            worst = max(worst, abs(float(np.mean(rho[sel])) / 4 - 1))
    return worst


def metrics(problem, out, s):
    """A dict of formatted metrics of one run (or '-' when it did not complete)."""
    if s is None or s == "timeout" or s["status"] != "completed":
        return {"status": status_of(s)}
    d = s.get("diagnostics", {})
    e = s.get("errors", {})
    m = {"status": "ok", "audit": abs(s["energy"]["relative_error"]), "cycles": s["cycles"]}
    if problem == "sod":
        m["L1"] = e.get("L1_density", math.nan)
    elif problem == "noh":
        m["jet"] = noh_jet(read_vtu(last_vtu(out)))
        m["plateau"] = d.get("plateau_density", math.nan)
    elif problem == "noh_polar":
        m["plateau"] = d.get("plateau_density", math.nan)
        m["asym"] = d.get("asymmetry", math.nan)
    elif problem == "sedov":
        m["scatter"], m["spread"] = sedov_metrics(read_vtu(last_vtu(out)))
        m["shock"] = d.get("shock_radius_error", math.nan)
    elif problem == "saltzman":
        m["rows"] = saltzman_rows(read_vtu(last_vtu(out)))
    m["summary"] = s
    return m


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--work", default=None)
    ap.add_argument("--only", nargs="*", default=list(PROBLEMS))
    ap.add_argument("--options", nargs="*", default=list(OPTIONS))
    ap.add_argument("--rerun", action="store_true")
    ap.add_argument("--dump", action="store_true", help="print each run's diagnostics and errors")
    args = ap.parse_args()
    work = args.work or os.path.join(args.build, "defaults")
    results = {}
    for option in args.options:
        for problem in args.only:
            out, s = run(args.build, work, problem, option, args.rerun)
            results[(option, problem)] = metrics(problem, out, s)
            if args.dump and isinstance(s, dict):
                print(option, problem, json.dumps({k: s.get(k) for k in ("status", "cycles", "diagnostics", "errors")}),
                      file=sys.stderr)
    print(table(results, args.options, args.only))


def fmt(m, key, spec):
    if m.get("status") != "ok":
        return m.get("status", "-")
    v = m.get(key, math.nan)
    return format(v, spec)


def table(results, options, problems):
    cols = []
    if "sod" in problems:
        cols.append(("Sod L1(rho) (<= 1.5e-3)", lambda o: fmt(results[(o, "sod")], "L1", ".3e")))
    if "noh" in problems:
        cols.append(("Noh 100x100 axis jet (<= 0.15)", lambda o: fmt(results[(o, "noh")], "jet", ".3f")))
        cols.append(("Noh 100x100 plateau", lambda o: fmt(results[(o, "noh")], "plateau", ".2f")))
    if "noh_polar" in problems:
        cols.append(("Noh polar plateau (>= 15)", lambda o: fmt(results[(o, "noh_polar")], "plateau", ".3f")))
        cols.append(("Noh polar asymmetry (<= 1e-12)", lambda o: fmt(results[(o, "noh_polar")], "asym", ".1e")))
    if "sedov" in problems:
        cols.append(("Sedov scatter (<= 0.05)", lambda o: fmt(results[(o, "sedov")], "scatter", ".3f")))
        cols.append(("Sedov peak spread (<= 0.0075)", lambda o: fmt(results[(o, "sedov")], "spread", ".4f")))
        cols.append(("Sedov shock error (<= 0.5 %)",
                     lambda o: fmt({**results[(o, "sedov")], "shock": 100 * results[(o, "sedov")].get("shock", 0)},
                                   "shock", "+.2f") + (" %" if results[(o, "sedov")].get("status") == "ok" else "")))
    if "saltzman" in problems:
        cols.append(("Saltzman worst row (<= 0.05)", lambda o: fmt(results[(o, "saltzman")], "rows", ".3f")))
    if "piston" in problems:
        cols.append(("piston", lambda o: piston_cell(results[(o, "piston")])))
    if "be_shell" in problems:
        cols.append(("Be shell r_in / r_out (mm)", lambda o: shell_cell(results[(o, "be_shell")])))

    def audit(o):
        a = [results[(o, p)]["audit"] for p in problems if "audit" in results[(o, p)]]
        return f"{max(a):.1e}" if a else "-"

    cols.append(("max audit", audit))
    lines = ["| options | " + " | ".join(c[0] for c in cols) + " |", "|---" * (len(cols) + 1) + "|"]
    for o in options:
        lines.append(f"| {o} | " + " | ".join(c[1](o) for c in cols) + " |")
    return "\n".join(lines)


def piston_cell(m):
    if m.get("status") != "ok":
        return m.get("status", "-")
    e = m["summary"].get("errors", {})
    d = m["summary"].get("diagnostics", {})
    v = e.get("L1_pressure", d.get("shock_position_error", math.nan))
    return f"L1(p) {v:.3g}"


def shell_cell(m):
    if m.get("status") != "ok":
        return m.get("status", "-")
    d = m["summary"].get("diagnostics", {})
    return f'{1e3 * d.get("inner_radius", math.nan):.3f} / {1e3 * d.get("outer_radius", math.nan):.3f}'


if __name__ == "__main__":
    main()
