#pragma once
// The one shoelace area and the one zone centre of the code (docs/algorithm.md §2), for any
// vertex storage: the callers pass accessors x(k), y(k) for the polygon's k-th vertex
// (k = 0..n-1, counter-clockwise). Mesh building, the hydro kernels, verification and output
// all call these, so every zone centre and area is computed with the same rounding.
#include <array>

namespace stagger {

// Twice the signed area, sum_k (x_k y_{k+1} - x_{k+1} y_k), summed from k = 0: positive for
// counter-clockwise polygons. Callers that need only the sign or a scale-free test use it
// without the final halving.
template <class X, class Y>
[[gnu::always_inline]] inline double polygon_twice_area(int n, X&& x, Y&& y) {
  double twice = 0;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    twice += x(k) * y(k1) - x(k1) * y(k);
  }
  return twice;
}

// Signed area (shoelace).
template <class X, class Y>
[[gnu::always_inline]] inline double polygon_area(int n, X&& x, Y&& y) {
  return 0.5 * polygon_twice_area(n, x, y);
}

// Zone centre: the vertex average (sum, then one division by n). This is the centre of the
// median mesh (corner areas) and the point where initial fields, sources and error norms are
// evaluated. Summing x_k / n instead rounds differently unless n is a power of two.
template <class X, class Y>
[[gnu::always_inline]] inline std::array<double, 2> polygon_centre(int n, X&& x, Y&& y) {
  double cx = 0, cy = 0;
  for (int k = 0; k < n; ++k) {
    cx += x(k);
    cy += y(k);
  }
  return {cx / n, cy / n};
}

}  // namespace stagger
