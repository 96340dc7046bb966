#!/usr/bin/env bash
# The Lagrangian step's speed on one problem, for two or more stagger binaries
# (docs/benchmarks.md, "Lagrangian step speed"). Builds nothing.
#
#   scripts/step_speed.sh time BIN_A BIN_B [BIN...]   # paired wall-clock runs, medians
#   scripts/step_speed.sh instructions BIN [BIN...]   # callgrind instructions per zone-cycle
#
# time: ROUNDS rounds (default 3); each round runs every binary once per thread count
# (THREADS, default "1 2"), in turn, on apps/bench/gauss_540.toml (540 x 540, CYCLES = 376
# cycles), and prints each binary's median M zone-cycles/s per thread count and its ratio to
# the first binary's. The stepping loop only is timed (stagger bench --one).
# instructions: one thread, the same scene at SIZE x SIZE (default 200) for CG_CYCLES cycles
# (default 60) under valgrind --tool=callgrind, counting inside Simulation::Impl::step only;
# prints the step's total and each function's own instructions per zone-cycle (the functions
# above 0.5 per zone-cycle).
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
scene=$root/apps/bench/gauss_540.toml
mode=${1:-}
shift || true
[ $# -ge 1 ] || { sed -n 2,16p "$0" >&2; exit 2; }
for b in "$@"; do [ -x "$b" ] || { echo "$0: not an executable: $b" >&2; exit 2; }; done

# One run: prints M zone-cycles/s.
run_once() {
  OMP_NUM_THREADS=$2 "$1" bench --one --scene "$scene" --threads "$2" --cycles "${CYCLES:-376}" --target |
    awk -F'\t' '$1 == "status" && $2 != "completed" {bad = 1} $1 == "zone_cycles_per_second" {v = $2 / 1e6}
                END {if (bad || v == "") print "nan"; else printf "%.3f\n", v}'
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

case "$mode" in
  time)
    rounds=${ROUNDS:-3}
    threads=${THREADS:-1 2}
    out=$(mktemp -d)
    for r in $(seq "$rounds"); do
      for t in $threads; do
        i=0
        for b in "$@"; do
          v=$(run_once "$b" "$t")
          echo "$v" >> "$out/$i.$t"
          echo "round $r, $t thread(s), $b: $v Mzc/s" >&2
          i=$((i + 1))
        done
      done
    done
    printf '| binary | threads | runs (M zone-cycles/s) | median | vs first |\n|---|---|---|---|---|\n'
    for t in $threads; do
      first=$(median < "$out/0.$t")
      i=0
      for b in "$@"; do
        m=$(median < "$out/$i.$t")
        printf '| %s | %s | %s | %s | %.3f |\n' "$b" "$t" "$(paste -sd' ' "$out/$i.$t")" "$m" \
          "$(awk -v a="$m" -v b="$first" 'BEGIN {print a / b}')"
        i=$((i + 1))
      done
    done
    rm -rf "$out"
    ;;
  instructions)
    size=${SIZE:-200}
    cycles=${CG_CYCLES:-60}
    zc=$((size * size * cycles))
    for b in "$@"; do
      f=$(mktemp)
      OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$f" \
        --toggle-collect='stagger::Simulation::Impl::step(double)' "$b" bench --one --scene "$scene" --threads 1 \
        --set mesh.nx="$size" --set mesh.ny="$size" --cycles "$cycles" --target > /dev/null 2>&1
      echo "== $b: ${size} x ${size}, $cycles cycles, instructions per zone-cycle"
      callgrind_annotate --threshold=100 "$f" 2> /dev/null |
        awk -v zc="$zc" '/PROGRAM TOTALS/ {gsub(",", "", $1); printf "%8.1f  the step (total)\n", $1 / zc}
          /\?\?\?:/ {n = $1; gsub(",", "", n); if (n / zc < 0.5) next
                     sub(/^[^?]*\?\?\?:/, ""); sub(/ \[\/.*$/, ""); printf "%8.1f  %s\n", n / zc, substr($0, 1, 110)}'
      rm -f "$f"
    done
    ;;
  *)
    sed -n 2,16p "$0" >&2
    exit 2
    ;;
esac
