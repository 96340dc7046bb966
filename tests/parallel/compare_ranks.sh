#!/usr/bin/env bash
# The distributed run's contract (docs/parallel.md): `mpirun -np N stagger run` gives the
# same bits as the serial run. Runs SCENE serially (no mpirun) and on each rank count, then
# compares history.csv and summary.json (timings and the rank count aside) and every .vtu
# dump byte for byte.
# usage: compare_ranks.sh STAGGER SCENE WORKDIR "RANKS..." [--set KEY=VALUE]...
set -euo pipefail
stagger=$1 scene=$2 work=$3 ranks=$4
shift 4
rm -rf "$work"
mkdir -p "$work"
# CI runs as root; oversubscription: more ranks than cores; yield when idle (shared cores).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1
"$stagger" run "$scene" --quiet --out "$work/serial" "$@" > "$work/serial.log" 2>&1 ||
  { cat "$work/serial.log"; echo "serial run failed"; exit 1; }
strip_timings() { grep -v -E '"(wall_seconds|loop_seconds|zone_cycles_per_second|ranks|threads)"' "$1"; }
status=0
for n in $ranks; do
  out="$work/np$n"
  if ! mpirun --oversubscribe -np "$n" "$stagger" run "$scene" --quiet --out "$out" "$@" > "$work/np$n.log" 2>&1; then
    cat "$work/np$n.log"
    echo "FAIL: $n ranks: the run failed"
    status=1
    continue
  fi
  grep -q "\"ranks\": $n," "$out/summary.json" || { echo "FAIL: $n ranks: summary.json does not report ranks = $n"; status=1; }
  cmp "$work/serial/history.csv" "$out/history.csv" || { echo "FAIL: $n ranks: history.csv differs"; status=1; }
  diff <(strip_timings "$work/serial/summary.json") <(strip_timings "$out/summary.json") ||
    { echo "FAIL: $n ranks: summary.json differs"; status=1; }
  count=0
  for f in "$work/serial"/*.vtu "$work/serial"/*.pvd; do
    cmp "$f" "$out/$(basename "$f")" || { echo "FAIL: $n ranks: $(basename "$f") differs"; status=1; }
    count=$((count + 1))
  done
  [ "$count" -ge 3 ] || { echo "FAIL: only $count dump files to compare"; status=1; }
  echo "$n ranks: history.csv, summary.json and $count dump files identical to the serial run"
done
exit $status
