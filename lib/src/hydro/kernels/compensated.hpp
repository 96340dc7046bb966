#pragma once
// Compensated accumulation of the point positions and velocities (docs/algorithm.md §20,
// `numerics.compensated_update`): each accumulated value x carries a low part lo, the
// round-off its last update lost, which the next update adds back, so x + lo follows the
// exact sum of the increments and x stays its rounding instead of drifting by a rounding per
// cycle. Needs IEEE double arithmetic as written (no -ffast-math, no reassociation).
#include "stagger/mesh.hpp"

namespace stagger {

// s = fl(a + b) and err = (a + b) - s exactly (Knuth's two-sum: no condition on |a|, |b|).
[[gnu::always_inline]] inline double two_sum(double a, double b, double& err) {
  const double s = a + b;
  const double bb = s - a;
  err = (a - (s - bb)) + (b - bb);
  return s;
}

// The velocities' low parts: of v^n in, of v^{n+1} out (all null: the plain update).
struct VelocityLowParts {
  const double *x = nullptr, *y = nullptr;
  double *x_new = nullptr, *y_new = nullptr;
};

// x^{n+1} = x^n + step, step = dt v_bar: as the step forms it everywhere (end geometry, wall
// test, commit), with the point's low part when lo is given (compensated), as is otherwise.
[[gnu::always_inline]] inline double advanced(double x, double step, const double* lo, Index p) {
  return lo ? x + (step + lo[p]) : x + step;
}

}  // namespace stagger
