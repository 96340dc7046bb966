#pragma once
// The walls as fixed lines in space, for the check that no point passes through one
// (docs/algorithm.md §10, "No point through a wall"). Built once by setup_boundaries.
#include <vector>

#include "stagger/mesh.hpp"  // Index

namespace stagger {

// One edge of a wall boundary on the initial mesh, a -> b, or a ray continuing an open end of
// the walls (a point on one wall edge only) beyond that end.
struct WallEdge {
  double ax = 0, ay = 0;  // start
  double tx = 0, ty = 0;  // unit direction along the wall
  double length = 0;      // |b - a|; infinity for a ray
  double nx = 0, ny = 0;  // unit outward normal (out of the domain, into the wall)
  double tol = 0;         // round-off tolerance, a length
  Index a = -1, b = -1;   // mesh points (b = -1 for a ray)
  int bc = 0;             // index into Problem::boundaries
};

// Walls binned on a uniform grid (segments only; rays are few and tested against every
// point): a point's step is tested against the segments of the cells its path touches.
struct WallGrid {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // covered box
  double inv_h = 0;                       // 1 / cell size
  int nx = 0, ny = 0;
  std::vector<Index> cell_begin;  // nx * ny + 1
  std::vector<Index> items;       // indices into the segment list
};

// How far each point may still move before it could reach a wall (docs/algorithm.md §10): a
// lower bound of its distance to every wall edge and ray, less what it has moved since. A
// point whose step is shorter than its budget cannot cross a wall and is not tested; the
// others are tested and get a fresh budget from their end position. Budgets hold only for the
// positions of accepted steps: a rejected step, a restore or a remap invalidates them
// (recompute_state), unless the remap charged its moves to them as a step does, and every
// budget is recomputed every kRefreshCycles cycles so the round-off of the subtracted steps
// cannot add up.
struct WallClearance {
  static constexpr long kRefreshCycles = 1024;
  std::vector<float> budget;  // per point, rounded down
  // Per block of kBlock points: some budget of the block ran out in this step's subtraction
  // (only those blocks hold points to test).
  static constexpr Index kBlock = 256;
  std::vector<unsigned char> block_spent;
  bool valid = false;
  bool charged = false;  // the last remap subtracted its moves from the valid budgets
  long cycle = 0;        // the cycle at which every budget was last computed afresh
  double slack = 0;      // subtracted from every distance: the walls' round-off tolerance and more
};

}  // namespace stagger
