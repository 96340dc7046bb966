#pragma once
// Corner forces of a zone stress (docs/algorithm.md §1, step 5) and their gather at points.
#include "hydro/kernels/strength.hpp"
#include "stagger/mesh.hpp"

namespace stagger {

// f_c = -sigma a_c with sigma = S - P I, P = p + q: written (not added) to the n corners.
[[gnu::always_inline]] inline void stress_corner_forces(int n, const Deviator& S, double P, const double* ax,
                                                        const double* ay, double* fx, double* fy) {
  const double sxx = S.xx - P, syy = S.yy - P, sxy = S.xy;
  for (int k = 0; k < n; ++k) {
    fx[k] = -(sxx * ax[k] + sxy * ay[k]);
    fy[k] = -(sxy * ax[k] + syy * ay[k]);
  }
}

// Point accumulation: F_p = sum of the corner values of point p, over its corners in
// ascending order (a fixed order: the same sum for any thread count, no atomics).
[[gnu::always_inline]] inline void gather_point_sum(const Index* point_corner_begin, const Index* point_corners,
                                                    const double* fx, const double* fy, Index p, double& Fx,
                                                    double& Fy) {
  Fx = 0, Fy = 0;
  for (Index k = point_corner_begin[p]; k < point_corner_begin[p + 1]; ++k)
    Fx += fx[point_corners[k]], Fy += fy[point_corners[k]];
}

}  // namespace stagger
