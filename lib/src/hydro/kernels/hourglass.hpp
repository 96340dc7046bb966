#pragma once
// Hourglass control of quadrilateral zones (docs/algorithm.md §6).
#include <cmath>

namespace stagger {

// Adds the hourglass viscosity of one quad to its corner forces: f_k -= a g_k (g . u),
// a = Q/4 rho C sqrt(A), with g the hourglass base vector. `gamma` mode: g = (1, -1, 1, -1).
// Flanagan-Belytschko: g = G - (G.x) a_x / A - (G.y) a_y / A, the part of G orthogonal to
// every linear velocity field, so that rigid motion and uniform strain feel no force.
// (vx, vy): the corner coordinates; (ax, ay): corner area vectors; (ux, uy): velocities.
[[gnu::always_inline]] inline void add_hourglass_forces(const double* vx, const double* vy, const double* ax,
                                                        const double* ay, double area, const double* ux,
                                                        const double* uy, double rho, double C, double coefficient,
                                                        bool flanagan_belytschko, double* fx, double* fy) {
  double g[4] = {1, -1, 1, -1};
  if (flanagan_belytschko) {
    const double gxs = vx[0] - vx[1] + vx[2] - vx[3], gys = vy[0] - vy[1] + vy[2] - vy[3];
    for (int k = 0; k < 4; ++k) g[k] -= (gxs * ax[k] + gys * ay[k]) / area;
  }
  double hx = 0, hy = 0;
  for (int k = 0; k < 4; ++k) hx += g[k] * ux[k], hy += g[k] * uy[k];
  const double a = 0.25 * coefficient * rho * C * std::sqrt(area);
  for (int k = 0; k < 4; ++k) {
    fx[k] -= a * g[k] * hx;
    fy[k] -= a * g[k] * hy;
  }
}

}  // namespace stagger
