#pragma once
// Edge viscosity of Caramana, Shashkov & Whalen (J. Comput. Phys. 144, 1998) with
// Christensen's limiter (docs/algorithm.md §5): forces along the compressing edges of each
// zone, added to its corner forces.
#include "stagger/mesh.hpp"

namespace stagger {

// Neighbour information for the limiter, per corner c (the edge from corner_point[c] to the
// next point of the zone): what continues the edge beyond each end. A point id (>= 0);
// kContinuationFree (ratio 0: free or pressure boundary); kContinuationOpen (ratio 1:
// periodic side); or mirror_code(w): the edge ends on a wall, symmetry plane or piston edge
// whose other end point is w, and the continuation is the edge's mirror image in it.
constexpr Index kContinuationFree = -1, kContinuationOpen = -2;
constexpr Index mirror_code(Index wall_end) {
  return -3 - wall_end;
}
constexpr Index mirror_wall_end(Index code) {
  return -3 - code;
}

struct EdgeContinuation {
  Index ahead = kContinuationFree, behind = kContinuationFree;
};

// Read-only inputs of the edge viscosity.
struct EdgeViscosityInput {
  const Index* zone_corner_begin;
  const Index* corner_point;
  const EdgeContinuation* continuation;  // per corner
  const double *x, *y;                   // positions (the half-step geometry)
  const double *ux, *uy;                 // velocities (v*, or v^n for a fresh evaluation)
  const double *rho, *C;                 // zone density and full sound speed at the same time
  double c1, c2;                         // linear and quadratic coefficients
  bool limiter;                          // Christensen's limiter on
};

// Adds the edge forces of the zones [begin, end), all of one material whose quadratic
// coefficient factor is gamma_factor ((gamma+1)/4 for an ideal gas), into (fx, fy) per corner.
// Each zone writes only its own corners.
void edge_forces_loop(const EdgeViscosityInput& in, Index begin, Index end, double gamma_factor, double* fx,
                      double* fy);

}  // namespace stagger
