#!/usr/bin/env python3
"""The copper Taylor anvil in rz (docs/solids.md §9): runs, the tables and the figure.

    /usr/bin/python3 scripts/verification/taylor_anvil.py [--build BUILD] [--work DIR] [--rerun]
                     [--refine 0.5 1 2] [--end T] [--set KEY=VALUE ...]
                     [--history] [--figure docs/figures/solids_taylor_anvil.png]

Runs `stagger run apps/scenes/taylor_anvil.toml --set mesh.refine=R` (10 x 100 zones times R;
--end sets time.end, --set adds any other override, e.g. numerics.hourglass_coefficient=0),
reads summary.json (status, time, cycles, audit and the `taylor_bar` diagnostics) and the
.vtu dumps (the reader of taylor_bar.py), and prints the markdown table of docs/solids.md §9:
the final length (top of the rod above the wall), the impact-face radius (the largest r of the
points on the wall), the largest radius of the rod (the largest r of all points: the "mushroom
radius" of the benchmark's reports), the side surface's radius 1 and 2 mm above the wall, the
height and plastic strain of the first zone on the wall at the axis, the largest equivalent
plastic strain, the crossing zones, the points below the wall and the audit. The length and
the face radius are compared with the reference below at the run's end time (a multiple of
10 us). --history prints the face radius and the length at every dump (every 10 us) of every
run next to the reference. With --figure it draws the final profiles of every resolution, the
face radius against time with the reference, and the finest run's plastic strain
(matplotlib, Agg).

Reference: the composite tetrahedron of Foulk et al. (2021) in Sierra/SM at h = 0.19 mm
(1.5 million elements), the same rod, wall and J2 material with linear hardening (no EOS: the
bulk modulus of E and nu), as recorded in the public repository Cthonios/Carina.jl, file
benchmark/tet15-p1/taylor/data/sierra-ct-h0.19-history.tsv (radius of the impact face = the
largest distance of its nodes from the axis, and length, every 1 us); the values at the
multiples of 10 us (to 0.01 us) are copied below, in mm.
"""
import argparse
import json
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from taylor_bar import crossing_zones, polygons, read_vtu  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENE = os.path.join(ROOT, "apps", "scenes", "taylor_anvil.toml")
L0, R0 = 32.4, 3.2  # mm
# t (us): (face radius, length) in mm, Sierra/SM composite tetrahedron, h = 0.19 mm (see above).
REFERENCE = {0: (3.2000, 32.4000), 10: (5.2325, 30.1393), 20: (6.2051, 28.0654), 30: (6.8200, 26.1889),
             40: (7.1467, 24.5618), 50: (7.2370, 23.2213), 60: (7.2341, 22.2129), 70: (7.2338, 21.5926),
             80: (7.2326, 21.4304)}


def run(args, refine):
    tag = "_".join(re.sub(r"[^A-Za-z0-9.]+", "-", s) for s in args.set) or "scene"
    out = os.path.join(args.work, "%s_end%g" % (tag, args.end * 1e6 if args.end else 80), "refine_%g" % refine)
    summary = os.path.join(out, "summary.json")
    if args.no_run and not os.path.exists(summary):
        return out, None  # not finished (or not run): its dumps so far, if any, for --history
    if args.rerun or not os.path.exists(summary):
        cmd = [os.path.join(args.build, "bin", "stagger"), "run", SCENE, "--out", out, "--quiet", "--threads", "1",
               "--set", "mesh.refine=%g" % refine]
        if args.end:
            cmd += ["--set", "time.end=%g" % args.end]
        for s in args.set:
            cmd += ["--set", s]
        subprocess.run(["nice", "-n", "10"] + cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out, json.load(open(summary))


def dumps(out):
    """(time in us, .vtu path) of every dump of a run, in order."""
    pvd = [f for f in os.listdir(out) if f.endswith(".pvd")][0]
    text = open(os.path.join(out, pvd)).read()
    return [(float(t) * 1e6, os.path.join(out, f)) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)]


def face_and_length(arrays):
    """Impact-face radius (largest r of the points on the wall y = 0) and length, mm."""
    pts = arrays["Points"][:, :2] * 1e3
    return float(np.max(pts[np.abs(pts[:, 1]) < 1e-9, 0])), float(np.max(pts[:, 1]))


def outline(first, arrays):
    """The rod's side surface (r, z) in mm: the points on r = R0 in the first dump, by z."""
    ids = np.flatnonzero(np.abs(first["Points"][:, 0] - R0 * 1e-3) < 1e-12)
    side = arrays["Points"][ids, :2] * 1e3
    return side[np.argsort(side[:, 1])]


def first_row_at_axis(first, arrays):
    """Height (over its initial height) and equivalent plastic strain of the zone on the wall at
    the axis: the zone with the point at (0, 0)."""
    corner = int(np.argmin(np.sum(first["Points"][:, :2] ** 2, axis=1)))
    for z, (ids0, ids) in enumerate(zip(polygons(first), polygons(arrays))):
        if corner in ids:
            h0 = np.ptp(first["Points"][ids0, 1])
            return float(np.ptp(arrays["Points"][ids, 1]) / h0), float(arrays["plastic_strain"][z])
    return float("nan"), float("nan")


def percent(value, ref):
    return "%+.1f %%" % (100 * (value / ref - 1))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", default="/tmp/stagger_taylor_anvil")
    parser.add_argument("--refine", nargs="*", type=float, default=[0.5, 1, 2])
    parser.add_argument("--end", type=float, help="time.end (s), a multiple of 10 us; default the scene's 80 us")
    parser.add_argument("--set", action="append", default=[], help="another KEY=VALUE override")
    parser.add_argument("--rerun", action="store_true")
    parser.add_argument("--no-run", action="store_true",
                        help="start no run: a run without summary.json enters --history with the dumps it has written")
    parser.add_argument("--history", action="store_true")
    parser.add_argument("--figure")
    args = parser.parse_args()
    runs = []
    for refine in args.refine:
        out, s = run(args, refine)
        if s is None and not os.path.isdir(out):
            continue
        series = dumps(out)
        first, last = read_vtu(series[0][1]), read_vtu(series[-1][1])
        runs.append(dict(label="%d x %d" % (round(10 * refine), round(100 * refine)), out=out, s=s, first=first,
                         last=last, series=series))
    t_end = args.end * 1e6 if args.end else 80.0
    ref = REFERENCE.get(int(round(t_end)))
    print("| mesh (r x z) | t (us) | status | cycles | length (mm) | vs reference | face radius (mm) | vs reference "
          "| largest radius (mm) | radius at z = 1 / 2 mm | first zone at the axis: height / initial, eps_p "
          "| max eps_p | crossing zones | points below the wall | audit |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        s, arrays = r["s"], r["last"]
        if s is None:
            print("| %s | %.1f | not finished | | | | | | | | | | | | |" % (r["label"], r["series"][-1][0]))
            continue
        face, length = face_and_length(arrays)
        side = outline(r["first"], arrays)
        r1, r2 = np.interp([1.0, 2.0], side[:, 1], side[:, 0])
        height, eps_axis = first_row_at_axis(r["first"], arrays)
        largest = float(np.max(arrays["Points"][:, 0]) * 1e3)
        below = int(np.sum(arrays["Points"][:, 1] < -1e-12))
        print("| %s | %.1f | %s | %d | %.3f | %s | %.3f | %s | %.3f | %.3f / %.3f | %.3f, %.2f | %.2f | %d | %d | %.1e |" % (
            r["label"], s["time"] * 1e6, s["status"][:60], s["cycles"], length,
            percent(length, ref[1]) if ref else "-", face, percent(face, ref[0]) if ref else "-", largest, r1, r2,
            height, eps_axis, s["diagnostics"]["max_plastic_strain"], crossing_zones(arrays), below,
            s["energy"]["relative_error"]))
    if ref:
        print("| reference (Sierra/SM composite tet, h = 0.19 mm) | %.0f | | | %.3f | | %.3f | | | | | | | | |" % (
            t_end, ref[1], ref[0]))
    if args.history:
        times = [int(round(t)) for t, _ in max((r["series"] for r in runs), key=len)]
        print()
        print("| t (us) | " + " | ".join("%s: face radius, length (mm)" % r["label"] for r in runs) +
              " | reference: face radius, length (mm) |")
        print("|---" * (len(runs) + 2) + "|")
        for i, t in enumerate(times):
            cells = []
            for r in runs:
                if i < len(r["series"]):
                    face, length = face_and_length(read_vtu(r["series"][i][1]))
                    cells.append("%.3f, %.3f" % (face, length))
                else:
                    cells.append("-")
            refc = "%.3f, %.3f" % REFERENCE[t] if t in REFERENCE else "-"
            print("| %d | %s | %s |" % (t, " | ".join(cells), refc))
    if args.figure:
        figure([r for r in runs if r["s"] is not None], args.figure)


def figure(runs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(13, 7), gridspec_kw=dict(width_ratios=[1.0, 1.2, 1.0]))
    for r in runs:
        side = outline(r["first"], r["last"])
        face, length = face_and_length(r["last"])
        ax0.plot(side[:, 0], side[:, 1], "-", lw=1.2, label="%s: L = %.2f, R = %.2f mm" % (r["label"], length, face))
        hist = np.array([(t,) + face_and_length(read_vtu(f)) for t, f in r["series"]])
        ax1.plot(hist[:, 0], hist[:, 1], "o-", ms=3, lw=1.2, label=r["label"])
    ax0.plot([R0, R0], [0, L0], "k:", lw=0.8, label="initial rod")
    ref = np.array([(t,) + v for t, v in sorted(REFERENCE.items())])
    ax0.plot([ref[-1, 1]], [0], "k*", ms=9, label="reference face radius")
    ax0.axhline(ref[-1, 2], color="k", lw=0.6, ls="--", label="reference length")
    ax0.set_xlim(0, 8)
    ax0.set_ylim(0, 34)
    ax0.set_aspect("equal")
    ax0.set_xlabel("r (mm)")
    ax0.set_ylabel("z (mm)")
    ax0.set_title("free surface at %.0f us" % (runs[0]["s"]["time"] * 1e6))
    ax0.legend(fontsize=6, loc="upper right")
    ax1.plot(ref[:, 0], ref[:, 1], "k*--", ms=7, lw=0.8, label="reference (Sierra/SM, h = 0.19 mm)")
    ax1.set_xlabel("t (us)")
    ax1.set_ylabel("impact-face radius (mm)")
    ax1.set_title("face radius against time")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7, loc="lower right")
    r = runs[-1]
    pts = r["last"]["Points"][:, :2] * 1e3
    pc = PolyCollection([pts[ids] for ids in polygons(r["last"])], array=r["last"]["plastic_strain"], cmap="viridis",
                        edgecolors="k", linewidths=0.05)
    ax2.add_collection(pc)
    ax2.set_xlim(0, 8)
    ax2.set_ylim(0, 12)
    ax2.set_aspect("equal")
    ax2.set_xlabel("r (mm)")
    ax2.set_title("%s, t = %.0f us (foot)" % (r["label"], r["s"]["time"] * 1e6))
    fig.colorbar(pc, ax=ax2, label="equivalent plastic strain", shrink=0.6)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
