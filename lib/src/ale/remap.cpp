// The swept-face remap (remap.hpp; docs/ale.md, "Remap").
//
// Zone z's sides are split at their midpoints, and each zone is split into its median-mesh
// corners (x_k, mid(k,k+1), centre, mid(k-1,k)), the subcells of Loubere & Shashkov (2005).
// Moving every point from its old to its new position, each sub-face (a half side, or a
// segment from a side's midpoint to the zone centre) sweeps a quadrilateral; its signed area
// is the volume the cell on the face's left gains from the cell on its right. The exchanged
// mass is the donor zone's linear density integrated over that quadrilateral, so
//   - half sides move mass between zones (and between corners of the same point),
//   - centre segments move mass between corners of the same zone (between points),
// and the zone, corner and point masses stay sums of one another. Every flux is added to one
// cell and subtracted from the other: mass, the mass-weighted zone quantities, momentum and
// the carried kinetic energy are conserved to round-off. The integrals of a linear function
// over a signed polygon are exact (area and first moments), which makes linear fields exact.
#include "ale/remap.hpp"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "hydro/kernels/zone_status.hpp"
#include "stagger/error.hpp"

namespace stagger {

namespace {

// Signed area and first moments about (ox, oy) of the quadrilateral p0 p1 p2 p3 (any shape,
// self-intersecting included: the signed integral). Coordinates relative to p0 keep the
// cancellation small; an unmoved face gives exactly zero.
struct Swept {
  double area = 0, mx = 0, my = 0;  // area, integral of (x - ox), of (y - oy)
  bool simple = true;               // not a bow-tie (one diagonal splits it into like-signed triangles)
};

// rz: the same with the measure r dA (x = r): area -> V = int x dA, mx -> int (x - ox) x dA,
// my -> int (y - oy) x dA, from the second moments of the signed quadrilateral.
template <bool Rz = false>
inline Swept swept_quad(double x0, double y0, double x1, double y1, double x2, double y2, double x3, double y3,
                        double ox, double oy) {
  const double ax[4] = {0.0, x1 - x0, x2 - x0, x3 - x0};
  const double ay[4] = {0.0, y1 - y0, y2 - y0, y3 - y0};
  double a2 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 1; i < 3; ++i) {  // the terms with the origin vanish
    const double cr = ax[i] * ay[i + 1] - ax[i + 1] * ay[i];
    a2 += cr;
    sx += (ax[i] + ax[i + 1]) * cr;
    sy += (ay[i] + ay[i + 1]) * cr;
    if constexpr (Rz) {
      sxx += (ax[i] * ax[i] + ax[i] * ax[i + 1] + ax[i + 1] * ax[i + 1]) * cr;
      sxy += (ax[i] * ay[i + 1] + 2 * ax[i] * ay[i] + 2 * ax[i + 1] * ay[i + 1] + ax[i + 1] * ay[i]) * cr;
    }
  }
  Swept s;
  s.area = 0.5 * a2;
  // Triangles of the two diagonal splits: (0,1,2) + (0,2,3) and (1,2,3) + (1,3,0).
  const double t012 = ax[1] * ay[2] - ax[2] * ay[1], t023 = ax[2] * ay[3] - ax[3] * ay[2];
  const double t123 = (ax[2] - ax[1]) * (ay[3] - ay[1]) - (ax[3] - ax[1]) * (ay[2] - ay[1]);
  const double t130 = (ax[3] - ax[1]) * (0 - ay[1]) - (0 - ax[1]) * (ay[3] - ay[1]);
  s.simple = t012 * t023 >= 0 || t123 * t130 >= 0;
  if constexpr (Rz) {
    // Relative to p0: A, int x', int y', int x'^2, int x'y'; then x = x' + x0, y = y' + y0.
    const double area = s.area, ix = sx / 6.0, iy = sy / 6.0, ixx = sxx / 12.0, ixy = sxy / 24.0;
    s.area = ix + x0 * area;
    s.mx = ixx + 2 * x0 * ix + x0 * x0 * area - ox * s.area;
    s.my = ixy + x0 * iy + y0 * ix + x0 * y0 * area - oy * s.area;
    return s;
  }
  s.mx = sx / 6.0 + (x0 - ox) * s.area;
  s.my = sy / 6.0 + (y0 - oy) * s.area;
  return s;
}

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
  // min(1, room / delta), dividing only when the quotient is below 1 (the same value).
  if (delta > 0) return qmax - q < delta ? (qmax - q) / delta : 1.0;
  if (delta < 0) return qmin - q > delta ? (qmin - q) / delta : 1.0;
  return 1.0;
}

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

// The corner after c in its zone (counter-clockwise).
inline Index next_corner(const Mesh& mesh, Index c) {
  const Index z = mesh.corner_zone[c];
  return c + 1 == mesh.zone_corner_begin[z + 1] ? mesh.zone_corner_begin[z] : c + 1;
}

}  // namespace

Remapper::Remapper(const Mesh& mesh, std::span<const int> zone_material, bool rz) : mesh_(mesh), rz_(rz) {
  find_sides(zone_material);
  find_neighbours(zone_material);
  allocate_workspace();
  order_flux_sums();
}

// The rz axis points, and per corner the zone across its side (same material only) with that
// zone's two corners on the side; the points of the other sides are boundary points.
void Remapper::find_sides(std::span<const int> zone_material) {
  const Mesh& mesh = mesh_;
  const Index np = mesh.num_points(), nc = mesh.num_corners();
  axis_point_.assign(np, 0);
  if (rz_)
    for (Index p = 0; p < np; ++p) axis_point_[p] = mesh.x[p] == 0;
  side_zone_.assign(nc, -1);
  side_corner0_.assign(nc, -1);
  side_corner1_.assign(nc, -1);
  boundary_point_.assign(np, 0);
  const std::vector<Index> twin = side_twins(mesh);
  for (Index c = 0; c < nc; ++c) {
    const Index a = mesh.corner_point[c], b = mesh.corner_point[next_corner(mesh, c)], t = twin[c];
    const Index z = mesh.corner_zone[c];
    if (t >= 0 && zone_material[mesh.corner_zone[t]] == zone_material[z]) {
      side_zone_[c] = mesh.corner_zone[t];
      side_corner1_[c] = t;                     // its corner at b
      side_corner0_[c] = next_corner(mesh, t);  // its corner at a
    } else {
      boundary_point_[a] = boundary_point_[b] = 1;
    }
  }
  // rz: a centre segment with an end on the axis exchanges nothing. The axis points are
  // massless in the Lagrangian rz step (docs/algorithm.md §19): their dual cells hold mass
  // (their corners') but no momentum, so mass moved between them and the other points'
  // dual cells would carry momentum from or into nothing.
  segment_point_.assign(nc, 1);
  for (Index c = 0; c < nc; ++c)
    if (axis_point_[mesh.corner_point[c]] || axis_point_[mesh.corner_point[next_corner(mesh, c)]])
      segment_point_[c] = 0;
}

// The gradients' stencils. Zone neighbours: same-material zones sharing a point. Point
// neighbours: along sides.
void Remapper::find_neighbours(std::span<const int> zone_material) {
  const Mesh& mesh = mesh_;
  const Index nz = mesh.num_zones(), np = mesh.num_points();
  zone_nbr_begin_.assign(nz + 1, 0);
  std::vector<Index> list;
  for (Index z = 0; z < nz; ++z) {
    list.clear();
    for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) {
      const Index p = mesh.corner_point[c];
      for (Index k = mesh.point_corner_begin[p]; k < mesh.point_corner_begin[p + 1]; ++k) {
        const Index other = mesh.corner_zone[mesh.point_corners[k]];
        if (other != z && zone_material[other] == zone_material[z]) list.push_back(other);
      }
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    zone_nbr_.insert(zone_nbr_.end(), list.begin(), list.end());
    zone_nbr_begin_[z + 1] = static_cast<Index>(zone_nbr_.size());
  }
  point_nbr_begin_.assign(np + 1, 0);
  for (Index p = 0; p < np; ++p) {
    list.clear();
    for (Index k = mesh.point_corner_begin[p]; k < mesh.point_corner_begin[p + 1]; ++k) {
      const Index c = mesh.point_corners[k], z = mesh.corner_zone[c];
      const Index b = mesh.zone_corner_begin[z], n = mesh.zone_corner_begin[z + 1] - b, j = c - b;
      list.push_back(mesh.corner_point[b + (j + 1) % n]);
      list.push_back(mesh.corner_point[b + (j + n - 1) % n]);
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    point_nbr_.insert(point_nbr_.end(), list.begin(), list.end());
    point_nbr_begin_[p + 1] = static_cast<Index>(point_nbr_.size());
  }
}

// The workspace, once for the topology (the remaps allocate nothing after the first).
void Remapper::allocate_workspace() {
  const Mesh& mesh = mesh_;
  const Index nz = mesh.num_zones(), np = mesh.num_points(), nc = mesh.num_corners();
  for (auto* v : {&area_, &cx_, &cy_, &rho_, &grx_, &gry_, &rlo_, &rhi_, &qgx_, &qgy_}) v->assign(nz, 0.0);
  zlsq_.assign(3 * static_cast<std::size_t>(nz), 0.0);
  plsq_.assign(3 * static_cast<std::size_t>(np), 0.0);
  for (auto* v : {&vgx_, &vgy_, &wgx_, &wgy_, &dm_point_, &dpx_, &dpy_, &dke_}) v->assign(np, 0.0);
  for (auto* v : {&crho_, &ccx_, &ccy_, &cgx_, &cgy_, &lvx_, &lvy_, &lmx_, &lmy_}) v->assign(nc, 0.0);
  limit_vertex_.assign(nc, 0);
  for (Index c = 0; c < nc; ++c) limit_vertex_[c] = !boundary_point_[mesh.corner_point[c]];
  ncx_.assign(zone_nbr_.size(), 0.0);
  ncy_.assign(zone_nbr_.size(), 0.0);
  pdx_.assign(point_nbr_.size(), 0.0);
  pdy_.assign(point_nbr_.size(), 0.0);
  gox_.assign(nz, 0.0);
  goy_.assign(nz, 0.0);
  point_touched_.assign(np, 0);
  flux_mass_.assign(3 * static_cast<std::size_t>(nc), 0.0);
  flux_active_.assign(3 * static_cast<std::size_t>(nc), 0);
  for (auto* v : {&seg_px_, &seg_py_, &seg_ke_}) v->assign(nc, 0.0);
  zone_dm_.assign(nz, 0.0);
  corner_dm_.assign(nc, 0.0);
  zone_hit_.assign(nz, 0);
  zone_resum_.assign(nz, 0);
  zone_active_.assign(nz, 1);
  zone_near_.assign(nz, 1);
  point_moved_.assign(np, 1);
  point_near_.assign(np, 1);
  bound_zones_.reserve(nz);
}

// The order in which a serial sweep over the zones adds each face's flux to its cells
// (zones in order; per corner its side's two halves, if this zone owns the side, then
// its centre segment): the gathers of remap() follow it.
void Remapper::order_flux_sums() {
  const Mesh& mesh = mesh_;
  const Index nz = mesh.num_zones(), np = mesh.num_points(), nc = mesh.num_corners();
  std::vector<std::vector<Index>> zl(nz), cl(nc), pl(np);
  for (Index z = 0; z < nz; ++z) {
    const Index b = mesh.zone_corner_begin[z], n = mesh.zone_corner_begin[z + 1] - b;
    for (Index k = 0; k < n; ++k) {
      const Index c = b + k, c1 = b + (k + 1 == n ? 0 : k + 1);
      const Index nb = side_zone_[c];
      if (nb > z) {
        for (Index h = 0; h < 2; ++h) {
          const Index slot = 2 * c + h;
          cl[h == 0 ? c : c1].push_back(2 * slot);
          cl[h == 0 ? side_corner0_[c] : side_corner1_[c]].push_back(2 * slot + 1);
          zl[z].push_back(2 * slot);
          zl[nb].push_back(2 * slot + 1);
        }
      }
      const Index slot = 2 * nc + c;
      cl[c].push_back(2 * slot);
      cl[c1].push_back(2 * slot + 1);
      pl[mesh.corner_point[c]].push_back(2 * c);
      pl[mesh.corner_point[c1]].push_back(2 * c + 1);
    }
  }
  const auto flatten = [](const std::vector<std::vector<Index>>& lists, std::vector<Index>& begin,
                          std::vector<Index>& flat) {
    begin.assign(lists.size() + 1, 0);
    for (std::size_t i = 0; i < lists.size(); ++i) {
      flat.insert(flat.end(), lists[i].begin(), lists[i].end());
      begin[i + 1] = static_cast<Index>(flat.size());
    }
  };
  flatten(zl, zone_list_begin_, zone_list_);
  flatten(cl, corner_list_begin_, corner_list_);
  flatten(pl, point_list_begin_, point_list_);
}

int Remapper::substeps(const double* xo, const double* yo, const double* xn, const double* yn, double fraction) const {
  const Index np = mesh_.num_points();
  // Squared lengths (no hypot: only the integer count is wanted).
  double worst2 = 0;
#pragma omp parallel for schedule(static) reduction(max : worst2) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    const double dx = xn[p] - xo[p], dy = yn[p] - yo[p], d2 = dx * dx + dy * dy;
    if (d2 == 0) continue;
    double shortest2 = std::numeric_limits<double>::infinity();
    for (Index k = point_nbr_begin_[p]; k < point_nbr_begin_[p + 1]; ++k) {
      const Index q = point_nbr_[k];
      const double ox = xo[q] - xo[p], oy = yo[q] - yo[p], nx = xn[q] - xn[p], ny = yn[q] - yn[p];
      shortest2 = std::min({shortest2, ox * ox + oy * oy, nx * nx + ny * ny});
    }
    worst2 = std::max(worst2, d2 / shortest2);
  }
  const double steps = std::ceil(std::sqrt(worst2) / fraction);
  return steps <= 1 ? 1 : steps < 1e6 ? static_cast<int>(steps) : 1000000;  // a zero edge: "too many"
}

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

void Remapper::remap(const double* xo, const double* yo, const double* xn, const double* yn, RemapFields& f,
                     bool limiter) {
  // rz as a template argument: the planar remap pays nothing for it.
  if (rz_)
    remap_impl<true>(xo, yo, xn, yn, f, limiter);
  else
    remap_impl<false>(xo, yo, xn, yn, f, limiter);
}

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

// The stages in order: where anything moves, the old geometry and the reconstruction, the
// face fluxes, the new zone and corner values (directly or gathered from the slots), the
// corner-mass repair, and the points' momentum.
template <bool Rz>
void Remapper::remap_impl(const double* xo, const double* yo, const double* xn, const double* yn, RemapFields& f,
                          bool limiter) {
  const Index nz = mesh_.num_zones();
  const std::size_t nf = f.specific.size();
  mark_active<Rz>(xo, yo, xn, yn);
  old_geometry<Rz>(xo, yo, f);
  least_squares_matrices(xo, yo);
  reconstruction_gradients(f, limiter);
  corner_gradients(xo, yo);
  const bool bound = limiter && remainder_bound_ && nf > 0;  // the donor remainder bound needs the half sides' slots
  if (bound) keep_.resize(nf * static_cast<std::size_t>(nz), 1.0);
  const bool direct = nz <= kParallelMin || omp_get_max_threads() == 1;
  face_fluxes<Rz>(xo, yo, xn, yn, f, limiter, direct, bound);
  if (direct) {
    if (bound) direct_remainder_bound(f);
    direct_zone_corner_values(f);
  } else {
    gather_fluxes(f, limiter);
  }
  repair_corner_masses<Rz>(xn, yn, f);
  point_momentum<Rz>(xo, yo, xn, yn, f);
}

}  // namespace stagger
