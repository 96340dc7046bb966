#!/usr/bin/env bash
# Installs Stagger's build and test dependencies from Debian 12 packages (as root).
# Quick when everything is already installed.
set -euo pipefail
packages=(cmake ninja-build g++ pkg-config libcgal-dev libgmsh-dev libvtk9-dev libgtest-dev
          libtomlplusplus-dev libmuparser-dev libeigen3-dev python3 python3-matplotlib clang-format
          python3-dev python3-numpy python3-pybind11 python3-pytest
          libopenmpi-dev openmpi-bin libmetis-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update
  apt-get install -y "${missing[@]}"
fi
