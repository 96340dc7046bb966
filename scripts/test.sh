#!/usr/bin/env bash
# Quick start, part 2: install, build, and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
cd build
# One OpenMP thread per test: ctest runs tests in parallel; tests that check thread
# determinism set their own thread counts.
OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}" ctest --output-on-failure -j "$(nproc)" --timeout 600
