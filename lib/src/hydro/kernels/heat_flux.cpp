// Noh's artificial heat flux (docs/algorithm.md §21); out of line: two extra zone passes,
// run only when the scene turns it on.
#include "hydro/kernels/heat_flux.hpp"

#include <algorithm>

#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/zone_status.hpp"

namespace stagger {

std::vector<Index> heat_flux_neighbours(const Mesh& m, const std::vector<int>& zone_material) {
  std::vector<Index> neighbour = side_twins(m);  // corners across, made zones below
  for (Index c = 0; c < m.num_corners(); ++c) {
    const Index zn = neighbour[c] < 0 ? -1 : m.corner_zone[neighbour[c]];
    neighbour[c] = zn >= 0 && zone_material[zn] == zone_material[m.corner_zone[c]] ? zn : kNoHeatNeighbour;
  }
  return neighbour;
}

template <class Geometry>
void heat_flux_conductivity(const HeatFluxInput& input, Index begin, Index end, double* kappa, double* cx, double* cy) {
  const HeatFluxInput in = input;  // thread-private below, as in zone_forces_loop
#pragma omp parallel for schedule(static) firstprivate(in) if (end - begin > kParallelMin)
  for (Index z = begin; z < end; ++z) {
    const Index b = in.zone_corner_begin[z];
    const int n = static_cast<int>(in.zone_corner_begin[z + 1] - b);
    const ZoneVertices v = gather_vertices<0>(in.corner_point, b, n, in.x, in.y);
    double ux[kMaxZoneVertices], uy[kMaxZoneVertices], ax[kMaxZoneVertices], ay[kMaxZoneVertices];
    for (int k = 0; k < n; ++k) ux[k] = in.vx[in.corner_point[b + k]], uy[k] = in.vy[in.corner_point[b + k]];
    const double area = Geometry::area(v);
    double div;
    if constexpr (Geometry::kRz) {
      div = Geometry::volume_divergence(v, ux, uy, Geometry::volume(v));
    } else {
      Geometry::corner_gradients(v, ax, ay);
      div = Geometry::divergence(n, ux, uy, ax, ay, area);
    }
    const double l = Geometry::characteristic_length(v, area);
    // The quadratic term in compression only, continuous in div u (no switch on its sign, so
    // round-off in div u stays round-off in kappa); the linear term wherever C > 0.
    kappa[z] = in.rho[z] * l * (in.c1 * in.C[z] + in.c2 * l * std::max(-div, 0.0));
    const auto [x0, y0] = Geometry::centre(v);
    cx[z] = x0, cy[z] = y0;
  }
}

template <class Geometry>
void heat_flux_rates(const HeatFluxInput& input, const double* kappa, const double* cx, const double* cy, Index begin,
                     Index end, double fraction, double* rate, DtChoice& choice) {
  const HeatFluxInput in = input;
  DtChoice best;
#pragma omp parallel firstprivate(in) if (end - begin > kParallelMin)
  {
    DtChoice local;
#pragma omp for schedule(static) nowait
    for (Index z = begin; z < end; ++z) {
      const Index b = in.zone_corner_begin[z];
      const int n = static_cast<int>(in.zone_corner_begin[z + 1] - b);
      double sum = 0, conductance = 0;
      for (int k = 0; k < n; ++k) {
        const Index zn = in.neighbour[b + k];
        if (zn == kNoHeatNeighbour) continue;
        const Index p0 = in.corner_point[b + k], p1 = in.corner_point[b + (k + 1 == n ? 0 : k + 1)];
        // Seen from zn, the edge is (p1, p0) and d is -d: each product below is then bitwise
        // the same (a - b = -(b - a) and (-a)(-b) = ab exactly in IEEE arithmetic), and so
        // is each sum (its terms are), so the two zones exchange exactly opposite fluxes.
        const double ex = in.x[p1] - in.x[p0], ey = in.y[p1] - in.y[p0];
        const double dx = cx[zn] - cx[z], dy = cy[zn] - cy[z];
        const double nd = ey * dx - ex * dy;  // |f| n_f . d
        if (!(nd > 0)) continue;              // a centre across the edge's line: a folding zone, no flux
        double g = 0.5 * (kappa[z] + kappa[zn]) * nd / (dx * dx + dy * dy);
        if constexpr (Geometry::kRz) g *= 0.5 * (in.x[p0] + in.x[p1]);
        sum += g * (in.e[zn] - in.e[z]);
        conductance += g;
      }
      rate[z] = sum;
      const double dt = conductance > 0 ? fraction * in.zone_mass[z] / conductance : 1e300;
      if (dt < local.dt) local = {dt, z};
    }
#pragma omp critical
    merge_thread_choice(best, local);
  }
  merge_range_choice(choice, best);
}

template void heat_flux_conductivity<PlanarGeometry>(const HeatFluxInput&, Index, Index, double*, double*, double*);
template void heat_flux_conductivity<RzGeometry>(const HeatFluxInput&, Index, Index, double*, double*, double*);
template void heat_flux_rates<PlanarGeometry>(const HeatFluxInput&, const double*, const double*, const double*, Index,
                                              Index, double, double*, DtChoice&);
template void heat_flux_rates<RzGeometry>(const HeatFluxInput&, const double*, const double*, const double*, Index,
                                          Index, double, double*, DtChoice&);

}  // namespace stagger
