#pragma once
// Noh's artificial heat flux (W. F. Noh, J. Comput. Phys. 72 (1987) 78-120; docs/algorithm.md
// §21): H = -kappa grad e with kappa = rho l (c1 C + c2 l max(-div u, 0)), as a conservative
// exchange of internal energy between zones that share an edge. Two zone passes on the state
// at t^n: the conductivity and centre of every zone, then per zone the gather of the fluxes
// through its edges (fixed order, no atomics) and its time-step limit.
#include <vector>

#include "hydro/kernels/time_step.hpp"
#include "stagger/mesh.hpp"

namespace stagger {

// Per corner c (the edge from corner_point[c] to the next point of its zone): the zone across
// that edge, or kNoHeatNeighbour (a boundary, or a zone of another material).
constexpr Index kNoHeatNeighbour = -1;

// The neighbour table: per corner, the zone holding the corner's edge reversed if its
// material (zone_material, per zone) is the same, kNoHeatNeighbour otherwise. Set-up only.
std::vector<Index> heat_flux_neighbours(const Mesh& mesh, const std::vector<int>& zone_material);

// The time-step limit's fraction of the forward-Euler bound M_z / sum_f G_f: margin for the
// mesh and the conductivities changing during the step.
constexpr double kHeatFluxDtFraction = 0.5;

// Read-only inputs of the heat flux, all at t^n.
struct HeatFluxInput {
  const Index* zone_corner_begin;
  const Index* corner_point;
  const Index* neighbour;  // per corner, as above
  const double *x, *y;     // x^n
  const double *vx, *vy;   // v^n
  const double *rho, *C, *e, *zone_mass;
  double c1, c2;  // linear (sound speed) and quadratic (l |div u| in compression) coefficients
};

// Pass 1 over the zones [begin, end): the conductivity kappa (per unit length, as q is a
// pressure) and the centre (vertex average) of each zone. Rz uses the volume divergence.
template <class Geometry>
void heat_flux_conductivity(const HeatFluxInput& in, Index begin, Index end, double* kappa, double* cx, double* cy);

// Pass 2 over the zones [begin, end): rate[z] = sum over the edges of z of the energy per unit
// time (per unit depth, or per radian in rz) flowing into z,
//   G_f (e_n - e_z),  G_f = 1/2 (kappa_z + kappa_n) r_f |f| (n_f . d) / |d|^2,
// d the vector between the two centres, n_f the unit outward normal of the edge, r_f its
// midpoint radius in rz (1 in planar). G_f and the difference are computed so that the flux of
// an edge seen from its other zone is the exact negative. Merges each zone's time-step limit,
// fraction M_z / sum_f G_f (forward Euler keeps e between its neighbours' values for
// fraction <= 1), into `choice`.
template <class Geometry>
void heat_flux_rates(const HeatFluxInput& in, const double* kappa, const double* cx, const double* cy, Index begin,
                     Index end, double fraction, double* rate, DtChoice& choice);

}  // namespace stagger
