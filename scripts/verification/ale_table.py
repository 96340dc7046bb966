#!/usr/bin/env python3
"""Measures the Lagrangian and ALE runs of docs/ale.md "Results" and prints its markdown table.

    python3 scripts/verification/ale_table.py [--build BUILD] [--work DIR] [--only NAME ...]
                                              [--timeout SECONDS]

Runs `stagger run SCENE --set ale.mode=MODE --set output.dumps=false --threads 1` for each
problem, Lagrangian and with the problem's ALE mode (defaults of the [ale] table unless the row
says otherwise), into a temporary directory (or WORK), and reads each summary.json: status,
cycles, errors.L1_density, diagnostics.shock_radius_error, energy.relative_error and
energy.ale_fixup. Each run gets a CPU limit
(--timeout, default 300 s); a run that hits it is reported as such.
"""
import argparse
import json
import os
import re
import resource
import signal
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "apps", "scenes")

# name -> (table label, scene, overrides for both runs, ALE mode, extra ALE overrides)
PROBLEMS = {
    "sod": ("Sod 400 x 5 (`sod.toml`, `mesh.refine=4`), eulerian", "sod", ["mesh.refine=4"], "eulerian", []),
    "sedov": ("Sedov 30 x 30 (`sedov.toml`)", "sedov", [], "ale", []),
    "noh50": ("Cartesian Noh 50 x 50 (`noh.toml`)", "noh", [], "ale", []),
    "noh100": ("Cartesian Noh 100 x 100 (`noh.toml`, `mesh.refine=2`)", "noh", ["mesh.refine=2"], "ale", []),
    "saltzman": ("Saltzman 100 x 10 (`saltzman.toml`)", "saltzman", [], "ale", []),
    "sedov_every": ("Sedov 30 x 30, `ale.remap_every=1`", "sedov", [], "ale", ["ale.remap_every=1"]),
    "saltzman_every": ("Saltzman, `ale.remap_every=1`", "saltzman", [], "ale", ["ale.remap_every=1"]),
    "blast_box": ("blast in a box 100 x 50 (`blast_box.toml`, `time.end=0.6`)", "blast_box", ["time.end=0.6"], "ale",
                  []),
    "blast_box_gmsh": ("blast in a box, gmsh mesh (`blast_box_gmsh.toml`, `time.end=0.6`)", "blast_box_gmsh",
                       ["time.end=0.6"], "ale", []),
    "blast_box_gmsh_every": ("blast in a box, gmsh mesh, `ale.remap_every=1`", "blast_box_gmsh", ["time.end=0.6"],
                             "ale", ["ale.remap_every=1"]),
    "blast_box_gmsh_regular": ("blast in a box, gmsh mesh, `ale.remap_every=1`, `ale.rezone=winslow_regular`",
                               "blast_box_gmsh", ["time.end=0.6"], "ale",
                               ["ale.remap_every=1", "ale.rezone=winslow_regular"]),
}


def run(build, work, name, mode, timeout):
    label, scene, common, ale_mode, ale_extra = PROBLEMS[name]
    out = os.path.join(work, name, mode)
    cmd = [os.path.join(build, "bin", "stagger"), "run", os.path.join(SCENES, scene + ".toml"), "--out", out,
           "--quiet", "--threads", "1"]
    sets = common + ["output.dumps=false", f"ale.mode={mode if mode == 'lagrangian' else ale_mode}"]
    if mode != "lagrangian":
        sets += ale_extra
    for s in sets:
        cmd += ["--set", s]

    def limit_cpu():
        resource.setrlimit(resource.RLIMIT_CPU, (timeout, timeout + 5))

    result = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=limit_cpu)
    if result.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        return "timeout"
    summary = os.path.join(out, "summary.json")
    return json.load(open(summary)) if os.path.exists(summary) else None


def cell(s, timeout):
    if s is None:
        return "failed (no summary.json)"
    if s == "timeout":
        return f"> {timeout} s CPU"
    parts = []
    if s["status"] != "completed":
        reached = re.search(r"t = ([0-9.eE+-]+)", s["status"])
        parts.append(f"stops at t = {float(reached.group(1)):.3g}" if reached else "stopped")
    else:
        parts.append("completes")
    l1 = s.get("errors", {}).get("L1_density")
    if l1 is not None:
        parts.append(f"L1 {l1:.3g}")
    shock = s.get("diagnostics", {}).get("shock_radius_error")
    if shock is not None:
        parts.append(f"shock radius {100 * shock:+.2f}%")
    parts.append(f"{s['cycles']} cycles")
    e = s.get("energy", {})
    if "relative_error" in e:
        parts.append(f"audit {e['relative_error']:.1e}")
    if e.get("ale_fixup"):
        parts.append(f"fix-up {e['ale_fixup']:.2g}")
    return ", ".join(parts)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--work", default=None, help="keep the runs here (default: a temporary directory)")
    ap.add_argument("--only", nargs="*", default=list(PROBLEMS), choices=list(PROBLEMS))
    ap.add_argument("--timeout", type=int, default=300, help="CPU seconds per run")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="ale_table_") as tmp:
        work = args.work or tmp
        lines = ["| problem | Lagrangian | ALE |", "|---|---|---|"]
        lagrangian = {}  # (scene, common overrides) -> cell: rows of one problem share the Lagrangian run
        for name in args.only:
            key = (PROBLEMS[name][1], tuple(PROBLEMS[name][2]))
            if key not in lagrangian:
                lagrangian[key] = cell(run(args.build, work, name, "lagrangian", args.timeout), args.timeout)
            lag = lagrangian[key]
            ale = cell(run(args.build, work, name, "ale", args.timeout), args.timeout)
            lines.append(f"| {PROBLEMS[name][0]} | {lag} | {ale} |")
            print(lines[-1], file=sys.stderr, flush=True)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
