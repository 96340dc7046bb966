// Edge viscosity (docs/algorithm.md §5); out of line: one extra pass over the zones.
#include "hydro/kernels/viscosity_edge.hpp"

#include <algorithm>
#include <cmath>

#include "hydro/kernels/zone_status.hpp"
#include "mesh/polygon.hpp"

namespace stagger {

void edge_forces_loop(const EdgeViscosityInput& input, Index begin, Index end, double gamma_factor, double* fx,
                      double* fy) {
  const EdgeViscosityInput in = input;  // thread-private below, as in zone_forces_loop
  const Index* cb = in.zone_corner_begin;
  const Index* cp = in.corner_point;
  const double *px = in.x, *py = in.y, *wx = in.ux, *wy = in.uy;
  const double g1 = gamma_factor;
#pragma omp parallel for schedule(static) firstprivate(in) if (end - begin > kParallelMin)
  for (Index z = begin; z < end; ++z) {
    const Index b = cb[z];
    const int n = static_cast<int>(cb[z + 1] - b);
    const auto [cx, cy] = polygon_centre(
        n, [&](int k) { return px[cp[b + k]]; }, [&](int k) { return py[cp[b + k]]; });
    const double rho = in.rho[z], C = in.C[z];
    for (int k = 0; k < n; ++k) {
      const Index p0 = cp[b + k], p1 = cp[b + (k + 1) % n];
      const double dux = wx[p1] - wx[p0], duy = wy[p1] - wy[p0];
      const double dxx = px[p1] - px[p0], dxy = py[p1] - py[p0];
      if (dux * dxx + duy * dxy >= 0) continue;  // only compressing edges
      const double du2 = dux * dux + duy * duy;
      const double du = std::sqrt(du2);
      double psi = 0;
      if (in.limiter) {
        // Ratios of the velocity gradient along the edges continuing this one.
        const double len = std::sqrt(dxx * dxx + dxy * dxy);
        const double gx = dux / len, gy = duy / len, gg = gx * gx + gy * gy;
        const EdgeContinuation& ec = in.continuation[b + k];
        // Ratio of the gradient along the continuing edge a -> c to this edge's.
        auto ratio = [&](Index a, Index c) -> double {
          const double l2 = std::hypot(px[c] - px[a], py[c] - py[a]);
          return ((wx[c] - wx[a]) * gx + (wy[c] - wy[a]) * gy) / (l2 * gg);
        };
        // Mirror image in the wall edge (a, w), velocities relative to the wall point (a
        // moving piston too): the continuing edge has du' = R(-du), so the ratio is
        // -1 + 2 (du.n)^2 / |du|^2 (1 for an edge normal to the wall, -1 along it).
        auto mirror_ratio = [&](Index a, Index w) -> double {
          const double nx = py[w] - py[a], ny = px[a] - px[w];
          const double dn = dux * nx + duy * ny;
          return -1.0 + 2.0 * dn * dn / (du2 * (nx * nx + ny * ny));
        };
        auto continuation_ratio = [&](Index code, Index from, Index to, Index wall_point) -> double {
          if (code >= 0) return ratio(from, to);
          if (code == kContinuationFree) return 0.0;
          if (code == kContinuationOpen) return 1.0;
          return mirror_ratio(wall_point, mirror_wall_end(code));
        };
        const double ra = continuation_ratio(ec.ahead, p1, ec.ahead, p1);
        const double rb = continuation_ratio(ec.behind, ec.behind, p0, p0);
        psi = std::max(0.0, std::min({0.5 * (ra + rb), 2 * ra, 2 * rb, 1.0}));
      }
      if (psi >= 1) continue;
      // Median surface vector: zone centre to edge midpoint, rotated a quarter turn.
      const double mx = 0.5 * (px[p0] + px[p1]) - cx, my = 0.5 * (py[p0] + py[p1]) - cy;
      const double proj = std::abs(-my * dux + mx * duy) / du;
      const double coef =
          rho * (in.c2 * g1 * du + std::sqrt(in.c2 * in.c2 * g1 * g1 * du2 + in.c1 * in.c1 * C * C)) * (1 - psi);
      const double f = coef * proj;
      // Equal and opposite: it slows the approach of p0 and p1.
      fx[b + k] += f * dux;
      fy[b + k] += f * duy;
      const Index c1 = b + (k + 1) % n;
      fx[c1] -= f * dux;
      fy[c1] -= f * duy;
    }
  }
}

}  // namespace stagger
