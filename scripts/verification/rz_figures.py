#!/usr/bin/env python3
"""Runs the axisymmetric (rz) verification scenes noh_rz and sedov_rz with stagger-profile and plots them.

    python3 scripts/verification/rz_figures.py [--build BUILD] [--work DIR] [--rings N|AxN ...]
                                               [--sedov-rings [N ...]] [--rerun]

A Noh mesh is N rings of the scene's 25 angles, or AxN for A angles (the scheme keeps every ring
symmetric; the angles set the chords' fit to the circle, 10 give the plateau of 25 within 0.5 %).
A run whose output is already in --work is reused unless --rerun.

The exact values (exact_density) and the diagnostics (shock radius, plateau, asymmetry) come
from the project's C++ code (NohSolution and SedovSolution with nu = 3, noh_reference and
sedov_reference). The Sedov asymmetry is computed here: the largest relative spread of the
density over a ring of zones (the generator numbers the zones ring by ring). Writes
docs/figures/verif_noh_rz.png and docs/figures/verif_sedov_rz.png and prints one table row per
run (docs/verification.md, "Axisymmetric (rz) problems").
"""
import argparse
import csv
import json
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0] if k != "region"}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", default="/tmp/stagger_rz_figures")
    parser.add_argument("--rings", nargs="+", default=["50"])
    parser.add_argument("--sedov-rings", type=int, nargs="*", default=[60])
    parser.add_argument("--rerun", action="store_true")
    args = parser.parse_args()
    noh(args)
    if args.sedov_rings:  # none: keep the Sedov figure
        sedov(args)


def run_profile(args, scene_name, out, overrides, t):
    profile = os.path.join(args.build, "bin", "stagger-profile")
    scene = os.path.join(ROOT, "apps", "scenes", scene_name)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    command = [profile, scene, "--out", out, "--times", str(t)]
    for o in overrides:
        command += ["--set", o]
    if args.rerun or not os.path.exists(os.path.join(out, "summary.json")):
        subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    errors = {}
    with open(os.path.join(out, f"errors_{t}.csv")) as f:
        for row in csv.DictReader(f):
            errors[row["name"]] = float(row["value"])
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    # The largest audit over the recorded history (and the end).
    audit = abs(summary["energy"]["relative_error"])
    with open(os.path.join(out, "history.csv")) as f:
        for row in csv.DictReader(f):
            audit = max(audit, abs(float(row["relative_energy_error"])))
    summary["max_audit"] = audit
    return read_csv(os.path.join(out, f"zones_{t}.csv")), errors, summary


def sedov(args):
    angles = 20
    fig, axes = plt.subplots(1, len(args.sedov_rings), figsize=(6 * len(args.sedov_rings), 4.5), squeeze=False)
    print()
    print("| angles x rings | cycles | shock r (1) | error | peak density (6) | asymmetry | max audit |")
    print("|---|---|---|---|---|---|---|")
    for ax, rings in zip(axes[0], args.sedov_rings):
        out = os.path.join(args.work, f"sedov_rz_{rings}")
        z, errors, summary = run_profile(args, "sedov_rz.toml", out, [f"mesh.n_r={rings}"], 1)
        density = z["density"]
        spread = 0.0
        for first in range(0, len(density), angles):
            ring = density[first:first + angles]
            spread = max(spread, (max(ring) - min(ring)) / max(ring))
        print(f"| {angles} x {rings} | {summary['cycles']} | {errors['shock_radius']:.4f} | "
              f"{100 * errors['shock_radius_error']:+.2f} % | {errors['peak_density']:.3f} | {spread:.1e} | "
              f"{summary['max_audit']:.1e} |")
        order = sorted(range(len(z["r"])), key=lambda k: z["r"][k])
        ax.plot(z["r"], density, ".", ms=2, label="zones (all angles)")
        ax.plot([z["r"][k] for k in order], [z["exact_density"][k] for k in order], "k-", lw=1,
                label="exact (SedovSolution, nu = 3)")
        ax.set_xlim(0, 1.2)
        ax.set_xlabel("r = sqrt(x^2 + y^2)")
        ax.set_ylabel("density")
        ax.set_title(f"spherical Sedov in rz, {angles} angles x {rings} rings, t = 1")
        ax.legend()
    path = os.path.join(ROOT, "docs", "figures", "verif_sedov_rz.png")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print("wrote", path)


def noh(args):
    fig, axes = plt.subplots(1, len(args.rings), figsize=(6 * len(args.rings), 4.5), squeeze=False)
    print("| angles x rings | cycles | plateau (64) | shock r (0.2) | asymmetry | max audit |")
    print("|---|---|---|---|---|---|")
    for ax, mesh in zip(axes[0], args.rings):
        angles, rings = (int(v) for v in mesh.split("x")) if "x" in mesh else (25, int(mesh))
        name = f"noh_rz_{rings}" if angles == 25 else f"noh_rz_{angles}x{rings}"
        out = os.path.join(args.work, name)
        z, errors, summary = run_profile(args, "noh_rz.toml", out, [f"mesh.n_r={rings}", f"mesh.n_theta={angles}"], 0.6)
        print(f"| {angles} x {rings} | {summary['cycles']} | {errors.get('plateau_density', float('nan')):.4g} | "
              f"{errors.get('shock_radius', float('nan')):.4g} | {errors.get('asymmetry', float('nan')):.2g} | "
              f"{summary['max_audit']:.1e} |")
        order = sorted(range(len(z["r"])), key=lambda k: z["r"][k])
        ax.plot(z["r"], z["density"], ".", ms=2, label="zones (all angles)")
        ax.plot([z["r"][k] for k in order], [z["exact_density"][k] for k in order], "k-", lw=1,
                label="exact (NohSolution, nu = 3)")
        ax.set_xlim(0, 0.6)
        ax.set_xlabel("r = sqrt(x^2 + y^2)")
        ax.set_ylabel("density")
        ax.set_title(f"spherical Noh in rz, {angles} angles x {rings} rings, t = 0.6")
        ax.legend()
    path = os.path.join(ROOT, "docs", "figures", "verif_noh_rz.png")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print("wrote", path)


if __name__ == "__main__":
    main()
