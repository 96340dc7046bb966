// The compatible staggered Lagrangian step (NUMERICS.md section 5). The numbered steps in
// the comments match the table in docs/algorithm.md. Loops are fused per entity:
//   P1 points: predictor gather, half positions, v*          (steps 1, 2, 4)
//   Z1 zones : half geometry, half state, q, hourglass, f_c  (steps 2, 3, 5)
//   P2 points: corrector gather, v^{n+1}, constraints, x^{n+1} (step 6)
//   Z2 zones : energy, stress, end geometry, EOS, dt         (steps 7, 8, 9)
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "eos/eos_kernels.hpp"
#include "hydro/boundary.hpp"
#include "hydro/kernels/subzonal_pressure.hpp"
#include "hydro/simulation_impl.hpp"
#include "hydro/zone_geometry.hpp"
#include "hydro/zone_physics.hpp"
#include "stagger/error.hpp"

namespace stagger {

namespace {

// Below this many zones or points a loop runs on one thread: thread start-up would cost
// more than the loop (results are identical either way).
constexpr Index kParallelMin = 4096;

enum ZoneFailure : int { kTangled = 0, kEosDomain = 1, kNotFinite = 2 };

// Encodes (zone, kind) so that a min-reduction picks the lowest zone deterministically.
inline std::int64_t failure_code(Index z, int kind) { return static_cast<std::int64_t>(z) * 4 + kind; }
constexpr std::int64_t kNoFailure = std::numeric_limits<std::int64_t>::max();

template <int N>
inline ZoneVertices gather_vertices(const Index* corner_point, Index begin, int n, const double* x, const double* y) {
  ZoneVertices v;
  v.n = N ? N : n;
  for (int k = 0; k < v.n; ++k) {
    const Index p = corner_point[begin + k];
    v.x[k] = x[p];
    v.y[k] = y[p];
  }
  return v;
}

// Burn fraction at time t (LS-DYNA programmed burn, optionally with beta burn), monotone.
inline double burn_fraction(double previous, double t, double lighting_time, double burn_length, double speed,
                            const Burn* burn, double rho, double rho0) {
  double f = t > lighting_time ? (t - lighting_time) * speed / burn_length : 0.0;
  if (burn->beta_burn && burn->cj_relative_volume < 1) {
    const double v = rho0 / rho;
    f = std::max(f, (1 - v) / (1 - burn->cj_relative_volume));
  }
  return std::clamp(std::max(previous, f), 0.0, 1.0);
}

// Per-range constants the zone kernels read.
struct RangeModel {
  const Material* material;
  double mu = 0, yield = 0;
  bool strength = false;
  const Burn* burn = nullptr;
  double rho0_burn = 0, edge_gamma_factor = 0.5;
  double min_energy = -1e300;  // Material::min_energy: below it the run stops
};

RangeModel range_model(const Simulation::Impl& s, const ZoneRange& r) {
  RangeModel m;
  m.material = &s.problem.materials[r.material];
  m.min_energy = m.material->min_energy;
  if (m.material->strength) {
    m.strength = true;
    m.mu = m.material->strength->shear_modulus;
    m.yield = m.material->strength->yield_stress;
  }
  if (m.material->burn) {
    m.burn = &*m.material->burn;
    m.rho0_burn = std::get<Jwl>(m.material->eos).rho0;
  }
  // (gamma+1)/4 of the edge viscosity's quadratic term; its analogue s/2 for Mie-Gruneisen.
  if (const auto* g = std::get_if<IdealGas>(&m.material->eos)) m.edge_gamma_factor = (g->gamma + 1) / 4;
  if (const auto* mg = std::get_if<MieGruneisen>(&m.material->eos)) m.edge_gamma_factor = mg->s / 2;
  if (const auto* j = std::get_if<Jwl>(&m.material->eos)) m.edge_gamma_factor = (j->omega + 2) / 4;
  return m;
}

// Inputs of the zone force kernel (Z1): where geometry and velocities come from.
struct ForcePass {
  // Positions of the force geometry: px/py when given (x^n, or the stored x^{n+1/2}),
  // else x^n + h_position v^n computed on the fly (the half step without an array).
  const double* px;
  const double* py;
  double h_position;
  const double* qvx;  // velocity for q and hourglass (v*, or v^n)
  const double* qvy;
  double dt_half;     // dt/2 for the predictor state; 0 for a fresh evaluation at t^n
  double t_eval;      // time of the force evaluation (burn)
  double* out_fx;     // corner forces written
  double* out_fy;
};

// Z1: half-step state and corner forces of the zones [r.begin, r.end) (steps 2, 3, 5).
template <int N, class Eos>
std::int64_t force_zones(Simulation::Impl& s, const ZoneRange& r, const Eos& eos, const RangeModel& m,
                         const ForcePass& pass) {
  const HydroOptions& o = s.problem.options;
  const Index* cb = s.zone_corner_begin.data();
  const Index* cp = s.corner_point.data();
  const double *vx = s.vx.data(), *vy = s.vy.data(), *x = s.x.data(), *y = s.y.data();
  // Predictor forces f^{n-1/2}; each zone reads its corners before overwriting them.
  const double *fpx = s.corner_fx.data(), *fpy = s.corner_fy.data();
  const bool bulk_q = !s.edge_viscosity;
  const bool objective = o.stress_update == StressUpdate::objective;
  const bool subzonal_any = o.hourglass == Hourglass::subzonal || o.hourglass == Hourglass::subzonal_triangles;
  const bool subzonal = subzonal_any && o.hourglass_coefficient > 0;
  const Subzones subzones = o.hourglass == Hourglass::subzonal ? Subzones::corners : Subzones::triangles;
  const double hg = subzonal_any ? 0.0 : o.hourglass_coefficient;
  const bool fb = o.hourglass == Hourglass::flanagan_belytschko;
  const auto* energy_source = s.problem.sources && s.problem.sources->energy ? &s.problem.sources->energy : nullptr;
  std::int64_t failure = kNoFailure;

#pragma omp parallel for schedule(static) reduction(min : failure) if (r.end - r.begin > kParallelMin)
  for (Index z = r.begin; z < r.end; ++z) {
    const Index b = cb[z];
    const int n = N ? N : cb[z + 1] - b;
    ZoneVertices v;
    if (pass.px) {
      v = gather_vertices<N>(cp, b, n, pass.px, pass.py);
    } else {
      v.n = n;
      for (int k = 0; k < n; ++k) {
        const Index p = cp[b + k];
        v.x[k] = x[p] + pass.h_position * vx[p];
        v.y[k] = y[p] + pass.h_position * vy[p];
      }
    }
    double ax[kMaxZoneVertices], ay[kMaxZoneVertices], wx[kMaxZoneVertices], wy[kMaxZoneVertices];
    double vnx[kMaxZoneVertices], vny[kMaxZoneVertices];
    corner_gradients<N>(v, ax, ay);
    const double area = polygon_area<N>(v);
    const double mass = s.zone_mass[z];
    const double rho = mass / area;
    // Step 3: predictor energy with the forces already known, e^{n+1/2} = e^n - dt/2 f.v^n / M.
    double work = 0;
    for (int k = 0; k < n; ++k) {
      const Index p = cp[b + k];
      vnx[k] = vx[p];
      vny[k] = vy[p];
      work += fpx[b + k] * vnx[k] + fpy[b + k] * vny[k];
      wx[k] = pass.qvx[p];
      wy[k] = pass.qvy[p];
    }
    double e_half = s.e[z] - pass.dt_half * work / mass;
    if (energy_source && pass.dt_half > 0) {
      // The predictor integrates the energy source too (at the middle of [t^n, t^{n+1/2}]),
      // or the scheme drops to first order in time; the audit counts only step 7's source.
      double cx = 0, cy = 0;
      for (int k = 0; k < n; ++k) cx += v.x[k] / n, cy += v.y[k] / n;
      e_half += pass.dt_half * (*energy_source)(cx, cy, pass.t_eval - 0.5 * pass.dt_half);
    }
    Deviator sh;
    if (m.strength) {
      // S^{n+1/2} = return(S^n + dt/2 dS/dt(S^n, L(v^n) on x^n)).
      const Deviator s0{s.sxx[z], s.syy[z], s.sxy[z]};
      sh = s0;
      if (pass.dt_half > 0) {
        // L(v^n) on x^n: kept from the end of the last step (end_state), bitwise the same.
        const VelocityGradient L{s.grad_xx[z], s.grad_xy[z], s.grad_yx[z], s.grad_yy[z]};
        sh = advance_stress(objective, m.mu, s0, s0, L, pass.dt_half);
        radial_return(m.yield, m.mu, sh);
      }
      s.sxx_half[z] = sh.xx, s.syy_half[z] = sh.yy, s.sxy_half[z] = sh.xy;
    }
    eos::PressureSound ps{};
    const bool in_domain = eos::evaluate(eos, rho, e_half, ps);
    if (!in_domain || !(area > 0)) failure = std::min(failure, failure_code(z, in_domain ? kTangled : kEosDomain));
    double pressure = ps.p;
    if (m.burn) {
      pressure *= burn_fraction(s.burn[z], pass.t_eval, s.lighting_time[z], s.burn_length[z],
                                m.burn->detonation_speed, m.burn, rho, m.rho0_burn);
    }
    const double C = std::sqrt(std::max(ps.c2, 0.0) + (m.strength ? (4.0 / 3.0) * m.mu / rho : 0.0));
    // Step 5: bulk q from div v* on the half geometry (NUMERICS section 7).
    double div = 0;
    for (int k = 0; k < n; ++k) div += wx[k] * ax[k] + wy[k] * ay[k];
    div /= area;
    double qz = 0;
    if (bulk_q && div < 0) {
      const double l = characteristic_length<N>(v, area);
      qz = rho * l * (-div) * (o.q2 * C + o.q1 * l * (-div));
    }
    s.q[z] = qz;
    if (s.edge_viscosity) {
      s.rho_half[z] = rho;
      s.c_half[z] = C;
    }
    // f_c = -sigma a_c with sigma = S - (p + q) I.
    const double P = pressure + qz;
    const double sxx = sh.xx - P, syy = sh.yy - P, sxy = sh.xy;
    double* ofx = pass.out_fx + b;
    double* ofy = pass.out_fy + b;
    for (int k = 0; k < n; ++k) {
      ofx[k] = -(sxx * ax[k] + sxy * ay[k]);
      ofy[k] = -(sxy * ax[k] + syy * ay[k]);
    }
    // Hourglass force with v* (quads): f_k = -a g_k h, a = Q/4 rho C sqrt(A).
    if (hg > 0 && n == 4) {
      double g[4] = {1, -1, 1, -1};
      if (fb) {
        // Flanagan-Belytschko: project out linear fields, g = G - (G.x) a_x/A - (G.y) a_y/A.
        const double gxs = v.x[0] - v.x[1] + v.x[2] - v.x[3], gys = v.y[0] - v.y[1] + v.y[2] - v.y[3];
        for (int k = 0; k < 4; ++k) g[k] -= (gxs * ax[k] + gys * ay[k]) / area;
      }
      double hx = 0, hy = 0;
      for (int k = 0; k < 4; ++k) hx += g[k] * wx[k], hy += g[k] * wy[k];
      const double a = 0.25 * hg * rho * C * std::sqrt(area);
      for (int k = 0; k < 4; ++k) {
        ofx[k] -= a * g[k] * hx;
        ofy[k] -= a * g[k] * hy;
      }
    }
    if (subzonal)  // docs/algorithm.md §15
      add_subzonal_pressure_forces<N>(v, s.corner_mass.data() + b, mass, area, std::max(ps.c2, 0.0),
                                      o.hourglass_coefficient, subzones, ofx, ofy);
  }
  return failure;
}

// Edge viscosity of Caramana, Shashkov & Whalen (JCP 144, 1998) with Christensen's limiter,
// added to the corner forces (NUMERICS section 7). Uses v* (or v^n) and the force geometry.
void edge_viscosity_forces(Simulation::Impl& s, const ForcePass& pass) {
  const HydroOptions& o = s.problem.options;
  const Index* cb = s.zone_corner_begin.data();
  const Index* cp = s.corner_point.data();
  const double *px = pass.px, *py = pass.py, *wx = pass.qvx, *wy = pass.qvy;
  for (const ZoneRange& r : s.ranges) {
    const RangeModel m = range_model(s, r);
    const double g1 = m.edge_gamma_factor;
#pragma omp parallel for schedule(static) if (r.end - r.begin > kParallelMin)
    for (Index z = r.begin; z < r.end; ++z) {
      const Index b = cb[z];
      const int n = cb[z + 1] - b;
      double cx = 0, cy = 0;
      for (int k = 0; k < n; ++k) cx += px[cp[b + k]], cy += py[cp[b + k]];
      cx /= n;
      cy /= n;
      const double rho = s.rho_half[z], C = s.c_half[z];
      for (int k = 0; k < n; ++k) {
        const Index p0 = cp[b + k], p1 = cp[b + (k + 1) % n];
        const double dux = wx[p1] - wx[p0], duy = wy[p1] - wy[p0];
        const double dxx = px[p1] - px[p0], dxy = py[p1] - py[p0];
        if (dux * dxx + duy * dxy >= 0) continue;  // only compressing edges
        const double du2 = dux * dux + duy * duy;
        const double du = std::sqrt(du2);
        double psi = 0;
        if (o.edge_limiter) {
          // Ratios of the velocity gradient along the edges continuing this one.
          const double len = std::sqrt(dxx * dxx + dxy * dxy);
          const double gx = dux / len, gy = duy / len, gg = gx * gx + gy * gy;
          const EdgeContinuation& ec = s.continuation[b + k];
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
            rho * (o.edge_c2 * g1 * du + std::sqrt(o.edge_c2 * o.edge_c2 * g1 * g1 * du2 + o.edge_c1 * o.edge_c1 * C * C)) *
            (1 - psi);
        const double f = coef * proj;
        // Equal and opposite: it slows the approach of p0 and p1.
        pass.out_fx[b + k] += f * dux;
        pass.out_fy[b + k] += f * duy;
        const Index c1 = b + (k + 1) % n;
        pass.out_fx[c1] -= f * dux;
        pass.out_fy[c1] -= f * duy;
      }
    }
  }
}

// The end-of-step zone state (step 9), shared with recompute_state so that a restart
// reproduces it bitwise. Returns the failure code or kNoFailure.
template <int N, class Eos>
[[gnu::always_inline]] inline std::int64_t end_state(Simulation::Impl& s, Index z, const ZoneVertices& v, const double* ux, const double* uy,
                              double energy, double burn, const Eos& eos, const RangeModel& m, double& dt_zone) {
  const HydroOptions& o = s.problem.options;
  double ca[kMaxZoneVertices], ax[kMaxZoneVertices], ay[kMaxZoneVertices];
  const double area = polygon_area<N>(v);
  if (!(area > 0) || (o.check_corner_areas && !(corner_areas<N>(v, ca) > 0))) return failure_code(z, kTangled);
  const double rho = s.zone_mass[z] / area;
  eos::PressureSound ps{};
  if (!eos::evaluate(eos, rho, energy, ps) || energy < m.min_energy) return failure_code(z, kEosDomain);
  const double C = std::sqrt(std::max(ps.c2, 0.0) + (m.strength ? (4.0 / 3.0) * m.mu / rho : 0.0));
  s.area[z] = area;
  s.rho[z] = rho;
  s.p[z] = m.burn ? burn * ps.p : ps.p;
  s.c[z] = C;
  if (!std::isfinite(s.p[z]) || !std::isfinite(C)) return failure_code(z, kNotFinite);
  corner_gradients<N>(v, ax, ay);
  double div = 0;
  for (int k = 0; k < (N ? N : v.n); ++k) div += ux[k] * ax[k] + uy[k] * ay[k];
  div /= area;
  if (m.strength) {
    // The next step's predictor needs L(v^n) on x^n: this is it.
    const VelocityGradient L = velocity_gradient(N ? N : v.n, ux, uy, ax, ay, area);
    s.grad_xx[z] = L.xx, s.grad_xy[z] = L.xy, s.grad_yx[z] = L.yx, s.grad_yy[z] = L.yy;
  }
  dt_zone = zone_time_step(o.cfl, o.q1, o.q2, o.volume_limit, characteristic_length<N>(v, area), C, div);
  return kNoFailure;
}

struct DtChoice {
  double dt = 1e300;
  Index zone = -1;
};

// Z2: energy, stress, end geometry, EOS and dt candidate (steps 7, 8, 9).
template <int N, class Eos>
std::int64_t finish_zones(Simulation::Impl& s, const ZoneRange& r, const Eos& eos, const RangeModel& m, double dt,
                          double t_new, DtChoice& choice) {
  const HydroOptions& o = s.problem.options;
  const Index* cb = s.zone_corner_begin.data();
  const Index* cp = s.corner_point.data();
  const double *vx = s.vx.data(), *vy = s.vy.data(), *ux = s.vx_new.data(), *uy = s.vy_new.data();
  const double *fx = s.corner_fx.data(), *fy = s.corner_fy.data();
  const double *x = s.x.data(), *y = s.y.data();
  const bool objective = o.stress_update == StressUpdate::objective;
  const auto* energy_source = s.problem.sources && s.problem.sources->energy ? &s.problem.sources->energy : nullptr;
  std::int64_t failure = kNoFailure;
  DtChoice best;
#pragma omp parallel if (r.end - r.begin > kParallelMin)
  {
    DtChoice local;
#pragma omp for schedule(static) reduction(min : failure) nowait
    for (Index z = r.begin; z < r.end; ++z) {
      const Index b = cb[z];
      const int n = N ? N : cb[z + 1] - b;
      double bx[kMaxZoneVertices], by[kMaxZoneVertices], nx[kMaxZoneVertices], ny[kMaxZoneVertices];
      double work = 0;
      for (int k = 0; k < n; ++k) {
        const Index p = cp[b + k];
        nx[k] = ux[p];
        ny[k] = uy[p];
        bx[k] = 0.5 * (vx[p] + nx[k]);
        by[k] = 0.5 * (vy[p] + ny[k]);
        work += fx[b + k] * bx[k] + fy[b + k] * by[k];
      }
      // Step 7: M_z (e^{n+1} - e^n) = -dt sum_c f_c . v_bar (section 4).
      double energy = s.e[z] - dt * work / s.zone_mass[z];
      if (energy_source) {
        const ZoneVertices vh = gather_vertices<N>(cp, b, n, s.x_half.data(), s.y_half.data());
        double cx = 0, cy = 0;
        for (int k = 0; k < n; ++k) cx += vh.x[k] / n, cy += vh.y[k] / n;
        const double se = (*energy_source)(cx, cy, t_new - 0.5 * dt);
        energy += dt * se;
        s.source_energy[z] = dt * se * s.zone_mass[z];
      }
      s.e_new[z] = energy;
      // Step 8: S^{n+1} = return(S^n + dt dS/dt(S^{n+1/2}, L(v_bar) on the half geometry)).
      if (m.strength) {
        const ZoneVertices vh = gather_vertices<N>(cp, b, n, s.x_half.data(), s.y_half.data());
        double ax[kMaxZoneVertices], ay[kMaxZoneVertices];
        corner_gradients<N>(vh, ax, ay);
        const VelocityGradient L = velocity_gradient(n, bx, by, ax, ay, polygon_area<N>(vh));
        Deviator sn = advance_stress(objective, m.mu, {s.sxx[z], s.syy[z], s.sxy[z]},
                                     {s.sxx_half[z], s.syy_half[z], s.sxy_half[z]}, L, dt);
        s.plastic_new[z] = s.plastic[z] + radial_return(m.yield, m.mu, sn);
        s.sxx_new[z] = sn.xx, s.syy_new[z] = sn.yy, s.sxy_new[z] = sn.xy;
      }
      // Step 9: end geometry, density, EOS, time-step candidate.
      // x^{n+1} = x^n + dt v_bar, computed here and committed after the whole step succeeds.
      ZoneVertices ve;
      ve.n = n;
      for (int k = 0; k < n; ++k) {
        const Index p = cp[b + k];
        ve.x[k] = x[p] + dt * 0.5 * (vx[p] + ux[p]);
        ve.y[k] = y[p] + dt * 0.5 * (vy[p] + uy[p]);
      }
      double burn = 1;
      if (m.burn) {
        burn = burn_fraction(s.burn[z], t_new, s.lighting_time[z], s.burn_length[z], m.burn->detonation_speed, m.burn,
                             s.zone_mass[z] / polygon_area<N>(ve), m.rho0_burn);
        s.burn_new[z] = burn;
      }
      double dtz = 1e300;
      std::int64_t code = end_state<N>(s, z, ve, nx, ny, energy, burn, eos, m, dtz);
      if (code == kNoFailure && !std::isfinite(energy)) code = failure_code(z, kNotFinite);
      failure = std::min(failure, code);
      if (dtz < local.dt) local = {dtz, z};
    }
#pragma omp critical
    if (local.dt < best.dt || (local.dt == best.dt && local.zone < best.zone && local.zone >= 0)) best = local;
  }
  if (best.dt < choice.dt || (best.dt == choice.dt && best.zone < choice.zone)) choice = best;
  return failure;
}

template <class F>
void for_each_range(Simulation::Impl& s, F&& f) {
  for (const ZoneRange& r : s.ranges) {
    const RangeModel m = range_model(s, r);
    std::visit([&](const auto& eos) { f(r, eos, m); }, m.material->eos);
  }
}

}  // namespace

std::string describe_zone(const Simulation::Impl& s, Index z) {
  const Mesh& m = s.mesh();
  std::ostringstream out;
  out << "zone " << z << " (region '" << m.region_names[m.zone_region[z]] << "', points";
  for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
    const Index p = m.corner_point[c];
    out << ' ' << p << " (" << s.x[p] << ", " << s.y[p] << ")";
  }
  out << ")";
  return out.str();
}

namespace {
[[noreturn]] void throw_zone_failure(const Simulation::Impl& s, std::int64_t code, const std::string& what_step) {
  const Index z = static_cast<Index>(code / 4);
  const int kind = static_cast<int>(code % 4);
  std::ostringstream msg;
  msg << "cycle " << s.cycle << ", t = " << s.t << ": " << describe_zone(s, z);
  if (kind == kEosDomain) {
    msg << " left the domain of its equation of state " << what_step << " (start-of-step density " << s.rho[z]
        << ", specific internal energy " << s.e[z] << "): the zone is over-compressed or over-expanded";
  } else if (kind == kNotFinite) {
    msg << " has a non-finite state (NaN or Inf) " << what_step;
  } else {
    msg << " has a non-positive area " << what_step;
  }
  throw Error(msg.str());
}
}  // namespace

void Simulation::Impl::recompute_state() {
  DtChoice best;
  std::int64_t failure = kNoFailure;
  const bool quads = all_quads;
  for_each_range(*this, [&](const ZoneRange& r, const auto& eos, const RangeModel& m) {
    DtChoice range_best;
#pragma omp parallel if (r.end - r.begin > kParallelMin)
    {
      DtChoice local;
#pragma omp for schedule(static) reduction(min : failure) nowait
      for (Index z = r.begin; z < r.end; ++z) {
        const Index b = zone_corner_begin[z];
        const int n = zone_corner_begin[z + 1] - b;
        const ZoneVertices v = gather_vertices<0>(corner_point.data(), b, n, x.data(), y.data());
        double ux[kMaxZoneVertices], uy[kMaxZoneVertices];
        for (int k = 0; k < n; ++k) ux[k] = vx[corner_point[b + k]], uy[k] = vy[corner_point[b + k]];
        double dtz = 1e300;
        const std::int64_t code = quads ? end_state<4>(*this, z, v, ux, uy, e[z], any_burn ? burn[z] : 1.0, eos, m, dtz)
                                        : end_state<0>(*this, z, v, ux, uy, e[z], any_burn ? burn[z] : 1.0, eos, m, dtz);
        failure = std::min(failure, code);
        if (dtz < local.dt) local = {dtz, z};
      }
#pragma omp critical
      if (local.dt < range_best.dt || (local.dt == range_best.dt && local.zone < range_best.zone && local.zone >= 0))
        range_best = local;
    }
    if (range_best.dt < best.dt || (range_best.dt == best.dt && range_best.zone < best.zone)) best = range_best;
  });
  if (failure != kNoFailure) throw_zone_failure(*this, failure, "in the initial or restored state");
  dt_next = best.dt;
  dt_zone = best.zone;
}

void Simulation::Impl::evaluate_forces_now() {
  ForcePass pass{x.data(), y.data(), 0.0, vx.data(), vy.data(), 0.0, t, corner_fx.data(), corner_fy.data()};
  std::int64_t failure = kNoFailure;
  for_each_range(*this, [&](const ZoneRange& r, const auto& eos, const RangeModel& m) {
    failure = std::min(failure, all_quads ? force_zones<4>(*this, r, eos, m, pass) : force_zones<0>(*this, r, eos, m, pass));
  });
  if (failure != kNoFailure) throw_zone_failure(*this, failure, "while evaluating forces");
  if (edge_viscosity) edge_viscosity_forces(*this, pass);
}

// External point forces at the half step: applied pressures (boundary work) and momentum
// sources (source work), on the half-step geometry (NUMERICS section 9).
void Simulation::Impl::external_forces(double t_half) {
  std::fill(ext_fx.begin(), ext_fx.end(), 0.0);
  std::fill(ext_fy.begin(), ext_fy.end(), 0.0);
  add_pressure_forces(*this, x_half, y_half, t_half, ext_fx, ext_fy);
  if (!(problem.sources && problem.sources->momentum)) return;
  std::fill(src_fx.begin(), src_fx.end(), 0.0);
  std::fill(src_fy.begin(), src_fy.end(), 0.0);
  // Median-dual area of each point on the half geometry, from the corner areas.
  const Index nz = mesh().num_zones();
#pragma omp parallel for schedule(static) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    const Index b = zone_corner_begin[z];
    const int n = zone_corner_begin[z + 1] - b;
    const ZoneVertices v = gather_vertices<0>(corner_point.data(), b, n, x_half.data(), y_half.data());
    corner_areas(v, corner_scratch.data() + b);
  }
  const Index np = mesh().num_points();
  const auto& momentum = problem.sources->momentum;
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    double vp = 0;
    for (Index k = point_corner_begin[p]; k < point_corner_begin[p + 1]; ++k) vp += corner_scratch[point_corners[k]];
    const auto f = momentum(x_half[p], y_half[p], t_half);
    src_fx[p] = vp * f[0];
    src_fy[p] = vp * f[1];
  }
  // Periodic copies of a point are one point: each copy holds part of its dual area, so the
  // group's force is the sum over its copies, shared among them by mass.
  for (const auto& group : periodic_groups) {
    double mass = 0, fx = 0, fy = 0;
    for (Index p : group) mass += point_mass[p], fx += src_fx[p], fy += src_fy[p];
    for (Index p : group) {
      src_fx[p] = fx * point_mass[p] / mass;
      src_fy[p] = fy * point_mass[p] / mass;
    }
  }
}

bool Simulation::Impl::try_step(double dt) {
  const Index np = mesh().num_points();
  const double t_half = t + 0.5 * dt, t_new = t + dt;
  const double* M = point_mass.data();
  const Index* pcb = point_corner_begin.data();
  const Index* pc = point_corners.data();

  // Step 1: predictor forces f^{n-1/2} (or f^n on the first cycle / fresh option).
  if (!have_previous_forces || problem.options.fresh_predictor) evaluate_forces_now();

  // P1 (steps 1, 2, 4): half positions and predicted half-step velocity v*.
  {
    const double h = 0.5 * dt;
    const double *fpx = corner_fx.data(), *fpy = corner_fy.data();
    const bool store_half = !x_half.empty();
#pragma omp parallel for schedule(static) if (np > kParallelMin)
    for (Index p = 0; p < np; ++p) {
      double Fx = 0, Fy = 0;
      for (Index k = pcb[p]; k < pcb[p + 1]; ++k) Fx += fpx[pc[k]], Fy += fpy[pc[k]];
      if (store_half) {
        x_half[p] = x[p] + h * vx[p];
        y_half[p] = y[p] + h * vy[p];
      }
      vx_star[p] = vx[p] + h * Fx / M[p];
      vy_star[p] = vy[p] + h * Fy / M[p];
    }
    if (has_external) {
      external_forces(t_half);
      const bool sources = !src_fx.empty();
      for (Index p = 0; p < np; ++p) {
        vx_star[p] += h * (ext_fx[p] + (sources ? src_fx[p] : 0.0)) / M[p];
        vy_star[p] += h * (ext_fy[p] + (sources ? src_fy[p] : 0.0)) / M[p];
      }
    }
    apply_constraints(*this, vx_star, vy_star, t_half);
  }

  // Z1 (steps 2, 3, 5): half-step state and the corner forces f^{n+1/2}.
  ForcePass pass{x_half.empty() ? nullptr : x_half.data(),
                 x_half.empty() ? nullptr : y_half.data(),
                 0.5 * dt,
                 vx_star.data(),
                 vy_star.data(),
                 0.5 * dt,
                 t_half,
                 corner_fx.data(),
                 corner_fy.data()};
  std::int64_t failure = kNoFailure;
  for_each_range(*this, [&](const ZoneRange& r, const auto& eos, const RangeModel& m) {
    failure = std::min(failure, all_quads ? force_zones<4>(*this, r, eos, m, pass) : force_zones<0>(*this, r, eos, m, pass));
  });
  if (failure != kNoFailure) {
    have_previous_forces = false;  // the corner forces now hold this failed attempt's
    if (failure % 4 == kTangled) return false;
    throw_zone_failure(*this, failure, "at the half step");
  }
  if (edge_viscosity) edge_viscosity_forces(*this, pass);

  // P2 (step 6): momentum with the same corner forces, constraints, positions.
  {
    const double *fxp = corner_fx.data(), *fyp = corner_fy.data();
    const bool external = has_external, sources = !src_fx.empty();
#pragma omp parallel for schedule(static) if (np > kParallelMin)
    for (Index p = 0; p < np; ++p) {
      double Fx = 0, Fy = 0;
      for (Index k = pcb[p]; k < pcb[p + 1]; ++k) Fx += fxp[pc[k]], Fy += fyp[pc[k]];
      if (external) {
        Fx += ext_fx[p] + (sources ? src_fx[p] : 0.0);
        Fy += ext_fy[p] + (sources ? src_fy[p] : 0.0);
      }
      vx_new[p] = vx[p] + dt * Fx / M[p];
      vy_new[p] = vy[p] + dt * Fy / M[p];
    }
    for (std::size_t i = 0; i < constrained.size(); ++i) {
      free_vx[i] = vx_new[constrained[i]];
      free_vy[i] = vy_new[constrained[i]];
    }
    apply_constraints(*this, vx_new, vy_new, t_new);
  }

  // Z2 (steps 7, 8, 9).
  DtChoice choice;
  failure = kNoFailure;
  for_each_range(*this, [&](const ZoneRange& r, const auto& eos, const RangeModel& m) {
    failure = std::min(failure, all_quads ? finish_zones<4>(*this, r, eos, m, dt, t_new, choice)
                                          : finish_zones<0>(*this, r, eos, m, dt, t_new, choice));
  });
  if (failure != kNoFailure) {
    have_previous_forces = false;
    recompute_state();  // restore area, density, pressure of the start of the step
    if (failure % 4 == kTangled) return false;
    throw_zone_failure(*this, failure, "at the end of the step");
  }

  // Work of constraints, applied pressures and sources, with the same v_bar (section 9).
  double constraint_work = 0, external_work = 0, source_added = 0;
  for (std::size_t i = 0; i < constrained.size(); ++i) {
    const Index p = constrained[i];
    const double bx = 0.5 * (vx[p] + vx_new[p]), by = 0.5 * (vy[p] + vy_new[p]);
    constraint_work += M[p] * ((vx_new[p] - free_vx[i]) * bx + (vy_new[p] - free_vy[i]) * by);
  }
  if (has_external) {
    for (Index p = 0; p < np; ++p) {
      const double bx = 0.5 * (vx[p] + vx_new[p]), by = 0.5 * (vy[p] + vy_new[p]);
      external_work += dt * (ext_fx[p] * bx + ext_fy[p] * by);
      if (!src_fx.empty()) source_added += dt * (src_fx[p] * bx + src_fy[p] * by);
    }
  }
  if (!source_energy.empty())
    for (double w : source_energy) source_added += w;

  // Commit: x^{n+1} = x^n + dt v_bar (the same expression as in Z2), then the state.
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    x[p] = x[p] + dt * 0.5 * (vx[p] + vx_new[p]);
    y[p] = y[p] + dt * 0.5 * (vy[p] + vy_new[p]);
  }
  vx.swap(vx_new);
  vy.swap(vy_new);
  e.swap(e_new);
  if (any_strength) {
    sxx.swap(sxx_new);
    syy.swap(syy_new);
    sxy.swap(sxy_new);
    plastic.swap(plastic_new);
  }
  if (any_burn) burn.swap(burn_new);
  have_previous_forces = true;
  boundary_work += constraint_work + external_work;
  source_work += source_added;
  t = t_new;
  ++cycle;
  dt_last = dt;
  dt_next = choice.dt;
  dt_zone = choice.zone;
  return true;
}

void Simulation::Impl::step(double t_stop) {
  if (t_stop <= t) return;
  const HydroOptions& o = problem.options;
  // Time-step control (section 6): CFL and volume limits from the end of the last step,
  // growth limit, dt_max, first-step dt_init; land exactly on t_stop.
  double dt = dt_next;
  dt_reason = DtReason::cfl;
  if (cycle > 0 && dt > o.dt_growth * dt_control_prev) dt = o.dt_growth * dt_control_prev, dt_reason = DtReason::growth;
  if (cycle == 0 && o.dt_init > 0 && o.dt_init < dt) dt = o.dt_init, dt_reason = DtReason::initial;
  if (o.dt_max > 0 && dt > o.dt_max) dt = o.dt_max, dt_reason = DtReason::maximum;
  for (int attempt = 0;; ++attempt) {
    if (dt < dt_min) {
      std::ostringstream msg;
      msg << "time step collapsed at cycle " << cycle << ", t = " << t << ": dt = " << dt << " < dt_min = " << dt_min;
      if (dt_zone >= 0 && dt_zone < mesh().num_zones()) {
        const Index z = dt_zone;
        msg << "; limiting " << describe_zone(*this, z) << ", area " << area[z] << ", sound speed " << c[z]
            << ", density " << rho[z];
      }
      msg << " (the mesh is tangling or a zone is being crushed: refine the mesh, lower the cfl, or raise the viscosity)";
      throw Error(msg.str());
    }
    dt_control_prev = dt;
    const bool clipped = t + dt >= t_stop;
    const double dt_taken = clipped ? t_stop - t : dt;
    if (try_step(dt_taken)) {
      if (clipped) t = t_stop, dt_reason = DtReason::landing;  // land exactly
      break;
    }
    if (attempt >= o.max_retries) {
      // Report the tangled zone at the end of the last attempt.
      std::ostringstream msg;
      msg << "cycle " << cycle << ", t = " << t << ": a zone tangled (non-positive zone or corner area) even with dt = "
          << dt_taken << " after " << attempt << " retries";
      const Index tangled = find_tangled_zone(dt_taken);
      if (tangled >= 0) msg << "; " << describe_zone(*this, tangled);
      msg << " (the mesh is folding there: add hourglass control, switch to the edge viscosity, lower the cfl or "
             "refine the mesh; if the zone only turned non-convex, numerics.check_corner_areas = false)";
      throw Error(msg.str());
    }
    dt *= 0.5;
    dt_reason = DtReason::retry;
  }
  if (remap) {
    RemapState state{mesh(), t, cycle, x, y, vx, vy, e, sxx, syy, sxy, zone_mass, point_mass, area};
    if (remap->remap(state)) recompute_state();
  }
  if (observer) observer(*owner);
}

// The lowest zone whose end-of-step geometry is tangled for a step of dt (diagnostics only).
Index Simulation::Impl::find_tangled_zone(double dt) {
  const Index nz = mesh().num_zones();
  for (Index z = 0; z < nz; ++z) {
    const Index b = zone_corner_begin[z];
    const int n = zone_corner_begin[z + 1] - b;
    // End positions of the failed attempt (v_new is still its velocity).
    ZoneVertices v;
    v.n = n;
    for (int k = 0; k < n; ++k) {
      const Index p = corner_point[b + k];
      v.x[k] = x[p] + dt * 0.5 * (vx[p] + vx_new[p]);
      v.y[k] = y[p] + dt * 0.5 * (vy[p] + vy_new[p]);
    }
    double ca[kMaxZoneVertices];
    const double smallest_corner = corner_areas(v, ca);
    if (!(polygon_area(v) > 0) || (problem.options.check_corner_areas && !(smallest_corner > 0))) return z;
  }
  return -1;
}

double Simulation::Impl::kinetic_energy() const {
  // Fixed blocks in a fixed order: the same sum for any thread count.
  const Index np = mesh().num_points();
  constexpr Index block = 4096;
  const Index nblocks = (np + block - 1) / block;
  double total = 0;
  for (Index bl = 0; bl < nblocks; ++bl) {
    double sum = 0;
    for (Index p = bl * block; p < std::min(np, (bl + 1) * block); ++p)
      sum += 0.5 * point_mass[p] * (vx[p] * vx[p] + vy[p] * vy[p]);
    total += sum;
  }
  return total;
}

double Simulation::Impl::internal_energy() const {
  const Index nz = mesh().num_zones();
  constexpr Index block = 4096;
  const Index nblocks = (nz + block - 1) / block;
  double total = 0;
  for (Index bl = 0; bl < nblocks; ++bl) {
    double sum = 0;
    for (Index z = bl * block; z < std::min(nz, (bl + 1) * block); ++z) sum += zone_mass[z] * e[z];
    total += sum;
  }
  return total;
}

}  // namespace stagger
