#!/usr/bin/env python3
"""The copper Taylor anvil in rz (docs/solids.md §9): runs, the table and the figure.

    /usr/bin/python3 scripts/verification/taylor_anvil.py [--build BUILD] [--work DIR] [--rerun]
                     [--refine 0.5 1 2] [--figure docs/figures/solids_taylor_anvil.png]

Runs `stagger run apps/scenes/taylor_anvil.toml --set mesh.refine=R` (10 x 100 zones times R),
reads summary.json (status, time, cycles, audit and the `taylor_bar` diagnostics: the final
length and the impact-face width, which is the face's radius since the axis is x = 0) and the
last .vtu (the reader of taylor_bar.py), where it counts the crossing zones and the points
below the wall, measures the rod's radius 1 and 2 mm above the wall (on the side surface) and
the height and plastic strain of the first zone on the wall at the axis, and prints the
markdown table of
docs/solids.md §9. With --figure it draws the final profiles of every resolution and the
finest one's equivalent plastic strain (matplotlib, Agg).
"""
import argparse
import json
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from taylor_bar import crossing_zones, last_vtu, polygons, read_vtu  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENE = os.path.join(ROOT, "apps", "scenes", "taylor_anvil.toml")
L0, R0 = 32.4, 3.2  # mm


def run(build, work, refine, rerun):
    out = os.path.join(work, "refine_%g" % refine)
    summary = os.path.join(out, "summary.json")
    if rerun or not os.path.exists(summary):
        cmd = [os.path.join(build, "bin", "stagger"), "run", SCENE, "--out", out, "--quiet", "--threads", "1",
               "--set", "mesh.refine=%g" % refine]
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out, json.load(open(summary))


def first_vtu(out):
    pvd = [f for f in os.listdir(out) if f.endswith(".pvd")][0]
    return os.path.join(out, re.findall(r'file="([^"]+)"', open(os.path.join(out, pvd)).read())[0])


def outline(out, arrays):
    """The rod's side surface (r, z) in mm at the last dump: the points on r = R0 in the first
    dump, followed by their ids, sorted by z."""
    first = read_vtu(first_vtu(out))["Points"]
    ids = np.flatnonzero(np.abs(first[:, 0] - R0 * 1e-3) < 1e-12)
    side = arrays["Points"][ids, :2] * 1e3
    return side[np.argsort(side[:, 1])]


def first_row_at_axis(arrays):
    """Height (mm) and equivalent plastic strain of the zone on the wall at the axis: the zone
    whose vertices include the point nearest to (0, 0)."""
    pts = arrays["Points"][:, :2] * 1e3
    corner = int(np.argmin(pts[:, 0] ** 2 + pts[:, 1] ** 2))
    for z, ids in enumerate(polygons(arrays)):
        if corner in ids:
            return float(np.max(pts[ids, 1]) - np.min(pts[ids, 1])), float(arrays["plastic_strain"][z])
    return float("nan"), float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", default="/tmp/stagger_taylor_anvil")
    parser.add_argument("--refine", nargs="*", type=float, default=[0.5, 1, 2])
    parser.add_argument("--rerun", action="store_true")
    parser.add_argument("--figure")
    args = parser.parse_args()
    print("| mesh (r x z) | t reached (us) | status | cycles | final length (mm) | L / L0 | impact-face radius (mm) "
          "| R / R0 | radius at z = 1 / 2 mm (mm) | first row at the axis: height / initial, eps_p | max eps_p "
          "| crossing zones | points below the wall | audit |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    runs = []
    for refine in args.refine:
        out, s = run(args.build, args.work, refine, args.rerun)
        arrays = read_vtu(last_vtu(out))
        d = s["diagnostics"]
        below = int(np.sum(arrays["Points"][:, 1] < -1e-12))
        nr, nz = int(round(10 * refine)), int(round(100 * refine))
        side = outline(out, arrays)
        r1, r2 = np.interp([1.0, 2.0], side[:, 1], side[:, 0])
        height, eps_axis = first_row_at_axis(arrays)
        print("| %d x %d | %.1f | %s | %d | %.3f | %.4f | %.3f | %.3f | %.3f / %.3f | %.3f, %.2f | %.2f | %d | %d | %.1e |" % (
            nr, nz, s["time"] * 1e6, s["status"][:60], s["cycles"], d["final_length"] * 1e3,
            d["final_length"] * 1e3 / L0, d["impact_face_width"] * 1e3, d["impact_face_width"] * 1e3 / R0, r1, r2,
            height / (L0 / nz), eps_axis, d["max_plastic_strain"], crossing_zones(arrays), below,
            s["energy"]["relative_error"]))
        runs.append(("%d x %d" % (nr, nz), out, arrays, s))
    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PolyCollection
        fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(9, 7.5))
        for label, out, arrays, s in runs:
            side = outline(out, arrays)
            ax0.plot(side[:, 0], side[:, 1], "-", lw=1.2, label="%s: L = %.2f, R = %.2f mm" % (
                label, s["diagnostics"]["final_length"] * 1e3, s["diagnostics"]["impact_face_width"] * 1e3))
        ax0.plot([R0, R0], [0, L0], "k:", lw=0.8, label="initial rod")
        ax0.set_xlim(0, 8)
        ax0.set_ylim(0, 34)
        ax0.set_aspect("equal")
        ax0.set_xlabel("r (mm)")
        ax0.set_ylabel("z (mm)")
        ax0.set_title("free surface at 80 us")
        ax0.legend(fontsize=7, loc="center right")
        label, out, arrays, s = runs[-1]
        pts = arrays["Points"][:, :2] * 1e3
        pc = PolyCollection([pts[ids] for ids in polygons(arrays)], array=arrays["plastic_strain"], cmap="viridis",
                            edgecolors="k", linewidths=0.05)
        ax1.add_collection(pc)
        ax1.autoscale()
        ax1.set_aspect("equal")
        ax1.set_xlabel("r (mm)")
        ax1.set_title("%s, t = %.0f us" % (label, s["time"] * 1e6))
        fig.colorbar(pc, ax=ax1, label="equivalent plastic strain")
        fig.tight_layout()
        fig.savefig(args.figure, dpi=110)


if __name__ == "__main__":
    main()
