#pragma once
// Zone geometry on a small local copy of the vertices (docs/algorithm.md §2), as a
// compile-time policy: the zone kernels take `class Geometry` and call only its static
// functions, so an axisymmetric policy (areas -> volumes, corner area vectors -> r-weighted
// ones) is one more struct, not a copy of the kernels (docs/architecture.md, "Geometry
// policy"). Header-only so that the fused zone loops inline it; N is the vertex count when
// every zone of the loop has it (4 for all-quad meshes), 0 for "read v.n".
#include <algorithm>
#include <cmath>
#include <span>

#include "mesh/polygon.hpp"
#include "stagger/mesh.hpp"

namespace stagger {

constexpr int kMaxZoneVertices = 8;

struct ZoneVertices {
  int n = 0;
  double x[kMaxZoneVertices], y[kMaxZoneVertices];
};

// The vertices of one zone, corners [begin, begin + n) of `corner_point`, from (x, y).
template <int N = 0>
[[gnu::always_inline]] inline ZoneVertices gather_vertices(const Index* corner_point, Index begin, int n,
                                                           const double* x, const double* y) {
  ZoneVertices v;
  v.n = N ? N : n;
  for (int k = 0; k < v.n; ++k) {
    const Index p = corner_point[begin + k];
    v.x[k] = x[p];
    v.y[k] = y[p];
  }
  return v;
}

// Velocity gradient L_ij = dv_i/dx_j of a zone.
struct VelocityGradient {
  double xx = 0, xy = 0, yx = 0, yy = 0;
};

// Plane (x, y) geometry, per unit length in z.
struct PlanarGeometry {
  static constexpr bool kRz = false;

  // Signed zone area (shoelace), positive for counter-clockwise zones.
  template <int N = 0>
  [[gnu::always_inline]] static double area(const ZoneVertices& v) {
    return polygon_area(
        N ? N : v.n, [&](int k) { return v.x[k]; }, [&](int k) { return v.y[k]; });
  }

  // Zone centre (vertex average).
  template <int N = 0>
  [[gnu::always_inline]] static std::array<double, 2> centre(const ZoneVertices& v) {
    return polygon_centre(
        N ? N : v.n, [&](int k) { return v.x[k]; }, [&](int k) { return v.y[k]; });
  }

  // Corner area vectors a_c = dA/dx_k = 1/2 (y_{k+1} - y_{k-1}, x_{k-1} - x_{k+1}): the
  // force of a zone stress on its points is -sigma a_c, and sum_c v_c a_c / A is grad v.
  template <int N = 0>
  [[gnu::always_inline]] static void corner_gradients(const ZoneVertices& v, double* ax, double* ay) {
    const int n = N ? N : v.n;
    for (int k = 0; k < n; ++k) {
      const int kp = (k + 1 == n) ? 0 : k + 1;
      const int km = (k == 0) ? n - 1 : k - 1;
      ax[k] = 0.5 * (v.y[kp] - v.y[km]);
      ay[k] = 0.5 * (v.x[km] - v.x[kp]);
    }
  }

  // Median-mesh corner areas (the corner weights: point masses, point volumes): corner k is
  // (x_k, mid(k,k+1), centre, mid(k-1,k)). Returns the smallest.
  template <int N = 0>
  [[gnu::always_inline]] static double corner_areas(const ZoneVertices& v, double* out) {
    const int n = N ? N : v.n;
    const auto [cx, cy] = centre<N>(v);
    double smallest = 1e300;
    for (int k = 0; k < n; ++k) {
      const int kp = (k + 1 == n) ? 0 : k + 1;
      const int km = (k == 0) ? n - 1 : k - 1;
      const double mpx = 0.5 * (v.x[k] + v.x[kp]), mpy = 0.5 * (v.y[k] + v.y[kp]);
      const double mmx = 0.5 * (v.x[k] + v.x[km]), mmy = 0.5 * (v.y[k] + v.y[km]);
      const double qx[4] = {v.x[k], mpx, cx, mmx}, qy[4] = {v.y[k], mpy, cy, mmy};
      out[k] = polygon_area(
          4, [&](int i) { return qx[i]; }, [&](int i) { return qy[i]; });
      smallest = std::min(smallest, out[k]);
    }
    return smallest;
  }

  // Characteristic length l = A / (longest diagonal) for quads (HEMP), A / (largest
  // vertex-to-vertex distance) otherwise.
  template <int N = 0>
  [[gnu::always_inline]] static double characteristic_length(const ZoneVertices& v, double area) {
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

  // div u = (1/A) sum_c u_c . a_c.
  [[gnu::always_inline]] static double divergence(int n, const double* ux, const double* uy, const double* ax,
                                                  const double* ay, double area) {
    double div = 0;
    for (int k = 0; k < n; ++k) div += ux[k] * ax[k] + uy[k] * ay[k];
    return div / area;
  }

  // Point forces of boundary tractions summed on the planar edge elements: as they are.
  static void scale_surface_forces(std::span<const double>, std::span<double>, std::span<double>) {}

  // L_ij = (1/A) sum_c u_i a_c,j.
  [[gnu::always_inline]] static VelocityGradient velocity_gradient(int n, const double* ux, const double* uy,
                                                                   const double* ax, const double* ay, double area) {
    VelocityGradient L;
    for (int k = 0; k < n; ++k) {
      L.xx += ux[k] * ax[k];
      L.xy += ux[k] * ay[k];
      L.yx += uy[k] * ax[k];
      L.yy += uy[k] * ay[k];
    }
    const double inv = 1.0 / area;
    L.xx *= inv, L.xy *= inv, L.yx *= inv, L.yy *= inv;
    return L;
  }
};

// Axisymmetric (r, z) geometry, per radian: x = r >= 0, y = z (docs/algorithm.md §19). The
// area-weighted scheme keeps every planar quantity of PlanarGeometry (areas, corner area
// vectors, lengths: the forces and the time step) and adds the true volumes V = int r dA
// (densities, masses) and the volume divergence (1/V) dV/dt (q, the volume limit, the hoop
// strain rate).
struct RzGeometry : PlanarGeometry {
  static constexpr bool kRz = true;

  // V = int r dA = 1/6 sum_k (x_k + x_{k+1}) (x_k y_{k+1} - x_{k+1} y_k), positive for
  // counter-clockwise zones in x >= 0.
  template <int N = 0>
  [[gnu::always_inline]] static double volume(const ZoneVertices& v) {
    const int n = N ? N : v.n;
    double sum = 0;
    for (int k = 0; k < n; ++k) {
      const int kp = (k + 1 == n) ? 0 : k + 1;
      sum += (v.x[k] + v.x[kp]) * (v.x[k] * v.y[kp] - v.x[kp] * v.y[k]);
    }
    return sum / 6.0;
  }

  // div u = (1/V) sum_k u_k . dV/dx_k, the exact rate (1/V) dV/dt of the zone's volume.
  template <int N = 0>
  [[gnu::always_inline]] static double volume_divergence(const ZoneVertices& v, const double* ux, const double* uy,
                                                         double volume) {
    const int n = N ? N : v.n;
    double rate = 0;
    for (int k = 0; k < n; ++k) {
      const int kp = (k + 1 == n) ? 0 : k + 1;
      const int km = (k == 0) ? n - 1 : k - 1;
      const double cp = v.x[k] * v.y[kp] - v.x[kp] * v.y[k];
      const double cm = v.x[km] * v.y[k] - v.x[k] * v.y[km];
      const double dvdx = cp + (v.x[k] + v.x[kp]) * v.y[kp] + cm - (v.x[km] + v.x[k]) * v.y[km];
      const double dvdy = (v.x[km] + v.x[k]) * v.x[km] - (v.x[k] + v.x[kp]) * v.x[kp];
      rate += ux[k] * dvdx + uy[k] * dvdy;
    }
    return rate / (6.0 * volume);
  }

  // Per radian, the r-weighted surface element: the planar point force times the point's
  // radius (zero on the axis), as the corner forces (docs/algorithm.md §19).
  static void scale_surface_forces(std::span<const double> x, std::span<double> fx, std::span<double> fy) {
    for (std::size_t p = 0; p < x.size(); ++p) fx[p] *= x[p], fy[p] *= x[p];
  }

  // Median-mesh corner volumes int r dA (the true corner masses rho^0 V_c at set-up).
  template <int N = 0>
  [[gnu::always_inline]] static void corner_volumes(const ZoneVertices& v, double* out) {
    const int n = N ? N : v.n;
    const auto [cx, cy] = centre<N>(v);
    for (int k = 0; k < n; ++k) {
      const int kp = (k + 1 == n) ? 0 : k + 1;
      const int km = (k == 0) ? n - 1 : k - 1;
      ZoneVertices q;
      q.n = 4;
      q.x[0] = v.x[k], q.y[0] = v.y[k];
      q.x[1] = 0.5 * (v.x[k] + v.x[kp]), q.y[1] = 0.5 * (v.y[k] + v.y[kp]);
      q.x[2] = cx, q.y[2] = cy;
      q.x[3] = 0.5 * (v.x[k] + v.x[km]), q.y[3] = 0.5 * (v.y[k] + v.y[km]);
      out[k] = volume<4>(q);
    }
  }
};

}  // namespace stagger
