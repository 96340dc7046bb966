#!/usr/bin/env python3
"""The plane-strain copper Taylor bars (docs/solids.md §8): runs and the table of results.

    /usr/bin/python3 scripts/verification/taylor_bar.py [--build BUILD] [--work DIR] [--rerun]
                     [--only taylor_bar_200 taylor_bar_400] [--figure docs/figures/solids_taylor_bar.png]

Runs `stagger run` on apps/scenes/taylor_bar_{200,400}.toml with each option set below (the
scenes' own numerics: the defaults), reads summary.json (status, time reached, cycles, the
energy audit and the diagnostics of the `taylor_bar` reference: final length, impact-face
width, largest equivalent plastic strain) and the last .vtu of each run (its own small
reader: raw appended, zlib-compressed, 64-bit headers, docs/output.md), where it counts the
crossing zones and the points below the wall (both must be 0: docs/algorithm.md §9-10), and
prints the markdown table of docs/solids.md §8. With --figure it draws the last state of the
scenes' own runs, coloured by the plastic strain (matplotlib, Agg).
"""
import argparse
import json
import os
import re
import subprocess
import zlib

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "apps", "scenes")

# Option sets: name -> --set overrides on top of the scene.
OPTIONS = {
    "scene (defaults)": [],
    "bulk q + gamma 0.1 (the old defaults)": ["numerics.viscosity=bulk", "numerics.hourglass=gamma",
                                              "numerics.hourglass_coefficient=0.1"],
}
SCENE_NAMES = ["taylor_bar_200", "taylor_bar_400"]


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
        if attrs["type"] == "String":  # field data of rz runs: NUL-terminated strings (docs/output.md)
            arrays[attrs.get("Name", "")] = [v.decode() for v in b"".join(chunks).split(b"\0") if v]
            continue
        dtype = {"Float64": np.float64, "Float32": np.float32, "Int64": np.int64, "Int32": np.int32,
                 "UInt8": np.uint8, "Int8": np.int8, "UInt64": np.uint64}[attrs["type"]]
        values = np.frombuffer(b"".join(chunks), dtype)
        comps = int(attrs.get("NumberOfComponents", "1"))
        arrays[attrs.get("Name", "")] = values.reshape(-1, comps) if comps > 1 else values
    return arrays


def polygons(arrays):
    conn, offs = arrays["connectivity"], arrays["offsets"]
    starts = np.concatenate([[0], offs[:-1]])
    return [conn[s:e] for s, e in zip(starts, offs)]


def crossing_zones(arrays):
    """Zones whose boundary crosses itself or whose signed area is not positive."""
    pts = arrays["Points"]
    count = 0
    for ids in polygons(arrays):
        x, y = pts[ids, 0], pts[ids, 1]
        if not 0.5 * (x * np.roll(y, -1) - np.roll(x, -1) * y).sum() > 0:
            count += 1
            continue
        n = len(ids)

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


def run(build, work, scene, option, rerun):
    out = os.path.join(work, scene, re.sub(r"[^a-z0-9]+", "_", option.lower()).strip("_"))
    summary = os.path.join(out, "summary.json")
    if rerun or not os.path.exists(summary):
        cmd = [os.path.join(build, "bin", "stagger"), "run", os.path.join(SCENES, scene + ".toml"), "--out", out,
               "--quiet", "--threads", "1"]
        for s in OPTIONS[option]:
            cmd += ["--set", s]
        subprocess.run(["nice", "-n", "10"] + cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out, json.load(open(summary))


def figure(runs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    fig, axes = plt.subplots(len(runs), 1, figsize=(10, 3.2 * len(runs)), squeeze=False)
    for ax, (scene, out, summary) in zip(axes[:, 0], runs):
        arrays = read_vtu(last_vtu(out))
        pts = arrays["Points"][:, :2] * 100  # cm
        pc = PolyCollection([pts[ids] for ids in polygons(arrays)], array=arrays["plastic_strain"], cmap="viridis",
                            edgecolors="k", linewidths=0.1)
        ax.add_collection(pc)
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_xlabel("x (cm)")
        ax.set_ylabel("y (cm)")
        ax.set_title("%s: t = %.0f us, %s" % (scene, summary["time"] * 1e6, summary["status"][:60]))
        fig.colorbar(pc, ax=ax, label="equivalent plastic strain")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", default="/tmp/stagger_taylor_bar")
    parser.add_argument("--only", nargs="*", default=SCENE_NAMES)
    parser.add_argument("--rerun", action="store_true")
    parser.add_argument("--figure")
    args = parser.parse_args()
    print("| scene | numerics | t reached (us) | status | cycles | final length (mm) | L / L0 | impact-face width (mm) "
          "| max eps_p | crossing zones | points below the wall | audit |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    scene_runs = []
    for scene in args.only:
        for option in OPTIONS:
            out, s = run(args.build, args.work, scene, option, args.rerun)
            d = s.get("diagnostics", {})
            arrays = read_vtu(last_vtu(out))
            below = int(np.sum(arrays["Points"][:, 1] < -1e-12))
            status = "completed" if s["status"] == "completed" else "stopped (tangled)"
            print("| %s | %s | %.1f | %s | %d | %.2f | %.3f | %.1f | %.2f | %d | %d | %.1e |" % (
                scene, option, s["time"] * 1e6, status, s["cycles"], d["final_length"] * 1e3, d["length_ratio"],
                d["impact_face_width"] * 1e3, d["max_plastic_strain"], crossing_zones(arrays), below,
                s["energy"]["relative_error"]))
            if option == "scene (defaults)":
                scene_runs.append((scene, out, s))
    if args.figure:
        figure(scene_runs, args.figure)


if __name__ == "__main__":
    main()
