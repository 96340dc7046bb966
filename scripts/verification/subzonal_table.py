#!/usr/bin/env python3
"""Measures the subzonal pressures (docs/algorithm.md §18) against the other options.

    /usr/bin/python3 scripts/verification/subzonal_table.py [--build BUILD] [--work DIR]
                     [--only blast|blast_gmsh|sedov|sedov_checked|sod|noh_polar|noh] [--rerun]

Runs `stagger run` on apps/scenes/{blast_box,blast_box_gmsh,sedov,sod,noh_polar,noh}.toml with --set
overrides for each option set, reads the last .vtu of each run (its own small reader: raw
appended, zlib-compressed, 64-bit headers, docs/output.md) and prints the tables of
docs/verification.md "Subzonal pressures" (markdown). Metrics (zone centroid = area centroid):
  blast, blast_gmsh: status (t reached), cycles, crossing zones in the last dump, energy audit.
  Sedov (the scene's check_corner_areas = false; sedov_checked: true): density scatter at fixed radius (0.6 < r < 0.9, 30 radial bins, mean of std/mean) and
         peak-density radius spread (r > 0.5, 18 angular bins over [0, pi/2], max - min of the
         r of each bin's densest zone); shock radius error and L1(rho) from summary.json.
  Sod:   L1(rho) from summary.json.
  Noh polar: plateau and asymmetry as the scene's reference reports them (summary.json).
  Noh Cartesian: axis jet (zones touching x = 0 or y = 0 with 0.05 < r < 0.15: worst
         |rho - 16| / 16).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import zlib

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "apps", "scenes")

# Option sets: name -> --set overrides (on top of the scene's own numerics).
BULK = ["numerics.viscosity=bulk"]
EDGE = ["numerics.viscosity=edge"]


def subzonal(alpha):
    return ["numerics.hourglass=subzonal", f"numerics.hourglass_coefficient={alpha}"]


def triangles(alpha):
    return ["numerics.hourglass=subzonal_triangles", f"numerics.hourglass_coefficient={alpha}"]


OPTIONS = {
    "bulk q, no hourglass control": BULK + ["numerics.hourglass_coefficient=0"],
    "bulk q + gamma 0.1 (default)": BULK + ["numerics.hourglass=gamma", "numerics.hourglass_coefficient=0.1"],
    "edge q + gamma 0.1": EDGE + ["numerics.hourglass=gamma", "numerics.hourglass_coefficient=0.1"],
    "bulk q + FB 1": BULK + ["numerics.hourglass=flanagan_belytschko", "numerics.hourglass_coefficient=1"],
    "bulk q + subzonal 0.25": BULK + subzonal(0.25),
    "bulk q + subzonal 0.5": BULK + subzonal(0.5),
    "bulk q + subzonal 1": BULK + subzonal(1),
    "bulk q + subzonal 2": BULK + subzonal(2),
    "bulk q + triangles 0.5": BULK + triangles(0.5),
    "bulk q + triangles 1": BULK + triangles(1),
    "bulk q + triangles 2": BULK + triangles(2),
    "edge q + subzonal 0.5": EDGE + subzonal(0.5),
    "edge q + subzonal 1": EDGE + subzonal(1),
    "edge q + triangles 1": EDGE + triangles(1),
    "edge q + triangles 2": EDGE + triangles(2),
}

# The Noh scenes run only with the edge viscosity (their own): with the bulk q the polar Noh takes
# 400 000 cycles (5 minutes) and gives a plateau of 14.1 (docs/verification.md section 2).
EDGE_ONLY = ["edge q + gamma 0.1", "edge q + subzonal 0.5", "edge q + subzonal 1", "edge q + triangles 1",
             "edge q + triangles 2"]
ONLY = {"noh_polar": EDGE_ONLY, "noh": EDGE_ONLY}

# problem -> (scene, extra overrides)
PROBLEMS = {
    "blast": ("blast_box", ["output.dump_interval=0"]),
    "blast_gmsh": ("blast_box_gmsh", ["output.dump_interval=0"]),
    "sedov": ("sedov", ["mesh.nx=120", "mesh.ny=120", "output.dump_interval=0"]),
    "sedov_checked": ("sedov", ["mesh.nx=120", "mesh.ny=120", "output.dump_interval=0",
                                "numerics.check_corner_areas=true"]),
    "sod": ("sod", ["mesh.refine=4", "output.dump_interval=0"]),
    "noh_polar": ("noh_polar", ["output.dump_interval=0"]),
    "noh": ("noh", ["mesh.nx=100", "mesh.ny=100", "output.dump_interval=0"]),
}


def read_vtu(path):
    """Points (n x 3), connectivity, offsets and the cell arrays of one .vtu."""
    data = open(path, "rb").read()
    start = data.index(b"<AppendedData")
    raw = data[data.index(b"_", start) + 1:]
    header = data[:start].decode()
    arrays = {}
    for m in re.finditer(r"<DataArray([^>]*)>", header):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        if attrs.get("format") != "appended":
            continue
        off = int(attrs["offset"])
        nblocks = int(np.frombuffer(raw, np.uint64, 1, off)[0])
        sizes = np.frombuffer(raw, np.uint64, 3 + nblocks, off)
        pos = off + 8 * (3 + nblocks)
        chunks = []
        for b in range(nblocks):
            n = int(sizes[3 + b])
            chunks.append(zlib.decompress(raw[pos:pos + n]))
            pos += n
        dtype = {"Float64": np.float64, "Float32": np.float32, "Int64": np.int64, "Int32": np.int32,
                 "UInt8": np.uint8, "Int8": np.int8, "UInt64": np.uint64}[attrs["type"]]
        values = np.frombuffer(b"".join(chunks), dtype)
        comps = int(attrs.get("NumberOfComponents", "1"))
        name = attrs.get("Name", "")
        arrays[name] = values.reshape(-1, comps) if comps > 1 else values
    return arrays


def zones(arrays):
    """Area centroids (cx, cy), areas and the polygons' point lists."""
    pts = arrays["Points"] if "Points" in arrays else arrays[""]
    conn, offs = arrays["connectivity"], arrays["offsets"]
    starts = np.concatenate([[0], offs[:-1]])
    cx = np.empty(len(offs))
    cy = np.empty(len(offs))
    area = np.empty(len(offs))
    polys = []
    for i, (s, e) in enumerate(zip(starts, offs)):
        ids = conn[s:e]
        x, y = pts[ids, 0], pts[ids, 1]
        x1, y1 = np.roll(x, -1), np.roll(y, -1)
        cr = x * y1 - x1 * y
        a = 0.5 * cr.sum()
        area[i] = a
        cx[i] = ((x + x1) * cr).sum() / (6 * a)
        cy[i] = ((y + y1) * cr).sum() / (6 * a)
        polys.append(ids)
    return cx, cy, area, polys, pts


def crossing_zones(arrays):
    """Zones whose boundary crosses itself or whose signed area is not positive."""
    _, _, area, polys, pts = zones(arrays)
    count = 0
    for ids, a in zip(polys, area):
        if not a > 0:
            count += 1
            continue
        n = len(ids)
        x, y = pts[ids, 0], pts[ids, 1]

        def side(i, j, k):
            return (x[j] - x[i]) * (y[k] - y[i]) - (y[j] - y[i]) * (x[k] - x[i])

        crossed = False
        for i in range(n):
            for j in range(i + 2, n):
                if (j + 1) % n == i:
                    continue
                i1, j1 = (i + 1) % n, (j + 1) % n
                if side(i, i1, j) * side(i, i1, j1) < 0 and side(j, j1, i) * side(j, j1, i1) < 0:
                    crossed = True
        count += crossed
    return count


def last_vtu(out):
    pvd = [f for f in os.listdir(out) if f.endswith(".pvd")][0]
    files = re.findall(r'file="([^"]+)"', open(os.path.join(out, pvd)).read())
    return os.path.join(out, files[-1])


def run(build, work, problem, option, rerun):
    scene, extra = PROBLEMS[problem]
    out = os.path.join(work, problem, re.sub(r"[^a-z0-9]+", "_", option.lower()).strip("_"))
    summary = os.path.join(out, "summary.json")
    if rerun or not os.path.exists(summary):
        cmd = [os.path.join(build, "bin", "stagger"), "run", os.path.join(SCENES, scene + ".toml"), "--out", out,
               "--quiet", "--threads", "1"]
        for s in extra + OPTIONS[option]:
            cmd += ["--set", s]
        subprocess.run(["nice", "-n", "10"] + cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out, json.load(open(summary))


def sedov_metrics(arrays):
    cx, cy, _, _, _ = zones(arrays)
    rho = arrays["density"]
    r = np.hypot(cx, cy)
    sel = (r > 0.6) & (r < 0.9)
    bins = np.linspace(0.6, 0.9, 31)
    idx = np.digitize(r[sel], bins) - 1
    scat = [np.std(rho[sel][idx == b]) / np.mean(rho[sel][idx == b]) for b in range(30) if np.any(idx == b)]
    ang = np.arctan2(cy, cx)
    sel = r > 0.5
    abins = np.linspace(0, math.pi / 2, 19)
    aidx = np.clip(np.digitize(ang[sel], abins) - 1, 0, 17)
    peaks = []
    for b in range(18):
        m = aidx == b
        if np.any(m):
            peaks.append(r[sel][m][np.argmax(rho[sel][m])])
    return float(np.mean(scat)), float(max(peaks) - min(peaks))


def noh_jet(arrays):
    cx, cy, _, polys, pts = zones(arrays)
    rho = arrays["density"]
    r = np.hypot(cx, cy)
    worst = 0.0
    for i, ids in enumerate(polys):
        if 0.05 < r[i] < 0.15 and (np.any(pts[ids, 0] == 0) or np.any(pts[ids, 1] == 0)):
            worst = max(worst, abs(rho[i] - 16) / 16)
    return worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--work", default=None)
    ap.add_argument("--only", nargs="*", default=list(PROBLEMS))
    ap.add_argument("--options", nargs="*", default=list(OPTIONS))
    ap.add_argument("--rerun", action="store_true")
    args = ap.parse_args()
    work = args.work or os.path.join(args.build, "subzonal")
    for problem in args.only:
        print(f"\n### {problem}\n")
        if problem.startswith("blast"):
            print("| options | status | cycles | crossing zones (last dump) | energy audit |\n|---|---|---|---|---|")
        elif problem.startswith("sedov"):
            print("| options | status | scatter at fixed r | peak-radius spread | shock radius | L1(rho) | cycles |\n"
                  "|---|---|---|---|---|---|---|")
        elif problem == "sod":
            print("| options | status | L1(rho) | audit |\n|---|---|---|---|")
        elif problem == "noh_polar":
            print("| options | status | plateau | asymmetry | cycles | audit |\n|---|---|---|---|---|---|")
        else:
            print("| options | status | axis jet | plateau | L1(rho) | cycles | audit |\n|---|---|---|---|---|---|---|")
        for option in args.options:
            if problem in ONLY and option not in ONLY[problem]:
                continue
            out, s = run(args.build, work, problem, option, args.rerun)
            status = "completed"
            if s["status"] != "completed":
                reached = re.search(r"t = ([0-9.eE+-]+)", s["status"])
                status = f'stopped at t = {float(reached.group(1)):.3g}' if reached else "stopped"
            audit = f'{s["energy"]["relative_error"]:.1e}'
            arrays = read_vtu(last_vtu(out))
            if problem.startswith("blast"):
                print(f'| {option} | {status} | {s["cycles"]} | {crossing_zones(arrays)} | {audit} |')
            elif problem.startswith("sedov"):
                if s["status"] == "completed":
                    scat, spread = sedov_metrics(arrays)
                    l1 = s.get("errors", {}).get("L1_density", float("nan"))
                    shock = 100 * s.get("diagnostics", {}).get("shock_radius_error", float("nan"))
                    print(f'| {option} | {status} | {scat:.3f} | {spread:.4f} | {shock:+.2f} % | {l1:.4f} | '
                          f'{s["cycles"]} |')
                else:
                    print(f'| {option} | {status} | - | - | - | - | {s["cycles"]} |')
            elif problem == "sod":
                l1 = s.get("errors", {}).get("L1_density", float("nan"))
                print(f"| {option} | {status} | {l1:.3e} | {audit} |")
            elif problem == "noh_polar":
                d = s.get("diagnostics", {})
                print(f'| {option} | {status} | {d.get("plateau_density", float("nan")):.3f} | '
                      f'{d.get("asymmetry", float("nan")):.1e} | {s["cycles"]} | {audit} |')
            else:
                l1 = s.get("errors", {}).get("L1_density", float("nan"))
                d = s.get("diagnostics", {})
                print(f'| {option} | {status} | {noh_jet(arrays):.3f} | {d.get("plateau_density", float("nan")):.2f} | '
                      f'{l1:.4f} | {s["cycles"]} | {audit} |')
            sys.stdout.flush()


if __name__ == "__main__":
    main()
