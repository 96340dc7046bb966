#!/usr/bin/env python3
"""Before/after figures of the ALE remap for docs/ale.md ("Remap").

Runs the blast in a walled box (apps/scenes/blast_box_ale.toml) with `stagger run`:

1. Lagrangian to t = T (C cycles): the mesh and density just before a remap.
2. ALE with ale.remap_every = C to t = T: bitwise the Lagrangian run until its first remap,
   which follows cycle C, so its last dump is the same state just after one remap.
3. ALE with a remap after every cycle (the scene's default) to t = T.

and plots docs/figures/ale_remap_one.png (mesh and density around the blast, before and
after the one remap) and docs/figures/ale_remap_blast.png (the whole box, Lagrangian
against ALE at t = T).

    scripts/remap_figures.py [--build build] [--out docs/figures] [--time 0.3]

(Debian's matplotlib belongs to /usr/bin/python3.)
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import zlib

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "apps", "scenes", "blast_box_ale.toml")


def read_vtu(path):
    """The appended, zlib-compressed arrays of one .vtu written by stagger, by name."""
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
        arrays[attrs.get("Name", "")] = values.reshape(-1, comps) if comps > 1 else values
    return arrays


def last_vtu(out):
    pvd = [f for f in os.listdir(out) if f.endswith(".pvd")][0]
    files = re.findall(r'file="([^"]+)"', open(os.path.join(out, pvd)).read())
    return os.path.join(out, files[-1])


def run(binary, out, settings):
    cmd = [binary, "run", SCENE, "--out", out, "--quiet", "--threads", "1", "--set", "output.checkpoints=false"]
    for s in settings:
        cmd += ["--set", s]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("remap_figures: %s failed:\n%s%s" % (" ".join(cmd), done.stdout, done.stderr))
    summary = json.load(open(os.path.join(out, "summary.json")))
    return read_vtu(last_vtu(out)), summary


def polygons(arrays):
    pts, conn, offs = arrays["Points"], arrays["connectivity"], arrays["offsets"]
    starts = np.concatenate([[0], offs[:-1]])
    return [pts[conn[s:e], :2] for s, e in zip(starts, offs)]


def draw(ax, arrays, title, field=None, norm=None, window=None, width=0.3):
    polys = polygons(arrays)
    if field is None:
        coll = PolyCollection(polys, facecolors="none", edgecolors="k", linewidths=width)
    else:
        coll = PolyCollection(polys, array=arrays[field], cmap="viridis", norm=norm, linewidths=0, antialiased=False)
    ax.add_collection(coll)
    ax.set_aspect("equal")
    if window:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    else:
        ax.autoscale_view()
    ax.set_title(title, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])
    return coll


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="docs/figures")
    parser.add_argument("--time", type=float, default=0.3, help="t = T of the three runs")
    args = parser.parse_args()
    binary = os.path.join(args.build, "bin", "stagger")
    end = "time.end=%g" % args.time
    with tempfile.TemporaryDirectory() as tmp:
        before, lag = run(binary, os.path.join(tmp, "lagrangian"), [end, "ale.mode=lagrangian"])
        cycles = lag["cycles"]
        after, one = run(binary, os.path.join(tmp, "one"), [end, "ale.remap_every=%d" % cycles])
        ale, every = run(binary, os.path.join(tmp, "ale"), [end])
    if one["cycles"] != cycles:
        sys.exit("remap_figures: the one-remap run took %d cycles, the Lagrangian one %d" % (one["cycles"], cycles))
    moved = np.abs(after["Points"] - before["Points"]).max()
    print("t = %g: %d Lagrangian cycles; one remap moved points by up to %.3g; the ALE run took %d cycles, "
          "energy audit %.2g (Lagrangian %.2g), fix-up %.3g" %
          (args.time, cycles, moved, every["cycles"], every["energy"]["relative_error"],
           lag["energy"]["relative_error"], every["energy"]["ale_fixup"]))
    os.makedirs(args.out, exist_ok=True)

    # One remap, around the upper right of the blast wave (hot spot at (0.4, 0.5), r = 0.15).
    window = (0.45, 0.95, 0.5, 1.0)
    rho = np.concatenate([before["density"], after["density"]])
    norm = matplotlib.colors.LogNorm(vmin=rho.min(), vmax=rho.max())
    fig, axes = plt.subplots(2, 2, figsize=(9, 8.4), layout="constrained")
    draw(axes[0][0], before, "Lagrangian mesh, t = %g (cycle %d)" % (args.time, cycles), window=window)
    draw(axes[0][1], after, "after one rezone + remap", window=window)
    draw(axes[1][0], before, "density before", "density", norm, window)
    coll = draw(axes[1][1], after, "density after", "density", norm, window)
    fig.colorbar(coll, ax=axes[1].tolist(), shrink=0.8, label="density (log scale)")
    fig.savefig(os.path.join(args.out, "ale_remap_one.png"), dpi=120)
    plt.close(fig)

    # Lagrangian against ALE (a remap after every cycle), the whole box.
    rho = np.concatenate([before["density"], ale["density"]])
    norm = matplotlib.colors.LogNorm(vmin=rho.min(), vmax=rho.max())
    fig, axes = plt.subplots(2, 2, figsize=(11, 6.2), layout="constrained")
    draw(axes[0][0], before, "Lagrangian, %d cycles" % cycles, width=0.2)
    draw(axes[0][1], ale, "ALE (remap every cycle), %d cycles" % every["cycles"], width=0.2)
    draw(axes[1][0], before, "density, Lagrangian", "density", norm)
    coll = draw(axes[1][1], ale, "density, ALE", "density", norm)
    fig.colorbar(coll, ax=axes[1].tolist(), shrink=0.8, label="density (log scale)")
    fig.suptitle("Blast in a walled box (100 x 50), t = %g" % args.time, fontsize=10)
    fig.savefig(os.path.join(args.out, "ale_remap_blast.png"), dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
