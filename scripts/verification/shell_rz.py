#!/usr/bin/env python3
"""Verney's spherical beryllium shell in rz (docs/verification.md, "Axisymmetric (rz) problems"):
runs, the table and the figure.

    /usr/bin/python3 scripts/verification/shell_rz.py [--build BUILD] [--work DIR] [--rerun]
                     [--refine 1 2] [--figure docs/figures/verif_shell_rz.png]

Runs `stagger-profile apps/scenes/shell_rz.toml --set mesh.refine=R` (20 x 16 zones times R,
angle x radius) with frames every 5 us; the `be_shell` reference of an rz scene is the spherical
exact solution (`HowellBallShell` with `spherical`, docs/derivations.md section 2.1), whose
radii and kinetic energy stagger-profile writes to exact_shell.csv. Prints the markdown table
(final radii against the stopping radii, asymmetry, audit) and draws the radii against time and
the kinetic energy against the exact one (matplotlib, Agg).
"""
import argparse
import csv
import json
import os
import subprocess

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENE = os.path.join(ROOT, "apps", "scenes", "shell_rz.toml")
TIMES = [5e-6 * k for k in range(1, 21)]  # to the scene's end, 100 us


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]} if rows else {}


def diagnostics(out, t):
    values = {}
    with open(os.path.join(out, "errors_%.6g.csv" % t)) as f:
        for row in csv.DictReader(f):
            values[row["name"]] = float(row["value"])
    return values


def run(build, work, refine, rerun):
    out = os.path.join(work, "refine_%g" % refine)
    if rerun or not os.path.exists(os.path.join(out, "summary.json")):
        cmd = [os.path.join(build, "bin", "stagger-profile"), SCENE, "--out", out, "--set", "mesh.refine=%g" % refine,
               "--times", ",".join(repr(t) for t in TIMES), "--history-every", "10"]
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    return out, json.load(open(os.path.join(out, "summary.json")))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", default="/tmp/stagger_shell_rz")
    parser.add_argument("--refine", nargs="*", type=float, default=[1, 2])
    parser.add_argument("--rerun", action="store_true")
    parser.add_argument("--figure")
    args = parser.parse_args()
    print("| mesh | cycles | r_in (mm) | r_out (mm) | r_in - exact (mm) | r_out - exact (mm) | asymmetry "
          "| kinetic energy left | max audit | loop s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    runs = []
    for refine in args.refine:
        out, s = run(args.build, args.work, refine, args.rerun)
        d = diagnostics(out, TIMES[-1])
        h = read_csv(os.path.join(out, "history.csv"))
        label = "%dx%d" % (round(20 * refine), round(16 * refine))
        print("| %s | %d | %.4f | %.4f | %+.4f | %+.4f | %.1e | %.1e | %.1e | %.1f |" % (
            label, s["cycles"], d["inner_radius"] * 1e3, d["outer_radius"] * 1e3,
            (d["inner_radius"] - d["inner_stopping_radius_exact"]) * 1e3,
            (d["outer_radius"] - d["outer_stopping_radius_exact"]) * 1e3, d["asymmetry"],
            d["kinetic_energy"] / h["kinetic"][0], np.max(np.abs(h["relative_energy_error"])), s["loop_seconds"]))
        runs.append((label, out, h))
    d = diagnostics(runs[-1][1], TIMES[-1])
    print("\nExact (incompressible, rigid-plastic) stopping radii %.4f / %.4f mm at %.2f us." % (
        d["inner_stopping_radius_exact"] * 1e3, d["outer_stopping_radius_exact"] * 1e3, d["stopping_time_exact"] * 1e6))
    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        exact = read_csv(os.path.join(runs[-1][1], "exact_shell.csv"))
        for (label, out, h), style in zip(runs, ("C2o", "C1s", "C0^")):
            t = np.array(TIMES)
            ri = np.array([diagnostics(out, x)["inner_radius"] for x in TIMES])
            ro = np.array([diagnostics(out, x)["outer_radius"] for x in TIMES])
            axes[0].plot(t * 1e6, ri * 1e3, style, mfc="none", label="inner, %s" % label)
            axes[0].plot(t * 1e6, ro * 1e3, style, label="outer, %s" % label)
        axes[0].plot(exact["time"] * 1e6, exact["inner_radius"] * 1e3, "k-", lw=0.8,
                     label="incompressible rigid-plastic (Verney)")
        axes[0].plot(exact["time"] * 1e6, exact["outer_radius"] * 1e3, "k-", lw=0.8)
        axes[0].set_xlabel("t (us)")
        axes[0].set_ylabel("radius (mm)")
        axes[0].legend(fontsize=7)
        axes[0].set_title("Spherical Be shell (rz): inner and outer radii")
        label, out, h = runs[-1]
        axes[1].plot(h["time"] * 1e6, h["kinetic"] / 1e3, label="kinetic")
        axes[1].plot(h["time"] * 1e6, (h["internal"] - h["internal"][0]) / 1e3, label="internal - internal(0)")
        axes[1].plot(h["time"] * 1e6, h["total"] / 1e3, label="total")
        scale = h["kinetic"][0] / exact["kinetic_energy"][0]
        axes[1].plot(exact["time"] * 1e6, exact["kinetic_energy"] * scale / 1e3, "k--", lw=0.8,
                     label="exact kinetic (scaled to the mesh)")
        axes[1].set_xlabel("t (us)")
        axes[1].set_ylabel("energy per radian (kJ)")
        axes[1].legend(fontsize=8)
        axes[1].set_title("%s: kinetic energy becomes plastic heat" % label)
        fig.tight_layout()
        fig.savefig(args.figure, dpi=110)


if __name__ == "__main__":
    main()
