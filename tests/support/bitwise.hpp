#pragma once
// Bitwise comparison of arrays of doubles (the determinism and restart checks).
#include <cstring>
#include <span>

namespace stagger::testing {

/// True if two spans hold the same bits (so -0.0 != 0.0 and NaN == NaN of the same payload).
inline bool bitwise_equal(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

}  // namespace stagger::testing
