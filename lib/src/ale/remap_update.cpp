// The remap's new values from the fluxes (remap.hpp; docs/ale.md, "Remap"): the donor
// remainder bound, the zone, corner and point sums (straight from the flux sweep on one
// thread, gathered from the slots on more), the corner-mass repair, and the points' momentum
// and kinetic energy.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "ale/remap.hpp"
#include "ale/swept_quad.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "stagger/error.hpp"

namespace stagger {

namespace {

// Whether a zone's new value q1 = (m0 q + sum of fluxes) / m1 lies outside its bounds [lo, hi]
// by more than the rounding of that sum and division can give (a few dozen ulps of the bounds,
// scaled by m0 / m1 for a zone that gives most of its mass away). The donor remainder bound is
// for outflows that carried too much of the high or low values (a solid's energy went negative
// by 2e6 J/kg so); a rounding is not that, and a bound acting on it would only add work (the
// zones next to a changed flux are summed again, docs/ale.md "Remap cost"). NaN counts as
// outside.
inline bool beyond_bounds(double q1, double lo, double hi, double m0, double m1) {
  const double tol =
      64 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo), std::abs(hi)) * (std::max(m0, m1) / m1);
  return !(q1 >= lo - tol && q1 <= hi + tol);
}

[[noreturn]] void fail_mass(const Mesh& m, const char* what, Index i, double value) {
  std::ostringstream msg;
  msg << "ALE remap: " << what << " " << i;
  if (std::string(what) == "zone") {
    msg << " (region '" << m.region_names[m.zone_region[i]] << "')";
  }
  msg << " would get the non-positive mass " << value
      << ": the mesh moved too far in one remap for the swept-face fluxes (lower ale.relaxation or "
         "remap more often, docs/ale.md)";
  throw Error(msg.str());
}

// The sum of value[slot] over a list of entries (slot * 2 + 1 where it is subtracted), in the
// list's order.
inline double signed_sum(const Index* begin, const Index* end, const double* value) {
  double s = 0;
  for (const Index* e = begin; e != end; ++e) {
    const double v = value[*e >> 1];
    if (*e & 1)
      s -= v;
    else
      s += v;
  }
  return s;
}

}  // namespace

// The donor's remainder (limiter only): each outflow's mean value is within the donor's
// bounds, but a zone that gives away much of its mass can be left with a value outside them
// (its outflows carried more than their share of the high or low values; a solid's specific
// energy went negative this way). Where that happens, the zone's outflows' deviations from
// its own value are scaled by the largest factor in [0, 1] that keeps its new value within
// its bounds (factor 0: the outflows carry the zone's value, and the new value is a mean of
// that and the inflows). It only changes fluxes, so it conserves, and it leaves every other
// zone's arithmetic as it was. This is the factor of field i in zone z (1: within bounds),
// from the half-side slots as the fluxes left them; m1 = m0 + the slots' mass sum.
double Remapper::remainder_keep(const RemapFields& f, Index z, std::size_t i, double m0, double m1) const {
  const double q = f.specific[i][z];
  if (!std::isfinite(q)) return 1.0;
  const Index nz = mesh_.num_zones();
  const std::size_t nc2 = 2 * static_cast<std::size_t>(mesh_.num_corners());
  const Index* lb = zone_list_.data() + zone_list_begin_[z];
  const Index* le = zone_list_.data() + zone_list_begin_[z + 1];
  const double* fq = flux_q_.data() + i * nc2;
  double all = 0, first = 0;  // with the outflows as they are, and carrying q
  for (const Index* e = lb; e != le; ++e) {
    const std::size_t sl = *e >> 1;
    const double sign = (*e & 1) ? -1.0 : 1.0, mass = sign * flux_mass_[sl], v = sign * fq[sl];
    all += v;
    first += mass < 0 ? mass * q : v;
  }
  const std::size_t id = i * nz + z;
  const double lo = qmin_[id], hi = qmax_[id];
  const double q1 = (m0 * q + all) / m1;
  if (!beyond_bounds(q1, lo, hi, m0, m1)) return 1.0;
  const double q0 = (m0 * q + first) / m1, bound = q1 > hi ? hi : lo;
  const double t = (q1 > hi ? q0 < hi : q0 > lo) ? (bound - q0) / (q1 - q0) : 0.0;
  return std::clamp(t, 0.0, 1.0);
}

// Zone z's outflows of field i keep the fraction t of their deviation from z's value.
void Remapper::keep_outflows(const RemapFields& f, Index z, std::size_t i, double t) {
  const std::size_t nc2 = 2 * static_cast<std::size_t>(mesh_.num_corners());
  const Index* lb = zone_list_.data() + zone_list_begin_[z];
  const Index* le = zone_list_.data() + zone_list_begin_[z + 1];
  const double q = f.specific[i][z];
  double* fq = flux_q_.data() + i * nc2;
  for (const Index* e = lb; e != le; ++e) {
    const std::size_t sl = *e >> 1;
    const double mass = (*e & 1) ? -flux_mass_[sl] : flux_mass_[sl];
    if (mass < 0) fq[sl] = flux_mass_[sl] * q + t * (fq[sl] - flux_mass_[sl] * q);  // z's outflow
  }
}

// The sums of the slots per zone, corner and point, in the serial sweep's order (bitwise the
// same on any number of threads), and the new zone and corner values; a list entry's low bit
// says whether the flux is added or taken.
void Remapper::gather_fluxes(RemapFields& f, bool limiter) {
  if (limiter && remainder_bound_ && !f.specific.empty()) slot_remainder_bound(f);
  gather_zone_values(f);
  gather_corner_point_sums(f);
}

// The donor remainder bound (remainder_keep) on the slots, from every zone's factors before
// any flux changes.
void Remapper::slot_remainder_bound(const RemapFields& f) {
  const Index nz = mesh_.num_zones();
  const std::size_t nf = f.specific.size();
  keep_.assign(nf * static_cast<std::size_t>(nz), 1.0);
  int any = 0;
#pragma omp parallel for schedule(static) reduction(max : any) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    if (!zone_active_[z]) continue;  // no flux, and no bounds computed
    const Index* lb = zone_list_.data() + zone_list_begin_[z];
    const Index* le = zone_list_.data() + zone_list_begin_[z + 1];
    double dm = 0;
    for (const Index* e = lb; e != le; ++e) dm += (*e & 1) ? -flux_mass_[*e >> 1] : flux_mass_[*e >> 1];
    const double m0 = f.zone_mass[z], m1 = m0 + dm;
    if (!(m1 > 0)) continue;
    for (std::size_t i = 0; i < nf; ++i) {
      const double t = remainder_keep(f, z, i, m0, m1);
      keep_[i * nz + z] = t;
      any = std::max(any, t != 1.0 ? 1 : 0);
    }
  }
  if (any) {
    long bounded = 0;
#pragma omp parallel for schedule(static) reduction(+ : bounded) if (nz > kParallelMin)
    for (Index z = 0; z < nz; ++z) {
      bool acted = false;
      for (std::size_t i = 0; i < nf; ++i)
        if (keep_[i * nz + z] != 1.0) keep_outflows(f, z, i, keep_[i * nz + z]), acted = true;
      bounded += acted;
    }
    bounded_ += bounded;
  }
}

// New zone values from the slots: mass plus fluxes, specific quantities from their
// mass-weighted sums.
void Remapper::gather_zone_values(RemapFields& f) {
  const Index nz = mesh_.num_zones();
  const std::size_t nf = f.specific.size(), nc2 = 2 * static_cast<std::size_t>(mesh_.num_corners());
  Index failed_zone = std::numeric_limits<Index>::max();
#pragma omp parallel for schedule(static) reduction(min : failed_zone) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    const Index* lb = zone_list_.data() + zone_list_begin_[z];
    const Index* le = zone_list_.data() + zone_list_begin_[z + 1];
    double dm = 0;
    char touched = 0;
    for (const Index* e = lb; e != le; ++e) {
      const Index s = *e >> 1;
      touched |= flux_active_[s];
      if (*e & 1)
        dm -= flux_mass_[s];
      else
        dm += flux_mass_[s];
    }
    if (!touched) continue;
    const double m0 = f.zone_mass[z], m1 = m0 + dm;
    if (!(m1 > 0)) {
      failed_zone = std::min(failed_zone, z);
      continue;
    }
    for (std::size_t i = 0; i < nf; ++i) {
      double& q = f.specific[i][z];
      if (std::isfinite(q)) q = (m0 * q + signed_sum(lb, le, flux_q_.data() + i * nc2)) / m1;
    }
    f.zone_mass[z] = m1;
  }
  if (failed_zone != std::numeric_limits<Index>::max()) {
    const Index* lb = zone_list_.data() + zone_list_begin_[failed_zone];
    const Index* le = zone_list_.data() + zone_list_begin_[failed_zone + 1];
    fail_mass(mesh_, "zone", failed_zone, f.zone_mass[failed_zone] + signed_sum(lb, le, flux_mass_.data()));
  }
}

// The new corner masses, and the points' sums of mass, momentum and kinetic energy from the
// centre segments' slots (written back by point_momentum).
void Remapper::gather_corner_point_sums(RemapFields& f) {
  const Index np = mesh_.num_points(), nc = mesh_.num_corners();
  const std::size_t nc2 = 2 * static_cast<std::size_t>(nc);
#pragma omp parallel for schedule(static) if (nc > kParallelMin)
  for (Index c = 0; c < nc; ++c) {
    const double dm = signed_sum(corner_list_.data() + corner_list_begin_[c],
                                 corner_list_.data() + corner_list_begin_[c + 1], flux_mass_.data());
    if (dm != 0) f.corner_mass[c] += dm;
  }
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    const Index* lb = point_list_.data() + point_list_begin_[p];
    const Index* le = point_list_.data() + point_list_begin_[p + 1];
    // One pass, four sums, each in the serial order.
    const double* mass = flux_mass_.data() + nc2;
    const char* flag = flux_active_.data() + nc2;
    double sm = 0, sx = 0, sy = 0, sk = 0;
    char a = 0;
    for (const Index* e = lb; e != le; ++e) {
      const Index s = *e >> 1;
      a |= flag[s];
      if (*e & 1)
        sm -= mass[s], sx -= seg_px_[s], sy -= seg_py_[s], sk -= seg_ke_[s];
      else
        sm += mass[s], sx += seg_px_[s], sy += seg_py_[s], sk += seg_ke_[s];
    }
    point_touched_[p] = a;
    dm_point_[p] = sm, dpx_[p] = sx, dpy_[p] = sy, dke_[p] = sk;
  }
}

// The donor remainder bound (remainder_keep) on the direct sums: the half sides' fluxes are
// in their slots too; where the bound acts (a zone's new value outside its bounds, tested
// on the same sums as gather_fluxes tests), the factors of all such zones are taken first,
// then their outflows changed, and the zones next to a changed flux summed again from the
// slots in the same order: bitwise what gather_fluxes gives.
void Remapper::direct_remainder_bound(const RemapFields& f) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones();
  const std::size_t nf = f.specific.size(), nc2 = 2 * static_cast<std::size_t>(m.num_corners());
  bound_zones_.clear();
  for (Index z = 0; z < nz; ++z) {
    if (!zone_hit_[z]) continue;  // no flux: its value stays (a rounding at most)
    const double m0 = f.zone_mass[z], m1 = m0 + zone_dm_[z];
    if (!(m1 > 0)) continue;
    bool acts = false;
    for (std::size_t i = 0; i < nf && !acts; ++i) {
      const double q = f.specific[i][z];
      if (!std::isfinite(q)) continue;
      const std::size_t id = i * nz + z;
      acts = beyond_bounds((m0 * q + zone_dq_[id]) / m1, qmin_[id], qmax_[id], m0, m1);
    }
    if (!acts) continue;
    bound_zones_.push_back(z);  // capacity nz: no allocation
    for (std::size_t i = 0; i < nf; ++i) keep_[i * nz + z] = remainder_keep(f, z, i, m0, m1);
  }
  for (const Index z : bound_zones_) {
    bool acted = false;
    for (std::size_t i = 0; i < nf; ++i)
      if (keep_[i * nz + z] != 1.0) {
        acted = true;
        keep_outflows(f, z, i, keep_[i * nz + z]);
        // The zone and the neighbours across its half sides: their sums again.
        zone_resum_[z] = 1;
        for (Index e = zone_list_begin_[z]; e < zone_list_begin_[z + 1]; ++e) {
          const Index c = zone_list_[e] >> 2;  // slot 2c + h
          zone_resum_[m.corner_zone[c]] = zone_resum_[side_zone_[c]] = 1;
        }
      }
    bounded_ += acted;
  }
  for (Index z = 0; z < nz; ++z) {
    if (!zone_resum_[z]) continue;
    zone_resum_[z] = 0;
    const Index* lb = zone_list_.data() + zone_list_begin_[z];
    const Index* le = zone_list_.data() + zone_list_begin_[z + 1];
    for (std::size_t i = 0; i < nf; ++i) zone_dq_[i * nz + z] = signed_sum(lb, le, flux_q_.data() + i * nc2);
  }
}

// The direct sums are there: the new zone and corner values.
void Remapper::direct_zone_corner_values(RemapFields& f) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones(), nc = m.num_corners();
  const std::size_t nf = f.specific.size();
  Index failed_zone = std::numeric_limits<Index>::max();
  for (Index z = 0; z < nz; ++z) {
    if (!zone_hit_[z]) continue;
    const double m0 = f.zone_mass[z], m1 = m0 + zone_dm_[z];
    if (!(m1 > 0)) {
      failed_zone = std::min(failed_zone, z);
      continue;
    }
    for (std::size_t i = 0; i < nf; ++i) {
      double& q = f.specific[i][z];
      if (std::isfinite(q)) q = (m0 * q + zone_dq_[i * nz + z]) / m1;
    }
    f.zone_mass[z] = m1;
  }
  if (failed_zone != std::numeric_limits<Index>::max())
    fail_mass(m, "zone", failed_zone, f.zone_mass[failed_zone] + zone_dm_[failed_zone]);
  for (Index c = 0; c < nc; ++c)
    if (corner_dm_[c] != 0) f.corner_mass[c] += corner_dm_[c];
}

// Repair: a zone whose corner kept less than a hundredth of its share (subcell densities
// can drift apart where the mesh and the flow shear; a swept region then takes more than
// the corner holds) gets its corner masses reset to its new mass shared by new corner area.
// The zone mass stays; the points' masses change by the difference, their momentum does
// not, and the kinetic energy this changes is part of the fix-up.
template <bool Rz>
void Remapper::repair_corner_masses(const double* xn, const double* yn, RemapFields& f) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones();
  for (Index z = 0; z < nz; ++z) {
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    bool bad = false;
    for (Index k = 0; k < n; ++k) bad = bad || !(f.corner_mass[b + k] > 0.01 * f.zone_mass[z] / n);
    if (!bad) continue;
    double gx = 0, gy = 0;
    for (Index k = 0; k < n; ++k) gx += xn[m.corner_point[b + k]] / n, gy += yn[m.corner_point[b + k]] / n;
    double areas[16], total = 0;
    for (Index k = 0; k < n; ++k) {
      const Index p = m.corner_point[b + k], pn = m.corner_point[b + (k + 1) % n],
                  pp = m.corner_point[b + (k + n - 1) % n];
      areas[k] = swept_quad<Rz>(xn[p], yn[p], 0.5 * (xn[p] + xn[pn]), 0.5 * (yn[p] + yn[pn]), gx, gy,
                                0.5 * (xn[p] + xn[pp]), 0.5 * (yn[p] + yn[pp]), 0.0, 0.0)
                     .area;
      total += areas[k];
    }
    for (Index k = 0; k < n; ++k) {
      const double share = areas[k] > 0 && total > 0 ? f.zone_mass[z] * (areas[k] / total) : 0.0;
      if (!(share > 0)) fail_mass(m, "corner of zone", z, share);
      const Index p = m.corner_point[b + k];
      dm_point_[p] += share - f.corner_mass[b + k];
      point_touched_[p] = 1;
      f.corner_mass[b + k] = share;
    }
    ++repaired_;
  }
}

// The points' new mass, velocity (momentum over mass) and carried kinetic energy (the old
// 1/2 M v^2 plus the fluxes, for the kinetic-energy fix-up); rz axis points take the
// reconstruction at their new position.
template <bool Rz>
void Remapper::point_momentum(const double* xo, const double* yo, const double* xn, const double* yn, RemapFields& f) {
  const Index np = mesh_.num_points();
  Index failed_point = std::numeric_limits<Index>::max();
#pragma omp parallel for schedule(static) reduction(min : failed_point) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    if (Rz && axis_point_[p]) {
      // Massless: the velocity is the (limited) reconstruction at the point's new position.
      const double dx = xn[p] - xo[p], dy = yn[p] - yo[p];
      f.vx[p] += vgx_[p] * dx + vgy_[p] * dy;
      f.vy[p] += wgx_[p] * dx + wgy_[p] * dy;
      if (f.point_kinetic) f.point_kinetic[p] = 0;
      continue;
    }
    const double m0 = f.point_mass[p], u = f.vx[p], w = f.vy[p];
    double ke = 0.5 * m0 * (u * u + w * w);
    if (point_touched_[p]) {
      const double m1 = m0 + dm_point_[p];
      if (!(m1 > 0)) {
        failed_point = std::min(failed_point, p);
        continue;
      }
      f.vx[p] = (m0 * u + dpx_[p]) / m1;
      f.vy[p] = (m0 * w + dpy_[p]) / m1;
      f.point_mass[p] = m1;
      ke += dke_[p];
    }
    if (f.point_kinetic) f.point_kinetic[p] = ke;
  }
  if (failed_point != std::numeric_limits<Index>::max())
    fail_mass(mesh_, "point", failed_point, f.point_mass[failed_point] + dm_point_[failed_point]);
}

template void Remapper::repair_corner_masses<false>(const double*, const double*, RemapFields&);
template void Remapper::repair_corner_masses<true>(const double*, const double*, RemapFields&);
template void Remapper::point_momentum<false>(const double*, const double*, const double*, const double*, RemapFields&);
template void Remapper::point_momentum<true>(const double*, const double*, const double*, const double*, RemapFields&);

}  // namespace stagger
