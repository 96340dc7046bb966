#pragma once
// `stagger bench scaling`: strong scaling over ranks and threads, halo figures, and the
// bitwise check on 8 ranks (bench_scaling.cpp, docs/parallel.md).
#include <filesystem>

namespace stagger::cli::bench {

/// Runs the suite, writes `out_dir`/scaling.csv and prints the summary; returns the number of
/// runs that failed (or 1 if the 8-rank run differs from the serial one).
int scaling_suite(const std::filesystem::path& scenes, const std::filesystem::path& out_dir, bool quick, int repeat);

}  // namespace stagger::cli::bench
