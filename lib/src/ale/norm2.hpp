#pragma once
// |(x, y)| for the rezone's mesh-sized lengths (docs/ale.md, "Rezone").
#include <cmath>

namespace stagger {

// |(x, y)| without std::hypot's overflow care (slow in glibc; lengths here are mesh-sized).
[[gnu::always_inline]] inline double norm2(double x, double y) {
  return std::sqrt(x * x + y * y);
}

}  // namespace stagger
