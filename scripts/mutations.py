#!/usr/bin/env python3
"""Breaks the physics one line at a time and lists the tests that catch each breakage
(docs/robustness.md, "Mutations").

Each mutation replaces one exact snippet of one source file (it must occur exactly once).
The script works on a detached git worktree of HEAD (the checkout is never touched), builds
it once, then for every mutation: applies it, rebuilds the test binaries it names, runs them
whole, records the failing tests, and reverts. It prints the table as Markdown and, with
--write-docs, puts it between the markers of docs/robustness.md.

    python3 scripts/mutations.py [--only NAME ...] [--jobs N] [--write-docs] [--keep] [--dir DIR]

A full pass (all mutations, the listed tests) takes about 40 minutes on two cores.
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent

# name, file, snippet, replacement, and the test binaries to run (tests/<area> -> test_<area>),
# each whole or as "binary:gtest filter" (the suites that could see the breakage, to keep a
# pass under an hour).
MUTATIONS = [
    dict(name="velocity remap first order (point gradients zeroed)",
         file="lib/src/ale/remap_reconstruction.cpp",
         find="    gax[p] = ax[0], gay[p] = ay[0], gbx[p] = ax[1], gby[p] = ay[1];",
         replace="    gax[p] = gay[p] = gbx[p] = gby[p] = 0.0;",
         binaries=["test_ale:Remap.*:RemapRz.*:RemapSimulation.*"]),
    dict(name="velocity remap limiter off",
         file="lib/src/ale/remap_reconstruction.cpp",
         find="      limit[i] = limiter && (ax[i] != 0 || ay[i] != 0);",
         replace="      limit[i] = limiter && false && (ax[i] != 0 || ay[i] != 0);",
         binaries=["test_ale:Remap.*:RemapRz.*:RemapSimulation.*"]),
    dict(name="scalar remap limiter off (control)",
         file="lib/src/ale/remap_reconstruction.cpp",
         find="    if (limiter && (ax != 0 || ay != 0)) {",
         replace="    if (limiter && false && (ax != 0 || ay != 0)) {",
         binaries=["test_ale:Remap.*:RemapRz.*:RemainderBound.*"]),
    dict(name="corner kinetic-energy gradient term of the momentum remap dropped",
         file="lib/src/ale/remap_fluxes.cpp",
         find="  const double ke = 0.5 * (u * u + w * w) * flux + crho_[cd] * (u * du + w * dw);",
         replace="  const double ke = 0.5 * (u * u + w * w) * flux;",
         binaries=["test_ale:Remap.*:RemapRz.*:RemapSimulation.*:AleFixup.*"]),
    dict(name="rz: half-step force radius at x^n instead of x^{n+1/2}",
         file="lib/src/hydro/step.cpp",
         find="  if (rz) weight_rz_forces(px, 0.5 * dt);  // rz: true corner forces from the area-weighted ones",
         replace="  if (rz) weight_rz_forces(px ? x.data() : nullptr, 0.0 * dt);",
         binaries=["test_step:TemporalOrder.*", "test_hydro:*Rz*:*RZ*"]),
    dict(name="time step after a remap not recomputed (the remapped mesh's limit ignored)",
         file="lib/src/hydro/step.cpp",
         find="      recompute_state();\n      wall_clearance.valid = charged;",
         replace="      const double kept = dt_next;\n      recompute_state();\n      dt_next = kept;\n"
                 "      wall_clearance.valid = charged;",
         binaries=["test_ale:RemapTimeStep.*:RemapSimulation.*", "test_api:*Remap*"]),
    dict(name="radial return after a remap skipped",
         file="lib/src/ale/ale_remap.cpp",
         find="  if (s_.any_strength) {\n    for (const ZoneRange& r : s_.ranges) {",
         replace="  if (false && s_.any_strength) {\n    for (const ZoneRange& r : s_.ranges) {",
         binaries=["test_ale:AleStrength.*:RemapSimulation.*"]),
    dict(name="fix-up: a point's deficit no longer paid by its neighbours",
         file="lib/src/ale/ale_remap.cpp",
         find="  pay_deficits_locally();\n  pay_deficits_globally();",
         replace="  if (false) pay_deficits_locally();\n  pay_deficits_globally();",
         binaries=["test_ale:AleFixup.*:RemapSimulation.*"]),
    dict(name="fix-up: what the neighbours cannot pay no longer paid by the other points",
         file="lib/src/ale/ale_remap.cpp",
         find="  pay_deficits_locally();\n  pay_deficits_globally();",
         replace="  pay_deficits_locally();\n  if (false) pay_deficits_globally();",
         binaries=["test_ale:AleFixup.*:RemapSimulation.*"]),
    dict(name="fix-up: the guard of the internal energy's floor dropped",
         file="lib/src/ale/ale_remap.cpp",
         find="  share_to_zones();\n  bound_zone_shares();",
         replace="  share_to_zones();\n  if (false) bound_zone_shares();",
         binaries=["test_ale:AleFixup.*:RemapSimulation.*"]),
    dict(name="kinetic-energy fix-up dropped (control)",
         file="lib/src/ale/ale_remap.cpp",
         find="    if (dE_[z] != 0) s_.e[z] = (s_.zone_mass[z] * s_.e[z] + dE_[z]) / s_.zone_mass[z];",
         replace="    if (false) s_.e[z] = 0;",
         binaries=["test_ale:AleFixup.*:RemapSimulation.*"]),
    dict(name="rezone relaxation toward the Lagrangian mesh ignored (weight 1)",
         file="lib/src/ale/rezone.cpp",
         find="  for (Index p = 0; p < np; ++p) blend(p, options.relaxation);",
         replace="  for (Index p = 0; p < np; ++p) blend(p, 1.0);",
         binaries=["test_ale:Rezone.*:RemapSimulation.*"]),
    dict(name="rz axis masses' shape factor doubled",
         file="lib/src/ale/ale_remap.cpp",
         find="      s.axis_moment[j] = s.ale_corner_mass[c] * shape;",
         replace="      s.axis_moment[j] = s.ale_corner_mass[c] * 2 * shape;",
         binaries=["test_ale:AleAxisMasses.*:RemapSimulation.*"]),
    dict(name="heat flux's time-step limit ignored",
         file="lib/src/hydro/step.cpp",
         find="    heat_limited = heat_dt.dt < candidate;",
         replace="    heat_limited = false;",
         binaries=["test_hydro:HeatFlux.*"]),
    dict(name="subzonal pressures at half the merit factor",
         file="lib/src/hydro/kernels/zone_forces.hpp",
         find="                                      o.hourglass_coefficient, subzones, out.fx + b, out.fy + b);",
         replace="                                      0.5 * o.hourglass_coefficient, subzones, out.fx + b, out.fy + b);",
         binaries=["test_step:SubzonalCoefficient.*:*Subzonal*", "test_kernels:*Subzonal*"]),
    dict(name="edge viscosity: Christensen's limiter off",
         file="lib/src/hydro/kernels/viscosity_edge.cpp",
         find="        psi = std::max(0.0, std::min({0.5 * (ra + rb), 2 * ra, 2 * rb, 1.0}));",
         replace="        psi = 0 * std::max(0.0, std::min({0.5 * (ra + rb), 2 * ra, 2 * rb, 1.0}));",
         binaries=["test_hydro:EdgeViscosity*:Sod*:Saltzman*", "test_kernels", "test_step:*Viscosity*"]),
]

BEGIN = "<!-- mutations table: scripts/mutations.py --write-docs -->"
END = "<!-- end of the mutations table -->"


def run(cmd, cwd, log=None, check=True):
    out = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if log is not None:
        log.write(out.stdout)
    if check and out.returncode != 0:
        sys.exit(f"mutations: '{' '.join(cmd)}' failed in {cwd}:\n{out.stdout[-3000:]}")
    return out


def failing_tests(binary, cwd, pattern=""):
    """Runs a gtest binary (whole, or the tests of a filter); returns the names of the failing
    tests (or a crash note)."""
    report = pathlib.Path(tempfile.mkstemp(suffix=".json")[1])
    args = [binary, f"--gtest_output=json:{report}"] + ([f"--gtest_filter={pattern}"] if pattern else [])
    out = subprocess.run(args, cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True, timeout=1800)
    failed = []
    try:
        data = json.loads(report.read_text())
        for suite in data.get("testsuites", []):
            for t in suite.get("testsuite", []):
                if t.get("failures"):
                    failed.append(f"{suite['name']}.{t['name']}")
    except (json.JSONDecodeError, OSError):
        failed.append(f"{pathlib.Path(binary).name}: no report (exit {out.returncode})")
    report.unlink(missing_ok=True)
    if out.returncode not in (0, 1) and not failed:
        failed.append(f"{pathlib.Path(binary).name}: exit {out.returncode}")
    return failed


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", nargs="*", help="substrings of the mutation names to run")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--write-docs", action="store_true", help="write the table into docs/robustness.md")
    ap.add_argument("--keep", action="store_true", help="keep the worktree afterwards")
    ap.add_argument("--dir", default=None, help="where to put the worktree (default: the system's temporary directory)")
    args = ap.parse_args()
    chosen = [m for m in MUTATIONS if not args.only or any(o in m["name"] for o in args.only)]
    work = pathlib.Path(tempfile.mkdtemp(prefix="stagger-mutations-", dir=args.dir))
    tree = work / "tree"
    run(["git", "worktree", "add", "--detach", str(tree), "HEAD"], ROOT)
    log = open(work / "build.log", "w")
    try:
        build = tree / "build"
        configure = ["cmake", "-S", ".", "-B", "build", "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release"]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        run(configure, tree, log)
        binaries = sorted({b.split(":")[0] for m in chosen for b in m["binaries"]})
        run(["ninja", "-C", "build", f"-j{args.jobs}"] + binaries, tree, log)
        rows = []
        for m in chosen:
            path = tree / m["file"]
            text = path.read_text()
            count = text.count(m["find"])
            if count != 1:
                sys.exit(f"mutations: the snippet of '{m['name']}' occurs {count} times in {m['file']}")
            path.write_text(text.replace(m["find"], m["replace"]))
            try:
                names = [b.split(":")[0] for b in m["binaries"]]
                built = run(["ninja", "-C", "build", f"-j{args.jobs}"] + names, tree, log, check=False)
                failed = [] if built.returncode == 0 else ["(the mutation does not build)"]
                for b in m["binaries"] if built.returncode == 0 else []:
                    name, _, pattern = b.partition(":")
                    failed += failing_tests(str(build / "tests" / name), build / "tests", pattern)
            finally:
                path.write_text(text)
            rows.append((m, failed))
            print(f"{m['name']}: {len(failed)} failing: {', '.join(failed) or '-'}", flush=True)
        table = ["| breakage | file | tests run (binary:filter) | failing tests |", "|---|---|---|---|"]
        for m, failed in rows:
            names = "<br>".join(f"`{t}`" for t in failed) if failed else "**none**"
            runs = ", ".join(f"`{b}`" for b in m["binaries"])
            table.append(f"| {m['name']} | `{m['file']}` | {runs} | {len(failed)}: {names} |")
        text = "\n".join(table)
        print(text)
        if args.write_docs:
            doc = ROOT / "docs" / "robustness.md"
            content = doc.read_text()
            pattern = re.compile(re.escape(BEGIN) + "\n(.*?)" + re.escape(END), re.S)
            found = pattern.search(content)
            if not found:
                sys.exit("mutations: the table's markers are missing from docs/robustness.md")
            if args.only:
                # Only the rows of the mutations run are replaced; the others stay, in the table's order.
                fresh = {line.split(" | ")[0]: line for line in table[2:]}
                old = [line for line in found.group(1).splitlines() if line.startswith("| ")][1:]  # no header
                rows_out = table[:2] + [fresh.pop(line.split(" | ")[0], line) for line in old] + list(fresh.values())
                text = "\n".join(rows_out)
            doc.write_text(pattern.sub(lambda _: BEGIN + "\n" + text + "\n" + END, content))
        if any(len(f) < 2 for _, f in rows):
            print("mutations: some breakage fails fewer than two tests", file=sys.stderr)
            return 1
        return 0
    finally:
        log.close()
        if not args.keep:
            run(["git", "worktree", "remove", "--force", str(tree)], ROOT, check=False)
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
