#!/usr/bin/env bash
# The distributed run's contract (docs/parallel.md): `mpirun -np N stagger run` gives the
# same bits as the serial run. Runs SCENE serially (no mpirun) and on each rank count, then
# compares history.csv and summary.json (timings and the rank count aside) and every dump:
# on more than one rank the per-rank pieces of each .pvtu against the serial .vtu, zone by
# zone (COMPARE_PIECES), and the .pvd series; on 3 ranks also the gathered dumps
# (output.gather_dumps), which are the serial .vtu files byte for byte.
# usage: compare_ranks.sh STAGGER SCENE WORKDIR "RANKS..." COMPARE_PIECES [--set KEY=VALUE]...
set -euo pipefail
stagger=$1 scene=$2 work=$3 ranks=$4 compare_pieces=$5
shift 5
rm -rf "$work"
mkdir -p "$work"
# CI runs as root; oversubscription: more ranks than cores; yield when idle (shared cores).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1
"$stagger" run "$scene" --quiet --out "$work/serial" "$@" > "$work/serial.log" 2>&1 ||
  { cat "$work/serial.log"; echo "serial run failed"; exit 1; }
strip_timings() { grep -v -E '"(wall_seconds|loop_seconds|zone_cycles_per_second|ranks|threads)"' "$1"; }
status=0
# compare RANKS OUT KIND: KIND is "pieces" (a .pvtu per dump) or "files" (one .vtu per dump)
compare() {
  local n=$1 out=$2 kind=$3 count=0
  grep -q "\"ranks\": $n," "$out/summary.json" || { echo "FAIL: $n ranks: summary.json does not report ranks = $n"; status=1; }
  cmp "$work/serial/history.csv" "$out/history.csv" || { echo "FAIL: $n ranks: history.csv differs"; status=1; }
  diff <(strip_timings "$work/serial/summary.json") <(strip_timings "$out/summary.json") ||
    { echo "FAIL: $n ranks: summary.json differs"; status=1; }
  for f in "$work/serial"/*.vtu; do
    local name
    name=$(basename "$f" .vtu)
    if [ "$kind" = pieces ]; then
      "$compare_pieces" "$f" "$out/$name.pvtu" "$n" || { echo "FAIL: $n ranks: $name.pvtu differs"; status=1; }
      for r in $(seq 0 $((n - 1))); do
        [ -f "$out/${name}_r$(printf %04d "$r").vtu" ] || { echo "FAIL: $n ranks: piece $r of $name missing"; status=1; }
      done
    else
      cmp "$f" "$out/$name.vtu" || { echo "FAIL: $n ranks: $name.vtu differs"; status=1; }
    fi
    count=$((count + 1))
  done
  local pvd
  pvd=$(basename "$work/serial"/*.pvd)
  if [ "$kind" = pieces ]; then
    diff <(sed 's/\.vtu"/.pvtu"/' "$work/serial/$pvd") "$out/$pvd" || { echo "FAIL: $n ranks: $pvd differs"; status=1; }
  else
    cmp "$work/serial/$pvd" "$out/$pvd" || { echo "FAIL: $n ranks: $pvd differs"; status=1; }
  fi
  [ "$count" -ge 2 ] || { echo "FAIL: only $count dumps to compare"; status=1; }
  echo "$n ranks ($kind): history.csv, summary.json, the .pvd and $count dumps identical to the serial run"
}
run_ranks() {  # run_ranks RANKS OUT [--set ...]
  local n=$1 out=$2
  shift 2
  if ! mpirun --oversubscribe -np "$n" "$stagger" run "$scene" --quiet --out "$out" "$@" > "$out.log" 2>&1; then
    cat "$out.log"
    echo "FAIL: $n ranks: the run failed"
    status=1
    return 1
  fi
}
for n in $ranks; do
  kind=pieces
  [ "$n" = 1 ] && kind=files  # one rank is a serial run
  run_ranks "$n" "$work/np$n" "$@" && compare "$n" "$work/np$n" "$kind"
  if [ "$n" = 3 ]; then
    run_ranks 3 "$work/np3-gather" "$@" --set output.gather_dumps=true && compare 3 "$work/np3-gather" files
  fi
done
exit $status
