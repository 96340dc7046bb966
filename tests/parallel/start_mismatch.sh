#!/usr/bin/env bash
# Ranks started otherwise than rank 0 (docs/parallel.md, "Ranks started alike"): another
# scene text, other --set values or another --out end every rank with ONE error line naming
# the rank (it used to be silently different physics, or a deadlock); `stagger check` under
# mpirun reports once, from rank 0.
# usage: start_mismatch.sh STAGGER SCENES_DIR WORKDIR
set -euo pipefail
stagger=$1 scenes=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1
status=0
small=(--set mesh.nx=40 --set time.end=0.01 --quiet)
sed 's/gamma = 1.4/gamma = 1.6/' "$scenes/sod.toml" > "$work/sod_other.toml"
cp "$scenes/sod.toml" "$work/sod_same.toml"
# Runs mpirun with the MPMD arguments given (rank 0 : rank 1); it must fail within 120 s with
# one error line containing EXPECTED.
mismatch() {
  local name=$1 expected=$2
  shift 2
  local code=0
  timeout 120 mpirun --oversubscribe "$@" > "$work/$name.out" 2> "$work/$name.err" || code=$?
  [ "$code" != 0 ] || { echo "FAIL: $name: the run succeeded"; status=1; return; }
  [ "$code" != 124 ] || { echo "FAIL: $name: hung (killed after 120 s)"; status=1; return; }
  local lines
  lines=$(grep -c '^stagger: error:' "$work/$name.err" || true)
  [ "$lines" = 1 ] || { echo "FAIL: $name: $lines error lines:"; cat "$work/$name.err"; status=1; }
  grep -q -F -- "$expected" "$work/$name.err" ||
    { echo "FAIL: $name: no '$expected' in:"; cat "$work/$name.err"; status=1; }
  echo "$name: $(grep '^stagger: error:' "$work/$name.err" | cut -c1-200)"
}
mismatch scene "rank 1 of 2 was started with a scene file whose text differs from rank 0's" \
  -np 1 "$stagger" run "$scenes/sod.toml" "${small[@]}" --out "$work/a" : \
  -np 1 "$stagger" run "$work/sod_other.toml" "${small[@]}" --out "$work/a"
mismatch set "rank 1 of 2 was started with --set values that differ from rank 0's" \
  -np 1 "$stagger" run "$scenes/sod.toml" "${small[@]}" --out "$work/b" : \
  -np 1 "$stagger" run "$scenes/sod.toml" "${small[@]}" --set numerics.cfl=0.3 --out "$work/b"
mismatch out "rank 2 of 3 was started with output settings (--out, --restart, --replace) that differ" \
  -np 2 "$stagger" run "$scenes/sod.toml" "${small[@]}" --out "$work/c" : \
  -np 1 "$stagger" run "$scenes/sod.toml" "${small[@]}" --out "$work/c2"
mismatch check "rank 1 of 2 was started with --set values that differ" \
  -np 1 "$stagger" check "$scenes/sod.toml" --set time.end=0.1 : -np 1 "$stagger" check "$scenes/sod.toml"
# The same text under another name is the same scene: the run completes.
timeout 120 mpirun --oversubscribe -np 1 "$stagger" run "$scenes/sod.toml" "${small[@]}" --out "$work/d" : \
  -np 1 "$stagger" run "$work/sod_same.toml" "${small[@]}" --out "$work/d" > "$work/same.out" 2> "$work/same.err" ||
  { echo "FAIL: same: the run with the same text failed:"; cat "$work/same.err"; status=1; }
# `stagger check` on 2 ranks: one report, from rank 0.
timeout 120 mpirun --oversubscribe -np 2 "$stagger" check "$scenes/sod.toml" > "$work/check.out" 2> "$work/check.err" ||
  { echo "FAIL: check: failed:"; cat "$work/check.err"; status=1; }
reports=$(grep -c '^scene is valid' "$work/check.out" || true)
[ "$reports" = 1 ] || { echo "FAIL: check: $reports reports on 2 ranks"; status=1; }
# A check error on 2 ranks: one line.
if timeout 120 mpirun --oversubscribe -np 2 "$stagger" check "$scenes/sod.toml" --set numerics.cfl=2 \
  > "$work/check_error.out" 2> "$work/check_error.err"; then
  echo "FAIL: check_error: succeeded"; status=1
fi
lines=$(grep -c '^stagger: error:' "$work/check_error.err" || true)
[ "$lines" = 1 ] || { echo "FAIL: check_error: $lines error lines:"; cat "$work/check_error.err"; status=1; }
echo "check: $reports report(s); check_error: $lines error line(s)"
exit $status
