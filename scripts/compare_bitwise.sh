#!/usr/bin/env bash
# Bitwise comparison of two stagger binaries over the example scenes.
#
#   scripts/compare_bitwise.sh BIN_A BIN_B [SCENE.toml...]
#
# Runs every scene of apps/scenes/ (or the scenes given) with both binaries on one thread
# and compares what a run produces: history.csv (every recorded cycle's time, dt and
# energies), summary.json without its wall-clock fields (cycles, final energies, error
# norms, status), the .pvd collection and every .vtu dump byte for byte (the final fields;
# the writer is deterministic). Checkpoints are not compared: they carry the wall clock.
# Prints one line per scene, SAME or DIFF (with what differs), and exits 1 on any DIFF.
# Set KEEP=DIR to keep the outputs in DIR (default: a temporary directory, removed).
set -u

if [ $# -lt 2 ]; then
  echo "usage: $0 BIN_A BIN_B [SCENE.toml...]" >&2
  exit 2
fi
bin_a=$(realpath "$1")
bin_b=$(realpath "$2")
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -gt 0 ]; then
  scenes=("$@")
else
  scenes=("$root"/apps/scenes/*.toml)
fi
for b in "$bin_a" "$bin_b"; do
  [ -x "$b" ] || { echo "$0: not an executable: $b" >&2; exit 2; }
done

if [ -n "${KEEP:-}" ]; then
  work=$KEEP
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi

# summary.json without the fields that measure the machine rather than the run.
strip_summary() {
  python3 - "$1" <<'EOF'
import json, sys
with open(sys.argv[1]) as f:
    s = json.load(f)
for key in ("wall_seconds", "loop_seconds", "zone_cycles_per_second", "threads"):
    s.pop(key, None)
print(json.dumps(s, sort_keys=True, indent=1))
EOF
}

status=0
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .toml)
  for side in a b; do
    bin=$bin_a
    [ $side = b ] && bin=$bin_b
    out="$work/$side/$name"
    rm -rf "$out"
    mkdir -p "$out"
    OMP_NUM_THREADS=1 "$bin" run "$scene" --out "$out" --threads 1 --quiet 2>"$out.stderr"
    echo $? >"$out.rc"
  done
  a="$work/a/$name"
  b="$work/b/$name"
  why=()
  cmp -s "$a.rc" "$b.rc" || why+=("exit status $(cat "$a.rc") vs $(cat "$b.rc")")
  cmp -s "$a.stderr" "$b.stderr" || why+=("stderr")
  if [ -f "$a/summary.json" ] && [ -f "$b/summary.json" ]; then
    cmp -s <(strip_summary "$a/summary.json") <(strip_summary "$b/summary.json") || why+=("summary.json")
  elif [ -f "$a/summary.json" ] || [ -f "$b/summary.json" ]; then
    why+=("summary.json missing on one side")
  fi
  # Every history, collection and dump, present on both sides with the same bytes.
  files_a=$(cd "$a" && ls | grep -E '\.(csv|pvd|vtu)$' | sort)
  files_b=$(cd "$b" && ls | grep -E '\.(csv|pvd|vtu)$' | sort)
  [ "$files_a" = "$files_b" ] || why+=("different output files")
  ndiff=0
  for f in $files_a; do
    [ -f "$b/$f" ] || continue
    if ! cmp -s "$a/$f" "$b/$f"; then
      ndiff=$((ndiff + 1))
      [ $ndiff -le 3 ] && why+=("$f")
    fi
  done
  [ $ndiff -gt 3 ] && why+=("... $ndiff files in all")
  if [ ${#why[@]} -eq 0 ]; then
    nvtu=$(echo "$files_a" | grep -c '\.vtu$')
    cycles=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1])).get('cycles'))" "$a/summary.json" 2>/dev/null)
    printf '%-14s SAME (%s cycles, %s dumps)\n' "$name" "$cycles" "$nvtu"
  else
    printf '%-14s DIFF: %s\n' "$name" "$(IFS=,; echo "${why[*]}")"
    status=1
  fi
done
exit $status
