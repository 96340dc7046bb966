#!/usr/bin/env python3
"""The plane-strain copper Taylor bars with ALE (docs/ale.md, "The Taylor bar at 800 m/s"):
runs, and the markdown table of docs/ale.md.

    python3 scripts/verification/taylor_ale.py [--build BUILD] [--work DIR] [--rerun] [--only NAME ...]

Runs, one thread each, into WORK (kept, so that a second call only prints):
  800_ale          apps/scenes/taylor_bar_800_ale.toml as shipped (ALE, reference_jacobian, a
                   remap after every cycle);
  800_lag          the same scene with ale.mode=lagrangian and time.end=40e-6;
  200_lag          apps/scenes/taylor_bar_200.toml as shipped (Lagrangian, to 120 us);
  200_ale          the same scene with the [ale] options of taylor_bar_800_ale.toml;
  200_ale_default  the same scene with ale.mode=ale alone (the [ale] defaults: Winslow, a remap
                   when the worst zone's shape quality is below 0.25).
and reads each summary.json: status, time reached, cycles, the `taylor_bar` diagnostics
(final length = the largest y of the points above the wall y = 0; the impact-face width; the
largest equivalent plastic strain), the audit and the energy the remap's fix-up moved. The
last line compares the ALE and Lagrangian final lengths at 200 m/s.
"""
import argparse
import json
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "apps", "scenes")
ALE_800 = ["ale.mode=ale", "ale.rezone=reference_jacobian", "ale.size_weight=1", "ale.remap_every=1"]

# name -> (label, scene, overrides)
RUNS = {
    "800_ale": ("800 m/s, ALE (`taylor_bar_800_ale.toml`)", "taylor_bar_800_ale", []),
    "800_lag": ("800 m/s, Lagrangian (`ale.mode=lagrangian`, `time.end=40e-6`)", "taylor_bar_800_ale",
                ["ale.mode=lagrangian", "time.end=40e-6"]),
    "200_lag": ("200 m/s, Lagrangian (`taylor_bar_200.toml`)", "taylor_bar_200", []),
    "200_ale": ("200 m/s, ALE (the [ale] options of the 800 m/s scene)", "taylor_bar_200", ALE_800),
    "200_ale_default": ("200 m/s, ALE (`ale.mode=ale`, the defaults)", "taylor_bar_200", ["ale.mode=ale"]),
}


def run(build, work, name, rerun):
    label, scene, sets = RUNS[name]
    out = os.path.join(work, name)
    summary = os.path.join(out, "summary.json")
    if rerun or not os.path.exists(summary):
        cmd = [os.path.join(build, "bin", "stagger"), "run", os.path.join(SCENES, scene + ".toml"), "--out", out,
               "--quiet", "--threads", "1", "--set", "output.dumps=false"]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return json.load(open(summary)) if os.path.exists(summary) else None


def status(s):
    if s["status"] == "completed":
        return "completed"
    reached = re.search(r"t = ([0-9.eE+-]+)", s["status"])
    return "stopped at %.2f us" % (float(reached.group(1)) * 1e6) if reached else "stopped"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--work", default="/tmp/stagger_taylor_ale")
    ap.add_argument("--only", nargs="*", default=list(RUNS), choices=list(RUNS))
    ap.add_argument("--rerun", action="store_true")
    args = ap.parse_args()
    print("| run | status | t reached (us) | cycles | final length (mm) | impact-face width (mm) | max eps_p "
          "| audit | fix-up (J/m) |")
    print("|---|---|---|---|---|---|---|---|---|")
    lengths = {}
    for name in args.only:
        s = run(args.build, args.work, name, args.rerun)
        if s is None:
            print("| %s | failed (no summary.json) | | | | | | | |" % RUNS[name][0])
            continue
        d, e = s["diagnostics"], s["energy"]
        if s["status"] == "completed":
            lengths[name] = d["final_length"]  # compared at the end time only
        print("| %s | %s | %.2f | %d | %.2f | %.1f | %.2f | %.1e | %.3g |" % (
            RUNS[name][0], status(s), s["time"] * 1e6, s["cycles"], d["final_length"] * 1e3,
            d["impact_face_width"] * 1e3, d["max_plastic_strain"], e["relative_error"], e.get("ale_fixup", 0)))
        sys.stdout.flush()
    for name in ("200_ale", "200_ale_default"):
        if "200_lag" in lengths and name in lengths:
            print("\n%s: the final length differs from the Lagrangian one by %+.2f %%." %
                  (RUNS[name][0], 100 * (lengths[name] / lengths["200_lag"] - 1)))


if __name__ == "__main__":
    main()
