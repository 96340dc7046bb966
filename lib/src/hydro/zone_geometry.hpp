#pragma once
// Zone geometry on a small local copy of the vertices (NUMERICS section 2). Header-only so
// that the zone loops inline it.
#include <algorithm>
#include <cmath>

namespace stagger {

constexpr int kMaxZoneVertices = 8;

struct ZoneVertices {
  int n = 0;
  double x[kMaxZoneVertices], y[kMaxZoneVertices];
};

// Signed area, 1/2 sum (x_k y_{k+1} - x_{k+1} y_k): positive for counter-clockwise zones.
template <int N = 0>
[[gnu::always_inline]] inline double polygon_area(const ZoneVertices& v) {
  const int n = N ? N : v.n;
  double twice = 0;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    twice += v.x[k] * v.y[k1] - v.x[k1] * v.y[k];
  }
  return 0.5 * twice;
}

// Corner area gradients a_c = dA/dx_k = 1/2 (y_{k+1} - y_{k-1}, x_{k-1} - x_{k+1}).
template <int N = 0>
[[gnu::always_inline]] inline void corner_gradients(const ZoneVertices& v, double* ax, double* ay) {
  const int n = N ? N : v.n;
  for (int k = 0; k < n; ++k) {
    const int kp = (k + 1 == n) ? 0 : k + 1;
    const int km = (k == 0) ? n - 1 : k - 1;
    ax[k] = 0.5 * (v.y[kp] - v.y[km]);
    ay[k] = 0.5 * (v.x[km] - v.x[kp]);
  }
}

// Characteristic length l = A / (longest diagonal) for quads (HEMP), A / (largest
// vertex-to-vertex distance) otherwise (NUMERICS section 2).
template <int N = 0>
[[gnu::always_inline]] inline double characteristic_length(const ZoneVertices& v, double area) {
  double longest2 = 0;
  if ((N ? N : v.n) == 4) {
    const double d0x = v.x[2] - v.x[0], d0y = v.y[2] - v.y[0];
    const double d1x = v.x[3] - v.x[1], d1y = v.y[3] - v.y[1];
    longest2 = std::max(d0x * d0x + d0y * d0y, d1x * d1x + d1y * d1y);
  } else {
    for (int i = 0; i < v.n; ++i)
      for (int j = i + 1; j < v.n; ++j) {
        const double dx = v.x[j] - v.x[i], dy = v.y[j] - v.y[i];
        longest2 = std::max(longest2, dx * dx + dy * dy);
      }
  }
  return area / std::sqrt(longest2);
}

// Median-mesh corner areas: corner k is (x_k, mid(k,k+1), centre, mid(k-1,k)), the centre
// being the vertex average (NUMERICS section 1). Returns the smallest.
template <int N = 0>
[[gnu::always_inline]] inline double corner_areas(const ZoneVertices& v, double* out) {
  const int n = N ? N : v.n;
  double cx = 0, cy = 0;
  for (int k = 0; k < n; ++k) {
    cx += v.x[k];
    cy += v.y[k];
  }
  cx /= n;
  cy /= n;
  double smallest = 1e300;
  for (int k = 0; k < n; ++k) {
    const int kp = (k + 1 == n) ? 0 : k + 1;
    const int km = (k == 0) ? n - 1 : k - 1;
    const double mpx = 0.5 * (v.x[k] + v.x[kp]), mpy = 0.5 * (v.y[k] + v.y[kp]);
    const double mmx = 0.5 * (v.x[k] + v.x[km]), mmy = 0.5 * (v.y[k] + v.y[km]);
    // Shoelace on (x_k, m+, c, m-).
    const double twice = (v.x[k] * mpy - mpx * v.y[k]) + (mpx * cy - cx * mpy) + (cx * mmy - mmx * cy) +
                         (mmx * v.y[k] - v.x[k] * mmy);
    out[k] = 0.5 * twice;
    smallest = std::min(smallest, out[k]);
  }
  return smallest;
}

}  // namespace stagger
