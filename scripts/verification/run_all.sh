#!/usr/bin/env bash
# Regenerates the verification figures and tables of docs/verification.md:
#   bash scripts/verification/run_all.sh [make_figures.py options, e.g. --rerun, --jobs 2]
# Builds stagger-profile (in $STAGGER_BUILD, default build/), runs every verification scene
# with it (results in $STAGGER_BUILD/verification/, reused unless --rerun) and writes
# docs/figures/verif_*.png and docs/figures/verif_results.md. About 10 minutes on one core.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${STAGGER_BUILD:-$root/build}"
if [ ! -f "$build/build.ninja" ] && [ ! -f "$build/Makefile" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSTAGGER_BUILD_TESTS=OFF
fi
cmake --build "$build" --target stagger_profile -- -j2

# A Python with matplotlib and numpy: the system one (python3-matplotlib) if the first
# python3 on PATH lacks them (e.g. a pyenv shim).
python=""
for candidate in "${PYTHON:-}" python3 /usr/bin/python3; do
  [ -n "$candidate" ] || continue
  if "$candidate" -c "import matplotlib, numpy" 2>/dev/null; then python="$candidate"; break; fi
done
if [ -z "$python" ]; then
  echo "run_all.sh: no python3 with matplotlib and numpy (apt-get install python3-matplotlib)" >&2
  exit 1
fi
exec "$python" "$root/scripts/verification/make_figures.py" --build "$build" --work "$build/verification" "$@"
