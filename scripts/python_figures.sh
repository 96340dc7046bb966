#!/usr/bin/env bash
# The Python example's figure and table (docs/python.md, "Example"): runs
# apps/examples/python/convergence.py with the build tree's package on one thread.
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}" OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}" \
  /usr/bin/python3 apps/examples/python/convergence.py docs/figures/python_convergence.png
