#pragma once
// Tensor artificial viscosity (docs/algorithm.md §4.1), after Campbell & Shashkov, "A tensor
// artificial viscosity using a mimetic finite difference algorithm", J. Comput. Phys. 172
// (2001): a viscous stress Q = mu S from the strain rate S of each corner of the zone, and
// corner forces that are the adjoint of that corner gradient, so that the work is
// -sum w mu S:S <= 0 (dissipative, exact in the corner-force energy update) and rigid motion
// (S = 0) feels none.
#include <cmath>

#include "hydro/kernels/geometry.hpp"

namespace stagger {

// Adds the tensor viscosity of one zone (n corners, counter-clockwise) to its corner forces
// (fx, fy) and returns its scalar size mu |lambda_min| (the bulk q in one dimension).
// (vx, vy): corner coordinates; (ux, uy): corner velocities; area, l: the zone's area and
// characteristic length; q1, q2: the bulk q's quadratic and linear coefficients (§4).
//
// Corner k (point k, edges e+ = x_{k+1} - x_k, e- = x_{k-1} - x_k, J = e+ x e-): the velocity
// gradient G_k that reproduces both edges' velocity differences, G_k = du+ (x) b+ + du- (x) b-,
// b+ = (e-_y, -e-_x)/J, b- = (-e+_y, e+_x)/J; S_k its symmetric part; weight w_k = A J_k / sum J
// (corners with J_k below 5 % of the mean are left out: their gradient is ill-posed). The zone
// compresses when the weighted mean strain has div < 0; then mu = rho l (q1 l |lambda_min| +
// q2 C) with lambda_min its most compressive eigenvalue (zero otherwise), Q_k = mu S_k and the
// force on point q of corner k is -w_k Q_k beta_q, beta = b+ at k+1, b- at k-1, -(b+ + b-) at k.
[[gnu::always_inline]] inline double add_tensor_viscosity_forces(int n, const double* vx, const double* vy,
                                                                 const double* ux, const double* uy, double area,
                                                                 double l, double rho, double C, double q1, double q2,
                                                                 double* fx, double* fy) {
  double jac[kMaxZoneVertices], sxx[kMaxZoneVertices], syy[kMaxZoneVertices], sxy[kMaxZoneVertices];
  double jsum = 0;
  for (int k = 0; k < n; ++k) {
    const int kp = k + 1 == n ? 0 : k + 1, km = k == 0 ? n - 1 : k - 1;
    jac[k] = (vx[kp] - vx[k]) * (vy[km] - vy[k]) - (vy[kp] - vy[k]) * (vx[km] - vx[k]);
    if (jac[k] > 0) jsum += jac[k];
  }
  if (!(jsum > 0)) return 0.0;
  const double floor = 0.05 * jsum / n;
  double wsum = 0, mxx = 0, myy = 0, mxy = 0;
  for (int k = 0; k < n; ++k) {
    if (!(jac[k] > floor)) continue;
    const int kp = k + 1 == n ? 0 : k + 1, km = k == 0 ? n - 1 : k - 1;
    const double epx = vx[kp] - vx[k], epy = vy[kp] - vy[k], emx = vx[km] - vx[k], emy = vy[km] - vy[k];
    const double bpx = emy / jac[k], bpy = -emx / jac[k], bmx = -epy / jac[k], bmy = epx / jac[k];
    const double dpx = ux[kp] - ux[k], dpy = uy[kp] - uy[k], dmx = ux[km] - ux[k], dmy = uy[km] - uy[k];
    sxx[k] = dpx * bpx + dmx * bmx;
    syy[k] = dpy * bpy + dmy * bmy;
    sxy[k] = 0.5 * (dpx * bpy + dmx * bmy + dpy * bpx + dmy * bmx);
    wsum += jac[k];
    mxx += jac[k] * sxx[k];
    myy += jac[k] * syy[k];
    mxy += jac[k] * sxy[k];
  }
  if (!(wsum > 0)) return 0.0;
  mxx /= wsum, myy /= wsum, mxy /= wsum;
  const double div = mxx + myy;
  if (!(div < 0)) return 0.0;
  const double half_diff = 0.5 * (mxx - myy);
  const double lambda_min = 0.5 * div - std::sqrt(half_diff * half_diff + mxy * mxy);
  const double mu = rho * l * (q1 * l * (-lambda_min) + q2 * C);
  const double scale = mu * area / wsum;  // w_k mu / J_k
  for (int k = 0; k < n; ++k) {
    if (!(jac[k] > floor)) continue;
    const int kp = k + 1 == n ? 0 : k + 1, km = k == 0 ? n - 1 : k - 1;
    const double epx = vx[kp] - vx[k], epy = vy[kp] - vy[k], emx = vx[km] - vx[k], emy = vy[km] - vy[k];
    // w_k Q_k b = scale J_k S_k b, and J_k b+- are the rotated edges (no division).
    const double qxx = scale * sxx[k], qyy = scale * syy[k], qxy = scale * sxy[k];
    const double jbpx = emy, jbpy = -emx, jbmx = -epy, jbmy = epx;
    const double fpx = qxx * jbpx + qxy * jbpy, fpy = qxy * jbpx + qyy * jbpy;
    const double fmx = qxx * jbmx + qxy * jbmy, fmy = qxy * jbmx + qyy * jbmy;
    fx[kp] -= fpx;
    fy[kp] -= fpy;
    fx[km] -= fmx;
    fy[km] -= fmy;
    fx[k] += fpx + fmx;
    fy[k] += fpy + fmy;
  }
  return mu * (-lambda_min);
}

}  // namespace stagger
