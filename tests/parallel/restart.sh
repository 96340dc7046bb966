#!/usr/bin/env bash
# Checkpoints of a distributed run (docs/output.md): a restart on the same number of ranks
# continues bit for bit, and another number of ranks (or a serial run) is one clear error.
# Runs SCENE on 2 ranks with a checkpoint every 60 cycles, restarts its last checkpoint into
# another directory, and compares history.csv, summary.json and the last dump's pieces.
# usage: restart.sh STAGGER SCENE WORKDIR [--set KEY=VALUE]... (after the defaults below)
set -euo pipefail
stagger=$1 scene=$2 work=$3
shift 3
rm -rf "$work"
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1
sets=(--set mesh.nx=16 --set mesh.ny=16 --set time.end=0.3 --set output.dump_interval=0.1
  --set output.checkpoint_every_cycles=60 --set output.checkpoint_every_seconds=0 "$@")
status=0
mpirun -np 2 "$stagger" run "$scene" --quiet --out "$work/whole" "${sets[@]}" > "$work/whole.log" 2>&1 ||
  { cat "$work/whole.log"; echo "FAIL: the uninterrupted run failed"; exit 1; }
manifest=$(ls "$work/whole"/*.checkpoint)
grep -q '^ranks 2$' "$manifest" || { echo "FAIL: the manifest does not say 2 ranks"; cat "$manifest"; exit 1; }
cycle=$(sed -n 's/^cycle //p' "$manifest")
cycles=$(sed -n 's/.*"cycles": \([0-9]*\),.*/\1/p' "$work/whole/summary.json")
[ "$cycle" -gt 0 ] && [ "$cycle" -lt "$cycles" ] || { echo "FAIL: checkpoint at cycle $cycle of $cycles"; exit 1; }
mpirun -np 2 "$stagger" run "$scene" --quiet --out "$work/resumed" "${sets[@]}" --restart "$manifest" \
  > "$work/resumed.log" 2>&1 || { cat "$work/resumed.log"; echo "FAIL: the restart failed"; exit 1; }
strip_timings() { grep -v -E '"(wall_seconds|loop_seconds|zone_cycles_per_second)"' "$1"; }
cmp "$work/whole/history.csv" "$work/resumed/history.csv" || { echo "FAIL: history.csv differs"; status=1; }
diff <(strip_timings "$work/whole/summary.json") <(strip_timings "$work/resumed/summary.json") ||
  { echo "FAIL: summary.json differs"; status=1; }
last=$(ls "$work/resumed"/*.pvtu | tail -1)
[ -n "$last" ] || { echo "FAIL: the restart wrote no dump"; exit 1; }
for f in "$last" "${last%.pvtu}"_r*.vtu; do
  cmp "$f" "$work/whole/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; status=1; }
done
echo "restart from cycle $cycle of $cycles on 2 ranks: history, summary and $(basename "$last") identical"
# Another number of ranks, and a serial run: one error line each, naming the rank count.
expect_error() {
  local name=$1 pattern=$2
  shift 2
  if "$@" > "$work/$name.out" 2> "$work/$name.err"; then echo "FAIL: $name: the restart succeeded"; status=1; return; fi
  local lines
  lines=$(grep -c '^stagger: error:' "$work/$name.err" || true)
  [ "$lines" = 1 ] || { echo "FAIL: $name: $lines error lines"; cat "$work/$name.err"; status=1; }
  grep -q -- "$pattern" "$work/$name.err" || { echo "FAIL: $name: no '$pattern' in:"; cat "$work/$name.err"; status=1; }
}
expect_error np3 "was written by a run on 2 ranks; restart it on as many (mpirun -np 2), not 3" \
  mpirun -np 3 "$stagger" run "$scene" --quiet --out "$work/np3" "${sets[@]}" --restart "$manifest"
expect_error serial "was written by a run on 2 ranks; restart it on as many (mpirun -np 2), not serially" \
  "$stagger" run "$scene" --quiet --out "$work/serial" "${sets[@]}" --restart "$manifest"
[ $status = 0 ] && echo "3 ranks and a serial run refuse the 2-rank checkpoint with one error line"
exit $status
