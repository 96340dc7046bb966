#!/usr/bin/env bash
# libFuzzer targets (docs/robustness.md §3): the scene parser, the polygon-soup
# import (build_mesh) and the .msh reader. Builds the libraries with clang and
# -fsanitize=fuzzer-no-link,address,undefined in build-fuzz/, links each target in fuzz/
# with -fsanitize=fuzzer,address,undefined, and runs each for SECONDS (default 60) on a
# copy of its seed corpus (scripts/fuzz_corpus.sh writes it to build-fuzz/seeds/<target> from
# the example scenes, the bad-input catalogue and fuzz/corpus; new inputs land in
# build-fuzz/corpus/).
#   scripts/fuzz.sh [SECONDS] [TARGET...]     TARGET: scene soup msh (default: all)
# Crashes are written to build-fuzz/artifacts/<target>/; rerun one with
#   build-fuzz/fuzz/<target>_fuzzer build-fuzz/artifacts/<target>/crash-...
set -euo pipefail
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene soup msh)
root=$(cd "$(dirname "$0")/.." && pwd)
build=${STAGGER_FUZZ_BUILD:-$root/build-fuzz}
jobs=${STAGGER_JOBS:-2}
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -g"

if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTAGGER_BUILD_TESTS=OFF -DSTAGGER_WERROR=OFF \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
fi
ninja -C "$build" -j"$jobs" stagger stagger_scene stagger_meshgen

mkdir -p "$build/fuzz"
"$root/scripts/fuzz_corpus.sh" "$build/seeds"
libs=(-L"$build/lib" -L"$build/lib/src/scene" -L"$build/meshgen"
      -Wl,-rpath,"$build/lib:$build/lib/src/scene:$build/meshgen"
      -lstagger_scene -lstagger_meshgen -lstagger)
for target in "${targets[@]}"; do
  source="$root/fuzz/${target}_fuzzer.cpp"
  binary="$build/fuzz/${target}_fuzzer"
  if [ ! -x "$binary" ] || [ "$source" -nt "$binary" ] || [ "$build/lib/libstagger.so" -nt "$binary" ]; then
    clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-omit-frame-pointer \
      -I"$root/lib/include" -I"$root/meshgen/include" "$source" -o "$binary" "${libs[@]}"
  fi
done

# UBSan findings are errors (abort with a report) rather than warnings.
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
# gmsh and VTK are not instrumented; leaks in them at exit are not ours. A huge allocation
# (gmsh trusting a corrupt count) returns null -> std::bad_alloc, as in a normal build.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:allocator_may_return_null=1}
status=0
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  artifacts="$build/artifacts/$target"
  mkdir -p "$corpus" "$artifacts"
  for seed in "$build/seeds/$target/"*; do [ -e "$corpus/$(basename "$seed")" ] || cp "$seed" "$corpus/"; done
  # STAGGER_FUZZ_KEEP_GOING=1: fork mode, record every crash/timeout and go on.
  keep_going=()
  [ "${STAGGER_FUZZ_KEEP_GOING:-0}" = 1 ] && keep_going=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  dictionary=()
  [ -f "$root/fuzz/$target.dict" ] && dictionary=(-dict="$root/fuzz/$target.dict")
  echo "== fuzzing $target for ${seconds}s (corpus $corpus)"
  (cd "$build/fuzz" && "$build/fuzz/${target}_fuzzer" "$corpus" "${dictionary[@]}" "${keep_going[@]}" \
      -max_total_time="$seconds" -timeout=20 -rss_limit_mb=3072 -max_len=4096 \
      -artifact_prefix="$artifacts/" -print_final_stats=1) 2>&1 | tee "$build/fuzz-$target.log" | \
      grep -E "DONE|INITED|ERROR|SUMMARY|stat::number_of_executed_units|stat::peak_rss" || true
  if grep -qE "ERROR: |crash-|timeout-|oom-" "$build/fuzz-$target.log"; then status=1; echo "!! $target: finding, see $build/fuzz-$target.log"; fi
done
exit $status
