#!/usr/bin/env bash
# Errors of a distributed run (docs/parallel.md): reported once, by rank 0, with the serial
# run's message, and every rank stops (no hang: ctest's timeout would catch one).
# usage: errors.sh STAGGER SCENES_DIR WORKDIR
set -euo pipefail
stagger=$1 scenes=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1
status=0
# Runs the case serially and on 3 ranks; both must fail with the same single error line.
check() {
  local name=$1
  shift
  if "$stagger" run "$@" --quiet --out "$work/$name-serial" > "$work/$name-serial.out" 2> "$work/$name-serial.err"; then
    echo "FAIL: $name: the serial run succeeded"; status=1; return
  fi
  if mpirun --oversubscribe -np 3 "$stagger" run "$@" --quiet --out "$work/$name-np3" > "$work/$name-np3.out" \
    2> "$work/$name-np3.err"; then
    echo "FAIL: $name: the 3-rank run succeeded"; status=1; return
  fi
  local lines
  lines=$(grep -c '^stagger: error:' "$work/$name-np3.err" || true)
  [ "$lines" = 1 ] || { echo "FAIL: $name: $lines error lines on 3 ranks:"; cat "$work/$name-np3.err"; status=1; }
  # (the output directory named in the message aside, and the last dump: a .pvtu on 3 ranks)
  if ! diff <(grep '^stagger: error:' "$work/$name-serial.err" | sed "s#$name-serial#OUT#g") \
    <(grep '^stagger: error:' "$work/$name-np3.err" | sed "s#$name-np3#OUT#g; s#\.pvtu'#.vtu'#g"); then
    echo "FAIL: $name: the 3-rank error differs from the serial one"; status=1
  fi
  echo "$name: $(grep '^stagger: error:' "$work/$name-np3.err" | cut -c1-150)"
}
# A scene error (every rank meets it while reading the scene).
check scene "$scenes/sod.toml" --set numerics.cfl=2
# A run that stops: the time step collapses; the message names the limiting zone, which one
# rank owns, by its serial number.
check collapse "$scenes/sedov.toml" --set mesh.nx=12 --set mesh.ny=12 --set numerics.dt_min=2.7e-3
grep -q "limiting zone" "$work/collapse-np3.err" || { echo "FAIL: collapse: no limiting zone named"; status=1; }
cmp "$work/collapse-serial/history.csv" "$work/collapse-np3/history.csv" ||
  { echo "FAIL: collapse: history.csv differs"; status=1; }
# A distributed checkpoint with a damaged piece (truncated, missing, or another rank's): the
# restart stops every rank with one error line naming the piece; nothing dies inside MPI (a
# rank that read a bad piece used to leave the others alone in the restore's collectives:
# MPI_ERR_TRUNCATE).
sedov=("$scenes/sedov.toml" --set mesh.nx=12 --set mesh.ny=12 --set time.end=0.2 --set output.checkpoint_every_cycles=20)
mpirun --oversubscribe -np 3 "$stagger" run "${sedov[@]}" --quiet --out "$work/pieces" > /dev/null 2>&1 ||
  { echo "FAIL: pieces: the checkpointed run failed"; status=1; }
parity=$(grep -a '^set ' "$work/pieces/sedov.checkpoint" | cut -d' ' -f2)  # the manifest's set
for damage in truncated missing foreign; do
  rm -rf "$work/damaged" "$work/restart-$damage"
  cp -r "$work/pieces" "$work/damaged"
  piece="$work/damaged/sedov.checkpoint.$parity.r0001"
  case $damage in
    truncated) truncate -s 1000 "$piece" ;;
    missing) rm "$piece" ;;
    foreign) cp "$work/damaged/sedov.checkpoint.$parity.r0000" "$piece" ;;
  esac
  if mpirun --oversubscribe -np 3 "$stagger" run "${sedov[@]}" --quiet --out "$work/restart-$damage" \
    --restart "$work/damaged/sedov.checkpoint" > "$work/$damage.out" 2> "$work/$damage.err"; then
    echo "FAIL: $damage piece: the restart succeeded"; status=1; continue
  fi
  lines=$(grep -c '^stagger: error:' "$work/$damage.err" || true)
  [ "$lines" = 1 ] || { echo "FAIL: $damage piece: $lines error lines:"; cat "$work/$damage.err"; status=1; }
  grep -q 'MPI_ERR' "$work/$damage.err" && { echo "FAIL: $damage piece: an MPI error"; status=1; }
  grep '^stagger: error:' "$work/$damage.err" | grep -q "r0001" ||
    { echo "FAIL: $damage piece: the error does not name the piece"; cat "$work/$damage.err"; status=1; }
  echo "$damage piece: $(grep '^stagger: error:' "$work/$damage.err" | cut -c1-150)"
done
exit $status
