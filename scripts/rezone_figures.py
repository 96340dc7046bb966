#!/usr/bin/env python3
"""Before/after meshes of the ALE rezone for docs/ale.md ("Rezone").

Runs the figure test of test_ale (tests/ale/rezone_figure_test.cpp), which rezones a
vortex-distorted Cartesian mesh with a material interface and a perturbed gmsh mesh of the
blast box, and writes each mesh as CSV; plots them into docs/figures/ale_rezone_*.png.

    scripts/rezone_figures.py [--build build] [--out docs/figures]
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

KIND_COLOURS = {1: "tab:blue", 2: "tab:red"}  # slide, fixed (interior points are not marked)


def read_mesh(path):
    zones, regions, marks = {}, {}, {}
    with open(path) as f:
        for row in csv.DictReader(f):
            z = int(row["zone"])
            xy = (float(row["x"]), float(row["y"]))
            zones.setdefault(z, []).append(xy)
            regions[z] = int(row["region"])
            kind = int(row["kind"])
            if kind in KIND_COLOURS:
                marks[xy] = kind
    return [zones[z] for z in sorted(zones)], [regions[z] for z in sorted(zones)], marks


def draw(ax, path, title):
    polys, regions, marks = read_mesh(path)
    faces = ["#dde8f5" if r == 0 else "#f5eedd" for r in regions]
    ax.add_collection(PolyCollection(polys, facecolors=faces, edgecolors="k", linewidths=0.4))
    for kind, colour in KIND_COLOURS.items():
        pts = [xy for xy, k in marks.items() if k == kind]
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], ".", ms=2.5, color=colour)
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="docs/figures")
    args = parser.parse_args()
    test = os.path.join(args.build, "tests", "test_ale")
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, STAGGER_REZONE_FIGURE_DIR=tmp, OMP_NUM_THREADS="1")
        run = subprocess.run([test, "--gtest_filter=RezoneFigure.*"], env=env, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"rezone_figures: {test} failed:\n{run.stdout}{run.stderr}")
        print("".join(line + "\n" for line in run.stdout.splitlines() if "scaled Jacobian" in line), end="")
        os.makedirs(args.out, exist_ok=True)

        fig, axes = plt.subplots(1, 2, figsize=(8, 4))
        draw(axes[0], os.path.join(tmp, "rezone_vortex_before.csv"), "Lagrangian (vortex)")
        draw(axes[1], os.path.join(tmp, "rezone_vortex_after.csv"), "Winslow rezone (20 sweeps)")
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "ale_rezone_vortex.png"), dpi=130)

        fig, axes = plt.subplots(3, 1, figsize=(7, 10))
        draw(axes[0], os.path.join(tmp, "rezone_gmsh_winslow_before.csv"), "Lagrangian (perturbed gmsh mesh)")
        draw(axes[1], os.path.join(tmp, "rezone_gmsh_winslow_after.csv"), "winslow")
        draw(axes[2], os.path.join(tmp, "rezone_gmsh_reference_after.csv"), "reference_jacobian")
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "ale_rezone_gmsh.png"), dpi=130)
        print(f"wrote {args.out}/ale_rezone_vortex.png, {args.out}/ale_rezone_gmsh.png")


if __name__ == "__main__":
    main()
