#pragma once
// Pointwise zone physics shared by the step's loops: deviatoric stress update and return,
// burn fraction, time-step candidate (NUMERICS sections 4, 6, 8).
#include <algorithm>
#include <cmath>

namespace stagger {

// Velocity gradient L_ij = dv_i/dx_j = (1/A) sum_c v_i a_c,j (NUMERICS section 2).
struct VelocityGradient {
  double xx = 0, xy = 0, yx = 0, yy = 0;
};

[[gnu::always_inline]] inline VelocityGradient velocity_gradient(int n, const double* vx, const double* vy, const double* ax,
                                          const double* ay, double area) {
  VelocityGradient L;
  for (int k = 0; k < n; ++k) {
    L.xx += vx[k] * ax[k];
    L.xy += vx[k] * ay[k];
    L.yx += vy[k] * ax[k];
    L.yy += vy[k] * ay[k];
  }
  const double inv = 1.0 / area;
  L.xx *= inv, L.xy *= inv, L.yx *= inv, L.yy *= inv;
  return L;
}

struct Deviator {
  double xx = 0, yy = 0, xy = 0;
};

// Jaumann rate of the Wilkins hypo-elastic model, plane strain (NUMERICS section 4):
// dS/dt = 2 mu (D - tr(D)/3 I) + W S - S W, evaluated at stress s.
[[gnu::always_inline]] inline Deviator stress_rate(double mu, const Deviator& s, const VelocityGradient& L) {
  const double spin = L.xy - L.yx;
  return {(4.0 / 3.0) * mu * L.xx - (2.0 / 3.0) * mu * L.yy + s.xy * spin,
          (4.0 / 3.0) * mu * L.yy - (2.0 / 3.0) * mu * L.xx - s.xy * spin,
          mu * (L.xy + L.yx) + 0.5 * (s.yy - s.xx) * spin};
}

// S(t+h) from S(t): either the rate form S + h dS/dt(s_rate, L) (the paper's), or the
// objective incremental update R S R^T + 2 mu D0 h with the Hughes-Winget rotation.
[[gnu::always_inline]] inline Deviator advance_stress(bool objective, double mu, const Deviator& s0, const Deviator& s_rate,
                               const VelocityGradient& L, double h) {
  if (!objective) {
    const Deviator r = stress_rate(mu, s_rate, L);
    return {s0.xx + h * r.xx, s0.yy + h * r.yy, s0.xy + h * r.xy};
  }
  const double a = 0.25 * h * (L.xy - L.yx);  // h w / 2 with w = (L_xy - L_yx)/2
  const double cs = (1 - a * a) / (1 + a * a), sn = 2 * a / (1 + a * a);
  Deviator out{cs * cs * s0.xx + 2 * cs * sn * s0.xy + sn * sn * s0.yy,
               sn * sn * s0.xx - 2 * sn * cs * s0.xy + cs * cs * s0.yy,
               -cs * sn * s0.xx + (cs * cs - sn * sn) * s0.xy + sn * cs * s0.yy};
  out.xx += h * ((4.0 / 3.0) * mu * L.xx - (2.0 / 3.0) * mu * L.yy);
  out.yy += h * ((4.0 / 3.0) * mu * L.yy - (2.0 / 3.0) * mu * L.xx);
  out.xy += h * mu * (L.xy + L.yx);
  return out;
}

// von Mises radial return with S_zz = -(S_xx + S_yy) in the norm; returns the equivalent
// plastic strain increment (sigma_eq - Y) / (3 mu).
[[gnu::always_inline]] inline double radial_return(double yield, double mu, Deviator& s) {
  const double szz = -(s.xx + s.yy);
  const double j2 = s.xx * s.xx + s.yy * s.yy + szz * szz + 2 * s.xy * s.xy;
  const double seq = std::sqrt(1.5 * j2);
  if (seq <= yield) return 0.0;
  const double f = yield / seq;
  s.xx *= f, s.yy *= f, s.xy *= f;
  return mu > 0 ? (seq - yield) / (3 * mu) : 0.0;
}

// Time-step candidate of one zone (NUMERICS section 6).
[[gnu::always_inline]] inline double zone_time_step(double cfl, double q1, double q2, double volume_limit, double l, double C,
                             double div) {
  const double qhat = div < 0 ? q1 * l * (-div) + q2 * C : 0.0;
  const double denom = qhat + std::sqrt(qhat * qhat + C * C);
  double dt = denom > 0 ? cfl * l / denom : 1e300;
  if (div != 0) dt = std::min(dt, volume_limit / std::abs(div));
  return dt;
}

}  // namespace stagger
