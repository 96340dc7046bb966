#!/usr/bin/env python3
"""Runs the verification scenes with stagger-profile and plots them against the exact solutions.

    python3 scripts/verification/make_figures.py [--build BUILD] [--work DIR] [--only NAME ...]
                                                 [--rerun] [--plot-only] [--jobs N]

Every exact value comes from the project's C++ code: stagger-profile writes, at each zone centre,
the exact solution of the scene's [verification] reference (exact_* columns of zones_<t>.csv) and
the reference's error norms and diagnostics (errors_<t>.csv). This script only runs, collects
and draws. Figures go to docs/figures/verif_*.png, and the tables to
docs/figures/verif_results.md (copied into docs/verification.md by hand, with commentary).
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "apps", "scenes")
FIGURES = os.path.join(ROOT, "docs", "figures")


def shell_times():
    return [k * 10e-6 for k in range(14)]


# name -> (scene, --set overrides, times, history_every)
RUNS = {}


def add(name, scene, sets=(), times=None, history_every=1):
    RUNS[name] = (scene, list(sets), times, history_every)


for r in (1, 2, 4):
    add(f"sod_{100 * r}", "sod", [f"mesh.refine={r}"], [0.1, 0.2])
add("sod_200_edge", "sod", ["mesh.refine=2", "numerics.viscosity=edge"], [0.2])
# Every check on (the scenes' own numerics: the Cartesian Noh, Sedov and Saltzman the default
# tensor q with subzonal triangles, the polar Noh the edge viscosity; docs/verification.md).
EDGE_TRIANGLES_1 = ["numerics.viscosity=edge", "numerics.hourglass_coefficient=1"]  # the old noh.toml
add("noh_50", "noh", [], [0.2, 0.4, 0.6])
add("noh_50_edge", "noh", EDGE_TRIANGLES_1, [0.6])
add("noh_100", "noh", ["mesh.refine=2"], [0.6])
add("noh_100_edge", "noh", ["mesh.refine=2"] + EDGE_TRIANGLES_1, [0.6])
add("noh_polar_50", "noh_polar", [], [0.2, 0.4, 0.6])
add("noh_polar_100", "noh_polar", ["mesh.refine=2"], [0.6])
add("noh_polar_50_bulk", "noh_polar", ["numerics.viscosity=bulk"], [0.6])
add("noh_polar_50_tensor", "noh_polar", ["numerics.viscosity=tensor"], [0.6])
add("noh_polar_50_nolimiter", "noh_polar", ["numerics.edge_limiter=false"], [0.6])
for n, r in ((30, 1), (60, 2), (120, 4)):
    add(f"sedov_{n}_tensor", "sedov", [f"mesh.refine={r}"], [0.5, 1.0])
    add(f"sedov_{n}_bulk", "sedov", [f"mesh.refine={r}", "numerics.viscosity=bulk"], [1.0])
add("saltzman_default", "saltzman", [], [0.2, 0.4, 0.6])
EDGE = ["numerics.viscosity=edge"]
FB = ["numerics.hourglass=flanagan_belytschko", "numerics.hourglass_coefficient=1"]
add("saltzman_edge_fb", "saltzman", EDGE + FB, [0.2, 0.4, 0.6])
add("saltzman_bulk_fb", "saltzman", ["numerics.viscosity=bulk"] + FB, [0.6])
add("saltzman_edge_gamma", "saltzman", EDGE + ["numerics.hourglass=gamma", "numerics.hourglass_coefficient=1"], [0.6])
add("saltzman_edge_none", "saltzman", EDGE + ["numerics.hourglass_coefficient=0"], [0.6])
for n in (16, 32, 64, 128):
    add(f"smooth_{n}", "smooth", [f"mesh.nx={n}", f"mesh.ny={n}"], [0.5])
for n in (20, 40, 80, 160):
    add(f"accuracy_{n}", "accuracy", [f"mesh.nx={n}", f"mesh.ny={n}"], [1e-4])
for r in (1, 2, 4, 10):
    add(f"piston_{100 * r}", "piston", [f"mesh.refine={r}"], [50e-6, 100e-6, 150e-6])
for r, label in ((1, "20x16"), (2, "40x32"), (4, "80x64")):
    add(f"be_shell_{label}", "be_shell", [f"mesh.refine={r}"], shell_times(), history_every=10)
add("detonation_200", "detonation", [], [0.2, 0.4, 0.6, 0.8, 1.0])
add("detonation_400", "detonation", ["mesh.refine=2"], [1.0])


# ---------------------------------------------------------------- running


def run_one(build, work, name, rerun):
    scene, sets, times, history_every = RUNS[name]
    out = os.path.join(work, name)
    if not rerun and os.path.exists(os.path.join(out, "summary.json")):
        return name, 0.0, "cached"
    command = [os.path.join(build, "bin", "stagger-profile"), os.path.join(SCENES, scene + ".toml"), "--out", out,
               "--history-every", str(history_every)]
    for s in sets:
        command += ["--set", s]
    if times:
        command += ["--times", ",".join(repr(t) for t in times)]
    start = time.time()
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "log.txt"), "w") as log:
        log.write(" ".join(command) + "\n")
        log.flush()
        result = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT,
                                env=dict(os.environ, OMP_NUM_THREADS="1"))
    status = "ok" if result.returncode == 0 else f"exit {result.returncode}"
    return name, time.time() - start, status


# ---------------------------------------------------------------- reading


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return {}
    data = {}
    for key in rows[0]:
        try:
            data[key] = np.array([float(r[key]) for r in rows])
        except ValueError:
            data[key] = np.array([r[key] for r in rows])
    return data


class Run:
    def __init__(self, work, name):
        self.name = name
        self.dir = os.path.join(work, name)
        with open(os.path.join(self.dir, "summary.json")) as f:
            self.summary = json.load(f)
        self.frames = read_csv(os.path.join(self.dir, "frames.csv"))
        self.history = read_csv(os.path.join(self.dir, "history.csv"))

    @property
    def ok(self):
        return self.summary["status"] == "completed"

    def frame_index(self, t):
        times = self.frames["time"]
        return int(np.argmin(np.abs(times - t)))

    def zones(self, t=None):
        k = len(self.frames["time"]) - 1 if t is None else self.frame_index(t)
        return read_csv(os.path.join(self.dir, self.frames["zones_file"][k]))

    def errors(self, t=None):
        k = len(self.frames["time"]) - 1 if t is None else self.frame_index(t)
        rows = read_csv(os.path.join(self.dir, self.frames["errors_file"][k]))
        if not rows:
            return {}
        return {n: v for n, v in zip(rows["name"], rows["value"])}

    def time(self, t=None):
        k = len(self.frames["time"]) - 1 if t is None else self.frame_index(t)
        return float(self.frames["time"][k])

    def cycles(self, t=None):
        k = len(self.frames["time"]) - 1 if t is None else self.frame_index(t)
        return int(self.frames["cycle"][k])

    def audit(self):
        """Largest |relative energy error| over the recorded history."""
        return float(np.max(np.abs(self.history["relative_energy_error"])))


def order(e_coarse, e_fine, ratio=2.0):
    if e_coarse <= 0 or e_fine <= 0:
        return float("nan")
    return math.log(e_coarse / e_fine) / math.log(ratio)


def fmt(v, digits=4):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    if isinstance(v, (int, np.integer)):
        return str(v)
    return f"{v:.{digits}g}"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        lines.append("| " + " | ".join(fmt(c) if not isinstance(c, str) else c for c in row) + " |")
    return "\n".join(lines) + "\n"


def save(fig, name):
    path = os.path.join(FIGURES, name)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return name


def sorted_by(z, key):
    i = np.argsort(z[key], kind="stable")
    return {k: v[i] for k, v in z.items()}


# ---------------------------------------------------------------- figures


def fig_sod(runs, out):
    fig, axes = plt.subplots(3, 2, figsize=(11, 10), sharex=True)
    for col, t in enumerate((0.1, 0.2)):
        for name, style in (("sod_100", "C0."), ("sod_400", "C1-")):
            z = sorted_by(runs[name].zones(t), "x")
            row = z["y"] < z["y"].min() + 1e-12  # one row of zones along the tube
            for ax, field in zip(axes[:, col], ("density", "velocity_x", "pressure")):
                ax.plot(z["x"][row], z[field][row], style, ms=3, lw=1, label=name.replace("sod_", "") + "x5")
        z = sorted_by(runs["sod_400"].zones(t), "x")
        for ax, field in zip(axes[:, col], ("density", "velocity_x", "pressure")):
            ax.plot(z["x"], z["exact_" + field], "k-", lw=0.8, label="exact (ExactRiemann)")
            ax.set_ylabel(field)
        axes[0, col].set_title(f"Sod, t = {t}")
        axes[2, col].set_xlabel("x")
    axes[0, 0].legend()
    fig.suptitle("Sod shock tube: zone values (velocity = mean of the zone's points) against the exact solution")
    out.append(save(fig, "verif_sod_profiles.png"))

    fig, ax = plt.subplots(figsize=(6, 4.5))
    n = np.array([100, 200, 400])
    for field, marker in (("density", "o"), ("velocity", "s"), ("pressure", "^")):
        e = [runs[f"sod_{k}"].errors(0.2)[f"L1_{field}"] for k in n]
        ax.loglog(n, e, marker + "-", label=f"L1 {field}")
    ax.loglog(n, 2.94e-3 * 200 / n, "k:", label="prototype L1 density (order 1)")
    ax.set_xlabel("zones along x")
    ax.set_ylabel("L1 error, t = 0.2")
    ax.legend()
    ax.set_title("Sod: convergence")
    out.append(save(fig, "verif_sod_convergence.png"))


def sod_tables(runs, roundoff=None):
    """roundoff formats the round-off columns (check_tables.py writes them as a decade bound)."""
    roundoff = roundoff or fmt
    rows = []
    for k in (100, 200, 400):
        r = runs[f"sod_{k}"]
        for t in (0.1, 0.2):
            e = r.errors(t)
            rows.append([f"{k}x5", t, r.cycles(t), e["L1_density"], e["L1_velocity"], e["L1_pressure"],
                         roundoff(e.get("max_y_variation", float("nan")))])
    text = table(["mesh", "t", "cycles", "L1 density", "L1 velocity", "L1 pressure", "max y-variation"], rows)
    orders = []
    for field in ("density", "velocity", "pressure"):
        e = [runs[f"sod_{k}"].errors(0.2)[f"L1_{field}"] for k in (100, 200, 400)]
        orders.append([field, order(e[0], e[1]), order(e[1], e[2])])
    text += "\nObserved orders (t = 0.2):\n\n" + table(["field", "100->200", "200->400"], orders)
    r = runs["sod_200_edge"]
    text += (f"\nEdge viscosity, 200x5, t = 0.2: {r.cycles()} cycles, L1 density "
             f"{fmt(r.errors()['L1_density'])} (bulk q: {runs['sod_200'].cycles(0.2)} cycles, "
             f"{fmt(runs['sod_200'].errors(0.2)['L1_density'])}).\n")
    return text


def radial_scatter(ax, z, field, label, style=".", **kw):
    ax.plot(z["r"], z[field], style, ms=3, label=label, **kw)


def fig_noh(runs, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    panels = (("noh_50", "Cartesian 50x50", "default: tensor q + triangles 2", "noh_50_edge", "edge q + triangles 1"),
              ("noh_polar_50", "polar 25 x 50 rings", "edge viscosity + gamma 0.1", "noh_polar_50_bulk", "bulk q"))
    for ax, (name, title, label, other, other_label) in zip(axes, panels):
        z = runs[name].zones(0.6)
        radial_scatter(ax, z, "density", label + " (every zone)", "C0.")
        zb = runs[other].zones()
        radial_scatter(ax, zb, "density", f"{other_label} (t = {runs[other].time():.3g})", "C3.", alpha=0.5)
        zs = sorted_by(z, "r")
        ax.plot(zs["r"], zs["exact_density"], "k-", lw=1, label="exact (NohSolution)")
        ax.set_xlim(0, 0.5)
        ax.set_title(f"Noh, {title}, t = 0.6")
        ax.set_xlabel("r (zone centre)")
    axes[0].set_ylabel("density")
    axes[0].set_ylim(0, 25)
    axes[0].legend(loc="upper right")
    out.append(save(fig, "verif_noh_density.png"))

    fig, axes = plt.subplots(1, 2, figsize=(11, 5))
    for ax, name in zip(axes, ("noh_50", "noh_polar_50")):
        z = runs[name].zones(0.6)
        sc = ax.scatter(z["x"], z["y"], c=z["density"], s=6, cmap="viridis", vmin=0, vmax=20)
        ax.set_aspect("equal")
        ax.set_xlim(0, 0.4)
        ax.set_ylim(0, 0.4)
        ax.set_title(name + ", density at zone centres, t = 0.6")
        fig.colorbar(sc, ax=ax, shrink=0.8)
    out.append(save(fig, "verif_noh_maps.png"))


def equivalent_shock_radius(z, threshold=10.0):
    """Radius of the quarter disc with the area of the zones above `threshold` (half-way
    between the plateau 16 and the pre-shock 4): insensitive to the few low-density zones
    at the centre, unlike a mean over threshold crossings."""
    area = float(np.sum(z["area"][z["density"] >= threshold]))
    return math.sqrt(4.0 * area / math.pi)


NOH_RUNS = ["noh_50", "noh_100", "noh_50_edge", "noh_100_edge", "noh_polar_50", "noh_polar_100", "noh_polar_50_bulk",
            "noh_polar_50_tensor", "noh_polar_50_nolimiter"]


def noh_tables(runs):
    rows = []
    for name in NOH_RUNS:
        r = runs[name]
        e = r.errors()
        rows.append([name, r.time(), r.cycles(), e.get("plateau_density"), e.get("shock_radius"),
                     equivalent_shock_radius(r.zones()), e.get("L1_density"), e.get("asymmetry"), float(np.min(r.zones()["density"])), r.audit(),
                     "completed" if r.ok else "stopped"])
    return table(["run", "t", "cycles", "plateau (16)", "shock r (crossings)", "shock r (area rho>=10)",
                  "L1 density", "asymmetry",
                  "min density", "max audit", "status"], rows)


def fig_sedov(runs, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    for ax, kind in zip(axes, ("tensor", "bulk")):
        for n, style in ((30, "C2."), (60, "C1."), (120, "C0.")):
            z = runs[f"sedov_{n}_{kind}"].zones(1.0)
            ax.plot(z["r"], z["density"], style, ms=1.5, label=f"{n}x{n}")
        z = sorted_by(runs["sedov_120_tensor"].zones(1.0), "r")
        ax.plot(z["r"], z["exact_density"], "k-", lw=1, label="exact (SedovSolution)")
        ax.set_title(f"Sedov, {kind} q + subzonal triangles 2, t = 1")
        ax.set_xlabel("r (zone centre)")
        ax.set_xlim(0, 1.2)
    axes[0].set_ylabel("density")
    axes[0].legend()
    out.append(save(fig, "verif_sedov_density.png"))

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    z = runs["sedov_120_tensor"].zones(1.0)
    zs = sorted_by(z, "r")
    axes[0].plot(z["r"], z["pressure"], "C0.", ms=1.5, label="120x120 tensor")
    axes[0].plot(zs["r"], zs["exact_pressure"], "k-", lw=1, label="exact")
    axes[0].set_ylabel("pressure")
    vr = (z["velocity_x"] * z["x"] + z["velocity_y"] * z["y"]) / np.maximum(z["r"], 1e-300)
    axes[1].plot(z["r"], vr, "C0.", ms=1.5, label="120x120 tensor")
    exact_vr = (zs["exact_velocity_x"] * zs["x"] + zs["exact_velocity_y"] * zs["y"]) / np.maximum(zs["r"], 1e-300)
    axes[1].plot(zs["r"], exact_vr, "k-", lw=1, label="exact")
    axes[1].set_ylabel("radial velocity")
    for ax in axes:
        ax.set_xlabel("r")
        ax.legend()
        ax.set_xlim(0, 1.2)
    fig.suptitle("Sedov 120x120, default numerics (tensor q + subzonal triangles 2), t = 1")
    out.append(save(fig, "verif_sedov_pressure_velocity.png"))


def sedov_tables(runs):
    rows = []
    for kind in ("tensor", "bulk"):
        for n in (30, 60, 120):
            r = runs[f"sedov_{n}_{kind}"]
            e = r.errors(1.0)
            rows.append([f"{n}x{n}", kind, r.cycles(1.0), e.get("shock_radius"), e.get("shock_radius_exact"),
                         100 * e.get("shock_radius_error", float("nan")), e.get("peak_density"), e.get("L1_density"),
                         r.audit(), "completed" if r.ok else "stopped at t=" + fmt(r.time())])
    return table(["mesh", "viscosity", "cycles", "shock r", "exact", "error %", "peak density (6)", "L1 density",
                  "max audit", "status"], rows)


def fig_saltzman(runs, out):
    fig, axes = plt.subplots(2, 1, figsize=(11, 7))
    r = runs["saltzman_default"]
    for t, style in ((0.2, "C2."), (0.4, "C1."), (0.6, "C0.")):
        z = r.zones(t)
        axes[0].plot(z["x"], z["density"], style, ms=2, label=f"t = {t}")
        zs = sorted_by(z, "x")
        axes[0].plot(zs["x"], zs["exact_density"], "k-", lw=0.8)
    axes[0].set_ylabel("density")
    axes[0].set_title("Saltzman piston (scene: tensor q + subzonal triangles 2.5): every zone; black: exact")
    axes[0].legend()
    for name, style in (("saltzman_default", "C0-"), ("saltzman_edge_fb", "C4-"), ("saltzman_edge_gamma", "C1-"),
                        ("saltzman_edge_none", "C3-"), ("saltzman_bulk_fb", "C2-")):
        z = runs[name].zones()
        # Inner rows only (the generator numbers zones row by row, 100 per row): the rows at
        # the walls are 15-20 % off in every variant (mesh skew), which hides the differences.
        row = z["zone"].astype(int) // 100
        for k in range(1, 9):
            sel = row == k
            zs = sorted_by({key: v[sel] for key, v in z.items()}, "x")
            axes[1].plot(zs["x"], zs["density"], style, lw=0.7,
                         label=f"{name} (t = {runs[name].time():.3g})" if k == 1 else None)
    axes[1].axhline(4, color="k", lw=0.8)
    axes[1].set_ylim(2.5, 5.5)
    axes[1].set_xlim(0.55, 0.85)
    axes[1].set_title("inner rows 2-9 of 10 (lines follow a row of zones)")
    axes[1].set_xlabel("x (zone centre)")
    axes[1].set_ylabel("density")
    axes[1].legend(fontsize=8)
    out.append(save(fig, "verif_saltzman_density.png"))

    # The mesh at the last time: zones drawn as their centres coloured by density.
    fig, ax = plt.subplots(figsize=(11, 2.2))
    z = runs["saltzman_default"].zones()
    sc = ax.scatter(z["x"], z["y"], c=z["density"], s=8, cmap="viridis", vmin=0, vmax=5)
    ax.set_aspect("equal")
    ax.set_title("Saltzman, the scene (tensor q + subzonal triangles 2.5), t = 0.6: density at zone centres")
    fig.colorbar(sc, ax=ax)
    out.append(save(fig, "verif_saltzman_map.png"))


SALTZMAN_RUNS = ["saltzman_default", "saltzman_edge_fb", "saltzman_edge_gamma", "saltzman_edge_none", "saltzman_bulk_fb"]


def saltzman_tables(runs, roundoff=None):
    roundoff = roundoff or fmt
    rows = []
    for name in SALTZMAN_RUNS:
        r = runs[name]
        e = r.errors()
        z = r.zones()
        t = r.time()
        row = z["zone"].astype(int) // 100
        core = (row >= 1) & (row <= 8) & (z["x"] > t + 0.02) & (z["x"] < 4 * t / 3 - 0.02)
        core_error = float(np.max(np.abs(z["density"][core] - 4))) if np.any(core) else float("nan")
        rows.append([name, r.time(), r.cycles(), e.get("shock_position"), e.get("shock_position_exact"),
                     e.get("plateau_density"), e.get("inner_row_max_density_error"), core_error,
                     e.get("L1_density"), roundoff(r.audit()),
                     "completed" if r.ok else "stopped"])
    return table(["run", "t reached", "cycles", "shock x", "exact", "plateau mean (4)", "inner-row max error",
                  "same, 0.02 away from piston and shock", "L1 density", "max audit", "status"], rows)


def fig_smooth(runs, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    ns = np.array([16, 32, 64, 128])
    for field, marker in (("velocity", "o"), ("pressure", "s"), ("density", "^")):
        e = np.array([runs[f"smooth_{n}"].errors()[f"L2_{field}"] for n in ns])
        axes[0].loglog(ns, e, marker + "-", label=f"L2 {field}")
    e0 = runs["smooth_16"].errors()["L2_velocity"]
    axes[0].loglog(ns, e0 * (16 / ns) ** 2, "k:", label="order 2")
    axes[0].set_xlabel("N (N x N zones)")
    axes[0].set_ylabel("L2 error, t = 0.5")
    axes[0].set_title("Taylor-Green vortex: convergence")
    axes[0].legend()
    z = runs["smooth_64"].zones()
    diag = np.abs(z["x"] - z["y"]) < 1e-9 + 0.5 / 64
    zz = sorted_by({k: v[diag] for k, v in z.items()}, "x")
    axes[1].plot(zz["x"], zz["pressure"], "C0.", label="pressure, 64x64, zones near y = x")
    axes[1].plot(zz["x"], zz["exact_pressure"], "k-", lw=0.8, label="exact")
    axes[1].set_xlabel("x")
    axes[1].legend()
    axes[1].set_title("Taylor-Green, t = 0.5")
    out.append(save(fig, "verif_smooth.png"))


def smooth_tables(runs, roundoff=None):
    roundoff = roundoff or fmt
    rows = []
    ns = (16, 32, 64, 128)
    for i, n in enumerate(ns):
        r = runs[f"smooth_{n}"]
        e = r.errors()
        row = [f"{n}x{n}", r.cycles(), e["L2_velocity"], e["L2_pressure"], e["L2_density"]]
        if i:
            p = runs[f"smooth_{ns[i - 1]}"].errors()
            row += [order(p["L2_velocity"], e["L2_velocity"]), order(p["L2_pressure"], e["L2_pressure"])]
        else:
            row += [float("nan"), float("nan")]
        row.append(roundoff(r.audit()))
        rows.append(row)
    return table(["mesh", "cycles", "L2 velocity", "L2 pressure", "L2 density", "order v", "order p", "max audit"],
                 rows)


def fig_accuracy(runs, out):
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.5))
    for n in (20, 40, 80, 160):
        h = runs[f"accuracy_{n}"].history
        # Mean velocity = total momentum / total mass; the exact solution keeps it at a = 1e4.
        mass = h["momentum_x"][0] / 1e4
        ax2.plot(h["time"] * 1e6, h["momentum_x"] / mass - 1e4, label=f"N = {n}")
    ax2.set_xlabel("t (us)")
    ax2.set_ylabel("mean velocity_x - a (m/s)")
    ax2.set_title("Mean x velocity minus a (exact: 0): total momentum")
    ax2.legend()
    ns = np.array([20, 40, 80, 160])
    for field, marker in (("density", "o"), ("deviatoric_stress_xx", "s"), ("deviatoric_stress_xy", "^")):
        e = np.array([runs[f"accuracy_{n}"].errors()[f"L2_{field}"] for n in ns])
        ax.loglog(ns, e / e[0], marker + "-", label=f"L2 {field} (relative to N = 20)")
    ax.loglog(ns, (20 / ns) ** 2, "k:", label="order 2")
    ax.set_xlabel("N")
    ax.set_title("Smooth elastic accuracy test, t = 1e-4 s")
    ax.legend(fontsize=8)
    out.append(save(fig, "verif_accuracy.png"))


def accuracy_tables(runs):
    rows = []
    ns = (20, 40, 80, 160)
    for i, n in enumerate(ns):
        r = runs[f"accuracy_{n}"]
        e = r.errors()
        row = [f"{n}x{n}", r.cycles(), e["L2_density"], e["L2_deviatoric_stress_xx"], e["L2_deviatoric_stress_xy"]]
        if i:
            p = runs[f"accuracy_{ns[i - 1]}"].errors()
            row += [order(p["L2_density"], e["L2_density"]),
                    order(p["L2_deviatoric_stress_xx"], e["L2_deviatoric_stress_xx"])]
        else:
            row += [float("nan"), float("nan")]
        row.append(r.audit())
        rows.append(row)
    return table(["mesh", "cycles", "L2 density", "L2 S_xx", "L2 S_xy", "order rho", "order S_xx", "max audit"], rows)


def fig_piston(runs, out):
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    fields = (("velocity_x", "velocity (m/s)", 1), ("pressure", "pressure (GPa)", 1e-9),
              ("deviatoric_stress_xx", "S_xx (MPa)", 1e-6), ("density", "density (kg/m^3)", 1))
    for ax, (field, label, scale) in zip(axes.flat, fields):
        for name, style in (("piston_100", "C2.-"), ("piston_400", "C1.-"), ("piston_1000", "C0-")):
            z = sorted_by(runs[name].zones(150e-6), "x")
            row = z["y"] < z["y"].min() + 1e-12
            ax.plot(z["x"][row], z[field][row] * scale, style, ms=2, lw=0.8, label=name.replace("piston_", "") + "x5")
        z = sorted_by(runs["piston_1000"].zones(150e-6), "x")
        ax.plot(z["x"], z["exact_" + field] * scale, "k-", lw=0.8, label="exact (ElasticPlasticPiston)")
        ax.set_ylabel(label)
        ax.set_xlim(0, 1.0)
    axes[0, 0].legend(fontsize=8)
    for ax in axes[1]:
        ax.set_xlabel("x (m)")
    fig.suptitle("Copper piston at 20 m/s, t = 150 us")
    out.append(save(fig, "verif_piston_profiles.png"))

    fig, ax = plt.subplots(figsize=(6, 4.5))
    ns = np.array([100, 200, 400, 1000])
    for field, marker in (("velocity", "o"), ("pressure", "s"), ("deviatoric_stress_xx", "^"), ("density", "v")):
        e = np.array([runs[f"piston_{n}"].errors(150e-6)[f"L1_{field}"] for n in ns])
        ax.loglog(ns, e / e[0], marker + "-", label=f"L1 {field} (relative to 100x5)")
    ax.loglog(ns, 100 / ns, "k:", label="order 1")
    ax.set_xlabel("zones along x")
    ax.legend(fontsize=8)
    ax.set_title("Piston: convergence at t = 150 us")
    out.append(save(fig, "verif_piston_convergence.png"))


def piston_tables(runs):
    rows = []
    ns = (100, 200, 400, 1000)
    for i, n in enumerate(ns):
        r = runs[f"piston_{n}"]
        e = r.errors(150e-6)
        row = [f"{n}x5", r.cycles(150e-6), e["L1_velocity"], e["L1_pressure"], e["L1_deviatoric_stress_xx"],
               e.get("elastic_front"), e.get("elastic_front_exact"), e.get("plastic_front"),
               e.get("plastic_front_exact"), r.audit()]
        rows.append(row)
    text = table(["mesh", "cycles", "L1 velocity", "L1 pressure", "L1 S_xx", "elastic front", "exact",
                  "plastic front", "exact", "max audit"], rows)
    orders = []
    for field in ("velocity", "pressure", "deviatoric_stress_xx", "density"):
        e = [runs[f"piston_{n}"].errors(150e-6)[f"L1_{field}"] for n in ns]
        orders.append([field, order(e[0], e[1]), order(e[1], e[2]), order(e[2], e[3], 2.5)])
    text += "\nObserved orders (L1, t = 150 us):\n\n" + table(["field", "100->200", "200->400", "400->1000"], orders)
    e = runs["piston_1000"].errors(150e-6)
    text += (f"\nExact states: elastic velocity {fmt(e.get('elastic_velocity_exact'))} m/s, elastic pressure "
             f"{fmt(e.get('elastic_pressure_exact'))} Pa, plastic pressure {fmt(e.get('plastic_pressure_exact'))} Pa, "
             f"plastic density {fmt(e.get('plastic_density_exact'))} kg/m^3.\n")
    return text


def fig_be_shell(runs, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    exact = read_csv(os.path.join(runs["be_shell_80x64"].dir, "exact_shell.csv"))
    for label, style in (("20x16", "C2o"), ("40x32", "C1s"), ("80x64", "C0^")):
        r = runs[f"be_shell_{label}"]
        t, ri, ro = [], [], []
        for k in range(len(r.frames["time"])):
            e = r.errors(r.frames["time"][k])
            if "inner_radius" in e:
                t.append(r.frames["time"][k])
                ri.append(e["inner_radius"])
                ro.append(e["outer_radius"])
        t = np.array(t) * 1e6
        axes[0].plot(t, np.array(ri) * 1e3, style, mfc="none", label=f"inner, {label}")
        axes[0].plot(t, np.array(ro) * 1e3, style, label=f"outer, {label}")
    axes[0].plot(exact["time"] * 1e6, exact["inner_radius"] * 1e3, "k-", lw=0.8,
                 label="incompressible analytic (HowellBallShell)")
    axes[0].plot(exact["time"] * 1e6, exact["outer_radius"] * 1e3, "k-", lw=0.8)
    axes[0].set_xlabel("t (us)")
    axes[0].set_ylabel("radius (mm)")
    axes[0].legend(fontsize=7)
    axes[0].set_title("Be shell: inner and outer radii")
    r = runs["be_shell_80x64"]
    h = r.history
    axes[1].plot(h["time"] * 1e6, h["kinetic"] / 1e6, label="kinetic")
    axes[1].plot(h["time"] * 1e6, (h["internal"] - h["internal"][0]) / 1e6, label="internal - internal(0)")
    axes[1].plot(h["time"] * 1e6, (h["total"]) / 1e6, label="total")
    scale = h["kinetic"][0] / exact["kinetic_energy"][0]
    axes[1].plot(exact["time"] * 1e6, exact["kinetic_energy"] * scale / 1e6, "k--", lw=0.8,
                 label="analytic kinetic (scaled to the quarter)")
    axes[1].set_xlabel("t (us)")
    axes[1].set_ylabel("energy per unit length (MJ/m)")
    axes[1].legend(fontsize=8)
    axes[1].set_title("Be shell 80x64: kinetic energy becomes plastic heat")
    out.append(save(fig, "verif_be_shell.png"))


def be_shell_tables(runs):
    rows = []
    for label in ("20x16", "40x32", "80x64"):
        r = runs[f"be_shell_{label}"]
        e = r.errors()
        rows.append([label, r.time() * 1e6, r.cycles(), e["inner_radius"] * 1e3, e["outer_radius"] * 1e3,
                     e["inner_radius_exact"] * 1e3, e["outer_radius_exact"] * 1e3, e["asymmetry"], r.audit(),
                     r.summary["loop_seconds"]])
    text = table(["mesh", "t (us)", "cycles", "r_in (mm)", "r_out (mm)", "analytic r_in", "analytic r_out",
                  "asymmetry", "max audit", "loop s"], rows)
    e = runs["be_shell_80x64"].errors()
    text += (f"\nAnalytic stopping radii {fmt(e['inner_stopping_radius_exact'] * 1e3, 6)} / "
             f"{fmt(e['outer_stopping_radius_exact'] * 1e3, 6)} mm at t = "
             f"{fmt(e['stopping_time_exact'] * 1e6, 5)} us.\n")
    return text


def fig_detonation(runs, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    r = runs["detonation_200"]
    for k, t in enumerate((0.2, 0.4, 0.6, 0.8, 1.0)):
        z = sorted_by(r.zones(t), "x")
        row = z["y"] < z["y"].min() + 1e-12
        axes[0].plot(z["x"][row], z["pressure"][row] * 100, f"C{k}.", ms=3, label=f"t = {t} us")
        axes[0].plot(z["x"], z["exact_pressure"] * 100, "k-", lw=0.7)
    axes[0].set_xlabel("x (cm)")
    axes[0].set_ylabel("pressure (GPa)")
    axes[0].set_title("Comp B detonation, 200x5; black: CJ + Taylor wave (CJDetonation)")
    axes[0].legend(fontsize=8)
    h = r.history
    axes[1].plot(h["time"], h["relative_energy_error"], "C0-")
    axes[1].set_xlabel("t (us)")
    axes[1].set_ylabel("(E - E0 - W) / max(E0, |W|, E)")
    axes[1].set_title("Energy audit (detonation energy is in e from t = 0)")
    out.append(save(fig, "verif_detonation.png"))


def detonation_tables(runs):
    rows = []
    for name in ("detonation_200", "detonation_400"):
        r = runs[name]
        for t in r.frames["time"]:
            e = r.errors(t)
            rows.append([name.replace("detonation_", "") + "x5", t, r.cycles(t), e.get("front_position"),
                         e.get("front_position_exact"), e.get("front_position_nominal"), e.get("peak_pressure"),
                         e.get("cj_pressure_exact"), e.get("plateau_pressure"), e.get("plateau_pressure_exact"),
                         e.get("L1_pressure")])
    text = table(["mesh", "t (us)", "cycles", "front (cm)", "exact", "nominal", "peak p (Mbar)", "P_CJ exact",
                  "plateau p", "exact", "L1 pressure"], rows)
    text += f"\nMax energy audit: 200x5 {fmt(runs['detonation_200'].audit())}, 400x5 " \
            f"{fmt(runs['detonation_400'].audit())}; CJ speed implied by the JWL fit " \
            f"{fmt(runs['detonation_200'].errors().get('cj_speed_exact'), 5)} cm/us.\n"
    return text


def audit_table(runs, old_rows=None):
    """One row per run; runs not loaded this time keep their row of the previous file."""
    rows = []
    for name in RUNS:
        if name in runs:
            r = runs[name]
            rows.append([name, r.summary["zones"], r.summary["cycles"], r.summary["time"], r.audit(),
                         r.summary["loop_seconds"], r.summary["status"][:60]])
        elif old_rows and name in old_rows:
            rows.append(old_rows[name])
    return table(["run", "zones", "cycles", "t reached", "max audit over the run", "loop s", "status"], rows)


def read_results(path):
    """The sections ("## title" -> text) and the audit-table rows (run -> cells) of an existing
    verif_results.md, so that a partial run (--only) keeps what it did not recompute."""
    sections, audit_rows = {}, {}
    if not os.path.exists(path):
        return sections, audit_rows
    with open(path) as f:
        text = f.read()
    for chunk in text.split("\n## ")[1:]:
        title = chunk.split("\n", 1)[0].strip()
        sections[title] = "## " + chunk.rstrip("\n") + "\n\n"
    audit = sections.get("Every run: energy audit and cost", "")
    for line in audit.splitlines()[4:]:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 7:
            audit_rows[cells[0]] = cells
    return sections, audit_rows


SECTIONS = [
    ("Sod", ["sod_100", "sod_200", "sod_400", "sod_200_edge"], fig_sod, sod_tables),
    ("Noh", NOH_RUNS, fig_noh,
     noh_tables),
    ("Sedov", [f"sedov_{n}_{k}" for n in (30, 60, 120) for k in ("tensor", "bulk")], fig_sedov, sedov_tables),
    ("Saltzman", SALTZMAN_RUNS,
     fig_saltzman, saltzman_tables),
    ("Taylor-Green", [f"smooth_{n}" for n in (16, 32, 64, 128)], fig_smooth, smooth_tables),
    ("Accuracy", [f"accuracy_{n}" for n in (20, 40, 80, 160)], fig_accuracy, accuracy_tables),
    ("Piston", [f"piston_{n}" for n in (100, 200, 400, 1000)], fig_piston, piston_tables),
    ("Be shell", ["be_shell_20x16", "be_shell_40x32", "be_shell_80x64"], fig_be_shell, be_shell_tables),
    ("Detonation", ["detonation_200", "detonation_400"], fig_detonation, detonation_tables),
]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "verification"))
    parser.add_argument("--only", nargs="*",
                        help="run names (or prefixes) to run, plot and tabulate; the other sections of "
                             "verif_results.md and their figures are kept as they are")
    parser.add_argument("--rerun", action="store_true", help="run again even if results exist")
    parser.add_argument("--plot-only", action="store_true")
    parser.add_argument("--jobs", type=int, default=1)
    args = parser.parse_args()

    names = [n for n in RUNS if not args.only or any(n.startswith(o) for o in args.only)]
    if not args.plot_only:
        # Longest first, so that parallel jobs finish together.
        heavy = {"be_shell_80x64": 0, "noh_100": 1, "noh_polar_100": 2, "sedov_120_tensor": 3, "sedov_120_bulk": 4,
                 "noh_polar_50_bulk": 5, "piston_1000": 6}
        names.sort(key=lambda n: heavy.get(n, 10))
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            for name, seconds, status in pool.map(lambda n: run_one(args.build, args.work, n, args.rerun), names):
                print(f"{name:24s} {status:10s} {seconds:7.1f} s", flush=True)

    runs = {}
    for name in names:
        try:
            runs[name] = Run(args.work, name)
        except (OSError, KeyError) as failure:
            print(f"warning: no results for {name}: {failure}", file=sys.stderr)
    os.makedirs(FIGURES, exist_ok=True)
    results_path = os.path.join(FIGURES, "verif_results.md")
    old_sections, old_audit_rows = read_results(results_path)
    figures = []
    text = ("# Verification results (generated)\n\nWritten by `scripts/verification/make_figures.py`; "
            "docs/verification.md discusses them.\n\n")
    for title, needed, figure, tables in SECTIONS:
        if not all(n in runs for n in needed):
            if title in old_sections:
                print(f"keeping {title} from {os.path.relpath(results_path, ROOT)}", file=sys.stderr)
                text += old_sections[title]
            else:
                print(f"skipping {title}: missing runs", file=sys.stderr)
            continue
        figure(runs, figures)
        text += f"## {title}\n\n" + tables(runs) + "\n"
    text += "## Every run: energy audit and cost\n\n" + audit_table(runs, old_audit_rows)
    with open(results_path, "w") as f:
        f.write(text)
    print("figures:", ", ".join(figures))


if __name__ == "__main__":
    main()
