#!/usr/bin/env bash
# Writes the seed corpora of the libFuzzer targets (scripts/fuzz.sh, docs/robustness.md) into
# DIR/<target>/ from the files they are made of, so that they never drift from them:
#   scene  every example scene (apps/scenes/*.toml) and every bad-input scene of the
#          catalogue (tests/bad_inputs/*.toml, as bad_<name>.toml);
#   msh    the catalogue's meshes (tests/bad_inputs/meshes/*.msh) and the hand-written
#          seeds in fuzz/corpus/msh (inputs that exist nowhere else, e.g. a binary MSH 4.1);
#   soup   the hand-written seeds in fuzz/corpus/soup.
#   scripts/fuzz_corpus.sh [DIR]     (default: build-fuzz/seeds; DIR is emptied first)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/build-fuzz/seeds}
rm -rf "$out/scene" "$out/msh" "$out/soup"
mkdir -p "$out/scene" "$out/msh" "$out/soup"
shopt -s nullglob
for scene in "$root"/apps/scenes/*.toml; do cp "$scene" "$out/scene/"; done
for scene in "$root"/tests/bad_inputs/*.toml; do cp "$scene" "$out/scene/bad_$(basename "$scene")"; done
for mesh in "$root"/tests/bad_inputs/meshes/*.msh "$root"/fuzz/corpus/msh/*; do cp "$mesh" "$out/msh/"; done
for seed in "$root"/fuzz/corpus/soup/*; do cp "$seed" "$out/soup/"; done
for target in scene msh soup; do
  count=$(find "$out/$target" -type f | wc -l)
  [ "$count" -gt 0 ] || { echo "fuzz_corpus.sh: no seeds for $target" >&2; exit 1; }
  echo "fuzz_corpus.sh: $target: $count seeds in $out/$target"
done
