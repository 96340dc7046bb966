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

#include <algorithm>
#include <cmath>
#include <limits>

#include "hydro/kernels/zone_status.hpp"

namespace stagger {

namespace {

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

void Remapper::remap(const double* xo, const double* yo, const double* xn, const double* yn, RemapFields& f,
                     bool limiter) {
  // rz as a template argument: the planar remap pays nothing for it.
  if (rz_)
    remap_impl<true>(xo, yo, xn, yn, f, limiter);
  else
    remap_impl<false>(xo, yo, xn, yn, f, limiter);
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
