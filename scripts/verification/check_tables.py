#!/usr/bin/env python3
"""Regenerates the cheap verification tables of docs/ and fails when docs/ differs from the code.

    python3 scripts/verification/check_tables.py [--build BUILD] [--work DIR] [--update]

"Cheap" means the runs take seconds: Sod (100, 200, 400 x 5), the five Saltzman variants and the
Taylor-Green ladder (16^2 to 128^2), about 20 s on one core. Each table in docs/ that this script
owns sits between

    <!-- BEGIN GENERATED <name> (scripts/verification/check_tables.py) -->
    <!-- END GENERATED <name> -->

Without --update the script reruns the scenes with stagger-profile (through the run list and the
table code of make_figures.py, so the numbers are the ones of the full suite), prints a diff of
every block that differs and exits with status 1; with --update it rewrites the blocks. Numbers
that are round-off (energy audit, y-variation) are written as a bound ("< 1e-13"), so the check
holds across compilers; everything else is deterministic (cycles, errors to 4 digits). CI
runs it as a ctest test (tests/docs/).
"""
import argparse
import difflib
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_figures as mf  # noqa: E402

DOCS = os.path.join(mf.ROOT, "docs")


def bound(limit):
    """Formats a round-off figure as "< limit" (or its value, if it is not below the limit), so
    that the tables do not depend on the last bits of the arithmetic."""
    def format_value(value):
        value = abs(float(value))
        return f"< {limit:.0e}".replace("e-0", "e-") if value < limit else mf.fmt(value)
    return format_value


AUDIT = bound(1e-13)  # docs/verification.md §11: round-off for runs of ~10^4 cycles
Y_VARIATION = bound(1e-11)  # uniform in y up to round-off that grows with the cycle count


def sod_block(runs):
    return mf.sod_tables(runs, roundoff=Y_VARIATION)


def saltzman_block(runs):
    return mf.saltzman_tables(runs, roundoff=AUDIT)


def taylor_green_block(runs):
    return mf.smooth_tables(runs, roundoff=AUDIT)


# block name -> (runs it needs, function of the loaded runs)
BLOCKS = {
    "sod": (["sod_100", "sod_200", "sod_400", "sod_200_edge"], sod_block),
    "saltzman": (mf.SALTZMAN_RUNS, saltzman_block),
    "taylor-green": ([f"smooth_{n}" for n in (16, 32, 64, 128)], taylor_green_block),
}

BLOCK = re.compile(r"(<!-- BEGIN GENERATED (?P<name>[\w-]+) \(scripts/verification/check_tables\.py\) -->\n)"
                   r"(?P<body>.*?)"
                   r"(<!-- END GENERATED (?P=name) -->)", re.S)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(mf.ROOT, "build"))
    parser.add_argument("--work", default=None, help="run directory (default BUILD/verification-check)")
    parser.add_argument("--update", action="store_true", help="rewrite the blocks in docs/ instead of checking")
    args = parser.parse_args()
    work = args.work or os.path.join(args.build, "verification-check")

    needed = [n for runs, _ in BLOCKS.values() for n in runs]
    failed_runs = []
    for name in needed:
        name, seconds, status = mf.run_one(args.build, work, name, True)
        print(f"{name:24s} {status:10s} {seconds:6.1f} s", flush=True)
        if status != "ok":
            failed_runs.append(name)
    if failed_runs:
        print("check_tables: runs failed: " + ", ".join(failed_runs) + f" (logs in {work})", file=sys.stderr)
        return 2
    runs = {n: mf.Run(work, n) for n in needed}
    generated = {name: function(runs) for name, (_, function) in BLOCKS.items()}

    found, differing = set(), []
    for file in sorted(os.listdir(DOCS)):
        if not file.endswith(".md"):
            continue
        path = os.path.join(DOCS, file)
        with open(path) as f:
            text = f.read()

        def replace(match):
            name = match.group("name")
            if name not in generated:
                differing.append(f"{file}: unknown generated block '{name}'")
                return match.group(0)
            found.add(name)
            body = match.group("body")
            wanted = generated[name].rstrip("\n") + "\n"
            if body != wanted:
                differing.append(f"{file}: block '{name}' differs from what the code produces")
                sys.stdout.writelines(difflib.unified_diff(body.splitlines(True), wanted.splitlines(True),
                                                           f"docs/{file} ({name})", "generated"))
            return match.group(1) + wanted + match.group(4)

        new_text = BLOCK.sub(replace, text)
        if args.update and new_text != text:
            with open(path, "w") as f:
                f.write(new_text)
            print(f"updated docs/{file}")
    for name in generated:
        if name not in found:
            differing.append(f"no block '{name}' in docs/*.md")
    if differing and not args.update:
        print("\n".join(differing), file=sys.stderr)
        print("check_tables: docs/ is stale; rerun with --update and review the diff", file=sys.stderr)
        return 1
    if not differing:
        print("check_tables: every generated table in docs/ matches the code")
    return 0


if __name__ == "__main__":
    sys.exit(main())
