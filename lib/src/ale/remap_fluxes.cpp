// The remap's face fluxes (remap.hpp; docs/ale.md, "Remap"): per face the swept region, the
// donor's reconstruction integrated over it, and the exchanged mass, specific quantities,
// momentum and kinetic energy, into the slots or straight into the sums.
#include <algorithm>
#include <cmath>

#include "ale/remap.hpp"
#include "ale/swept_quad.hpp"
#include "hydro/kernels/zone_status.hpp"

namespace stagger {

// One side of a zone during the flux sweep: the zone, its corners at the side's two points,
// the points, and the side's midpoint on the old and the new mesh.
struct Remapper::ZoneSide {
  Index z, c, c1, pa, pb;
  double mox, moy, mnx, mny;
};

// The fluxes, face by face (each face once, from the zone that owns it), into their slots.
// On one thread (or below the parallel loops' size) each flux goes straight into the sums
// of its cells instead (`direct`), in the order in which the gathers would add it: the same
// bits without the slots' second pass (docs/ale.md, "Remap cost"). `bound`: the donor
// remainder bound needs the half sides' slots in the direct mode too.
template <bool Rz>
void Remapper::face_fluxes(const double* xo, const double* yo, const double* xn, const double* yn, const RemapFields& f,
                           bool limiter, bool direct, bool bound) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones();
  const std::size_t nf = f.specific.size();
  if (direct) {
    std::fill(zone_dm_.begin(), zone_dm_.end(), 0.0);
    std::fill(corner_dm_.begin(), corner_dm_.end(), 0.0);
    zone_dq_.assign(nf * nz, 0.0);  // allocates at the first remap only
    std::fill(zone_hit_.begin(), zone_hit_.end(), 0);
    for (auto* v : {&dm_point_, &dpx_, &dpy_, &dke_}) std::fill(v->begin(), v->end(), 0.0);
    std::fill(point_touched_.begin(), point_touched_.end(), 0);
  }
#pragma omp parallel for schedule(static) if (nz > kParallelMin && !direct)
  for (Index z = 0; z < nz; ++z) {
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    if (!zone_active_[z]) {  // every face it owns sweeps nothing: empty slots, nothing to add
      if (!(direct && !bound)) clear_zone_slots(z, nf, direct);
      continue;
    }
    double gnx = 0, gny = 0;
    for (Index k = 0; k < n; ++k) {
      const Index p = m.corner_point[b + k];
      gnx += xn[p], gny += yn[p];
    }
    gnx /= n, gny /= n;
    for (Index k = 0; k < n; ++k) {
      const Index kp = (k + 1 == n) ? 0 : k + 1;
      ZoneSide side;
      side.z = z, side.c = b + k, side.c1 = b + kp;
      side.pa = m.corner_point[side.c], side.pb = m.corner_point[side.c1];
      side.mox = 0.5 * (xo[side.pa] + xo[side.pb]), side.moy = 0.5 * (yo[side.pa] + yo[side.pb]);
      side.mnx = 0.5 * (xn[side.pa] + xn[side.pb]), side.mny = 0.5 * (yn[side.pa] + yn[side.pb]);
      // Half sides, once per interior side (from the lower zone).
      if (side_zone_[side.c] > z) half_side_fluxes<Rz>(side, xo, yo, xn, yn, f, limiter, direct, bound);
      centre_segment_flux<Rz>(side, gnx, gny, xo, yo, f, direct);
    }
  }
}

// The slots of a zone none of whose points moved: zero (they may hold a previous remap's).
void Remapper::clear_zone_slots(Index z, std::size_t nf, bool direct) {
  const Index b = mesh_.zone_corner_begin[z], n = mesh_.zone_corner_begin[z + 1] - b;
  const std::size_t nc2 = 2 * static_cast<std::size_t>(mesh_.num_corners());
  for (Index c = b; c < b + n; ++c) {
    if (side_zone_[c] > z)
      for (std::size_t slot = 2 * static_cast<std::size_t>(c); slot < 2 * static_cast<std::size_t>(c) + 2; ++slot) {
        flux_mass_[slot] = 0, flux_active_[slot] = 0;
        for (std::size_t i = 0; i < nf; ++i) flux_q_[i * nc2 + slot] = 0;
      }
    if (!direct) flux_mass_[nc2 + c] = seg_px_[c] = seg_py_[c] = seg_ke_[c] = 0, flux_active_[nc2 + c] = 0;
  }
}

// The two half sides of an interior side owned by side.z: mass and every specific quantity
// between the zone and its neighbour (and between the corners at the side's points).
template <bool Rz>
void Remapper::half_side_fluxes(const ZoneSide& side, const double* xo, const double* yo, const double* xn,
                                const double* yn, const RemapFields& f, bool limiter, bool direct, bool bound) {
  const Index nz = mesh_.num_zones();
  const std::size_t nf = f.specific.size(), nc2 = 2 * static_cast<std::size_t>(mesh_.num_corners());
  const Index z = side.z, c = side.c, pa = side.pa, pb = side.pb, nb = side_zone_[c];
  const double mox = side.mox, moy = side.moy, mnx = side.mnx, mny = side.mny;
  // A side neither of whose ends moved is skipped by that test, not by its swept area
  // being 0: the area is exactly 0 only if the compiler does not contract its products
  // into fused multiply-adds, and a zone at rest (no gradients computed) must never give.
  const bool still = !point_moved_[pa] && !point_moved_[pb];
  for (int h = 0; h < 2; ++h) {
    // Half h: a -> mid (corner c) or mid -> b (corner c1); the cell on the left gains.
    const std::size_t slot = 2 * static_cast<std::size_t>(c) + h;
    const double ax0 = h == 0 ? xo[pa] : mox, ay0 = h == 0 ? yo[pa] : moy;
    const double ax1 = h == 0 ? xn[pa] : mnx, ay1 = h == 0 ? yn[pa] : mny;
    const double bx0 = h == 0 ? mox : xo[pb], by0 = h == 0 ? moy : yo[pb];
    const double bx1 = h == 0 ? mnx : xn[pb], by1 = h == 0 ? mny : yn[pb];
    const Swept s0 = still ? Swept{} : swept_quad<Rz>(ax0, ay0, ax1, ay1, bx1, by1, bx0, by0, 0.0, 0.0);
    if (still || (s0.area == 0 && s0.mx == 0 && s0.my == 0)) {
      if (direct && !bound) continue;  // adds nothing
      flux_mass_[slot] = 0, flux_active_[slot] = 0;
      for (std::size_t i = 0; i < nf; ++i) flux_q_[i * nc2 + slot] = 0;
      continue;
    }
    const Index d = s0.area > 0 ? nb : z;
    const Index left = h == 0 ? c : side.c1, right = h == 0 ? side_corner0_[c] : side_corner1_[c];
    // The donor corner's density and (zone) gradient: a corner never gives more than
    // it holds, and corner densities stay tied to their neighbours'.
    const Index dc = s0.area > 0 ? right : left;
    const double mx = s0.mx - ccx_[dc] * s0.area, my = s0.my - ccy_[dc] * s0.area;
    double flux = crho_[dc] * s0.area + cgx_[dc] * mx + cgy_[dc] * my;
    // Its mean density within the donor zone's bounds (corner densities may lie
    // outside them): no new extrema.
    if (s0.simple && limiter) {
      const double lo = s0.area * rlo_[d], hi = s0.area * rhi_[d];
      flux = std::clamp(flux, std::min(lo, hi), std::max(lo, hi));
    }
    if (direct) {
      zone_dm_[z] += flux, zone_dm_[nb] -= flux;
      corner_dm_[left] += flux, corner_dm_[right] -= flux;
      zone_hit_[z] = zone_hit_[nb] = 1;
    }
    if (!direct || bound) flux_mass_[slot] = flux, flux_active_[slot] = 1;
    for (std::size_t i = 0; i < nf; ++i) {
      const double qd = f.specific[i][d];
      double fq = 0;
      if (std::isfinite(qd)) {
        const std::size_t id = i * nz + d;
        const double mqx = s0.mx - cx_[d] * s0.area, mqy = s0.my - cy_[d] * s0.area;
        fq = qd * flux + crho_[dc] * (qgx_[id] * mqx + qgy_[id] * mqy);
        // The flux's mean value stays within the donor's neighbourhood bounds (a jump
        // of density inside the swept region could push it out): a repair that keeps
        // conservation, since the same flux leaves one zone and enters the other.
        // (A bow-tie region's mean is no point value: it is left alone.)
        if (s0.simple) {
          const double lo = flux * qmin_[id], hi = flux * qmax_[id];
          fq = std::clamp(fq, std::min(lo, hi), std::max(lo, hi));
        }
      }
      if (direct) zone_dq_[i * nz + z] += fq, zone_dq_[i * nz + nb] -= fq;
      if (!direct || bound) flux_q_[i * nc2 + slot] = fq;
    }
  }
}

// Centre segment mid(k, k+1) -> centre (gn on the new mesh, the zone's gox/goy on the old):
// mass between corners c (on the left) and c1 of the same zone, and with it momentum and
// kinetic energy between the side's points.
template <bool Rz>
void Remapper::centre_segment_flux(const ZoneSide& side, double gnx, double gny, const double* xo, const double* yo,
                                   const RemapFields& f, bool direct) {
  const std::size_t nc2 = 2 * static_cast<std::size_t>(mesh_.num_corners());
  const Index c = side.c, pa = side.pa, pb = side.pb;
  const std::size_t slot = nc2 + c;
  const Swept s =
      swept_quad<Rz>(side.mox, side.moy, side.mnx, side.mny, gnx, gny, gox_[side.z], goy_[side.z], 0.0, 0.0);
  if ((s.area == 0 && s.mx == 0 && s.my == 0) || (Rz && !segment_point_[c])) {
    if (!direct) flux_mass_[slot] = seg_px_[c] = seg_py_[c] = seg_ke_[c] = 0, flux_active_[slot] = 0;
    return;
  }
  const Index cd = s.area > 0 ? side.c1 : c;  // the donor corner
  const double flux =
      crho_[cd] * s.area + cgx_[cd] * (s.mx - ccx_[cd] * s.area) + cgy_[cd] * (s.my - ccy_[cd] * s.area);
  const Index pd = s.area > 0 ? pb : pa;
  const double mx = s.mx - xo[pd] * s.area, my = s.my - yo[pd] * s.area;
  const double u = f.vx[pd], w = f.vy[pd];
  const double du = vgx_[pd] * mx + vgy_[pd] * my, dw = wgx_[pd] * mx + wgy_[pd] * my;
  const double px = u * flux + crho_[cd] * du;
  const double py = w * flux + crho_[cd] * dw;
  const double ke = 0.5 * (u * u + w * w) * flux + crho_[cd] * (u * du + w * dw);
  if (direct) {
    corner_dm_[c] += flux, corner_dm_[side.c1] -= flux;
    dm_point_[pa] += flux, dpx_[pa] += px, dpy_[pa] += py, dke_[pa] += ke, point_touched_[pa] = 1;
    dm_point_[pb] -= flux, dpx_[pb] -= px, dpy_[pb] -= py, dke_[pb] -= ke, point_touched_[pb] = 1;
  } else {
    flux_mass_[slot] = flux, flux_active_[slot] = 1;
    seg_px_[c] = px, seg_py_[c] = py, seg_ke_[c] = ke;
  }
}

template void Remapper::face_fluxes<false>(const double*, const double*, const double*, const double*,
                                           const RemapFields&, bool, bool, bool);
template void Remapper::face_fluxes<true>(const double*, const double*, const double*, const double*,
                                          const RemapFields&, bool, bool, bool);

}  // namespace stagger
