#pragma once
// Is a zone still a zone? The tangling check of docs/algorithm.md §9: a zone whose boundary
// crosses itself or whose signed area is not positive is never committed, dumped or reported
// as part of a completed run, whatever the options say. The crossing test is a property of
// the polygon in its own plane, so every geometry policy shares it.
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "hydro/kernels/geometry.hpp"

namespace stagger {

// Twice the signed area of the triangle (a, b, c): > 0 when c is left of a -> b.
[[gnu::always_inline]] inline double orientation(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// Segments p0-p1 and q0-q1 cross properly: each one's end points lie strictly on both sides
// of the other's line. Touching or collinear overlap is not a proper crossing.
[[gnu::always_inline]] inline bool segments_cross(double p0x, double p0y, double p1x, double p1y, double q0x,
                                                  double q0y, double q1x, double q1y) {
  const double a = orientation(p0x, p0y, p1x, p1y, q0x, q0y);
  const double b = orientation(p0x, p0y, p1x, p1y, q1x, q1y);
  const double c = orientation(q0x, q0y, q1x, q1y, p0x, p0y);
  const double d = orientation(q0x, q0y, q1x, q1y, p1x, p1y);
  return ((a > 0 && b < 0) || (a < 0 && b > 0)) && ((c > 0 && d < 0) || (c < 0 && d > 0));
}

// A quad's two segment tests, (0-1, 2-3) and (1-2, 3-0), each need the first half of
// segments_cross (the ends of the second edge on both sides of the first's line) before the
// second half matters. Both first halves at once in packed doubles: the same IEEE operations
// in the same order as orientation() (no contraction without FMA), so bitwise the same
// values and the same decisions. True when either first half holds: then the full test runs.
[[gnu::always_inline]] inline bool quad_may_cross(const ZoneVertices& v) {
#if defined(__SSE2__) && !defined(__FMA__)
  const __m128d ax = _mm_loadu_pd(v.x), ay = _mm_loadu_pd(v.y);                  // (v0, v1)
  const __m128d bx = _mm_loadu_pd(v.x + 1), by = _mm_loadu_pd(v.y + 1);          // (v1, v2)
  const __m128d cx = _mm_loadu_pd(v.x + 2), cy = _mm_loadu_pd(v.y + 2);          // (v2, v3)
  const __m128d dx = _mm_shuffle_pd(cx, ax, 1), dy = _mm_shuffle_pd(cy, ay, 1);  // (v3, v0)
  const __m128d ex = _mm_sub_pd(bx, ax), ey = _mm_sub_pd(by, ay);
  const __m128d a = _mm_sub_pd(_mm_mul_pd(ex, _mm_sub_pd(cy, ay)), _mm_mul_pd(ey, _mm_sub_pd(cx, ax)));
  const __m128d b = _mm_sub_pd(_mm_mul_pd(ex, _mm_sub_pd(dy, ay)), _mm_mul_pd(ey, _mm_sub_pd(dx, ax)));
  const __m128d zero = _mm_setzero_pd();
  const __m128d opposite = _mm_or_pd(_mm_and_pd(_mm_cmpgt_pd(a, zero), _mm_cmplt_pd(b, zero)),
                                     _mm_and_pd(_mm_cmplt_pd(a, zero), _mm_cmpgt_pd(b, zero)));
  return _mm_movemask_pd(opposite) != 0;
#else
  (void)v;
  return true;
#endif
}

// Two edges of the zone that share no point cross properly. O(n^2) in the vertex count: two
// segment tests for a quad, most of which end after two orientations.
template <int N = 0>
[[gnu::always_inline]] inline bool edges_cross(const ZoneVertices& v) {
  if constexpr (N == 4) {
    if (!quad_may_cross(v)) return false;
  }
  const int n = N ? N : v.n;
  for (int i = 0; i + 2 < n; ++i) {
    const int i1 = i + 1;
    // Edge j must share no point with edge i: j from i + 2 up to n - 1, except the edge
    // n-1 -> 0 when i = 0.
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const int j1 = (j + 1 == n) ? 0 : j + 1;
      if (segments_cross(v.x[i], v.y[i], v.x[i1], v.y[i1], v.x[j], v.y[j], v.x[j1], v.y[j1])) return true;
    }
  }
  return false;
}

// A crossing zone (docs/verification.md §12): two edges that share no point cross properly,
// or the signed area is not positive. Convexity is not required.
template <int N = 0>
[[gnu::always_inline]] inline bool zone_crosses(const ZoneVertices& v) {
  return !(PlanarGeometry::area<N>(v) > 0) || edges_cross<N>(v);
}

}  // namespace stagger
