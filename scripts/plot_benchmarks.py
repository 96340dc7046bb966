#!/usr/bin/env python3
"""Figures and tables of `stagger bench` (docs/benchmarks.md).

    python3 scripts/plot_benchmarks.py [--csv bench_out] [--out docs/figures]

Reads ladders.csv, orders.csv, throughput.csv and stress.csv (whichever exist) and writes
  bench_work_precision.png  error against wall time, one curve per scene and option
  bench_convergence.png     error against resolution, observed order in the legend
  bench_throughput.png      zone-cycles/s, ns per zone-cycle and bytes per zone
                            against zones, 1 and 2 threads
  bench_orders.md, bench_throughput.md, bench_stress.md   markdown tables
Only matplotlib (Agg) and the standard library are needed.
"""
import argparse
import csv
import math
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The error measure shown per scene (the first one present is used).
PRIMARY = {
    "sod": ["L1_density"],
    "noh": ["L1_density"],
    "noh_polar": ["L1_density"],
    "sedov": ["L1_density"],
    "saltzman": ["L1_density"],
    "smooth": ["L2_velocity"],
    "piston": ["L1_velocity"],
    "be_shell": ["inner_radius_relerr"],
    "accuracy": ["L2_density"],
    "detonation": ["L1_pressure"],
}
FALLBACK = ["L1_density", "L1_velocity", "L2_velocity", "L1_pressure"]


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def number(row, key):
    try:
        value = float(row.get(key, "") or "nan")
    except ValueError:
        return math.nan
    return value


def primary_measure(scene, rows):
    candidates = PRIMARY.get(scene, []) + FALLBACK
    for name in candidates:
        if any(math.isfinite(number(row, name)) and number(row, name) > 0 for row in rows):
            return name
    for row in rows:  # any *_relerr
        for key in row:
            if key.endswith("_relerr") and math.isfinite(number(row, key)):
                return key
    return None


def ladder_groups(ladders):
    groups = OrderedDict()
    for row in ladders:
        if row["status"] != "completed":
            continue
        groups.setdefault((row["scene"], row["option"]), []).append(row)
    for rows in groups.values():
        rows.sort(key=lambda r: number(r, "refine"))
    return groups


def grid(count):
    columns = min(4, max(1, count))
    rows = (count + columns - 1) // columns
    figure, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.4 * rows), squeeze=False)
    flat = [axis for row in axes for axis in row]
    for axis in flat[count:]:
        axis.set_visible(False)
    return figure, flat


def observed_orders(orders, scene, option, measure):
    return [number(r, "order") for r in orders
            if r["scene"] == scene and r["option"] == option and r["measure"] == measure]


def plot_ladders(ladders, orders, out):
    groups = ladder_groups(ladders)
    scenes = list(OrderedDict((scene, None) for scene, _ in groups))
    if not scenes:
        return []
    written = []
    for kind in ("work_precision", "convergence"):
        figure, axes = grid(len(scenes))
        for axis, scene in zip(axes, scenes):
            scene_rows = [r for (s, _), rows in groups.items() if s == scene for r in rows]
            measure = primary_measure(scene, scene_rows)
            if measure is None:
                axis.set_title(scene + " (no error measure)")
                continue
            for (s, option), rows in groups.items():
                if s != scene:
                    continue
                points = [(number(r, "wall_seconds" if kind == "work_precision" else "refine"), number(r, measure))
                          for r in rows]
                points = [(x, y) for x, y in points if x > 0 and y > 0 and math.isfinite(y)]
                if not points:
                    continue
                label = option
                if kind == "convergence":
                    found = observed_orders(orders, scene, option, measure)
                    if found:
                        label += "  p = " + ", ".join("%.2f" % p for p in found)
                axis.loglog([p[0] for p in points], [p[1] for p in points], "o-", label=label)
            axis.set_title(scene + ": " + measure, fontsize=10)
            axis.set_xlabel("wall seconds (stepping loop)" if kind == "work_precision" else "mesh.refine (1/h)")
            axis.set_ylabel(measure)
            axis.grid(True, which="both", alpha=0.3)
            axis.legend(fontsize=7)
        figure.suptitle("Work-precision: error against run time" if kind == "work_precision"
                        else "Error against resolution (observed order p between successive rungs)")
        figure.tight_layout()
        path = os.path.join(out, "bench_%s.png" % kind)
        figure.savefig(path, dpi=110)
        plt.close(figure)
        written.append(path)
    return written


def plot_throughput(rows, out):
    scan = [r for r in rows if r["scene"] == "sedov" and r["option"] == "scene" and r["status"] == "completed"]
    if not scan:
        return []
    figure, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for threads in sorted({r["threads"] for r in scan}, key=int):
        data = sorted(((number(r, "zones"), r) for r in scan if r["threads"] == threads), key=lambda p: p[0])
        zones = [z for z, _ in data]
        label = "%s thread%s" % (threads, "" if threads == "1" else "s")
        axes[0].semilogx(zones, [number(r, "zone_cycles_per_second") / 1e6 for _, r in data], "o-", label=label)
        axes[1].semilogx(zones, [1e9 / number(r, "zone_cycles_per_second") for _, r in data], "o-", label=label)
        axes[2].loglog(zones, [number(r, "bytes_per_zone") for _, r in data], "o-", label=label + " (peak RSS)")
        if threads == "1":
            axes[2].loglog(zones, [(number(r, "peak_rss_bytes") - number(r, "baseline_rss_bytes")) / number(r, "zones")
                                   for _, r in data], "s--", label="1 thread, above start-up RSS")
    for threshold, label in ((7.0, "target 1 thread (7)"), (12.0, "target 2 threads (12)")):
        axes[0].axhline(threshold, color="grey", linestyle=":", linewidth=1)
        axes[0].text(1.1e3, threshold * 1.02, label, fontsize=7, color="grey")
    axes[2].axhline(500, color="grey", linestyle=":", linewidth=1)
    axes[0].set_ylabel("million zone-cycles / s")
    axes[1].set_ylabel("ns per zone-cycle (flat = cost linear in zones)")
    axes[2].set_ylabel("bytes per zone")
    for axis in axes:
        axis.set_xlabel("zones (Sedov, n x n)")
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=8)
    axes[1].set_ylim(bottom=0)
    figure.suptitle("Throughput of the Sedov scene (stepping loop only)")
    figure.tight_layout()
    path = os.path.join(out, "bench_throughput.png")
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return [path]


def fmt(value, digits=3):
    if not math.isfinite(value):
        return ""
    return "%.*g" % (digits, value)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def write_tables(ladders, orders, throughput, stress, out):
    written = []
    if orders:
        groups = ladder_groups(ladders)
        body = []
        for (scene, option), rows in groups.items():
            measure = primary_measure(scene, rows)
            if measure is None:
                continue
            found = [r for r in orders if r["scene"] == scene and r["option"] == option and r["measure"] == measure]
            errors = " / ".join(fmt(number(r, measure)) for r in rows)
            zones = " / ".join(r["zones"] for r in rows)
            body.append([scene, option, measure, zones, errors, ", ".join(fmt(number(r, "order")) for r in found),
                         fmt(sum(number(r, "wall_seconds") for r in rows))])
        all_rows = [r for r in ladders]
        stopped = [[r["scene"], r["option"], fmt(number(r, "refine")), r["zones"], r["cycles"], r["status"]]
                   for r in all_rows if r["status"] != "completed"]
        text = table(["scene", "option", "measure", "zones", "error", "observed orders", "wall s"], body)
        if stopped:
            text += "\nLadder runs that did not complete:\n\n" + table(
                ["scene", "option", "refine", "zones", "cycles", "status"], stopped)
        path = os.path.join(out, "bench_orders.md")
        with open(path, "w") as handle:
            handle.write(text)
        written.append(path)
    if throughput:
        body = []
        for r in throughput:
            body.append([r["scene"], r["option"], r["threads"], r["zones"], r["cycles"], fmt(number(r, "wall_seconds")),
                         fmt(number(r, "zone_cycles_per_second") / 1e6), fmt(number(r, "peak_rss_bytes") / 2**20, 4),
                         fmt(number(r, "bytes_per_zone"), 4), fmt(number(r, "setup_seconds")),
                         r["status"] if r["status"] == "completed" else r["status"][:80]])
        path = os.path.join(out, "bench_throughput.md")
        with open(path, "w") as handle:
            handle.write(table(["scene", "option", "threads", "zones", "cycles", "loop s", "Mzc/s", "peak RSS MiB",
                                "B/zone", "set-up s", "status"], body))
        written.append(path)
    if stress:
        body = []
        for r in stress:
            status = r["status"]
            outcome = "completed" if status == "completed" else "stopped"
            message = "" if status == "completed" else status.replace("|", "/")
            if len(message) > 160:
                message = message[:157] + "..."
            body.append([r["scene"], r["option"], r["zones"], r["cycles"], fmt(number(r, "time"), 4),
                         outcome, fmt(number(r, "energy_audit"), 2), message])
        path = os.path.join(out, "bench_stress.md")
        with open(path, "w") as handle:
            handle.write(table(["scene", "option", "zones", "cycles", "t reached", "outcome", "energy audit",
                                "message"], body))
        written.append(path)
    return written


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--csv", default="bench_out", help="directory of the CSVs of stagger bench")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs",
                                                      "figures"), help="where to write the PNGs and tables")
    arguments = parser.parse_args()
    ladders = read_csv(os.path.join(arguments.csv, "ladders.csv"))
    orders = read_csv(os.path.join(arguments.csv, "orders.csv"))
    throughput = read_csv(os.path.join(arguments.csv, "throughput.csv"))
    stress = read_csv(os.path.join(arguments.csv, "stress.csv"))
    if not (ladders or throughput or stress):
        sys.exit("plot_benchmarks.py: no ladders.csv, throughput.csv or stress.csv in %s; run stagger bench first"
                 % arguments.csv)
    os.makedirs(arguments.out, exist_ok=True)
    written = plot_ladders(ladders, orders, arguments.out) + plot_throughput(throughput, arguments.out)
    written += write_tables(ladders, orders, throughput, stress, arguments.out)
    for path in written:
        print("wrote", os.path.normpath(path))


if __name__ == "__main__":
    main()
