#pragma once
// Loop Z1 of the step (docs/algorithm.md §1, steps 2, 3 and 5): per zone, the half-step
// geometry and state and the corner forces f^{n+1/2}. One fused loop calling the kernels,
// over explicit inputs and outputs.
#include <algorithm>
#include <cstdint>

#include "eos/eos_kernels.hpp"
#include "hydro/kernels/burn.hpp"
#include "hydro/kernels/corner_forces.hpp"
#include "hydro/kernels/energy.hpp"
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/hourglass.hpp"
#include "hydro/kernels/rz.hpp"
#include "hydro/kernels/strength.hpp"
#include "hydro/kernels/subzonal_pressure.hpp"
#include "hydro/kernels/viscosity_bulk.hpp"
#include "hydro/kernels/viscosity_tensor.hpp"
#include "hydro/kernels/zone_model.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "stagger/problem.hpp"

namespace stagger {

// Read-only inputs of Z1 (per point, per zone, per corner arrays; null where absent).
struct ZoneForceInput {
  const Index* zone_corner_begin;
  const Index* corner_point;
  // Positions of the force geometry: (px, py) when given (x^n, or the stored x^{n+1/2}), else
  // x^n + h_position v^n formed on the fly (the half step without an array).
  const double *px, *py;
  double h_position;
  const double *x, *y, *vx, *vy;  // x^n, v^n
  const double *qvx, *qvy;        // velocity for q and hourglass (v*, or v^n)
  // Predictor forces f^{n-1/2} per corner. They may be the output arrays: each zone reads
  // its own corners before it overwrites them.
  const double *f_prev_x, *f_prev_y;
  const double *zone_mass, *e;
  const double *sxx, *syy, *sxy, *plastic;              // S^n, eps_p^n (strength)
  const double *grad_xx, *grad_xy, *grad_yx, *grad_yy;  // L(v^n) on x^n (strength)
  const double *burn, *lighting_time, *burn_length;     // (burn)
  const EnergySource* energy_source;                    // null: none
  double dt_half;              // t_eval - t^n: dt/2 for the predictor state, 0 for an evaluation at t^n
  double t_eval;               // time of the force evaluation
  const double* subzone_mass;  // constant subzonal masses per corner (subzonal hourglass options)
  const double* heat_rate;     // heat flux energy rate per zone at t^n (docs/algorithm.md §21); null: off
};

// Outputs of Z1, written per zone (null where absent).
struct ZoneForceOutput {
  double *fx, *fy;                         // f^{n+1/2} per corner (overwritten)
  double* q;                               // bulk q
  double *rho_half, *c_half;               // half-step density and C (edge viscosity)
  double *sxx_half, *syy_half, *sxy_half;  // S^{n+1/2} (strength)
};

// Z1 needs none of strength, burn, energy source, heat flux, tensor q or subzonal pressures
// (the gas with bulk q, hourglass or edge viscosity): zone_forces_loop<N, G, true> then gives the
// same bits without testing for them per zone (docs/benchmarks.md, "Lagrangian step speed").
inline bool plain_zone_forces(const ZoneForceInput& in, const HydroOptions& o, const ZoneModel& m) {
  const bool subzonal_hourglass = o.hourglass == Hourglass::subzonal || o.hourglass == Hourglass::subzonal_triangles;
  return !m.strength && !m.burn && !in.energy_source && !in.heat_rate && o.viscosity != Viscosity::tensor &&
         !subzonal_hourglass;
}

// Z1 over the zones [begin, end) of one material (EOS `eos`, constants `m`). Returns the
// lowest zone's failure code, kNoFailure if none. kPlain: plain_zone_forces holds, and the
// tests for what it excludes are compiled out.
template <int N, class Geometry, bool kPlain = false, class Eos>
std::int64_t zone_forces_loop(const ZoneForceInput& input, const HydroOptions& o, const ZoneModel& m, const Eos& eos,
                              Index begin, Index end, const ZoneForceOutput& output) {
  // Thread-private copies: the loop's stores cannot alias them, so their fields stay in
  // registers (through the caller's references every field would be reloaded per zone).
  const ZoneForceInput in = input;
  const ZoneForceOutput out = output;
  const Index* cb = in.zone_corner_begin;
  const Index* cp = in.corner_point;
  const double *vx = in.vx, *vy = in.vy, *x = in.x, *y = in.y;
  const bool bulk_q = o.viscosity == Viscosity::bulk;
  const bool tensor_q = !kPlain && o.viscosity == Viscosity::tensor;
  const bool objective = o.stress_update == StressUpdate::objective;
  const bool subzonal_any = o.hourglass == Hourglass::subzonal || o.hourglass == Hourglass::subzonal_triangles;
  const bool subzonal = !kPlain && subzonal_any && o.hourglass_coefficient > 0;
  const Subzones subzones = o.hourglass == Hourglass::subzonal ? Subzones::corners : Subzones::triangles;
  const double hg = subzonal_any ? 0.0 : o.hourglass_coefficient;
  const bool fb = o.hourglass == Hourglass::flanagan_belytschko;
  const bool strength = !kPlain && m.strength, burn = !kPlain && m.burn;
  const bool energy_source = !kPlain && in.energy_source, heat_flux = !kPlain && in.heat_rate;
  std::int64_t failure = kNoFailure;

#pragma omp parallel for schedule(static) reduction(min : failure) firstprivate(in, out) if (end - begin > kParallelMin)
  for (Index z = begin; z < end; ++z) {
    const Index b = cb[z];
    const int n = N ? N : cb[z + 1] - b;
    // Step 2: the half-step geometry.
    ZoneVertices v;
    if (in.px) {
      v = gather_vertices<N>(cp, b, n, in.px, in.py);
    } else {
      v.n = n;
      for (int k = 0; k < n; ++k) {
        const Index p = cp[b + k];
        v.x[k] = x[p] + in.h_position * vx[p];
        v.y[k] = y[p] + in.h_position * vy[p];
      }
    }
    double ax[kMaxZoneVertices], ay[kMaxZoneVertices], wx[kMaxZoneVertices], wy[kMaxZoneVertices];
    double vnx[kMaxZoneVertices], vny[kMaxZoneVertices];
    Geometry::template corner_gradients<N>(v, ax, ay);
    const double area = Geometry::template area<N>(v);
    const double mass = in.zone_mass[z];
    // The mass measure: the area, or in rz the volume per radian (docs/algorithm.md §19).
    double measure = area;
    if constexpr (Geometry::kRz) measure = Geometry::template volume<N>(v);
    const double rho = mass / measure;
    for (int k = 0; k < n; ++k) {
      const Index p = cp[b + k];
      vnx[k] = vx[p];
      vny[k] = vy[p];
      wx[k] = in.qvx[p];
      wy[k] = in.qvy[p];
    }
    // Step 3: the predictor energy with the forces already known, e^{n+1/2} = e^n - dt/2 f.v^n / M.
    // An evaluation at t^n (dt_half = 0) takes e^n as it is: the corner arrays may then hold
    // a failed attempt's forces, non-finite where a zone folded, and 0 * NaN is NaN.
    double e_half = in.e[z];
    if (in.dt_half > 0)
      e_half = energy_after_work(e_half, in.dt_half, corner_work(n, in.f_prev_x + b, in.f_prev_y + b, vnx, vny), mass);
    if (energy_source && in.dt_half > 0) {
      // The predictor integrates the energy source too (at the middle of [t^n, t^{n+1/2}]),
      // or the scheme drops to first order in time; the audit counts only step 7's source.
      const auto [cx, cy] = Geometry::template centre<N>(v);
      e_half += in.dt_half * (*in.energy_source)(cx, cy, in.t_eval - 0.5 * in.dt_half);
    }
    // The heat flux's half step, for the same reason (docs/algorithm.md §21).
    if (heat_flux && in.dt_half > 0) e_half += in.dt_half * in.heat_rate[z] / mass;
    Deviator sh;
    if (strength) {
      // L(v^n) on x^n: kept from the end of the last step, bitwise what recomputing it gives.
      const VelocityGradient L{in.grad_xx[z], in.grad_xy[z], in.grad_yx[z], in.grad_yy[z]};
      if constexpr (Geometry::kRz) {
        // The hoop strain rate of v^n on x^n, which the stored planar L lacks.
        sh = {in.sxx[z], in.syy[z], in.sxy[z]};
        if (in.dt_half > 0) {
          const double hoop = hoop_strain_rate<N>(gather_vertices<N>(cp, b, n, x, y), vnx);
          sh = advance_stress(objective, m.mu, sh, sh, L, in.dt_half);
          add_hoop_stress_rate(m.mu, hoop, in.dt_half, sh);
          radial_return(m.yield, m.hardening, in.plastic[z], m.mu, sh);
        }
      } else {
        sh = predict_stress(objective, m.mu, m.yield, m.hardening, in.plastic[z], {in.sxx[z], in.syy[z], in.sxy[z]}, L,
                            in.dt_half);
      }
      out.sxx_half[z] = sh.xx, out.syy_half[z] = sh.yy, out.sxy_half[z] = sh.xy;
    }
    eos::PressureSound ps{};
    const bool in_domain = eos::evaluate(eos, rho, e_half, ps);
    // The area first: a folded half-step zone has a negative density, which the EOS rejects
    // too, but it is tangling (retried with a smaller dt), not an EOS failure.
    bool folded = !(area > 0);
    if constexpr (Geometry::kRz) {
      folded = folded || !(measure > 0);
      for (int k = 0; k < n; ++k) folded = folded || v.x[k] < 0;  // across the axis
    }
    if (folded) {
      failure = std::min(failure, failure_code(z, kTangled));
    } else if (!in_domain) {
      failure = std::min(failure, failure_code(z, kEosDomain));
    }
    double pressure = ps.p;
    if (burn)
      pressure *= burn_fraction(in.burn[z], in.t_eval, in.lighting_time[z], in.burn_length[z], m.burn_model, rho);
    const double C = full_sound_speed(ps.c2, rho, strength, m.mu);
    // Step 5: bulk q from div v* on the half geometry.
    double div;
    if constexpr (Geometry::kRz) {
      div = Geometry::template volume_divergence<N>(v, wx, wy, measure);
    } else {
      div = Geometry::divergence(n, wx, wy, ax, ay, area);
    }
    double qz = 0;
    if (bulk_q && div < 0)
      qz = bulk_viscosity(rho, Geometry::template characteristic_length<N>(v, area), div, C, o.q1, o.q2);
    out.q[z] = qz;
    if (out.rho_half) {
      out.rho_half[z] = rho;
      out.c_half[z] = C;
    }
    stress_corner_forces(n, sh, pressure + qz, ax, ay, out.fx + b, out.fy + b);
    // Or the tensor q (docs/algorithm.md §4.1), with the same coefficients and velocity.
    if (tensor_q)
      out.q[z] =
          add_tensor_viscosity_forces(n, v.x, v.y, wx, wy, area, Geometry::template characteristic_length<N>(v, area),
                                      rho, C, o.q1, o.q2, out.fx + b, out.fy + b);
    if constexpr (Geometry::kRz) {
      // Area-weighted: the hoop body force on the planar corner areas.
      if (strength) {
        double ca[kMaxZoneVertices];
        Geometry::template corner_areas<N>(v, ca);
        add_hoop_forces(n, sh, ca, measure / area, out.fx + b, out.fy + b);
      }
    }
    // Hourglass force with v* (quads).
    if (hg > 0 && n == 4) add_hourglass_forces(v.x, v.y, ax, ay, area, wx, wy, rho, C, hg, fb, out.fx + b, out.fy + b);
    // Subzonal pressures (any polygon; docs/algorithm.md §18).
    if (subzonal) {
      // rz: the planar subzone masses rho^0 A_k^0 against their sum (area-weighted, like the
      // other forces; docs/algorithm.md §19).
      double subzonal_mass = mass;
      if constexpr (Geometry::kRz) {
        subzonal_mass = 0;
        for (int k = 0; k < n; ++k) subzonal_mass += in.subzone_mass[b + k];
      }
      add_subzonal_pressure_forces<N>(v, in.subzone_mass + b, subzonal_mass, area, std::max(ps.c2, 0.0),
                                      o.hourglass_coefficient, subzones, out.fx + b, out.fy + b);
    }
  }
  return failure;
}

}  // namespace stagger
