#!/usr/bin/env bash
# Quick start, part 1: install, build, and run the headline scene (the Howell-Ball
# beryllium shell collapse on the gmsh quarter shell). Writes VTK output (open
# output/be_shell/be_shell.pvd in ParaView), history.csv and summary.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
./build/bin/stagger run apps/scenes/be_shell.toml --out output/be_shell "$@"
