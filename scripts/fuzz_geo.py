#!/usr/bin/env python3
"""Random-mutation fuzzing of .geo text through `stagger mesh` (docs/robustness.md, section 3).

Mutates the repository's .geo files (byte flips, deleted and repeated spans, splices, and
inserted gmsh words, including the commands stagger refuses) and runs each result through
the real command line, which meshes it in gmsh's child process. What must hold for every
input: stagger exits 0 (a mesh report) or 1 with exactly one 'stagger: error:' line; it is
never killed by a signal, never hangs (the gmsh time limit is 5 s, the outer limit 60 s),
and nothing is written into the working directory (the scan and the sandbox).

    nice -n 19 scripts/fuzz_geo.py SECONDS [--stagger build/bin/stagger] [--work DIR]

Findings are copied to WORK/findings/ with the command's output; the exit status is 1 if
there are any.
"""
import argparse
import os
import random
import shutil
import subprocess
import sys
import time

WORDS = [
    b"Point(newp) = {0.5, 0.5, 0, 0.1};", b"Line(newl) = {1, 3};", b"Curve Loop(9) = {1, 2};",
    b"Plane Surface(newreg) = {1};", b"Physical Surface(\"x\") = {1};", b"Physical Curve(\"w\") = {1, 2};",
    b"Transfinite Surface{:};", b"Transfinite Curve{:} = 1e6;", b"Recombine Surface{:};",
    b"Mesh.Algorithm = 8;", b"MeshAlgorithm Surface{1} = 8;", b"Mesh.CharacteristicLengthMax = 1e-5;",
    b"Extrude {0, 0, 1} { Surface{1}; }", b"Rotate {{1, 0, 0}, {0, 0, 0}, Pi/2} { Surface{:}; }",
    b"For i In {1:1e9} a = i; EndFor", b"Sleep 100;", b"Exit;", b"SystemCall \"touch pwned\";",
    b"Printf(\"x\") > \"pwned\";", b"Save \"pwned.msh\";", b"Merge \"pwned.py\";", b"CreateDir \"pwned_dir\";",
    b"Include \"nowhere.geo\";", b"Include StrCat(\"a\", \"b\");", b"a[] = {1:1e8};", b"Delete Model;",
    b"SetFactory(\"OpenCASCADE\");", b"Rectangle(100) = {0, 0, 0, 1, 1};", b"Disk(101) = {0, 0, 0, 1};",
    b"BooleanFragments{ Surface{:}; Delete; }{}", b"Coherence;", b"Mesh 2;", b"RefineMesh;",
    b"Physical Surface(1) = {};", b"Point(1) = {0, 0, 1e308};", b"Point(2) = {NaN, 0, 0};",
    b"//", b"/*", b"\"", b"'", b"{", b"}", b"(", b")", b";", b"1e308", b"-1", b"0", b"Pi",
]


def mutate(data, seeds, rng):
    data = bytearray(data)
    for _ in range(rng.randint(1, 3)):
        choice = rng.random()
        if choice < 0.1 and data:
            at = rng.randrange(len(data))
            data[at] = rng.randrange(256)
        elif choice < 0.3 and data:
            a = rng.randrange(len(data))
            b = min(len(data), a + rng.randint(1, 80))
            del data[a:b]
        elif choice < 0.45 and data:
            a = rng.randrange(len(data))
            b = min(len(data), a + rng.randint(1, 80))
            data[a:a] = data[a:b]
        elif choice < 0.6:
            other = rng.choice(seeds)
            if other:
                a = rng.randrange(len(other))
                b = min(len(other), a + rng.randint(1, 200))
                at = rng.randrange(len(data) + 1)
                data[at:at] = other[a:b]
        else:
            at = rng.randrange(len(data) + 1)
            data[at:at] = b"\n" + rng.choice(WORDS) + b"\n"
    return bytes(data[:8192])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("seconds", type=float)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--stagger", default=os.path.join(root, "build", "bin", "stagger"))
    parser.add_argument("--work", default=os.path.join(root, "build", "fuzz-geo"))
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    seeds = []
    for folder in ("geometries", "tests/bad_inputs/meshes"):
        for name in sorted(os.listdir(os.path.join(root, folder))):
            if name.endswith(".geo"):
                with open(os.path.join(root, folder, name), "rb") as f:
                    seeds.append(f.read())
    shutil.rmtree(args.work, ignore_errors=True)
    work = os.path.join(args.work, "run")
    findings = os.path.join(args.work, "findings")
    os.makedirs(work)
    os.makedirs(findings)
    # Included files of the seeds (relative includes resolve next to the input).
    for folder in ("tests/bad_inputs/meshes",):
        shutil.copy(os.path.join(root, folder, "unit_square.geo"), work)
    allowed = set(os.listdir(work)) | {"input.geo"}
    counts = {"runs": 0, "meshed": 0, "errors": 0, "findings": 0}
    kinds = {}
    stop = time.monotonic() + args.seconds
    slowest = 0.0
    while time.monotonic() < stop:
        data = mutate(rng.choice(seeds), seeds, rng)
        path = os.path.join(work, "input.geo")
        with open(path, "wb") as f:
            f.write(data)
        start = time.monotonic()
        problem = None
        try:
            result = subprocess.run(
                [args.stagger, "mesh", "input.geo", "--gmsh-time-limit", "5", "--gmsh-memory-limit", "2048"],
                cwd=work, capture_output=True, timeout=60, stdin=subprocess.DEVNULL)
            err = result.stderr.decode(errors="replace")
            if result.returncode < 0:
                problem = "stagger killed by signal %d" % -result.returncode
            elif result.returncode == 0:
                counts["meshed"] += 1
                if b" zones (" not in result.stdout:
                    problem = "exit 0 without a mesh report"
            elif result.returncode == 1:
                counts["errors"] += 1
                lines = err.splitlines()
                if len(lines) != 1 or not lines[0].startswith("stagger: error: "):
                    problem = "exit 1 without exactly one error line"
                else:
                    kind = " ".join(lines[0].split()[2:5])
                    kinds[kind] = kinds.get(kind, 0) + 1
            else:
                problem = "exit status %d" % result.returncode
            output = result.stdout.decode(errors="replace") + "\n--- stderr\n" + err
        except subprocess.TimeoutExpired:
            problem, output = "hang (60 s)", ""
        slowest = max(slowest, time.monotonic() - start)
        extra = set(os.listdir(work)) - allowed
        if extra:
            problem = (problem + "; " if problem else "") + "wrote files: " + ", ".join(sorted(extra))
            for name in extra:
                target = os.path.join(work, name)
                shutil.rmtree(target, ignore_errors=True) if os.path.isdir(target) else os.remove(target)
        counts["runs"] += 1
        if problem:
            counts["findings"] += 1
            base = os.path.join(findings, "finding-%d" % counts["findings"])
            with open(base + ".geo", "wb") as f:
                f.write(data)
            with open(base + ".txt", "w") as f:
                f.write(problem + "\n" + output)
            print("finding %d: %s" % (counts["findings"], problem), flush=True)
    print("runs %(runs)d, meshed %(meshed)d, clean errors %(errors)d, findings %(findings)d" % counts)
    print("slowest input %.1f s" % slowest)
    for kind, n in sorted(kinds.items(), key=lambda item: -item[1])[:12]:
        print("  %6d  %s" % (n, kind))
    return 1 if counts["findings"] else 0


if __name__ == "__main__":
    sys.exit(main())
