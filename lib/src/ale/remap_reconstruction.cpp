// The remap's reconstruction (remap.hpp; docs/ale.md, "Reconstruction and limiter"): where
// anything moves, the old geometry (zone areas, centroids, densities, the old corners), the
// least-squares gradients of the density, the specific quantities and the velocities with
// their Barth-Jespersen limiter, and the corner gradients the fluxes integrate.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "ale/remap.hpp"
#include "ale/swept_quad.hpp"
#include "hydro/kernels/zone_status.hpp"

namespace stagger {

namespace {

// Pseudo-inverse of the symmetric 2x2 least-squares matrix [a b; b c] (rank-deficient
// stencils, e.g. one zone wide, get the gradient along the direction they resolve).
inline void pseudo_inverse(double a, double b, double c, double* out) {
  Eigen::Matrix2d m;
  m << a, b, b, c;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver;
  solver.computeDirect(m);
  const Eigen::Vector2d lambda = solver.eigenvalues();
  const Eigen::Matrix2d u = solver.eigenvectors();
  const double top = std::max(std::abs(lambda(0)), std::abs(lambda(1)));
  Eigen::Matrix2d p = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 2; ++i)
    if (top > 0 && lambda(i) > 1e-10 * top) p += u.col(i) * u.col(i).transpose() / lambda(i);
  out[0] = p(0, 0), out[1] = p(0, 1), out[2] = p(1, 1);
}

// Barth-Jespersen factor for a reconstruction that changes the mean q by `delta` at one
// evaluation point, within [qmin, qmax].
inline double bj_factor(double q, double delta, double qmin, double qmax) {
  // min(1, room / delta), dividing only when the quotient is below 1 (the same value). A
  // change far below the neighbourhood's range does not limit: along a direction in which the
  // field is flat (a ridge, a column where cos(2 pi x) = 0) both it and the room are round-off,
  // their quotient is noise, and it would cut the whole gradient, across the ridge too; a
  // uniform velocity added everywhere (another frame) changes that noise, and the remap was not
  // Galilean invariant (docs/ale.md, "Reconstruction and limiter"). The overshoot allowed is
  // below 1e-12 of the range; the test costs nothing where nothing limits.
  if (delta > 0 && qmax - q < delta) return delta <= 1e-12 * (qmax - qmin) ? 1.0 : (qmax - q) / delta;
  if (delta < 0 && qmin - q > delta) return -delta <= 1e-12 * (qmax - qmin) ? 1.0 : (qmin - q) / delta;
  return 1.0;
}

}  // namespace

// Least-squares gradient of the zone values q over the zone neighbours (centroids), limited
// by Barth-Jespersen at the zone's interior vertices and interior side midpoints.
void Remapper::zone_gradients(const double* q, bool limiter, double* gx, double* gy, double* lo, double* hi) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones();
#pragma omp parallel for schedule(static) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    if (!zone_active_[z]) continue;  // gives nothing (remap_impl)
    gx[z] = gy[z] = 0;
    if (lo) lo[z] = hi[z] = q[z];
    if (!std::isfinite(q[z])) continue;
    const double qz = q[z];
    double bx = 0, by = 0, qmin = qz, qmax = qz;
    bool finite = true;
    for (Index k = zone_nbr_begin_[z]; k < zone_nbr_begin_[z + 1]; ++k) {
      const double qn = q[zone_nbr_[k]];
      if (!std::isfinite(qn)) {
        finite = false;
        break;
      }
      const double dq = qn - qz;
      bx += ncx_[k] * dq;
      by += ncy_[k] * dq;
      qmin = std::min(qmin, qn);
      qmax = std::max(qmax, qn);
    }
    if (!finite) continue;
    if (lo) lo[z] = qmin, hi[z] = qmax;
    const double* pinv = &zlsq_[3 * static_cast<std::size_t>(z)];
    double ax = pinv[0] * bx + pinv[1] * by, ay = pinv[1] * bx + pinv[2] * by;
    const Index b = m.zone_corner_begin[z], e = m.zone_corner_begin[z + 1];
    if (limiter && (ax != 0 || ay != 0)) {
      // A side that is not shared has a zero midpoint offset: a zero change, factor 1.
      double phi = 1.0;
      for (Index c = b; c < e; ++c) {
        if (limit_vertex_[c]) phi = std::min(phi, bj_factor(qz, ax * lvx_[c] + ay * lvy_[c], qmin, qmax));
        phi = std::min(phi, bj_factor(qz, ax * lmx_[c] + ay * lmy_[c], qmin, qmax));
      }
      phi = std::max(phi, 0.0);
      ax *= phi, ay *= phi;
    }
    gx[z] = ax, gy[z] = ay;
    if (lo && (ax != 0 || ay != 0)) {
      // The bounds of a flux's mean value: the neighbourhood's, widened by the (limited)
      // reconstruction at the zone's vertices (which the limiter leaves free on the boundary).
      for (Index c = b; c < e; ++c) {
        const double v = qz + ax * lvx_[c] + ay * lvy_[c];
        lo[z] = std::min(lo[z], v), hi[z] = std::max(hi[z], v);
      }
    }
  }
}

// Both velocity components in one pass over the neighbours (each component's arithmetic as
// for a single field).
void Remapper::point_gradients(const double* qa, const double* qb, bool limiter, double* gax, double* gay, double* gbx,
                               double* gby) {
  const Index np = mesh_.num_points();
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    if (!point_near_[p]) continue;  // gives nothing (remap_impl)
    const double* q[2] = {qa, qb};
    double bx[2] = {0, 0}, by[2] = {0, 0}, qmin[2] = {qa[p], qb[p]}, qmax[2] = {qa[p], qb[p]};
    for (Index k = point_nbr_begin_[p]; k < point_nbr_begin_[p + 1]; ++k) {
      const Index n = point_nbr_[k];
      const double dx = pdx_[k], dy = pdy_[k];
      for (int i = 0; i < 2; ++i) {
        const double dq = q[i][n] - q[i][p];
        bx[i] += dx * dq;
        by[i] += dy * dq;
        qmin[i] = std::min(qmin[i], q[i][n]);
        qmax[i] = std::max(qmax[i], q[i][n]);
      }
    }
    const double* pinv = &plsq_[3 * static_cast<std::size_t>(p)];
    double ax[2], ay[2], phi[2] = {1.0, 1.0};
    bool limit[2];
    for (int i = 0; i < 2; ++i) {
      ax[i] = pinv[0] * bx[i] + pinv[1] * by[i], ay[i] = pinv[1] * bx[i] + pinv[2] * by[i];
      limit[i] = limiter && (ax[i] != 0 || ay[i] != 0);
    }
    if (limit[0] || limit[1]) {
      for (Index k = point_nbr_begin_[p]; k < point_nbr_begin_[p + 1]; ++k) {
        const double mx = 0.5 * pdx_[k], my = 0.5 * pdy_[k];
        for (int i = 0; i < 2; ++i)
          if (limit[i]) phi[i] = std::min(phi[i], bj_factor(q[i][p], ax[i] * mx + ay[i] * my, qmin[i], qmax[i]));
      }
    }
    for (int i = 0; i < 2; ++i)
      if (limit[i]) {
        phi[i] = std::max(phi[i], 0.0);
        ax[i] *= phi[i], ay[i] *= phi[i];
      }
    gax[p] = ax[0], gay[p] = ay[0], gbx[p] = ax[1], gby[p] = ay[1];
  }
}

// Where anything happens. A face whose ends did not move sweeps no area (the flux loop skips
// it by that test), so a zone none of whose points moved neither gives nor takes anything: it needs
// no gradient, bounds or corner values (active zones do); a point gives momentum only
// through the centre segments of active zones, so only their points need a velocity
// gradient ("near" points, and the rz axis points, whose velocity is the reconstruction);
// the gradients read the old geometry of the zones around them ("near" zones). The values
// computed are the same bits as when every zone computes them (docs/ale.md, "Remap cost").
template <bool Rz>
void Remapper::mark_active(const double* xo, const double* yo, const double* xn, const double* yn) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones(), np = m.num_points();
  Index moved = 0;
#pragma omp parallel for schedule(static) reduction(+ : moved) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    point_moved_[p] = xn[p] != xo[p] || yn[p] != yo[p];
    moved += point_moved_[p];
  }
  Index active = nz;
  if (moved < np) {
    active = 0;
#pragma omp parallel for schedule(static) reduction(+ : active) if (nz > kParallelMin)
    for (Index z = 0; z < nz; ++z) {
      char a = 0;
      for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) a |= point_moved_[m.corner_point[c]];
      zone_active_[z] = a;
      active += a;
    }
  }
  if (active == nz) {  // every zone has a moving point (a few fixed corners at most)
    std::fill(zone_active_.begin(), zone_active_.end(), 1);
    std::fill(zone_near_.begin(), zone_near_.end(), 1);
    std::fill(point_near_.begin(), point_near_.end(), 1);
  } else {
#pragma omp parallel for schedule(static) if (np > kParallelMin)
    for (Index p = 0; p < np; ++p) {
      char a = Rz && axis_point_[p];
      for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k)
        a |= zone_active_[m.corner_zone[m.point_corners[k]]];
      point_near_[p] = a;
    }
#pragma omp parallel for schedule(static) if (nz > kParallelMin)
    for (Index z = 0; z < nz; ++z) {
      char a = 0;
      for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) a |= point_near_[m.corner_point[c]];
      zone_near_[z] = a;
    }
  }
}

// Old geometry: areas, centroids (the reconstruction's centres), densities, and the old
// corners (x_k, mid(k, k+1), centre, mid(k-1, k)): their own densities m_c / A_c feed the
// centre-segment fluxes, so that a corner never gives more than it holds.
template <bool Rz>
void Remapper::old_geometry(const double* xo, const double* yo, const RemapFields& f) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones();
#pragma omp parallel for schedule(static) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    if (!zone_near_[z]) continue;
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    const double x0 = xo[m.corner_point[b]], y0 = yo[m.corner_point[b]];
    double a2 = 0, sx = 0, sy = 0;
    for (Index k = 1; k + 1 < n; ++k) {
      const Index p = m.corner_point[b + k], q = m.corner_point[b + k + 1];
      const double ux = xo[p] - x0, uy = yo[p] - y0, wx = xo[q] - x0, wy = yo[q] - y0;
      const double cr = ux * wy - wx * uy;
      a2 += cr, sx += (ux + wx) * cr, sy += (uy + wy) * cr;
    }
    area_[z] = 0.5 * a2;
    cx_[z] = x0 + sx / (3 * a2);
    cy_[z] = y0 + sy / (3 * a2);
    if constexpr (Rz) {  // the volume and its centroid (int x r dA / V, int y r dA / V)
      double v = 0, mx = 0, my = 0;
      for (Index k = 1; k + 1 < n; ++k) {
        const Index p = m.corner_point[b + k], q = m.corner_point[b + k + 1];
        const Swept t = swept_quad<true>(x0, y0, xo[p], yo[p], xo[q], yo[q], xo[q], yo[q], 0.0, 0.0);
        v += t.area, mx += t.mx, my += t.my;
      }
      area_[z] = v, cx_[z] = mx / v, cy_[z] = my / v;
    }
    rho_[z] = f.zone_mass[z] / area_[z];
    if (!zone_active_[z]) continue;
    old_corners<Rz>(z, xo, yo, f);
  }
}

// The old corners of active zone z: the mean of its vertices (the corners' centre point), the
// limiter's offsets from the centroid, and each corner's density and centroid.
template <bool Rz>
void Remapper::old_corners(Index z, const double* xo, const double* yo, const RemapFields& f) {
  const Mesh& m = mesh_;
  const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
  double gox = 0, goy = 0;
  for (Index k = 0; k < n; ++k) gox += xo[m.corner_point[b + k]], goy += yo[m.corner_point[b + k]];
  gox /= n, goy /= n;
  gox_[z] = gox, goy_[z] = goy;
  for (Index k = 0; k < n; ++k) {
    const Index p = m.corner_point[b + k], pn = m.corner_point[b + (k + 1 == n ? 0 : k + 1)],
                pp = m.corner_point[b + (k == 0 ? n - 1 : k - 1)];
    const double qx[4] = {xo[p], 0.5 * (xo[p] + xo[pn]), gox, 0.5 * (xo[p] + xo[pp])};
    const double qy[4] = {yo[p], 0.5 * (yo[p] + yo[pn]), goy, 0.5 * (yo[p] + yo[pp])};
    // The limiter's offsets from the centroid: the point, and the side's midpoint if shared.
    const bool shared = side_zone_[b + k] >= 0;
    lvx_[b + k] = qx[0] - cx_[z], lvy_[b + k] = qy[0] - cy_[z];
    lmx_[b + k] = shared ? qx[1] - cx_[z] : 0.0, lmy_[b + k] = shared ? qy[1] - cy_[z] : 0.0;
    const Swept a = swept_quad<Rz>(qx[0], qy[0], qx[1], qy[1], qx[2], qy[2], qx[3], qy[3], 0.0, 0.0);
    crho_[b + k] = a.area > 0 ? f.corner_mass[b + k] / a.area : rho_[z];
    ccx_[b + k] = a.area > 0 ? a.mx / a.area : gox;
    ccy_[b + k] = a.area > 0 ? a.my / a.area : goy;
  }
}

// Least-squares matrices of the zone stencils (centroids) and the point stencils (old
// positions), and the offsets every field's gradient reads.
void Remapper::least_squares_matrices(const double* xo, const double* yo) {
  const Index nz = mesh_.num_zones(), np = mesh_.num_points();
#pragma omp parallel for schedule(static) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    if (!zone_active_[z]) continue;
    double a = 0, b = 0, c = 0;
    for (Index k = zone_nbr_begin_[z]; k < zone_nbr_begin_[z + 1]; ++k) {
      const double dx = cx_[zone_nbr_[k]] - cx_[z], dy = cy_[zone_nbr_[k]] - cy_[z];
      ncx_[k] = dx, ncy_[k] = dy;  // for every field's gradient
      a += dx * dx, b += dx * dy, c += dy * dy;
    }
    pseudo_inverse(a, b, c, &zlsq_[3 * static_cast<std::size_t>(z)]);
  }
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    if (!point_near_[p]) continue;
    double a = 0, b = 0, c = 0;
    for (Index k = point_nbr_begin_[p]; k < point_nbr_begin_[p + 1]; ++k) {
      const double dx = xo[point_nbr_[k]] - xo[p], dy = yo[point_nbr_[k]] - yo[p];
      pdx_[k] = dx, pdy_[k] = dy;  // for the velocity gradients
      a += dx * dx, b += dx * dy, c += dy * dy;
    }
    pseudo_inverse(a, b, c, &plsq_[3 * static_cast<std::size_t>(p)]);
  }
}

// The reconstruction's gradients (limited if `limiter`): the zone density with its bounds,
// every specific quantity with its bounds, and the point velocities.
void Remapper::reconstruction_gradients(const RemapFields& f, bool limiter) {
  const Index nz = mesh_.num_zones();
  const std::size_t nf = f.specific.size();
  zone_gradients(rho_.data(), limiter, grx_.data(), gry_.data(), rlo_.data(), rhi_.data());
  qgx_.resize(nf * nz), qgy_.resize(nf * nz), qmin_.resize(nf * nz), qmax_.resize(nf * nz);
  flux_q_.resize(nf * 2 * static_cast<std::size_t>(mesh_.num_corners()));
  for (std::size_t i = 0; i < nf; ++i)
    zone_gradients(f.specific[i], limiter, qgx_.data() + i * nz, qgy_.data() + i * nz, qmin_.data() + i * nz,
                   qmax_.data() + i * nz);
  point_gradients(f.vx, f.vy, limiter, vgx_.data(), vgy_.data(), wgx_.data(), wgy_.data());
}

// The corner gradient: the zone's limited one, scaled where needed so that the corner's
// reconstruction stays non-negative at its vertices.
void Remapper::corner_gradients(const double* xo, const double* yo) {
  const Mesh& m = mesh_;
  const Index nz = m.num_zones();
#pragma omp parallel for schedule(static) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    if (!zone_active_[z]) continue;
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    const double gox = gox_[z], goy = goy_[z];
    if (grx_[z] == 0 && gry_[z] == 0) {  // nothing to limit (phi = 1)
      for (Index c = b; c < b + n; ++c) cgx_[c] = grx_[z], cgy_[c] = gry_[z];
      continue;
    }
    for (Index k = 0; k < n; ++k) {
      const Index c = b + k, cn = b + (k + 1 == n ? 0 : k + 1), cp = b + (k == 0 ? n - 1 : k - 1);
      const double r = crho_[c];
      const Index p = m.corner_point[c], pn = m.corner_point[cn], pp = m.corner_point[cp];
      const double qx[4] = {xo[p], 0.5 * (xo[p] + xo[pn]), gox, 0.5 * (xo[p] + xo[pp])};
      const double qy[4] = {yo[p], 0.5 * (yo[p] + yo[pn]), goy, 0.5 * (yo[p] + yo[pp])};
      double phi = 1.0;
      for (int i = 0; i < 4; ++i) {
        const double d = grx_[z] * (qx[i] - ccx_[c]) + gry_[z] * (qy[i] - ccy_[c]);
        if (d < 0 && r + d < 0) phi = std::min(phi, r / -d);  // never negative
      }
      phi = std::max(phi, 0.0);
      cgx_[c] = phi * grx_[z], cgy_[c] = phi * gry_[z];
    }
  }
}

template void Remapper::mark_active<false>(const double*, const double*, const double*, const double*);
template void Remapper::mark_active<true>(const double*, const double*, const double*, const double*);
template void Remapper::old_geometry<false>(const double*, const double*, const RemapFields&);
template void Remapper::old_geometry<true>(const double*, const double*, const RemapFields&);

}  // namespace stagger
