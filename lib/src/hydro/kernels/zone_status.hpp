#pragma once
// What a zone kernel reports, and when a loop runs in parallel.
#include <cstdint>
#include <limits>

#include "stagger/mesh.hpp"

namespace stagger {

// Below this many zones or points a loop runs on one thread: thread start-up would cost
// more than the loop (results are identical either way).
constexpr Index kParallelMin = 4096;

// Why a zone failed. A tangled zone (non-positive zone or corner area) is retried with a
// smaller dt; the others stop the run.
enum ZoneFailure : int { kTangled = 0, kEosDomain = 1, kNotFinite = 2 };

// Encodes (zone, kind) so that a min-reduction picks the lowest zone deterministically.
inline std::int64_t failure_code(Index z, int kind) {
  return static_cast<std::int64_t>(z) * 4 + kind;
}
constexpr std::int64_t kNoFailure = std::numeric_limits<std::int64_t>::max();
inline Index failure_zone(std::int64_t code) {
  return static_cast<Index>(code / 4);
}
inline int failure_kind(std::int64_t code) {
  return static_cast<int>(code % 4);
}

}  // namespace stagger
